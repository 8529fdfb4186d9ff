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
    r = bwcl.laws(["flores", "carvalho-martins"], ("0.3", "0.9"), points=7)
    code, out, err = cli("laws", "--formulas", "flores,carvalho-martins", "--e-star", "0.3..0.9",
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
    r = bwcl.laws(["hunt-crossley", "lankarani-nikravesh", "gonthier", "hu-guo"], points=25)
    for f in r.formulas.values():
        for s_lo, s_hi, e_lo, e_hi in zip(f.sigma_lo, f.sigma_hi, f.e_lo, f.e_hi):
            sigma = 0.5 * (s_lo + s_hi)
            e = _cor(sigma)
            # the float root's own error is a few ulps; the enclosure is ≈ 1 ulp wide
            assert e_lo - 1e-14 <= e <= e_hi + 1e-14, (f.key, sigma, e, e_lo, e_hi)
            assert e_hi - e_lo < 1e-12


def test_bad_input():
    with pytest.raises(ValueError, match="--tol"):
        bwcl.laws(tol=0)
    with pytest.raises(ValueError, match="e-star"):
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
