"""bwcl.laws: the same proved numbers as `bwcl laws --format json`, the enclosures against SciPy's
root of the closed form, and bad input as ValueError / TypeError."""

import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import bwcl


def _cor(sigma):
    """The Hunt–Crossley CoR by SciPy: the root of G(σe) = G(−σ), G(u) = −u − ln(1 − u)."""
    g = lambda u: -u - math.log1p(-u)  # noqa: E731
    c = g(-sigma)
    return brentq(lambda e: g(sigma * e) - c, 0.0, min(1.0, 1.0 / sigma) * (1 - 1e-15),
                  xtol=1e-17, rtol=8.9e-16)


def test_laws_matches_the_program(cli):
    r = bwcl.laws(["flores", "carvalho-martins"], ("0.3", "0.5"), points=7)
    code, out, err = cli("laws", "--formulas", "flores,carvalho-martins", "--e-star", "0.3..0.5",
                         "--points", "7", "--format", "json")
    assert code == 0, err
    d = json.loads(out)
    assert list(r.formulas) == ["flores", "carvalho-martins"]
    for f in d["formulas"]:
        got = r.formulas[f["key"]]
        assert got.e_lo.tolist() == [float(p["e"][0]) for p in f["points"]]
        assert got.e_hi.tolist() == [float(p["e"][1]) for p in f["points"]]
        assert got.runs == [(float(s["lo"]), float(s["hi"]), s["verdict"]) for s in f["segments"]]
    # the exact damping gives its targets back
    cm = r.formulas["carvalho-martins"]
    assert np.all(cm.e_lo <= cm.e_star) and np.all(cm.e_star <= cm.e_hi)
    assert cm.within() and "LawsResult(2 formulas" in repr(r)


def test_enclosures_hold_scipys_root():
    # tol = 0.5: the pavings (what tol is for) settle at once; the points are the test
    r = bwcl.laws(["hunt-crossley", "lankarani-nikravesh", "gonthier", "hu-guo"], points=25,
                  tol=0.5)
    for f in r.formulas.values():
        for s_lo, s_hi, e_lo, e_hi in zip(f.sigma_lo, f.sigma_hi, f.e_lo, f.e_hi):
            sigma = 0.5 * (s_lo + s_hi)
            e = _cor(sigma)
            # the float root's own error is a few ulps; the enclosure is ≈ 1 ulp wide
            assert e_lo - 1e-14 <= e <= e_hi + 1e-14, (f.key, sigma, e, e_lo, e_hi)
            assert e_hi - e_lo < 1e-12


def test_bad_input():
    with pytest.raises(ValueError, match="tol"):
        bwcl.laws(tol=0)
    with pytest.raises(ValueError, match="e_star"):
        bwcl.laws(e_star=(0.9, 0.1))
    with pytest.raises(ValueError, match="formulas"):
        bwcl.laws("hertz")
    with pytest.raises(ValueError, match="points"):
        bwcl.laws(points=1)
    with pytest.raises(TypeError):
        bwcl.laws(e_star=(b"0.1", "0.9"))
    with pytest.raises(TypeError):
        bwcl.laws(points=2.5)


def test_classical_against_the_closed_form(cli):
    """Kelvin–Voigt: T_s = (π − φ)/ω, e = exp(−ζ T_s) (src/models/kelvin_voigt.rs); the proved
    bounds hold it and match the program's JSON; the float engine agrees to 1e-9."""
    z = 0.3
    w = math.sqrt(1 - z * z)
    ts = (math.pi - math.atan2(2 * z * w, 1 - 2 * z * z)) / w
    e = math.exp(-z * ts)
    r = bwcl.classical("kelvin-voigt", zeta="0.3", rigorous=True)
    assert r.proved and r.rigorous
    assert r.e_lo - 1e-15 <= e <= r.e_hi + 1e-15 and r.e_hi - r.e_lo < 1e-12
    assert r.ts_lo - 1e-15 <= ts <= r.ts_hi + 1e-15
    code, out, err = cli("classical", "--law", "kelvin-voigt", "--zeta", "0.3", "--rigorous",
                         "--format", "json")
    assert code == 0, err
    d = json.loads(out)
    assert [r.e_lo, r.e_hi] == [float(x) for x in d["e"]]
    f = bwcl.classical("kelvin-voigt", zeta=0.3)
    assert not f.rigorous and abs(f.e - e) < 1e-9 and abs(f.ts - ts) < 1e-9
    # Hunt–Crossley tuned by the exact formula gives its target back
    cm = bwcl.classical("hunt-crossley", formula="carvalho-martins", e_star="0.5", rigorous=True)
    assert cm.e_lo <= 0.5 <= cm.e_hi
    assert cm.params == {"n": "1.5", "formula": "carvalho-martins", "e_star": "0.5"}


