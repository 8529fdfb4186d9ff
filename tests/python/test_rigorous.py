"""Proved enclosures: they contain the f64 values (within the f64 engine's own error at the
paper's tolerances; strictly for ranges), their decimals are outward, failures are reported
per case or raised."""

import pickle
from fractions import Fraction

import numpy as np
import pytest

import bwcl
from conftest import DSS


def dist(enc, x):
    """How far x lies outside [lo, hi] (≤ 0 inside)."""
    return np.maximum(enc[:, 0] - x, x - enc[:, 1])


@pytest.mark.parametrize("name", list(bwcl.TABLE1))
def test_point_enclosures_hold_the_f64_values(name):
    """The f64 engine is off the proved value by 2e-12 … 2e-9 at the paper's settings
    (README): the proved enclosures (widths ~1e-13) hold its values to that error, and to
    ~1e-12 at tight tolerances."""
    model, base = bwcl.TABLE1[name]
    v = [0.1, 1, 5]
    q = bwcl.cor_rigorous(model, base=base, v0=v)
    assert q.proved.all() and (q.width_e < 1e-11).all()
    f = bwcl.cor(model, base=base, v0=v)
    assert (dist(q.e, f.e) < 5e-9).all() and (dist(q.ts, f.ts) < 5e-9).all()
    f = bwcl.cor(model, base=base, v0=v, rtol=1e-13, atol=1e-15)
    assert (dist(q.e, f.e) < 5e-12).all() and (dist(q.ts, f.ts) < 5e-12).all()


def test_range_enclosures_contain_f64_values_strictly():
    """A range of v0 and of κ: the f64 CoR at points inside lies inside the enclosure."""
    q = bwcl.cor_rigorous("shc", base=DSS, v0=[(0.99, 1.01)])
    assert q.proved[0]
    pts = np.linspace(0.99, 1.01, 9)
    f = bwcl.cor("shc", base=DSS, v0=pts)
    assert (q.e[0, 0] < f.e).all() and (f.e < q.e[0, 1]).all()
    assert (q.ts[0, 0] < f.ts).all() and (f.ts < q.ts[0, 1]).all()
    base = [1.43, -1.42, ("0.6317", "0.6323"), 0.00715, 1.31, 1.27]
    q = bwcl.cor_rigorous("shc", base=base, v0=1)
    for kappa in (0.6317, 0.632, 0.6323):
        f = bwcl.cor("shc", base=[1.43, -1.42, kappa, 0.00715, 1.31, 1.27], v0=1)
        assert q.e[0, 0] < f.e[0] < q.e[0, 1]


def test_decimals_are_outward_and_read_back():
    q = bwcl.cor_rigorous("shc", base=DSS, v0=[0.5, "1", 2])
    for i in range(len(q)):
        for pair, enc in ((q.e_text[i], q.e[i]), (q.ts_text[i], q.ts[i])):
            lo, hi = pair
            assert Fraction(lo) <= Fraction(enc[0]) and Fraction(hi) >= Fraction(enc[1])
            assert float(lo) == enc[0] and float(hi) == enc[1]
        assert Fraction(q.width_e_text[i]) >= Fraction(q.e[i, 1]) - Fraction(q.e[i, 0])


def test_a_range_of_v0_is_printed_inward():
    """The result holds for every speed of a range: its decimals (v0_text, to_pandas) lie
    inside the doubles they read back to; the enclosures' outside."""
    pytest.importorskip("pandas")
    q = bwcl.cor_rigorous("shc", base=DSS, v0=[(0.3, 0.31)])
    assert q.proved[0]
    lo, hi = q.v0_text[0]
    assert float(lo) == q.v0[0, 0] and float(hi) == q.v0[0, 1]
    assert Fraction(lo) >= Fraction(q.v0[0, 0]) and Fraction(hi) <= Fraction(q.v0[0, 1])
    assert Fraction(hi) != Fraction(q.v0[0, 1])  # (0.31000000000000005: rounded down)
    df = q.to_pandas()
    assert (df.v0_lo[0], df.v0_hi[0]) == (lo, hi)
    assert Fraction(df.e_lo[0]) <= Fraction(q.e[0, 0])


def test_digits_report_no_separation_as_proved():
    """``digits``: no separation before the horizon is proved there too (as without digits)."""
    r = bwcl.cor_rigorous("maxwell", nd=[1, 0, 0.5, 100, 1.5, 2], digits=20, horizon=5.0)
    assert r.status == ("proved",) and r.proved.all() and not r.separated.any()
    assert "no separation before the horizon T = 5" in r.reason[0]


def test_numbers_strings_and_doubles():
    """A float is enclosed as its repr: the same enclosure as the string; the enclosure of
    the decimal holds the double too (the f64 case at that double is inside, to f64 error)."""
    a = bwcl.cor_rigorous("shc", base=DSS, v0=[0.3])
    b = bwcl.cor_rigorous("shc", base=DSS, v0=["0.3"])
    assert np.array_equal(a.e, b.e) and np.array_equal(a.v0, b.v0)
    assert a.v0[0, 0] <= 0.3 <= a.v0[0, 1] and a.v0[0, 0] < a.v0[0, 1]


