"""bwcl — verified numerics for the Bouc–Wen collision laws, from Python.

The models of Milehins & Marghitu, *The Bouc–Wen Model for Binary Direct Collinear
Collisions of Convex Viscoplastic Bodies*: the NDBWSHCCM (``model="shc"``, eq:BWSHCCM_nd,
Kelvin–Voigt type, states X, Z, V) and the NDBWMCM (``model="maxwell"``, eq:BWMCM_nd, states
R, Y, Z, W). For a collision starting at X = Z = 0, V = −1 the package computes

    T_s = inf{T ≥ 0 : F_P(Φ(T)) ≤ 0 and V(T) ≥ 0}    (eq:main_t_s)
    e   = V(T_s)                                      (eq:main_cor)

- :func:`cor` — T_s and e on the f64 DOP853 engine at the paper's SciPy settings
  (``rtol=1e-10, atol=1e-12, max_step=1e-2``), one case per impact speed v0, the cases in
  parallel;
- :func:`cor_rigorous` — proved enclosures of T_s and e (interval Taylor engine): the true
  values lie inside, rounding and truncation included;
- :func:`trajectory`, :func:`loop` — the trajectory up to T_s and the hysteresis loop
  (F_P against X, eq:BWHCL), nondimensional or in SI units;
- :func:`cost`, :func:`fit` — the cost J (eq:J) of a base set P* on measured CoR data and
  its minimization over 𝓟 (seeded multi-start Nelder–Mead);
- :func:`laws` — the published Hunt–Crossley damping formulas χ(e*) against the CoR the law
  really produces, proved;
- :func:`classical` — T_s and e of the classical laws (Hooke, Hertz, Hunt–Crossley, linear
  Kelvin–Voigt and Maxwell) on the same engines, float or proved;
- :func:`compare` — every model (Bouc–Wen and classical) fitted to the same CoR data, with
  AIC/AICc/BIC and each classical law's proved feasible set (:func:`identify` takes the laws
  too: ``model="hunt-crossley"``).

Parameters come as in the CLI (``bwcl --help``): exactly one of

- ``nd``: a nondimensional set P = (B, Γ, κ, σ, n, p) — one case, no ``v0``;
- ``base``: a base set P* = (B_b, Γ_b, κ, σ_b, n, p), mapped to each ``v0`` by the
  base-parameter map 𝓟(P*, v0) (sec:KVCL, sec:MCL);
- ``physical``: SI parameters ``{"m": …, "k": …, "c": …, "n": …, "p": …, "alpha": …,
  "beta": …, "gamma": …, "A": …}`` (eq:BWSHCCM, eq:BWMCM), with ``v0`` in m/s.

A set is a sequence of six values or the CLI's text ``"1.43,-1.42,0.632,0.00715,1.31,1.27"``.
Each value may be a number, a decimal string (read as written: with :func:`cor_rigorous`
``"0.632"`` is enclosed exactly, it is not rounded to a double) or, for :func:`cor_rigorous`,
a range ``(lo, hi)``. Bad input raises :class:`ValueError` with the CLI's one-line message
(a wrong type raises :class:`TypeError`). Every call releases the GIL; ``threads`` sets the
size of the call's own thread pool (default: all cores). Results are plain dataclasses of
NumPy arrays: they pickle, and so do the functions (for Dask, see ``examples/dask_sweep.py``).
"""

from __future__ import annotations

import json
import numbers
import os
import sys
import warnings
from dataclasses import dataclass, field
from collections.abc import Mapping
from typing import Any, Callable, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from ._native import native as _bwcl
from ._native import pythonic as _pythonic

__version__ = _bwcl.__version__

__all__ = [
    "cor",
    "cor_rigorous",
    "DERIVED",
    "trajectory",
    "loop",
    "cost",
    "fit",
    "identify",
    "identify_dask",
    "laws",
    "LawsResult",
    "FormulaErrors",
    "classical",
    "compare",
    "ClassicalResult",
    "IdentifyResult",
    "profile",
    "CorResult",
    "RigorousResult",
    "TrajectoryResult",
    "LoopResult",
    "CostResult",
    "FitResult",
    "FitStart",
    "FitProgress",
    "FallbackRun",
    "NotProvedError",
    "TABLE1",
    "Table1Set",
    "Sensitivity",
    "band",
    "BandResult",
    "InterpBandResult",
    "prove_monotone",
    "MonotoneResult",
    "plot",
]

class Table1Set(NamedTuple):
    """One base set of the paper's Table 1: ``model`` and ``base`` = P* = (B_b, Γ_b, κ, σ_b,
    n, p) as numbers (each the double nearest the printed decimal; :func:`cor_rigorous`
    encloses the decimal itself, as it encloses every float by its ``repr``); ``text`` is the
    row as printed (the CLI's ``--base``), ``named`` the values by name."""

    model: str
    base: Tuple[float, float, float, float, float, float]

    @property
    def text(self) -> str:
        return ",".join(repr(x) if x != int(x) else str(int(x)) for x in self.base)

    @property
    def named(self) -> dict:
        return dict(zip(("B_b", "Gamma_b", "kappa", "sigma_b", "n", "p"), self.base))


#: The paper's Table 1 (tab:param): the base sets P* = (B_b, Γ_b, κ, σ_b, n, p) identified from
#: the DSS and DSA data, as ``Table1Set(model, base)``: ``model, base = TABLE1["SHC DSS"]``.
TABLE1 = {
    "SHC DSS": Table1Set("shc", (1.43, -1.42, 0.632, 0.00715, 1.31, 1.27)),
    "SHC DSA": Table1Set("shc", (0.63, -0.611, 0.188, 0.00594, 1.0, 2.02)),
    "Maxwell DSS": Table1Set("maxwell", (0.655, -0.64, 0.519, 0.0118, 1.94, 2.28)),
    "Maxwell DSA": Table1Set("maxwell", (0.44, -0.418, 0.113, 0.00785, 1.27, 3.14)),
}

_MAX_THREADS = 1024
# the float engine's defaults (the paper's SciPy call), in every signature that takes them
_RTOL, _ATOL, _MAX_STEP = 1e-10, 1e-12, 1e-2


class NotProvedError(RuntimeError):
    """Raised by :func:`cor_rigorous` with ``raise_on_failure=True`` when a case was not
    proved. ``result`` holds every case (the proved ones too) and ``reason`` the first
    reason."""

    def __init__(self, message: str, result: Optional["RigorousResult"] = None):
        super().__init__(message)
        self.result = result

    def __reduce__(self):
        return (NotProvedError, (str(self), self.result))


# ---------------------------------------------------------------------------------------------
# arguments → the CLI's arguments


def _token(x: Any, what: str, ranges: bool) -> str:
    """One value as the CLI reads it: a string as written, an integer in full, a float as its
    shortest decimal (``repr``), a pair (lo, hi) as the range ``lo..hi``."""
    if isinstance(x, str):
        # one value: a comma would make it two items of the CLI's list
        if "," in x:
            raise ValueError(f"{what}: the value {_frames_repr(x)} holds a comma; give one "
                             "value per item")
        return x
    if isinstance(x, (bool, np.bool_)):
        raise TypeError(f"{what}: expected a number, got the bool {x!r}")
    if isinstance(x, numbers.Integral):
        return str(int(x))
    if isinstance(x, numbers.Real):
        return repr(float(x))
    if ranges and isinstance(x, tuple) and len(x) == 2:
        return f"{_token(x[0], what, False)}..{_token(x[1], what, False)}"
    kind = "a number, a decimal string or a (lo, hi) pair" if ranges else "a number"
    raise TypeError(f"{what}: expected {kind}, got {type(x).__name__} {x!r:.40}")


def _six(p: Any, what: str, ranges: bool) -> str:
    """A parameter set (six values, or the CLI's comma-separated text)."""
    if isinstance(p, str):
        return p
    if isinstance(p, np.ndarray):
        if p.ndim != 1:
            raise ValueError(
                f"{what} must be six values B,Γ,κ,σ,n,p, got an array of shape {p.shape}"
            )
        p = p.tolist()
    if isinstance(p, dict) or not isinstance(p, Sequence):
        raise TypeError(
            f"{what}: expected six values B,Γ,κ,σ,n,p (a sequence or a comma-separated "
            f"string), got {type(p).__name__}"
        )
    return ",".join(_token(x, what, ranges) for x in p)


