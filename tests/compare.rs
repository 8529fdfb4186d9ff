//! The classical laws against data (issue #33, item 4): `fit`, `identify` and `compare` with
//! `--model <law>`, checked against exact references.
//!
//! - Hunt–Crossley's feasible set is known exactly: e(σ) is decreasing, so row i allows
//!   σ_b ∈ [σ*(e_i + E)/v0_i, σ*(e_i − E)/v0_i] with σ* the inverse of the restitution law, and
//!   F is the intersection. σ* is bracketed here by bisection on the 400-bit restitution bracket
//!   of `tests/common` (independent of the crate's MPFR code), the data's decimals as written;
//!   every feasible interval must lie inside F, every infeasible one outside, as rationals, and
//!   the hull must hold F and be within 1e−5 of it.
//! - Constant-CoR laws (Kelvin–Voigt) on data spread beyond 2E: F is empty, with a certificate
//!   that names the two extreme rows and, by monotonicity, covers every ζ ≥ 0.

use bwcl::fit::laws::Law;
use bwcl::observables::FloatOptions;
use bwcl::observables::decimal::parse_rational;
use rug::Rational;
use serde_json::Value;
use std::io::Write;

use crate::common;
use common::{bwcl, hunt_crossley_bracket};

const SIGMA_B: f64 = 0.37;
const E: &str = "0.02";

/// HC data at σ_b = 0.37: 10 speeds in [0.2, 4], e to 6 decimals, offsets of ±0.008 and 0.
fn hc_data() -> Vec<(String, String)> {
    let o = FloatOptions::default();
    (0..10)
        .map(|i| {
            let v = 0.2 + 0.42 * i as f64;
            let e = Law::HuntCrossley.cor(SIGMA_B, v, &o).unwrap() + [0.008, 0.0, -0.008][i % 3];
            (format!("{v:.2}"), format!("{e:.6}"))
        })
        .collect()
}

fn write(name: &str, rows: &[(String, String)]) -> std::path::PathBuf {
    let p = std::env::temp_dir().join(format!("bwcl-compare-{}-{name}.csv", std::process::id()));
    let mut f = std::fs::File::create(&p).unwrap();
    writeln!(f, "v0,e").unwrap();
    for (v, e) in rows {
        writeln!(f, "{v},{e}").unwrap();
    }
    p
}

fn q(s: &str) -> Rational {
    parse_rational(s).unwrap()
}

/// [a, b] ∋ σ*(t): the σ with e(σ) = t, for 0 < t < 1 (e decreasing; 120 bisections).
fn sigma_star(t: &Rational) -> (Rational, Rational) {
    let (mut a, mut b) = (Rational::from(0), Rational::from(64));
    for _ in 0..120 {
        let m = Rational::from(&a + &b) / 2u32;
        let (lo, hi) = hunt_crossley_bracket(&m);
        if lo > *t {
            a = m; // e(m) > t: m < σ*
        } else if hi < *t {
            b = m;
        } else {
            // t inside the 1e−120 bracket: σ* within a hair of m
            let eps = Rational::from((1, 1u64 << 60));
            return (Rational::from(&m - &eps), Rational::from(&m + &eps));
        }
    }
    (a, b)
}

/// F = [lo, hi] as brackets: ((lo_a, lo_b), (hi_a, hi_b)).
fn exact_f(rows: &[(String, String)], err: &str) -> ((Rational, Rational), (Rational, Rational)) {
    let err = q(err);
    let mut lo = (Rational::from(0), Rational::from(0));
    let mut hi = (Rational::from(1_000_000), Rational::from(1_000_000));
    for (v, e) in rows {
        let (v, e) = (q(v), q(e));
        let up = Rational::from(&e + &err);
        if up < 1u32 {
            let (a, b) = sigma_star(&up);
            let (a, b) = (a / &v, b / &v);
            if a > lo.0 {
                lo.0 = a;
            }
            if b > lo.1 {
                lo.1 = b;
            }
        }
        let down = Rational::from(&e - &err);
        if down > 0u32 {
            let (a, b) = sigma_star(&down);
            let (a, b) = (a / &v, b / &v);
            if a < hi.0 {
                hi.0 = a;
            }
            if b < hi.1 {
                hi.1 = b;
            }
        }
    }
    (lo, hi)
}

fn json(args: &[&str]) -> Value {
    let o = bwcl(args);
    assert!(
        o.status.code() == Some(0),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).unwrap()
}

fn num(v: &Value) -> Rational {
    q(&v.to_string())
}

