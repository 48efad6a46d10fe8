#!/usr/bin/env bash
# Times the main job as a newcomer's fresh Debian 12 machine runs it: a minimal bookworm
# (debootstrap --variant=minbase) in a chroot, given only what such a machine starts with
# (gcc, g++, make, git, curl, CA certificates, and the host's Rust toolchain mounted read-only
# with an empty cargo registry), a clean clone of this checkout's HEAD, and
# `bash scripts/main.sh` run in it: apt, pip, crate downloads, build and every step.
#
#   sudo bash scripts/fresh_machine.sh [DIR]    # DIR defaults to /var/tmp/revdist-fresh (~2.5 GB)
#
# Needs root and debootstrap (apt-get install debootstrap). Writes the run's figures/ (step
# times in DIR/figures/main_timing.txt) and its log DIR/main.log; the chroot is removed at
# the end. The host's
# /etc/ssl/certs/ca-certificates.crt is copied in, so a proxy's CA the host trusts works.
set -euo pipefail
[ "$(id -u)" -eq 0 ] || { echo "error: needs root (chroot, mount)" >&2; exit 2; }
command -v debootstrap > /dev/null || { echo "error: debootstrap missing: apt-get install debootstrap" >&2; exit 2; }
repo=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-/var/tmp/revdist-fresh}
root="$dir/root"
rustup_home=${RUSTUP_HOME:-$HOME/.rustup}
cargo_bin=${CARGO_HOME:-$HOME/.cargo}/bin
[ -d "$rustup_home/toolchains" ] || { echo "error: no Rust toolchain under $rustup_home" >&2; exit 2; }
[ ! -e "$root" ] || { echo "error: $root exists (a previous run?): remove it first" >&2; exit 2; }
mkdir -p "$dir"

mounts=()
cleanup() {
  local i
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount -l "${mounts[i]}" 2> /dev/null || true; done
  # Never remove through a mount that is still there (/dev, the toolchain).
  if grep -q " $root/" /proc/mounts; then
    echo "warning: mounts remain under $root: not removed" >&2
  else
    rm -rf "$root"
  fi
}
trap cleanup EXIT
bind() {  # bind SOURCE TARGET [ro]
  mkdir -p "$2"
  mount --bind "$1" "$2"
  mounts+=("$2")
  [ "${3:-}" != ro ] || mount -o remount,ro,bind "$2"
}

debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian > "$dir/debootstrap.log"
mount -t proc proc "$root/proc"; mounts+=("$root/proc")
bind /dev "$root/dev"; bind /dev/pts "$root/dev/pts"; bind /sys "$root/sys"
cp /etc/resolv.conf "$root/etc/resolv.conf"
chroot "$root" bash -c 'export DEBIAN_FRONTEND=noninteractive; apt-get update -qq &&
  apt-get install -y -qq --no-install-recommends gcc g++ make git curl ca-certificates libc6-dev sudo' > /dev/null
cp /etc/ssl/certs/ca-certificates.crt "$root/etc/ssl/certs/ca-certificates.crt"
bind "$rustup_home" "$root/root/.rustup" ro
mkdir -p "$root/root/.cargo/bin"
cp -a "$cargo_bin/." "$root/root/.cargo/bin/"
git clone -q "$repo" "$root/opt/revdist"

ca=/etc/ssl/certs/ca-certificates.crt
chroot "$root" env -i HOME=/root PATH=/root/.cargo/bin:/usr/sbin:/usr/bin:/sbin:/bin \
  RUSTUP_HOME=/root/.rustup CARGO_HOME=/root/.cargo SSL_CERT_FILE=$ca PIP_CERT=$ca \
  CURL_CA_BUNDLE=$ca GIT_SSL_CAINFO=$ca \
  bash -c 'cd /opt/revdist && git log --oneline -1 && bash scripts/main.sh' 2>&1 | tee "$dir/main.log"
rm -rf "$dir/figures"
cp -r "$root/opt/revdist/figures" "$dir/figures"
echo "fresh-machine main job: step times in $dir/figures/main_timing.txt, its figures in $dir/figures/"