def _physical(p: Any, ranges: bool) -> str:
    if isinstance(p, str):
        return p
    if not hasattr(p, "items"):
        raise TypeError(
            "physical: expected a mapping {'m': …, 'k': …, …} or the CLI's text "
            f"'m=…,k=…,…', got {type(p).__name__}"
        )
    return ",".join(f"{_key(k, 'physical')}={_token(v, 'physical', ranges)}"
                    for k, v in p.items())


def _named(p: Any, what: str, ranges: bool) -> str:
    """A classical law's parameters by name: a mapping {'sigma': …, 'n': …} or the CLI's
    text 'sigma=…,n=…' ('' or {} for Hooke's)."""
    if isinstance(p, str):
        return p
    if not hasattr(p, "items"):
        raise TypeError(
            f"{what}: a classical law's parameters go by name, as a mapping "
            f"{{'sigma': …, 'n': …}} or the CLI's text 'sigma=…,n=…'; got {type(p).__name__}"
        )
    return ",".join(f"{_key(k, what)}={_token(v, what, ranges)}" for k, v in p.items())


def _flag(x: Any, name: str) -> bool:
    """A switch: True or False (NumPy's bools too), anything else a TypeError."""
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    raise TypeError(f"{name} must be True or False, not {type(x).__name__} {_frames_repr(x)}")


def _flags_checked(fn: Callable) -> Callable:
    """``fn`` with each of its switches (the parameters whose default is True or False) checked
    by :func:`_flag` when given: ``rigorous="no"`` is a TypeError, not a truthy string."""
    import functools
    import inspect

    sig = inspect.signature(fn)
    names = [n for n, p in sig.parameters.items() if isinstance(p.default, bool)]

    @functools.wraps(fn)
    def checked(*args: Any, **kwargs: Any) -> Any:
        try:
            given = sig.bind_partial(*args, **kwargs).arguments
        except TypeError:
            given = {}  # the call itself reports the wrong arguments
        for n in names:
            if n in given:
                _flag(given[n], n)
        return fn(*args, **kwargs)

    return checked


def _key(k: Any, what: str) -> str:
    """A parameter's name in a mapping: a plain name, Greek ones too (a key holding ',' or '='
    would be read as more than one item)."""
    if not isinstance(k, str) or not k.isidentifier():
        raise ValueError(f"{what}: {_frames_repr(k)} is not a parameter name")
    return k


def _frames_repr(x: Any) -> str:
    text = repr(x)
    return text if len(text) <= 40 else text[:37] + "..."


def _source(model: Any, base: Any, nd: Any, physical: Any, ranges: bool) -> list:
    if not isinstance(model, str):
        raise TypeError(
            f"model: expected 'shc', 'maxwell' or a classical law ({', '.join(LAWS)}), "
            f"got {type(model).__name__}"
        )
    argv = [f"--model={model}"]
    params = _named if model in LAWS else _six
    if base is not None:
        argv.append("--base=" + params(base, "base", ranges))
    if nd is not None:
        argv.append("--nd=" + params(nd, "nd", ranges))
    if physical is not None:
        argv.append("--physical=" + _physical(physical, ranges))
    return argv


def _num(x: Any, what: str) -> str:
    return _token(x, what, False)


def _plain(x: Any, what: str) -> Any:
    """Refuses what would be read as something else: bytes (b'1' iterates as 49), a masked
    array with masked entries (the mask would be ignored); an unmasked one is its data."""
    if isinstance(x, (bytes, bytearray, memoryview)):
        raise TypeError(f"{what}: expected numbers or a decimal string, got {type(x).__name__} "
                        f"{bytes(x)[:40]!r}")
    if isinstance(x, np.ma.MaskedArray):
        if np.ma.is_masked(x):
            raise ValueError(f"{what}: a masked array with masked entries; give the values to "
                             "use (x.compressed(), or x.filled(value))")
        return np.ma.getdata(x)
    return x


def _speeds_array(v0: Any) -> Optional[np.ndarray]:
    """v0 as a 1-D float64 array when it is numeric, else None."""
    v0 = _plain(v0, "v0")
    if isinstance(v0, str):
        return None
    if isinstance(v0, (list, tuple)) and any(isinstance(x, (str, tuple)) for x in v0):
        return None
    arr = np.asarray(v0)
    if arr.ndim == 0:
        arr = arr.reshape(1)
    if arr.ndim != 1:
        raise ValueError(f"v0 must be a number or a 1-D array of impact speeds, got shape {arr.shape}")
    if arr.dtype.kind == "b":
        raise TypeError("v0: expected impact speeds, got an array of bools")
    if arr.dtype.kind == "f":
        return np.ascontiguousarray(arr, dtype=np.float64)
    return None  # integers go as tokens, written as given (messages echo them so)


def _speed_tokens(v0: Any, ranges: bool) -> list:
    """v0 as the CLI's tokens: a string is the CLI's list; else one token per item."""
    v0 = _plain(v0, "v0")
    if isinstance(v0, str):
        return v0.split(",")
    items = v0.tolist() if isinstance(v0, np.ndarray) else v0
    if isinstance(items, (numbers.Real, str)):
        items = [items]
    if not isinstance(items, Sequence):
        raise TypeError(f"v0: expected impact speeds, got {type(v0).__name__}")
    out = []
    for x in items:
        t = _token(x, "v0", ranges)
        if isinstance(x, str) and "," in x:
            raise ValueError(f"v0: the item '{x:.40}' holds a comma: give one speed per item")
        out.append(t)
    return out


def _threads(threads: Any) -> Optional[int]:
    # None and −1 (SciPy's and joblib's "all cores"): the global pool, one thread per core
    if threads is None or (isinstance(threads, numbers.Integral)
                           and not isinstance(threads, bool) and int(threads) == -1):
        return None
    if isinstance(threads, bool) or not isinstance(threads, numbers.Integral) or not (
        1 <= int(threads) <= _MAX_THREADS
    ):
        raise ValueError(
            f"threads = {threads!r:.40} must be a whole number in 1..={_MAX_THREADS}, or -1 (all cores)"
        )
    return int(threads)


def _float_engine(rtol: Any, atol: Any, max_step: Any, horizon: Any) -> list:
    argv = [f"--horizon={_num(horizon, 'horizon')}"]
    for name, x in (("rtol", rtol), ("atol", atol), ("max-step", max_step)):
        # (None is refused by _num: a setting given is a number, never a silent default)
        argv.append(f"--{name}={_num(x, name.replace('-', '_'))}")
    return argv


# ---------------------------------------------------------------------------------------------
# results

#: The derived outputs (``derived=True``): nondimensional, then SI (with ``physical``).
DERIVED = ("peak_force", "max_indentation", "energy_lost", "peak_force_newtons",
           "max_indentation_m", "energy_lost_joules")


