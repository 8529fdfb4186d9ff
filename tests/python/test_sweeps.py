"""Many parameter sets in one call (issue #34, item 3): an (m, 6) array of sets against n
speeds gives (m, n) arrays equal, case by case and bit for bit, to one call per set; the sets
of a law or of SI parameters as mappings of arrays; bad sets named by their index."""

import numpy as np
import pytest

import bwcl
from conftest import BASEBALL

DSS = bwcl.TABLE1["SHC DSS"].base
SPEEDS = np.array([0.3, 1.0, 2.5])


def grid(m):
    sets = np.tile(np.array(DSS), (m, 1))
    sets[:, 2] = np.linspace(0.4, 0.8, m)  # κ
    sets[:, 3] = np.linspace(0.004, 0.02, m)  # σ_b
    return sets


def test_sets_by_speeds_equal_one_call_per_set():
    sets = grid(5)
    r = bwcl.cor("shc", base=sets, v0=SPEEDS)
    assert r.e.shape == r.ts.shape == r.nfev.shape == (5, 3)
    assert r.params.shape == (5, 3, 6) and r.v0.shape == (5, 3)
    assert len(r.error) == 5 and all(len(row) == 3 for row in r.error)
    assert r.ok.shape == (5, 3) and r.ok.all()
    for i, s in enumerate(sets):
        one = bwcl.cor("shc", base=s, v0=SPEEDS)
        assert np.array_equal(r.e[i], one.e) and np.array_equal(r.ts[i], one.ts)
        assert np.array_equal(r.params[i], one.params) and np.array_equal(r.v0[i], SPEEDS)
    # the sets differ: so do the rows
    assert len({tuple(row) for row in r.e}) == 5
    # a list of sets is the same as the array
    again = bwcl.cor("shc", base=[list(s) for s in sets], v0=SPEEDS)
    assert np.array_equal(again.e, r.e)


def test_nd_sets_and_a_law_and_physical_sets():
    nd = np.array([[1.0, 0.0, 0.5, 0.1, 1.2, 1.5], [2.0, -1.0, 0.3, 0.05, 1.5, 2.0]])
    r = bwcl.cor("shc", nd=nd)
    assert r.e.shape == (2,)
    for i in range(2):
        assert r.e[i] == bwcl.cor("shc", nd=nd[i]).e[0]
    law = bwcl.cor("hunt-crossley", base={"sigma_b": np.array([0.1, 0.2, 0.4]), "n": 1.5},
                   v0=SPEEDS)
    assert law.e.shape == (3, 3) and law.params["sigma"].shape == (3, 3)
    for i, sb in enumerate((0.1, 0.2, 0.4)):
        one = bwcl.cor("hunt-crossley", base={"sigma_b": sb, "n": 1.5}, v0=SPEEDS)
        assert np.array_equal(law.e[i], one.e)
    ks = [BASEBALL["k"], 2 * BASEBALL["k"]]
    phys = bwcl.cor("shc", physical={**BASEBALL, "k": ks}, v0=[2.15, 3.03])
    assert phys.e.shape == phys.ts_seconds.shape == (2, 2)
    for i, k in enumerate(ks):
        one = bwcl.cor("shc", physical={**BASEBALL, "k": k}, v0=[2.15, 3.03])
        assert np.array_equal(phys.e[i], one.e) and np.array_equal(phys.ts_seconds[i], one.ts_seconds)


def test_rigorous_sets_equal_one_call_per_set():
    sets = grid(2)
    r = bwcl.cor_rigorous("shc", base=sets, v0=[0.5, 1.5])
    assert r.e.shape == (2, 2, 2) and r.proved.shape == (2, 2) and r.params.shape == (2, 2, 6, 2)
    assert len(r.status) == 2 and r.status[0] == ("proved", "proved")
    for i, s in enumerate(sets):
        one = bwcl.cor_rigorous("shc", base=s, v0=[0.5, 1.5])
        assert np.array_equal(r.e[i], one.e) and r.e_text[i] == one.e_text


