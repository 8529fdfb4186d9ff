//! The 28 Table 1 cases (4 sets × 7 speeds) through the rigorous engine: the enclosures of e
//! and T_s bit for bit (hex floats), their widths, the pieces of the flow and the median time
//! per case on one thread, beside the f64 time. For before/after comparisons of engine changes
//! (issue #32): run it on both builds and diff (`--compare A.tsv B.tsv`).
//!
//! ```text
//! cargo run --release --features bench --example cases -- [--reps N] > after.tsv
//! cargo run --release --features bench --example cases -- --compare before.tsv after.tsv
//! ```

use std::hint::black_box;
use std::time::Instant;

use bwcl::arith::Real;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::scaling::nd_from_base;
use bwcl::models::{Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::rigorous::rigorous_impact;
use bwcl::observables::{FloatOptions, impact};
use inari::Interval;

const SPEEDS: [f64; 7] = [0.1, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0];

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// (e, T_s, pieces) of one case, or the engine's reason.
fn rigorous(kind: ModelKind, base: &str, v0: f64) -> Result<(Interval, Interval, usize), String> {
    let b = NdParams::<Interval>::parse(kind, base).map_err(|e| e.0)?;
    let v = <Interval as Real>::parse_decimal(&format!("{v0}"))?;
    let p = nd_from_base(kind, &b, &v).map_err(|e| e.0)?;
    let opts = TaylorOptions::default();
    let r = match kind {
        ModelKind::Shc => rigorous_impact(&Shc::new(p), &opts).map(|r| (r.e, r.ts, r.flow.len())),
        ModelKind::Maxwell => {
            rigorous_impact(&Maxwell::new(p), &opts).map(|r| (r.e, r.ts, r.flow.len()))
        }
    };
    r.map_err(|e| e.reason)
}

fn float(kind: ModelKind, base: &str, v0: f64) -> f64 {
    let b = NdParams::<f64>::parse(kind, base).expect("base set");
    let p = nd_from_base(kind, &b, &v0).expect("P(P*, v0)");
    let o = FloatOptions::default();
    match kind {
        ModelKind::Shc => impact(&Shc::new(p), &o).map(|r| r.e),
        ModelKind::Maxwell => impact(&Maxwell::new(p), &o).map(|r| r.e),
    }
    .unwrap_or(f64::NAN)
}

fn time(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut v: Vec<f64> = (0..reps)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    median(&mut v)
}

fn hex(x: f64) -> String {
    format!("{:016x}", x.to_bits())
}

fn run(reps: usize) {
    println!("case\tv0\te_lo\te_hi\tts_lo\tts_hi\twid_e\twid_ts\tpieces\tt_rig_s\tt_f64_s");
    for (name, kind, base) in bwcl::models::params::TABLE1 {
        for v0 in SPEEDS {
            let r = rigorous(kind, base, v0);
            let (tr, tf) = {
                // interleaved: one rigorous and one f64 run per repetition
                let mut a = Vec::new();
                let mut b = Vec::new();
                for _ in 0..reps {
                    a.push(time(1, || {
                        black_box(rigorous(kind, base, black_box(v0)).ok());
                    }));
                    b.push(time(1, || {
                        black_box(float(kind, base, black_box(v0)));
                    }));
                }
                (median(&mut a), median(&mut b))
            };
            match r {
                Ok((e, ts, n)) => println!(
                    "{name}\t{v0}\t{}\t{}\t{}\t{}\t{:.3e}\t{:.3e}\t{n}\t{tr:.4e}\t{tf:.4e}",
                    hex(e.inf()),
                    hex(e.sup()),
                    hex(ts.inf()),
                    hex(ts.sup()),
                    e.wid(),
                    ts.wid()
                ),
                Err(why) => {
                    println!("{name}\t{v0}\tnot proved: {why}\t\t\t\t\t\t\t{tr:.4e}\t{tf:.4e}")
                }
            }
        }
    }
}

fn compare(a: &str, b: &str) {
    let read = |p: &str| -> Vec<Vec<String>> {
        std::fs::read_to_string(p)
            .unwrap_or_else(|e| panic!("{p}: {e}"))
            .lines()
            .skip(1)
            .map(|l| l.split('\t').map(String::from).collect())
            .collect()
    };
    let (ra, rb) = (read(a), read(b));
    let f = |r: &Vec<String>, i: usize| {
        r.get(i)
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    println!("case\tv0\twid_e A→B\twid_ts A→B\tpieces A→B\ttime B/A\tbits equal");
    let (mut narrower, mut ratios, mut same) = (0, Vec::new(), 0);
    for (x, y) in ra.iter().zip(&rb) {
        let eq = x[2..6] == y[2..6];
        same += usize::from(eq);
        let (we, we2) = (f(x, 6), f(y, 6));
        narrower += usize::from(we2 <= we);
        let r = f(y, 9) / f(x, 9);
        ratios.push(r);
        println!(
            "{}\t{}\t{we:.3e}→{we2:.3e}\t{:.3e}→{:.3e}\t{}→{}\t{r:.3}\t{eq}",
            x[0],
            x[1],
            f(x, 7),
            f(y, 7),
            x[8],
            y[8]
        );
    }
    println!(
        "e no wider on {narrower} of {}; identical enclosures on {same}; median time ratio B/A {:.3}",
        ra.len(),
        median(&mut ratios)
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--compare") {
        compare(&args[i + 1], &args[i + 2]);
        return;
    }
    let reps = args
        .iter()
        .position(|a| a == "--reps")
        .and_then(|i| args.get(i + 1)?.parse().ok())
        .unwrap_or(5);
    // one thread for the rigorous engine (its step halves otherwise run as a rayon::join)
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build_global()
        .expect("one-thread pool");
    run(reps);
}
