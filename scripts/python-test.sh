#!/usr/bin/env bash
# Builds the Python package (python/) as a wheel, installs it in a fresh virtual environment
# (what `pip install` gives a user), then into the test environment, and runs its tests
# (pytest): parity with `revdist distance --batch`, shapes and errors, the GIL released, Pair
# against cold queries, pickling across processes, profiles from arrays, Dask. Called by
# scripts/test.sh; runs alone too.
# The venvs live in target/python-venv (tests; its tools pinned in
# python/requirements-test.txt, from the package index) and target/wheel-venv (recreated on
# every run: the wheel and its declared dependencies only), both git-ignored. The extension is
# compiled into the same Cargo target directory as the workspace, so crates.io dependencies
# built for the core are reused.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
scripts/deps.sh
target="${CARGO_TARGET_DIR:-$root/target}"
venv="$root/target/python-venv"
# Debian's interpreter: scripts/deps.sh installs its venv and pip modules.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
if [ ! -x "$venv/bin/python" ]; then
  "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet -r python/requirements-test.txt
cargo build --release --bin revdist
export REVDIST_CLI="$target/release/revdist"

# The wheel: abi3 (one wheel for CPython >= 3.9), stripped.
wheels="$target/wheels"
rm -f "$wheels"/revdist-*.whl
(
  cd python
  CARGO_TARGET_DIR="$target" "$venv/bin/maturin" build --release --quiet --out "$wheels"
)
wheel=$(ls "$wheels"/revdist-*.whl)

# A fresh venv with nothing but the wheel and what it declares (numpy): import it, pickle a
# solid, answer a query (from outside the source tree, so that python/revdist is not found).
fresh="$root/target/wheel-venv"
"$python" -m venv --clear "$fresh"
"$fresh/bin/python" -m pip install --quiet "$wheel"
(
  cd "$fresh"
  bin/python - <<'PY'
import pickle, numpy as np, revdist
a = pickle.loads(pickle.dumps(revdist.Solid.model("pawn", eps=1e-3)))
r = revdist.distance(a, revdist.Solid.model("cup", eps=1e-3), np.array([1.2, 0, 0.3, 1, 0, 0, 0]))
assert r.lower <= r.value <= r.upper, r
print(f"wheel {revdist.__file__}: pawn-cup {r.lower:.6f} <= {r.value:.6f} <= {r.upper:.6f}")
PY
)

# The tests, against the installed wheel (pytest's own entry point, which does not put
# python/ itself on sys.path).
"$venv/bin/python" -m pip install --quiet --force-reinstall --no-deps "$wheel"
(
  cd python
  "$venv/bin/pytest" -q -rs tests
)
"$venv/bin/python" examples/python/motion_interval.py --quick --out "$target/python-example"
