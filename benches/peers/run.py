#!/usr/bin/env python3
"""bwcl against kv over a window: builds both sides, runs every configuration interleaved for R
rounds (one thread each) and regenerates the section "## kv side by side (issue #32)" of
benches/RESULTS.md (between <!-- kv:begin --> and <!-- kv:end -->; the rest is left as is).

    python3 benches/peers/run.py [--rounds 7] [--min-ms 300] [--no-kv] [--no-write]

The cases: SHC DSS and Maxwell DSS (Table 1) at v0 = 1 over [0.5, 1.5], from the f64 state at
0.5 (exact doubles, printed by `window_bwcl start`) and from a box of radius 1e-8 around it;
bwcl's `Window::enclose` (order 16, the engine's defaults) against kv's odelong_maffine,
odelong_maffine2 and odelong_qr_lohner (order 16, kv's defaults otherwise). Each run is one
process that repeats the integration for at least --min-ms and reports the wall and CPU time
per integration; a round runs every configuration once (the order rotated from round to
round), and the ratios bwcl/kv are taken within each round.

kv's headers are read from $KV_DIR (default: ../shared/peers/kv/kv-src beside the repository);
kv_window is built with `g++ -O3 -DNDEBUG -DKV_FASTROUND` and needs Boost's headers, which are
installed with apt-get (libboost-dev) when missing. Without g++ or Boost the kv side is skipped
and said so, and only bwcl's rows are produced. Python 3 standard library only.
"""

import argparse
import datetime
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
RESULTS = os.path.join(REPO, "benches", "RESULTS.md")
BEGIN, END = "<!-- kv:begin -->", "<!-- kv:end -->"
CXXFLAGS = ["-O3", "-DNDEBUG", "-DKV_FASTROUND"]
CASES = [("shc_dss", "SHC DSS"), ("maxwell_dss", "Maxwell DSS")]
RADII = [0.0, 1e-8]
KV_METHODS = ["maffine", "maffine2", "qr_lohner"]
T0, T1, ORDER = "0.5", "1.5", 16


def sh(argv, **kw):
    return subprocess.run(argv, check=True, text=True, capture_output=True, **kw).stdout


def boost_present(kv_dir):
    """Whether a program including kv's ODE header compiles far enough to find Boost."""
    with tempfile.TemporaryDirectory() as d:
        src = os.path.join(d, "t.cc")
        with open(src, "w") as f:
            f.write("#include <boost/numeric/ublas/vector.hpp>\nint main() { return 0; }\n")
        r = subprocess.run(["g++", "-fsyntax-only", "-I", kv_dir, src], capture_output=True)
        return r.returncode == 0


def install_boost():
    """apt-get update, then apt-get install -y libboost-dev (Debian's Boost headers)."""
    if not shutil.which("apt-get"):
        return "no apt-get"
    sudo = [] if os.geteuid() == 0 else (["sudo", "-n"] if shutil.which("sudo") else None)
    if sudo is None:
        return "not root and no sudo"
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    for argv in (["apt-get", "update"], ["apt-get", "install", "-y", "libboost-dev"]):
        print("+", " ".join(sudo + argv), flush=True)
        r = subprocess.run(sudo + argv, env=env, capture_output=True, text=True)
        if r.returncode != 0:
            return f"`{' '.join(argv)}` failed: {r.stderr.strip().splitlines()[-1:]}"
    return None


def build_kv(kv_dir, out_dir):
    """Builds kv_window; returns (path, compiler line) or (None, why not)."""
    if not shutil.which("g++"):
        return None, "no g++ on this machine"
    if not os.path.isfile(os.path.join(kv_dir, "kv", "ode-maffine.hpp")):
        return None, f"no kv headers in KV_DIR = {kv_dir}"
    if not boost_present(kv_dir):
        why = install_boost()
        if why or not boost_present(kv_dir):
            return None, f"Boost's headers are missing and could not be installed ({why})"
    version = "?"
    for line in open(os.path.join(kv_dir, "kv", "version.hpp")) if os.path.isfile(os.path.join(kv_dir, "kv", "version.hpp")) else []:
        if "KV_VERSION_STRING" in line:
            version = line.split()[-1].strip('"')
    exe = os.path.join(out_dir, "kv_window")
    argv = ["g++", *CXXFLAGS, "-I", kv_dir, os.path.join(HERE, "kv_window.cc"), "-o", exe]
    print("+", " ".join(argv), flush=True)
    sh(argv)
    return exe, f"kv {version}, " + sh(["g++", "--version"]).splitlines()[0]


def build_bwcl(target):
    argv = ["cargo", "build", "--release", "--features", "bench", "--example", "window_bwcl"]
    print("+", " ".join(argv), flush=True)
    subprocess.run(argv, check=True, cwd=REPO, env=dict(os.environ, CARGO_TARGET_DIR=target))
    return os.path.join(target, "release", "examples", "window_bwcl")