def test_bad_sets_are_named_by_index():
    sets = grid(3)
    sets[1, 1] = -2.0  # |Γ_b| ≥ B_b: outside 𝓟
    with pytest.raises(ValueError, match=r"parameter set 1\b"):
        bwcl.cor("shc", base=sets, v0=SPEEDS)
    with pytest.raises(ValueError, match="differ in length"):
        bwcl.cor("shc", physical={**BASEBALL, "k": [1e8, 2e8], "c": [1e6, 2e6, 3e6]}, v0=1)
    with pytest.raises(ValueError, match="at most"):
        bwcl.cor("shc", base=np.tile(np.array(DSS), (10_001, 1)), v0=np.linspace(0.1, 5, 1000))


def test_sensitivities_hold_central_differences():
    """∂e/∂v0 proved at v0 = 1 holds the central difference of the f64 engine at tight
    tolerances (its error ~1e-12/h ≪ the margin)."""
    q = bwcl.cor_rigorous("shc", base=DSS, v0=1, sensitivities=True)
    (sens,) = q.sensitivities
    assert "v0" in sens and sens["v0"].de is not None
    h = 1e-4
    f = bwcl.cor("shc", base=DSS, v0=[1 - h, 1 + h], rtol=1e-13, atol=1e-15)
    fd = (f.e[1] - f.e[0]) / (2 * h)
    lo, hi = sens["v0"].de
    assert lo - 1e-6 <= fd <= hi + 1e-6 and hi - lo < 1e-6
    # a negative control: the slope is not the slope of T_s
    tlo, thi = sens["v0"].dts
    assert not (tlo - 1e-6 <= fd <= thi + 1e-6)


def test_band_holds_point_enclosures_and_monotone_verdicts():
    b = bwcl.band("shc", base=DSS, v0=(0.9, 1.0), thickness=1e-4)
    assert len(b) >= 1 and b.thickness <= 1e-4
    assert b.v0_lo[0] <= 0.9 + 1e-12 and b.v0_hi[-1] >= 1.0 - 1e-12
    assert (b.v0_lo[1:] == b.v0_hi[:-1]).all()
    q = bwcl.cor_rigorous("shc", base=DSS, v0=[0.9, 0.95, 1.0])
    for k, v in enumerate([0.9, 0.95, 1.0]):
        i = int(np.searchsorted(b.v0_hi, v))
        i = min(i, len(b) - 1)
        # the band's hull on the piece holds the point's enclosure's intersection
        assert b.e[i, 0] <= q.e[k, 1] and q.e[k, 0] <= b.e[i, 1]
    assert "pieces" in repr(b) and len(repr(b)) < 300
    m = bwcl.prove_monotone("shc", base=DSS, v0=(0.5, 1.0))
    assert m.verdict == "proved" and m.proved and m.max_slope < 0
    with pytest.raises(ValueError, match="v0"):
        bwcl.prove_monotone("shc", base=DSS, v0=(1.0, 0.5))
    with pytest.raises(ValueError, match="thickness"):
        bwcl.band("shc", base=DSS, v0=(0.9, 1.0), thickness=2.0)


