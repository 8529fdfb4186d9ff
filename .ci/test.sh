#!/usr/bin/env bash
# The test command of the README: setup, the whole test suite (unit, integration, property
# tests, CLI, proofs' cores), the computer-assisted proofs as programs (each exits non-zero if
# it cannot prove its statement) and the re-check of the Table 1 certificate, the mutation
# guards' check, the Python package's tests and its documentation with the notebooks executed.
#
# On 2 CPUs the order is chosen so that no core idles (issue #34, the test command's time):
# the Python venv and wheels are downloaded while cargo compiles; then the Rust test programs
# run (started directly, not by `cargo test`, which would hold cargo's lock on the target
# directory) while the extension is built, and beside the Python tests and the documentation
# (each of those leaves a core mostly idle on its own); the doc-tests last. Each part's output
# is printed when it ends; the exit status is non-zero if any part failed.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
stamp() { echo "test.sh: $1 ($(( $(date +%s) - start )) s)"; }
FLAGS=$(bash .ci/setup.sh)
export BWCL_CARGO_FLAGS="$FLAGS" # for tests/python/run.sh
LOGS=$(mktemp -d)
trap 'rm -rf "$LOGS"' EXIT
show() { # name: print a part's log, framed
    echo "----- $1 -----"
    cat "$LOGS/$1.log"
    echo "----- end of $1 -----"
}

# the Python side's setup (a venv, the wheels of the tests and of the documentation) in the
# background: mostly network and disk
{ BWCL_PY_STEPS=setup bash tests/python/run.sh && BWCL_DOCS_STEPS=setup bash docs/build.sh; } \
    >"$LOGS/python-setup.log" 2>&1 &
setup_pid=$!

# shellcheck disable=SC2086 # FLAGS is empty or a few flags
cargo test --release $FLAGS --no-run
stamp "compiled"
if ! wait "$setup_pid"; then
    show python-setup
    echo "test.sh: the Python setup failed" >&2
    exit 1
fi
stamp "Python venv ready"

# The programs as `cargo test` built them: `cargo run` would build the library once more,
# with the features the dev-dependencies do not unify (about 2 min on 2 cores).
BIN="${CARGO_TARGET_DIR:-target}/release"
# the test programs `cargo test` runs (the unit tests, the suite), from cargo's messages (the
# build above is done: this only lists it)
# shellcheck disable=SC2086
TESTS=$(cargo test --release $FLAGS --no-run --message-format=json 2>/dev/null | python3 -c '
import json, sys
for line in sys.stdin:
    try:
        m = json.loads(line)
    except ValueError:
        continue
    if m.get("reason") == "compiler-artifact" and m.get("profile", {}).get("test") \
            and m.get("executable"):
        print(m["executable"])')
[ -n "$TESTS" ] || { echo "test.sh: no test program found" >&2; exit 1; }
# the Rust tests (from the repository root, as `cargo test` runs them), one program after the
# other, each printing its name and result
{
    rc=0
    for t in $TESTS; do
        echo "     Running $t"
        "$t" || rc=1
    done
    exit "$rc"
} >"$LOGS/rust-tests.log" 2>&1 &
rust_pid=$!
# the extension module, linking the library `cargo test` built, then the Python tests and the
# documentation (the package's API reference and the notebooks, executed, with warnings as
# errors: issue #34)
{ BWCL_PY_STEPS=build BWCL_BIN="$BIN/bwcl" bash tests/python/run.sh && \
    BWCL_PY_STEPS=test BWCL_BIN="$BIN/bwcl" bash tests/python/run.sh && \
    BWCL_DOCS_STEPS=build bash docs/build.sh; } >"$LOGS/python-tests.log" 2>&1 &
python_pid=$!
status=0
if wait "$python_pid"; then py=ok; else py=FAILED; status=1; fi
show python-tests
stamp "Python tests and documentation: $py"
if wait "$rust_pid"; then rust=ok; else rust=FAILED; status=1; fi
show rust-tests
stamp "Rust tests: $rust"
[ "$status" = 0 ] || exit "$status"
# the documentation's examples (cargo's lock is free now)
# shellcheck disable=SC2086
cargo test --release $FLAGS --doc

"$BIN/proof-lyapunov"
"$BIN/proof-equilibria"
"$BIN/proof-certificate" check
# the mutation guards still name code that exists (each guard's text once; no build)
python3 proofs/mutants/guards.py --check
stamp "done"
