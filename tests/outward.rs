//! Every enclosure `bwcl cor --rigorous` prints is a bound as a decimal: each printed lower
//! bound, read as an exact rational, is ≤ the double lower bound the library proves for the same
//! case, each upper bound ≥ the upper one, each width ≥ the exact width, in the table, CSV and
//! JSON formats. JSON and CSV print the shortest such decimal, which must also read back to the
//! very double (so these are the library's doubles); the table prints 17 digits, within one
//! double of the bound. The speeds v0 a result holds for are printed inward instead (each end
//! reading back to its double). Also: the stored decimals of the proof certificate.

use crate::certificate_core;

use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::scaling::{PhysicalParams, nd_from_base, parse_speeds};
use bwcl::models::{Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::decimal::{Rounding, parse_rational};
use bwcl::observables::rigorous::rigorous_impact;
use inari::Interval;
use rug::Rational;
use serde_json::value::RawValue;
use std::collections::BTreeMap;
use std::process::Command;

const DSS: &str = "1.43,-1.42,0.632,0.00715,1.31,1.27";
const MAXWELL_DSA: &str = "0.44,-0.418,0.113,0.00785,1.27,3.14";
const SPEEDS: &str = "0.1,0.5,1,2,3,4,5";
const BASEBALL: &str =
    "m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925";
/// Sub-ranges of a v0 range (small, for a quick test).
const PIECES: usize = 4;

/// One case as the library proves it (the same construction as the CLI's).
struct Expected {
    v0: Option<Interval>,
    ts: Interval,
    e: Interval,
    ts_seconds: Option<Interval>,
    params: NdParams<Interval>,
}

/// How the CLI is told about the parameters.
#[derive(Clone, Copy)]
enum Set<'a> {
    Base(ModelKind, &'a str, &'a str),
    Nd(ModelKind, &'a str),
    Physical(ModelKind, &'a str, &'a str),
}

fn model_name(kind: ModelKind) -> &'static str {
    match kind {
        ModelKind::Shc => "shc",
        ModelKind::Maxwell => "maxwell",
    }
}

fn args(set: Set, format: &str) -> Vec<String> {
    let mut a: Vec<String> = vec!["cor".into()];
    let (kind, rest): (ModelKind, Vec<&str>) = match set {
        Set::Base(k, b, v) => (k, vec!["--base", b, "--v0", v]),
        Set::Nd(k, p) => (k, vec!["--nd", p]),
        Set::Physical(k, p, v) => (k, vec!["--physical", p, "--v0", v]),
    };
    a.extend(["--model", model_name(kind)].map(String::from));
    a.extend(rest.into_iter().map(String::from));
    a.extend(
        [
            "--rigorous",
            "--pieces",
            &PIECES.to_string(),
            "--format",
            format,
        ]
        .map(String::from),
    );
    a
}

fn prove(kind: ModelKind, p: NdParams<Interval>) -> (Interval, Interval) {
    let opts = TaylorOptions::default();
    let r = match kind {
        ModelKind::Shc => rigorous_impact(&Shc::new(p), &opts).map(|r| (r.ts, r.e)),
        ModelKind::Maxwell => rigorous_impact(&Maxwell::new(p), &opts).map(|r| (r.ts, r.e)),
    };
    r.expect("the library proves the case")
}

