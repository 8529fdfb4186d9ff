"""The GIL is released during a call (two threads overlap), results and functions pickle,
and the Dask example runs on a LocalCluster with two worker processes."""

import importlib.util
import pickle
import sys
import threading
import time

import numpy as np
import pytest

import bwcl
from conftest import DSS, ROOT

V = np.linspace(0.5, 2.0, 400)


def test_two_threads_overlap():
    """Two calls from two Python threads (one rayon thread each) run at the same time: their
    intervals overlap, which a call holding the GIL would forbid. On ≥ 2 idle cores the pair
    also takes about the time of one (printed, not asserted: the machine is shared)."""
    t0 = time.perf_counter()
    bwcl.cor("shc", base=DSS, v0=V, threads=1)
    one = time.perf_counter() - t0
    spans = {}

    def run(k):
        s = time.perf_counter()
        bwcl.cor("shc", base=DSS, v0=V, threads=1)
        spans[k] = (s, time.perf_counter())

    ths = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    t0 = time.perf_counter()
    for t in ths:
        t.start()
    for t in ths:
        t.join()
    both = time.perf_counter() - t0
    (a0, a1), (b0, b1) = spans[0], spans[1]
    overlap = min(a1, b1) - max(a0, b0)
    print(f"one call {one:.3f} s, two concurrent calls {both:.3f} s (ratio {both / one:.2f})")
    assert overlap > 0.5 * min(a1 - a0, b1 - b0)


def test_python_runs_during_a_call():
    """A pure-Python thread keeps counting while a call computes (with the GIL held it could
    count only until the interpreter's next switch, set here to 0.1 ms)."""
    counter = [0]
    done = threading.Event()

    def spin():
        while not done.is_set():
            counter[0] += 1

    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-4)
    t = threading.Thread(target=spin)
    try:
        t.start()
        time.sleep(0.01)
        c0 = counter[0]
        bwcl.cor("shc", base=DSS, v0=np.linspace(0.5, 2.0, 1000), threads=1)
        c1 = counter[0]
    finally:
        done.set()
        t.join()
        sys.setswitchinterval(old)
    assert c1 - c0 > 20000, (c0, c1)


def test_results_and_functions_pickle():
    r = bwcl.cor("shc", base=DSS, v0=[0.5, 1])
    q = bwcl.cor_rigorous("shc", base=DSS, v0=[1])
    t = bwcl.trajectory("shc", nd=DSS, points=5)
    for obj in (r, q, t):
        back = pickle.loads(pickle.dumps(obj))
        assert type(back) is type(obj)
    back = pickle.loads(pickle.dumps(r))
    assert np.array_equal(back.e, r.e) and back.error == r.error
    assert pickle.loads(pickle.dumps(q)).e_text == q.e_text
    for f in (bwcl.cor, bwcl.cor_rigorous, bwcl.trajectory, bwcl.loop, bwcl.fit, bwcl.cost):
        assert pickle.loads(pickle.dumps(f)) is f


def _example():
    spec = importlib.util.spec_from_file_location("dask_sweep", ROOT / "examples" / "dask_sweep.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_dask_example_on_a_local_cluster():
    distributed = pytest.importorskip(
        "dask.distributed", reason="dask[distributed] is not installed: the Dask example is skipped"
    )
    ex = _example()
    bases = ex.grid(12)
    v0 = np.array([0.5, 1.0, 3.0])
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        client.upload_file(str(ROOT / "examples" / "dask_sweep.py"))
        e = ex.sweep(client, "shc", bases, v0, chunk=5)
        # plain bwcl.cor mapped directly works as well (functions pickle by reference)
        fut = client.submit(bwcl.cor, "shc", base=bases[0], v0=v0, threads=1)
        r = fut.result()
    assert e.shape == (12, 3)
    assert np.array_equal(e, ex.cor_chunk("shc", bases, v0))
    assert np.array_equal(r.e, e[0])


def test_a_fit_progress_callback_may_call_bwcl():
    """A progress callback of fit runs on a worker of the shared pool; when it calls bwcl
    itself (a parallel cor), that call runs on the same worker instead of waiting for it
    outside the pool: with every worker so waiting it hung for ever, deaf to Ctrl-C (found by a
    probe). In a child process, so that a hang fails the test instead of the run."""
    import subprocess
    import textwrap

    code = textwrap.dedent(f"""
        import bwcl
        calls = []
        def progress(p):
            r = bwcl.cor("shc", base={DSS!r}, v0=[1.0, 2.0])
            calls.append(float(r.e[0]))
        fit = bwcl.fit("shc", {str(ROOT / "paper_repro/data/synthetic_dss.csv")!r}, starts=4,
                       max_iter=20, progress=progress)
        assert calls and all(abs(e - calls[0]) == 0 for e in calls), calls
        print("ok", len(calls), fit.J)
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0 and out.stdout.startswith("ok"), out.stderr[-2000:]