def test_no_separation_is_proved_and_not_proved_is_raised():
    # separation cannot happen before T = 1: that is proved (T_s > 1, e = 0 by the paper's
    # convention), with no enclosure of e and the statement in ``reason``
    r = bwcl.cor_rigorous("shc", base=DSS, v0=[1, 2], horizon=1.0)
    assert r.status == ("proved", "proved") and r.proved.all() and not r.separated.any()
    assert all("no separation before the horizon" in s for s in r.reason)
    assert np.isnan(r.e).all() and r.e_text == (None, None)
    # ... and not raised as a failure
    bwcl.cor_rigorous("shc", base=DSS, v0=[1], horizon=1.0, raise_on_failure=True)
    # the Hunt–Crossley limit at σ = 24 without the precision fallback is not proved, with
    # its reason, and raised on request
    nd = ["1e-300", 0, 0.5, 24, 1.5, 1.5]
    q = bwcl.cor_rigorous("shc", nd=nd, fallback_bits=0)
    assert q.status == ("not proved",) and "undecidable" in q.reason[0]
    with pytest.raises(bwcl.NotProvedError) as ex:
        bwcl.cor_rigorous("shc", nd=nd, fallback_bits=0, raise_on_failure=True)
    err = pickle.loads(pickle.dumps(ex.value))
    assert isinstance(err, bwcl.NotProvedError) and str(err) == str(ex.value)
    assert err.result.status == ("not proved",)
    ok = bwcl.cor_rigorous("shc", base=DSS, v0=[1], raise_on_failure=True)
    assert ok.status == ("proved",)


def test_the_precision_that_decided_is_reported():
    """The Hunt–Crossley limit at σ = 24 is undecidable with f64 intervals and proved by the
    precision fallback at 128 bits (tests/fallback.rs checks its e against the closed form):
    ``bits`` names the precision and ``fallback`` the runs; with the fallback off it is not
    proved; an ordinary case is decided at 53 bits with no fallback run."""
    nd = ["1e-300", 0, 0.5, 24, 1.5, 1.5]
    q = bwcl.cor_rigorous("shc", nd=nd, fallback_bits=128)
    assert q.proved[0] and q.bits == (128,)
    (run,) = q.fallback[0]
    assert isinstance(run, bwcl.FallbackRun) and run.bits == 128 and run.proved
    assert run.reason is None and run.seconds > 0
    assert 0.04166 < q.e[0, 0] <= q.e[0, 1] < 0.04167
    off = bwcl.cor_rigorous("shc", nd=nd, fallback_bits=0)
    assert not off.proved[0] and off.bits == (53,) and off.fallback == (None,)
    assert "undecidable" in off.reason[0]
    plain = bwcl.cor_rigorous("shc", base=DSS, v0=[0.5, 1])
    assert plain.proved.all() and plain.bits == (53, 53) and plain.fallback == (None, None)
    assert pickle.loads(pickle.dumps(q)).fallback == q.fallback


def test_digits_match_the_cli_and_the_reference_table(cli):
    """digits=30: the same decimals as `bwcl cor --rigorous --digits 30 --format json` (every
    digit the width allows, rounded outward), the doubles outward of them, ≤ 1e-30 wide, the
    f64-interval enclosure around them, and the values of paper_repro's 30-digit table."""
    from conftest import ROOT

    q = bwcl.cor_rigorous("shc", base=DSS, v0=[1, "0.5"], digits=30)
    assert q.proved.all() and q.bits == (128, 128) and q.order == 30
    code, out, err = cli(
        "cor", "--model", "shc", "--base", DSS, "--v0", "1,0.5", "--rigorous",
        "--digits", "30", "--format", "json",
    )
    assert code == 0, err
    import json

    rows = json.loads(out, parse_float=str)
    rows = rows["cases"] if isinstance(rows, dict) else rows
    for i, row in enumerate(rows):
        assert tuple(row["ts"]) == q.ts_text[i] and tuple(row["e"]) == q.e_text[i]
    f64 = bwcl.cor_rigorous("shc", base=DSS, v0=[1, 0.5])
    for i in range(len(q)):
        for (lo, hi), enc, wide in ((q.e_text[i], q.e[i], f64.e[i]), (q.ts_text[i], q.ts[i], f64.ts[i])):
            assert Fraction(enc[0]) <= Fraction(lo) and Fraction(hi) <= Fraction(enc[1])
            assert Fraction(hi) - Fraction(lo) <= Fraction(1, 10**30)
            mid = (Fraction(lo) + Fraction(hi)) / 2
            assert Fraction(wide[0]) <= mid <= Fraction(wide[1])
        # the widths are the exact enclosures' (rounded up), not the printed ends'
        assert Fraction(q.width_e_text[i]) <= Fraction(1, 10**30) and q.width_e[i] <= 1e-30
        assert Fraction(q.width_ts_text[i]) <= Fraction(1, 10**30) and q.width_ts[i] <= 1e-30
    table = (ROOT / "paper_repro" / "data" / "reference_30_digits.csv").read_text()
    for i, v in enumerate(["1", "0.5"]):
        line = next(l for l in table.splitlines() if l.startswith(f'shc,DSS,"{DSS}",{v},'))
        cells = line.split('"')[2].split(",")
        assert (cells[2], cells[3]) == q.ts_text[i] and (cells[4], cells[5]) == q.e_text[i]


def test_digits_refuse_ranges_and_bad_values():
    with pytest.raises(ValueError, match="digits"):
        bwcl.cor_rigorous("shc", base=DSS, v0=[(0.9, 1.1)], digits=30)
    with pytest.raises(ValueError, match="digits"):
        bwcl.cor_rigorous("shc", base=DSS, v0=1, digits=0)
    with pytest.raises(ValueError, match="digits"):
        bwcl.cor_rigorous("shc", base=DSS, v0=1, digits=101)
