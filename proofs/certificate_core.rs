//! Core of `proof-certificate`: proved enclosures of T_s and e for the Table 1 sets at the
//! paper's speeds (`nd_from_base` with interval parameters enclosing the decimals, then
//! `rigorous_impact`), their JSON certificate, and its independent check.
//!
//! Bounds are stored as exact doubles twice: `dec`, the shortest decimal on the outer side of
//! the bound (lo rounded down, hi up) that parses back to the same double
//! (`bwcl::observables::decimal::outward`), and the IEEE-754 bit pattern in hex; `check` reads
//! the bits and checks that `dec` is that double and lies on the outer side of it.
#![allow(dead_code)]

use bwcl::arith::Real;
use bwcl::engines::dop853::Options;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::scaling::nd_from_base;
use bwcl::models::{Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::decimal::{Rounding, outward, parse_rational, width_up};
use bwcl::observables::rigorous::rigorous_impact;
use bwcl::observables::{FloatOptions, impact};
use inari::Interval;
use serde_json::{Value, json};

pub const SETS: [(&str, ModelKind, &str); 4] = bwcl::models::params::TABLE1;

pub const SPEEDS: [&str; 7] = ["0.1", "0.5", "1", "2", "3", "4", "5"];

/// Proved (T_s, e) for a base set at v0 (decimals enclosed as written).
pub fn enclose(kind: ModelKind, base: &str, v0: &str) -> Result<(Interval, Interval), String> {
    let b = NdParams::<Interval>::parse(kind, base).map_err(|e| e.0)?;
    let v = <Interval as Real>::parse_decimal(v0)?;
    let p = nd_from_base(kind, &b, &v).map_err(|e| e.0)?;
    let opts = TaylorOptions::default();
    let r = match kind {
        ModelKind::Shc => rigorous_impact(&Shc::new(p), &opts).map(|r| (r.ts, r.e)),
        ModelKind::Maxwell => rigorous_impact(&Maxwell::new(p), &opts).map(|r| (r.ts, r.e)),
    };
    r.map_err(|e| format!("{e}"))
}

/// e from DOP853 at rtol 1e-13 (f64 parameters: the nearest doubles to the decimals).
pub fn float_e(kind: ModelKind, base: &str, v0: &str) -> Result<f64, String> {
    let b = NdParams::<f64>::parse(kind, base).map_err(|e| e.0)?;
    let v: f64 = v0.parse().map_err(|_| format!("bad v0 {v0}"))?;
    let p = nd_from_base(kind, &b, &v).map_err(|e| e.0)?;
    let opts = FloatOptions {
        ode: Options {
            rtol: 1e-13,
            atol: 1e-15,
            ..Options::paper()
        },
        ..Default::default()
    };
    let r = match kind {
        ModelKind::Shc => impact(&Shc::new(p), &opts).map(|r| r.e),
        ModelKind::Maxwell => impact(&Maxwell::new(p), &opts).map(|r| r.e),
    };
    r.map_err(|e| format!("{e}"))
}

fn bound(x: f64, dir: Rounding) -> Value {
    json!({ "dec": outward(x, dir), "bits": format!("{:#018x}", x.to_bits()) })
}

fn interval_json(i: Interval) -> Value {
    json!({ "lo": bound(i.inf(), Rounding::Down), "hi": bound(i.sup(), Rounding::Up) })
}

/// An enclosure as text for the log lines, rounded outward.
pub fn show(i: Interval) -> String {
    format!(
        "[{}, {}]",
        outward(i.inf(), Rounding::Down),
        outward(i.sup(), Rounding::Up)
    )
}

/// A width as text, rounded up (2 digits).
fn show_width(i: Interval) -> String {
    bwcl::observables::decimal::sci_up(width_up(i.inf(), i.sup()), 2)
}

/// Relative margin by which stored claims are wider than the proved enclosures, so that a
/// re-proof by another build (last-ulp differences) still lies inside them.
pub const MARGIN: f64 = 1e-14;

/// The interval widened outward by [`MARGIN`] (relative): still proved, since it contains a
/// proved enclosure.
pub fn widen(x: Interval) -> Interval {
    let lo = (x.inf() - MARGIN * x.inf().abs()).next_down();
    let hi = (x.sup() + MARGIN * x.sup().abs()).next_up();
    Interval::try_from((lo, hi)).unwrap()
}

/// One certificate entry: the claim is the proved enclosure widened by [`MARGIN`].
pub fn entry(name: &str, kind: ModelKind, base: &str, v0: &str) -> Result<Value, String> {
    let (ts, e) = enclose(kind, base, v0)?;
    let (ts, e) = (widen(ts), widen(e));
    Ok(json!({
        "set": name,
        "model": kind.name(),
        "base": base,
        "v0": v0,
        "T_s": interval_json(ts),
        "e": interval_json(e),
        "e_width": outward(width_up(e.inf(), e.sup()), Rounding::Up),
    }))
}

/// The whole certificate (28 entries).
pub fn certificate() -> Result<Value, String> {
    let mut entries = Vec::new();
    for (name, kind, base) in SETS {
        for v0 in SPEEDS {
            entries.push(entry(name, kind, base, v0)?);
        }
    }
    Ok(json!({
        "what": "proved enclosures of the separation time T_s and the CoR e for the Table 1 base sets at v0 (nd_from_base with interval parameters enclosing the decimals, rigorous_impact with TaylorOptions::default())",
        "generator": "cargo run --release --bin proof-certificate -- write",
        "entries": entries,
    }))
}

/// A stored bound: its bits, after checking that `dec` reads back to them and, as an exact
/// decimal, lies on side `dir` of them (a printed lower bound ≤ the double, upper ≥).
pub fn read_bound(v: &Value, dir: Rounding) -> Result<f64, String> {
    let s = v["bits"].as_str().ok_or("missing bits")?;
    let bits = u64::from_str_radix(s.trim_start_matches("0x"), 16).map_err(|e| e.to_string())?;
    let x = f64::from_bits(bits);
    let dec = v["dec"].as_str().ok_or("missing dec")?;
    // the decimal must be the same double
    let d: f64 = dec.parse().map_err(|_| "bad dec")?;
    if d.to_bits() != bits {
        return Err(format!("dec {dec} and bits {s} disagree"));
    }
    // and a bound of it as a decimal
    let (exact, xr) = match (parse_rational(dec), rug::Rational::from_f64(x)) {
        (Some(a), Some(b)) => (a, b),
        _ => return Err(format!("dec {dec} is not a finite decimal")),
    };
    let outward = match dir {
        Rounding::Down => exact <= xr,
        Rounding::Up => exact >= xr,
    };
    if !outward {
        return Err(format!(
            "dec {dec} lies inside the bound {s}: not rounded {dir:?}"
        ));
    }
    Ok(x)
}

fn read_interval(v: &Value) -> Result<Interval, String> {
    let (a, b) = (
        read_bound(&v["lo"], Rounding::Down)?,
        read_bound(&v["hi"], Rounding::Up)?,
    );
    Interval::try_from((a, b)).map_err(|_| format!("[{a}, {b}] is not an interval"))
}

/// Checks one stored entry: re-proves the enclosures (the stored claims must contain them) and
/// the DOP853 e at rtol 1e-13 (within the stored e ± 1e-11). Returns a one-line report.
pub fn check_entry(v: &Value) -> Result<String, String> {
    let name = v["set"].as_str().ok_or("missing set")?;
    let kind = match v["model"].as_str() {
        Some("shc") => ModelKind::Shc,
        Some("maxwell") => ModelKind::Maxwell,
        m => return Err(format!("unknown model {m:?}")),
    };
    let base = v["base"].as_str().ok_or("missing base")?;
    let v0 = v["v0"].as_str().ok_or("missing v0")?;
    let (sts, se) = (read_interval(&v["T_s"])?, read_interval(&v["e"])?);
    let (ts, e) = enclose(kind, base, v0)?;
    // the check re-proves each claim: the recomputed enclosure must lie inside the stored one
    // (which is why `write` stores the enclosures widened by MARGIN)
    let relation = |s: Interval, r: Interval| {
        if s.inf() <= r.inf() && r.sup() <= s.sup() {
            Ok("re-proved: contains the recomputed enclosure")
        } else {
            Err(())
        }
    };
    let (Ok(rts), Ok(re)) = (relation(sts, ts), relation(se, e)) else {
        return Err(format!(
            "{name} v0={v0}: stored T_s {} / e {} not re-proved: the recomputed enclosure is not inside it, T_s {} / e {}",
            show(sts),
            show(se),
            show(ts),
            show(e)
        ));
    };
    let ef = float_e(kind, base, v0)?;
    if !(se.inf() - 1e-11 <= ef && ef <= se.sup() + 1e-11) {
        return Err(format!(
            "{name} v0={v0}: DOP853 e = {ef} ∉ {} ± 1e-11",
            show(se)
        ));
    }
    Ok(format!(
        "{name} v0={v0}: T_s ∈ {} ({rts}), e ∈ {} (width {}, {re}); DOP853(1e-13) e = {ef:e} (distance to the enclosure {:.1e})",
        show(sts),
        show(se),
        show_width(se),
        (se.inf() - ef).max(ef - se.sup()).max(0.0)
    ))
}
