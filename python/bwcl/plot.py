"""Plots of results on Matplotlib (optional: ``pip install matplotlib``). Each helper draws on
``ax`` (a new figure's axes when None) and returns the axes (or the array of axes).

- :func:`cor_curve` — e against v0 of a :class:`~bwcl.CorResult`, with the proofs of a
  :class:`~bwcl.RigorousResult` or :class:`~bwcl.BandResult` (drawn only where proved);
- :func:`loop` — the hysteresis loop F against x (the paper's Fig. 4);
- :func:`trajectory` — the states against time;
- :func:`residuals` — a fit's data and model CoRs and the residuals;
- :func:`profiles` — the profile likelihoods Δχ² of :func:`~bwcl.profile` with the 95 %
  threshold;
- :func:`paving` — a 2-D projection of the boxes of :func:`~bwcl.identify` by status.
"""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np

__all__ = ["cor_curve", "loop", "trajectory", "residuals", "profiles", "paving"]

#: colours of the paving's statuses
STATUS_COLOURS = {"feasible": "#2ca02c", "infeasible": "#d62728", "undecided": "#ffbf00"}


def _pyplot() -> Any:
    try:
        import matplotlib.pyplot as plt  # type: ignore
    except ImportError as e:  # pragma: no cover - exercised without matplotlib
        raise ImportError("bwcl.plot needs matplotlib: pip install matplotlib") from e
    return plt


def _axes(ax: Any) -> Any:
    if ax is None:
        _, ax = _pyplot().subplots()
    return ax


def cor_curve(result: Any = None, band: Any = None, ax: Any = None, label: Optional[str] = None,
              **kw: Any) -> Any:
    """e against v0: the f64 curve of ``result`` (a CorResult; one line per set for a grid
    of sets × speeds) and the proofs of ``band``, drawn only where they are proved: a
    RigorousResult's enclosures as markers at point speeds (each ~1e-13 wide: far thinner
    than a line) and as boxes over speed ranges; a BandResult (:func:`~bwcl.band`) as its
    pieces' boxes. Nothing is interpolated between proved speeds."""
    if result is None and band is None:
        raise ValueError("cor_curve: give a CorResult (result=) and/or proofs (band=: a "
                         "RigorousResult or a BandResult)")
    ax = _axes(ax)
    colour = kw.pop("color", None)
    if result is not None:
        e = np.asarray(result.e, dtype=float)
        v0 = np.asarray(result.v0, dtype=float)
        if e.ndim == 2:
            for i in range(e.shape[0]):
                ax.plot(v0[i], e[i], lw=1, label=f"set {i}" if e.shape[0] <= 10 else None, **kw)
        else:
            (line,) = ax.plot(v0, e, lw=1.2, color=colour, label=label or f"{result.model} (f64)",
                              **kw)
            colour = line.get_color()
    if band is not None:
        what = f"{label} proved" if label else "proved"
        if hasattr(band, "piece_thickness"):  # a BandResult: its pieces
            lo, hi, e = band.v0_lo, band.v0_hi, np.asarray(band.e, dtype=float)
        else:
            v = np.asarray(band.v0, dtype=float).reshape(-1, 2)
            e = np.asarray(band.e, dtype=float).reshape(-1, 2)
            ok = np.isfinite(e).all(axis=1)
            lo, hi, e = v[ok, 0], v[ok, 1], e[ok]
        # a speed given as a number is enclosed as its decimal: a point, a few ulps wide
        points = (hi - lo) <= 1e-12 * np.maximum(np.abs(lo), 1.0)
        if points.any():
            ax.plot(lo[points], e[points].mean(axis=1), "o", ms=3.5, mfc="none", color=colour,
                    label=f"{what} ({int(points.sum())} speeds)")
        for k, i in enumerate(np.flatnonzero(~points)):
            ax.fill_between([lo[i], hi[i]], [e[i, 0]] * 2, [e[i, 1]] * 2, color=colour,
                            alpha=0.5, lw=0, label=f"{what} (ranges)" if k == 0 else None)
    ax.set_xlabel("impact speed $v_0$ [m/s]")
    ax.set_ylabel("coefficient of restitution $e$")
    ax.legend(loc="best", fontsize="small")
    return ax


def loop(result: Any, ax: Any = None, **kw: Any) -> Any:
    """The hysteresis loop of a LoopResult: F against x (proved: the boxes' corners)."""
    ax = _axes(ax)
    x, F = np.asarray(result.x, dtype=float), np.asarray(result.F, dtype=float)
    if result.rigorous and x.ndim == 2:
        ax.fill_between(x.mean(axis=1), F[:, 0], F[:, 1], alpha=0.4, label="proved enclosure")
        ax.plot(x.mean(axis=1), F.mean(axis=1), lw=0.8, **kw)
    else:
        ax.plot(x, F, **kw)
    physical = result.units == "physical"
    ax.set_xlabel("deformation |x| [mm]" if physical else "X")
    ax.set_ylabel("contact force F [N]" if physical else "$F_P$")
    return ax


