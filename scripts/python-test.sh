#!/usr/bin/env bash
# Builds the Python package (python/) into a project-local virtual environment and runs its
# tests (pytest): parity with `revdist distance --batch`, shapes and errors, the GIL released,
# Pair against cold queries. Called by scripts/test.sh; runs alone too.
# The venv lives in target/python-venv (git-ignored); its tools are pinned in
# python/requirements-test.txt and come from the package index. The extension is compiled
# into the same Cargo target directory as the workspace, so crates.io dependencies built for
# the core are reused.
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
(
  cd python
  VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" CARGO_TARGET_DIR="$target" \
    "$venv/bin/maturin" develop --release --quiet
  "$venv/bin/python" -m pytest -q -rs tests
)
"$venv/bin/python" examples/python/motion_interval.py --quick --out "$target/python-example"
