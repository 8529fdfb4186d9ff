//! `proof-equilibria`: thm:BWSHCCM_eq and thm:BWMCM_eq in the region [−L, L]^N for the
//! parameter sets of `equilibria_core::SETS` (see that file for the method).
//!
//! `cargo run --release --bin proof-equilibria [-- L δ]` (default L = 2, δ = 1e-2). Exits
//! non-zero when a box is left undecided or 0 ∉ f at a point of 𝓔.

#[path = "equilibria_core.rs"]
mod equilibria_core;
#[path = "verdict.rs"]
mod verdict;

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let half = args.first().copied().unwrap_or(2.0);
    let delta = args.get(1).copied().unwrap_or(1e-2);
    let mut ok = true;
    let t0 = std::time::Instant::now();
    for (kind, set) in equilibria_core::SETS {
        let t = std::time::Instant::now();
        let o = equilibria_core::prove_set(kind, set, half, delta, 5_000_000);
        let good = o.undecided == 0 && o.e_contains_zero;
        ok &= good;
        println!(
            "{kind:?} {set}: in [−{half}, {half}]^N every equilibrium is within δ = {delta:e} of 𝓔 — {} boxes excluded (f ∌ 0), {} boxes within δ of 𝓔, {} undecided; 0 ∈ f(𝓔 point box) at 41 points: {} (widest {:e}); {:.2?} {}",
            o.excluded,
            o.near,
            o.undecided,
            o.e_contains_zero,
            o.e_width,
            t.elapsed(),
            if good { "PROVED" } else { "FAILED" }
        );
    }
    verdict::finish("total", t0, ok, "PROVED")
}
