//! The Hunt–Crossley damping formulas and the proved CoR they produce (issue #33, item 3),
//! against two independent references:
//! - the restitution law's root at 400 bits (`tests/common`, Newton on plain MPFR floats, not
//!   the crate's interval code), bracketed to ±10⁻⁹⁰ and compared as exact rationals, with σ
//!   computed from each formula anew here in exact rational arithmetic;
//! - the rigorous ODE engine on the Hunt–Crossley limit of the NDBWSHCCM (B = 10⁻³⁰⁰, Γ = 0,
//!   n = p = 1.5), whose enclosure must contain the closed form's.

use bwcl::arith::Real;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::hunt_crossley::DampingFormula;
use bwcl::models::{NdParams, Shc};
use bwcl::observables::decimal::parse_rational;
use bwcl::observables::restitution::{Big, Verdict, cor_of_sigma, evaluate, pave_within};
use bwcl::observables::rigorous::rigorous_impact;
use inari::Interval;
use rug::Rational;

use crate::common;
use common::bwcl;

fn q(num: i64, den: i64) -> Rational {
    Rational::from((num, den))
}

/// σ(e*) of each rational formula, written again here in exact rationals.
fn sigma_exact(f: DampingFormula, e: &Rational) -> Option<Rational> {
    let one = Rational::from(1);
    let c = Rational::from(&one - e);
    let c2 = &one - Rational::from(e * e);
    Some(match f {
        DampingFormula::HuntCrossley => c * q(3, 2),
        DampingFormula::HerbertMcWhannell => {
            let d = Rational::from(e * 2u32) - 1u32;
            c * 6u32 / (Rational::from(&d * &d) + 3u32)
        }
        DampingFormula::LeeWang => c * q(3, 4),
        DampingFormula::LankaraniNikravesh => c2 * q(3, 4),
        DampingFormula::Gonthier => c2 / e,
        DampingFormula::Flores => c * 8u32 / (Rational::from(e * 5u32)),
        DampingFormula::GharibHurmuzlu => (one / e) - 1u32,
        DampingFormula::HuGuo => c * 3u32 / (Rational::from(e * 2u32)),
        DampingFormula::ZhiyingQishao | DampingFormula::CarvalhoMartins => return None,
    })
}

fn ends(x: &Big) -> (Rational, Rational) {
    (
        x.inf().to_rational().unwrap(),
        x.sup().to_rational().unwrap(),
    )
}

#[test]
fn every_rational_formula_contains_the_400_bit_root() {
    let targets = [(1, 20), (3, 10), (1, 2), (9, 10), (99, 100)];
    let mut checked = 0;
    for f in DampingFormula::ALL {
        for (n, d) in targets {
            let Some(s) = sigma_exact(f, &q(n, d)) else {
                continue;
            };
            let text = format!("{}", n as f64 / d as f64);
            let p = evaluate(f, &Big::parse_decimal(&text).unwrap()).unwrap();
            let (lo, hi) = common::hunt_crossley_bracket(&s);
            let (elo, ehi) = ends(&p.e);
            assert!(elo <= lo && hi <= ehi, "{f:?} at {text}: {:?}", p.e);
            // the error's enclosure holds the exact error of the exact target
            let (dlo, dhi) = ends(&p.error);
            let err = Rational::from(&lo - &q(n, d));
            assert!(dlo <= err && err <= dhi, "{f:?} at {text}");
            // and it is tight: far below the 1e-12
            assert!(p.e.wid_f64() < 1e-25, "{f:?} at {text}: {}", p.e.wid_f64());
            checked += 1;
        }
    }
    assert_eq!(checked, 8 * targets.len());
}

#[test]
fn the_exact_damping_gives_back_its_target_and_the_others_do_not() {
    for t in ["0.05", "0.5", "0.9"] {
        let e = Big::parse_decimal(t).unwrap();
        let exact = evaluate(DampingFormula::CarvalhoMartins, &e).unwrap();
        assert!(exact.e.encloses(&e), "{t}");
        // negative control: Hunt–Crossley's own first-order formula misses at these targets
        let hc = evaluate(DampingFormula::HuntCrossley, &e).unwrap();
        assert!(
            hc.error.hi() < 0.0 || hc.error.lo() > 0.0,
            "{t}: {:?}",
            hc.error
        );
    }
}

/// The closed form against the ODE engine: its enclosure of e on the Hunt–Crossley limit of
/// the NDBWSHCCM (n = p = 1.5) contains the closed form's (10⁻³⁰⁰ apart, far inside).
#[test]
fn the_ode_engine_agrees_with_the_closed_form() {
    for (f, t) in [
        (DampingFormula::LankaraniNikravesh, "0.5"),
        (DampingFormula::Flores, "0.8"),
        (DampingFormula::Gonthier, "0.3"),
    ] {
        let e_star = Big::parse_decimal(t).unwrap();
        let p = evaluate(f, &e_star).unwrap();
        // σ as a short decimal inside the formula's enclosure (the ODE takes decimals)
        let s = p.sigma.to_interval();
        let sigma = format!("{:.17e}", s.mid());
        let sb = Big::parse_decimal(&sigma).unwrap();
        let closed = cor_of_sigma(&sb).unwrap().to_interval();
        let nd = format!("1e-300,0,0.5,{sigma},1.5,1.5");
        let params = NdParams::<Interval>::parse(bwcl::models::ModelKind::Shc, &nd).unwrap();
        let r = rigorous_impact(&Shc::new(params), &TaylorOptions::default()).unwrap();
        assert!(
            r.e.inf() <= closed.inf() && closed.sup() <= r.e.sup(),
            "{f:?} at {t}: ODE {:?}, closed form {closed:?}",
            r.e
        );
        assert!(r.e.wid() < 1e-12, "{f:?} at {t}: {}", r.e.wid());
    }
}