@dataclass(frozen=True, eq=False, repr=False)
class CorResult:
    """T_s and e of every case of :func:`cor`, one entry per impact speed (in order).

    Attributes
    ----------
    model : "shc" or "maxwell".
    v0 : impact speeds [m/s] (NaN for ``nd``).
    ts : T_s (eq:main_t_s), nondimensional (T = t/T_c); NaN without separation before the
        horizon, or where the integration failed.
    e : the CoR e = V(T_s) (eq:main_cor); 0 without separation, NaN where it failed.
    separated : whether F_P ≤ 0 and V ≥ 0 was reached before the horizon.
    nfev : right-hand-side evaluations; ``steps``: accepted DOP853 steps.
    params : (n, 6) the nondimensional set P = (B, Γ, κ, σ, n, p) of each case; for a
        classical law a dict of (n,) arrays by name (sigma, n, zeta or c, nondimensional).
    error : per case, None or why the case could not be integrated.
    ts_seconds, t_c : with ``physical``: T_s·T_c and the time scale T_c [s].
    peak_force, max_indentation, energy_lost : with ``derived=True``: the peak contact force
        F_max = max F over [0, T_s], the maximum indentation δ_max = max(−X) and the kinetic
        energy lost ΔE = (1 − e²)/2, nondimensional (NaN where not computed: ``derived_reason``).
    peak_force_newtons, max_indentation_m, energy_lost_joules : with ``derived=True`` and
        ``physical``: the same in N, m and J (ΔE = ½ m v0² (1 − e²)).
    seconds : wall time of the computation (the cases only, as the CLI's ``--timing``).
    """

    model: str
    v0: np.ndarray
    ts: np.ndarray
    e: np.ndarray
    separated: np.ndarray
    nfev: np.ndarray
    steps: np.ndarray
    params: Any
    error: Tuple[Optional[str], ...]
    ts_seconds: Optional[np.ndarray] = None
    t_c: Optional[np.ndarray] = None
    horizon: float = 100.0
    seconds: float = 0.0
    threads: int = 0
    peak_force: Optional[np.ndarray] = None
    max_indentation: Optional[np.ndarray] = None
    energy_lost: Optional[np.ndarray] = None
    peak_force_newtons: Optional[np.ndarray] = None
    max_indentation_m: Optional[np.ndarray] = None
    energy_lost_joules: Optional[np.ndarray] = None
    derived_reason: Optional[Tuple[Optional[str], ...]] = None

    @property
    def ok(self) -> np.ndarray:
        """Per case: integrated (separated or not)."""
        err = np.empty(np.shape(self.e), dtype=object)
        err[...] = self.error if err.ndim == 1 else [list(row) for row in self.error]
        return np.frompyfunc(lambda m: m is None, 1, 1)(err).astype(bool)

    def __len__(self) -> int:
        return len(self.e)

    def __repr__(self) -> str:
        n = int(np.size(self.e))
        return (
            f"CorResult(model={self.model!r}, {_frames.shape_text(np.shape(self.e))}, "
            f"v0 {_frames.span(self.v0)} m/s, e {_frames.span(self.e)}, "
            f"T_s {_frames.span(self.ts)}, separated {int(np.sum(self.separated))}/{n}, "
            f"failed {n - int(np.sum(self.ok))}, {self.seconds:.3g} s)"
        )

    def to_pandas(self) -> Any:
        """One row per case (``set``, ``speed`` indices for a grid of sets × speeds): v0, ts,
        e, separated, nfev, steps, [ts_seconds, t_c,] [the derived outputs,] the parameters of
        the case and error. Needs pandas."""
        pd = _frames.pandas()
        shape = np.shape(self.e)
        n = int(np.size(self.e))
        cols = _frames.grid_index(shape)
        for name in ("v0", "ts", "e", "separated", "nfev", "steps", "ts_seconds", "t_c") + DERIVED:
            if getattr(self, name) is not None:
                cols[name] = _frames.flat(getattr(self, name))
        cols.update(_frames.params_columns(self.params, n, False))
        cols["error"] = _frames.flat_items(self.error, len(shape) - 1)
        return pd.DataFrame(cols)


class FallbackRun(NamedTuple):
    """One run of the precision fallback of :func:`cor_rigorous`: MPFR intervals of ``bits``
    bits, ``seconds`` of wall time, proved or not (``reason``)."""

    bits: int
    seconds: float
    proved: bool
    reason: Optional[str]


class Sensitivity(NamedTuple):
    """Proved ∂T_s/∂u and ∂e/∂u of one input u of a case (:func:`cor_rigorous` with
    ``sensitivities=True``): (lo, hi) bounds rounded outward, or None with ``reason``."""

    dts: Optional[Tuple[float, float]]
    de: Optional[Tuple[float, float]]
    reason: Optional[str]

    def __repr__(self) -> str:
        def pair(b: Optional[Tuple[float, float]]) -> str:
            if b is None:
                return "None"
            return _frames.bracket(b[0], b[1])

        why = f", reason={self.reason!r}" if self.reason else ""
        return f"Sensitivity(dts={pair(self.dts)}, de={pair(self.de)}{why})"


@dataclass(frozen=True, eq=False, repr=False)
class RigorousResult:
    """Proved enclosures of :func:`cor_rigorous`, one entry per case (in order).

    For a proved case the true T_s lies in ``ts[i] = (lo, hi)`` and the true e in ``e[i]``
    for every input in the enclosures of the inputs (a decimal string is enclosed as written,
    a range ``(lo, hi)`` whole). The float bounds are the engine's doubles; the ``*_text``
    bounds are the decimals the CLI prints: the shortest decimal on the outer side that reads
    back to the same double (lower bounds rounded down, upper bounds and widths up).

    Attributes
    ----------
    status : per case "proved" or "not proved"; ``proved`` the same as booleans.
    reason : per case None, or why it was not proved (the engine's words); for a proved case
        a note where there is one (no separation before the horizon; with ``digits``, the
        f64-interval engine's enclosure in place of the digits asked for).
    v0 : (n, 2) the enclosure of each impact speed (NaN for ``nd``).
    ts, e : (n, 2) the enclosures of T_s (nondimensional) and e (NaN where not proved).
    width_ts, width_e : upper bounds of the widths.
    ts_text, e_text : per case (lo, hi) decimals rounded outward, or None.
    v0_text : per case the (lo, hi) of the speeds the result holds for, rounded inward (the
        printed range claims no speed the run did not cover), or None.
    width_ts_text, width_e_text : the widths as decimals rounded up, or None.
    ts_seconds : with ``physical``: (n, 2) an enclosure of T_s·T_c [s].
    params : (n, 6, 2) the enclosures of P = (B, Γ, κ, σ, n, p) of each case; for a classical
        law a dict of (n, 2) arrays by name.
    bits : per case the precision of the run that proved it (or was tried last): 53 for the
        f64-interval engine, 128/192/256 where the precision fallback decided it.
    fallback : per case None, or the precision fallback's runs as
        ``FallbackRun(bits, seconds, proved, reason)``, in order.
    peak_force, max_indentation, energy_lost : with ``derived=True``: (n, 2) enclosures of
        F_max = max F over [0, T_s], δ_max = max(−X) over [0, T_s] and ΔE = (1 − e²)/2 (NaN
        where not computed: ``derived_reason``); ``derived_text[name]`` the decimals rounded
        outward.
    peak_force_newtons, max_indentation_m, energy_lost_joules : with ``derived=True`` and
        ``physical``: the same in N, m and J.
    """

    model: str
    status: Tuple[str, ...]
    proved: np.ndarray
    separated: np.ndarray
    reason: Tuple[Optional[str], ...]
    v0: np.ndarray
    ts: np.ndarray
    e: np.ndarray
    width_ts: np.ndarray
    width_e: np.ndarray
    v0_text: Tuple[Optional[Tuple[str, str]], ...]
    ts_text: Tuple[Optional[Tuple[str, str]], ...]
    e_text: Tuple[Optional[Tuple[str, str]], ...]
    width_ts_text: Tuple[Optional[str], ...]
    width_e_text: Tuple[Optional[str], ...]
    params: np.ndarray
    ts_seconds: Optional[np.ndarray] = None
    horizon: float = 100.0
    order: int = 16
    bits: Tuple[int, ...] = ()
    fallback: Tuple[Optional[Tuple["FallbackRun", ...]], ...] = ()
    seconds: float = 0.0
    threads: int = 0
    #: with ``sensitivities=True``: per case {input name: Sensitivity(dts, de, reason)}
    #: (names as the CLI's: the parameters of the source given, and v0), None where the case
    #: was not proved
    sensitivities: Tuple[Optional[dict], ...] = ()
    peak_force: Optional[np.ndarray] = None
    max_indentation: Optional[np.ndarray] = None
    energy_lost: Optional[np.ndarray] = None
    peak_force_newtons: Optional[np.ndarray] = None
    max_indentation_m: Optional[np.ndarray] = None
    energy_lost_joules: Optional[np.ndarray] = None
    #: with ``derived=True``: per case {name: (lo, hi) decimals rounded outward, or None}
    derived_text: Tuple[Optional[dict], ...] = ()
    derived_reason: Optional[Tuple[Optional[str], ...]] = None

    def __len__(self) -> int:
        return len(self.proved)

    def __repr__(self) -> str:
        shape = np.shape(self.proved)
        depth = len(shape) - 1
        proved = int(np.sum(self.proved))
        n = int(np.size(self.proved))
        text = f"RigorousResult(model={self.model!r}, {_frames.shape_text(shape)}: {proved} proved"
        if proved < n:
            text += f", {n - proved} not proved"
        if n == 1 and self.e_text[0] is not None and depth == 0:
            (elo, ehi), (tlo, thi) = self.e_text[0], self.ts_text[0]
            text += f"; e ∈ [{elo}, {ehi}], T_s ∈ [{tlo}, {thi}]"
        else:
            for name in ("e", "ts"):
                w = _frames.widest(getattr(self, "width_" + name),
                                   _frames.flat_items(getattr(self, f"width_{name}_text"), depth))
                if w is not None:
                    text += f"; widest {'T_s' if name == 'ts' else 'e'} ≤ {w}"
        return text + f"; {self.seconds:.3g} s)"

    def to_pandas(self, floats: bool = False) -> Any:
        """One row per case (``set``, ``speed`` for a grid): the enclosures of v0, T_s and e as
        ``*_lo``/``*_hi`` and their widths, [the derived outputs' enclosures,] status,
        separated, bits, reason and the enclosures of the parameters. By default the bounds are
        the outward decimals (v0's inward: the speeds the result holds for; text: each reads
        back to its double, ``df.e_lo.astype(float)``), so that printing the frame prints
        bounds; ``floats=True`` gives float64 columns (pandas displays those rounded to
        nearest). Needs pandas."""
        pd = _frames.pandas()
        shape = np.shape(self.proved)
        depth = len(shape) - 1
        n = int(np.size(self.proved))
        cols = _frames.grid_index(shape)
        for name in ("v0", "ts", "e", "ts_seconds") + DERIVED:
            b = getattr(self, name)
            if b is None:
                continue
            if floats:
                a = np.asarray(b, dtype=float).reshape(-1, 2)
                cols[f"{name}_lo"], cols[f"{name}_hi"] = a[:, 0], a[:, 1]
            elif name == "v0":
                # the speeds the result holds for: inward
                cols["v0_lo"], cols["v0_hi"] = _frames.inward_pairs(b)
            else:
                cols[f"{name}_lo"], cols[f"{name}_hi"] = _frames.outward_pairs(b)
        for name in ("ts", "e"):
            w = getattr(self, "width_" + name)
            cols["width_" + name] = (_frames.flat(w) if floats else
                                     _frames.flat_items(getattr(self, f"width_{name}_text"), depth))
        cols["status"] = _frames.flat_items(self.status, depth)
        cols["separated"] = _frames.flat(self.separated)
        if self.bits:
            cols["bits"] = _frames.flat_items(self.bits, depth)
        cols["reason"] = _frames.flat_items(self.reason, depth)
        if floats:
            cols.update(_frames.params_columns(self.params, n, True))
        else:
            if isinstance(self.params, dict):
                items = list(self.params.items())
            else:
                a = np.asarray(self.params, dtype=float).reshape(n, 6, 2)
                items = [(name, a[:, j]) for j, name in enumerate(_frames.SIX)]
            for name, b in items:
                cols[f"{name}_lo"], cols[f"{name}_hi"] = _frames.outward_pairs(b)
        return pd.DataFrame(cols)


