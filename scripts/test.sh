#!/usr/bin/env bash
# Runs revdist's whole test suite (core, verify, experiments), installing system packages first.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cargo test --workspace --release
