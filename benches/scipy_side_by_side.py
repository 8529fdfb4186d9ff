#!/usr/bin/env python3
"""SciPy side by side: the CoR e of the four Table 1 base sets at v0 in {0.1, 1, 5}.

SciPy: solve_ivp(method="DOP853", rtol=1e-10, atol=1e-12, max_step=1e-2) on the
nondimensional models written here from the paper (NDBWSHCCM eq:BWSHCCM_nd; NDBWMCM
eq:BWMCM_nd with the output V = R' + W of eq:BWMCM_nd_output), parameters
P(P*, v0) = (B_b v0^(2n/(p+1)), Gamma_b v0^(2n/(p+1)), kappa, sigma_b v0^s, n, p) with
s = 1 (SHC) or (p-1)/(p+1) (Maxwell). Separation T_s = inf{T >= 0 : F <= 0 and V >= 0} is a
terminal event on g = max(F, -V) crossing zero downward (g(0) = max(0, 1) = 1; the event
ignores T = 0 anyway); e = V(T_s).

bwcl: `bwcl cor --model M --base P* --v0 v,v,...,v --format json --timing` with REPEAT
copies of the speed in one call. Two times per CoR: t_bwcl, the computation's own time as
`--timing` reports it / REPEAT (like t_scipy, which is one solve_ivp call in a running
interpreter: no start-up, parsing or output on either side), and t_wall, the call's wall time
/ REPEAT (process start-up, argument parsing and JSON output included, amortized). By
default RAYON_NUM_THREADS=1 (single-threaded, like SciPy); pass --threads N to change it.
The binary is $BWCL_BIN, else target/release/bwcl at the repo root (built with
`cargo build --release` if missing).

Timing: the machine's speed drifts (a shared VM: the same solve_ivp call takes 28 to 70 ms
within one run), so the two sides are timed in ROUNDS interleaved rounds per case, each one
SciPy solve_ivp call right beside one bwcl call, and each round gives its own ratios
t_scipy / t_bwcl and t_scipy / t_wall. The columns are the medians over the rounds: t_scipy,
t_bwcl, t_wall, and the ratios (the medians of the per-round ratios, so that a slow spell of
the machine slows both sides of the ratios it enters). `cargo run --release --features bench --example results`
(benches/generator/results.rs) runs this script with --json and adds an in-process bwcl time
next to it.

Usage: python3 benches/scipy_side_by_side.py [--repeat 400] [--threads 1] [--no-bwcl]
       [--json OUT.json]
"""

import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

CASES = [
    ("SHC DSS", "shc", "1.43,-1.42,0.632,0.00715,1.31,1.27"),
    ("SHC DSA", "shc", "0.63,-0.611,0.188,0.00594,1,2.02"),
    ("Maxwell DSS", "maxwell", "0.655,-0.64,0.519,0.0118,1.94,2.28"),
    ("Maxwell DSA", "maxwell", "0.44,-0.418,0.113,0.00785,1.27,3.14"),
]
SPEEDS = [0.1, 1.0, 5.0]
RTOL, ATOL, MAX_STEP, HORIZON = 1e-10, 1e-12, 1e-2, 100.0
ROUNDS = 7

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def spow(x, q):
    """|x|^(q-1) x (signed power)."""
    return math.copysign(abs(x) ** q, x)


def nd_params(model, base, v0):
    """P(P*, v0) of sections KVCL / MCL."""
    b, g, kappa, sigma, n, p = (float(s) for s in base.split(","))
    s = v0 ** (2.0 * n / (p + 1.0))
    sig_exp = 1.0 if model == "shc" else (p - 1.0) / (p + 1.0)
    return b * s, g * s, kappa, sigma * v0**sig_exp, n, p


def shc_model(P):
    """NDBWSHCCM (eq:BWSHCCM_nd), state (X, Z, V)."""
    B, G, kappa, sigma, n, p = P
    kc = 1.0 - kappa

    def force(y):
        X, Z, V = y
        return -kappa * spow(X, p) - kc * spow(Z, p) - sigma * abs(X) ** p * V

    def rhs(t, y):
        X, Z, V = y
        Zd = V - B * spow(Z, n) * abs(V) - G * abs(Z) ** n * V
        Vd = -kappa * spow(X, p) - kc * spow(Z, p) - sigma * abs(X) ** p * V
        return [V, Zd, Vd]

    def velocity(y):
        return y[2]

    return rhs, force, velocity, [0.0, 0.0, -1.0]