def test_classical_bad_input():
    with pytest.raises(ValueError, match="zeta"):
        bwcl.classical("hertz", zeta=0.1)
    with pytest.raises(ValueError, match="sigma"):
        bwcl.classical("hunt-crossley")
    with pytest.raises(ValueError):
        bwcl.classical("coulomb")
    with pytest.raises(TypeError):
        bwcl.classical("hertz", n=b"1.5")


def _scipy_cor(rhs, force, y0):
    """e and T_s by SciPy's solve_ivp (DOP853, rtol 1e-12): the first time after the start
    where F ≤ 0 with V ≥ 0 (the crate's separation rule), located by an event on F."""
    from scipy.integrate import solve_ivp

    def sep(t, y):
        return force(y) if t > 1e-9 else 1.0
    sep.terminal = True
    sep.direction = -1
    r = solve_ivp(rhs, (0.0, 50.0), y0, method="DOP853", rtol=1e-12, atol=1e-14, events=sep)
    assert r.t_events[0].size == 1
    y = r.y_events[0][0]
    return y[-1], r.t_events[0][0]


def _hc(sigma, n):
    f = lambda y: -abs(y[0]) ** (n - 1) * y[0] - sigma * abs(y[0]) ** n * y[1]  # noqa: E731
    # separation at X = 0 (F = 0 there): the event on X crossing 0 from below
    return (lambda t, y: [y[1], f(y)]), (lambda y: -y[0]), [0.0, -1.0]


def test_each_law_agrees_with_scipy_solve_ivp():
    cases = {
        ("hooke", ()): _hc(0.0, 1.0),
        ("hertz", (("n", 1.5),)): _hc(0.0, 1.5),
        ("hunt-crossley", (("sigma", 0.4), ("n", 1.5))): _hc(0.4, 1.5),
        ("hunt-crossley", (("sigma", 1.5), ("n", 1.2))): _hc(1.5, 1.2),
    }
    z = 0.3
    cases[("kelvin-voigt", (("zeta", z),))] = (
        lambda t, y: [y[1], -y[0] - 2 * z * y[1]], lambda y: -y[0] - 2 * z * y[1], [0.0, -1.0])
    c = 2.0
    cases[("linear-maxwell", (("c", c),))] = (
        lambda t, y: [y[2], (y[0] - y[1]) / c, -(y[0] - y[1])], lambda y: -(y[0] - y[1]),
        [0.0, 0.0, -1.0])
    for (law, params), (rhs, force, y0) in cases.items():
        e, ts = _scipy_cor(rhs, force, y0)
        r = bwcl.classical(law, **dict(params))
        assert abs(r.e - e) < 1e-8 and abs(r.ts - ts) < 1e-8, (law, params, r.e, e, r.ts, ts)


def test_compare_and_identify_take_the_laws(tmp_path):
    """Hunt–Crossley data (σ_b = 0.37): compare ranks it first and its proved feasible set
    holds 0.37; constant-CoR laws are refuted with a certificate; identify takes a law."""
    v0 = np.linspace(0.2, 4.0, 8)
    e = np.array([bwcl.classical("hunt-crossley", sigma=0.37 * float(v), n=1.5).e for v in v0])
    rows = bwcl.compare(v0=v0, e=e, models=["hunt-crossley", "kelvin-voigt", "hertz"],
                        error=0.01)
    assert [r["model"] for r in rows][0] == "hunt-crossley"
    assert rows[0]["J"] < 1e-8
    kv = next(r for r in rows if r["model"] == "kelvin-voigt")
    assert kv["feasible"].startswith("empty") and kv["certificate"] and kv["refuted_everywhere"]
    r = bwcl.identify("hunt-crossley", v0=v0, e=e, error=0.01)
    (lo, hi), = r.hull.values()
    assert lo < 0.37 < hi and not r.empty
    r = bwcl.identify("kelvin-voigt", v0=v0, e=e, error=0.01)
    assert r.empty and r.certificate
    with pytest.raises(ValueError, match="models"):
        bwcl.compare(v0=v0, e=e, models="shc,coulomb")
    with pytest.raises(ValueError, match="no-tc|fix|Bouc"):
        bwcl.identify("hunt-crossley", v0=v0, e=e, error=0.01, fix={"kappa": 0.5})


