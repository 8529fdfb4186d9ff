#!/usr/bin/env bash
# The Python package's tests on a fresh machine: a venv (.venv-test), the test tools from PyPI,
# the `bwcl` program (the tests compare against it) and the package built from this checkout
# into the venv (maturin develop --release: the same cargo target directory as the program, so
# a warm cargo cache is reused), then pytest on tests/python/.
#
#   bash tests/python/run.sh            # extra arguments go to pytest, e.g. -k dask -x
#
# Environment: PYTHON (the interpreter for the venv, default python3), BWCL_VENV (default
# .venv-test at the repo root), CARGO_TARGET_DIR (default target/), BWCL_CARGO_FLAGS (extra
# cargo flags, set by .ci/test.sh after its setup), BWCL_PY_STEPS (the steps to run, default
# "setup build test": setup = the venv and the wheels, build = the program and the package,
# test = pytest; .ci/test.sh runs the setup while cargo compiles).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
VENV="${BWCL_VENV:-$ROOT/.venv-test}"
PY="${PYTHON:-python3}"
start=$(date +%s)

STEPS="${BWCL_PY_STEPS:-setup build test}"
step() { case " $STEPS " in *" $1 "*) return 0 ;; *) return 1 ;; esac; }

if step setup; then
    if [ ! -x "$VENV/bin/python" ]; then
        if ! "$PY" -m venv "$VENV" 2>/dev/null; then
            # Debian/Ubuntu ship venv (ensurepip) separately
            rm -rf "$VENV"
            SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
            $SUDO apt-get update -qq && $SUDO apt-get install -y -qq python3-venv >/dev/null
            "$PY" -m venv "$VENV"
        fi
    fi
    "$VENV/bin/python" -m pip install -q --disable-pip-version-check \
        "maturin>=1.7,<2" numpy scipy pytest "dask[distributed]" pandas matplotlib
fi

# BWCL_BIN: a `bwcl` program already built (.ci/test.sh passes the one `cargo test` built).
BIN="${BWCL_BIN:-$CARGO_TARGET_DIR/release/bwcl}"
if step build; then
    echo "run.sh: building the bwcl program and the Python package (CARGO_TARGET_DIR=$CARGO_TARGET_DIR)"
    # BWCL_CARGO_FLAGS: the cargo flags of .ci/setup.sh (the GMP/MPFR fallback), for both builds.
    if [ -z "${BWCL_BIN:-}" ] || [ ! -x "$BWCL_BIN" ]; then
        # shellcheck disable=SC2086 # empty or a few flags
        cargo build --release --quiet ${BWCL_CARGO_FLAGS:-} --bin bwcl
    fi
    # shellcheck disable=SC2086
    VIRTUAL_ENV="$VENV" PATH="$VENV/bin:$PATH" "$VENV/bin/maturin" develop --release --quiet ${BWCL_CARGO_FLAGS:-}
fi

if step test; then
    BWCL_BIN="$BIN" "$VENV/bin/python" -m pytest tests/python -q "$@"
fi
echo "run.sh: $STEPS: done in $(( $(date +%s) - start )) s"
