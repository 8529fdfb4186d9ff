#!/usr/bin/env bash
# The test command of the README: setup, the whole test suite (unit, integration, property
# tests, CLI, proofs' cores), then the computer-assisted proofs as programs (each exits
# non-zero if it cannot prove its statement) and the re-check of the Table 1 certificate.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup.sh
cargo test --release
cargo run --release --quiet --bin proof-lyapunov
cargo run --release --quiet --bin proof-equilibria
cargo run --release --quiet --bin proof-certificate -- check
