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
"$VENV/bin/python" -m pip install -q --disable-pip-version-check \
    "sphinx>=7,<9" "myst-nb>=1.1,<2" ipykernel matplotlib pandas
"$VENV/bin/python" -c "import bwcl" || { echo "docs: the bwcl package is not installed in $VENV (bash tests/python/run.sh)" >&2; exit 1; }
# the notebooks' kernel is the venv's interpreter
"$VENV/bin/python" -m ipykernel install --prefix "$VENV" --name python3 >/dev/null
rm -rf docs/_build
PATH="$VENV/bin:$PATH" JUPYTER_PATH="$VENV/share/jupyter" \
    "$VENV/bin/python" -m sphinx -W --keep-going -q -b html docs docs/_build/html
echo "docs: built docs/_build/html in $(( $(date +%s) - start )) s (notebooks executed, no warnings)"
