"""A parameter sweep of the CoR on a Dask cluster: e(𝓟(P*, v0)) (eq:main_cor) over a grid of
base sets P* = (B_b, Γ_b, κ, σ_b, n, p) around the paper's SHC DSS set, at several impact
speeds, mapped over the cluster in chunks of base sets.

Each task calls ``bwcl.cor`` once for its whole chunk: the chunk's (k, 6) array of base sets
against the speeds gives a (k, n_speeds) array (the k·n_speeds cases in parallel inside the
worker when it has threads); the chunks are gathered into an (n_sets, n_speeds) matrix. The same code runs on a real cluster: give the
scheduler's address instead of starting a LocalCluster.

    python examples/dask_sweep.py                          # LocalCluster, 2 worker processes
    python examples/dask_sweep.py --sets 2000 --speeds 20 --chunk 100
    python examples/dask_sweep.py --scheduler tcp://host:8786 --sets 1000000

It prints the throughput (CoRs per second) of the cluster and of one process on the same
grid (bwcl.cor with its own thread pool), as measured on this machine.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import bwcl

#: The paper's SHC DSS base set (Table 1).
DSS = (1.43, -1.42, 0.632, 0.00715, 1.31, 1.27)


def grid(n_sets: int, seed: int = 0) -> np.ndarray:
    """n_sets base sets around DSS: κ ∈ [0.3, 0.9], σ_b ∈ [0.003, 0.02] (log-uniform),
    Γ_b/B_b ∈ [−0.99, 0.5], B_b, n, p of DSS (a reproducible random grid)."""
    rng = np.random.default_rng(seed)
    sets = np.tile(np.array(DSS, dtype=float), (n_sets, 1))
    sets[:, 2] = rng.uniform(0.3, 0.9, n_sets)
    sets[:, 3] = np.exp(rng.uniform(np.log(0.003), np.log(0.02), n_sets))
    sets[:, 1] = sets[:, 0] * rng.uniform(-0.99, 0.5, n_sets)
    return sets


def cor_chunk(model: str, bases: np.ndarray, v0: np.ndarray, threads: int = 1) -> np.ndarray:
    """e for every base set of the chunk (rows) at every speed (columns): NaN where a case
    could not be integrated."""
    return bwcl.cor(model, base=bases, v0=v0, threads=threads).e


def sweep(client, model: str, bases: np.ndarray, v0: np.ndarray, chunk: int) -> np.ndarray:
    """The (n_sets, n_speeds) matrix of e, computed on the cluster in chunks of base sets."""
    chunks = [bases[i : i + chunk] for i in range(0, len(bases), chunk)]
    futures = client.map(cor_chunk, [model] * len(chunks), chunks, [v0] * len(chunks), pure=False)
    return np.vstack(client.gather(futures))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sets", type=int, default=400, help="base sets in the grid")
    ap.add_argument("--speeds", type=int, default=25, help="impact speeds per set (0.1 … 5 m/s)")
    ap.add_argument("--chunk", type=int, default=25, help="base sets per task")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    ap.add_argument("--scheduler", default=None, help="address of a running scheduler")
    a = ap.parse_args()

    from dask.distributed import Client, LocalCluster

    bases = grid(a.sets)
    v0 = np.linspace(0.1, 5.0, a.speeds)
    n = a.sets * a.speeds
    if a.scheduler:
        client = Client(a.scheduler)
    else:
        cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True)
        client = Client(cluster)
    # the workers import this file as a module (functions pickle by reference)
    client.upload_file(os.path.abspath(__file__))
    client.run(lambda: __import__("bwcl").__version__)  # workers warm

    t0 = time.perf_counter()
    e_cluster = sweep(client, "shc", bases, v0, a.chunk)
    t_cluster = time.perf_counter() - t0
    nworkers = len(client.scheduler_info()["workers"])
    client.close()

    t0 = time.perf_counter()
    e_one = cor_chunk("shc", bases, v0, threads=None)
    t_one = time.perf_counter() - t0
    assert np.array_equal(e_cluster, e_one, equal_nan=True)

    print(f"grid: {a.sets} base sets x {a.speeds} speeds = {n} CoRs (model shc)")
    print(f"dask ({nworkers} worker processes): {t_cluster:.2f} s, {n / t_cluster:,.0f} CoR/s")
    print(f"one process (bwcl.cor, all cores): {t_one:.2f} s, {n / t_one:,.0f} CoR/s")
    print(f"load average at the end: {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")


if __name__ == "__main__":
    main()
