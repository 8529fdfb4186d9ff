//! Issue #15: the singular step across branch points, measured side by side with the Taylor
//! steps it replaces and with the f64 engine, on the 28 Table 1 cases (4 sets × v0 ∈ {0.1, 0.5,
//! 1, 2, 3, 4, 5}). One thread (a one-thread rayon pool for the rigorous engine); times are
//! medians of interleaved repetitions, each a batch of ≈ 20 ms.
//!
//! Three settings, interleaved: the singular step off, on without the start step
//! ([`TaylorOptions::singular_start`] off: the crossings only), and on (crossings and start).
//!
//! `cargo run --release --features bench --example singular` prints a Markdown table (pieces, widths, times,
//! ratios) for benches/RESULTS.md.

use bwcl::arith::Real;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::scaling::nd_from_base;
use bwcl::models::{CollisionModel, Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::rigorous::rigorous_impact;
use bwcl::observables::{FloatOptions, impact};
use inari::Interval;
use std::hint::black_box;
use std::time::Instant;

const SPEEDS: [f64; 7] = [0.1, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0];

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Seconds per call, over a batch of n calls.
fn per_call(n: usize, mut f: impl FnMut()) -> f64 {
    let t = Instant::now();
    for _ in 0..n {
        f();
    }
    t.elapsed().as_secs_f64() / n as f64
}

struct Row {
    pieces: [usize; 3],
    e_wid: [f64; 3],
    ts_wid: [f64; 3],
    time: [f64; 3],
    f64_time: f64,
    err: Option<String>,
}

fn measure<Mf, Mi, const N: usize>(mf: &Mf, mi: &Mi, reps: usize) -> Row
where
    Mf: CollisionModel<f64, N>,
    Mi: CollisionModel<Interval, N> + Sync,
{
    let on = TaylorOptions::default();
    let off = TaylorOptions {
        singular: false,
        ..TaylorOptions::default()
    };
    let cross = TaylorOptions {
        singular_start: false,
        ..TaylorOptions::default()
    };
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let fo = FloatOptions::default();
    let mut row = Row {
        pieces: [0; 3],
        e_wid: [f64::NAN; 3],
        ts_wid: [f64::NAN; 3],
        time: [f64::NAN; 3],
        f64_time: f64::NAN,
        err: None,
    };
    for (k, o) in [&off, &cross, &on].into_iter().enumerate() {
        match one.install(|| rigorous_impact(mi, o)) {
            Ok(e) => {
                row.pieces[k] = e.flow.len();
                row.e_wid[k] = e.e.wid();
                row.ts_wid[k] = e.ts.wid();
            }
            Err(e) => row.err = Some(format!("{}: {e}", ["off", "crossings", "on"][k])),
        }
    }
    if row.err.is_some() {
        return row;
    }
    let t1 = per_call(1, || {
        black_box(one.install(|| rigorous_impact(mi, &on)).ok());
    });
    let nb = ((0.02 / t1).ceil() as usize).clamp(1, 1000);
    let tf1 = per_call(5, || {
        black_box(impact(mf, &fo).ok());
    });
    let nbf = ((0.02 / tf1).ceil() as usize).clamp(1, 100_000);
    let (mut a, mut c, mut b, mut f) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for _ in 0..reps {
        a.push(per_call(nb, || {
            black_box(one.install(|| rigorous_impact(mi, &off)).ok());
        }));
        c.push(per_call(nb, || {
            black_box(one.install(|| rigorous_impact(mi, &cross)).ok());
        }));
        b.push(per_call(nb, || {
            black_box(one.install(|| rigorous_impact(mi, &on)).ok());
        }));
        f.push(one.install(|| {
            per_call(nbf, || {
                black_box(impact(mf, &fo).ok());
            })
        }));
    }
    row.time = [median(&mut a), median(&mut c), median(&mut b)];
    row.f64_time = median(&mut f);
    row
}

fn main() {
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(7);
    println!(
        "| set | v0 | pieces off → crossings → +start | e width crossings → +start | T_s width crossings → +start | rigorous off | crossings | +start | +start/crossings | f64 | +start/f64 |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let (mut offs, mut before, mut after, mut ratios, mut gains) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let (mut wider_e, mut wider_ts) = (0, 0);
    for (name, kind, base) in bwcl::models::params::TABLE1 {
        let pb = NdParams::<Interval>::parse(kind, base).expect("base set");
        let pf = NdParams::<f64>::parse(kind, base).expect("base set");
        for v0 in SPEEDS {
            let v0i = <Interval as Real>::parse_decimal(&format!("{v0}")).expect("v0");
            let ni = nd_from_base(kind, &pb, &v0i).expect("P(P*, v0)");
            let nf = nd_from_base(kind, &pf, &v0).expect("P(P*, v0)");
            let r = match kind {
                ModelKind::Shc => measure(&Shc::new(nf), &Shc::new(ni), reps),
                ModelKind::Maxwell => measure(&Maxwell::new(nf), &Maxwell::new(ni), reps),
            };
            if let Some(e) = &r.err {
                println!("| {name} | {v0} | failed: {e} | | | | | | | | |");
                continue;
            }
            if r.e_wid[2] > r.e_wid[1] {
                wider_e += 1;
            }
            if r.ts_wid[2] > r.ts_wid[1] {
                wider_ts += 1;
            }
            offs.push(r.time[0]);
            before.push(r.time[1]);
            after.push(r.time[2]);
            gains.push(r.time[2] / r.time[1]);
            ratios.push(r.time[2] / r.f64_time);
            println!(
                "| {name} | {v0} | {} → {} → {} | {:.4e} → {:.4e} | {:.4e} → {:.4e} | {:.2} ms | {:.2} ms | {:.2} ms | {:.3} | {:.1} µs | {:.0}× |",
                r.pieces[0],
                r.pieces[1],
                r.pieces[2],
                r.e_wid[1],
                r.e_wid[2],
                r.ts_wid[1],
                r.ts_wid[2],
                r.time[0] * 1e3,
                r.time[1] * 1e3,
                r.time[2] * 1e3,
                r.time[2] / r.time[1],
                r.f64_time * 1e6,
                r.time[2] / r.f64_time
            );
        }
    }
    println!(
        "\nmedian rigorous time: off {:.2} ms, crossings {:.2} ms, +start {:.2} ms; median of the per-case ratios +start/crossings {:.3}; median +start/f64 {:.0}×; with the start step e wider in {wider_e}, T_s wider in {wider_ts} of {} cases",
        median(&mut offs) * 1e3,
        median(&mut before) * 1e3,
        median(&mut after) * 1e3,
        median(&mut gains),
        median(&mut ratios),
        before.len()
    );
}
