#!/usr/bin/env bash
# Installs the Debian packages revdist's harness needs, only when some are missing.
# Core library: nothing (pure Rust). verify/: GMP + MPFR for exact arithmetic (rug with system libs),
# and the C++ baselines bridged with cxx (verify/build.rs, cpp/): FCL 0.7 (pulls in octomap),
# libccd 2.1, CGAL 5.5 (header-only; pulls in Boost) and Eigen 3; OpenCASCADE 7.6 (the exact
# B-rep reference; a header it needs ships only in libocct-visualization-dev; libtbb12 at run time).
# python/ (scripts/python-test.sh): Python 3 with its venv and pip modules. experiments/' peers
# benchmark: coal 3 from PyPI's libcoal wheel (C++ headers and libcoal.so under cmeel.prefix/),
# installed with pip into .peers/coal in the checkout (git-ignored; nothing system-wide).
# Usage: scripts/deps.sh [extra packages...]
set -euo pipefail
packages=(pkg-config m4 libgmp-dev libmpfr-dev libfcl-dev libccd-dev libcgal-dev libeigen3-dev
  libocct-modeling-algorithms-dev libocct-visualization-dev libtbb12
  python3 python3-venv python3-pip "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "revdist: installing missing packages: ${missing[*]}" >&2
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then
    sudo_cmd=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# coal for the peers benchmark (docs/verification.md, "Peers"): experiments/build.rs compiles cpp/coal/coal_peer.cc
# against it. About 350 MB with its cmeel dependencies (Boost, assimp, octomap, qhull, zlib).
coal_version=3.0.3
root=$(cd "$(dirname "$0")/.." && pwd)
coal_dir="$root/.peers/coal"
if [ ! -f "$coal_dir/cmeel.prefix/lib/libcoal.so" ] || [ ! -d "$coal_dir/libcoal-$coal_version.dist-info" ]; then
  echo "revdist: installing coal $coal_version (PyPI libcoal wheel) into $coal_dir" >&2
  rm -rf "$coal_dir.tmp"
  py=/usr/bin/python3  # Debian's, with the python3-pip installed above (not a pyenv shim's)
  [ -x "$py" ] || py=python3
  if ! "$py" -m pip install --disable-pip-version-check --no-warn-script-location --root-user-action=ignore -q \
      --target "$coal_dir.tmp" "libcoal==$coal_version"; then
    rm -rf "$coal_dir.tmp"
    free=$(df -h --output=avail "$root" 2>/dev/null | tail -1 | tr -d ' ')
    echo "revdist: error: pip could not install libcoal==$coal_version (about 350 MB; pip's error above says why: no network, or no space left, ${free:-?} free under $root); the peers benchmark needs it" >&2
    exit 1
  fi
  rm -rf "$coal_dir"
  mv "$coal_dir.tmp" "$coal_dir"
  # The shim's build script watches its source: a new coal is picked up by the next build.
  touch "$root/cpp/coal/coal_peer.cc"
fi