@dataclass(frozen=True, eq=False, repr=False)
class TrajectoryResult:
    """Samples of the trajectory at uniform times, the last at T_s (or ``t_end``).

    Float engine: ``t`` (n,), ``states`` (n, N) with columns ``state_names`` (X, Z, V or
    R, Y, Z, W; always nondimensional), ``x``, ``v``, ``F`` (the contact force F_P) (n,); in
    ``units="physical"`` t [s], x [m], v [m/s], F [N]. Proved (``rigorous=True``): the same
    as enclosures, ``states`` (n, N, 2) and ``x``, ``v``, ``F`` (n, 2) as (lo, hi).
    """

    model: str
    t: np.ndarray
    states: np.ndarray
    state_names: Tuple[str, ...]
    x: np.ndarray
    v: np.ndarray
    F: np.ndarray
    units: str
    rigorous: bool
    note: Optional[str] = None

    def __repr__(self) -> str:
        t = np.asarray(self.t, dtype=float)
        end = t[-1] if t.size else float("nan")
        return (f"TrajectoryResult(model={self.model!r}, {t.size} samples, t 0…{end:.4g}, "
                f"{self.units}{', proved enclosures' if self.rigorous else ''})")

    def to_pandas(self, floats: bool = False) -> Any:
        """One row per sample: t, the states by name, x, v, F; for proved enclosures
        ``*_lo``/``*_hi`` columns, as outward decimals unless ``floats=True`` (see
        :meth:`RigorousResult.to_pandas`). Needs pandas."""
        named = [(k, self.states[:, j]) for j, k in enumerate(self.state_names)]
        items = [("t", self.t)] + named + [("x", self.x), ("v", self.v), ("F", self.F)]
        return _frames.pandas().DataFrame(_frames.sample_columns(items, floats))


@dataclass(frozen=True, eq=False, repr=False)
class LoopResult:
    """The hysteresis loop F against x up to T_s, as the CLI's ``loop``: nondimensional
    (x = X, F = F_P), or with ``physical_units=True`` x = ``|x|`` in millimetres and F in newtons
    (the paper's Fig. 4). Proved: (n, 2) enclosures."""

    model: str
    x: np.ndarray
    F: np.ndarray
    units: str
    rigorous: bool
    note: Optional[str] = None

    def __repr__(self) -> str:
        return (f"LoopResult(model={self.model!r}, {len(self.F)} samples, {self.units}"
                f"{', proved enclosures' if self.rigorous else ''})")

    def to_pandas(self, floats: bool = False) -> Any:
        """One row per sample: x, F (``*_lo``/``*_hi`` for proved enclosures, as outward
        decimals unless ``floats=True``). Needs pandas."""
        items = [("x", self.x), ("F", self.F)]
        return _frames.pandas().DataFrame(_frames.sample_columns(items, floats))


@dataclass(frozen=True, eq=False, repr=False)
class CostResult:
    """J(ṽ0, ẽ, P*) = sqrt(Σ (ẽ_i − e(𝓟(P*, ṽ0_i)))²) (eq:J) and the curve.

    ``e_model`` is NaN where the model could not be evaluated (listed in ``errors`` as
    (v0, reason)); such a speed counts with residual 1, and J is then an upper bound.
    ``rms`` = J/√M."""

    model: str
    base: Tuple[float, ...]
    J: float
    m: int
    rms: float
    v0: np.ndarray
    e_data: np.ndarray
    e_model: np.ndarray
    errors: Tuple[Tuple[float, str], ...]

    def __repr__(self) -> str:
        base = ", ".join(f"{x:.4g}" for x in self.base)
        return (f"{type(self).__name__}(model={self.model!r}, J={self.J:.6g}, rms={self.rms:.4g}, "
                f"{self.m} rows, base=({base}){self._more()})")

    def _more(self) -> str:
        return ""

    def to_pandas(self) -> Any:
        """One row per data point: v0, e_data, e_model, residual = e_data − e_model. Needs
        pandas."""
        pd = _frames.pandas()
        return pd.DataFrame({"v0": self.v0, "e_data": self.e_data, "e_model": self.e_model,
                             "residual": np.asarray(self.e_data) - np.asarray(self.e_model)})


@dataclass(frozen=True, eq=False)
class FitStart:
    """One start of :func:`fit`: where it began, the best P* it found and J there."""

    start: int
    J: float
    base: Tuple[float, ...]
    initial: Tuple[float, ...]
    iterations: int
    evaluations: int
    converged: bool


@dataclass(frozen=True, eq=False, repr=False)
class FitResult(CostResult):
    """The best base set ``base`` = P* = (B_b, Γ_b, κ, σ_b, n, p) of :func:`fit`, J (eq:J)
    there with its curve (as :class:`CostResult`), and every start."""

    p1: bool = False
    seed: int = 1
    evaluations: int = 0
    seconds: float = 0.0
    starts: Tuple[FitStart, ...] = field(default_factory=tuple)
    #: the distinct minima, best first: dicts with P_star, base, J, basin_size, starts,
    #: delta_chi2, indistinguishable, converged, at_bound (and uncertainty with
    #: ``uncertainty=True``), as the CLI's JSON
    minima: Tuple[dict, ...] = field(default_factory=tuple)
    #: the uncertainty at the best fit (``uncertainty=True``): names, theta, jacobian,
    #: jacobian_source, s2, covariance, std_errors, correlation, singular_values, directions,
    #: condition_number, poorly_determined
    uncertainty: Optional[dict] = None
    #: χ² = J², J²/(M_res − k), the scale s² of Δχ² and the covariance, the free parameters
    chi2: float = float("nan")
    reduced_chi2: float = float("nan")
    s2: float = float("nan")
    free: Tuple[str, ...] = field(default_factory=tuple)
    converged: bool = True
    at_bound: Tuple[str, ...] = field(default_factory=tuple)
    #: the whole JSON report of the CLI's ``fit --format json``
    report: dict = field(default_factory=dict)

    def _more(self) -> str:
        flags = "" if self.converged else ", NOT converged"
        if self.at_bound:
            flags += f", at bound: {', '.join(self.at_bound)}"
        return (f", {len(self.minima)} distinct minim{'um' if len(self.minima) == 1 else 'a'}, "
                f"{len(self.starts)} starts{flags}, {self.seconds:.3g} s")

    def minima_frame(self) -> Any:
        """The distinct minima, best first, one row per minimum: J, basin_size, P* by name (B,
        Gamma, kappa, sigma, n, p: the base set, σ_b as sigma), delta_chi2, indistinguishable,
        converged. Needs pandas."""
        pd = _frames.pandas()
        rows = []
        for k in self.minima:
            row = {"J": k.get("J"), "basin_size": k.get("basin_size")}
            row.update(k.get("P_star", {}))
            for name in ("delta_chi2", "indistinguishable", "converged"):
                row[name] = k.get(name)
            rows.append(row)
        return pd.DataFrame(rows)