#[test]
fn the_paving_proves_the_known_regimes() {
    let tol = Big::parse_decimal("0.001").unwrap();
    // Lankarani–Nikravesh: accurate for nearly elastic targets, not for e* ≤ 0.5
    let ln = pave_within(DampingFormula::LankaraniNikravesh, 0.3, 0.99, &tol, 1e-6);
    assert_eq!(ln.first().unwrap().verdict, Verdict::Outside);
    assert_eq!(ln.last().unwrap().verdict, Verdict::Within);
    // the exact damping is within everywhere
    let cm = pave_within(DampingFormula::CarvalhoMartins, 0.05, 0.99, &tol, 1e-6);
    assert!(cm.iter().all(|s| s.verdict == Verdict::Within), "{cm:?}");
    // each proved run's claim checked at its ends and middle against the 400-bit root, for
    // formulas whose errors are positive (LN) and negative (Flores, Gonthier)
    for f in [
        DampingFormula::LankaraniNikravesh,
        DampingFormula::Flores,
        DampingFormula::Gonthier,
    ] {
        let runs = pave_within(f, 0.05, 0.99, &tol, 1e-6);
        assert!(runs.iter().any(|s| s.verdict == Verdict::Within), "{f:?}");
        assert!(runs.iter().any(|s| s.verdict == Verdict::Outside), "{f:?}");
        for s in &runs {
            if s.verdict == Verdict::Undecided {
                continue;
            }
            for x in [s.lo, 0.5 * (s.lo + s.hi), s.hi] {
                let e = Rational::from_f64(x).unwrap();
                let sig = sigma_exact(f, &e).unwrap();
                let (lo, hi) = common::hunt_crossley_bracket(&sig);
                let tolq = q(1, 1000);
                let (elo, ehi) = (Rational::from(&lo - &e), Rational::from(&hi - &e));
                let within = elo.clone().abs() <= tolq && ehi.clone().abs() <= tolq;
                assert_eq!(within, s.verdict == Verdict::Within, "{f:?} at e* = {x}");
            }
        }
    }
}

fn stdout(args: &[&str]) -> String {
    common::bwcl_ok(args)
}

#[test]
fn the_csv_prints_outward_bounds_that_hold_the_references() {
    let out = stdout(&[
        "laws",
        "--formulas",
        "carvalho-martins,hunt-crossley",
        "--e-star",
        "0.3..0.9",
        "--points",
        "4",
        "--format",
        "csv",
    ]);
    let mut lines = out.lines();
    assert_eq!(
        lines.next().unwrap(),
        "formula,e_star,sigma_lo,sigma_hi,e_lo,e_hi,error_lo,error_hi"
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 8);
    for r in rows {
        let t = parse_rational(r[1]).unwrap();
        let (elo, ehi) = (parse_rational(r[4]).unwrap(), parse_rational(r[5]).unwrap());
        let want = match r[0] {
            "carvalho-martins" => (t.clone(), t.clone()),
            "hunt-crossley" => common::hunt_crossley_bracket(&(Rational::from(1 - &t) * q(3, 2))),
            other => panic!("{other}"),
        };
        assert!(elo <= want.0 && want.1 <= ehi, "{r:?}");
        assert!(
            Rational::from(&ehi - &elo) < q(1, 1_000_000_000_000),
            "{r:?}"
        );
    }
}

#[test]
fn the_json_runs_cover_the_range_as_written() {
    let out = stdout(&[
        "laws",
        "--formulas",
        "lee-wang,hu-guo",
        "--e-star",
        "0.3..0.9",
        "--points",
        "3",
        "--format",
        "json",
    ]);
    let d: serde_json::Value = serde_json::from_str(&out).unwrap();
    for f in d["formulas"].as_array().unwrap() {
        let segs = f["segments"].as_array().unwrap();
        let r = |v: &serde_json::Value| parse_rational(v.as_str().unwrap()).unwrap();
        // the ends are printed inward; the paving covers the range's decimals themselves
        assert!(r(&segs[0]["lo"]) <= q(3, 10), "{f}");
        assert!(r(&segs[segs.len() - 1]["hi"]) >= q(9, 10), "{f}");
        assert_eq!(f["points"].as_array().unwrap().len(), 3);
    }
}

#[test]
fn the_table_names_every_formula_and_its_proved_range() {
    // a narrow range of targets: the pavings of the default range (12 s on 2 cores) are
    // the_paving_proves_the_known_regimes'; here the table's shape
    let out = stdout(&["laws", "--points", "20", "--e-star", "0.5..0.7"]);
    for f in DampingFormula::ALL {
        assert!(out.contains(f.source()), "{}", f.source());
    }
    assert!(out.contains("∪") || out.contains('['));
}

#[test]
fn bad_options_get_one_line_and_exit_2() {
    for args in [
        vec!["laws", "--tol", "0"],
        vec!["laws", "--tol", "nan"],
        vec!["laws", "--e-star", "0..0.5"],
        vec!["laws", "--e-star", "0.9..0.1"],
        vec!["laws", "--e-star", "0.5"],
        vec!["laws", "--points", "1"],
        vec!["laws", "--formulas", "hertz"],
        vec!["laws", "--formulas", "flores,\u{1b}[31m"],
    ] {
        let o = bwcl(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8(o.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("bwcl: error: "), "{err}");
        assert!(!err.contains('\u{1b}'), "{err}");
        assert!(o.stdout.is_empty());
    }
}
