//! Issue #15, deliverable 4: what double precision cannot decide. On a spread of cases over 𝓟
//! (both models) and the Hunt–Crossley limits σ ∈ {12, 15, 20, 30, 50}, each case is run
//!
//! 1. on the f64-interval engine with the box evaluation of F and V alone in the event scan
//!    (`event_forms` off: the engine before this change);
//! 2. on the f64-interval engine as it is (the polynomial and centred forms on);
//! 3. where 2 failed for a reason precision may remove, through the precision fallback
//!    ([`bwcl::observables::precision::decide`]: 128, 192, 256 bits, `SECONDS` per rung).
//!
//! `cargo run --release --features bench --example fallback` prints Markdown for benches/RESULTS.md. The spread
//! is deterministic (a fixed xorshift): N cases per model (env `N`, default 60), parameters
//! written as 3-digit decimals so that every precision encloses the same text:
//! B log-uniform on [10⁻³, 10], Γ = g·B with g uniform on (−0.99, 0.99), κ on [0.01, 0.99],
//! σ log-uniform on [10⁻³, 100], n = 1 (a third) or uniform on [1, 3], p: SHC uniform on
//! [1, 3.5], Maxwell 1 (a third) or uniform on [2, 3.5].

use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::{Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::precision::{FallbackBudget, ParamText, decide};
use bwcl::observables::rigorous::rigorous_impact;
use inari::Interval;
use rayon::prelude::*;
use std::time::Instant;

struct Xorshift(u64);
impl Xorshift {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn uniform(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }
    fn log_uniform(&mut self, a: f64, b: f64) -> f64 {
        (a.ln() + (b.ln() - a.ln()) * self.unit()).exp()
    }
}

/// x as a decimal with 3 significant digits.
fn d3(x: f64) -> String {
    format!("{:.2e}", x)
}

fn spread(kind: ModelKind, n: usize, rng: &mut Xorshift) -> Vec<String> {
    let mut out = Vec::new();
    while out.len() < n {
        let b = rng.log_uniform(1e-3, 10.0);
        let g = rng.uniform(-0.99, 0.99);
        let k = rng.uniform(0.01, 0.99);
        let s = rng.log_uniform(1e-3, 100.0);
        let nn = if rng.unit() < 1.0 / 3.0 {
            1.0
        } else {
            rng.uniform(1.0, 3.0)
        };
        let p = match kind {
            ModelKind::Shc => rng.uniform(1.0, 3.5),
            ModelKind::Maxwell if rng.unit() < 1.0 / 3.0 => 1.0,
            ModelKind::Maxwell => rng.uniform(2.0, 3.5),
        };
        let (bt, gt) = (d3(b), d3(g * b));
        let text = format!("{bt},{gt},{},{},{},{}", d3(k), d3(s), d3(nn), d3(p));
        if NdParams::<Interval>::parse(kind, &text).is_ok() {
            out.push(text);
        }
    }
    out
}

struct Outcome {
    before: Result<(), String>,
    now: Result<(), String>,
    /// The fallback's result: the bits that proved it, or why not; None if it did not run.
    fallback: Option<Result<u32, String>>,
    seconds: f64,
}

fn short(e: &str) -> String {
    e.split(':').next().unwrap_or(e).trim().to_string()
}

fn run(kind: ModelKind, text: &str, budget: &FallbackBudget) -> Outcome {
    let p = NdParams::<Interval>::parse(kind, text).unwrap();
    let f64_run = |forms: bool| {
        let opts = TaylorOptions {
            event_forms: forms,
            ..TaylorOptions::default()
        };
        match kind {
            ModelKind::Shc => rigorous_impact(&Shc::new(p.clone()), &opts).map(|_| ()),
            ModelKind::Maxwell => rigorous_impact(&Maxwell::new(p.clone()), &opts).map(|_| ()),
        }
    };
    let before = f64_run(false).map_err(|e| short(&e.reason));
    let now_r = f64_run(true);
    let now = now_r.clone().map_err(|e| short(&e.reason));
    let t0 = Instant::now();
    let fallback = match &now_r {
        Err(e) if e.precision_may_help() => {
            let d = decide(
                kind,
                &ParamText::Nd(text.into()),
                e,
                &TaylorOptions::default(),
                budget,
            );
            Some(match (&d.enclosure, d.attempts.last()) {
                (Some(enc), _) => Ok(enc.bits),
                (None, Some(a)) => Err(format!(
                    "{} bits: {}",
                    a.bits,
                    a.error.as_ref().map_or(String::new(), |e| short(&e.reason))
                )),
                (None, None) => Err("not run".into()),
            })
        }
        _ => None,
    };
    Outcome {
        before,
        now,
        fallback,
        seconds: t0.elapsed().as_secs_f64(),
    }
}

fn main() {
    let n: usize = std::env::var("N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(60);
    let seconds: f64 = std::env::var("SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20.0);
    let budget = FallbackBudget {
        max_bits: 256,
        seconds,
    };
    let mut rng = Xorshift(0x9E37_79B9_7F4A_7C15);
    let mut cases: Vec<(ModelKind, String, &str)> = [12, 15, 20, 30, 50]
        .iter()
        .map(|s| {
            (
                ModelKind::Shc,
                format!("1e-300,0,0.5,{s},1.5,1.5"),
                "Hunt–Crossley limit",
            )
        })
        .collect();
    for kind in [ModelKind::Shc, ModelKind::Maxwell] {
        for t in spread(kind, n, &mut rng) {
            cases.push((kind, t, "spread"));
        }
    }
    let start = Instant::now();
    let out: Vec<Outcome> = cases
        .par_iter()
        .map(|(k, t, _)| run(*k, t, &budget))
        .collect();
    println!(
        "`cargo run --release --features bench --example fallback` (benches/generator/fallback.rs), N = {n} per \
         model, {seconds} s per rung, 2 threads; total {:.0} s.\n",
        start.elapsed().as_secs_f64()
    );
    println!("| case | model | P | f64, box scan | f64, now | fallback | fallback time |");
    println!("|---|---|---|---|---|---|---:|");
    let cell = |r: &Result<(), String>| match r {
        Ok(()) => "proved".to_string(),
        Err(e) => e.clone(),
    };
    for ((k, t, what), o) in cases.iter().zip(&out) {
        if o.before.is_ok() && o.now.is_ok() && *what == "spread" {
            continue;
        }
        let fb = match &o.fallback {
            None => "—".to_string(),
            Some(Ok(b)) => format!("proved at {b} bits"),
            Some(Err(e)) => e.clone(),
        };
        let time = if o.fallback.is_some() {
            format!("{:.1} s", o.seconds)
        } else {
            "—".into()
        };
        println!(
            "| {what} | {} | {t} | {} | {} | {fb} | {time} |",
            k.name(),
            cell(&o.before),
            cell(&o.now)
        );
    }
    let spread: Vec<&Outcome> = cases
        .iter()
        .zip(&out)
        .filter(|(c, _)| c.2 == "spread")
        .map(|(_, o)| o)
        .collect();
    let count = |f: &dyn Fn(&Outcome) -> bool| spread.iter().filter(|o| f(o)).count();
    println!(
        "\nSpread ({} cases; rows above: the cases not proved by one of the runs, all HC rows): \
         proved at f64 with the box scan {}, at f64 now {}, by the fallback {} more; not proved \
         {} (of which precision could not help {}).",
        spread.len(),
        count(&|o| o.before.is_ok()),
        count(&|o| o.now.is_ok()),
        count(&|o| matches!(o.fallback, Some(Ok(_)))),
        count(&|o| o.now.is_err() && !matches!(o.fallback, Some(Ok(_)))),
        count(&|o| o.now.is_err() && o.fallback.is_none()),
    );
}
