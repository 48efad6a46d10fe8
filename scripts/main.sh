#!/usr/bin/env bash
# The main job: regenerates every figure and table under figures/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cargo build --release --workspace
target/release/revdist figures --out figures