def maxwell_model(P):
    """NDBWMCM (eq:BWMCM_nd), state (R, Y, Z, W); outputs X = R + Y, V = R' + Y'."""
    B, G, kappa, sigma, n, p = P
    kc = 1.0 - kappa

    def rdot(y):
        R, Y, Z, W = y
        return kappa * sigma * spow(Y, p) + kc * sigma * spow(Z, p)

    def rhs(t, y):
        R, Y, Z, W = y
        Rd = rdot(y)
        Yd = W
        Zd = W - B * spow(Z, n) * abs(W) - G * abs(Z) ** n * W
        Wd = (
            -Rd / sigma
            - kappa * p * sigma * abs(Y) ** (p - 1.0) * Yd
            - kc * p * sigma * abs(Z) ** (p - 1.0) * Zd
        )
        return [Rd, Yd, Zd, Wd]

    def force(y):
        # F_P = -kappa |Y|^(p-1) Y - kappa_c |Z|^(p-1) Z  (so R' = -sigma F_P)
        return -kappa * spow(y[1], p) - kc * spow(y[2], p)

    def velocity(y):
        return rdot(y) + y[3]

    return rhs, force, velocity, [0.0, 0.0, 0.0, -1.0]


def scipy_case(model, base, v0, solve_ivp):
    """(run, result): run() times one solve_ivp call and keeps its solution; result() gives
    (ts, e, nfev/steps, error) of the last solution."""
    P = nd_params(model, base, v0)
    rhs, force, velocity, y0 = (shc_model if model == "shc" else maxwell_model)(P)

    def g(t, y):
        if t == 0.0:
            return 1.0
        return max(force(y), -velocity(y))

    g.terminal = True
    g.direction = -1
    last = {}

    def run():
        t0 = time.perf_counter()
        last["sol"] = solve_ivp(
            rhs, (0.0, HORIZON), y0, method="DOP853", rtol=RTOL, atol=ATOL,
            max_step=MAX_STEP, events=g,
        )
        return time.perf_counter() - t0

    def result():
        sol = last["sol"]
        if not sol.success:
            return None, None, sol.nfev, sol.message
        nf = f"{sol.nfev}/{len(sol.t) - 1}"  # nfev, accepted steps
        if sol.t_events[0].size == 0:
            return math.inf, 0.0, nf, None
        return sol.t_events[0][0], velocity(sol.y_events[0][0]), nf, None

    return run, result


def find_bwcl():
    b = os.environ.get("BWCL_BIN")
    if b:
        return b if os.path.isfile(b) and os.access(b, os.X_OK) else None
    b = os.path.join(REPO, "target", "release", "bwcl")
    if os.path.isfile(b):
        return b
    if shutil.which("cargo") is None:
        return None
    print("building bwcl: cargo build --release ...", file=sys.stderr)
    r = subprocess.run(["cargo", "build", "--release"], cwd=REPO)
    return b if r.returncode == 0 and os.path.isfile(b) else None


def bwcl_case(binary, model, base, v0, repeat, threads):
    """(run, result) as for SciPy: run() times one `bwcl cor` call of REPEAT CoRs and returns
    the seconds per CoR (computation as `--timing` reports it, wall), or None if it failed;
    result() gives (e, nfev/steps, error)."""
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    speeds = ",".join([repr(v0)] * repeat)
    cmd = [binary, "cor", "--model", model, "--base", base, "--v0", speeds, "--format", "json",
           "--timing"]
    last = {}

    def run():
        t0 = time.perf_counter()
        r = subprocess.run(cmd, capture_output=True, text=True, env=env)
        dt = time.perf_counter() - t0
        last["r"] = r
        m = re.search(r"timing: (\d+) case\(s\) in ([0-9.eE+-]+) s", r.stderr)
        if r.returncode != 0 or not m or int(m.group(1)) != repeat:
            return None
        return float(m.group(2)) / repeat, dt / repeat

    def result():
        r = last["r"]
        if r.returncode != 0:
            return None, None, (r.stderr.strip() or f"exit {r.returncode}")[:200]
        try:
            rows = json.loads(r.stdout)
            if isinstance(rows, dict):
                rows = rows.get("rows") or rows.get("results") or [rows]
            row = rows[0]
        except (ValueError, IndexError, KeyError, TypeError) as err:
            return None, None, f"unparsable JSON: {err}"
        if len(rows) != repeat:
            return None, None, f"expected {repeat} rows, got {len(rows)}"
        if row.get("error"):
            return None, row.get("nfev"), row["error"]
        nf = row.get("nfev")
        if nf is not None and row.get("steps") is not None:
            nf = f"{nf}/{row['steps']}"
        return row.get("e"), nf, None

    return run, result


