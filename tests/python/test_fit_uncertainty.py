"""Issue #31 from Python: bwcl.fit's minima and uncertainty fields and bwcl.profile equal the
CLI's JSON; bad options raise ValueError with the CLI's line."""

import warnings

import pytest

import bwcl

from conftest import DATA

FIX = {"B_b": 1.43, "Gamma_b": -1.42, "n": 1.31, "p": 1.27}
FIX_TEXT = "--fix=B_b=1.43,Gamma_b=-1.42,n=1.31,p=1.27"


def test_fit_minima_and_uncertainty_equal_cli(cli_json):
    f = bwcl.fit("shc", DATA, starts=2, max_iter=40, seed=3, fix=FIX,
                 bounds={"sigma_b": (0.001, 0.1)}, uncertainty=True, jacobian="central")
    j = cli_json("fit", "--model=shc", f"--data={DATA}", "--starts=2", "--max-iter=40",
                 "--seed=3", FIX_TEXT, "--bounds=sigma_b=0.001..0.1", "--uncertainty",
                 "--jacobian=central")
    assert f.free == ("kappa", "sigma_b") == tuple(j["free"])
    # the fixture keeps every JSON number as its text
    assert [m["J"] for m in f.minima] == [float(m["J"]) for m in j["minima"]]
    assert sum(m["basin_size"] for m in f.minima) == 2
    assert f.uncertainty["std_errors"] == [float(x) for x in j["uncertainty"]["std_errors"]]
    assert f.uncertainty["names"] == ["kappa", "sigma_b"]
    assert f.chi2 == pytest.approx(f.J ** 2, rel=1e-12)
    assert f.base[0] == 1.43 and 0.001 <= f.base[3] <= 0.1


def test_profile_equals_cli(cli_json):
    p = bwcl.profile("shc", DATA, param="kappa", points=3, starts=1, max_iter=40, fix=FIX)
    j = cli_json("profile", "--model=shc", f"--data={DATA}", "--param=kappa", "--points=3",
                 "--starts=1", "--max-iter=40", FIX_TEXT)
    assert [q["J"] for q in p["profiles"][0]["points"]] == [
        float(q["J"]) for q in j["profiles"][0]["points"]
    ]
    assert p["profiles"][0]["name"] == "kappa" and len(p["profiles"]) == 1
    assert p["threshold"] == pytest.approx(3.841458820694124)


def test_a_profile_that_used_its_budget_says_so():
    """Grid points whose re-optimization stopped at max_iter are named in a RuntimeWarning (the
    notebook once showed such a profile as an interval); a profile with budget enough is
    silent."""
    with pytest.warns(RuntimeWarning, match=r"of kappa used their whole budget \(max_iter=2\)"):
        p = bwcl.profile("shc", DATA, param="kappa", points=3, starts=1, max_iter=2, fix=FIX)
    assert not all(q["converged"] for q in p["profiles"][0]["points"])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        q = bwcl.profile("shc", DATA, param="kappa", points=3, starts=1, max_iter=300, fix=FIX)
    assert all(x["converged"] for x in q["profiles"][0]["points"])


def test_bad_search_options_raise():
    with pytest.raises(ValueError, match="error"):
        bwcl.fit("shc", DATA, starts=1, error=0)
    with pytest.raises(ValueError, match="zeta"):
        bwcl.fit("shc", DATA, starts=1, fix={"zeta": 1})
    with pytest.raises(ValueError, match="fixed"):
        bwcl.profile("shc", DATA, param="kappa", fix={"kappa": 0.6})
