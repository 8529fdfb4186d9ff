"""Type stubs of the bwcl package (see the docstrings in __init__.py)."""

import os
from typing import Any, Callable, Dict, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from .identify import IdentifyResult as IdentifyResult
from .identify import identify as identify
from .identify import identify_dask as identify_dask
from .laws import FORMULAS as FORMULAS
from .laws import LAWS as LAWS
from .laws import ClassicalResult as ClassicalResult
from .laws import classical as classical
from .laws import compare as compare
from .laws import FormulaErrors as FormulaErrors
from .laws import LawsResult as LawsResult
from .laws import laws as laws
from .band import BandResult as BandResult
from .band import InterpBandResult as InterpBandResult
from .band import MonotoneResult as MonotoneResult
from .band import band as band
from .band import prove_monotone as prove_monotone
from . import plot as plot

__version__: str
DERIVED: Tuple[str, ...]
class Table1Set(NamedTuple):
    model: str
    base: Tuple[float, float, float, float, float, float]
    @property
    def text(self) -> str: ...
    @property
    def named(self) -> Dict[str, float]: ...

TABLE1: Dict[str, Table1Set]

#: a value: a number, a decimal string read as written, or (cor_rigorous) a range (lo, hi)
Value = Union[float, int, str, Tuple[Union[float, int, str], Union[float, int, str]]]
#: six values B,Γ,κ,σ,n,p (or B_b,Γ_b,κ,σ_b,n,p), or the CLI's comma-separated text; for
#: cor/cor_rigorous also several sets: an (m, 6) array or a list of sets (results (m, n, …))
ParamSet = Union[str, Sequence[Value], npt.NDArray[np.floating[Any]],
                 Sequence[Sequence[Value]]]
#: a classical law's parameters by name (e.g. {"sigma": 0.3, "n": 1.5}), or "sigma=0.3,n=1.5"
LawParams = Union[str, Mapping[str, Value]]
#: SI parameters m, k, c, n, p, alpha, beta, gamma, A (a classical law: m, k and its own,
#: e.g. chi, n), or the CLI's "m=…,k=…" text
Physical = Union[str, Mapping[str, Value]]
#: impact speeds [m/s]: a number, a 1-D array or sequence, or the CLI's list "0.5,1,2"
Speeds = Union[float, int, str, Sequence[Value], npt.ArrayLike]
PathLike = Union[str, os.PathLike]

class NotProvedError(RuntimeError):
    result: Optional[RigorousResult]
    def __init__(self, message: str, result: Optional[RigorousResult] = ...) -> None: ...

class CorResult:
    model: str
    v0: npt.NDArray[np.float64]
    ts: npt.NDArray[np.float64]
    e: npt.NDArray[np.float64]
    separated: npt.NDArray[np.bool_]
    nfev: npt.NDArray[np.int64]
    steps: npt.NDArray[np.int64]
    #: (n, 6) for a Bouc–Wen model; for a classical law a dict of (n,) arrays by name
    params: Union[npt.NDArray[np.float64], Dict[str, npt.NDArray[np.float64]]]
    error: Tuple[Optional[str], ...]
    ts_seconds: Optional[npt.NDArray[np.float64]]
    t_c: Optional[npt.NDArray[np.float64]]
    horizon: float
    seconds: float
    threads: int
    peak_force: Optional[npt.NDArray[np.float64]]
    max_indentation: Optional[npt.NDArray[np.float64]]
    energy_lost: Optional[npt.NDArray[np.float64]]
    peak_force_newtons: Optional[npt.NDArray[np.float64]]
    max_indentation_m: Optional[npt.NDArray[np.float64]]
    energy_lost_joules: Optional[npt.NDArray[np.float64]]
    derived_reason: Optional[Tuple[Optional[str], ...]]
    @property
    def ok(self) -> npt.NDArray[np.bool_]: ...
    def __len__(self) -> int: ...
    def to_pandas(self) -> Any: ...

class Sensitivity(NamedTuple):
    dts: Optional[Tuple[float, float]]
    de: Optional[Tuple[float, float]]
    reason: Optional[str]

class FallbackRun(NamedTuple):
    bits: int
    seconds: float
    proved: bool
    reason: Optional[str]