class FitProgress(NamedTuple):
    """What the ``progress`` callback of :func:`fit` receives after every Nelder–Mead
    iteration: iterations done of ``total`` (a start that stops early counts its unused
    budget as done), starts finished of ``starts``, and J of the last finished start (NaN
    before the first)."""

    done: int
    total: int
    starts_done: int
    starts: int
    last_J: float


# ---------------------------------------------------------------------------------------------
# the functions


@_flags_checked
def cor(
    model: str,
    *,
    base: Any = None,
    nd: Any = None,
    physical: Any = None,
    v0: Any = None,
    rtol: float = _RTOL,
    atol: float = _ATOL,
    max_step: float = _MAX_STEP,
    horizon: float = 100.0,
    threads: Optional[int] = None,
    progress: Union[None, bool, Callable[[int, int], Any]] = None,
    derived: bool = False,
) -> CorResult:
    """T_s (eq:main_t_s) and the coefficient of restitution e = V(T_s) (eq:main_cor) on the
    f64 DOP853 engine, one case per impact speed.

    Parameters
    ----------
    model : "shc" (NDBWSHCCM, eq:BWSHCCM_nd), "maxwell" (NDBWMCM, eq:BWMCM_nd), or a classical
        law: "hooke", "hertz", "hunt-crossley", "kelvin-voigt", "linear-maxwell".
    base : P* = (B_b, Γ_b, κ, σ_b, n, p), mapped to each v0 by 𝓟(P*, v0). For a law its
        family by name: {"sigma_b": …, "n": …} (hunt-crossley, σ = σ_b·v0), {"n": …}
        (hertz), {"zeta": …} (kelvin-voigt), {"c": …} (linear-maxwell), {} (hooke).
    nd : P = (B, Γ, κ, σ, n, p), one case (no v0). For a law by name: {"sigma": …, "n": …},
        {"n": …}, {"zeta": …}, {"c": …} (c̃ = c/√(mk)), {}; n is 3/2 when not given.
    physical : SI parameters {m, k, c, n, p, alpha, beta, gamma, A} (eq:BWSHCCM, eq:BWMCM);
        for a law {m, k} and hertz {n}, hunt-crossley {chi, n}, kelvin-voigt and
        linear-maxwell {c} (``bwcl cor --help``, CLASSICAL LAWS).
    v0 : impact speed(s) v0 > 0 [m/s]: a number, a 1-D array, or the CLI's list "0.5,1,2".

        Several parameter sets in one call: ``base`` or ``nd`` as an (m, 6) array or a list
        of m sets; ``physical`` (and a law's ``base``/``nd``) as a mapping whose values are
        1-D arrays of length m (scalars are repeated) or a list of m mappings. Every set is
        paired with every speed and the m·n cases run in parallel; each per-case field of the
        result is then an (m, n[, …]) array (m, n: sets, speeds; ``error`` a tuple of m
        tuples), (m, …) for ``nd``. At most 10⁷ cases per call.
    rtol, atol, max_step : DOP853 settings, the paper's by default (its SciPy call).
    horizon : nondimensional time after which "no separation" is reported (0 < T ≤ 1e6).
    threads : the size of this call's thread pool (default: the global pool, all cores;
        -1 too).
    progress : True for a progress bar (tqdm when installed), or a callable receiving
        ``(done, total)`` cases (at most every 0.1 s, and at the end); an exception it raises
        stops the call and is raised.
    derived : also the peak contact force, the maximum indentation and the kinetic energy
        lost (``result.peak_force``, ``max_indentation``, ``energy_lost``; in N, m and J too
        with ``physical``), on the same dense output.

    Returns
    -------
    CorResult with NumPy arrays ``ts``, ``e``, ``separated``, ``nfev`` (one entry per speed).
    A RuntimeWarning counts the separations whose e lies below ``atol``: the run's rounding
    level, where such a separation may not be real (``cor_rigorous`` decides).

    Examples
    --------
    >>> r = bwcl.cor("shc", base=bwcl.TABLE1["SHC DSS"].base, v0=[0.5, 1, 2])
    >>> r.e  # doctest: +SKIP
    array([0.9…, 0.8…, 0.7…])
    >>> sets = np.tile(bwcl.TABLE1["SHC DSS"].base, (100, 1))
    >>> sets[:, 2] = np.linspace(0.3, 0.9, 100)           # κ from 0.3 to 0.9
    >>> bwcl.cor("shc", base=sets, v0=np.linspace(0.1, 5, 50)).e.shape
    (100, 50)
    """
    base, nd, physical, sets = _sets.source_sets(model, base, nd, physical, False)
    argv = ["cor"] + _source(model, base, nd, physical, False)
    argv += _float_engine(rtol, atol, max_step, horizon)
    if _flag(derived, "derived"):
        argv.append("--derived")
    arr = tokens = None
    if v0 is not None:
        arr = _speeds_array(v0)
        if arr is None:
            tokens = _speed_tokens(v0, False)
    _sets.check_size(sets, len(arr) if arr is not None else len(tokens or ()))
    cb = _progress.cases(progress, "cor")
    d = _bwcl.cor(argv, v0_array=arr, v0_tokens=tokens, sets=sets, threads=_threads(threads),
                  progress=cb)
    _progress.finish(cb, len(d["e"]))
    _warn_rounding_level(d, float(atol))
    return _sets.reshape(_cor_result(d), sets, nd is not None)


def _warn_rounding_level(d: dict, atol: float) -> None:
    """A RuntimeWarning where a separation's e lies below the run's absolute tolerance: V and F
    are 0 to what the float run resolves there, and rounding may have met the condition (as
    ``bwcl cor``'s note; the linear Maxwell law with c = 1/2 + 2⁻⁵³ "separates" at T ≈ 39 with
    e ≈ 1e-14, its T_s ≈ 1.5e8)."""
    e = np.asarray(d["e"], dtype=float)
    low = int(np.count_nonzero(np.asarray(d["separated"], dtype=bool) & (np.abs(e) < atol)))
    if low:
        warnings.warn(f"{low} case(s) with e below atol = {atol!r}: the float run's separation "
                      "lies at its rounding level there and may not be real (cor_rigorous "
                      "proves or refutes it)", RuntimeWarning, stacklevel=4)


def _cor_result(d: dict) -> CorResult:
    return CorResult(
        model=d["model"],
        v0=d["v0"],
        ts=d["ts"],
        e=d["e"],
        separated=d["separated"],
        nfev=d["nfev"],
        steps=d["steps"],
        params=d["params"],
        error=tuple(d["error"]),
        ts_seconds=d.get("ts_seconds"),
        t_c=d.get("t_c"),
        horizon=d["horizon"],
        seconds=d["seconds"],
        threads=d["threads"],
        **{name: d.get(name) for name in DERIVED},
        derived_reason=None if "derived_reason" not in d else tuple(d["derived_reason"]),
    )


