#!/usr/bin/env bash
# Installs the Debian packages revdist's harness needs, only when some are missing.
# Core library: nothing (pure Rust). verify/: GMP + MPFR for exact arithmetic (rug with system libs),
# and the C++ baselines bridged with cxx (verify/build.rs, cpp/): FCL 0.7 (pulls in octomap),
# libccd 2.1, CGAL 5.5 (header-only; pulls in Boost) and Eigen 3; OpenCASCADE 7.6 (the exact
# B-rep reference; a header it needs ships only in libocct-visualization-dev; libtbb12 at run time).
# Usage: scripts/deps.sh [extra packages...]
set -euo pipefail
packages=(pkg-config m4 libgmp-dev libmpfr-dev libfcl-dev libccd-dev libcgal-dev libeigen3-dev
          libocct-modeling-algorithms-dev libocct-visualization-dev libtbb12 "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "revdist: installing missing packages: ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
