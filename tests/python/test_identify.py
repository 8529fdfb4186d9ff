"""bwcl.identify: the same paving as `bwcl identify --format json`, bad input as ValueError,
arrays as data, and the Dask split-and-merge against the whole paving."""

import json

import numpy as np
import pytest

import bwcl
from conftest import DSS

V0 = [0.5, 2.5]
E = [0.9054, 0.7731]
BOX = {"sigma_b": (0.003, 0.02)}


def _write(tmp_path):
    p = tmp_path / "d.csv"
    p.write_text("v0,e\n" + "".join(f"{v!r},{e!r}\n" for v, e in zip(V0, E)))
    return p


def test_identify_matches_the_program(tmp_path, cli):
    p = _write(tmp_path)
    r = bwcl.identify("shc", p, bounds=BOX, error=0.01, base=DSS, resolution=16)
    code, out, err = cli("identify", "--model", "shc", "--data", str(p), "--error", "0.01",
                         "--base=" + DSS, "--bounds", "sigma_b=0.003..0.02", "--resolution", "16",
                         "--format", "json")
    assert code == 0, err
    d = json.loads(out)
    assert r.free == ("sigma_b",)
    assert r.counts == d["counts"]
    assert r.hull == {k: tuple(v) for k, v in d["hull"].items()}
    assert r.lo.shape == (len(d["boxes"]), 1)
    assert sorted(zip(r.lo[:, 0], r.status)) == sorted((b["lo"][0], b["status"]) for b in d["boxes"])
    # the data's truth region: the generating σ_b is not in an infeasible box
    bad = [(a, b) for a, b, s in zip(r.lo[:, 0], r.hi[:, 0], r.status) if s == "infeasible"]
    assert not any(a <= 0.00715 <= b for a, b in bad)
    assert r.counts["feasible"] > 0 and r.complete


def test_to_pandas_rounds_proved_boxes_inward(tmp_path):
    """A feasible or infeasible box is a claim on its every point: its printed ends lie inside
    the doubles they read back to; an undecided box's outside (compared exactly)."""
    from decimal import Decimal

    pytest.importorskip("pandas")
    p = _write(tmp_path)
    r = bwcl.identify("shc", p, bounds=BOX, error=0.01, base=DSS, resolution=16)
    df = r.to_pandas()
    differs = 0
    for lo_t, hi_t, lo, hi, s in zip(df["sigma_b_lo"], df["sigma_b_hi"], r.lo[:, 0], r.hi[:, 0],
                                     r.status):
        assert float(lo_t) == lo and float(hi_t) == hi
        if s == "undecided":
            assert Decimal(lo_t) <= Decimal(lo) and Decimal(hi_t) >= Decimal(hi), (lo_t, hi_t, s)
        else:
            assert Decimal(lo_t) >= Decimal(lo) and Decimal(hi_t) <= Decimal(hi), (lo_t, hi_t, s)
            differs += Decimal(lo_t) != Decimal(lo) or Decimal(hi_t) != Decimal(hi)
    assert differs > 0 and {"feasible", "infeasible"} & set(r.status)


def test_sample_brackets_the_proved_hull(tmp_path):
    """``sample=N``: the hull of the f64-feasible points lies inside the proved hull, holds the
    generating σ_b (the data are within E of its curve), and is absent without ``sample``."""
    p = _write(tmp_path)
    r = bwcl.identify("shc", p, bounds=BOX, error=0.01, base=DSS, resolution=16, sample=100)
    assert r.sampled is not None and 0 < r.sampled["feasible"] <= r.sampled["tested"]
    (a, b), (lo, hi) = r.sampled["hull"]["sigma_b"], r.hull["sigma_b"]
    assert lo <= a <= 0.00715 <= b <= hi
    assert bwcl.identify("shc", p, bounds=BOX, error=0.01, base=DSS, resolution=4).sampled is None


def test_arrays_give_the_same_paving(tmp_path):
    p = _write(tmp_path)
    a = bwcl.identify("shc", p, bounds=BOX, error=0.01, base=DSS, resolution=8)
    b = bwcl.identify("shc", v0=np.array(V0), e=np.array(E), bounds="sigma_b=0.003..0.02",
                      error=0.01, base=DSS, resolution=8)
    assert a.counts == b.counts and a.hull == b.hull


@pytest.mark.parametrize("kw, needle", [
    (dict(error=0.0), "error"),
    (dict(error=0.01, bounds={"kappa": (1.2, 1.5)}), "outside"),
    (dict(error=0.01, bounds={"zeta": (0.1, 0.2)}), "zeta"),
    (dict(error=0.01, free=["kappa"]), "free"),
])
def test_bad_input_raises_value_error(tmp_path, kw, needle):
    p = _write(tmp_path)
    args = dict(bounds=BOX, base=DSS, resolution=4)
    args.update(kw)
    with pytest.raises(ValueError, match=needle):
        bwcl.identify("shc", p, **args)


def test_dask_split_and_merge_covers_the_box(tmp_path):
    """Four sub-boxes paved on a Dask LocalCluster (two worker processes) and merged: the boxes
    tile the whole box (their lengths add up), and the merged hull holds the generating σ_b as
    the whole paving's does."""
    distributed = pytest.importorskip("distributed")
    p = _write(tmp_path)
    whole = bwcl.identify("shc", p, bounds=BOX, error=0.01, base=DSS, resolution=16)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        merged = bwcl.identify_dask(client, "shc", str(p), bounds=BOX, parts=4, resolution=16,
                                    error=0.01, base=DSS, threads=1)
    length = float(np.sum(merged.hi[:, 0] - merged.lo[:, 0]))
    assert abs(length - (0.02 - 0.003)) < 1e-9
    assert merged.hull is not None and whole.hull is not None
    assert merged.hull["sigma_b"][0] <= 0.00715 <= merged.hull["sigma_b"][1]
    assert abs(sum(merged.shares.values()) - 1.0) < 1e-9
    # the merged shares against the boxes' exact lengths: the undecided one not understated,
    # the proved ones not overstated (summed in floats they could be either)
    from fractions import Fraction

    total = Fraction(merged.box["sigma_b"][1]) - Fraction(merged.box["sigma_b"][0])
    for s in ("feasible", "infeasible", "undecided"):
        x = sum((Fraction(b) - Fraction(a) for a, b, t in
                 zip(merged.lo[:, 0], merged.hi[:, 0], merged.status) if t == s), Fraction(0))
        share = Fraction(merged.shares[s])
        assert share >= x / total if s == "undecided" else share <= x / total, (s, share)
    assert "undecided" in repr(merged)
    # the same resolution everywhere: the hulls agree to within one finest box
    w = (0.02 - 0.003) / 16
    assert abs(merged.hull["sigma_b"][1] - whole.hull["sigma_b"][1]) <= w
