//! The second derivatives over a range of v0 (issue #32 item 4, `observables::curvature`):
//! per Table 1 set and piece width w about v0, the widths of [e″] and [T_s″], the time of the
//! second-order run beside the first-order slope run (`slopes_over_set`) on the same piece,
//! medians of `--reps` runs on one thread.
//!
//! ```text
//! cargo run --release --features bench --example curvature -- [--reps N] [--v0 V] [--w W,W,..]
//! ```
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::NdParams;
use bwcl::models::params::TABLE1;
use bwcl::observables::band_second::{InterpOptions, prove_band_second};
use bwcl::observables::curvature::curvature_over_range;
use bwcl::observables::sets::{Inputs, slopes_over_set};
use inari::Interval;
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let opt = |k: &str| {
        args.iter()
            .position(|a| a == k)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let reps: usize = opt("--reps").map_or(3, |s| s.parse().unwrap());
    let v0: f64 = opt("--v0").map_or(1.0, |s| s.parse().unwrap());
    let ws: Vec<f64> = opt("--w").map_or(vec![1e-2, 1e-3, 1e-4], |s| {
        s.split(',').map(|x| x.parse().unwrap()).collect()
    });
    let opts = TaylorOptions::default();
    if let Some(spec) = opt("--band") {
        // --band lo,hi,T[,first_width]: the band in the interpolation form, SHC DSS and
        // Maxwell DSA (threads: RAYON_NUM_THREADS)
        let v: Vec<f64> = spec.split(',').map(|x| x.parse().unwrap()).collect();
        let io = InterpOptions {
            thickness: v[2],
            first_width: v
                .get(3)
                .copied()
                .unwrap_or(InterpOptions::default().first_width),
            ..InterpOptions::default()
        };
        println!("set\tv0\tthickness\tpieces\trange_runs\tpoint_runs\tseconds");
        for case in [0, 3] {
            let (name, kind, base) = TABLE1[case];
            let b = NdParams::<Interval>::parse(kind, base).unwrap();
            let s = Instant::now();
            match prove_band_second(kind, &b, v[0], v[1], &io, &opts) {
                Ok(band) => println!(
                    "{name}\t[{}, {}]\t{:.3e}\t{}\t{}\t{}\t{:.1}",
                    v[0],
                    v[1],
                    band.thickness(),
                    band.pieces.len(),
                    band.range_runs,
                    band.point_runs,
                    s.elapsed().as_secs_f64()
                ),
                Err(e) => println!(
                    "{name}\tnot proved: {} ({:.1} s)",
                    e.reason,
                    s.elapsed().as_secs_f64()
                ),
            }
        }
        return;
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    println!("set\tv0\tw\te2_mid\te2_wid\tts2_wid\te1_wid\tsteps\tms_second\tms_first\tratio");
    pool.install(|| {
        for (name, kind, base) in TABLE1 {
            for &w in &ws {
                let inputs = Inputs::Base {
                    base: NdParams::<Interval>::parse(kind, base).unwrap(),
                    v0: Interval::try_from((v0 - w / 2.0, v0 + w / 2.0)).unwrap(),
                };
                let (mut t2, mut t1) = (Vec::new(), Vec::new());
                let mut last = None;
                for _ in 0..reps {
                    let s = Instant::now();
                    last = Some(curvature_over_range(kind, &inputs, &opts));
                    t2.push(s.elapsed().as_secs_f64() * 1e3);
                    let s = Instant::now();
                    let _ = slopes_over_set(kind, &inputs, &opts);
                    t1.push(s.elapsed().as_secs_f64() * 1e3);
                }
                let (m2, m1) = (median(t2), median(t1));
                match last.unwrap() {
                    Ok(c) => println!(
                        "{name}\t{v0}\t{w:e}\t{:.6}\t{:.2e}\t{:.2e}\t{:.2e}\t{}\t{m2:.1}\t{m1:.1}\t{:.2}",
                        c.e2.mid(),
                        c.e2.wid(),
                        c.ts2.wid(),
                        c.e1.wid(),
                        c.steps,
                        m2 / m1
                    ),
                    Err(e) => println!("{name}\t{v0}\t{w:e}\tnot proved: {} (t = {:.3e})\t\t\t\t\t{m2:.1}\t{m1:.1}", e.reason, e.t),
                }
            }
        }
    });
}
