"""Results as tables and plots (issue #34, item 5): short reprs, ``to_pandas()`` whose printed
bounds are bounds, TABLE1 as numbers, and the ``bwcl.plot`` helpers."""

from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest

import bwcl
from bwcl._frames import outward

DSS = bwcl.TABLE1["SHC DSS"].base


def test_table1_numbers_are_the_printed_rows():
    texts = {
        "SHC DSS": "1.43,-1.42,0.632,0.00715,1.31,1.27",
        "SHC DSA": "0.63,-0.611,0.188,0.00594,1,2.02",
        "Maxwell DSS": "0.655,-0.64,0.519,0.0118,1.94,2.28",
        "Maxwell DSA": "0.44,-0.418,0.113,0.00785,1.27,3.14",
    }
    assert set(bwcl.TABLE1) == set(texts)
    for name, text in texts.items():
        model, base = bwcl.TABLE1[name]
        assert all(isinstance(x, float) for x in base)
        assert bwcl.TABLE1[name].text == text
        assert base == tuple(float(x) for x in text.split(","))
        assert set(bwcl.TABLE1[name].named) == {"B_b", "Gamma_b", "kappa", "sigma_b", "n", "p"}
    # numbers and text give the same proved enclosure (a float is enclosed as its repr, the
    # decimal as printed)
    a = bwcl.cor_rigorous("shc", base=DSS, v0=1)
    b = bwcl.cor_rigorous("shc", base=bwcl.TABLE1["SHC DSS"].text, v0=1)
    assert np.array_equal(a.e, b.e)


def test_reprs_are_short():
    r = bwcl.cor("shc", base=DSS, v0=np.linspace(0.1, 5, 10_000))
    text = repr(r)
    assert len(text) < 250 and "array" not in text and "10000 cases" in text
    q = bwcl.cor_rigorous("shc", base=DSS, v0=[1, 2])
    assert "2 proved" in repr(q) and len(repr(q)) < 250
    one = bwcl.cor_rigorous("shc", base=DSS, v0=1)
    lo, hi = one.e_text[0]
    assert f"e ∈ [{lo}, {hi}]" in repr(one)
    t = bwcl.trajectory("shc", base=DSS, v0=1, points=5000)
    assert len(repr(t)) < 200 and "5000 samples" in repr(t)


def test_outward_decimals_are_bounds_and_read_back():
    rng = np.random.default_rng(3)
    xs = np.concatenate([rng.uniform(-1, 1, 2000) * 10.0 ** rng.integers(-20, 20, 2000),
                         [0.1, 0.3, 1 / 3, 5e-324, 1e300]])
    for x in xs:
        x = float(x)
        lo, hi = outward(x, False), outward(x, True)
        assert Fraction(Decimal(lo)) <= Fraction(x) <= Fraction(Decimal(hi))
        assert float(lo) == x == float(hi)
        for d in (1, 4, 8):
            assert Fraction(Decimal(outward(x, False, d))) <= Fraction(x)
            assert Fraction(x) <= Fraction(Decimal(outward(x, True, d)))
    # a negative control: round-to-nearest at 4 digits is not a lower bound for 0.86096
    assert Decimal(f"{0.86096:.4g}") > Decimal(0.86096)
    assert Decimal(outward(0.86096, False, 4)) <= Decimal(0.86096)


def test_outward_agrees_with_the_engine_texts():
    q = bwcl.cor_rigorous("shc", base=DSS, v0=[0.3, 1, 3])
    for i in range(3):
        lo, hi = q.e_text[i]
        assert Decimal(outward(q.e[i, 0], False)) == Decimal(lo)
        assert Decimal(outward(q.e[i, 1], True)) == Decimal(hi)


pd = pytest.importorskip("pandas")


def test_to_pandas_float_and_grid():
    sets = np.tile(np.array(DSS), (3, 1))
    sets[:, 2] = [0.5, 0.6, 0.7]
    r = bwcl.cor("shc", base=sets, v0=[0.5, 1.0])
    df = r.to_pandas()
    assert len(df) == 6 and list(df["set"]) == [0, 0, 1, 1, 2, 2]
    assert list(df["speed"]) == [0, 1] * 3
    assert np.array_equal(df["e"].to_numpy(), r.e.reshape(-1))
    assert np.array_equal(df["kappa"].to_numpy(), r.params[:, :, 2].reshape(-1))
    assert df["error"].isna().all()


def test_rigorous_frame_prints_bounds():
    q = bwcl.cor_rigorous("shc", base=DSS, v0=[0.5, 1.0, 2.0])
    df = q.to_pandas()
    for i in range(3):
        lo, hi = df["e_lo"][i], df["e_hi"][i]
        assert isinstance(lo, str) and float(lo) == q.e[i, 0] and float(hi) == q.e[i, 1]
        assert Fraction(Decimal(lo)) <= Fraction(q.e[i, 0])
        assert Fraction(q.e[i, 1]) <= Fraction(Decimal(hi))
        assert Fraction(Decimal(df["width_e"][i])) >= Fraction(q.e[i, 1]) - Fraction(q.e[i, 0])
    # the printed frame shows every bound as its outward decimal
    text = df.to_string()
    for i in range(3):
        assert df["e_lo"][i] in text and df["e_hi"][i] in text
    f = q.to_pandas(floats=True)
    assert np.array_equal(f[["e_lo", "e_hi"]].to_numpy(), q.e)
    assert (df["status"] == "proved").all()


