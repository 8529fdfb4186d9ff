#!/usr/bin/env python3
"""bwcl from Python beside SciPy, and beside the `bwcl` program, on this machine.

1. Per CoR against SciPy: the four Table 1 base sets at v0 in {0.1, 1, 5}; SciPy is
   solve_ivp(method="DOP853", rtol=1e-10, atol=1e-12, max_step=1e-2) with the separation event
   (the models and the event of benches/scipy_side_by_side.py, imported from it); bwcl is
   `bwcl.cor(model, base=P*, v0=[v0]*REPEAT, threads=1)` timed as a whole Python call (argument
   conversion, parsing and the NumPy results included), divided by REPEAT. Both on one thread.
   Each case is timed in ROUNDS interleaved rounds (one solve_ivp call beside one bwcl.cor
   call); the ratio is the median of the per-round ratios.
2. 10⁴ speeds against the CLI: `bwcl.cor` on 10 000 speeds (0.1 … 5 m/s, DSS set, default
   threads) timed as a whole Python call, beside `bwcl cor … --timing` on the same list (its
   computation only, as it reports it), in ROUNDS interleaved rounds; the ratio is
   Python wall time / CLI computation time (the issue's floor: ≤ 1.2).

Usage: python benches/python_vs_scipy.py [--repeat 200] [--rounds 5] [--no-scipy] [--no-cli]
"""

import argparse
import importlib.util
import os
import re
import statistics
import subprocess
import sys
import time

import numpy as np

import bwcl

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def side_by_side():
    spec = importlib.util.spec_from_file_location(
        "scipy_side_by_side", os.path.join(REPO, "benches", "scipy_side_by_side.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def against_scipy(repeat, rounds):
    from scipy.integrate import solve_ivp

    sbs = side_by_side()
    print(f"## bwcl.cor (Python, 1 thread, {repeat} CoRs per call) against SciPy solve_ivp(DOP853)")
    print()
    print("| case | v0 | SciPy ms/CoR | bwcl.cor µs/CoR | ratio | |e_bwcl − e_SciPy| |")
    print("|---|---|---|---|---|---|")
    ratios = []
    for name, model, base in sbs.CASES:
        for v0 in sbs.SPEEDS:
            run_scipy, result = sbs.scipy_case(model, base, v0, solve_ivp)
            ts, tb, rs = [], [], []
            for _ in range(rounds):
                a = run_scipy()
                t0 = time.perf_counter()
                r = bwcl.cor(model, base=base, v0=[v0] * repeat, threads=1)
                b = (time.perf_counter() - t0) / repeat
                ts.append(a), tb.append(b), rs.append(a / b)
            e_scipy = result()[1]
            ratio = statistics.median(rs)
            ratios.append(ratio)
            print(f"| {name} | {v0} | {statistics.median(ts) * 1e3:.1f} | "
                  f"{statistics.median(tb) * 1e6:.1f} | {ratio:.0f}× | {abs(r.e[0] - e_scipy):.1e} |")
    print()
    print(f"ratio over the {len(ratios)} cases: {min(ratios):.0f}×–{max(ratios):.0f}× "
          f"(median {statistics.median(ratios):.0f}×)")
    return ratios


def against_cli(rounds):
    binary = os.environ.get("BWCL_BIN") or os.path.join(
        os.environ.get("CARGO_TARGET_DIR", os.path.join(REPO, "target")), "release", "bwcl")
    base = bwcl.TABLE1["SHC DSS"][1]
    v = np.round(np.linspace(0.1, 5.0, 10_000), 6)
    text = ",".join(repr(float(x)) for x in v)
    print()
    print("## bwcl.cor on 10⁴ speeds against `bwcl cor --timing` (same list, default threads)")
    print()
    py, cl, rs = [], [], []
    for _ in range(rounds):
        t0 = time.perf_counter()
        r = bwcl.cor("shc", base=base, v0=v)
        a = time.perf_counter() - t0
        p = subprocess.run([binary, "cor", "--model=shc", f"--base={base}", f"--v0={text}",
                            "--timing", "--format=csv"], capture_output=True, text=True)
        m = re.search(r"timing: (\d+) case\(s\) in ([0-9.eE+-]+) s", p.stderr)
        if p.returncode != 0 or not m:
            sys.exit(f"bwcl failed: {p.stderr.strip()[:200]}")
        b = float(m.group(2))
        py.append(a), cl.append(b), rs.append(a / b)
    print(f"Python bwcl.cor (whole call): median {statistics.median(py):.3f} s "
          f"({statistics.median(py) / len(v) * 1e6:.1f} µs per CoR, {r.threads} threads)")
    print(f"CLI --timing (computation):   median {statistics.median(cl):.3f} s")
    print(f"ratio Python/CLI per round: {', '.join(f'{x:.2f}' for x in rs)}; "
          f"median {statistics.median(rs):.2f}")
    return rs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=200)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--no-scipy", action="store_true")
    ap.add_argument("--no-cli", action="store_true")
    a = ap.parse_args()
    print(f"machine: {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f} at the start")
    if not a.no_scipy:
        against_scipy(a.repeat, a.rounds)
    if not a.no_cli:
        against_cli(a.rounds)
    print(f"\nload average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
