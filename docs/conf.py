# Sphinx configuration of the bwcl Python package's documentation: the API reference from the
# docstrings (autodoc + napoleon, NumPy style) and the worked notebooks, executed at every
# build (myst-nb), so that they cannot rot. Built by docs/build.sh with warnings as errors.
project = "bwcl"
author = "the bwcl developers"
extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "myst_nb",
]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
exclude_patterns = ["_build", "**.ipynb_checkpoints"]
master_doc = "index"
html_theme = "alabaster"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
autodoc_member_order = "bysource"
autodoc_typehints = "none"
# every notebook runs at every build; a cell that raises fails the build
nb_execution_mode = "force"
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_execution_show_tb = True
suppress_warnings = ["myst.header"]


# The package's docstrings write parameters as "name : what it is" (one line, then indented
# lines): napoleon would read the part after the colon as a type. They are rewritten as
# "name" and an indented description before napoleon reads them.
import re  # noqa: E402

_PARAM = re.compile(r"^(\w[\w, ]*) : (.+)$")
_SECTIONS = ("Parameters", "Attributes", "Other Parameters")


def _descriptions(app, what, name, obj, options, lines):
    out, inside = [], False
    for i, line in enumerate(lines):
        nxt = lines[i + 1].strip() if i + 1 < len(lines) else ""
        if line.strip() and nxt and set(nxt) == {"-"}:
            inside = line.strip() in _SECTIONS
        m = _PARAM.match(line) if inside else None
        if m:
            out += [m.group(1), "    " + m.group(2)]
        else:
            out.append(line)
    lines[:] = out


def setup(app):
    app.connect("autodoc-process-docstring", _descriptions, priority=100)