def fmt(x, spec, unit=""):
    return "-" if x is None else format(x, spec) + unit


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=400, help="copies of v0 per bwcl call")
    ap.add_argument("--threads", type=int, default=1, help="RAYON_NUM_THREADS for bwcl")
    ap.add_argument("--no-bwcl", action="store_true", help="SciPy side only")
    ap.add_argument("--json", metavar="PATH", help="also write the rows as JSON to PATH")
    args = ap.parse_args()

    try:
        import scipy
        from scipy.integrate import solve_ivp
    except ImportError:
        print("SciPy not installed: skipped")
        return 0

    binary = None if args.no_bwcl else find_bwcl()
    if binary is None and not args.no_bwcl:
        print("bwcl binary not available (set BWCL_BIN or build it): SciPy side only",
              file=sys.stderr)
    print(f"SciPy {scipy.__version__}, Python {sys.version.split()[0]}; DOP853 rtol={RTOL} "
          f"atol={ATOL} max_step={MAX_STEP}")
    if binary:
        print(f"bwcl = {binary}; one call = {args.repeat} CoRs (process start-up included), "
              f"RAYON_NUM_THREADS={args.threads}")
    print(f"per case: 1 warm-up round, then {ROUNDS} rounds of one SciPy call beside one bwcl "
          f"call; medians over the rounds; ratio = median of the per-round t_scipy/t_bwcl "
          f"(min..max after it), t_bwcl from --timing; t_wall and its ratio: the call's wall "
          f"time per CoR")
    head = (f"{'case':<12} {'v0':>4} {'e_scipy':>20} {'e_bwcl':>20} {'|diff|':>9} "
            f"{'nfev/st_sp':>11} {'nfev/st_bw':>11} {'t_scipy/CoR':>12} {'t_bwcl/CoR':>12} "
            f"{'ratio':>6} {'(range)':>11} {'t_wall':>10} {'ratio':>6}")
    print(head)
    print("-" * len(head))
    notes = []
    rows = []
    for name, model, base in CASES:
        for v0 in SPEEDS:
            run_s, result_s = scipy_case(model, base, v0, solve_ivp)
            run_b = result_b = None
            if binary:
                run_b, result_b = bwcl_case(binary, model, base, v0, args.repeat, args.threads)
            times_s, times_b, times_w, ratios_case, ratios_wall = [], [], [], [], []
            for rnd in range(ROUNDS + 1):
                t_s = run_s()
                t_bw = run_b() if run_b else None
                if rnd == 0:
                    continue  # warm-up
                times_s.append(t_s)
                if t_bw:
                    times_b.append(t_bw[0])
                    times_w.append(t_bw[1])
                    ratios_case.append(t_s / t_bw[0])
                    ratios_wall.append(t_s / t_bw[1])
            ts, e_s, nfev_s, err_s = result_s()
            if err_s:
                notes.append(f"{name} v0={v0}: SciPy failed: {err_s}")
            e_b = nfev_b = None
            if result_b:
                e_b, nfev_b, err_b = result_b()
                if err_b:
                    notes.append(f"{name} v0={v0}: bwcl: {err_b}")
            t_s = statistics.median(times_s)
            t_b = statistics.median(times_b) if times_b else None
            t_w = statistics.median(times_w) if times_w else None
            ratio = statistics.median(ratios_case) if ratios_case else None
            ratio_w = statistics.median(ratios_wall) if ratios_wall else None
            spread = (f"{min(ratios_case):.0f}..{max(ratios_case):.0f}" if ratios_case
                      else "-")
            diff = abs(e_s - e_b) if (e_s is not None and e_b is not None) else None
            print(f"{name:<12} {v0:>4g} {fmt(e_s, '.15f'):>20} {fmt(e_b, '.15f'):>20} "
                  f"{fmt(diff, '.2e'):>9} {fmt(nfev_s, ''):>11} {fmt(nfev_b, ''):>11} "
                  f"{fmt(t_s * 1e3, '.3f', ' ms'):>12} "
                  f"{fmt(t_b * 1e6 if t_b else None, '.1f', ' us'):>12} "
                  f"{fmt(ratio, '.0f'):>6} {spread:>11} "
                  f"{fmt(t_w * 1e6 if t_w else None, '.1f', ' us'):>10} {fmt(ratio_w, '.0f'):>6}")
            sys.stdout.flush()
            rows.append({"case": name, "v0": v0,
                         "ts_scipy": ts if ts is None or math.isfinite(ts) else None, "e_scipy": e_s,
                         "nfev_scipy": nfev_s, "t_scipy": t_s, "e_bwcl": e_b,
                         "nfev_bwcl": nfev_b, "t_bwcl": t_b, "ratio": ratio,
                         "ratios": ratios_case, "t_wall": t_w, "ratio_wall": ratio_w})
    ratios = sorted(r["ratio"] for r in rows if r["ratio"])
    if ratios:
        every = sorted(x for r in rows for x in r["ratios"])
        walls = sorted(r["ratio_wall"] for r in rows if r["ratio_wall"])
        print(f"ratio t_scipy/t_wall, per case: min {walls[0]:.0f}, "
              f"median {statistics.median(walls):.0f}, max {walls[-1]:.0f}")
        print(f"ratio t_scipy/t_bwcl, per case: min {ratios[0]:.0f}, "
              f"median {statistics.median(ratios):.0f}, max {ratios[-1]:.0f}; "
              f"all {len(every)} rounds: median {statistics.median(every):.0f}, "
              f"{sum(x >= 300 for x in every)} of {len(every)} at 300 or more")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, default=lambda x: None if x is None else str(x))
    for n in notes:
        print("note:", n)
    return 0


if __name__ == "__main__":
    sys.exit(main())
