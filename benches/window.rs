//! Window benchmarks: the flow of SHC DSS and Maxwell DSS (Table 1, v0 = 1) over [0.5, 1.5]
//! enclosed by the rigorous engine's [`Window::enclose`] (order 16, `TaylorOptions` defaults),
//! from the f64 state at 0.5 as a thin start (`window/*_thin`) and from a box of radius 1e-8
//! around it (`window/*_box1e-8`): the bwcl side of the kv comparison (benches/peers/run.py,
//! whose interleaved rounds give the numbers in benches/RESULTS.md). The field is recorded
//! once, outside the timed loop. Each case prints its steps and widths once. Run with
//! `cargo bench --features bench --bench window`.

use std::hint::black_box;
use std::time::Duration;

use bwcl::arith::{Enclosure, Real};
use bwcl::engines::taylor::TaylorOptions;
use bwcl::engines::taylor::window::Window;
use bwcl::models::params::TABLE1;
use bwcl::models::scaling::nd_from_base;
use bwcl::models::{CollisionModel, Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::FloatOptions;
use bwcl::observables::trajectory::{Units, trajectory};
use criterion::{Criterion, criterion_group, criterion_main};
use inari::Interval;

#[path = "../paper_repro/font.rs"]
mod font;

const T0: f64 = 0.5;
const T1: f64 = 1.5;

/// 𝓟(P*, 1) of a Table 1 set, as f64 and as intervals.
fn params(kind: ModelKind, base: &str) -> (NdParams<f64>, NdParams<Interval>) {
    let b = NdParams::<f64>::parse(kind, base).expect("base set");
    let bi = NdParams::<Interval>::parse(kind, base).expect("base set");
    let one = Interval::from_exact_f64(1.0);
    (
        nd_from_base(kind, &b, &1.0).expect("P(P*, 1)"),
        nd_from_base(kind, &bi, &one).expect("P(P*, 1)"),
    )
}

fn case<F: CollisionModel<f64, N>, M: CollisionModel<Interval, N>, const N: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: &str,
    float: F,
    model: M,
) {
    let samples = trajectory(
        &float,
        &FloatOptions::default(),
        Some(T0),
        2,
        &Units::Nondimensional,
    )
    .expect("the f64 state at t0");
    let x: [f64; N] = samples[1].state.clone().try_into().expect("N states");
    let window = Window::new(&model);
    let opts = TaylorOptions::default();
    for (suffix, radius) in [("thin", 0.0), ("box1e-8", 1e-8)] {
        let r = Interval::from_bounds(-radius, radius).expect("a radius");
        let x0: [Interval; N] = std::array::from_fn(|i| Interval::from_exact_f64(x[i]) + r);
        let name = format!("{id}_{suffix}");
        match window.enclose(x0, T0, T1, &opts) {
            Ok(w) => eprintln!(
                "[window/{name}] steps {}, widths at {T1}: {:?}",
                w.steps,
                w.x1.iter().map(|c| c.wid()).collect::<Vec<_>>()
            ),
            Err(e) => eprintln!("[window/{name}] FAILED ({e}): timing the failure"),
        }
        g.bench_function(&name, |b| {
            b.iter(|| {
                window
                    .enclose(black_box(x0), T0, T1, black_box(&opts))
                    .is_ok()
            })
        });
    }
}

fn window(c: &mut Criterion) {
    let mut g = c.benchmark_group("window");
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(3));
    for (name, kind, base) in TABLE1.into_iter().filter(|c| c.0.ends_with("DSS")) {
        let id = name.to_lowercase().replace(' ', "_");
        let (pf, pi) = params(kind, base);
        match kind {
            ModelKind::Shc => case(&mut g, &id, Shc::new(pf), Shc::new(pi)),
            ModelKind::Maxwell => case(&mut g, &id, Maxwell::new(pf), Maxwell::new(pi)),
        }
    }
    g.finish();
}

/// Criterion with its HTML report's plots when a font can be registered (as in cor.rs).
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
    targets = window
}
criterion_main!(benches);