class RigorousResult:
    model: str
    status: Tuple[str, ...]
    proved: npt.NDArray[np.bool_]
    separated: npt.NDArray[np.bool_]
    reason: Tuple[Optional[str], ...]
    v0: npt.NDArray[np.float64]
    ts: npt.NDArray[np.float64]
    e: npt.NDArray[np.float64]
    width_ts: npt.NDArray[np.float64]
    width_e: npt.NDArray[np.float64]
    v0_text: Tuple[Optional[Tuple[str, str]], ...]
    ts_text: Tuple[Optional[Tuple[str, str]], ...]
    e_text: Tuple[Optional[Tuple[str, str]], ...]
    width_ts_text: Tuple[Optional[str], ...]
    width_e_text: Tuple[Optional[str], ...]
    #: (n, 6, 2) for a Bouc–Wen model; for a classical law a dict of (n, 2) arrays by name
    params: Union[npt.NDArray[np.float64], Dict[str, npt.NDArray[np.float64]]]
    ts_seconds: Optional[npt.NDArray[np.float64]]
    horizon: float
    order: int
    seconds: float
    threads: int
    peak_force: Optional[npt.NDArray[np.float64]]
    max_indentation: Optional[npt.NDArray[np.float64]]
    energy_lost: Optional[npt.NDArray[np.float64]]
    peak_force_newtons: Optional[npt.NDArray[np.float64]]
    max_indentation_m: Optional[npt.NDArray[np.float64]]
    energy_lost_joules: Optional[npt.NDArray[np.float64]]
    derived_text: Tuple[Optional[Dict[str, Optional[Tuple[str, str]]]], ...]
    derived_reason: Optional[Tuple[Optional[str], ...]]
    bits: Tuple[int, ...]
    fallback: Tuple[Optional[Tuple[FallbackRun, ...]], ...]
    sensitivities: Tuple[Optional[Dict[str, Sensitivity]], ...]
    def __len__(self) -> int: ...
    def to_pandas(self, floats: bool = ...) -> Any: ...

class TrajectoryResult:
    model: str
    t: npt.NDArray[np.float64]
    states: npt.NDArray[np.float64]
    state_names: Tuple[str, ...]
    x: npt.NDArray[np.float64]
    v: npt.NDArray[np.float64]
    F: npt.NDArray[np.float64]
    units: str
    rigorous: bool
    note: Optional[str]
    def to_pandas(self, floats: bool = ...) -> Any: ...

class LoopResult:
    model: str
    x: npt.NDArray[np.float64]
    F: npt.NDArray[np.float64]
    units: str
    rigorous: bool
    note: Optional[str]
    def to_pandas(self, floats: bool = ...) -> Any: ...

class CostResult:
    model: str
    base: Tuple[float, ...]
    J: float
    m: int
    rms: float
    v0: npt.NDArray[np.float64]
    e_data: npt.NDArray[np.float64]
    e_model: npt.NDArray[np.float64]
    errors: Tuple[Tuple[float, str], ...]
    def to_pandas(self) -> Any: ...

class FitStart:
    start: int
    J: float
    base: Tuple[float, ...]
    initial: Tuple[float, ...]
    iterations: int
    evaluations: int
    converged: bool

class FitResult(CostResult):
    p1: bool
    seed: int
    evaluations: int
    seconds: float
    starts: Tuple[FitStart, ...]
    minima: Tuple[Dict[str, Any], ...]
    uncertainty: Optional[Dict[str, Any]]
    chi2: float
    reduced_chi2: float
    s2: float
    free: Tuple[str, ...]
    converged: bool
    at_bound: Tuple[str, ...]
    report: Dict[str, Any]
    def minima_frame(self) -> Any: ...

class FitProgress(NamedTuple):
    done: int
    total: int
    starts_done: int
    starts: int
    last_J: float

