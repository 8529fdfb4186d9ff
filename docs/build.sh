#!/usr/bin/env bash
# The Python package's documentation: the API reference from the docstrings and the three
# notebooks, each executed (myst-nb; a cell that raises fails the build), with warnings as
# errors. Needs the package installed in the venv of tests/python/run.sh (run that first, or
# set BWCL_VENV); installs the documentation tools from PyPI into it.
#
#   bash docs/build.sh            # → docs/_build/html/index.html
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
VENV="${BWCL_VENV:-$ROOT/.venv-test}"
start=$(date +%s)
# BWCL_DOCS_STEPS: the steps to run, default "setup build" (setup = the documentation tools
# from PyPI and the notebooks' kernel; .ci/test.sh runs it while cargo compiles)
STEPS="${BWCL_DOCS_STEPS:-setup build}"
step() { case " $STEPS " in *" $1 "*) return 0 ;; *) return 1 ;; esac; }
if step setup; then
    "$VENV/bin/python" -m pip install -q --disable-pip-version-check \
        "sphinx>=7,<9" "myst-nb>=1.1,<2" ipykernel matplotlib pandas
    # the notebooks' kernel is the venv's interpreter
    "$VENV/bin/python" -m ipykernel install --prefix "$VENV" --name python3 >/dev/null
fi
if step build; then
    "$VENV/bin/python" -c "import bwcl" || { echo "docs: the bwcl package is not installed in $VENV (bash tests/python/run.sh)" >&2; exit 1; }
    rm -rf docs/_build
    PATH="$VENV/bin:$PATH" JUPYTER_PATH="$VENV/share/jupyter" \
        "$VENV/bin/python" -m sphinx -W --keep-going -q -b html docs docs/_build/html
    echo "docs: built docs/_build/html in $(( $(date +%s) - start )) s (notebooks executed, no warnings)"
fi