def test_a_second_order_band_holds_point_enclosures_between_its_nodes():
    b = bwcl.band("shc", base=DSS, v0=(0.95, 1.05), second_order=True)
    assert isinstance(b, bwcl.InterpBandResult)
    assert len(b) >= 10 and b.thickness <= 1e-9 and b.pieces_count >= 1
    assert b.v0_lo[0] == 0.95 and b.v0_hi[-1] == 1.05
    assert (b.v0_lo[1:] == b.v0_hi[:-1]).all()
    assert (b.interval_thickness <= 1e-9).all()
    # between nodes and at one: the exact form's bounds hold the point runs' enclosures
    vs = [0.95, 0.9731, float(b.v0_lo[len(b) // 2]), 1.0437, 1.05]
    q = bwcl.cor_rigorous("shc", base=DSS, v0=vs)
    for k, v in enumerate(vs):
        lo, hi = b.e_at(v)
        assert 0 < hi - lo <= 1e-9
        # both enclose the true value: they meet
        assert lo <= q.e[k, 1] and q.e[k, 0] <= hi, (v, lo, hi, q.e[k])
        tlo, thi = b.ts_at(v)
        assert tlo <= q.ts[k, 1] and q.ts[k, 0] <= thi
    # a decimal as written (not its double) gives bounds as tight
    lo, hi = b.e_at("0.9731")
    assert 0 < hi - lo <= 1e-9 and lo <= q.e[1, 1] and q.e[1, 0] <= hi
    # a negative control: the form of a neighbouring speed misses this one's e
    lo, hi = b.e_at(1.0437)
    assert not (lo <= q.e[0, 0] and q.e[0, 1] <= hi)
    with pytest.raises(ValueError, match="outside"):
        b.e_at(1.06)
    with pytest.raises(ValueError, match="finite"):
        b.e_at(float("nan"))
    # NumPy's scalars are their values; a bool is no speed (it was read as 1)
    assert b.e_at(np.float32(1.0)) == b.e_at(1.0) == b.e_at(np.int64(1))
    with pytest.raises(TypeError, match="bool"):
        b.e_at(True)
    assert "node intervals" in repr(b) and len(repr(b)) < 300
    assert len(b.to_pandas()) == len(b)


def test_progress_callbacks():
    calls = []
    r = bwcl.cor("shc", base=grid(40), v0=np.linspace(0.1, 5, 100),
                 progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (4000, 4000)
    assert all(t == 4000 for _, t in calls)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)
    assert r.e.shape == (40, 100)
    seen = []
    bwcl.cor_rigorous("shc", base=DSS, v0=[0.5, 1, 2], progress=lambda d, t: seen.append((d, t)))
    assert seen[-1] == (3, 3)

    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop()

    with pytest.raises(Stop):
        bwcl.cor_rigorous("shc", base=DSS, v0=np.linspace(0.1, 5, 400), progress=stop)
    # the engines run again after the stop
    assert bwcl.cor_rigorous("shc", base=DSS, v0=1).proved.all()
    with pytest.raises(TypeError, match="progress"):
        bwcl.cor("shc", base=DSS, v0=1, progress="yes")


def test_trajectories_and_loops_at_several_speeds():
    ts = bwcl.trajectory("shc", base=DSS, v0=[0.5, 2.0], points=30)
    assert isinstance(ts, tuple) and len(ts) == 2
    for v, t in zip((0.5, 2.0), ts):
        one = bwcl.trajectory("shc", base=DSS, v0=v, points=30)
        assert np.array_equal(t.states, one.states) and np.array_equal(t.t, one.t)
    assert not np.array_equal(ts[0].states, ts[1].states)
    loops = bwcl.loop("shc", base=DSS, v0=np.array([1.0, 3.0]), points=20, rigorous=True)
    assert len(loops) == 2 and loops[1].F.shape == (20, 2)
    assert isinstance(bwcl.trajectory("shc", base=DSS, v0=[1.0], points=5), bwcl.TrajectoryResult)


def test_progress_of_band_and_identify():
    seen = []
    b = bwcl.band("shc", base=DSS, v0=(0.5, 1.0), thickness=1e-5,
                  progress=lambda s, m: seen.append((s, m)))
    # the share settled as the band goes (≈ 4 s), then the end
    assert len(b) > 1 and seen[-1] == (1.0, "done") and len(seen) >= 3
    assert any("pieces" in m for _, m in seen[:-1]), seen
    assert all(0.0 <= s <= 1.0 for s, _ in seen)
    shares = [s for s, _ in seen]
    assert shares == sorted(shares)
    from conftest import DATA

    seen = []
    r = bwcl.identify("shc", DATA, error=0.02, base=DSS, bounds={"sigma_b": (0.001, 0.02)},
                      resolution=8, progress=lambda s, m: seen.append((s, m)))
    assert seen[-1] == (1.0, "done") and len(r.status) > 1
    assert any("boxes done" in m for _, m in seen[:-1]), seen
    with pytest.raises(TypeError, match="progress"):
        bwcl.band("shc", base=DSS, v0=(0.9, 1.0), progress=3)
    seen = []
    m = bwcl.prove_monotone("shc", base=DSS, v0=(0.5, 1.0), progress=lambda s, m: seen.append(s))
    assert m.proved and seen[-1] == 1.0
