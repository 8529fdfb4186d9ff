//! The bwcl side of the kv comparison (benches/peers/run.py): the flow of a Table 1 set at
//! v0 = 1 over a window [t0, t1] enclosed by [`Window::enclose`], from the same exact start
//! state that kv_window reads.
//!
//! ```text
//! window_bwcl start <case> [t0=0.5] [t1=1.5]
//! window_bwcl run <case> <x1,..,xN> [t0=0.5] [t1=1.5] [radius=0] [order=16] [reps=0] [min_ms=300]
//! ```
//!
//! `<case>`: a Table 1 set, e.g. `shc_dss`, `maxwell_dss` (its name in lower case, `_` for the
//! space). `start` prints the model, the parameters as written (𝓟(P*, 1) = P*), the f64 state
//! at t0 (DOP853 at rtol 1e-13 from the model's start, as decimals that read back to the same
//! doubles) and `lin_width_per_radius`: 2·Σ_j |J_ij| for the f64 Jacobian J of the flow from
//! t0 to t1 (central differences), the widths at t1 of the linearized image of a box of radius
//! 1 — the linearized optimum for a small box. `run` prints the same keys as kv_window
//! (`engine`, `steps`, `reps`, `wall_per_run_s`, `cpu_per_run_s`, `x <i> <lo> <hi>` in hex
//! floats); the field is recorded once, outside the timed runs. Run it with
//! `RAYON_NUM_THREADS=1` for one thread.

use std::time::Instant;

