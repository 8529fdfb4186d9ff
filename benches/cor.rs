//! CoR benchmarks: one coefficient of restitution per iteration for the four Table 1 base
//! sets at v0 = 1, on the f64 DOP853 engine (`float_cor/*`, the paper's settings
//! rtol 1e-10, atol 1e-12, max_step 1e-2) and on the rigorous interval Taylor engine
//! (`rigorous_cor/*`, `TaylorOptions::default()`).
//!
//! Outside the timed loops each case prints once its RHS-evaluation count and steps (to
//! compare with SciPy's `solve_ivp(method="DOP853")`, see `benches/scipy_side_by_side.py`)
//! and the width of the rigorous e enclosure. `jet/*`: one order-16 jet on one repeated box
//! and on varying boxes (see [`jet`]). Run with
//! `cargo bench --features bench --bench cor`; the float/rigorous ratio is read from criterion's medians.

use std::hint::black_box;
use std::time::Duration;

use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::scaling::nd_from_base;
use bwcl::models::{CollisionModel, Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::rigorous::rigorous_impact;
use bwcl::observables::{FloatOptions, impact};
use criterion::{Criterion, criterion_group, criterion_main};

#[path = "../paper_repro/font.rs"]
mod font;
use inari::Interval;

/// (bench id, model, base set P* = B_b,Γ_b,κ,σ_b,n,p) of Table 1.
const CASES: [(&str, ModelKind, &str); 4] = [
    (
        "shc_dss_v0_1",
        ModelKind::Shc,
        "1.43,-1.42,0.632,0.00715,1.31,1.27",
    ),
    (
        "shc_dsa_v0_1",
        ModelKind::Shc,
        "0.63,-0.611,0.188,0.00594,1,2.02",
    ),
    (
        "maxwell_dss_v0_1",
        ModelKind::Maxwell,
        "0.655,-0.64,0.519,0.0118,1.94,2.28",
    ),
    (
        "maxwell_dsa_v0_1",
        ModelKind::Maxwell,
        "0.44,-0.418,0.113,0.00785,1.27,3.14",
    ),
];

fn nd_f64(kind: ModelKind, base: &str) -> NdParams<f64> {
    let base = NdParams::<f64>::parse(kind, base).expect("base set");
    nd_from_base(kind, &base, &1.0).expect("P(P*, 1)")
}

fn nd_interval(kind: ModelKind, base: &str) -> NdParams<Interval> {
    let base = NdParams::<Interval>::parse(kind, base).expect("base set");
    let v0 = inari::interval!(1.0, 1.0).unwrap();
    nd_from_base(kind, &base, &v0).expect("P(P*, 1)")
}

fn float_case<M: CollisionModel<f64, N>, const N: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: &str,
    model: M,
) {
    let opts = FloatOptions::default();
    let r = impact(&model, &opts).expect("float CoR");
    eprintln!(
        "[float_cor/{id}] e = {:.17e}, ts = {:?}, nfev = {}, steps accepted = {}, rejected = {}",
        r.e, r.ts, r.stats.nfev, r.stats.naccepted, r.stats.nrejected
    );
    g.bench_function(id, |b| {
        b.iter(|| impact(black_box(&model), black_box(&opts)).unwrap().e)
    });
}

fn rigorous_case<M: CollisionModel<Interval, N>, const N: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: &str,
    model: M,
) {
    let opts = TaylorOptions::default();
    let t0 = std::time::Instant::now();
    let r = rigorous_impact(&model, &opts);
    let dt = t0.elapsed();
    match &r {
        Ok(enc) => eprintln!(
            "[rigorous_cor/{id}] e in [{:.17e}, {:.17e}], e width = {:e}, ts width = {:e}, \
             pieces = {}, one call {:?}",
            enc.e.inf(),
            enc.e.sup(),
            enc.e.wid(),
            enc.ts.wid(),
            enc.flow.len(),
            dt
        ),
        Err(e) => eprintln!("[rigorous_cor/{id}] FAILED ({e}) after {dt:?}: timing the failure"),
    }
    g.bench_function(id, |b| {
        b.iter(|| rigorous_impact(black_box(&model), black_box(&opts)).is_ok())
    });
}

fn float_cor(c: &mut Criterion) {
    let mut g = c.benchmark_group("float_cor");
    g.warm_up_time(Duration::from_secs(1));
    g.measurement_time(Duration::from_secs(3));
    for (id, kind, base) in CASES {
        match kind {
            ModelKind::Shc => float_case(&mut g, id, Shc::new(nd_f64(kind, base))),
            ModelKind::Maxwell => float_case(&mut g, id, Maxwell::new(nd_f64(kind, base))),
        }
    }
    g.finish();
}

fn rigorous_cor(c: &mut Criterion) {
    let mut g = c.benchmark_group("rigorous_cor");
    // ~1 s per call: 10 samples of one call each, a short warm-up.
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(5));
    for (id, kind, base) in CASES {
        match kind {
            ModelKind::Shc => rigorous_case(&mut g, id, Shc::new(nd_interval(kind, base))),
            ModelKind::Maxwell => rigorous_case(&mut g, id, Maxwell::new(nd_interval(kind, base))),
        }
    }
    g.finish();
}

/// One order-16 jet of the SHC DSS field (v0 = 1) in the rigorous engine's jet arithmetic:
/// `jet/one_box` repeats one thin box, `jet/varying_boxes` cycles through 1024 boxes that
/// differ by up to 1e-6. The directed roundings decide by data which side to step; where the
/// inputs repeat, every such decision is predicted, so a micro-benchmark on one box hides what
/// a branch on them costs (84fa2d5: 6.4 µs on one box, 9.9 µs on varying boxes with the
/// branches, 6.9 µs without). The two should stay close.
fn jet(c: &mut Criterion) {
    use bwcl::arith::Enclosure;
    use bwcl::engines::taylor::tape::{Tape, Workspace};
    let (_, kind, base) = CASES[0];
    let m = Shc::new(nd_interval(kind, base));
    let tape = Tape::<Interval, 3>::record(|v| {
        let mut o = m.field(v).to_vec();
        o.push(m.force(v));
        o.push(m.velocity(v));
        o
    })
    .map(|c| c.to_jet());
    let around = [-0.5, -0.0331, 0.786];
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let boxes: Vec<[_; 3]> = (0..1024)
        .map(|_| {
            std::array::from_fn(|i| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                let x = around[i] + (seed >> 11) as f64 / (1u64 << 53) as f64 * 1e-6;
                Interval::try_from((x, x + 1e-13)).unwrap().to_jet()
            })
        })
        .collect();
    let mut ws = Workspace::default();
    let mut g = c.benchmark_group("jet");
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(2));
    g.bench_function("one_box", |b| {
        b.iter(|| black_box(tape.jet(black_box(&boxes[0]), 16, &mut ws).is_ok()))
    });
    let mut i = 0;
    g.bench_function("varying_boxes", |b| {
        b.iter(|| {
            i = (i + 1) % boxes.len();
            black_box(tape.jet(black_box(&boxes[i]), 16, &mut ws).is_ok())
        })
    });
    g.finish();
}

/// Criterion with its HTML report's plots when a font can be registered (plotters is built
/// with `ab_glyph` here, so text needs a registered TrueType font), without them otherwise.
fn config() -> Criterion {
    match font::init_font() {
        Ok(_) => Criterion::default(),
        Err(e) => {
            eprintln!("criterion plots off: {e}");
            Criterion::default().without_plots()
        }
    }
}

criterion_group! {
    name = benches;
    config = config();
    targets = float_cor, rigorous_cor, jet
}
criterion_main!(benches);