def keyvals(text):
    """The key value lines of window_bwcl / kv_window."""
    out = {"x": []}
    for line in text.splitlines():
        k, _, v = line.partition(" ")
        if k == "x":
            _, lo, hi = v.split()
            out["x"].append((float.fromhex(lo), float.fromhex(hi)))
        else:
            out[k] = v
    return out


def run_one(argv):
    env = dict(os.environ, RAYON_NUM_THREADS="1", OMP_NUM_THREADS="1")
    r = subprocess.run(argv, env=env, capture_output=True, text=True)
    kv = keyvals(r.stdout)
    if r.returncode != 0 or "failed" in kv:
        return {"failed": kv.get("failed", r.stderr.strip()[-300:] or f"exit {r.returncode}")}
    return {
        "wall": float(kv["wall_per_run_s"]),
        "cpu": float(kv["cpu_per_run_s"]),
        "steps": int(kv["steps"]),
        "x": kv["x"],
    }


def fmt_time(s):
    return f"{s * 1e3:.3g} ms" if s >= 1e-3 else f"{s * 1e6:.3g} µs"


def machine():
    model = "?"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} CPUs, {platform.system()} {platform.release()}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--min-ms", type=float, default=300.0)
    ap.add_argument("--no-kv", action="store_true", help="bwcl's rows only")
    ap.add_argument("--no-write", action="store_true", help="print the section, leave RESULTS.md")
    a = ap.parse_args()

    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(REPO, "target"))
    kv_dir = os.environ.get("KV_DIR", os.path.join(os.path.dirname(REPO), "shared", "peers", "kv", "kv-src"))
    out_dir = os.path.join(target, "peers")
    os.makedirs(out_dir, exist_ok=True)
    kv_exe, kv_note = (None, "the kv side was not asked for (--no-kv)") if a.no_kv else build_kv(kv_dir, out_dir)
    if kv_exe is None:
        print(f"kv side skipped: {kv_note}", flush=True)
    bwcl_exe = build_bwcl(target)

    # the start states and the linearized widths, from the f64 engine
    starts = {}
    for case, _ in CASES:
        s = keyvals(sh([bwcl_exe, "start", case, f"t0={T0}", f"t1={T1}"]))
        starts[case] = s
    # the configurations: (case, radius, engine label, argv)
    configs = []
    opts = lambda r: [f"radius={r!r}", f"order={ORDER}", f"min_ms={a.min_ms!r}"]
    for case, _ in CASES:
        s = starts[case]
        for r in RADII:
            configs.append((case, r, "bwcl", [bwcl_exe, "run", case, s["start"], f"t0={T0}", f"t1={T1}", *opts(r)]))
            if kv_exe:
                for m in KV_METHODS:
                    argv = [kv_exe, s["model"], m, s["params"], T0, T1, s["start"], *opts(r)]
                    configs.append((case, r, f"kv {m}", argv))

    results = {i: [] for i in range(len(configs))}
    loads = []
    for rnd in range(a.rounds):
        loads.append(open("/proc/loadavg").read().split()[0])
        order = list(range(len(configs)))
        k = rnd % len(order)
        for i in order[k:] + order[:k]:
            res = run_one(configs[i][3])
            results[i].append(res)
            c = configs[i]
            tail = res.get("failed") or f"{fmt_time(res['wall'])}, {res['steps']} steps"
            print(f"round {rnd + 1}/{a.rounds}  {c[0]:12s} r={c[1]:g}  {c[2]:13s} {tail}", flush=True)
    loads.append(open("/proc/loadavg").read().split()[0])

    section, alarms = report(a, configs, results, starts, loads, kv_note, kv_exe is not None)
    print(section)
    for m in alarms:
        print("!" * 20, m, "!" * 20, file=sys.stderr)
    if not a.no_write:
        write_section(section)
        print(f"wrote the section to {RESULTS}")
    return 1 if alarms else 0


