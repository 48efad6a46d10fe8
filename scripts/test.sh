#!/usr/bin/env bash
# Runs revdist's whole test suite (core, verify, experiments, the Python package), installing
# system packages first.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
# Property tests draw from a fixed seed so that a run is reproducible (a random draw once failed
# CI on a profile no test had met); set PROPTEST_RNG_SEED to another value to explore.
export PROPTEST_RNG_SEED="${PROPTEST_RNG_SEED:-20261125}"
cargo test --workspace --release
# The Python package: built into target/python-venv and tested with pytest.
scripts/python-test.sh
