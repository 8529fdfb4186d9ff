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
# The programs as `cargo test` built them (it builds every binary, for the CLI tests): `cargo
# run` would build the library once more, with the features the dev-dependencies do not
# unify (about 2 min on 2 cores).
BIN="${CARGO_TARGET_DIR:-target}/release"
"$BIN/proof-lyapunov"
"$BIN/proof-equilibria"
"$BIN/proof-certificate" check
# the mutation guards still name code that exists (each guard's text once; no build)
python3 proofs/mutants/guards.py --check
# the Python package (issue #14): a venv, the package built with maturin, pytest (with the
# `bwcl` program of the test build)
BWCL_BIN="$BIN/bwcl" bash tests/python/run.sh
# the Python package's documentation: the API reference and the notebooks, executed, with
# warnings as errors (issue #34)
bash docs/build.sh