@_flags_checked
def cor_rigorous(
    model: str,
    *,
    base: Any = None,
    nd: Any = None,
    physical: Any = None,
    v0: Any = None,
    horizon: float = 100.0,
    order: int = 16,
    pieces: Optional[int] = None,
    threads: Optional[int] = None,
    raise_on_failure: bool = False,
    fallback_bits: Optional[int] = None,
    fallback_seconds: Optional[float] = None,
    digits: Optional[int] = None,
    time_limit: float = 300.0,
    sensitivities: bool = False,
    progress: Union[None, bool, Callable[[int, int], Any]] = None,
    derived: bool = False,
) -> RigorousResult:
    """Proved enclosures of T_s (eq:main_t_s) and e = V(T_s) (eq:main_cor) from the interval
    Taylor engine, one case per impact speed.

    Every input may be a number (enclosed as its shortest decimal ``repr``: the enclosure
    holds that decimal and the double itself), a decimal string (enclosed as written:
    ``"0.632"`` is not a double) or a range ``(lo, hi)`` (proved over the whole range, split
    adaptively into at most ``pieces`` sub-ranges where a piece cannot be proved or makes the
    hull of e or T_s wider than 1.1× the spread proved at points; the hull is the result). In
    ``v0`` a range is an item: ``v0=[(0.9, 1.1)]``.

    A batch reports per case: ``status[i]`` is "proved" or "not proved", with ``reason[i]``
    saying why (the other cases are still computed). With ``raise_on_failure=True`` a case
    not proved raises :class:`NotProvedError` (carrying the whole result) instead.

    Parameters
    ----------
    model, base, nd, physical, v0 : as :func:`cor` (several parameter sets too: every field
        then (m, n[, …]), the per-case tuples nested as m tuples of n).
    horizon : nondimensional time within which separation must be proved.
    order : Taylor order K of the engine, 2 ≤ K ≤ 40.
    pieces : ceiling of the adaptive split of a range input, 1 ≤ N ≤ 1024 (default 256; a
        classical law's range is proved whole).
    threads : the size of this call's thread pool.
    fallback_bits : a point case that double precision cannot decide ("grazing or
        undecidable", "grew too wide", "cannot cross") is tried again on MPFR intervals at
        128, 192, then 256 bits, up to this many (0, 128, 192 or 256, default 256; 0 turns
        it off; the Bouc–Wen models only).
    fallback_seconds : wall-clock budget of each precision of the fallback, 0 < S ≤ 3600
        (default 60).
    digits : prove T_s and e to this many significant digits, 1 ≤ D ≤ 100, on intervals over
        MPFR floats (``bwcl cor --rigorous --digits D``: 30 digits take ≈ 1–2 s a case, 60
        ≈ 5–9 s); ``ts_text`` and ``e_text`` then carry every digit the width allows, rounded
        outward, ``ts`` and ``e`` the ends rounded outward to doubles, ``bits`` the precision
        (128, 192, 256 or 384). Single values only (no ranges, not with ``physical``); the
        Taylor order and tolerances follow D (``order`` reports it). Where the precise run
        fails (not for lack of time) the case still gets the f64-interval engine's proof,
        with ``bits`` 53 and the reason in ``reason``.
    time_limit : the wall-clock budget of the whole call in seconds, 0 < S ≤ 86400 (``bwcl
        cor --rigorous --time-limit S``): cases not proved by then are "not proved" with the
        reason "the time budget of S s ran out".

    sensitivities : also prove ∂T_s/∂u and ∂e/∂u of every input u of each case (its
        parameters and v0), at its value or over its range (``result.sensitivities``; the
        Bouc–Wen models, not with ``digits``).
    progress : as :func:`cor` (cases proved or not, as they end).
    derived : also enclose the peak contact force, the maximum indentation (max over
        [0, T_s], by a branch and bound on the proved flow) and the kinetic energy lost
        (``result.peak_force``, ``max_indentation``, ``energy_lost`` as (n, 2) bounds; in N, m
        and J too with ``physical``). Point cases on the f64-interval engine: a range, a case
        decided by the precision fallback or without separation has NaN bounds and the reason
        in ``derived_reason``; not with ``digits``.

    A case proved to have no separation before the horizon (T_s > horizon) has status
    "proved", ``separated`` False, NaN bounds and that statement in ``reason``.

    Returns
    -------
    RigorousResult: ``ts``, ``e`` (n, 2) float bounds, ``ts_text``, ``e_text`` the decimals
    rounded outward, ``status`` and ``reason`` per case, ``bits`` the precision that decided
    it.
    """
    base, nd, physical, sets = _sets.source_sets(model, base, nd, physical, True)
    argv = ["cor"] + _source(model, base, nd, physical, True)
    argv += ["--rigorous", f"--horizon={_num(horizon, 'horizon')}"]
    argv += [f"--order={_num(order, 'order')}"]
    for opt, x in (("pieces", pieces), ("fallback-bits", fallback_bits),
                   ("fallback-seconds", fallback_seconds)):
        if x is not None:
            argv.append(f"--{opt}={_num(x, opt.replace('-', '_'))}")
    if digits is not None:
        if sensitivities:
            raise ValueError("sensitivities are proved on the f64-interval engine: not with digits")
        argv += [f"--digits={_num(digits, 'digits')}"]
    if sensitivities:
        argv.append("--sensitivities")
    if _flag(derived, "derived"):
        if digits is not None:
            raise ValueError("derived outputs are proved on the f64-interval engine: not with digits")
        argv.append("--derived")
    argv += [f"--time-limit={_num(time_limit, 'time_limit')}"]
    tokens = None if v0 is None else _speed_tokens(v0, True)
    _sets.check_size(sets, len(tokens or ()))
    cb = _progress.cases(progress, "cor_rigorous")
    d = _bwcl.cor_rigorous(argv, v0_tokens=tokens, sets=sets, threads=_threads(threads),
                           progress=cb)
    n = len(d["proved"])
    _progress.finish(cb, n)
    res = RigorousResult(
        model=d["model"],
        status=tuple("proved" if p else "not proved" for p in d["proved"]),
        proved=d["proved"],
        separated=d["separated"],
        # the reasons in the Python call's terms (time_limit, not --time-limit)
        reason=tuple(None if r is None else _pythonic(r) for r in d["reason"]),
        v0=d["v0"],
        ts=d["ts"],
        e=d["e"],
        width_ts=d["width_ts"],
        width_e=d["width_e"],
        v0_text=tuple(d["v0_text"]),
        ts_text=tuple(d["ts_text"]),
        e_text=tuple(d["e_text"]),
        width_ts_text=tuple(d["width_ts_text"]),
        width_e_text=tuple(d["width_e_text"]),
        params=d["params"].reshape(n, 6, 2) if isinstance(d["params"], np.ndarray)
        else d["params"],
        ts_seconds=d.get("ts_seconds"),
        horizon=d["horizon"],
        order=d["order"],
        seconds=d["seconds"],
        threads=d["threads"],
        bits=tuple(d["bits"]),
        fallback=tuple(
            None if runs is None else tuple(FallbackRun(*r) for r in runs)
            for runs in d["fallback"]
        ),
        sensitivities=tuple(
            None if case is None else {
                name: Sensitivity(None if dts is None else tuple(dts),
                                  None if de is None else tuple(de), why)
                for name, dts, de, why in case
            }
            for case in d.get("sensitivities", ())
        ),
        **{name: d[name] for name in DERIVED if name in d},
        derived_text=tuple(
            {name: d[name + "_text"][i] for name in DERIVED if name in d}
            for i in range(n)
        ) if "derived_reason" in d else (),
        derived_reason=None if "derived_reason" not in d else tuple(d["derived_reason"]),
    )
    flat = res
    res = _sets.reshape(res, sets, nd is not None)
    if raise_on_failure and not flat.proved.all():
        bad = [i for i in range(n) if not flat.proved[i]]
        where = bad[0] if res is flat else tuple(int(k) for k in np.argwhere(~res.proved)[0])
        raise NotProvedError(
            f"{len(bad)} of {n} case(s) not proved; case {where}: {flat.reason[bad[0]]}", res
        )
    return res


def _curve(
    command: str,
    model: Any,
    base: Any,
    nd: Any,
    physical: Any,
    v0: Any,
    t_end: Any,
    points: Any,
    physical_units: bool,
    rigorous: bool,
    rtol: Any,
    atol: Any,
    max_step: Any,
    horizon: Any,
    order: Any,
    threads: Any,
) -> dict:
    argv = [command] + _source(model, base, nd, physical, rigorous)
    if v0 is not None:
        argv.append("--v0=" + ",".join(_speed_tokens(v0, rigorous)))
    argv.append(f"--points={_num(points, 'points')}")
    if t_end is not None:
        argv.append(f"--t-end={_num(t_end, 't_end')}")
    if physical_units:
        argv.append("--physical-units")
    if rigorous:
        # the float engine's settings would be silently unused (as order is refused without
        # rigorous): given with other values than their defaults, they are refused
        for name, x, default in (("rtol", rtol, _RTOL), ("atol", atol, _ATOL),
                                 ("max_step", max_step, _MAX_STEP)):
            if not (isinstance(x, numbers.Real) and not isinstance(x, bool) and x == default):
                raise ValueError(f"{name} = {_frames_repr(x)} is a setting of the float engine, "
                                 "not of rigorous=True")
        argv += ["--rigorous", f"--horizon={_num(horizon, 'horizon')}"]
        if order is not None:
            argv.append(f"--order={_num(order, 'order')}")
    else:
        argv += _float_engine(rtol, atol, max_step, horizon)
        if order is not None:
            argv.append(f"--order={_num(order, 'order')}")
    return _bwcl.trajectory(argv, threads=_threads(threads))