def test_cor_of_a_law_in_si_units_agrees_with_solve_ivp():
    """bwcl.cor / cor_rigorous / trajectory with a law's physical parameters against SciPy on
    the SI equation m δ̈ = −k δ^n − χ δ^n δ̇ (δ ≥ 0 the indentation, δ̇(0) = v0), to the
    return δ = 0: t_s in seconds and e = −δ̇(t_s)/v0 (the scales are checked with them)."""
    from scipy.integrate import solve_ivp

    m, k, chi, n = 0.146, 1e9, 2e8, 1.5
    phys = {"m": m, "k": k, "chi": chi, "n": n}
    v0 = np.array([0.5, 1.0, 2.0])
    r = bwcl.cor("hunt-crossley", physical=phys, v0=v0)
    assert r.model == "hunt-crossley" and set(r.params) == {"sigma", "n"}
    np.testing.assert_allclose(r.params["sigma"], chi * v0 / k, rtol=1e-15)
    p = bwcl.cor_rigorous("hunt-crossley", physical=phys, v0=v0)
    assert p.proved.all() and p.params["sigma"].shape == (3, 2)
    for i, v in enumerate(v0):
        def rhs(t, y):
            d = max(y[0], 0.0)
            return [y[1], -(k * d**n + chi * d**n * y[1]) / m]

        back = lambda t, y: y[0]  # noqa: E731
        back.terminal, back.direction = True, -1
        t_c = (m * v**2 / k) ** (1 / (n + 1)) / v
        s = solve_ivp(rhs, (0, 10 * t_c), [0.0, v], method="DOP853", rtol=1e-12, atol=1e-20,
                      events=back, first_step=1e-4 * t_c, max_step=0.01 * t_c)
        t_s, e = s.t_events[0][0], -s.y_events[0][0][1] / v
        assert abs(r.e[i] - e) < 1e-8 and abs(r.ts_seconds[i] - t_s) < 1e-8 * t_s, (v, r.e[i], e)
        assert p.e[i, 0] <= r.e[i] + 1e-9 and r.e[i] - 1e-9 <= p.e[i, 1]
        assert p.ts_seconds[i, 0] - 1e-8 * t_s <= t_s <= p.ts_seconds[i, 1] + 1e-8 * t_s
    tr = bwcl.trajectory("hunt-crossley", physical=phys, v0=1.0, physical_units=True, points=50)
    assert tr.state_names == ("X", "V") and tr.units == "physical"
    assert abs(tr.t[-1] - r.ts_seconds[1]) < 1e-12 and abs(tr.v[-1] - r.e[1]) < 1e-9
    lm = bwcl.loop("linear-maxwell", nd={"c": 2}, rigorous=True, points=5)
    assert lm.x.shape == (5, 2)
    # the base family and the nondimensional set by name; Hooke takes none
    b = bwcl.cor("hunt-crossley", base={"sigma_b": 0.25}, v0=2.0)
    assert b.e[0] == bwcl.cor("hunt-crossley", nd="sigma=0.5").e[0]
    assert bwcl.cor("hooke", nd={}).e[0] == pytest.approx(1.0, abs=1e-9)
    with pytest.raises(ValueError, match="k = -1 must be > 0"):
        bwcl.cor("kelvin-voigt", physical={"m": 1, "k": -1, "c": 1}, v0=1)
    with pytest.raises(ValueError, match="fallback_bits is for the Bouc–Wen models"):
        bwcl.cor_rigorous("hooke", nd={}, fallback_bits=128)
    with pytest.raises(TypeError, match="by name"):
        bwcl.cor("kelvin-voigt", nd=[0.3])


def _printed_bounds(text):
    """Every [lo, hi] pair of decimals in a repr."""
    import re

    return [(a, b) for a, b in re.findall(r"\[([-0-9.e]+), ([-0-9.e]+)\]", text)]