/// The library's enclosures for the cases of `set`, in the CLI's order.
fn expected(set: Set) -> Vec<Expected> {
    let wide = |v: &Interval| v.wid() > 4.0 * f64::EPSILON * v.mag();
    match set {
        Set::Nd(kind, text) => {
            let p = NdParams::<Interval>::parse(kind, text).unwrap();
            let (ts, e) = prove(kind, p.clone());
            vec![Expected {
                v0: None,
                ts,
                e,
                ts_seconds: None,
                params: p,
            }]
        }
        Set::Base(kind, base, speeds) => {
            let b = NdParams::<Interval>::parse(kind, base).unwrap();
            parse_speeds::<Interval>(speeds)
                .unwrap()
                .into_iter()
                .map(|v| {
                    let p = nd_from_base(kind, &b, &v).unwrap();
                    let (ts, e) = if wide(&v) {
                        let opts = TaylorOptions::default();
                        // the CLI's own computation of a range (issue #13)
                        let inputs = bwcl::observables::sets::Inputs::Base {
                            base: b.clone(),
                            v0: v,
                        };
                        let split = bwcl::observables::split::SplitOptions {
                            max_pieces: PIECES,
                            ..Default::default()
                        };
                        let r = bwcl::observables::split::prove_over_set_adaptive(
                            kind, &inputs, &opts, &split,
                        )
                        .unwrap();
                        (r.ts, r.e)
                    } else {
                        prove(kind, p.clone())
                    };
                    Expected {
                        v0: Some(v),
                        ts,
                        e,
                        ts_seconds: None,
                        params: p,
                    }
                })
                .collect()
        }
        Set::Physical(kind, phys, speeds) => {
            let ph = PhysicalParams::<Interval>::parse(kind, phys).unwrap();
            parse_speeds::<Interval>(speeds)
                .unwrap()
                .into_iter()
                .map(|v| {
                    assert!(!wide(&v), "point speeds only here");
                    // as the CLI: through the base set unless v0 is a point double
                    let p = if v.inf() < v.sup() {
                        nd_from_base(kind, &ph.base(kind).unwrap(), &v).unwrap()
                    } else {
                        ph.nondimensionalize(kind, &v).unwrap()
                    };
                    let (ts, e) = prove(kind, p.clone());
                    Expected {
                        v0: Some(v),
                        ts,
                        e,
                        ts_seconds: Some(ts * ph.scales(&v).t_c),
                        params: p,
                    }
                })
                .collect()
        }
    }
}