/// Checks a paving of σ_b against the exact F; returns the hull.
fn check_against(
    j: &Value,
    f: &((Rational, Rational), (Rational, Rational)),
) -> (Rational, Rational) {
    let ((lo_a, lo_b), (hi_a, hi_b)) = f;
    let mut feasible = 0;
    for b in j["boxes"].as_array().unwrap() {
        let (a, z) = (num(&b["lo"][0]), num(&b["hi"][0]));
        match b["status"].as_str().unwrap() {
            "feasible" => {
                feasible += 1;
                assert!(a >= *lo_b && z <= *hi_a, "feasible [{a}, {z}] leaves F");
            }
            "infeasible" => assert!(
                z <= *lo_a || a >= *hi_b,
                "infeasible [{a}, {z}] meets F = [{lo_a}, {hi_b}]"
            ),
            _ => {}
        }
    }
    assert!(feasible > 0, "no interval proved feasible");
    let h = &j["hull"]["sigma_b"];
    let (ha, hz) = (num(&h[0]), num(&h[1]));
    assert!(
        ha <= *lo_a && hz >= *hi_b,
        "hull [{ha}, {hz}] does not hold F"
    );
    (ha, hz)
}

#[test]
fn hunt_crossley_feasible_set_is_the_exact_intersection() {
    let rows = hc_data();
    let path = write("hc", &rows);
    let f = exact_f(&rows, E);
    assert!(f.0.1 < f.1.0, "the reference F is not empty");
    let j = json(&[
        "identify",
        "--model",
        "hunt-crossley",
        "--data",
        path.to_str().unwrap(),
        "--error",
        E,
        "--format",
        "json",
    ]);
    assert_eq!(j["empty"], false);
    let (ha, hz) = check_against(&j, &f);
    // tight: within 1e−5 of F's width at each end
    let w = Rational::from(&f.1.1 - &f.0.0);
    let tol = w / 100_000u32;
    assert!(Rational::from(&f.0.0 - &ha) <= tol && Rational::from(&hz - &f.1.1) <= tol);
    // the generating σ_b is in F (the offsets are within E)
    assert!(ha < q("0.37") && hz > q("0.37"));
    // negative control: the reference at a larger error is wider than this hull
    let wider = exact_f(&rows, "0.021");
    assert!(
        wider.0.1 < ha || wider.1.0 > hz,
        "the check cannot tell E apart"
    );
}

