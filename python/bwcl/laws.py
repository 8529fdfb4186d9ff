"""``bwcl.laws``: the published Hunt–Crossley damping formulas against the CoR the law really
produces, proved (``bwcl laws``, issue #33).

The Simon–Hunt–Crossley law F = k|δ|^(n−1)δ + χ|δ|^n δ̇ is tuned for a target CoR e* by a
formula σ = χ v0 / k = σ(e*). Its CoR e solves G(σe) = G(−σ), G(u) = −u − ln(1 − u), whatever
n; each e(σ(e*)) and each error e − e* is proved in 128-bit interval arithmetic, and over the
whole range of targets the runs where |e − e*| ≤ tol are proved by a paving.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _flags_checked, _frames, _num, _threads, _whole
from ._native import native as _bwcl

#: The formulas' names (``bwcl laws --formulas``), in order of publication.
FORMULAS = (
    "hunt-crossley",
    "herbert-mcwhannell",
    "lee-wang",
    "lankarani-nikravesh",
    "gonthier",
    "zhiying-qishao",
    "flores",
    "gharib-hurmuzlu",
    "hu-guo",
    "carvalho-martins",
)


def _bounds(lo: Any, hi: Any) -> str:
    """[lo, hi] with each end printed on its outer side (a bound as a decimal is a bound)."""
    lo_a, hi_a = np.atleast_1d(np.asarray(lo, dtype=float)), np.atleast_1d(np.asarray(hi, dtype=float))
    pairs = [_frames.bracket(a, b) for a, b in zip(lo_a, hi_a)]
    if np.ndim(lo) == 0:
        return pairs[0]
    shown = pairs if len(pairs) <= 4 else pairs[:2] + ["…"] + pairs[-1:]
    return "[" + ", ".join(shown) + "]"


@dataclass(repr=False)
class FormulaErrors:
    """One formula: at each target ``e_star`` the bounds of σ(e*), of the CoR e the law
    produces and of the error e − e* (floats, lower bounds rounded down and upper bounds up), and
    the proved runs of targets: ``(lo, hi, verdict)`` with verdict "within" (|e − e*| ≤ tol for
    every target of the run), "outside" (> tol for every target) or "undecided"."""

    key: str
    source: str
    sigma_formula: str
    e_star: np.ndarray
    sigma_lo: np.ndarray
    sigma_hi: np.ndarray
    e_lo: np.ndarray
    e_hi: np.ndarray
    error_lo: np.ndarray
    error_hi: np.ndarray
    max_abs_error: float
    runs: List[Tuple[float, float, str]]

    def within(self) -> List[Tuple[float, float]]:
        """The runs of targets where |e − e*| ≤ tol is proved."""
        return [(a, b) for a, b, v in self.runs if v == "within"]

    def __repr__(self) -> str:
        # the bounds as decimals on their outer sides (numpy's 8 digits, or Python's shortest
        # round trip, may lie inside them)
        return (f"FormulaErrors(key={self.key!r}, source={self.source!r}, "
                f"{len(self.e_star)} targets, sigma {_bounds(self.sigma_lo, self.sigma_hi)}, "
                f"e {_bounds(self.e_lo, self.e_hi)}, error {_bounds(self.error_lo, self.error_hi)}, "
                f"max_abs_error ≤ {_frames.outward(self.max_abs_error, True)}, "
                f"{len(self.runs)} runs)")


@dataclass
class LawsResult:
    tol: float
    formulas: Dict[str, FormulaErrors]
    seconds: float

    def __repr__(self) -> str:
        return (f"LawsResult({len(self.formulas)} formulas × "
                f"{len(next(iter(self.formulas.values())).e_star) if self.formulas else 0} "
                f"targets, tol={self.tol}, {self.seconds:.2f} s)")


def _pairs(points: Sequence[dict], key: str) -> Tuple[np.ndarray, np.ndarray]:
    lo = np.array([float(p[key][0]) for p in points])
    hi = np.array([float(p[key][1]) for p in points])
    return lo, hi


@_flags_checked
def laws(
    formulas: Union[str, Sequence[str]] = "all",
    e_star: Tuple[Any, Any] = ("0.05", "0.99"),
    *,
    points: int = 100,
    tol: Any = "1e-3",
    threads: Optional[int] = None,
) -> LawsResult:
    """The damping formulas' errors, proved, as ``bwcl laws``: ``formulas`` ("all" or names from
    :data:`FORMULAS`), ``e_star`` the range (lo, hi) of targets with 0 < lo < hi < 1 (decimals,
    read as written), ``points`` targets on the grid, ``tol`` the error bound whose validity is
    proved over the range. Bad input raises ValueError with the program's one line."""
    if isinstance(formulas, str):
        names = formulas
    else:
        if any(not isinstance(f, str) for f in formulas):
            raise TypeError("formulas must be names (str)")
        names = ",".join(formulas)
    _whole(points, "points")
    try:
        lo, hi = e_star
    except (TypeError, ValueError):
        raise TypeError("e_star must be a pair (lo, hi)") from None
    argv = ["laws", f"--formulas={names}",
            f"--e-star={_num(lo, 'e_star')}..{_num(hi, 'e_star')}",
            f"--points={int(points)}", f"--tol={_num(tol, 'tol')}", "--format=json"]
    d = json.loads(_bwcl.laws(argv, threads=_threads(threads)))
    out = {}
    for f in d["formulas"]:
        pts = f["points"]
        s_lo, s_hi = _pairs(pts, "sigma")
        e_lo, e_hi = _pairs(pts, "e")
        d_lo, d_hi = _pairs(pts, "error")
        out[f["key"]] = FormulaErrors(
            key=f["key"],
            source=f["source"],
            sigma_formula=f["sigma"],
            e_star=np.array([float(p["e_star"]) for p in pts]),
            sigma_lo=s_lo, sigma_hi=s_hi, e_lo=e_lo, e_hi=e_hi,
            error_lo=d_lo, error_hi=d_hi,
            max_abs_error=float(f["max_abs_error"]),
            runs=[(float(s["lo"]), float(s["hi"]), s["verdict"]) for s in f["segments"]],
        )
    return LawsResult(tol=float(d["tol"]), formulas=out, seconds=float(d["seconds"]))