def test_fit_and_trajectory_frames():
    from conftest import DATA

    fit = bwcl.fit("shc", DATA, starts=2, max_iter=30, seed=3)
    df = fit.to_pandas()
    assert np.allclose(df["residual"], df["e_data"] - df["e_model"])
    mf = fit.minima_frame()
    assert len(mf) == len(fit.minima) and "kappa" in mf.columns
    assert "FitResult" in repr(fit) and len(repr(fit)) < 400
    t = bwcl.trajectory("shc", base=DSS, v0=1, points=20, rigorous=True)
    td = t.to_pandas()
    assert len(td) == 20 and {"X_lo", "X_hi", "F_lo", "F_hi"} <= set(td.columns)
    assert all(float(a) <= float(b) for a, b in zip(td["X_lo"], td["X_hi"]))


def test_plots(tmp_path):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    f = bwcl.cor("shc", base=DSS, v0=np.linspace(0.2, 3, 30))
    q = bwcl.cor_rigorous("shc", base=DSS, v0=np.linspace(0.2, 3, 8))
    ax = bwcl.plot.cor_curve(f, band=q)
    # the curve and the proved speeds as markers: nothing filled between proved speeds
    assert len(ax.lines) == 2 and len(ax.collections) == 0
    assert len(ax.lines[1].get_xdata()) == 8
    ax.figure.savefig(tmp_path / "cor.png")
    b = bwcl.band("shc", base=DSS, v0=(0.9, 1.0), thickness=1e-3)
    ax = bwcl.plot.cor_curve(band=b)
    assert len(ax.collections) == len(b)
    ax = bwcl.plot.loop(bwcl.loop("shc", base=DSS, v0=1, points=50))
    assert len(ax.lines) == 1
    ax = bwcl.plot.trajectory(bwcl.trajectory("shc", base=DSS, v0=1, points=50), states=["X", "V"])
    assert len(ax.lines) == 2
    with pytest.raises(ValueError, match="no state"):
        bwcl.plot.trajectory(bwcl.trajectory("shc", base=DSS, v0=1, points=5), states=["Q"])
    from conftest import DATA

    axes = bwcl.plot.residuals(bwcl.cost("shc", DATA, base=DSS))
    assert len(axes) == 2
    with pytest.raises(ValueError):
        bwcl.plot.cor_curve()
    plt.close("all")


def test_profile_plot_marks_the_points_that_used_their_budget():
    """A profile point whose re-optimization used its whole budget is drawn hollow (its J only
    bounds the profile from above), as the CLI's SVG does; the interval is shaded and the best
    value marked."""
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pts = [{"value": v, "J": 0.02, "delta_chi2": d, "converged": c}
           for v, d, c in [(0.5, 6.0, True), (0.6, 0.0, True), (0.7, 2.0, False), (0.8, 9.0, True)]]
    report = {"threshold": 3.84, "profiles": [{
        "name": "kappa", "best_value": 0.6, "points": pts,
        "lo": {"value": 0.52, "open": False}, "hi": {"value": 0.75, "open": False}}]}
    (ax,) = bwcl.plot.profiles(report).reshape(-1)
    marks = {ln.get_label(): ln for ln in ax.lines if ln.get_marker() == "o"}
    hollow = marks["budget used (J an upper bound)"]
    assert list(hollow.get_xdata()) == [0.7]
    assert matplotlib.colors.to_rgba(hollow.get_markerfacecolor()) == (1.0, 1.0, 1.0, 1.0)
    assert list(marks["converged"].get_xdata()) == [0.5, 0.6, 0.8]
    assert len(ax.patches) == 1  # the interval
    plt.close("all")


def _bounds_in(text):
    import re

    return [Fraction(Decimal(x)) for x in re.findall(r"-?\d+\.\d+(?:e-?\d+)?", text)]


def test_reprs_of_proofs_print_bounds():
    """Review of #34: the sensitivities, the band's range and the monotone verdict print the
    bounds outward (or as the report's inward range), never a float's nearest repr."""
    q = bwcl.cor_rigorous("shc", base=DSS, v0=[1.0], sensitivities=True)
    for name, s in q.sensitivities[0].items():
        lo_dts, hi_dts, lo_de, hi_de = _bounds_in(repr(s))[:4]
        assert lo_dts <= Fraction(s.dts[0]) and Fraction(s.dts[1]) <= hi_dts, (name, repr(s))
        assert lo_de <= Fraction(s.de[0]) and Fraction(s.de[1]) <= hi_de, (name, repr(s))
    b = bwcl.band("shc", base=DSS, v0=(0.9, 1.0), thickness=1e-4)
    assert f"v0 ∈ [{b.v0_text[0]}, {b.v0_text[1]}]" in repr(b)
    # the range printed inward: inside the doubles the band was proved between
    assert Fraction(Decimal(b.v0_text[0])) >= Fraction(b.v0_range[0])
    assert Fraction(Decimal(b.v0_text[1])) <= Fraction(b.v0_range[1])
    m = bwcl.prove_monotone("shc", base=DSS, v0=(0.5, 0.52))
    assert f"de/dv0 ≤ {m.report['max_slope']} < 0" in repr(m)
    assert Fraction(Decimal(m.report["max_slope"])) >= Fraction(m.max_slope)
