//! Runs the cores of the computer-assisted proofs in `proofs/` on a small budget, so that
//! `cargo test` exercises them (the full runs are the `proof-*` binaries: proofs/README.md).

use crate::certificate_core;
#[path = "../proofs/equilibria_core.rs"]
mod equilibria_core;
#[path = "../proofs/lyapunov_core.rs"]
mod lyapunov_core;
// (lyapunov_core names `crate::sym`: the suite declares it at its root, tests/suite.rs)

use bwcl::models::ModelKind;
use lyapunov_core::{PBox, Which, classification_mismatches, gamma_counterexample, prove};

/// thm:BWSHCCM_dV_leq_0, thm:BWMCM_dV_leq_0, thm:BWSHCCM_inv_dV_1, thm:BWMCM_inv_dV_1 (the
/// zero set): the branch and bound of `proof-lyapunov` on its default box (σ > 0), and the
/// counterexamples for |Γ| > B.
#[test]
fn lyapunov_rate_proof_core() {
    for (which, p) in [
        (Which::Shc, (1.0, 4.0)),
        (Which::Maxwell, (1.0, 1.0)),
        (Which::Maxwell, (2.0, 4.0)),
    ] {
        let root = PBox::new([
            (0.1, 3.0),
            (-0.99, 0.99),
            (0.01, 0.99),
            (0.01, 2.0),
            (1.0, 3.0),
            p,
        ]);
        let o = prove(which, root, 40, 100_000);
        assert!(
            o.undecided.is_empty() && o.counterexamples.is_empty(),
            "{which:?}: {o:?}"
        );
        assert!(classification_mismatches(which, &o).is_empty());
        let bad = PBox::new([
            (0.1, 3.0),
            (1.01, 2.0),
            (0.01, 0.99),
            (0.0, 2.0),
            (1.0, 3.0),
            (2.0, 3.0),
        ]);
        assert!(!prove(which, bad, 20, 10_000).counterexamples.is_empty());
    }
    for (what, r) in gamma_counterexample() {
        assert!(r.inf() > 0.0, "{what}: {r:?}");
    }
}

/// thm:BWSHCCM_eq, thm:BWMCM_eq: `proof-equilibria` with δ = 5e-2 on one set of each model.
#[test]
fn equilibria_proof_core() {
    for (kind, set) in [
        (ModelKind::Shc, equilibria_core::SETS[0].1),
        (ModelKind::Maxwell, equilibria_core::SETS[5].1),
    ] {
        let o = equilibria_core::prove_set(kind, set, 2.0, 5e-2, 200_000);
        assert!(
            o.undecided == 0 && o.e_contains_zero,
            "{kind:?} {set}: {o:?}"
        );
    }
}

/// The Table 1 certificate: two stored entries (one per model) recomputed and checked.
#[test]
fn certificate_check_core() {
    let text = std::fs::read_to_string("proofs/certificates/table1.json").unwrap();
    let c: serde_json::Value = serde_json::from_str(&text).unwrap();
    let entries = c["entries"].as_array().unwrap();
    assert_eq!(entries.len(), 28);
    for v in [&entries[2], &entries[27]] {
        let line = certificate_core::check_entry(v).unwrap();
        eprintln!("{line}");
    }
}
