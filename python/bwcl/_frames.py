"""Results as tables: a short ``repr`` (a few figures, never whole arrays) and ``to_pandas()``
(pandas optional), shared by the result classes.

Printed bounds are bounds: where a repr or a frame shows an enclosure as text it uses the
decimals the engine rounded outward (lower bounds down, upper bounds and widths up); those
decimals read back to the very doubles of the float columns.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence

import numpy as np

#: names of the six nondimensional parameters as columns
SIX = ("B", "Gamma", "kappa", "sigma", "n", "p")


def pandas() -> Any:
    try:
        import pandas as pd  # type: ignore
    except ImportError as e:  # pragma: no cover - exercised without pandas
        raise ImportError("to_pandas() needs pandas: pip install pandas") from e
    return pd


def flat(x: Any) -> np.ndarray:
    """A per-case field as a 1-D array over the cases (set-major for a grid)."""
    return np.asarray(x).reshape(-1)


def flat_items(x: Any, depth: int) -> List[Any]:
    """A per-case tuple field (nested ``depth`` levels for a grid) as a flat list."""
    out: List[Any] = list(x)
    for _ in range(depth):
        out = [item for row in out for item in row]
    return out


def grid_index(shape: Sequence[int]) -> Dict[str, np.ndarray]:
    """The ``set`` (and ``speed``) index columns of a grid of cases of ``shape`` (m, n) —
    none for one set (shape (n,))."""
    if len(shape) < 2:
        return {}
    m, n = shape[0], shape[1]
    return {"set": np.repeat(np.arange(m), n), "speed": np.tile(np.arange(n), m)}


def params_columns(params: Any, per_case: int, bounds: bool) -> Dict[str, np.ndarray]:
    """The parameter columns: B, Gamma, … of an (…, 6[, 2]) array, or a law's by name."""
    cols: Dict[str, np.ndarray] = {}
    if isinstance(params, dict):
        items = list(params.items())
    else:
        a = np.asarray(params)
        a = a.reshape((per_case, 6, 2) if bounds else (per_case, 6))
        items = [(name, a[:, j]) for j, name in enumerate(SIX)]
    for name, v in items:
        v = np.asarray(v)
        if bounds:
            v = v.reshape(per_case, 2)
            cols[f"{name}_lo"] = v[:, 0]
            cols[f"{name}_hi"] = v[:, 1]
        else:
            cols[name] = v.reshape(per_case)
    return cols


def sample_columns(items: Sequence, floats: bool) -> Dict[str, Any]:
    """Columns of samples by name: a plain array as is, an (n, 2) array of enclosures as
    ``<name>_lo``/``<name>_hi`` (outward decimals, or the float bounds with ``floats``)."""
    cols: Dict[str, Any] = {}
    for name, v in items:
        v = np.asarray(v)
        if v.ndim == 2 and v.shape[1] == 2:
            cols[f"{name}_lo"], cols[f"{name}_hi"] = (
                (v[:, 0], v[:, 1]) if floats else outward_pairs(v))
        else:
            cols[name] = v
    return cols


def span(a: np.ndarray, digits: int = 4) -> str:
    """``lo…hi`` of the finite values of a float array (to ``digits`` figures; not bounds),
    or one value, or "—"."""
    a = np.asarray(a, dtype=float).reshape(-1)
    a = a[np.isfinite(a)]
    if a.size == 0:
        return "—"
    lo, hi = float(a.min()), float(a.max())
    if lo == hi:
        return f"{lo:.{digits}g}"
    return f"{lo:.{digits}g}…{hi:.{digits}g}"


def widest(widths: np.ndarray, texts: Sequence[Optional[str]]) -> Optional[str]:
    """The widest of the widths (each an upper bound) rounded up to 2 digits (None when
    nothing is proved)."""
    w = np.asarray(widths, dtype=float).reshape(-1)
    ok = [i for i in range(w.size) if texts[i] is not None and np.isfinite(w[i])]
    if not ok:
        return None
    return outward(max(w[i] for i in ok), True, 2)


def shape_text(shape: Sequence[int]) -> str:
    if len(shape) >= 2:
        return f"{shape[0]} sets × {shape[1]} speeds"
    n = shape[0] if shape else 0
    return f"{n} case{'s' if n != 1 else ''}"


def outward(x: float, up: bool, digits: Optional[int] = None) -> str:
    """A bound as a decimal on its outer side (``up``: ≥ x, else ≤ x): with ``digits``
    significant digits (a coarser bound), else the shortest such decimal that reads back to
    the double x (the CLI's convention). Non-finite values as ``inf``/``-inf``/``nan``."""
    from decimal import ROUND_CEILING, ROUND_FLOOR, Context, Decimal

    x = float(x)
    if not np.isfinite(x):
        return repr(x)
    exact = Decimal(x)
    rounding = ROUND_CEILING if up else ROUND_FLOOR

    def at(k: int) -> str:
        d = Context(prec=k, rounding=rounding).plus(exact)
        s = format(d, "g" if abs(d.adjusted()) < 16 else "e")
        return s.replace("E", "e")

    if digits is not None:
        return at(max(1, digits))
    shortest = repr(x)
    if (Decimal(shortest) >= exact) if up else (Decimal(shortest) <= exact):
        return shortest
    for k in range(1, 40):
        s = at(k)
        if float(s) == x:
            return s
    return format(exact, "f")  # unreachable: the exact value reads back


def bracket(lo: float, hi: float) -> str:
    """"[lo, hi]" with each end a decimal on its outer side."""
    return f"[{outward(lo, False)}, {outward(hi, True)}]"


def inward_pairs(lohi: Any) -> tuple:
    """(lo, hi) columns of an (…, 2) array of a range a result is claimed for (v0 given as
    a..b), rounded inward: each decimal still reads back to its double; a single double
    (lo == hi) as its exact decimal (its inward ends would cross)."""
    from decimal import Decimal

    a = np.asarray(lohi, dtype=float).reshape(-1, 2)

    def end(lo: float, hi: float, up: bool) -> str:
        x = lo if up else hi
        if lo == hi and np.isfinite(x):
            return format(Decimal(x), "f") if abs(Decimal(x).adjusted()) < 16 else str(Decimal(x))
        return outward(x, up)

    return ([end(lo, hi, True) for lo, hi in a], [end(lo, hi, False) for lo, hi in a])


def outward_pairs(lohi: Any, digits: Optional[int] = None) -> tuple:
    """(lo, hi) columns of an (…, 2) array of bounds as outward decimals."""
    a = np.asarray(lohi, dtype=float).reshape(-1, 2)
    return ([outward(v, False, digits) for v in a[:, 0]],
            [outward(v, True, digits) for v in a[:, 1]])
