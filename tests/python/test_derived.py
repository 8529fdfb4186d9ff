"""Derived outputs of a collision (issue #34, item 4): the peak contact force, the maximum
indentation and the kinetic energy lost, float and proved, nondimensional and in SI — checked
against closed forms (Hooke, Hertz) at 50 digits, compared as exact fractions."""

from decimal import Decimal, localcontext
from fractions import Fraction

import numpy as np
import pytest

import bwcl
from conftest import BASEBALL

DSS = bwcl.TABLE1["SHC DSS"].base


def hertz_maxima(n):
    """δ_max = ((n+1)/2)^(1/(n+1)) and F_max = δ_max^n (V²/2 + |X|^(n+1)/(n+1) is conserved)
    to 50 digits."""
    with localcontext() as ctx:
        ctx.prec = 50
        n = Decimal(n)
        x = ((n + 1) / 2) ** (1 / (n + 1))
        return x, x ** n


def holds(bounds, text, exact):
    """The float bounds and the outward decimals both hold `exact` (a Decimal), as fractions,
    with 1e-45 to spare (the reference is good to ~1e-49)."""
    ref, margin = Fraction(exact), Fraction(1, 10 ** 45)
    lo, hi = bounds
    assert Fraction(lo) <= ref - margin and ref + margin <= Fraction(hi), (bounds, exact)
    assert Fraction(Decimal(text[0])) <= Fraction(lo) and Fraction(hi) <= Fraction(Decimal(text[1]))


@pytest.mark.parametrize("n", ["1.5", "2.5"])
def test_hertz_maxima_are_proved_around_the_closed_form(n):
    r = bwcl.cor_rigorous("hertz", nd={"n": n}, derived=True)
    x, f = hertz_maxima(n)
    holds(r.max_indentation[0], r.derived_text[0]["max_indentation"], x)
    holds(r.peak_force[0], r.derived_text[0]["peak_force"], f)
    for name in ("max_indentation", "peak_force"):
        lo, hi = getattr(r, name)[0]
        assert hi - lo < 1e-13, (name, lo, hi)
    lo, hi = r.energy_lost[0]
    assert lo <= 0 <= hi and hi - lo < 1e-12
    assert r.derived_reason == (None,)


def test_hooke_in_si_float_and_proved():
    # m = 2 kg, k = 8 N/m, v0 = 3 m/s: ω = 2/s, δ_max = v0/ω = 1.5 m, F_max = k δ_max = 12 N
    phys = {"m": 2, "k": 8}
    r = bwcl.cor("hooke", physical=phys, v0=3, derived=True)
    assert abs(r.peak_force_newtons[0] - 12) < 1e-8
    assert abs(r.max_indentation_m[0] - 1.5) < 1e-9
    assert abs(r.energy_lost_joules[0]) < 1e-7
    p = bwcl.cor_rigorous("hooke", physical=phys, v0=3, derived=True)
    for name, exact in (("peak_force_newtons", 12), ("max_indentation_m", "1.5"),
                        ("energy_lost_joules", 0)):
        holds(getattr(p, name)[0], p.derived_text[0][name], Decimal(exact))


def test_baseball_energy_is_half_m_v0_squared_times_one_minus_e_squared():
    r = bwcl.cor_rigorous("shc", physical=BASEBALL, v0=[2.15, 30], derived=True)
    assert r.proved.all()
    m = Fraction(Decimal(str(BASEBALL["m"])))
    for i, v0 in enumerate((Decimal("2.15"), Decimal(30))):
        elo, ehi = (Fraction(x) for x in r.e[i])
        jlo, jhi = (Fraction(x) for x in r.energy_lost_joules[i])
        # ½ m v0² (1 − e²) is decreasing in e: its value at e's ends lies inside the enclosure
        assert jlo <= m * Fraction(v0) ** 2 * (1 - ehi ** 2) / 2
        assert m * Fraction(v0) ** 2 * (1 - elo ** 2) / 2 <= jhi
        for name in ("peak_force_newtons", "max_indentation_m"):
            lo, hi = getattr(r, name)[i]
            assert 0 < lo <= hi and hi - lo < 1e-10 * hi, (name, lo, hi)
    # the float engine agrees to its tolerance
    f = bwcl.cor("shc", physical=BASEBALL, v0=[2.15, 30], derived=True)
    for name in bwcl.DERIVED:
        mid = getattr(r, name).mean(axis=1)
        assert np.allclose(getattr(f, name), mid, rtol=1e-8, atol=1e-12), name


def test_sets_ranges_frames_and_bad_switches():
    sets = np.tile(np.array(DSS), (2, 1))
    sets[1, 2] = 0.5
    r = bwcl.cor_rigorous("shc", base=sets, v0=[1, 2], derived=True)
    assert r.peak_force.shape == (2, 2, 2) and r.proved.all()
    one = bwcl.cor_rigorous("shc", base=sets[1], v0=[1, 2], derived=True)
    assert np.array_equal(r.peak_force[1], one.peak_force)
    f = bwcl.cor("shc", base=sets, v0=[1, 2], derived=True)
    assert f.max_indentation.shape == (2, 2) and f.peak_force_newtons is None
    # a range is proved, its derived outputs are not computed, and the reason says so
    g = bwcl.cor_rigorous("shc", base=DSS, v0=[(1, 1.01)], derived=True)
    assert g.proved[0] and np.isnan(g.peak_force[0]).all()
    assert "point cases" in g.derived_reason[0]
    df = bwcl.cor_rigorous("shc", base=DSS, v0=[1], derived=True).to_pandas()
    assert {"peak_force_lo", "peak_force_hi", "energy_lost_lo"} <= set(df.columns)
    assert "peak_force" in bwcl.cor("shc", base=DSS, v0=1, derived=True).to_pandas().columns
    with pytest.raises(TypeError, match="derived must be True or False"):
        bwcl.cor("shc", base=DSS, v0=1, derived=1)
    with pytest.raises(ValueError, match="not with digits"):
        bwcl.cor_rigorous("shc", base=DSS, v0=1, digits=20, derived=True)
    # without derived=True, no fields
    assert bwcl.cor("shc", base=DSS, v0=1).peak_force is None
