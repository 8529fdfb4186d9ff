"""The extension module's functions, with their messages in the Python call's own terms.

The extension reads the CLI's arguments, so its messages name the CLI's options
(``'--max-step <H>'``, ``--v0``, "see --help"). Every call of the package goes through
:data:`native`, which rewrites them as the keyword arguments of the Python call
(``max_step``, ``v0``) and keeps the exception's type: ``ValueError`` for bad input,
``RuntimeError`` for a computation that failed on valid input, ``KeyboardInterrupt`` as is.
"""

from __future__ import annotations

import functools
import re
from typing import Any

from . import _bwcl

# '--max-step <H>' / "--max-step <H>" / --max-step=… / --max-step → max_step
_OPTION = re.compile(r"""(['"]?)--([a-z][a-z0-9-]*)(?:[ =]<[^>]*>)?\1""")
# the CLI's pointers to its help, which mean nothing in Python
_HELP = re.compile(r"\s*[(;,]?\s*(?:see|try) '?--help'?\)?\.?|\s*For more information, try '--help'\.?",
                   re.IGNORECASE)
#: options whose Python name differs from the CLI's
_RENAMED = {"physical-units": "physical_units", "v0": "v0", "t-end": "t_end"}


# --fix name=value / --bounds name=lo..hi as the Python call writes them
_FIX = re.compile(r"--fix[ =]([A-Za-z_]+)=([^\s,)]+)")
_BOUNDS = re.compile(r"--bounds[ =]([A-Za-z_]+)=([^\s,.)]+)\.\.([^\s,)]+)")


def pythonic(message: str) -> str:
    """A CLI message with the options written as the Python call's keyword arguments."""
    message = _HELP.sub("", message)
    message = _FIX.sub(lambda m: f"fix={{'{m.group(1)}': {m.group(2)}}}", message)
    message = _BOUNDS.sub(lambda m: f"bounds={{'{m.group(1)}': ({m.group(2)}, {m.group(3)})}}",
                          message)

    def name(m: "re.Match[str]") -> str:
        opt = m.group(2)
        return _RENAMED.get(opt, opt.replace("-", "_"))

    return _OPTION.sub(name, message).strip()


class _Native:
    """The extension module, its functions' messages rewritten by :func:`pythonic`."""

    def __getattr__(self, name: str) -> Any:
        f = getattr(_bwcl, name)
        if not callable(f):
            return f

        @functools.wraps(f)
        def call(*args: Any, **kwargs: Any) -> Any:
            try:
                return f(*args, **kwargs)
            except (ValueError, RuntimeError) as e:
                if type(e) not in (ValueError, RuntimeError):
                    raise
                raise type(e)(pythonic(str(e))) from None

        return call


#: the extension, as the package calls it
native = _Native()
