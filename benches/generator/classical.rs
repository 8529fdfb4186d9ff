//! The classical laws' proved CoR beside the SHC model's (issue #33's floor: median time ≤ the
//! SHC model's on the same machine, side by side; width ≤ 1e-12): one thread, the cases
//! interleaved, the median of `--reps` runs each.
//!
//! ```text
//! cargo run --release --features bench --example classical -- [--reps 21]
//! ```

use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::hunt_crossley::HuntCrossley;
use bwcl::models::kelvin_voigt::KelvinVoigt;
use bwcl::models::linear_maxwell::LinearMaxwell;
use bwcl::models::scaling::nd_from_base;
use bwcl::models::{CollisionModel, ModelKind, NdParams, Shc};
use bwcl::observables::rigorous::rigorous_impact;
use inari::Interval;
use std::time::Instant;

fn iv(x: f64) -> Interval {
    Interval::try_from((x, x)).unwrap()
}

/// One proved CoR: (seconds, width of e).
fn run<M: CollisionModel<Interval, N>, const N: usize>(m: &M) -> (f64, f64) {
    let t = Instant::now();
    let r = rigorous_impact(m, &TaylorOptions::default()).expect("proved");
    (t.elapsed().as_secs_f64(), r.e.wid())
}

fn main() {
    let reps: usize = std::env::args()
        .skip_while(|a| a != "--reps")
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(21);
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build_global()
        .expect("one-thread pool");
    let b =
        NdParams::<Interval>::parse(ModelKind::Shc, "1.43,-1.42,0.632,0.00715,1.31,1.27").unwrap();
    let shc = Shc::new(nd_from_base(ModelKind::Shc, &b, &iv(1.0)).unwrap());
    let hooke = HuntCrossley::<Interval>::hooke();
    let hertz = HuntCrossley::hertz(iv(1.5)).unwrap();
    let hc = HuntCrossley::new(iv(0.75), iv(1.5)).unwrap();
    let kv = KelvinVoigt::new(iv(0.3)).unwrap();
    let lm = LinearMaxwell::new(iv(2.0)).unwrap();
    let names = [
        "SHC DSS v0 = 1",
        "Hooke",
        "Hertz n = 1.5",
        "Hunt–Crossley σ = 0.75, n = 1.5",
        "Kelvin–Voigt ζ = 0.3",
        "linear Maxwell c̃ = 2",
    ];
    let mut times = vec![Vec::new(); names.len()];
    let mut widths = vec![0.0; names.len()];
    for _ in 0..reps {
        let r = [
            run(&shc),
            run(&hooke),
            run(&hertz),
            run(&hc),
            run(&kv),
            run(&lm),
        ];
        for (i, (t, w)) in r.into_iter().enumerate() {
            times[i].push(t);
            widths[i] = w;
        }
    }
    let med = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let shc_t = med(&mut times[0].clone());
    println!("case\tmedian_ms\tratio_to_shc\twidth_e");
    for (i, n) in names.iter().enumerate() {
        let t = med(&mut times[i]);
        println!("{n}\t{:.3}\t{:.3}\t{:.2e}", t * 1e3, t / shc_t, widths[i]);
    }
}
