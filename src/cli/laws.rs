//! `bwcl laws`: the published Hunt–Crossley damping formulas against the CoR the law really
//! produces, proved ([`bwcl::observables::restitution`]).
//!
//! For each formula: at a grid of target CoRs e* (decimals, enclosed as written) the damping
//! σ(e*), the proved CoR e(σ(e*)) and the error e − e*; and over the whole range of targets
//! the runs where |e − e*| ≤ tol is proved, where |e − e*| > tol is proved, and what is left
//! undecided at the paving's floor. Everything is validated before anything is computed.

use super::CliError;
use super::args::{Format, LawsArgs};
use super::output::{self, outward_pair};
use bwcl::arith::Real;
use bwcl::fit::data::echo;
use bwcl::models::hunt_crossley::DampingFormula;
use bwcl::observables::decimal::{self, Rounding, parse_rational};
use bwcl::observables::restitution::{
    Big, FormulaPoint, FormulaStudy as FormulaResult, MIN_WIDTH, Segment, Verdict, study,
};
use inari::Interval;
use serde::Serialize;
use std::time::Instant;

/// The largest grid.
const MAX_POINTS: usize = 10_000;

/// The range of targets "a..b" with 0 < a < b < 1.
fn targets(text: &str) -> Result<(String, String), CliError> {
    let bad = || {
        CliError::Input(format!(
            "--e-star '{}' must be a range a..b of target CoRs with 0 < a < b < 1",
            echo(text)
        ))
    };
    let (a, b) = text.split_once("..").ok_or_else(bad)?;
    let (a, b) = (a.trim(), b.trim());
    let (ra, rb) = (
        parse_rational(a).ok_or_else(bad)?,
        parse_rational(b).ok_or_else(bad)?,
    );
    if !(ra > 0 && ra < rb && rb < 1) {
        return Err(bad());
    }
    Ok((a.to_string(), b.to_string()))
}

fn formulas(list: &str) -> Result<Vec<DampingFormula>, CliError> {
    if list == "all" {
        return Ok(DampingFormula::ALL.to_vec());
    }
    let mut out = Vec::new();
    for k in list.split(',') {
        if k.trim() == "all" {
            return Err(CliError::Input(format!(
                "--formulas '{}': all stands alone, not in a list",
                echo(list)
            )));
        }
        let f = DampingFormula::from_key(k.trim()).ok_or_else(|| {
            CliError::Input(format!(
                "--formulas: '{}' is not a formula (one of all, {})",
                echo(k),
                DampingFormula::ALL.map(|f| f.key()).join(", ")
            ))
        })?;
        if !out.contains(&f) {
            out.push(f);
        }
    }
    Ok(out)
}

fn tolerance(text: &str) -> Result<Big, CliError> {
    let t = Big::parse_decimal(text).ok();
    match t {
        Some(t) if t.lo() > 0.0 && t.hi() < 1.0 => Ok(t),
        _ => Err(CliError::Input(format!(
            "--tol '{}' must be a number in (0, 1)",
            echo(text)
        ))),
    }
}

pub fn laws(a: &LawsArgs) -> Result<i32, CliError> {
    let bytes = report(a)?;
    output::emit(a.out.as_deref(), &bytes)?;
    Ok(super::EXIT_OK)
}

/// The output of `bwcl laws` (everything validated first, then computed).
pub fn report(a: &LawsArgs) -> Result<Vec<u8>, CliError> {
    let list = formulas(&a.formulas)?;
    let (lo, hi) = targets(&a.e_star)?;
    if !(2..=MAX_POINTS).contains(&a.points) {
        return Err(CliError::Input(format!(
            "--points {} must be between 2 and {MAX_POINTS}",
            a.points
        )));
    }
    let tol = tolerance(&a.tol)?;
    super::input::out_path(a.out.as_deref())?;
    let start = Instant::now();
    let results = study(&list, &lo, &hi, a.points, &tol, MIN_WIDTH).map_err(CliError::Failed)?;
    let seconds = start.elapsed().as_secs_f64();
    match a.format {
        Format::Table => Ok(table(&results, &a.tol, seconds).into_bytes()),
        Format::Csv => csv(&results),
        Format::Json => json(&results, &a.tol, seconds),
    }
}

fn f64s(x: &Big) -> Interval {
    x.to_interval()
}

/// The largest |error| on the grid, rounded up.
fn max_abs(points: &[(String, FormulaPoint)]) -> f64 {
    points
        .iter()
        .map(|(_, p)| f64s(&p.error).mag())
        .fold(0.0, f64::max)
}

fn verdict(v: Verdict) -> &'static str {
    match v {
        Verdict::Within => "within",
        Verdict::Outside => "outside",
        Verdict::Undecided => "undecided",
    }
}

