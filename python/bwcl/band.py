"""Proved statements over a whole range of impact speeds: the CoR band (:func:`band`, the
CLI's ``cor --rigorous --band``) and the monotonicity of e(v0) (:func:`prove_monotone`, the
CLI's ``prove monotone``).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Optional, Tuple, Union

import numpy as np

from . import _flags_checked
from ._native import native as _bwcl

__all__ = ["band", "BandResult", "InterpBandResult", "prove_monotone", "MonotoneResult"]


def _range(v0: Any, what: str) -> str:
    """A range of speeds (lo, hi) — or the CLI's text "a..b" — as the CLI's token."""
    from . import _num

    if isinstance(v0, str):
        return v0
    try:
        lo, hi = v0
    except (TypeError, ValueError):
        raise TypeError(f"{what}: expected a range of impact speeds (lo, hi), got {v0!r:.40}") from None
    try:
        wrong = float(lo) >= float(hi)
    except (TypeError, ValueError):
        wrong = False  # the CLI names what it cannot read
    if wrong:
        raise ValueError(f"{what}: expected a range (lo, hi) with lo < hi, got ({lo!r:.20}, {hi!r:.20})")
    return f"{_num(lo, what)}..{_num(hi, what)}"


@dataclass(frozen=True, eq=False, repr=False)
class BandResult:
    """The proved CoR curve over a range of v0, piece by piece: on piece i, for every v0 in
    [v0_lo[i], v0_hi[i]], e(v0) ∈ e_c[i] + de[i]·(v0 − v0_c[i]) (interval arithmetic) and
    T_s likewise; ``e``/``ts`` the hulls of each piece, ``thickness`` the largest vertical
    width of the band. Every bound is rounded outward (the pieces' v0 ends inward, the centres
    exact); ``pieces`` holds the report's text of every field as written (exact decimals)."""

    model: str
    #: the range proved, as floats and (``v0_text``) as the report's decimals, rounded inward
    v0_range: Tuple[float, float]
    v0_lo: np.ndarray
    v0_hi: np.ndarray
    v0_c: np.ndarray
    e_c: np.ndarray
    de: np.ndarray
    e: np.ndarray
    ts_c: np.ndarray
    dts: np.ndarray
    ts: np.ndarray
    piece_thickness: np.ndarray
    thickness: float
    seconds: float
    pieces: Tuple[dict, ...]
    v0_text: Tuple[str, str] = ("", "")

    def __len__(self) -> int:
        return len(self.v0_lo)

    def __repr__(self) -> str:
        from ._frames import outward

        lo = outward(float(np.min(self.e[:, 0])), False, 6) if len(self) else "—"
        hi = outward(float(np.max(self.e[:, 1])), True, 6) if len(self) else "—"
        return (f"BandResult(model={self.model!r}, v0 ∈ [{self.v0_text[0]}, "
                f"{self.v0_text[1]}], {len(self)} pieces, thickness ≤ "
                f"{outward(self.thickness, True, 3)}, e ∈ [{lo}, {hi}], {self.seconds:.3g} s)")

    def to_pandas(self) -> Any:
        """One row per piece, the report's exact decimals as text (each bound outward), so that
        printing the frame prints bounds; ``astype(float)`` gives the float bounds."""
        from ._frames import pandas

        return pandas().DataFrame(list(self.pieces))


def _down(x: Fraction) -> float:
    """The largest float ≤ x (−inf below the floats' range)."""
    try:
        f = float(x)
    except OverflowError:
        return -math.inf if x < 0 else math.nextafter(math.inf, 0)
    return f if Fraction(f) <= x else math.nextafter(f, -math.inf)


def _up(x: Fraction) -> float:
    """The smallest float ≥ x (+inf above the floats' range)."""
    try:
        f = float(x)
    except OverflowError:
        return math.inf if x > 0 else math.nextafter(-math.inf, 0)
    return f if Fraction(f) >= x else math.nextafter(f, math.inf)


