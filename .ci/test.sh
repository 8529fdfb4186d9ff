#!/usr/bin/env bash
# The test command of the README: setup, the whole test suite (unit, integration, property
# tests, CLI, proofs' cores), then the computer-assisted proofs as programs (each exits
# non-zero if it cannot prove its statement) and the re-check of the Table 1 certificate.
set -euo pipefail
cd "$(dirname "$0")/.."
FLAGS=$(bash .ci/setup.sh)
export BWCL_CARGO_FLAGS="$FLAGS" # for tests/python/run.sh
# shellcheck disable=SC2086 # FLAGS is empty or a few flags
cargo test --release $FLAGS
# shellcheck disable=SC2086
cargo run --release --quiet $FLAGS --bin proof-lyapunov
# shellcheck disable=SC2086
cargo run --release --quiet $FLAGS --bin proof-equilibria
# shellcheck disable=SC2086
cargo run --release --quiet $FLAGS --bin proof-certificate -- check
# the mutation guards still name code that exists (each guard's text once; no build)
python3 proofs/mutants/guards.py --check
# the Python package (issue #14): a venv, the package built with maturin, pytest
bash tests/python/run.sh
