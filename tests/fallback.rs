//! Deciding what double precision cannot (issue #15, 4): the event scan's polynomial and
//! centred forms, and the precision fallback, on the Hunt–Crossley limit of the NDBWSHCCM,
//! whose CoR has a closed form.
//!
//! The reference is the Hunt–Crossley restitution law −u − ln(1 − u) = σ − ln(1 + σ), u = σe
//! (derived in `tests/common/mod.rs`), its root bracketed to ±10⁻⁹⁰ at 400 bits; every
//! enclosure must contain the whole bracket, compared as exact rationals.

use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::{ModelKind, NdParams, Shc};
use bwcl::observables::precision::{FallbackBudget, ParamText, decide};
use bwcl::observables::rigorous::rigorous_impact;
use inari::Interval;
use rug::Rational;

use crate::common;
use common::bwcl;

/// The bracket of the Hunt–Crossley e(σ) for a whole-number σ.
fn hc_bracket(sigma: u32) -> (Rational, Rational) {
    common::hunt_crossley_bracket(&Rational::from(sigma))
}

fn rat(x: f64) -> Rational {
    Rational::from_f64(x).unwrap()
}

fn nd(sigma: u32) -> String {
    format!("1e-300,0,0.5,{sigma},1.5,1.5")
}

fn f64_run(
    sigma: u32,
    forms: bool,
) -> Result<(Interval, Interval), bwcl::engines::taylor::RigorError> {
    let p = NdParams::<Interval>::parse(ModelKind::Shc, &nd(sigma)).unwrap();
    let opts = TaylorOptions {
        event_forms: forms,
        ..TaylorOptions::default()
    };
    rigorous_impact(&Shc::new(p), &opts).map(|r| (r.ts, r.e))
}

#[test]
fn the_reference_is_the_hunt_crossley_law() {
    // against an independent evaluation: σ = 12 by the f64 solver, 0.0833308845711…
    let (lo, hi) = hc_bracket(12);
    assert!(lo > rat(0.0833308845711) && hi < rat(0.0833308845712));
}

#[test]
fn f64_decides_sigma_12_15_20_with_the_forms_and_not_without() {
    for sigma in [12, 15, 20] {
        let (lo, hi) = hc_bracket(sigma);
        let (_, e) = f64_run(sigma, true).unwrap_or_else(|e| panic!("σ = {sigma}: {e}"));
        assert!(
            rat(e.inf()) <= lo && hi <= rat(e.sup()),
            "σ = {sigma}: e {e:?} does not contain the Hunt–Crossley value"
        );
        assert!(e.wid() < 1e-12, "σ = {sigma}: e {e:?}");
        // the negative control: the box evaluation alone cannot decide the separation
        let err = f64_run(sigma, false).expect_err("undecidable with the box scan alone");
        assert!(err.precision_may_help(), "{err}");
    }
}

#[test]
fn the_fallback_decides_sigma_30_at_128_bits_and_50_at_192() {
    let budget = FallbackBudget {
        max_bits: 256,
        seconds: 300.0,
    };
    for (sigma, bits, tried) in [(30, 128, 1), (50, 192, 2)] {
        let err = f64_run(sigma, true).expect_err("f64 cannot decide");
        assert!(err.precision_may_help(), "{err}");
        let d = decide(
            ModelKind::Shc,
            &ParamText::Nd(nd(sigma)),
            &err,
            &TaylorOptions::default(),
            &budget,
        );
        let enc = d
            .enclosure
            .as_ref()
            .unwrap_or_else(|| panic!("σ = {sigma}: {:?}", d.why_not()));
        assert_eq!((enc.bits, d.attempts.len()), (bits, tried), "σ = {sigma}");
        let (lo, hi) = hc_bracket(sigma);
        assert!(
            enc.e[0] <= lo && hi <= enc.e[1],
            "σ = {sigma}: e [{}, {}] does not contain the Hunt–Crossley value",
            enc.e[0].to_f64(),
            enc.e[1].to_f64()
        );
        assert!(enc.width_e() < (1, 10u64.pow(16)), "σ = {sigma}");
    }
}

#[test]
fn the_fallback_does_not_run_where_precision_cannot_help() {
    // no separation before a short horizon: proved, not a question of width
    let p = NdParams::<Interval>::parse(ModelKind::Shc, &nd(12)).unwrap();
    let opts = TaylorOptions {
        horizon: 1.0,
        ..TaylorOptions::default()
    };
    let err = rigorous_impact(&Shc::new(p), &opts).expect_err("no separation before T = 1");
    assert!(!err.precision_may_help(), "{err}");
    let d = decide(
        ModelKind::Shc,
        &ParamText::Nd(nd(12)),
        &err,
        &opts,
        &FallbackBudget::default(),
    );
    assert!(d.enclosure.is_none() && d.attempts.is_empty());
}

/// The `bits` cell of `cor --rigorous --format csv` for the --nd set `p` (one case), the row
/// as long as the header.
fn csv_bits(p: &str) -> String {
    let o = bwcl(&[
        "cor",
        "--model",
        "shc",
        "--nd",
        p,
        "--rigorous",
        "--format",
        "csv",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8(o.stdout).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(head.len(), row.len());
    let j = head
        .iter()
        .position(|h| *h == "bits")
        .expect("a bits column");
    row[j].to_string()
}

#[test]
fn the_csv_always_has_a_bits_column() {
    // a case the f64 intervals decide: 53 bits, in the same columns as a case the fallback
    // decided (runs written in batches share one header)
    assert_eq!(csv_bits(&nd(12)), "53");
}

#[test]
fn the_cli_names_the_precision_that_decided() {
    // σ = 24: the smallest whole σ f64 cannot decide here (σ = 22 it can), decided at 128 bits
    // in ≈ 0.7 s (σ = 30: ≈ 2.5 s; the library test above keeps σ = 30 and 50)
    let p = nd(24);
    let o = bwcl(&[
        "cor",
        "--model",
        "shc",
        "--nd",
        &p,
        "--rigorous",
        "--format",
        "json",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let row = &v[0];
    assert_eq!(row["proved"], true);
    assert_eq!(row["bits"], 128);
    assert_eq!(row["fallback"][0]["bits"], 128);
    assert_eq!(row["fallback"][0]["proved"], true);
    // the printed bounds (outward to doubles) contain the Hunt–Crossley value
    let (lo, hi) = hc_bracket(24);
    let e = (row["e"][0].as_f64().unwrap(), row["e"][1].as_f64().unwrap());
    assert!(rat(e.0) <= lo && hi <= rat(e.1), "{e:?}");
    // CSV and table name it in a bits column
    assert_eq!(csv_bits(&p), "128");
    // off: not proved (exit 1), the f64 reason
    let o = bwcl(&[
        "cor",
        "--model",
        "shc",
        "--nd",
        &p,
        "--rigorous",
        "--fallback-bits",
        "0",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stdout).contains("grazing or undecidable"));
    // options out of range: one line, exit 2
    for bad in [
        ["--fallback-bits", "100"],
        ["--fallback-seconds", "0"],
        ["--fallback-seconds", "nan"],
    ] {
        let mut args = vec!["cor", "--model", "shc", "--nd", &p, "--rigorous"];
        args.extend(bad);
        let o = bwcl(&args);
        assert_eq!(o.status.code(), Some(2), "{bad:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(bad[1]), "{err}");
    }
}