def trajectory(result: Any, states: Optional[Sequence[str]] = None, ax: Any = None,
               **kw: Any) -> Any:
    """The states of a TrajectoryResult against time (by default all; proved: bands)."""
    ax = _axes(ax)
    names = list(result.state_names)
    pick = names if states is None else list(states)
    t = np.asarray(result.t, dtype=float)
    tt = t.mean(axis=1) if t.ndim == 2 else t
    for name in pick:
        if name not in names:
            raise ValueError(f"trajectory: no state {name!r} (the states are {', '.join(names)})")
        y = np.asarray(result.states)[:, names.index(name)]
        if result.rigorous and y.ndim == 2:
            ax.fill_between(tt, y[:, 0], y[:, 1], alpha=0.4, label=name)
        else:
            ax.plot(tt, y, label=name, **kw)
    ax.set_xlabel("t [s]" if result.units == "physical" else "T")
    ax.legend(loc="best", fontsize="small")
    return ax


def residuals(result: Any, axes: Any = None) -> Any:
    """A fit (FitResult or CostResult): the data and the model's CoR against v0, and below
    the residuals e_data − e_model."""
    if axes is None:
        _, axes = _pyplot().subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    top, bottom = axes
    order = np.argsort(result.v0)
    v0, ed, em = (np.asarray(a)[order] for a in (result.v0, result.e_data, result.e_model))
    top.plot(v0, ed, "o", ms=4, label="data")
    top.plot(v0, em, "-", label=f"{result.model}, J = {result.J:.4g}")
    top.set_ylabel("e")
    top.legend(loc="best", fontsize="small")
    bottom.axhline(0, color="0.5", lw=0.8)
    bottom.plot(v0, ed - em, "o", ms=3)
    bottom.set_xlabel("impact speed $v_0$ [m/s]")
    bottom.set_ylabel("residual")
    return axes


def profiles(report: dict, axes: Any = None) -> Any:
    """The profiles of :func:`~bwcl.profile`: Δχ² against each parameter with the threshold
    of its 95 % likelihood-ratio interval (dashed), the interval shaded and the best fit's value
    a vertical line, as the CLI's ``profile --plot``. A grid point whose re-optimization used
    its whole budget (``converged`` false) is drawn hollow: its J is only an upper bound of the
    profile there."""
    profs = report.get("profiles", [])
    if not profs:
        raise ValueError("profiles: the report holds no profiles")
    if axes is None:
        cols = min(3, len(profs))
        rows = (len(profs) + cols - 1) // cols
        _, axes = _pyplot().subplots(rows, cols, figsize=(4 * cols, 3 * rows), squeeze=False)
    flat = np.asarray(axes).reshape(-1)
    threshold = report.get("threshold")
    for ax, prof in zip(flat, profs):
        pts = [p for p in prof["points"] if p.get("delta_chi2") is not None]
        x = [p["value"] for p in pts]
        y = [p["delta_chi2"] for p in pts]
        ax.plot(x, y, "-", color="C0")
        done = [p.get("converged", True) for p in pts]
        for ok, label in ((True, "converged"), (False, "budget used (J an upper bound)")):
            sel = [k for k, d in enumerate(done) if d == ok]
            if sel:
                ax.plot([x[k] for k in sel], [y[k] for k in sel], "o", ms=4, color="C0",
                        markerfacecolor="C0" if ok else "white", label=label)
        lo, hi = prof.get("lo"), prof.get("hi")
        if lo is not None and hi is not None:
            ax.axvspan(lo["value"], hi["value"], color="C0", alpha=0.12, lw=0)
        if prof.get("best_value") is not None:
            ax.axvline(prof["best_value"], color="0.5", lw=0.8)
        if threshold is not None:
            ax.axhline(threshold, color="C3", lw=0.8, ls="--")
        if not all(done):
            ax.legend(loc="best", fontsize="small")
        ax.set_xlabel(prof["name"])
        ax.set_ylabel("Δχ²")
    for ax in flat[len(profs):]:
        ax.set_visible(False)
    return axes


def paving(result: Any, x: Optional[str] = None, y: Optional[str] = None, ax: Any = None) -> Any:
    """The boxes of an IdentifyResult projected on the plane of the free parameters ``x`` and
    ``y`` (the first two by default), coloured by status (undecided and feasible on top)."""
    from matplotlib.patches import Rectangle  # type: ignore

    free = list(result.free)
    if len(free) < 2 and (x is None or y is None):
        raise ValueError("paving: a 2-D projection needs two free parameters")
    x = x or free[0]
    y = y or (free[1] if free[0] != x else free[0])
    for name in (x, y):
        if name not in free:
            raise ValueError(f"paving: {name!r} is not free (free: {', '.join(free)})")
    i, j = free.index(x), free.index(y)
    ax = _axes(ax)
    lo, hi = np.asarray(result.lo, dtype=float), np.asarray(result.hi, dtype=float)
    for status in ("infeasible", "undecided", "feasible"):
        for k in (k for k, s in enumerate(result.status) if s == status):
            ax.add_patch(Rectangle((lo[k, i], lo[k, j]), hi[k, i] - lo[k, i], hi[k, j] - lo[k, j],
                                   facecolor=STATUS_COLOURS[status], edgecolor="none",
                                   alpha=0.8))
    box = result.box
    ax.set_xlim(*box[x])
    ax.set_ylim(*box[y])
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    handles = [Rectangle((0, 0), 1, 1, color=c) for c in STATUS_COLOURS.values()]
    ax.legend(handles, list(STATUS_COLOURS), loc="best", fontsize="small")
    return ax