def cor(
    model: str,
    *,
    base: Optional[Union[ParamSet, LawParams]] = ...,
    nd: Optional[Union[ParamSet, LawParams]] = ...,
    physical: Optional[Physical] = ...,
    v0: Optional[Speeds] = ...,
    rtol: float = ...,
    atol: float = ...,
    max_step: float = ...,
    horizon: float = ...,
    threads: Optional[int] = ...,
    progress: Union[None, bool, Callable[[int, int], Any]] = ...,
    derived: bool = ...,
) -> CorResult: ...
def cor_rigorous(
    model: str,
    *,
    base: Optional[Union[ParamSet, LawParams]] = ...,
    nd: Optional[Union[ParamSet, LawParams]] = ...,
    physical: Optional[Physical] = ...,
    v0: Optional[Speeds] = ...,
    horizon: float = ...,
    order: int = ...,
    pieces: Optional[int] = ...,
    threads: Optional[int] = ...,
    raise_on_failure: bool = ...,
    fallback_bits: Optional[int] = ...,
    fallback_seconds: Optional[float] = ...,
    digits: Optional[int] = ...,
    time_limit: float = ...,
    sensitivities: bool = ...,
    progress: Union[None, bool, Callable[[int, int], Any]] = ...,
    derived: bool = ...,
) -> RigorousResult: ...
def trajectory(
    model: str,
    *,
    base: Optional[Union[ParamSet, LawParams]] = ...,
    nd: Optional[Union[ParamSet, LawParams]] = ...,
    physical: Optional[Physical] = ...,
    v0: Optional[Speeds] = ...,
    t_end: Optional[float] = ...,
    points: int = ...,
    physical_units: bool = ...,
    rigorous: bool = ...,
    rtol: float = ...,
    atol: float = ...,
    max_step: float = ...,
    horizon: float = ...,
    order: Optional[int] = ...,
    threads: Optional[int] = ...,
) -> Union[TrajectoryResult, Tuple[TrajectoryResult, ...]]: ...
def loop(
    model: str,
    *,
    base: Optional[Union[ParamSet, LawParams]] = ...,
    nd: Optional[Union[ParamSet, LawParams]] = ...,
    physical: Optional[Physical] = ...,
    v0: Optional[Speeds] = ...,
    t_end: Optional[float] = ...,
    points: int = ...,
    physical_units: bool = ...,
    rigorous: bool = ...,
    rtol: float = ...,
    atol: float = ...,
    max_step: float = ...,
    horizon: float = ...,
    order: Optional[int] = ...,
    threads: Optional[int] = ...,
) -> Union[LoopResult, Tuple[LoopResult, ...]]: ...
def cost(
    model: str,
    data: Optional[PathLike] = ...,
    *,
    base: ParamSet,
    v0: Optional[npt.ArrayLike] = ...,
    e: Optional[npt.ArrayLike] = ...,
    threads: Optional[int] = ...,
) -> CostResult: ...
def fit(
    model: str,
    data: Optional[PathLike] = ...,
    *,
    v0: Optional[npt.ArrayLike] = ...,
    e: Optional[npt.ArrayLike] = ...,
    starts: int = ...,
    seed: int = ...,
    max_iter: int = ...,
    init: Optional[ParamSet] = ...,
    p1: bool = ...,
    fix: Optional[Mapping[str, float]] = ...,
    bounds: Optional[Mapping[str, Tuple[float, float]]] = ...,
    error: Optional[float] = ...,
    tc_error: Optional[float] = ...,
    use_tc: bool = ...,
    uncertainty: bool = ...,
    jacobian: str = ...,
    cluster: bool = ...,
    progress: Union[None, bool, Callable[[FitProgress], Any]] = ...,
    threads: Optional[int] = ...,
) -> FitResult: ...
def profile(
    model: str,
    data: Optional[PathLike] = ...,
    *,
    v0: Optional[npt.ArrayLike] = ...,
    e: Optional[npt.ArrayLike] = ...,
    param: Optional[str] = ...,
    points: int = ...,
    starts: int = ...,
    seed: int = ...,
    max_iter: int = ...,
    fix: Optional[Mapping[str, float]] = ...,
    bounds: Optional[Mapping[str, Tuple[float, float]]] = ...,
    error: Optional[float] = ...,
    tc_error: Optional[float] = ...,
    use_tc: bool = ...,
    threads: Optional[int] = ...,
) -> Dict[str, Any]: ...
