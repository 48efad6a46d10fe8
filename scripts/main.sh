#!/usr/bin/env bash
# The main job: regenerates every figure and table under figures/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cargo build --release --workspace
out=figures
mkdir -p "$out"
target/release/revdist figures --out "$out"          # model profiles and M_t frames
target/release/convergence "$out"                    # biarc vs chord convergence (CSV + SVG)
target/release/accuracy_time "$out"                  # tree sizes, certified query times (CSV + MD + SVG)
target/release/fcl_bench --out "$out"                # revdist vs FCL OBBRSS/RSS at equal eps (CSV + MD), ~6 min
target/release/verify crosscheck --out "$out/crosscheck"   # revdist vs FCL, CGAL, libccd on certified meshes (MD + CSV)
target/release/patch_kernels "$out"                  # leaf kernels: time per patch pair, misses near contact
echo "figures and tables written to $out/"