#: The classical laws of :func:`classical` (``bwcl classical --law``).
LAWS = ("hooke", "hertz", "hunt-crossley", "kelvin-voigt", "linear-maxwell")


@dataclass(repr=False)
class ClassicalResult:
    """T_s and e of a classical law, nondimensional. With ``rigorous`` the bounds are proved
    (lower rounded down, upper up) and ``ts``/``e`` are their midpoints; otherwise the f64
    engine's values, with lo = hi. ``proved`` is False (and ``reason`` says why) when the case
    was not proved or not integrated. ``separated`` is False when the law does not separate
    before the horizon H (``reason`` says so): then ts_lo = H and ts_hi = ∞ (T_s > H), and e is
    0 by the paper's convention where T_s = +∞ — the float run's answer, or proved when the law
    never separates (a closed form: linear Maxwell with c ≤ 1/2; ts_lo = ∞) — and NaN after a
    proved T_s > H alone."""

    law: str
    params: Dict[str, str]
    rigorous: bool
    proved: bool
    ts_lo: float
    ts_hi: float
    e_lo: float
    e_hi: float
    reason: Optional[str] = None
    separated: bool = True

    @property
    def ts(self) -> float:
        return 0.5 * (self.ts_lo + self.ts_hi)

    @property
    def e(self) -> float:
        return 0.5 * (self.e_lo + self.e_hi)

    def __repr__(self) -> str:
        if not self.separated:
            values = self.reason
        elif self.rigorous and self.proved:
            # proved bounds printed on their outer sides
            values = f"ts {_bounds(self.ts_lo, self.ts_hi)}, e {_bounds(self.e_lo, self.e_hi)}"
        elif self.proved:
            values = f"ts={self.ts!r}, e={self.e!r}"
        else:
            values = f"not proved: {self.reason}"
        return (f"ClassicalResult(law={self.law!r}, params={self.params!r}, "
                f"rigorous={self.rigorous!r}, {values})")