fn run(set: Set, format: &str) -> String {
    let a = args(set, format);
    let o = Command::new(env!("CARGO_BIN_EXE_bwcl"))
        .args(&a)
        .output()
        .expect("bwcl runs");
    assert_eq!(
        o.status.code(),
        Some(0),
        "{a:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

fn exact(x: f64) -> Rational {
    Rational::from_f64(x).expect("a finite bound")
}

/// How closely a printed bound must match the double besides being on its outer side.
#[derive(Clone, Copy)]
enum Tight {
    /// Reads back to the double itself (the shortest outward decimal of JSON and CSV).
    ReadsBack,
    /// Strictly between the double and its outer neighbour (17 digits in the table).
    WithinOneDouble,
}

/// `text`, a printed bound, lies on side `dir` of the double `x` exactly, and as close as `t`.
fn check_bound(what: &str, text: &str, x: f64, dir: Rounding, t: Tight) {
    let printed = parse_rational(text).unwrap_or_else(|| panic!("{what}: '{text}' is no decimal"));
    let ok = match dir {
        Rounding::Down => printed <= exact(x),
        Rounding::Up => printed >= exact(x),
    };
    assert!(
        ok,
        "{what}: printed {text} is not a {dir:?}-rounded bound of {x:e}"
    );
    match t {
        Tight::ReadsBack => {
            assert_eq!(
                text.parse::<f64>().unwrap(),
                x,
                "{what}: {text} is not {x:e}"
            )
        }
        Tight::WithinOneDouble => {
            let outer = match dir {
                Rounding::Down => x.next_down(),
                Rounding::Up => x.next_up(),
            };
            let inside = match dir {
                Rounding::Down => printed > exact(outer),
                Rounding::Up => printed < exact(outer),
            };
            assert!(inside, "{what}: {text} is beyond the next double of {x:e}");
        }
    }
}

fn check_pair(what: &str, lo: &str, hi: &str, i: Interval, t: Tight) {
    check_bound(&format!("{what} lo"), lo, i.inf(), Rounding::Down, t);
    check_bound(&format!("{what} hi"), hi, i.sup(), Rounding::Up, t);
}

/// The speeds a result holds for (v0, a point's enclosure or a range a..b): printed inward, each
/// end reading back to its double — a printed range claims no speed the run did not cover.
fn check_speeds(what: &str, lo: &str, hi: &str, i: Interval) {
    let t = Tight::ReadsBack;
    check_bound(&format!("{what} lo"), lo, i.inf(), Rounding::Up, t);
    check_bound(&format!("{what} hi"), hi, i.sup(), Rounding::Down, t);
    assert!(
        parse_rational(lo) <= parse_rational(hi),
        "{what}: [{lo}, {hi}] crossed"
    );
}

/// A printed width is ≥ the exact width of the library's enclosure (and no looser than the
/// double rounded up, which reads back).
fn check_width(what: &str, text: &str, i: Interval) {
    let w = parse_rational(text).unwrap_or_else(|| panic!("{what}: '{text}' is no decimal"));
    let true_w = exact(i.sup()) - exact(i.inf());
    assert!(
        w >= true_w,
        "{what}: printed width {text} < the exact width"
    );
}

/// The bracketed cells `[a, b]` of a table line, with the word after each.
fn brackets(line: &str) -> Vec<(String, String, String)> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(i) = rest.find('[') {
        let j = rest[i..].find(']').expect("closed bracket") + i;
        let (a, b) = rest[i + 1..j].split_once(", ").expect("two bounds");
        rest = &rest[j + 1..];
        let next = rest.split_whitespace().next().unwrap_or("").to_string();
        out.push((a.to_string(), b.to_string(), next));
    }
    out
}

fn check_table(set: Set, exp: &[Expected]) {
    let text = run(set, "table");
    let lines: Vec<&str> = text.lines().skip(1).collect();
    assert_eq!(lines.len(), exp.len(), "{text}");
    let t = Tight::WithinOneDouble;
    for (line, x) in lines.iter().zip(exp) {
        let mut cells = brackets(line);
        let range = x.v0.is_some_and(|v| v.wid() > 4.0 * f64::EPSILON * v.mag());
        if range {
            let (a, b, _) = cells.remove(0);
            check_speeds("table v0", &a, &b, x.v0.unwrap());
        }
        let n = if x.ts_seconds.is_some() { 3 } else { 2 };
        assert_eq!(cells.len(), n, "{line}");
        check_pair("table ts", &cells[0].0, &cells[0].1, x.ts, t);
        check_width("table width_ts", &cells[0].2, x.ts);
        check_pair("table e", &cells[1].0, &cells[1].1, x.e, t);
        check_width("table width_e", &cells[1].2, x.e);
        if let Some(s) = x.ts_seconds {
            check_pair("table ts_seconds", &cells[2].0, &cells[2].1, s, t);
        }
    }
}

fn check_csv(set: Set, exp: &[Expected]) {
    let text = run(set, "csv");
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).expect(name);
    let t = Tight::ReadsBack;
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), exp.len(), "{text}");
    for (r, x) in rows.iter().zip(exp) {
        if let Some(v) = x.v0 {
            check_speeds("csv v0", r[col("v0_lo")], r[col("v0_hi")], v);
        }
        check_pair("csv ts", r[col("ts_lo")], r[col("ts_hi")], x.ts, t);
        check_width("csv width_ts", r[col("width_ts")], x.ts);
        check_pair("csv e", r[col("e_lo")], r[col("e_hi")], x.e, t);
        check_width("csv width_e", r[col("width_e")], x.e);
        if let Some(s) = x.ts_seconds {
            let (a, b) = (r[col("ts_seconds_lo")], r[col("ts_seconds_hi")]);
            check_pair("csv ts_seconds", a, b, s, t);
        }
    }
}

/// A JSON pair `[lo, hi]` as the two numbers' exact texts.
fn raw_pair(v: &RawValue) -> (String, String) {
    let p: Vec<Box<RawValue>> = serde_json::from_str(v.get()).expect("an array");
    assert_eq!(p.len(), 2);
    (p[0].get().to_string(), p[1].get().to_string())
}