@dataclass(frozen=True, eq=False, repr=False)
class InterpBandResult:
    """The proved CoR curve over a range of v0 in the interpolation form (:func:`band` with
    ``second_order=True``, the CLI's ``--band --second-order``), one row per node interval
    [v0_lo[i], v0_hi[i]] (h = v0_hi − v0_lo): for every v0 in it,

    e(v0) ∈ e_at_lo·(v0_hi − v0)/h + e_at_hi·(v0 − v0_lo)/h − d2e·(v0 − v0_lo)(v0_hi − v0)/2,

    with e_at_lo, e_at_hi the proved e at the nodes and d2e the proved e″ over the node
    interval's piece (interval arithmetic), T_s likewise; ``interval_thickness`` each row's
    largest vertical width, ``thickness`` the band's. Every bound is rounded outward, the nodes
    are exact; ``intervals`` holds the report's text of every field (exact decimals).
    :meth:`e_at` and :meth:`ts_at` evaluate the form exactly (rationals) and round outward."""

    model: str
    #: the range proved, as floats and (``v0_text``) as the report's decimals
    v0_range: Tuple[float, float]
    v0_lo: np.ndarray
    v0_hi: np.ndarray
    e_at_lo: np.ndarray
    e_at_hi: np.ndarray
    d2e: np.ndarray
    ts_at_lo: np.ndarray
    ts_at_hi: np.ndarray
    d2ts: np.ndarray
    interval_thickness: np.ndarray
    thickness: float
    pieces_count: int
    seconds: float
    intervals: Tuple[dict, ...]
    v0_text: Tuple[str, str] = ("", "")

    def __len__(self) -> int:
        return len(self.v0_lo)

    def __repr__(self) -> str:
        from ._frames import outward

        return (f"InterpBandResult(model={self.model!r}, v0 ∈ [{self.v0_text[0]}, "
                f"{self.v0_text[1]}], {self.pieces_count} pieces, {len(self)} node intervals, "
                f"thickness ≤ {outward(self.thickness, True, 3)}, {self.seconds:.3g} s)")

    def to_pandas(self) -> Any:
        """One row per node interval, the report's exact decimals as text (each bound
        outward); ``astype(float)`` gives the float bounds."""
        from ._frames import pandas

        return pandas().DataFrame(list(self.intervals))

    def _form(self, v0: Any, q: str) -> Tuple[float, float]:
        # v0 exactly: a float as the double it is (NumPy's too), a str, int, Decimal or
        # Fraction as written; a bool is no speed
        if isinstance(v0, (bool, np.bool_)):
            raise TypeError(f"v0: expected an impact speed, got the bool {v0!r}")
        if isinstance(v0, (np.floating, np.integer)):
            v0 = v0.item()
        try:
            x = Fraction(v0)
        except (TypeError, ValueError, OverflowError):
            raise ValueError(f"v0: expected a finite impact speed, got {v0!r:.20}") from None
        rows = self.intervals
        if not rows or not (Fraction(rows[0]["v0_lo"]) <= x <= Fraction(rows[-1]["v0_hi"])):
            raise ValueError(f"v0: {v0!r:.20} is outside the band's range "
                             f"[{self.v0_text[0]}, {self.v0_text[1]}]")
        # the first node interval holding x (the left one at a shared node)
        i = min(int(np.searchsorted(self.v0_hi, float(x))), len(self) - 1)
        while i > 0 and x <= Fraction(rows[i - 1]["v0_hi"]):
            i -= 1
        while x > Fraction(rows[i]["v0_hi"]):
            i += 1
        r = rows[i]
        lo, hi = Fraction(r["v0_lo"]), Fraction(r["v0_hi"])
        assert lo <= x <= hi, (v0, r["v0_lo"], r["v0_hi"])
        h, p, qq = hi - lo, x - lo, hi - x
        a = (Fraction(r[q + "_at_lo_lo"]), Fraction(r[q + "_at_lo_hi"]))
        b = (Fraction(r[q + "_at_hi_lo"]), Fraction(r[q + "_at_hi_hi"]))
        d = (Fraction(r["d2" + q + "_lo"]), Fraction(r["d2" + q + "_hi"]))
        # p, q, h ≥ 0: each bound from the matching ends
        low = a[0] * qq / h + b[0] * p / h - d[1] * p * qq / 2
        high = a[1] * qq / h + b[1] * p / h - d[0] * p * qq / 2
        return _down(low), _up(high)

    def e_at(self, v0: Any) -> Tuple[float, float]:
        """Bounds (lower, upper) of e at the impact speed ``v0`` in the band's range: the
        form evaluated exactly (a float as the double it is; a str, int, Decimal or Fraction
        as written), rounded outward."""
        return self._form(v0, "e")

    def ts_at(self, v0: Any) -> Tuple[float, float]:
        """Bounds (lower, upper) of T_s at ``v0`` (as :meth:`e_at`)."""
        return self._form(v0, "ts")