def _several(v0: Any) -> Optional[list]:
    """The speeds of a ``v0`` that holds several (a sequence, a 1-D array or the CLI's list
    "1,2"), else None."""
    v0 = _plain(v0, "v0")
    if isinstance(v0, str):
        items = v0.split(",")
    elif isinstance(v0, np.ndarray) and v0.ndim == 1:
        items = v0.tolist()
    elif isinstance(v0, (list, tuple)):
        items = list(v0)
    else:
        return None
    return items if len(items) > 1 else None


@_flags_checked
def trajectory(
    model: str,
    *,
    base: Any = None,
    nd: Any = None,
    physical: Any = None,
    v0: Any = None,
    t_end: Optional[float] = None,
    points: int = 1000,
    physical_units: bool = False,
    rigorous: bool = False,
    rtol: float = _RTOL,
    atol: float = _ATOL,
    max_step: float = _MAX_STEP,
    horizon: float = 100.0,
    order: Optional[int] = None,
    threads: Optional[int] = None,
) -> TrajectoryResult:
    """The trajectory Φ(T) of the collision at ``points`` uniform times from 0 to T_s
    (eq:main_t_s; or ``t_end``; the horizon without separation), as the CLI's
    ``trajectory``.

    Float (default): samples of the DOP853 dense output; with ``physical`` and
    ``physical_units=True``, t [s], x [m], v [m/s], F [N] (t = T·T_c, x = X·X_c,
    eq:BWSHCCM_T_c, eq:BWSHCCM_X_c). ``rigorous=True``: enclosures of the proved flow up to
    the upper bound of T_s. One impact speed ``v0`` (with ``base`` or ``physical``) gives
    one result; several (a list or 1-D array) a tuple of results, one per speed, in order.
    """
    many = _several(v0)
    if many is not None:
        return tuple(trajectory(model, base=base, nd=nd, physical=physical, v0=v, t_end=t_end,
                                points=points, physical_units=physical_units,
                                rigorous=rigorous, rtol=rtol, atol=atol, max_step=max_step,
                                horizon=horizon, order=order, threads=threads) for v in many)
    d = _curve("trajectory", model, base, nd, physical, v0, t_end, points, physical_units,
               rigorous, rtol, atol, max_step, horizon, order, threads)
    states = d["states"]
    names = tuple(d["state_names"])
    if d["rigorous"]:
        states = states.reshape(len(d["t"]), len(names), 2)
    return TrajectoryResult(
        model=d["model"], t=d["t"], states=states, state_names=names, x=d["x"], v=d["v"],
        F=d["F"], units=d["units"], rigorous=d["rigorous"], note=d["note"],
    )


@_flags_checked
def loop(
    model: str,
    *,
    base: Any = None,
    nd: Any = None,
    physical: Any = None,
    v0: Any = None,
    t_end: Optional[float] = None,
    points: int = 1000,
    physical_units: bool = False,
    rigorous: bool = False,
    rtol: float = _RTOL,
    atol: float = _ATOL,
    max_step: float = _MAX_STEP,
    horizon: float = 100.0,
    order: Optional[int] = None,
    threads: Optional[int] = None,
) -> LoopResult:
    """The hysteresis loop: the contact force F_P against the deformation X up to T_s, as the
    CLI's ``loop`` (the paper's Fig. 4). Nondimensional, or with ``physical`` and
    ``physical_units=True`` x = ``|x|`` in mm and F in N. Arguments as :func:`trajectory`
    (several speeds: a tuple of loops)."""
    many = _several(v0)
    if many is not None:
        return tuple(loop(model, base=base, nd=nd, physical=physical, v0=v, t_end=t_end,
                          points=points, physical_units=physical_units, rigorous=rigorous,
                          rtol=rtol, atol=atol, max_step=max_step, horizon=horizon, order=order,
                          threads=threads) for v in many)
    d = _curve("loop", model, base, nd, physical, v0, t_end, points, physical_units,
               rigorous, rtol, atol, max_step, horizon, order, threads)
    x = d["x"]
    if d["units"] == "physical":
        x = np.abs(x) * 1e3
    return LoopResult(model=d["model"], x=x, F=d["F"], units=d["units"],
                      rigorous=d["rigorous"], note=d["note"])


def _data_args(data: Any, v0: Any, e: Any) -> Tuple[str, Optional[np.ndarray], Optional[np.ndarray]]:
    """--data and the arrays: a CSV path (header v0,e) or two 1-D arrays."""
    if data is not None:
        if v0 is not None or e is not None:
            raise ValueError("give either data (a CSV file) or the arrays v0 and e, not both")
        if not isinstance(data, (str, os.PathLike)):
            raise TypeError(f"data: expected the path of a CSV file, got {type(data).__name__}")
        return "--data=" + os.fspath(data), None, None
    if v0 is None or e is None:
        raise ValueError("give data (a CSV file with the header v0,e) or both arrays v0 and e")
    arrays = []
    for name, a in (("v0", v0), ("e", e)):
        a = np.asarray(_plain(a, name))
        if a.ndim != 1:
            raise ValueError(f"{name} must be a 1-D array, got shape {a.shape}")
        if a.dtype.kind not in "fiu":
            raise TypeError(f"{name}: expected numbers, got an array of dtype {a.dtype}")
        arrays.append(np.ascontiguousarray(a, dtype=np.float64))
    return "--data=<arrays>", arrays[0], arrays[1]


def _cost_result(cls: Any, d: dict, **extra: Any) -> Any:
    return cls(
        model=d["model"], base=tuple(d["base"]), J=d["J"], m=d["m"], rms=d["rms"],
        v0=d["v0"], e_data=d["e_data"], e_model=d["e_model"],
        errors=tuple(tuple(x) for x in d["errors"]), **extra,
    )


@_flags_checked
def cost(
    model: str,
    data: Any = None,
    *,
    base: Any,
    v0: Any = None,
    e: Any = None,
    threads: Optional[int] = None,
) -> CostResult:
    """J(ṽ0, ẽ, P*) = sqrt(Σ_i (ẽ_i − e(𝓟(P*, ṽ0_i)))²) (eq:J) of the base set ``base`` on
    measured data: a CSV file ``data`` with the header ``v0,e`` (as the CLI's ``--data``), or
    the arrays ``v0`` [m/s] and ``e``. The CoRs at the paper's settings, in parallel."""
    data_arg, a, b = _data_args(data, v0, e)
    argv = ["cost"] + _source(model, base, None, None, False) + [data_arg]
    d = _bwcl.cost(argv, v0=a, e=b, threads=_threads(threads))
    return _cost_result(CostResult, d)


def _text_progress() -> Callable[[FitProgress], None]:
    """A progress bar: tqdm when installed, else one line on stderr rewritten in place."""
    try:
        from tqdm.auto import tqdm  # type: ignore

        bar = None

        def show(p: FitProgress) -> None:
            nonlocal bar
            if bar is None:
                bar = tqdm(total=p.total, desc="fit", unit="it")
            bar.n = p.done
            bar.set_postfix(starts=f"{p.starts_done}/{p.starts}", J=f"{p.last_J:.4e}")
            if p.done >= p.total or p.starts_done == p.starts:
                bar.close()

        return show
    except ImportError:
        def line(p: FitProgress) -> None:
            end = "\n" if p.starts_done == p.starts else ""
            last = "" if p.last_J != p.last_J else f", last J = {p.last_J:.4e}"
            sys.stderr.write(
                f"\rfit {p.done}/{p.total} iterations, {p.starts_done}/{p.starts} starts{last}{end}"
            )
            sys.stderr.flush()

        return line