#[test]
fn an_empty_box_is_not_extended_where_monotonicity_does_not_carry_it() {
    // σ_b ≤ 0.05 gives e too high at every speed: refuted in the box, but larger σ_b fit, so
    // the certificate must stop at the box's end
    let path = write("hc-box", &hc_data());
    let j = json(&[
        "identify",
        "--model",
        "hunt-crossley",
        "--data",
        path.to_str().unwrap(),
        "--error",
        E,
        "--bounds",
        "sigma_b=0..0.05",
        "--format",
        "json",
    ]);
    assert_eq!(j["empty"], true);
    let cert: Vec<&str> = j["certificate"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    assert!(cert.iter().all(|c| !c.contains('∞')), "{cert:?}");
    assert!(j["verdict"].as_str().unwrap().contains("in the box"));
}

#[test]
fn where_the_engine_fails_the_paving_stays_bounded() {
    // σ = σ_b v0 ≳ 100 is beyond the engine (an undecidable separation): up to σ_b = 10⁴ those
    // intervals stop at 1/16 of their distance to 0 instead of 2^-20, so the run completes
    let path = write("hc-wide", &hc_data());
    let j = json(&[
        "identify",
        "--model",
        "hunt-crossley",
        "--data",
        path.to_str().unwrap(),
        "--error",
        E,
        "--bounds",
        "sigma_b=0..10000",
        "--format",
        "json",
    ]);
    assert_eq!(j["complete"], true);
    assert!(
        j["processed"].as_u64().unwrap() < 5000,
        "{}",
        j["processed"]
    );
    assert!(j["counts"]["feasible"].as_u64().unwrap() > 0);
}

#[test]
fn constant_cor_laws_are_refuted_everywhere_by_the_extreme_rows() {
    let rows: Vec<(String, String)> = [("1", "0.9"), ("2", "0.7"), ("3", "0.5")]
        .iter()
        .map(|(v, e)| (v.to_string(), e.to_string()))
        .collect();
    let path = write("kv", &rows);
    for (law, name) in [("kelvin-voigt", "zeta"), ("linear-maxwell", "c")] {
        let j = json(&[
            "identify",
            "--model",
            law,
            "--data",
            path.to_str().unwrap(),
            "--error",
            "0.1",
            "--format",
            "json",
        ]);
        assert_eq!(j["empty"], true, "{law}");
        let cert = j["certificate"].to_string();
        assert!(
            cert.contains("row 1 ") && cert.contains("row 3 ") && cert.contains('∞'),
            "{law}: {cert}"
        );
        assert!(cert.contains(name));
        assert!(
            j["verdict"]
                .as_str()
                .unwrap()
                .contains("in the box or beyond it")
        );
    }
    // at ±0.21 the middle fits: F is the ζ with e(ζ) ∈ [0.69, 0.71]
    let j = json(&[
        "identify",
        "--model",
        "kelvin-voigt",
        "--data",
        path.to_str().unwrap(),
        "--error",
        "0.21",
        "--format",
        "json",
    ]);
    assert_eq!(j["empty"], false);
}

#[test]
fn fit_and_compare_rank_the_generating_law_first() {
    let path = write("hc-fit", &hc_data());
    let p = path.to_str().unwrap();
    let j = json(&[
        "fit",
        "--model",
        "hunt-crossley",
        "--data",
        p,
        "--format",
        "json",
    ]);
    let t = j["theta"].as_f64().unwrap();
    let (a, b) = (
        j["interval"][0]["value"].as_f64().unwrap(),
        j["interval"][1]["value"].as_f64().unwrap(),
    );
    assert!(
        a < SIGMA_B && SIGMA_B < b && (t - SIGMA_B).abs() < 0.01,
        "{t} [{a}, {b}]"
    );
    assert!(j["se"].as_f64().unwrap() > 0.0);
    let j = json(&[
        "compare",
        "--data",
        p,
        "--models",
        "hertz,kelvin-voigt,hunt-crossley",
        "--error",
        E,
        "--format",
        "json",
    ]);
    let rows = j["rows"].as_array().unwrap();
    assert_eq!(rows[0]["model"], "hunt-crossley", "{j}");
    assert!(
        rows[0]["feasible"]
            .as_str()
            .unwrap()
            .starts_with("sigma_b ∈ [")
    );
    let kv = rows.iter().find(|r| r["model"] == "kelvin-voigt").unwrap();
    assert_eq!(kv["refuted_everywhere"], true);
    assert!(kv["delta_aic"].as_f64().unwrap() > 10.0);
    // AIC: M ln(J²/M) + 2(k + 1)
    let hc = &rows[0];
    let (m, jj) = (10.0, hc["J"].as_f64().unwrap());
    let want = m * (jj * jj / m).ln() + 4.0;
    assert!((hc["aic"].as_f64().unwrap() - want).abs() < 1e-9);
}

#[test]
fn compare_states_what_it_proved() {
    // a sigma column weights the fits, but the feasible sets are at ±E for every row: with
    // E = 0.5 the constant-CoR law fits both rows (a review found the column used instead)
    let dir = std::env::temp_dir();
    let sig = dir.join(format!("bwcl-compare-{}-sigma.csv", std::process::id()));
    std::fs::write(&sig, "v0,e,sigma\n1,0.9,0.001\n2,0.8,0.001\n").unwrap();
    let j = json(&[
        "compare",
        "--data",
        sig.to_str().unwrap(),
        "--models",
        "kelvin-voigt",
        "--error",
        "0.5",
        "--format",
        "json",
    ]);
    let f = j["rows"][0]["feasible"].as_str().unwrap();
    assert!(f.starts_with("zeta ∈ ["), "{f}");
    // F reaching the searched box's end is not printed as all of F
    let low = dir.join(format!("bwcl-compare-{}-low.csv", std::process::id()));
    std::fs::write(&low, "v0,e\n1,0.003\n2,0.004\n").unwrap();
    let j = json(&[
        "compare",
        "--data",
        low.to_str().unwrap(),
        "--models",
        "kelvin-voigt",
        "--error",
        "0.01",
        "--format",
        "json",
    ]);
    let f = j["rows"][0]["feasible"].as_str().unwrap();
    assert!(f.contains("may reach past the searched 0..10"), "{f}");
}

#[test]
fn bad_input_gets_one_line_and_exit_2() {
    let path = write("bad", &hc_data());
    let p = path.to_str().unwrap();
    let tc = std::env::temp_dir().join(format!("bwcl-compare-{}-tc.csv", std::process::id()));
    std::fs::write(&tc, "v0,e,tc\n1,0.8,1.2\n2,0.7,1.1\n").unwrap();
    for (args, needle) in [
        (
            vec![
                "fit",
                "--model",
                "hunt-crossley",
                "--data",
                p,
                "--fix",
                "kappa=0.6",
            ],
            "--fix",
        ),
        (
            vec![
                "identify",
                "--model",
                "kelvin-voigt",
                "--data",
                p,
                "--error",
                "0.02",
                "--bounds",
                "c=1..2",
            ],
            "'c'",
        ),
        (
            vec![
                "identify",
                "--model",
                "hunt-crossley",
                "--data",
                p,
                "--error",
                "0.02",
                "--bounds",
                "sigma_b=-1..2",
            ],
            "admissible",
        ),
        (
            vec![
                "fit",
                "--model",
                "linear-maxwell",
                "--data",
                p,
                "--bounds",
                "c=0.3..2",
            ],
            "never separates",
        ),
        (
            vec!["identify", "--model", "hunt-crossley", "--data", p],
            "error of e",
        ),
        (
            vec![
                "identify",
                "--model",
                "hunt-crossley",
                "--data",
                tc.to_str().unwrap(),
                "--error",
                "0.1",
            ],
            "--no-tc",
        ),
        (
            vec!["compare", "--data", p, "--models", "shc,foo\u{1b}"],
            "'foo\\x1b'",
        ),
        (vec!["compare", "--data", p, "--error", "-1"], "--error"),
        (vec!["compare", "--data", p, "--models", ","], "no model"),
        (
            vec![
                "identify",
                "--model",
                "hunt-crossley",
                "--data",
                p,
                "--error",
                "0.02",
                "--bounds",
                "sigma_b=0..1e300",
            ],
            "beyond",
        ),
    ] {
        let o = bwcl(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?}");
    }
}
