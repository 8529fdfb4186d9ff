"""Proved feasible sets of P* (set-membership identification, ``bwcl identify``).

``identify`` paves a box of the free base parameters into boxes proved feasible (every data row
is matched to within its error at every point of the box), proved infeasible (no point of the
box matches every row) and undecided at the resolution; ``identify_dask`` splits the box into
sub-boxes and paves them on a Dask cluster (or any executor with ``submit``), then merges.
Box ends as decimals read back to the paving's own doubles; they are rounded inward for a
proved box (every point of a feasible box is consistent, of an infeasible one inconsistent:
a printed box claims no point the paving did not prove) and outward for an undecided one.
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _bounds_text, _fix_text, _flags_checked, _num, _threads, _whole
from ._native import native as _bwcl

_STATUS = ("feasible", "infeasible", "undecided")


@dataclass(frozen=True, repr=False)
class IdentifyResult:
    """A paving. ``lo``/``hi``: (k, d) arrays of the boxes' ends in the order of ``free``;
    ``status``: k strings; ``hull``: {name: (lo, hi)} the proved outer hull of F (None: F is
    proved empty, the model falsified at these errors); ``feasible_hull`` likewise for the boxes
    proved feasible; ``complete``: False when the time limit or box budget stopped the work (the
    rest is undecided; what is reported is still proved)."""

    model: str
    free: Tuple[str, ...]
    box: Dict[str, Tuple[float, float]]
    lo: np.ndarray
    hi: np.ndarray
    status: Tuple[str, ...]
    hull: Optional[Dict[str, Tuple[float, float]]]
    feasible_hull: Optional[Dict[str, Tuple[float, float]]]
    counts: Dict[str, int]
    shares: Dict[str, float]
    verdict: str
    complete: bool
    processed: int
    seconds: float
    #: A classical law's empty F: the rows that refute each range of its parameter.
    certificate: Tuple[str, ...] = ()
    #: ``sample=N``: {"tested": points tested, "feasible": found feasible by the f64 engine,
    #: "hull": {name: (lo, hi)} of those points or None} — an unproved inner estimate of F's
    #: hull, beside the proved outer ``hull``; None without ``sample``.
    sampled: Optional[Dict[str, Any]] = None

    @property
    def empty(self) -> bool:
        return self.hull is None

    def __repr__(self) -> str:
        from ._frames import outward

        # the undecided share rounded up, the proved ones down
        shares = ", ".join(f"{k} {_percent(v, k == 'undecided')}" for k, v in self.shares.items())
        if self.hull is None:
            hull = "F proved empty (the model is falsified at these errors)"
        else:
            hull = "hull " + ", ".join(
                f"{k} ∈ [{outward(lo, False, 6)}, {outward(hi, True, 6)}]"
                for k, (lo, hi) in self.hull.items())
        more = "" if self.complete else ", incomplete (time or box budget)"
        return (f"IdentifyResult(model={self.model!r}, {len(self.status)} boxes: {shares}; "
                f"{hull}{more}; {self.seconds:.3g} s)")

    def to_pandas(self, floats: bool = False) -> Any:
        """One row per box: ``<name>_lo``/``<name>_hi`` for each free parameter (as decimals
        unless ``floats=True``: inward for a feasible or infeasible box, whose every point the
        claim is about, outward for an undecided one) and status. Needs pandas."""
        from ._frames import outward, pandas

        pd = pandas()
        cols: Dict[str, Any] = {}
        lo, hi = np.asarray(self.lo, dtype=float), np.asarray(self.hi, dtype=float)
        proved = [s != "undecided" for s in self.status]
        for j, name in enumerate(self.free):
            a = lo[:, j] if len(lo) else np.empty(0)
            b = hi[:, j] if len(hi) else np.empty(0)
            if floats:
                cols[f"{name}_lo"], cols[f"{name}_hi"] = a, b
            else:
                cols[f"{name}_lo"] = [outward(v, p) for v, p in zip(a, proved)]
                cols[f"{name}_hi"] = [outward(v, not p) for v, p in zip(b, proved)]
        cols["status"] = list(self.status)
        return pd.DataFrame(cols)


def _directed(x: Fraction, up: bool) -> float:
    """The exact rational x as a float rounded up (``up``) or down."""
    f = float(x)
    if up and Fraction(f) < x:
        f = float(np.nextafter(f, np.inf))
    elif not up and Fraction(f) > x:
        f = float(np.nextafter(f, -np.inf))
    return f


def _percent(v: float, up: bool) -> str:
    """A share as a percentage with one decimal, rounded up (``up``) or down exactly."""
    from decimal import ROUND_CEILING, ROUND_FLOOR, Decimal

    d = (Decimal(v) * 100).quantize(Decimal("0.1"), rounding=ROUND_CEILING if up else ROUND_FLOOR)
    return f"{d} %"


def _spec(v: Any, what: str, pair: bool) -> str:
    """A mapping {name: value or (lo, hi)} (as fit's) or the CLI's text."""
    if isinstance(v, str):
        return v
    if not isinstance(v, Mapping):
        raise TypeError(f"{what}: expected a mapping or a string, got {type(v).__name__}")
    return _bounds_text(v) if pair else _fix_text(v)


def _data_file(data: Any, v0: Any, e: Any, sigma: Any, tc: Any, tc_sigma: Any):
    """The CSV path, or a temporary CSV of the arrays (exact float reprs); (path, temp?)."""
    if data is not None:
        if any(x is not None for x in (v0, e, sigma, tc, tc_sigma)):
            raise ValueError("give either data (a CSV file) or the arrays, not both")
        return os.fspath(data), False
    if v0 is None or e is None:
        raise ValueError("give data (a CSV file) or the arrays v0 and e")
    cols = {"v0": v0, "e": e, "sigma": sigma, "tc": tc, "tc_sigma": tc_sigma}
    cols = {k: np.asarray(c, dtype=np.float64) for k, c in cols.items() if c is not None}
    n = len(cols["v0"])
    for k, c in cols.items():
        if c.ndim != 1 or len(c) != n:
            raise ValueError(f"{k}: expected a 1-D array of length {n}, got shape {c.shape}")
    fd, path = tempfile.mkstemp(prefix="bwcl-identify-", suffix=".csv")
    with os.fdopen(fd, "w") as f:
        f.write(",".join(cols) + "\n")
        for i in range(n):
            f.write(",".join(repr(float(c[i])) for c in cols.values()) + "\n")
    return path, True


def _result(d: dict) -> IdentifyResult:
    free = tuple(d["free"])
    k = len(d["boxes"])
    lo = np.array([b["lo"] for b in d["boxes"]], dtype=np.float64).reshape(k, len(free))
    hi = np.array([b["hi"] for b in d["boxes"]], dtype=np.float64).reshape(k, len(free))
    pairs = lambda h: None if h is None else {n: (float(a), float(b)) for n, (a, b) in h.items()}
    return IdentifyResult(
        model=d["model"], free=free, box=pairs(d["box"]), lo=lo, hi=hi,
        status=tuple(b["status"] for b in d["boxes"]), hull=pairs(d["hull"]),
        feasible_hull=pairs(d["feasible_hull"]), counts=dict(d["counts"]),
        shares=dict(d["shares"]), verdict=d["verdict"], complete=d["complete"],
        processed=d["processed"], seconds=d["seconds"],
        certificate=tuple(d.get("certificate", ())),
        sampled=None if d.get("sampled") is None else {
            "tested": d["sampled"]["tested"], "feasible": d["sampled"]["feasible"],
            "hull": pairs(d["sampled"]["hull"])},
    )


@_flags_checked
def identify(
    model: str,
    data: Any = None,
    *,
    bounds: Union[None, str, Mapping[str, Tuple[float, float]]] = None,
    error: Optional[float] = None,
    fix: Union[None, str, Mapping[str, float]] = None,
    base: Optional[Sequence[float]] = None,
    free: Optional[Sequence[str]] = None,
    tc_error: Optional[float] = None,
    no_tc: bool = False,
    resolution: Optional[int] = None,
    time_limit: Optional[float] = None,
    max_boxes: Optional[int] = None,
    sample: int = 0,
    v0: Any = None,
    e: Any = None,
    sigma: Any = None,
    tc: Any = None,
    tc_sigma: Any = None,
    threads: Optional[int] = None,
    progress: Any = None,
) -> IdentifyResult:
    """Proved feasible set F = {P* in the box : ``|e(𝓟(P*, v0_i)) − e_i| ≤ E_i`` for every i}
    (and ``|tc − tc_i| ≤ T_i`` with a tc column), as ``bwcl identify``. ``bounds`` gives the free
    parameters and their box ({"kappa": (0.4, 0.8)} or "kappa=0.4..0.8"; names B_b, Gamma_b,
    kappa, sigma_b, n, p, Greek accepted); the others are fixed by ``fix`` or ``base``
    (B_b, Γ_b, κ, σ_b, n, p). ``error``: the ±E of every e (a ``sigma`` column overrides it).
    Data: a CSV file, or the arrays v0, e (and sigma, tc, tc_sigma). A classical law
    (``model="hunt-crossley"``, "kelvin-voigt", "linear-maxwell", "hertz", "hooke") paves its
    one parameter (``bounds`` optional: its useful range); an empty F comes with
    ``certificate``, the rows that refute each range. ``resolution``: 128 for the Bouc–Wen
    models, 2^20 for a law. Bad input raises ValueError with the program's one line.
    ``progress``: True for a bar (tqdm when installed) or a callable receiving ``(share,
    message)``: the share of the box decided (a Bouc–Wen model), at most every 0.1 s.
    ``sample``: N > 0 also samples F with the f64 engine (N uniform points, then pushes towards
    the box's faces): ``result.sampled["hull"]`` is the hull of the points found feasible, an
    unproved inner estimate of F's hull (a Bouc–Wen model)."""
    path, temp = _data_file(data, v0, e, sigma, tc, tc_sigma)
    try:
        argv = ["identify", f"--model={model}", f"--data={path}", "--format=json"]
        if bounds is not None:
            argv.append("--bounds=" + _spec(bounds, "bounds", True))
        if resolution is not None:
            argv.append(f"--resolution={_whole(resolution, 'resolution')}")
        if error is not None:
            argv.append(f"--error={_num(error, 'error')}")
        if tc_error is not None:
            argv.append(f"--tc-error={_num(tc_error, 'tc_error')}")
        if no_tc:
            argv.append("--no-tc")
        if fix is not None:
            argv.append("--fix=" + _spec(fix, "fix", False))
        if base is not None:
            if isinstance(base, str):
                argv.append("--base=" + base)
            else:
                argv.append("--base=" + ",".join(repr(float(x)) for x in base))
        if free is not None:
            argv.append("--free=" + (free if isinstance(free, str) else ",".join(free)))
        if time_limit is not None:
            argv.append(f"--time-limit={_num(time_limit, 'time_limit')}")
        if max_boxes is not None:
            argv.append(f"--max-boxes={_whole(max_boxes, 'max_boxes')}")
        if sample:
            argv.append(f"--sample={_whole(sample, 'sample')}")
        from ._progress import share as _share

        cb = _share(progress, "identify")
        out = _result(json.loads(_bwcl.identify(argv, threads=_threads(threads), progress=cb)))
        if cb is not None:
            cb(1.0, "done")
        return out
    finally:
        if temp:
            os.unlink(path)


def split_box(bounds: Mapping[str, Tuple[float, float]], parts: int) -> list:
    """``parts`` (a power of two) sub-boxes of ``bounds``: halved along the relatively widest
    side, as the paving bisects. Each is a dict like ``bounds``."""
    if parts < 1 or parts & (parts - 1):
        raise ValueError(f"parts = {parts} must be a power of two ≥ 1")
    boxes = [dict(bounds)]
    full = {k: float(b) - float(a) for k, (a, b) in bounds.items()}
    while len(boxes) < parts:
        nxt = []
        for bx in boxes:
            k = max(bx, key=lambda n: (bx[n][1] - bx[n][0]) / full[n])
            a, b = bx[k]
            m = a + (b - a) / 2
            nxt += [{**bx, k: (a, m)}, {**bx, k: (m, b)}]
        boxes = nxt
    return boxes


@_flags_checked
def identify_dask(
    client: Any,
    model: str,
    data: Any = None,
    *,
    bounds: Mapping[str, Tuple[float, float]],
    parts: int = 8,
    resolution: int = 128,
    **kwargs: Any,
) -> IdentifyResult:
    """``identify`` on a Dask cluster (``client``: a ``distributed.Client``, or any executor
    with ``submit`` and futures with ``result``): the box is split into ``parts`` sub-boxes,
    each paved where the cluster runs it at the resolution of the whole box (each side's finest
    width is the whole box's side / ``resolution``), and the pavings are merged: boxes
    concatenated, hulls of the non-infeasible and of the feasible boxes, counts and shares
    added. Data: a CSV file every worker can read, or arrays (v0, e, …: they are shipped)."""
    subs = split_box(bounds, parts)
    full = {k: float(b) - float(a) for k, (a, b) in bounds.items()}
    futures = []
    for bx in subs:
        res = max(1, round(resolution * min((bx[k][1] - bx[k][0]) / full[k] for k in bx)))
        extra = {"pure": False} if _is_dask(client) else {}
        futures.append(client.submit(identify, model, data, bounds=bx, resolution=res,
                                     **extra, **kwargs))
    try:
        parts_out = [f.result() for f in futures]
    except BaseException:
        # Ctrl-C (or a part that failed): the parts not yet done are cancelled, not left running
        for f in futures:
            f.cancel()
        raise
    return merge(parts_out, bounds)


def _is_dask(client: Any) -> bool:
    return type(client).__module__.startswith("distributed")


def merge(parts: Sequence[IdentifyResult], bounds: Mapping[str, Tuple[float, float]]) -> IdentifyResult:
    """One paving from the pavings of sub-boxes of ``bounds`` (see ``identify_dask``)."""
    first = parts[0]
    lo = np.concatenate([p.lo for p in parts])
    hi = np.concatenate([p.hi for p in parts])
    status = tuple(s for p in parts for s in p.status)

    def hull(keep):
        idx = [i for i, s in enumerate(status) if s in keep]
        if not idx:
            return None
        return {n: (float(lo[idx, j].min()), float(hi[idx, j].max()))
                for j, n in enumerate(first.free)}

    counts = {s: sum(p.counts[s] for p in parts) for s in _STATUS}
    # the shares summed exactly (the parts' own shares are already rounded: proved down,
    # undecided up) and rounded the same way
    vol = {n: Fraction(float(b)) - Fraction(float(a)) for n, (a, b) in bounds.items()}
    exact = {s: Fraction(0) for s in _STATUS}
    for p in parts:
        w = Fraction(1)
        for n in first.free:
            w *= (Fraction(p.box[n][1]) - Fraction(p.box[n][0])) / vol[n]
        for s in _STATUS:
            exact[s] += w * Fraction(p.shares[s])
    shares = {s: _directed(exact[s], s == "undecided") for s in _STATUS}
    h = hull(("feasible", "undecided"))
    # (no decimals here: the hull's floats are the paving's own box ends, exact as floats)
    verdict = ("proved: no P* in the box is consistent with the data (F is empty)" if h is None
               else "proved: every P* in the box consistent with the data lies in the hull")
    return IdentifyResult(
        model=first.model, free=first.free,
        box={n: (min(p.box[n][0] for p in parts), max(p.box[n][1] for p in parts))
             for n in first.free},
        lo=lo, hi=hi, status=status, hull=h, feasible_hull=hull(("feasible",)), counts=counts,
        shares=shares, verdict=verdict, complete=all(p.complete for p in parts),
        processed=sum(p.processed for p in parts), seconds=max(p.seconds for p in parts),
    )
