#!/usr/bin/env python3
"""SciPy side by side: the CoR e of the four Table 1 base sets at v0 in {0.1, 1, 5}.

SciPy: solve_ivp(method="DOP853", rtol=1e-10, atol=1e-12, max_step=1e-2) on the
nondimensional models written here from the paper (NDBWSHCCM eq:BWSHCCM_nd; NDBWMCM
eq:BWMCM_nd with the output V = R' + W of eq:BWMCM_nd_output), parameters
P(P*, v0) = (B_b v0^(2n/(p+1)), Gamma_b v0^(2n/(p+1)), kappa, sigma_b v0^s, n, p) with
s = 1 (SHC) or (p-1)/(p+1) (Maxwell). Separation T_s = inf{T >= 0 : F <= 0 and V >= 0} is a
terminal event on g = max(F, -V) crossing zero downward (g(0) = max(0, 1) = 1; the event
ignores T = 0 anyway); e = V(T_s). t_scipy is the median of 5 runs of one solve_ivp call.

bwcl: `bwcl cor --model M --base P* --v0 v,v,...,v --format json` with REPEAT copies of the
speed in one call; t_bwcl per CoR = (median wall time of 3 such calls) / REPEAT. It INCLUDES
the process start-up and JSON output amortized over REPEAT CoRs (nothing is subtracted). By
default RAYON_NUM_THREADS=1 (single-threaded, like SciPy); pass --threads N to change it.
The binary is $BWCL_BIN, else target/release/bwcl at the repo root (built with
`cargo build --release` if missing).

The ratio column is t_scipy / t_bwcl per case (t_bwcl as above, i.e. with process start-up);
`cargo run --release --example results` (benches/results.rs) runs this script with --json and
adds the in-process bwcl time and the like-for-like ratio next to it.

Usage: python3 benches/scipy_side_by_side.py [--repeat 200] [--threads 1] [--no-bwcl]
       [--json OUT.json]
"""

import argparse
import json
import math
import os
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
SCIPY_RUNS, BWCL_RUNS = 5, 3

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


def scipy_cor(model, base, v0, solve_ivp):
    P = nd_params(model, base, v0)
    rhs, force, velocity, y0 = (shc_model if model == "shc" else maxwell_model)(P)

    def g(t, y):
        if t == 0.0:
            return 1.0
        return max(force(y), -velocity(y))

    g.terminal = True
    g.direction = -1

    def run():
        return solve_ivp(
            rhs, (0.0, HORIZON), y0, method="DOP853", rtol=RTOL, atol=ATOL,
            max_step=MAX_STEP, events=g,
        )

    times, sol = [], None
    for _ in range(SCIPY_RUNS):
        t0 = time.perf_counter()
        sol = run()
        times.append(time.perf_counter() - t0)
    if not sol.success:
        return None, None, sol.nfev, statistics.median(times), sol.message
    # nfev, accepted steps
    nf = f"{sol.nfev}/{len(sol.t) - 1}"
    if sol.t_events[0].size == 0:
        return math.inf, 0.0, nf, statistics.median(times), None
    ts = sol.t_events[0][0]
    e = velocity(sol.y_events[0][0])
    return ts, e, nf, statistics.median(times), None


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


def bwcl_cor(binary, model, base, v0, repeat, threads):
    """(e, nfev, seconds per CoR, error) from `bwcl cor`, REPEAT copies of v0 in one call."""
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    speeds = ",".join([repr(v0)] * repeat)
    cmd = [binary, "cor", "--model", model, "--base", base, "--v0", speeds, "--format", "json"]
    times, out = [], None
    for _ in range(BWCL_RUNS):
        t0 = time.perf_counter()
        r = subprocess.run(cmd, capture_output=True, text=True, env=env)
        times.append(time.perf_counter() - t0)
        if r.returncode != 0:
            return None, None, None, (r.stderr.strip() or f"exit {r.returncode}")[:200]
        out = r.stdout
    try:
        rows = json.loads(out)
        if isinstance(rows, dict):
            rows = rows.get("rows") or rows.get("results") or [rows]
        row = rows[0]
    except (ValueError, IndexError, KeyError, TypeError) as err:
        return None, None, None, f"unparsable JSON: {err}"
    if len(rows) != repeat:
        return None, None, None, f"expected {repeat} rows, got {len(rows)}"
    if row.get("error"):
        return None, row.get("nfev"), None, row["error"]
    e = row.get("e")
    nf = row.get("nfev")
    if nf is not None and row.get("steps") is not None:
        nf = f"{nf}/{row['steps']}"
    return e, nf, statistics.median(times) / repeat, None


def fmt(x, spec, unit=""):
    return "-" if x is None else format(x, spec) + unit


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=200, help="copies of v0 per bwcl call")
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
          f"atol={ATOL} max_step={MAX_STEP}; t_scipy = median of {SCIPY_RUNS} runs")
    if binary:
        print(f"bwcl = {binary}; t_bwcl = median of {BWCL_RUNS} calls / {args.repeat} CoRs per "
              f"call (includes process start-up amortized), RAYON_NUM_THREADS={args.threads}")
    head = (f"{'case':<12} {'v0':>4} {'e_scipy':>20} {'e_bwcl':>20} {'|diff|':>9} "
            f"{'nfev/st_sp':>11} {'nfev/st_bw':>11} {'t_scipy/CoR':>12} {'t_bwcl/CoR':>12} {'ratio':>8}")
    print(head)
    print("-" * len(head))
    notes = []
    rows = []
    for name, model, base in CASES:
        for v0 in SPEEDS:
            ts, e_s, nfev_s, t_s, err_s = scipy_cor(model, base, v0, solve_ivp)
            if err_s:
                notes.append(f"{name} v0={v0}: SciPy failed: {err_s}")
            e_b = nfev_b = t_b = None
            if binary:
                e_b, nfev_b, t_b, err_b = bwcl_cor(binary, model, base, v0, args.repeat,
                                                  args.threads)
                if err_b:
                    notes.append(f"{name} v0={v0}: bwcl: {err_b}")
            diff = abs(e_s - e_b) if (e_s is not None and e_b is not None) else None
            ratio = t_s / t_b if (t_s and t_b) else None
            print(f"{name:<12} {v0:>4g} {fmt(e_s, '.15f'):>20} {fmt(e_b, '.15f'):>20} "
                  f"{fmt(diff, '.2e'):>9} {fmt(nfev_s, ''):>11} {fmt(nfev_b, ''):>11} "
                  f"{fmt(t_s * 1e3 if t_s else None, '.3f', ' ms'):>12} "
                  f"{fmt(t_b * 1e6 if t_b else None, '.1f', ' us'):>12} "
                  f"{fmt(ratio, '.0f'):>8}")
            sys.stdout.flush()
            rows.append({"case": name, "v0": v0,
                         "ts_scipy": ts if ts is None or math.isfinite(ts) else None, "e_scipy": e_s,
                         "nfev_scipy": nfev_s, "t_scipy": t_s, "e_bwcl": e_b,
                         "nfev_bwcl": nfev_b, "t_bwcl": t_b, "ratio": ratio})
    ratios = sorted(r["ratio"] for r in rows if r["ratio"])
    if ratios:
        print(f"ratio t_scipy/t_bwcl (CLI): min {ratios[0]:.0f}, "
              f"median {statistics.median(ratios):.0f}, max {ratios[-1]:.0f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, default=lambda x: None if x is None else str(x))
    for n in notes:
        print("note:", n)
    return 0


if __name__ == "__main__":
    sys.exit(main())
