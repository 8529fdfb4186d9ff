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

# a quoted option as clap names it: '--max-step <H>' (a quoted '--x' is a value the user wrote)
_QUOTED_OPTION = re.compile(r"""(['"])--([a-z][a-z0-9-]*) <[^>]*>\1""")
# an option in the text (not inside a value): --max-step, --max-step=…, --max-step <H>
_OPTION = re.compile(r"(?<![\w'\"-])--([a-z][a-z0-9-]*)(?:[ =]<[^>]*>)?")
# a quoted value as the user wrote it, left alone
_QUOTED = re.compile(r"'[^']*'|\"[^\"]*\"")
# the CLI's pointers to its help, which mean nothing in Python
_HELP = re.compile(r"\s*[(;,]?\s*(?:see|try) '?--help'?\)?\.?|\s*For more information, try '--help'\.?",
                   re.IGNORECASE)
#: options whose Python name differs from the CLI's
_RENAMED = {"physical-units": "physical_units", "v0": "v0", "t-end": "t_end"}
# --fix name=value / --bounds name=lo..hi as the Python call writes them
_FIX = re.compile(r"(?<![\w-])--fix[ =]([A-Za-z_]+)=([^\s,)']+)")
_BOUNDS = re.compile(r"(?<![\w-])--bounds[ =]([A-Za-z_]+)=([^\s,)']+?)\.\.([^\s,)']+)")
# "v0: v0 = …" after "--v0: v0 = …" is rewritten: one name is enough
_TWICE = re.compile(r"^(\w+): \1(\W)")


def _name(opt: str) -> str:
    return _RENAMED.get(opt, opt.replace("-", "_"))


def pythonic(message: str) -> str:
    """A CLI message with the options written as the Python call's keyword arguments; the
    values the user wrote, quoted in the message, are left as written."""
    message = _HELP.sub("", message)
    message = _QUOTED_OPTION.sub(lambda m: _name(m.group(2)), message)
    out, end = [], 0
    for q in _QUOTED.finditer(message):
        out.append(_plain(message[end:q.start()]))
        out.append(q.group(0))
        end = q.end()
    out.append(_plain(message[end:]))
    return _TWICE.sub(r"\1\2", "".join(out).strip())


def _plain(text: str) -> str:
    text = _FIX.sub(lambda m: f"fix={{'{m.group(1)}': {m.group(2)}}}", text)
    text = _BOUNDS.sub(lambda m: f"bounds={{'{m.group(1)}': ({m.group(2)}, {m.group(3)})}}",
                       text)
    return _OPTION.sub(lambda m: _name(m.group(1)), text)


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