def report(a, configs, results, starts, loads, kv_note, have_kv):
    alarms = []
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    try:
        commit = sh(["git", "-C", REPO, "rev-parse", "--short", "HEAD"]).strip()
        dirty = sh(["git", "-C", REPO, "status", "--porcelain", "--untracked-files=no"]).strip()
        commit += " (with uncommitted changes)" if dirty else ""
    except (subprocess.CalledProcessError, FileNotFoundError):
        commit = "?"
    rustc = sh(["rustc", "--version"]).strip()
    lines = [
        BEGIN,
        "## kv side by side (issue #32)",
        "",
        f"Regenerated by `python3 benches/peers/run.py` (`--rounds {a.rounds}`) on {now}, bwcl {commit}: "
        f"{machine()}; load average (1 min) at each round's start and at the end: {', '.join(loads)}.",
        f"kv: {'`g++ ' + ' '.join(CXXFLAGS) + '` (' + kv_note + ')' if have_kv else 'not run: ' + kv_note}; "
        f"bwcl: {rustc}, `cargo build --release`.",
        "",
        f"The flow of each Table 1 set at v0 = 1 over the window [{T0}, {T1}] (every switching component keeps its sign "
        "there: kv gets the field with the signs substituted, benches/peers/kv_window.cc), from the f64 state at "
        f"{T0} (DOP853, rtol 1e-13) as exact doubles — a thin start, and a box of radius 1e-8 around it. bwcl: "
        f"`Window::enclose` (src/engines/taylor/window.rs; order {ORDER}, the engine's defaults: mean-value form, "
        f"the set carried as an affine set); kv: odelong_maffine, odelong_maffine2 and odelong_qr_lohner at order {ORDER} (kv's defaults "
        "otherwise). One thread each; a process repeats its integration for at least "
        f"{a.min_ms:g} ms, time = wall time per integration, median over the rounds (CPU time beside it); "
        "bwcl/kv = the ratio of the two within each round, median (min–max). Widths: of each component at "
        f"{T1}; bwcl/kv widths: per component. The linearized optimum: 2r·Σ_j |J_ij| (J the f64 Jacobian of "
        "the flow by central differences) — the widths of the linearized image of the box.",
        "",
        "| case | method | steps | widths at t1 | bwcl/kv widths | time per run | CPU per run | bwcl/kv time (median, min–max) | bwcl/kv CPU |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    by_key = {(c[0], c[1], c[2]): results[i] for i, c in enumerate(configs)}
    for case, title in CASES:
        names = starts[case]["names"]
        for r in RADII:
            label = f"{title} ({names.replace(',', ', ')}), " + ("thin" if r == 0 else f"box r = {r:g}")
            engines = [c[2] for c in configs if c[0] == case and c[1] == r]
            bw = by_key.get((case, r, "bwcl"), [])
            for e in engines:
                rs = by_key[(case, r, e)]
                fails = [x["failed"] for x in rs if "failed" in x]
                if fails:
                    lines.append(f"| {label} | {e} | — | failed: {fails[0]} | | | | | |")
                    alarms.append(f"{title} r={r:g} {e} failed: {fails[0]}")
                    continue
                first = rs[0]
                if any(x["x"] != first["x"] for x in rs):
                    alarms.append(f"{title} r={r:g} {e}: the enclosure differs between rounds")
                widths = [hi - lo for lo, hi in first["x"]]
                wall = statistics.median(x["wall"] for x in rs)
                cpu = statistics.median(x["cpu"] for x in rs)
                wr = cr = wratio = ""
                if e != "bwcl" and bw and all("failed" not in x for x in bw):
                    q = [b["wall"] / k["wall"] for b, k in zip(bw, rs)]
                    qc = [b["cpu"] / k["cpu"] for b, k in zip(bw, rs)]
                    wr = f"{statistics.median(q):.3g} ({min(q):.3g}–{max(q):.3g})"
                    cr = f"{statistics.median(qc):.3g}"
                    bwid = [hi - lo for lo, hi in bw[0]["x"]]
                    wratio = ", ".join(f"{b / w:.3g}" if w > 0 else "∞" for b, w in zip(bwid, widths))
                lines.append(
                    f"| {label} | {e} | {first['steps']} | {', '.join(f'{w:.3g}' for w in widths)} | {wratio} | "
                    f"{fmt_time(wall)} | {fmt_time(cpu)} | {wr} | {cr} |"
                )
            if r > 0:
                lin = [float(v) * r for v in starts[case]["lin_width_per_radius"].split(",")]
                lines.append(f"| {label} | linearized optimum | | {', '.join(f'{w:.4g}' for w in lin)} | | | | | |")
            # every pair of enclosures of the same case must intersect, component by component
            ok = [(e, by_key[(case, r, e)][0]["x"]) for e in engines if "failed" not in by_key[(case, r, e)][0]]
            for i in range(len(ok)):
                for j in range(i + 1, len(ok)):
                    for k, ((l1, h1), (l2, h2)) in enumerate(zip(ok[i][1], ok[j][1])):
                        if max(l1, l2) > min(h1, h2):
                            alarms.append(
                                f"disjoint! {title} r={r:g} {names.split(',')[k]}: {ok[i][0]} [{l1!r}, {h1!r}] "
                                f"and {ok[j][0]} [{l2!r}, {h2!r}]"
                            )
    lines.append("")
    if any(m.startswith("disjoint!") for m in alarms):
        lines.append("**disjoint!** Some enclosures do not intersect: " + "; ".join(m for m in alarms if m.startswith("disjoint!")))
    else:
        lines.append("Every pair of enclosures of the same case intersects, component by component.")
    others = [m for m in alarms if not m.startswith("disjoint!")]
    if others:
        lines.append("")
        lines.append("Warnings: " + "; ".join(others) + ".")
    lines.append(END)
    return "\n".join(lines), alarms


def write_section(section):
    text = open(RESULTS).read() if os.path.exists(RESULTS) else ""
    if BEGIN in text and END in text:
        a, b = text.index(BEGIN), text.index(END) + len(END)
        text = text[:a] + section + text[b:]
    else:
        text = text.rstrip("\n") + "\n\n" + section + "\n"
    with open(RESULTS, "w") as f:
        f.write(text)


if __name__ == "__main__":
    sys.exit(main())
