"""The package gives the CLI's values for the same cases: the same engines, bit for bit."""

import csv
import io
import json

import numpy as np
import pytest

import bwcl
from conftest import BASEBALL, BASEBALL_TEXT, DATA, DSS

SPEEDS = [0.1, 0.5, 1.0, 2.0, 3.0, 5.0]


@pytest.mark.parametrize("name", list(bwcl.TABLE1))
def test_cor_equals_cli(name, cli_json):
    model, base = bwcl.TABLE1[name]
    r = bwcl.cor(model, base=base, v0=SPEEDS)
    rows = cli_json("cor", f"--model={model}", f"--base={bwcl.TABLE1[name].text}",
                    "--v0=" + ",".join(map(str, SPEEDS)))
    assert len(r) == len(rows) == len(SPEEDS)
    for i, row in enumerate(rows):
        assert float(row["e"]) == r.e[i]
        assert float(row["ts"]) == r.ts[i]
        assert row["nfev"] == r.nfev[i] and row["steps"] == r.steps[i]
        assert row["separated"] is bool(r.separated[i])
        assert float(row["params"]["sigma"]) == r.params[i, 3]
    assert r.ok.all() and r.separated.all()


def test_cor_settings_nd_and_physical_equal_cli(cli_json):
    r = bwcl.cor("shc", nd=DSS, rtol=1e-8, atol=1e-10, max_step=0.05, horizon=50)
    (row,) = cli_json("cor", "--model=shc", f"--nd={DSS}", "--rtol=1e-8", "--atol=1e-10",
                      "--max-step=0.05", "--horizon=50")
    assert (float(row["e"]), float(row["ts"]), row["nfev"]) == (r.e[0], r.ts[0], r.nfev[0])
    assert np.isnan(r.v0[0])
    r = bwcl.cor("shc", physical=BASEBALL, v0=[2.15, 3.03])
    rows = cli_json("cor", "--model=shc", f"--physical={BASEBALL_TEXT}", "--v0=2.15,3.03")
    for i, row in enumerate(rows):
        assert float(row["e"]) == r.e[i]
        assert float(row["ts_seconds"]) == r.ts_seconds[i]
        assert float(row["t_c"]) == r.t_c[i]


def test_cor_rigorous_equals_cli(cli_json):
    """Bounds and their outward decimals are the CLI's: decimals as written, a range, v0 list."""
    base = ["0.44", "-0.418", "0.113", "0.00785", "1.27", "3.14"]
    r = bwcl.cor_rigorous("maxwell", base=base, v0=["1", "5", ("0.999", "1.001")])
    rows = cli_json("cor", "--model=maxwell", "--base=" + ",".join(base), "--v0=1,5,0.999..1.001",
                    "--rigorous")
    assert r.status == ("proved",) * 3
    for i, row in enumerate(rows):
        assert row["proved"] is True
        assert tuple(row["e"]) == r.e_text[i] and tuple(row["ts"]) == r.ts_text[i]
        assert row["width_e"] == r.width_e_text[i]
        assert [float(x) for x in row["e"]] == list(r.e[i])
        assert [float(x) for x in row["v0"]] == list(r.v0[i])


def test_rigorous_physical_equals_cli(cli_json):
    r = bwcl.cor_rigorous("shc", physical=BASEBALL_TEXT, v0="2.15")
    (row,) = cli_json("cor", "--model=shc", f"--physical={BASEBALL_TEXT}", "--v0=2.15", "--rigorous")
    assert r.proved[0] and r.ts_seconds.shape == (1, 2)
    assert [float(x) for x in row["ts_seconds"]] == list(r.ts_seconds[0])