@_flags_checked
def band(
    model: str,
    *,
    base: Any = None,
    physical: Any = None,
    v0: Any,
    thickness: Optional[float] = None,
    order: Optional[int] = None,
    time_limit: float = 300.0,
    threads: Optional[int] = None,
    progress: Any = None,
    second_order: bool = False,
) -> Union[BandResult, InterpBandResult]:
    """Prove the CoR curve e(v0) over a whole range of impact speeds ``v0=(lo, hi)`` (the
    CLI's ``cor --rigorous --band``): pieces on which e lies in a linear form e_c + de·(v0 −
    v0_c), each at most ``thickness`` wide (1e-14 ≤ T ≤ 1; default 1e-6), proved by the
    variational interval engine. With ``second_order=True`` (``--second-order``, for thin bands:
    default thickness 1e-9) the curve in the interpolation form between proved nodes, with e″
    proved over each piece by the second variational system: an :class:`InterpBandResult`
    ([0.1, 5] at 1e-9 takes ≈ 15 s on 2 CPUs). ``base`` (or ``physical``) as :func:`~bwcl.cor`
    (one set; decimals enclosed as written). Not proved within ``time_limit`` seconds (or the
    engine cannot) raises RuntimeError with the reason. ``progress``: True for a bar (tqdm
    when installed) or a callable receiving ``(share, message)``: the share of the range
    settled, at most every 0.1 s."""
    from . import _num, _source, _threads

    argv = ["cor"] + _source(model, base, None, physical, True)
    argv += ["--v0=" + _range(v0, "v0"), "--rigorous", "--band=python.json",
             f"--time-limit={_num(time_limit, 'time_limit')}"]
    if thickness is not None:
        argv.append(f"--thickness={_num(thickness, 'thickness')}")
    if order is not None:
        argv.append(f"--order={_num(order, 'order')}")
    if second_order:
        argv.append("--second-order")
    from ._progress import share as _share

    cb = _share(progress, "band")
    # numbers kept as the report's text (each reads back to its double)
    d = json.loads(_bwcl.band(argv, threads=_threads(threads), progress=cb), parse_float=str)
    if cb is not None:
        cb(1.0, "done")
    if "intervals" in d:
        return _interp(d)
    pieces = tuple(d["pieces"])
    col, pair = _columns(pieces)

    return BandResult(
        model=d["model"], v0_range=(float(d["v0"][0]), float(d["v0"][1])),
        v0_lo=col("v0_lo"), v0_hi=col("v0_hi"), v0_c=col("v0_c"), e_c=pair("e_c"),
        de=pair("de"), e=pair("e"), ts_c=pair("ts_c"), dts=pair("dts"), ts=pair("ts"),
        piece_thickness=col("thickness"), thickness=float(d["thickness"]),
        seconds=float(d["seconds"]), pieces=pieces, v0_text=(d["v0"][0], d["v0"][1]),
    )


def _columns(rows: Tuple[dict, ...]) -> Tuple[Any, Any]:
    """Readers of the report's rows: ``col(name)`` the floats of a field, ``pair(name)`` the
    (n, 2) array of its ``_lo`` and ``_hi`` fields."""

    def col(name: str) -> np.ndarray:
        return np.array([float(r[name]) for r in rows], dtype=float)

    def pair(name: str) -> np.ndarray:
        return np.stack([col(name + "_lo"), col(name + "_hi")], axis=1) if rows else np.empty((0, 2))

    return col, pair


