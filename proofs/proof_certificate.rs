//! `proof-certificate write|check [FILE]`: proved enclosures of T_s and e for the Table 1 sets
//! at v0 ∈ {0.1, 0.5, 1, 2, 3, 4, 5} (see `certificate_core.rs`).
//!
//! - `write` computes the 28 enclosures and writes the certificate (default
//!   `proofs/certificates/table1.json`);
//! - `check` reads it, recomputes every enclosure (each stored one must contain the recomputed
//!   one) and checks the DOP853 (rtol 1e-13) e against the stored enclosure ± 1e-11.
//!
//! Exits non-zero on any failure.

#[path = "certificate_core.rs"]
mod certificate_core;
#[path = "verdict.rs"]
mod verdict;

use std::process::ExitCode;

const DEFAULT: &str = "proofs/certificates/table1.json";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args.get(1).map_or(DEFAULT, String::as_str);
    let t0 = std::time::Instant::now();
    match args.first().map(String::as_str) {
        Some("write") => match certificate_core::certificate() {
            Ok(c) => {
                let text = serde_json::to_string_pretty(&c).unwrap() + "\n";
                if let Err(e) = std::fs::write(path, text) {
                    eprintln!("cannot write {path}: {e}");
                    return ExitCode::FAILURE;
                }
                println!(
                    "wrote {} proved enclosures to {path} in {:.2?}",
                    c["entries"].as_array().map_or(0, Vec::len),
                    t0.elapsed()
                );
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("FAILED: {e}");
                ExitCode::FAILURE
            }
        },
        Some("check") => {
            let text = match std::fs::read_to_string(path) {
                Ok(t) => t,
                Err(e) => {
                    eprintln!("cannot read {path}: {e}");
                    return ExitCode::FAILURE;
                }
            };
            let c: serde_json::Value = match serde_json::from_str(&text) {
                Ok(c) => c,
                Err(e) => {
                    eprintln!("{path}: {e}");
                    return ExitCode::FAILURE;
                }
            };
            let entries = c["entries"].as_array().cloned().unwrap_or_default();
            let mut ok = entries.len() == 28;
            for v in &entries {
                match certificate_core::check_entry(v) {
                    Ok(line) => println!("{line}"),
                    Err(e) => {
                        println!("FAILED: {e}");
                        ok = false;
                    }
                }
            }
            let what = format!("{} entries checked in", entries.len());
            verdict::finish(&what, t0, ok, "VERIFIED")
        }
        _ => {
            eprintln!("usage: proof-certificate write|check [FILE]");
            ExitCode::from(2)
        }
    }
}
