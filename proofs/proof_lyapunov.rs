//! `proof-lyapunov`: computer-assisted proof of thm:BWSHCCM_dV_leq_0, thm:BWMCM_dV_leq_0 and of
//! the zero-set part of thm:BWSHCCM_inv_dV_1, thm:BWMCM_inv_dV_1, on the implementation's
//! `lyapunov_rate`, by branch and bound over parameter boxes × every sign orthant of the state
//! space (see `sym.rs` and `lyapunov_core.rs`), and a proved counterexample for |Γ| > B.
//!
//! `cargo run --release --bin proof-lyapunov [-- --wide]`. Exits non-zero if any box is left
//! undecided, any counterexample is found inside 𝓟, the zero-set classification differs from the
//! lemma's, or no counterexample is found outside 𝓟.

#[path = "lyapunov_core.rs"]
mod lyapunov_core;
#[path = "sym.rs"]
mod sym;
#[path = "verdict.rs"]
mod verdict;

use lyapunov_core::{PBox, Which, classification_mismatches, gamma_counterexample, prove};
use std::process::ExitCode;

fn main() -> ExitCode {
    let wide = std::env::args().any(|a| a == "--wide");
    let t0 = std::time::Instant::now();
    let mut ok = true;
    // the brief's box (σ ≥ 0: the appendix's closed set) and, for the zero-set statement
    // (σ > 0), the same box with σ ∈ [0.01, 2]
    let (b, g, s, np) = if wide {
        ((1e-3, 1e3), (-0.999, 0.999), (0.0, 100.0), (1.0, 10.0))
    } else {
        ((0.1, 3.0), (-0.99, 0.99), (0.0, 2.0), (1.0, 3.0))
    };
    for which in [Which::Shc, Which::Maxwell] {
        let p_ranges: Vec<(f64, f64)> = match (which, wide) {
            (Which::Shc, false) => vec![(1.0, 4.0)],
            (Which::Shc, true) => vec![(1.0, 10.0)],
            (Which::Maxwell, false) => vec![(1.0, 1.0), (2.0, 4.0)],
            (Which::Maxwell, true) => vec![(1.0, 1.0), (2.0, 10.0)],
        };
        for p in p_ranges {
            for sigma in [s, (0.01, s.1)] {
                let root = PBox::new([b, g, (0.01, 0.99), sigma, np, p]);
                let t = std::time::Instant::now();
                let o = prove(which, root.clone(), 40, 200_000);
                println!(
                    "{which:?}: B ∈ [{}, {}], Γ/B ∈ [{}, {}], κ ∈ [0.01, 0.99], σ ∈ [{}, {}], n ∈ [{}, {}], p ∈ [{}, {}], every state orthant:",
                    b.0, b.1, g.0, g.1, sigma.0, sigma.1, np.0, np.1, p.0, p.1
                );
                println!(
                    "  {} boxes proved 𝒱̇ ≤ 0 (depth {}), {} undecided, {} counterexamples, {:.2?}",
                    o.proved,
                    o.depth,
                    o.undecided.len(),
                    o.counterexamples.len(),
                    t.elapsed()
                );
                if !o.undecided.is_empty() || !o.counterexamples.is_empty() {
                    println!(
                        "  FAILED: {:?} {:?}",
                        o.undecided.first(),
                        o.counterexamples.first()
                    );
                    ok = false;
                }
                if sigma.0 > 0.0 {
                    let bad = classification_mismatches(which, &o);
                    if bad.is_empty() {
                        println!(
                            "  zero set: 𝒱̇ ≡ 0 on {} orthants (U1 ∪ U2), < 0 on {}, ≤ 0 (= 0 only where h = 0, i.e. on 𝓔) on {}: as in thm:{}_inv_dV_1",
                            o.zero.len(),
                            o.negative.len(),
                            o.nonpositive.len(),
                            if which == Which::Shc {
                                "BWSHCCM"
                            } else {
                                "BWMCM"
                            }
                        );
                    } else {
                        println!("  FAILED zero-set classification: {bad:?}");
                        ok = false;
                    }
                }
            }
        }
        // outside 𝓟: Γ/B ∈ [1.01, 2] and [−2, −1.01] must give counterexamples
        for g in [(1.01, 2.0), (-2.0, -1.01)] {
            let root = PBox::new([b, g, (0.01, 0.99), (0.0, 2.0), np, (2.0, 3.0)]);
            let o = prove(which, root, 20, 10_000);
            match o.counterexamples.first() {
                Some((bx, s, w)) => println!(
                    "{which:?} outside 𝓟 (Γ/B ∈ [{}, {}]): counterexample region B ∈ [{}, {}], Γ/B ∈ [{}, {}], state orthant {s:?}: {w} > 0, so 𝒱̇ > 0 there",
                    g.0, g.1, bx.lo[0], bx.hi[0], bx.lo[1], bx.hi[1]
                ),
                None => {
                    println!("{which:?} outside 𝓟 (Γ/B ∈ {g:?}): FAILED to find a counterexample");
                    ok = false;
                }
            }
        }
    }
    for (what, r) in gamma_counterexample() {
        let proved = r.inf() > 0.0;
        println!(
            "counterexample box: {what}: 𝒱̇ ∈ [{:e}, {:e}] {}",
            r.inf(),
            r.sup(),
            if proved {
                "> 0 (proved)"
            } else {
                "NOT proved > 0"
            }
        );
        ok &= proved;
    }
    verdict::finish("total", t0, ok, "PROVED")
}