/// A segment's ends: a proved run (within, outside) printed inward, so that the printed range
/// lies inside the proved one; an undecided run outward, so that it covers what is undecided.
fn segment_ends(s: &Segment) -> [String; 2] {
    let d = |x: f64, r| {
        decimal::directed(x, 7, r)
            .map(|d| d.plain())
            .unwrap_or_else(|| format!("{x}"))
    };
    match s.verdict {
        Verdict::Undecided => [d(s.lo, Rounding::Down), d(s.hi, Rounding::Up)],
        _ => [d(s.lo, Rounding::Up), d(s.hi, Rounding::Down)],
    }
}

/// "e* ∈ [a, b] ∪ [c, d]" of a verdict's runs, or "none".
fn runs(segs: &[Segment], v: Verdict) -> String {
    let r: Vec<String> = segs
        .iter()
        .filter(|s| s.verdict == v)
        .map(|s| {
            let [a, b] = segment_ends(s);
            format!("[{a}, {b}]")
        })
        .collect();
    if r.is_empty() {
        "none".into()
    } else {
        r.join(" ∪ ")
    }
}

fn table(results: &[FormulaResult], tol: &str, seconds: f64) -> String {
    let head = [
        "formula",
        "σ(e*)",
        "max |e − e*| on the grid",
        "|e − e*| ≤ tol proved for e* in",
    ];
    let rows: Vec<Vec<String>> = results
        .iter()
        .map(|r| {
            vec![
                r.formula.source().to_string(),
                r.formula.formula().to_string(),
                decimal::sci_up(max_abs(&r.points), 3),
                runs(&r.segments, Verdict::Within),
            ]
        })
        .collect();
    let mut s = format!(
        "Hunt–Crossley law F = k|δ|^(n−1)δ + χ|δ|^n δ̇ tuned by a formula σ = χv0/k = σ(e*) for a \
         target CoR e*: the CoR e it really produces (proved; n does not enter), tol = {tol}\n\n"
    );
    s.push_str(&output::table(&head, &rows));
    let undecided: Vec<String> = results
        .iter()
        .filter(|r| r.segments.iter().any(|s| s.verdict == Verdict::Undecided))
        .map(|r| {
            format!(
                "{}: {}",
                r.formula.key(),
                runs(&r.segments, Verdict::Undecided)
            )
        })
        .collect();
    if !undecided.is_empty() {
        s.push_str(&format!(
            "\nundecided at the floor ({MIN_WIDTH:e} wide): {}\n",
            undecided.join("; ")
        ));
    }
    s.push_str(&format!(
        "\n{} formulas × {} targets, and the paving of the range, in {seconds:.2} s\n",
        results.len(),
        results.first().map_or(0, |r| r.points.len())
    ));
    s
}

fn csv(results: &[FormulaResult]) -> Result<Vec<u8>, CliError> {
    let head = [
        "formula", "e_star", "sigma_lo", "sigma_hi", "e_lo", "e_hi", "error_lo", "error_hi",
    ];
    let rows = results.iter().flat_map(|r| {
        r.points.iter().map(move |(t, p)| {
            let [sl, sh] = outward_pair(f64s(&p.sigma));
            let [el, eh] = outward_pair(f64s(&p.e));
            let [dl, dh] = outward_pair(f64s(&p.error));
            vec![
                r.formula.key().to_string(),
                t.clone(),
                sl,
                sh,
                el,
                eh,
                dl,
                dh,
            ]
        })
    });
    output::csv(&head, rows)
}

#[derive(Serialize)]
struct JsonPoint {
    e_star: String,
    sigma: [String; 2],
    e: [String; 2],
    error: [String; 2],
}

#[derive(Serialize)]
struct JsonSegment {
    lo: String,
    hi: String,
    verdict: &'static str,
}

#[derive(Serialize)]
struct JsonFormula {
    key: &'static str,
    source: &'static str,
    sigma: &'static str,
    max_abs_error: String,
    points: Vec<JsonPoint>,
    segments: Vec<JsonSegment>,
}

#[derive(Serialize)]
struct JsonOut {
    tol: String,
    formulas: Vec<JsonFormula>,
    seconds: f64,
}

fn json(results: &[FormulaResult], tol: &str, seconds: f64) -> Result<Vec<u8>, CliError> {
    let out = JsonOut {
        tol: tol.to_string(),
        formulas: results
            .iter()
            .map(|r| JsonFormula {
                key: r.formula.key(),
                source: r.formula.source(),
                sigma: r.formula.formula(),
                max_abs_error: output::outward(max_abs(&r.points), Rounding::Up),
                points: r
                    .points
                    .iter()
                    .map(|(t, p)| JsonPoint {
                        e_star: t.clone(),
                        sigma: outward_pair(f64s(&p.sigma)),
                        e: outward_pair(f64s(&p.e)),
                        error: outward_pair(f64s(&p.error)),
                    })
                    .collect(),
                segments: r
                    .segments
                    .iter()
                    .map(|s| {
                        let [lo, hi] = segment_ends(s);
                        JsonSegment {
                            lo,
                            hi,
                            verdict: verdict(s.verdict),
                        }
                    })
                    .collect(),
            })
            .collect(),
        seconds,
    };
    output::json(&out)
}