def _csv(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


def test_trajectory_and_loop_equal_cli(cli):
    t = bwcl.trajectory("maxwell", base=bwcl.TABLE1["Maxwell DSS"][1], v0=2, points=50)
    code, out, err = cli("trajectory", "--model=maxwell", "--base=" + bwcl.TABLE1["Maxwell DSS"].text,
                         "--v0=2", "--points=50")
    head, a = _csv(out)
    assert head == ["t", *t.state_names, "x", "v", "F"]
    assert np.array_equal(a[:, 0], t.t) and np.array_equal(a[:, 1:5], t.states)
    assert np.array_equal(a[:, 5], t.x) and np.array_equal(a[:, 7], t.F)
    lp = bwcl.loop("shc", physical=BASEBALL, v0=2.15, physical_units=True, points=40)
    code, out, err = cli("loop", "--model=shc", f"--physical={BASEBALL_TEXT}", "--v0=2.15",
                         "--physical-units", "--points=40")
    head, a = _csv(out)
    assert head == ["x_mm", "F_N"] and lp.units == "physical"
    assert np.array_equal(a[:, 0], lp.x) and np.array_equal(a[:, 1], lp.F)


def test_rigorous_trajectory_equals_cli(cli):
    t = bwcl.trajectory("shc", nd=DSS, points=7, rigorous=True)
    code, out, err = cli("trajectory", "--model=shc", f"--nd={DSS}", "--points=7", "--rigorous")
    head, a = _csv(out)
    assert head[:3] == ["t", "X_lo", "X_hi"]
    assert np.array_equal(a[:, 1:3], t.states[:, 0, :])
    assert np.array_equal(a[:, -2:], t.F)
    assert (t.F[:, 0] <= t.F[:, 1]).all()


def test_cost_and_fit_equal_cli(cli_json):
    c = bwcl.cost("shc", DATA, base=DSS)
    j = cli_json("cost", "--model=shc", f"--base={DSS}", f"--data={DATA}")
    assert float(j["J"]) == c.J and j["m"] == c.m
    assert [float(p["e_model"]) for p in j["curve"]] == list(c.e_model)
    # the same data as arrays
    c2 = bwcl.cost("shc", base=DSS, v0=c.v0, e=c.e_data)
    assert c2.J == c.J
    f = bwcl.fit("shc", DATA, starts=2, max_iter=15, seed=3)
    j = cli_json("fit", "--model=shc", f"--data={DATA}", "--starts=2", "--max-iter=15", "--seed=3")
    assert float(j["J"]) == f.J
    assert [float(j["P_star"][k]) for k in ("B", "Gamma", "kappa", "sigma", "n", "p")] == list(f.base)
    assert [s["evaluations"] for s in j["starts"]] == [s.evaluations for s in f.starts]


def test_fit_progress_callback():
    seen = []
    f = bwcl.fit("shc", DATA, starts=1, max_iter=10, progress=seen.append, threads=1)
    assert seen and all(isinstance(p, bwcl.FitProgress) for p in seen)
    assert [p.done for p in seen] == sorted(p.done for p in seen)
    assert seen[-1].done == seen[-1].total == 20 and seen[-1].starts_done == 1
    assert seen[-1].last_J == f.starts[0].J

    def stop(p):
        raise KeyboardInterrupt("stop")

    with pytest.raises(KeyboardInterrupt):
        bwcl.fit("shc", DATA, starts=1, max_iter=5, progress=stop)


def test_more_speeds_than_one_cli_list():
    """The CLI takes 10⁴ speeds per list; the package parses longer arrays list by list."""
    v = np.linspace(0.5, 2.0, bwcl._bwcl.MAX_SPEEDS_PER_PARSE + 3)
    r = bwcl.cor("shc", base=DSS, v0=v, rtol=1e-4, atol=1e-6, max_step=1.0)
    assert len(r) == len(v) and np.array_equal(r.v0, v)
    s = bwcl.cor("shc", base=DSS, v0=v[-3:], rtol=1e-4, atol=1e-6, max_step=1.0)
    assert np.array_equal(r.e[-3:], s.e)


def test_threads_keyword():
    assert bwcl.cor("shc", base=DSS, v0=[1, 2], threads=1).threads == 1
    assert bwcl.cor("shc", base=DSS, v0=[1, 2], threads=3).threads == 3