def _interp(d: dict) -> InterpBandResult:
    rows = tuple(d["intervals"])
    col, pair = _columns(rows)

    return InterpBandResult(
        model=d["model"], v0_range=(float(d["v0"][0]), float(d["v0"][1])),
        v0_lo=col("v0_lo"), v0_hi=col("v0_hi"), e_at_lo=pair("e_at_lo"),
        e_at_hi=pair("e_at_hi"), d2e=pair("d2e"), ts_at_lo=pair("ts_at_lo"),
        ts_at_hi=pair("ts_at_hi"), d2ts=pair("d2ts"), interval_thickness=col("thickness"),
        thickness=float(d["thickness"]), pieces_count=int(d["pieces_count"]),
        seconds=float(d["seconds"]), intervals=rows, v0_text=(d["v0"][0], d["v0"][1]),
    )


@dataclass(frozen=True, eq=False, repr=False)
class MonotoneResult:
    """The verdict of :func:`prove_monotone`: "proved" (e strictly decreasing on the whole
    range: de/dv0 ≤ ``max_slope`` < 0 on each of ``pieces`` pieces), "disproved" (e strictly
    increasing on the sub-ranges ``increasing``: (lo, hi, (de_lo, de_hi))) or "not proved"
    (``undecided``: (lo, hi, reason)). Sub-range ends are rounded so that the claim holds on
    them (inward), slopes outward."""

    model: str
    v0: Tuple[float, float]
    verdict: str
    proved: bool
    pieces: int
    max_slope: Optional[float]
    increasing: Tuple[Tuple[float, float, Tuple[float, float]], ...]
    undecided: Tuple[Tuple[float, float, str], ...]
    seconds: float
    #: the report as the CLI writes it, every number as its text (the v0 ends inward, the
    #: slopes outward): what the repr prints
    report: dict = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        r = self.report or {}
        lo, hi = r.get("v0", ("?", "?"))
        text = f"MonotoneResult(model={self.model!r}, {self.verdict} for v0 ∈ [{lo}, {hi}]"
        if self.proved:
            text += f": de/dv0 ≤ {r.get('max_slope')} < 0 on {self.pieces} pieces"
        for p in r.get("increasing", [])[:3]:
            text += f"; increasing on [{p['v0'][0]}, {p['v0'][1]}] (de/dv0 ≥ {p['de_dv0'][0]})"
        if self.undecided:
            text += f"; {len(self.undecided)} sub-range(s) undecided"
        return text + f"; {self.seconds:.3g} s)"


@_flags_checked
def prove_monotone(
    model: str,
    *,
    base: Any,
    v0: Any,
    time_limit: float = 300.0,
    threads: Optional[int] = None,
    progress: Any = None,
) -> MonotoneResult:
    """Prove e(v0) strictly decreasing over ``v0=(lo, hi)`` for the base set ``base`` (the
    CLI's ``prove monotone``): a verdict, never silence — proved, disproved with the
    sub-ranges that refute it, or not proved with the reason per sub-range, within
    ``time_limit`` seconds. ``progress`` as :func:`band`."""
    from . import _num, _six, _threads

    if not isinstance(model, str):
        raise TypeError(f"model: expected 'shc' or 'maxwell', got {type(model).__name__}")
    argv = ["prove", "monotone", f"--model={model}", "--base=" + _six(base, "base", False),
            "--v0=" + _range(v0, "v0"), "--format=json",
            f"--time-limit={_num(time_limit, 'time_limit')}"]
    from ._progress import share as _share

    cb = _share(progress, "prove_monotone")
    d = json.loads(_bwcl.prove_monotone(argv, threads=_threads(threads), progress=cb),
                   parse_float=str)
    if cb is not None:
        cb(1.0, "done")
    return MonotoneResult(
        model=d["model"], v0=(float(d["v0"][0]), float(d["v0"][1])), verdict=d["verdict"],
        proved=bool(d["proved_decreasing"]), pieces=int(d["pieces"]),
        max_slope=None if d["max_slope"] is None else float(d["max_slope"]),
        increasing=tuple((float(p["v0"][0]), float(p["v0"][1]),
                          (float(p["de_dv0"][0]), float(p["de_dv0"][1])))
                         for p in d["increasing"]),
        undecided=tuple((float(p["v0"][0]), float(p["v0"][1]), p["reason"])
                        for p in d["undecided"]),
        seconds=float(d["seconds"]), report=d,
    )