fn check_json(set: Set, exp: &[Expected]) {
    let text = run(set, "json");
    let rows: Vec<BTreeMap<String, Box<RawValue>>> = serde_json::from_str(&text).unwrap();
    assert_eq!(rows.len(), exp.len(), "{text}");
    let t = Tight::ReadsBack;
    for (r, x) in rows.iter().zip(exp) {
        let pair = |k: &str, i: Interval| {
            let (a, b) = raw_pair(&r[k]);
            check_pair(&format!("json {k}"), &a, &b, i, t);
        };
        if let Some(v) = x.v0 {
            let (a, b) = raw_pair(&r["v0"]);
            check_speeds("json v0", &a, &b, v);
        }
        pair("ts", x.ts);
        pair("e", x.e);
        check_width("json width_ts", r["width_ts"].get(), x.ts);
        check_width("json width_e", r["width_e"].get(), x.e);
        if let Some(s) = x.ts_seconds {
            pair("ts_seconds", s);
        }
        // the parameters echoed as intervals
        let params: BTreeMap<String, Box<RawValue>> =
            serde_json::from_str(r["params"].get()).unwrap();
        let p = &x.params;
        for (k, i) in [
            ("B", p.b),
            ("Gamma", p.gamma),
            ("kappa", p.kappa),
            ("sigma", p.sigma),
            ("n", p.n),
            ("p", p.p),
        ] {
            let (a, b) = raw_pair(&params[k]);
            check_pair(&format!("json params.{k}"), &a, &b, i, t);
        }
    }
    // and the schema is unchanged: every number still reads as a JSON number
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(v[0]["e"][0].is_f64() && v[0]["params"]["B"][1].is_f64());
}

fn check_all_formats(set: Set) {
    let exp = expected(set);
    check_table(set, &exp);
    check_csv(set, &exp);
    check_json(set, &exp);
}

#[test]
fn shc_dss_table1_speeds_outward() {
    check_all_formats(Set::Base(ModelKind::Shc, DSS, SPEEDS));
}

#[test]
fn maxwell_dsa_table1_speeds_outward() {
    check_all_formats(Set::Base(ModelKind::Maxwell, MAXWELL_DSA, SPEEDS));
}

#[test]
fn nd_range_and_physical_outward() {
    check_all_formats(Set::Nd(ModelKind::Shc, "1,0,0.5,1,1,1.2"));
    check_all_formats(Set::Nd(ModelKind::Maxwell, "1,0,0.5,1,1,2.5"));
    check_all_formats(Set::Base(ModelKind::Shc, DSS, "1..1.01"));
    check_all_formats(Set::Physical(ModelKind::Shc, BASEBALL, "2.15,5.02"));
}

/// The round-to-nearest 17-digit form the table printed before is not a bound: on the DSS
/// run some printed lower bound lay above the double (the defect this file guards).
#[test]
fn nearest_rounding_would_not_be_outward() {
    let exp = expected(Set::Base(ModelKind::Shc, DSS, SPEEDS));
    let above = exp
        .iter()
        .flat_map(|x| [x.ts.inf(), x.e.inf()])
        .filter(|&lo| parse_rational(&format!("{lo:.16e}")).unwrap() > exact(lo))
        .count();
    assert!(
        above > 0,
        "no nearest-rounded lower bound lies above its double"
    );
}

/// Every stored decimal of the certificate is on the outer side of its bits (and reads back
/// to them): `read_bound` checks both.
#[test]
fn certificate_decimals_outward() {
    let text = std::fs::read_to_string("proofs/certificates/table1.json").unwrap();
    let c: serde_json::Value = serde_json::from_str(&text).unwrap();
    let entries = c["entries"].as_array().unwrap();
    assert_eq!(entries.len(), 28);
    for v in entries {
        for k in ["T_s", "e"] {
            certificate_core::read_bound(&v[k]["lo"], Rounding::Down).unwrap();
            certificate_core::read_bound(&v[k]["hi"], Rounding::Up).unwrap();
        }
        let w = parse_rational(v["e_width"].as_str().unwrap()).unwrap();
        let lo = certificate_core::read_bound(&v["e"]["lo"], Rounding::Down).unwrap();
        let hi = certificate_core::read_bound(&v["e"]["hi"], Rounding::Up).unwrap();
        assert!(w >= exact(hi) - exact(lo), "e_width below the width");
    }
    // a decimal on the wrong side is refused
    let x = 0.1f64;
    let bad = serde_json::json!({ "dec": "0.1", "bits": format!("{:#018x}", x.to_bits()) });
    assert!(certificate_core::read_bound(&bad, Rounding::Up).is_err());
    assert!(certificate_core::read_bound(&bad, Rounding::Down).is_ok());
}
