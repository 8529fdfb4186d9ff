"""Many parameter sets in one call: ``base``/``nd``/``physical`` given as an (m, 6) array, a
list of sets, or a mapping whose values are 1-D arrays, broadcast against ``v0``.

The sets go to the extension as texts (each read as the CLI reads ``--base``), their cases are
built set-major and run on one thread pool, and every per-case field of the result is reshaped
from (m·n, …) to (m, n, …) — (m, …) for ``nd``, which has no speeds.
"""

from __future__ import annotations

import dataclasses
from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

#: The most cases (sets × speeds) of one call: about 2 GB of cases and rows; a larger sweep is
#: split (the Dask example sends chunks of sets).
MAX_CASES = 10_000_000


def _is_list(x: Any) -> bool:
    return isinstance(x, (list, np.ndarray))


def _bouc_wen_sets(x: Any, what: str, ranges: bool) -> Optional[List[str]]:
    """The texts of several Bouc–Wen sets, or None for one set (then read as before)."""
    from . import _six

    if isinstance(x, np.ndarray):
        if x.ndim != 2:
            return None
        if x.shape[0] == 0:
            raise ValueError(f"{what}: an array of 0 parameter sets")
        if x.shape[1] != 6:
            raise ValueError(
                f"{what}: an array of parameter sets has one set of six values B,Γ,κ,σ,n,p per "
                f"row, got shape {x.shape}"
            )
        return [_six(row, f"{what}[{i}]", ranges) for i, row in enumerate(x)]
    if isinstance(x, str) or not isinstance(x, Sequence) or len(x) == 0:
        return None

    def is_set(item: Any) -> bool:
        if isinstance(item, str):
            return "," in item
        return isinstance(item, (list, tuple, np.ndarray)) and len(item) == 6

    if not all(is_set(item) for item in x):
        return None
    return [_six(item, f"{what}[{i}]", ranges) for i, item in enumerate(x)]


def _named_sets(x: Any, what: str, ranges: bool, text: Any) -> Optional[List[str]]:
    """Several sets by name: a list of mappings, or a mapping with 1-D arrays as values
    (scalars repeated for every set)."""
    if isinstance(x, (list, tuple)) and len(x) > 0 and all(hasattr(m, "items") for m in x):
        return [text(m, f"{what}[{i}]") for i, m in enumerate(x)]
    if not hasattr(x, "items"):
        return None
    lengths = {k: len(v) for k, v in x.items() if _is_list(v) and np.ndim(v) == 1}
    if not lengths:
        for k, v in x.items():
            if _is_list(v):
                raise ValueError(f"{what}: {k} must be a value or a 1-D array of values, got "
                                 f"shape {np.shape(v)}")
        return None
    m = set(lengths.values())
    if len(m) != 1:
        raise ValueError(
            f"{what}: the arrays of values differ in length ({', '.join(f'{k}: {n}' for k, n in lengths.items())})"
        )
    (m,) = m
    if m == 0:
        raise ValueError(f"{what}: arrays of 0 values (no parameter set)")
    sets = []
    for i in range(m):
        one = {k: (v[i] if k in lengths else v) for k, v in x.items()}
        one = {k: (v.item() if isinstance(v, np.generic) else v) for k, v in one.items()}
        sets.append(text(one, f"{what}[{i}]"))
    return sets


def source_sets(model: Any, base: Any, nd: Any, physical: Any,
                ranges: bool) -> Tuple[Any, Any, Any, Optional[List[str]]]:
    """(base, nd, physical, sets): with several sets in the one source given, that source is
    replaced by its first set's text (so that the CLI's checks of the arguments run) and
    ``sets`` lists every set's text; else the arguments unchanged and None."""
    from . import LAWS, _named, _physical

    given = [(k, v) for k, v in (("base", base), ("nd", nd), ("physical", physical))
             if v is not None]
    if len(given) != 1 or not isinstance(model, str):
        return base, nd, physical, None
    (what, x), = given
    if what == "physical":
        sets = _named_sets(x, what, ranges, lambda m, w: _physical(m, ranges))
    elif model in LAWS:
        sets = _named_sets(x, what, ranges, lambda m, w: _named(m, w, ranges))
    else:
        sets = _bouc_wen_sets(x, what, ranges)
    if sets is None:
        return base, nd, physical, None
    first = {"base": None, "nd": None, "physical": None}
    first[what] = sets[0]
    return first["base"], first["nd"], first["physical"], sets


def check_size(sets: Optional[List[str]], speeds: int) -> None:
    m = 1 if sets is None else len(sets)
    if m * max(speeds, 1) > MAX_CASES:
        raise ValueError(
            f"{m} parameter set(s) × {speeds} speed(s) = {m * speeds} cases: at most {MAX_CASES} "
            "in one call (split the sweep: the Dask example sends chunks of sets)"
        )


def _nest(seq: Sequence, m: int) -> tuple:
    per = len(seq) // m
    return tuple(tuple(seq[i * per:(i + 1) * per]) for i in range(m))


def _grid(x: Any, n: int, m: int, nd: bool) -> Any:
    if isinstance(x, np.ndarray) and x.ndim >= 1 and x.shape[0] == n:
        return x.reshape((m,) + x.shape[1:] if nd else (m, n // m) + x.shape[1:])
    if isinstance(x, tuple) and len(x) == n:
        return tuple(x) if nd else _nest(x, m)
    if isinstance(x, dict):
        return {k: _grid(v, n, m, nd) for k, v in x.items()}
    return x


def reshape(result: Any, sets: Optional[List[str]], nd: bool) -> Any:
    """``result`` (a dataclass of per-case fields in set-major order) with every per-case
    field as (m, n, …), or (m, …) for ``nd``; unchanged for one set."""
    if sets is None:
        return result
    n = len(result)
    m = len(sets)
    changes = {f.name: _grid(getattr(result, f.name), n, m, nd)
               for f in dataclasses.fields(result)}
    return dataclasses.replace(result, **changes)