use bwcl::arith::{Enclosure, Real};
use bwcl::engines::dop853::{self, Options};
use bwcl::engines::taylor::TaylorOptions;
use bwcl::engines::taylor::window::Window;
use bwcl::models::params::TABLE1;
use bwcl::models::scaling::nd_from_base;
use bwcl::models::{BoucWenModel, CollisionModel, Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::FloatOptions;
use bwcl::observables::trajectory::{Units, trajectory};
use inari::Interval;

/// The f64 integrations of `start`: tight, so that J is good to many digits.
fn tight() -> Options {
    Options {
        rtol: 1e-13,
        atol: 1e-16,
        ..Options::default()
    }
}

/// (name, model, parameters as written) of a Table 1 set by its case name.
fn case(name: &str) -> (&'static str, ModelKind, &'static str) {
    TABLE1
        .into_iter()
        .find(|c| c.0.to_lowercase().replace(' ', "_") == name)
        .unwrap_or_else(|| fail(&format!("no Table 1 set '{name}'")))
}

fn fail(why: &str) -> ! {
    println!("failed {why}");
    std::process::exit(1)
}

/// `key=value` options after the positional arguments.
fn option(args: &[String], key: &str, default: f64) -> f64 {
    let mut v = default;
    for a in args {
        match a.split_once('=') {
            Some((k, x)) if k == key => {
                v = x
                    .parse()
                    .unwrap_or_else(|_| fail(&format!("{key}: not a number '{x}'")))
            }
            Some((k, _)) if ["t0", "t1", "radius", "order", "reps", "min_ms"].contains(&k) => {}
            _ => fail(&format!("unknown option '{a}'")),
        }
    }
    v
}

/// The bits of x as a hex float (`-0x1.f1c3p-2`), read back exactly by C's strtod and
/// Python's float.fromhex.
fn hex(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    let sign = if x.is_sign_negative() { "-" } else { "" };
    let bits = x.to_bits();
    let (e, m) = (((bits >> 52) & 0x7ff) as i64, bits & ((1 << 52) - 1));
    match e {
        0 if m == 0 => format!("{sign}0x0p+0"),
        0 => format!("{sign}0x0.{m:013x}p-1022"),
        _ => format!("{sign}0x1.{m:013x}p{:+}", e - 1023),
    }
}

/// The f64 flow from `x` at t0 to t1.
fn flow_f64<M: CollisionModel<f64, N>, const N: usize>(
    m: &M,
    x: [f64; N],
    t0: f64,
    t1: f64,
) -> [f64; N] {
    dop853::integrate(|_t, y: &[f64; N]| m.field(y), t0, x, t1, tight())
        .unwrap_or_else(|e| fail(&format!("f64 flow: {e:?}")))
        .0
}

fn start<M: CollisionModel<f64, N>, const N: usize>(m: &M, t0: f64, t1: f64) {
    let opts = FloatOptions {
        ode: tight(),
        ..FloatOptions::default()
    };
    let samples = trajectory(m, &opts, Some(t0), 2, &Units::Nondimensional)
        .unwrap_or_else(|e| fail(&format!("f64 trajectory: {e:?}")));
    let x: [f64; N] = samples[1].state.clone().try_into().expect("N states");
    // J by central differences, column by column
    let mut lin = [0.0_f64; N];
    for j in 0..N {
        let d = 1e-5 * x[j].abs().max(1.0);
        let (mut up, mut down) = (x, x);
        up[j] += d;
        down[j] -= d;
        let (a, b) = (flow_f64(m, up, t0, t1), flow_f64(m, down, t0, t1));
        for i in 0..N {
            lin[i] += 2.0 * ((a[i] - b[i]) / (up[j] - down[j])).abs();
        }
    }
    let list = |v: &[f64]| {
        v.iter()
            .map(|c| format!("{c:?}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    println!("names {}", M::STATE_NAMES.join(","));
    println!("start {}", list(&x));
    println!("lin_width_per_radius {}", list(&lin));
}

/// CPU time of all the threads of this process (s): the first field of each task's schedstat.
fn cpu_seconds() -> f64 {
    let tasks = std::fs::read_dir("/proc/self/task").unwrap_or_else(|e| fail(&format!("{e}")));
    let ns: u64 = tasks
        .filter_map(|t| std::fs::read_to_string(t.ok()?.path().join("schedstat")).ok())
        .filter_map(|s| s.split_whitespace().next()?.parse::<u64>().ok())
        .sum();
    ns as f64 * 1e-9
}

fn run<M: BoucWenModel<Interval, N>, const N: usize>(
    m: &M,
    xs: &[f64],
    t0: f64,
    t1: f64,
    args: &[String],
) {
    let radius = option(args, "radius", 0.0);
    let order = option(args, "order", 16.0) as usize;
    let reps = option(args, "reps", 0.0) as usize;
    let min_ms = option(args, "min_ms", 300.0);
    if xs.len() != N {
        fail(&format!("want {N} states ({})", M::STATE_NAMES.join(",")));
    }
    let r = Interval::from_bounds(-radius, radius).unwrap_or_else(|| fail("radius"));
    let x0: [Interval; N] = std::array::from_fn(|i| Interval::from_exact_f64(xs[i]) + r);
    let opts = TaylorOptions {
        order,
        ..TaylorOptions::default()
    };
    let window = Window::new(m);
    let once = || {
        window
            .enclose(x0, t0, t1, &opts)
            .unwrap_or_else(|e| fail(&e.to_string()))
    };
    let out = once();
    let (c0, w0) = (cpu_seconds(), Instant::now());
    let mut n = 0usize;
    while {
        std::hint::black_box(once());
        n += 1;
        if reps > 0 {
            n < reps
        } else {
            w0.elapsed().as_secs_f64() * 1e3 < min_ms
        }
    } {}
    let wall = w0.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - c0;
    println!(
        "engine bwcl {}",
        if opts.qr { "taylor_qr" } else { "taylor" }
    );
    println!("model {}", M::KIND.name());
    println!("order {order}");
    println!("radius {}", hex(radius));
    println!("steps {}", out.steps);
    println!("reps {n}");
    println!("wall_per_run_s {:.6e}", wall / n as f64);
    println!("cpu_per_run_s {:.6e}", cpu / n as f64);
    for (i, c) in out.x1.iter().enumerate() {
        println!("x {i} {} {}", hex(c.inf()), hex(c.sup()));
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: window_bwcl start <case> [t0=] [t1=] | run <case> <x1,..,xN> [t0=] [t1=] [radius=] [order=] [reps=] [min_ms=]";
    let (mode, name) = match (args.first(), args.get(1)) {
        (Some(m), Some(c)) => (m.as_str(), c.as_str()),
        _ => {
            eprintln!("{usage}");
            std::process::exit(2)
        }
    };
    let (_, kind, base) = case(name);
    let rest = &args[if mode == "run" { 3 } else { 2 }.min(args.len())..];
    let (t0, t1) = (option(rest, "t0", 0.5), option(rest, "t1", 1.5));
    match mode {
        "start" => {
            let b = NdParams::<f64>::parse(kind, base).unwrap_or_else(|e| fail(&e.0));
            let p = nd_from_base(kind, &b, &1.0).unwrap_or_else(|e| fail(&e.0));
            println!("model {}", kind.name());
            println!("params {base}");
            println!("t0 {t0:?}");
            println!("t1 {t1:?}");
            match kind {
                ModelKind::Shc => start(&Shc::new(p), t0, t1),
                ModelKind::Maxwell => start(&Maxwell::new(p), t0, t1),
            }
        }
        "run" => {
            let xs: Vec<f64> = args
                .get(2)
                .unwrap_or_else(|| fail(usage))
                .split(',')
                .map(|s| s.parse().unwrap_or_else(|_| fail(&format!("state '{s}'"))))
                .collect();
            let b = NdParams::<Interval>::parse(kind, base).unwrap_or_else(|e| fail(&e.0));
            let one = Interval::from_exact_f64(1.0);
            let p = nd_from_base(kind, &b, &one).unwrap_or_else(|e| fail(&e.0));
            match kind {
                ModelKind::Shc => run(&Shc::new(p), &xs, t0, t1, rest),
                ModelKind::Maxwell => run(&Maxwell::new(p), &xs, t0, t1, rest),
            }
        }
        _ => fail(usage),
    }
}
