#!/usr/bin/env bash
# Installs the Debian packages revdist's harness needs, only when some are missing.
# Core library: nothing (pure Rust). verify/: GMP + MPFR for exact arithmetic (rug with system libs).
# Usage: scripts/deps.sh [extra packages...]
set -euo pipefail
packages=(pkg-config m4 libgmp-dev libmpfr-dev "$@")
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