@_flags_checked
def fit(
    model: str,
    data: Any = None,
    *,
    v0: Any = None,
    e: Any = None,
    starts: int = 8,
    seed: int = 1,
    max_iter: int = 300,
    init: Any = None,
    p1: bool = False,
    fix: Optional[dict] = None,
    bounds: Optional[dict] = None,
    error: Optional[float] = None,
    tc_error: Optional[float] = None,
    use_tc: bool = True,
    uncertainty: bool = False,
    jacobian: str = "central",
    cluster: bool = True,
    progress: Union[None, bool, Callable[[FitProgress], Any]] = None,
    threads: Optional[int] = None,
) -> FitResult:
    """Identify the base parameters P* = (B_b, Γ_b, κ, σ_b, n, p) from measured CoR data by
    minimizing J (eq:J) inside 𝓟, as the CLI's ``fit``: Nelder–Mead from ``starts`` seeded
    random points (and ``init``, a base set to refine), each restarted once from its best
    vertex, on a smooth bijection ℝ⁶ → 𝓟. The Maxwell model's p = 1 (an isolated point of 𝓟)
    is searched only with ``p1=True``.

    Parameters
    ----------
    data : a CSV file with the header v0,e — or give the arrays ``v0`` and ``e``.
    starts : random starts, 0 ≤ N ≤ 256 (0 needs ``init``); ``seed``: their seed.
    max_iter : Nelder–Mead iterations per run, 1 ≤ M ≤ 10000.
    fix : {name: value} held fixed (names B_b, Gamma_b, kappa, sigma_b, n, p; Greek too).
    bounds : {name: (lo, hi)} searched within bounds.
    error, tc_error : the error of every CoR / contact duration without a ``sigma`` /
        ``tc_sigma`` column value; ``use_tc=False`` ignores a ``tc`` column.
    uncertainty : the Jacobian, covariance, standard errors, correlations and SVD at the best
        fit (``result.uncertainty``) and at every minimum (``result.minima[i]["uncertainty"]``);
        ``jacobian``: "central" (central differences of the f64 engine) or "proved" (the proved
        sensitivities' midpoints: exact to ~1e-8, but M·k variational runs).
    cluster : cluster the starts into distinct minima (``result.minima``).
    progress : a callable receiving a :class:`FitProgress` after every iteration, or True for
        a progress bar (tqdm when installed). An exception it raises is raised when the fit
        returns.
    threads : the size of this call's thread pool (starts and speeds run in parallel).
    """
    data_arg, a, b = _data_args(data, v0, e)
    argv = ["fit"] + _source(model, None, None, None, False) + [data_arg]
    argv += [f"--starts={_num(starts, 'starts')}", f"--seed={_num(seed, 'seed')}",
             f"--max-iter={_num(max_iter, 'max_iter')}"]
    if init is not None:
        argv.append("--init=" + _six(init, "init", False))
    if p1:
        argv.append("--p1")
    argv += _search(fix, bounds, error, tc_error, use_tc)
    if uncertainty:
        argv += ["--uncertainty", f"--jacobian={jacobian}"]
    if not cluster:
        argv.append("--no-cluster")
    user = _progress.given(progress, "a FitProgress")
    if user is True:
        user = _text_progress()

    def cb(done: int, total: int, starts_done: int, n: int, j: float) -> None:
        user(FitProgress(done, total, starts_done, n, j))

    d = _bwcl.fit(argv, v0=a, e=b, progress=None if user is None else cb,
                  threads=_threads(threads))
    starts_out = tuple(
        FitStart(start=s["start"], J=s["J"], base=tuple(s["base"]), initial=tuple(s["initial"]),
                 iterations=s["iterations"], evaluations=s["evaluations"],
                 converged=s["converged"])
        for s in d["starts"]
    )
    r = json.loads(d["report"])
    return _cost_result(FitResult, d, p1=d["p1"], seed=d["seed"], evaluations=d["evaluations"],
                        seconds=d["seconds"], starts=starts_out, minima=tuple(r["minima"]),
                        uncertainty=r.get("uncertainty"), chi2=r["chi2"],
                        reduced_chi2=_float(r["reduced_chi2"]), s2=_float(r["s2"]),
                        free=tuple(r["free"]), converged=r["converged"],
                        at_bound=tuple(r["at_bound"]), report=r)


def _float(x: Any) -> float:
    """A JSON number, or NaN for null (a non-finite value)."""
    return float("nan") if x is None else float(x)


def _fix_text(fix: Any) -> str:
    """A mapping {name: value} as the CLI's --fix text (fit, profile, identify)."""
    if not isinstance(fix, Mapping):
        raise TypeError(f"fix: expected a dict name -> value, got {type(fix).__name__}")
    return ",".join(f"{_key(k, 'fix')}={_num(v, 'fix')}" for k, v in fix.items())


def _bounds_text(bounds: Any) -> str:
    """A mapping {name: (lo, hi)} as the CLI's --bounds text (fit, profile, identify)."""
    if not isinstance(bounds, Mapping):
        raise TypeError(f"bounds: expected a dict name -> (lo, hi), got {type(bounds).__name__}")
    items = []
    for k, v in bounds.items():
        if isinstance(v, (str, bytes)) or not isinstance(v, Sequence) or len(v) != 2:
            raise TypeError(f"bounds: {_frames_repr(k)} needs a pair (lo, hi), got "
                            f"{_frames_repr(v)}")
        lo, hi = v
        items.append(f"{_key(k, 'bounds')}={_num(lo, 'bounds')}..{_num(hi, 'bounds')}")
    return ",".join(items)


def _whole(x: Any, what: str) -> int:
    """A whole number as given (2.9 or "x" refused, not truncated or passed on)."""
    if isinstance(x, bool) or not isinstance(x, numbers.Integral):
        raise TypeError(f"{what} = {x!r:.40} must be a whole number")
    return int(x)


def _search(fix: Optional[dict], bounds: Optional[dict], error: Optional[float],
            tc_error: Optional[float], use_tc: bool) -> list:
    """The CLI's --fix, --bounds, --error, --tc-error and --no-tc."""
    out = []
    if fix:
        out.append("--fix=" + _fix_text(fix))
    if bounds:
        out.append("--bounds=" + _bounds_text(bounds))
    if error is not None:
        out.append(f"--error={_num(error, 'error')}")
    if tc_error is not None:
        out.append(f"--tc-error={_num(tc_error, 'tc_error')}")
    if not use_tc:
        out.append("--no-tc")
    return out


@_flags_checked
def profile(
    model: str,
    data: Any = None,
    *,
    v0: Any = None,
    e: Any = None,
    param: Optional[str] = None,
    points: int = 21,
    starts: int = 8,
    seed: int = 1,
    max_iter: int = 300,
    fix: Optional[dict] = None,
    bounds: Optional[dict] = None,
    error: Optional[float] = None,
    tc_error: Optional[float] = None,
    use_tc: bool = True,
    threads: Optional[int] = None,
) -> dict:
    """Fit (as :func:`fit`), then profile J along each free parameter (or ``param``) with the
    others re-optimized, as the CLI's ``profile``: a dict with the best fit (P_star, base, J,
    s2, threshold) and ``profiles``, one per parameter: name, best_value, J_min, points (value,
    J, delta_chi2, p_star, converged) and the 95 % likelihood-ratio interval ``lo``/``hi``
    ({"value", "open"}: open where it reaches the grid's end). A ``RuntimeWarning`` names the
    grid points whose re-optimization used its whole budget (``converged`` false)."""
    data_arg, a, b = _data_args(data, v0, e)
    argv = ["profile"] + _source(model, None, None, None, False) + [data_arg]
    argv += [f"--points={_num(points, 'points')}", f"--starts={_num(starts, 'starts')}",
             f"--seed={_num(seed, 'seed')}", f"--max-iter={_num(max_iter, 'max_iter')}"]
    if param is not None:
        argv.append(f"--param={param}")
    argv += _search(fix, bounds, error, tc_error, use_tc)
    out = json.loads(_bwcl.profile(argv, v0=a, e=b, threads=_threads(threads)))
    for prof in out.get("profiles", []):
        budget = sum(1 for q in prof["points"] if not q.get("converged", True))
        if budget:
            warnings.warn(
                f"bwcl.profile: {budget} of {len(prof['points'])} grid points of "
                f"{prof['name']} used their whole budget (max_iter={max_iter}): their J is only "
                "an upper bound of the profile there, and the interval may be off; raise "
                "max_iter, or fix the parameters the data do not determine",
                RuntimeWarning, stacklevel=2)
    return out


from . import _frames, _progress, _sets, plot  # noqa: E402
from .band import BandResult, InterpBandResult, MonotoneResult, band, prove_monotone  # noqa: E402
from .identify import IdentifyResult, identify, identify_dask  # noqa: E402
from .laws import (  # noqa: E402
    FORMULAS, LAWS, ClassicalResult, FormulaErrors, LawsResult, classical, compare, laws,
)