@_flags_checked
def classical(
    law: str,
    *,
    n: Any = None,
    sigma: Any = None,
    zeta: Any = None,
    c: Any = None,
    formula: Optional[str] = None,
    e_star: Any = None,
    rigorous: bool = False,
    threads: Optional[int] = None,
) -> ClassicalResult:
    """T_s and e of a classical collision law, as ``bwcl classical``: ``law`` one of
    :data:`LAWS`; ``n`` (hertz, hunt-crossley; default 1.5), ``sigma`` (hunt-crossley, or
    ``formula`` and ``e_star``: σ from a published formula of :data:`FORMULAS`), ``zeta``
    (kelvin-voigt), ``c`` (linear-maxwell). Numbers or decimal strings (read as written).
    Bad input raises ValueError with the program's one line."""
    if not isinstance(law, str):
        raise TypeError("law must be a name (str)")
    argv = ["classical", f"--law={law}", "--format=json"]
    for name, x in (("n", n), ("sigma", sigma), ("zeta", zeta), ("c", c), ("e-star", e_star)):
        if x is not None:
            argv.append(f"--{name}={_num(x, name)}")
    if formula is not None:
        if not isinstance(formula, str):
            raise TypeError("formula must be a name (str)")
        argv.append(f"--formula={formula}")
    if rigorous:
        argv.append("--rigorous")
    d = json.loads(_bwcl.classical(argv, threads=_threads(threads)))
    if "error" in d:
        nan = float("nan")
        return ClassicalResult(d["law"], d["params"], bool(rigorous), False, nan, nan, nan, nan,
                               d["error"])
    if not d["separated"]:
        inf, nan = float("inf"), float("nan")
        never = bool(d["never_separates"])
        e = d["e"]
        e = float(e[0]) if isinstance(e, list) else (nan if e is None else float(e))
        return ClassicalResult(d["law"], d["params"], bool(d["rigorous"]), True,
                               inf if never else float(d["horizon"]), inf, e, e, d["reason"],
                               separated=False)
    if d["rigorous"]:
        (tl, th), (el, eh) = d["ts"], d["e"]
        return ClassicalResult(d["law"], d["params"], True, True, float(tl), float(th),
                               float(el), float(eh))
    return ClassicalResult(d["law"], d["params"], False, True, float(d["ts"]), float(d["ts"]),
                           float(d["e"]), float(d["e"]))


@_flags_checked
def compare(
    data: Any = None,
    *,
    models: Union[None, str, Sequence[str]] = None,
    error: Any = None,
    starts: int = 8,
    seed: int = 1,
    time_limit: Any = None,
    v0: Any = None,
    e: Any = None,
    sigma: Any = None,
    threads: Optional[int] = None,
) -> List[Dict[str, Any]]:
    """Every model fitted to the same CoR data, as ``bwcl compare``: a list of dicts, best AIC
    first, each with model, k (parameters that enter e), J, aic, aicc, bic, delta_aic,
    delta_bic, parameters (text), seconds and, with ``error`` (every e known to ±E), each
    classical law's proved feasible set ``feasible`` and, when it is empty, ``certificate``
    (the rows that refute each range of its parameter; ``refuted_everywhere``: for every
    admissible value). ``models``: names among shc, maxwell, hunt-crossley, kelvin-voigt,
    linear-maxwell, hertz, hooke (default all); ``starts``/``seed``: the Bouc–Wen fits'.
    Data: a CSV file, or the arrays v0, e (and sigma). Bad input raises ValueError with the
    program's one line."""
    from .identify import _data_file

    path, temp = _data_file(data, v0, e, sigma, None, None)
    try:
        argv = ["compare", f"--data={path}", f"--starts={_num(starts, 'starts')}",
                f"--seed={_num(seed, 'seed')}", "--format=json"]
        if models is not None:
            if not isinstance(models, str):
                if any(not isinstance(m, str) for m in models):
                    raise TypeError("models must be names (str)")
                models = ",".join(models)
            argv.append(f"--models={models}")
        if error is not None:
            argv.append(f"--error={_num(error, 'error')}")
        if time_limit is not None:
            argv.append(f"--time-limit={_num(time_limit, 'time_limit')}")
        return json.loads(_bwcl.compare(argv, threads=_threads(threads)))["rows"]
    finally:
        if temp:
            os.unlink(path)
