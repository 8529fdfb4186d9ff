//! The integration tests as one program (issue #34, the test command's time): each file of
//! `tests/` is a module here, so the engines' generic code they instantiate is compiled and
//! linked once, not once per file. `tests/cancel.rs` sets the process-wide cancel flag, which
//! would stop the other tests' runs: its test runs itself in a child process.
//!
//! Run one file's tests by its module name: `cargo test --release --test suite cli::`.

// shared by several files (each names it `crate::…`)
#[path = "../proofs/certificate_core.rs"]
mod certificate_core;
mod common;
// proofs/lyapunov_core.rs names `crate::sym`, as in its program proofs/proof_lyapunov.rs
#[path = "../proofs/sym.rs"]
mod sym;

#[path = "cancel.rs"]
mod cancel;
#[path = "classical.rs"]
mod classical;
#[path = "cli.rs"]
mod cli;
#[path = "cli_fuzz.rs"]
mod cli_fuzz;
#[path = "compare.rs"]
mod compare;
#[path = "curvature.rs"]
mod curvature;
#[path = "dop853.rs"]
mod dop853;
#[path = "fallback.rs"]
mod fallback;
#[path = "fit.rs"]
mod fit;
#[path = "fit_uncertainty.rs"]
mod fit_uncertainty;
#[path = "guards.rs"]
mod guards;
#[path = "identify.rs"]
mod identify;
#[path = "law_cor.rs"]
mod law_cor;
#[path = "laws.rs"]
mod laws;
#[path = "layers.rs"]
mod layers;
#[path = "outward.rs"]
mod outward;
#[path = "paper_repro.rs"]
mod paper_repro;
#[path = "precision.rs"]
mod precision;
#[path = "proofs.rs"]
mod proofs;
#[path = "properties.rs"]
mod properties;
#[path = "references.rs"]
mod references;
#[path = "rigorous.rs"]
mod rigorous;
#[path = "sets.rs"]
mod sets;
#[path = "verdicts.rs"]
mod verdicts;