def test_proved_reprs_print_bounds_outward():
    # a decimal printed for a bound lies on its outer side of the double (Python's shortest
    # round trip, or numpy's 8 digits, may lie inside: found by a probe, e_lo of this case)
    from decimal import Decimal

    r = bwcl.classical("hunt-crossley", sigma=0.3, rigorous=True)
    text = repr(r)
    pairs = _printed_bounds(text)
    assert len(pairs) == 2, text
    for (lo, hi), (a, b) in zip(pairs, [(r.ts_lo, r.ts_hi), (r.e_lo, r.e_hi)]):
        assert Decimal(lo) <= Decimal(a) and Decimal(hi) >= Decimal(b), (text, a, b)
    # the probe's case: the shortest round trip of e_lo lies above it
    assert Decimal(repr(r.e_lo)) > Decimal(r.e_lo) or Decimal(repr(r.e_hi)) < Decimal(r.e_hi)
    f = bwcl.laws("flores", e_star=("0.5", "0.6"), points=3).formulas["flores"]
    text = repr(f)
    pairs = _printed_bounds(text)
    assert len(pairs) == 9, text
    ends = [(f.sigma_lo, f.sigma_hi), (f.e_lo, f.e_hi), (f.error_lo, f.error_hi)]
    for k, (lo, hi) in enumerate(pairs):
        a, b = ends[k // 3][0][k % 3], ends[k // 3][1][k % 3]
        assert Decimal(lo) <= Decimal(a) and Decimal(hi) >= Decimal(b), (text, a, b)
    mx = text.split("max_abs_error ≤ ")[1].split(",")[0]
    assert Decimal(mx) >= Decimal(f.max_abs_error), text


def test_classical_linear_maxwell_below_a_half_never_separates():
    """c ≤ 1/2: the closed form says the law never separates (T_s = +∞, e = 0), on both
    engines; above 1/2 it separates."""
    for rigorous in (False, True):
        r = bwcl.classical("linear-maxwell", c="0.4", rigorous=rigorous)
        assert r.proved and not r.separated, r
        assert r.ts_lo == math.inf and r.e_lo == r.e_hi == 0.0
        assert "never separates" in r.reason and "never separates" in repr(r)
    s = bwcl.classical("linear-maxwell", c="0.6", rigorous=True)
    assert s.separated and 0 < s.e_lo <= s.e_hi < 1


def test_cor_warns_where_e_is_below_atol():
    """A float separation with e below the absolute tolerance lies at the run's rounding level
    (linear Maxwell, c = 1/2 + 2⁻⁵³: T ≈ 39, e ≈ 1e-14; its T_s ≈ 1.5e8): a RuntimeWarning, as
    the CLI's note; none where e is resolved."""
    with pytest.warns(RuntimeWarning, match="below atol"):
        r = bwcl.cor("linear-maxwell", nd={"c": "0.50000000000000011"})
    assert r.separated.all() and abs(r.e[0]) < 1e-12
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        bwcl.cor("linear-maxwell", nd={"c": "0.6"})
        bwcl.cor("linear-maxwell", nd={"c": "0.4"})


def test_a_law_that_never_separates_in_cor_rigorous_and_trajectory():
    """c ≤ 1/2: cor_rigorous proves no separation with e = 0 (the paper's convention for
    T_s = +∞, as cor and classical); the proved trajectory runs to t_end."""
    r = bwcl.cor_rigorous("linear-maxwell", nd={"c": "0.4"})
    assert r.proved.all() and not r.separated.any()
    assert (r.e == 0).all()
    t = bwcl.trajectory("linear-maxwell", nd={"c": "0.3"}, rigorous=True, t_end=10, points=3)
    assert len(t.t) == 3 and t.t[-1] == 10


def test_fit_of_a_classical_law_points_to_compare():
    """bwcl.fit fits the Bouc–Wen models; for a law it names bwcl.compare (the CLI's message,
    rewritten for Python, read `bwcl fit model kelvin-voigt`)."""
    with pytest.raises(ValueError, match=r'bwcl\.compare\(data, models="kelvin-voigt"\)'):
        bwcl.fit("kelvin-voigt", v0=[1.0, 2.0, 3.0], e=[0.5, 0.5, 0.5])
