//! The classical Hunt–Crossley damping formulas against the CoR the law really produces
//! (issue #33, item 3): the proved errors e(σ(e*)) − e* on 100 targets over [0.05, 0.99], the
//! proved runs of targets where |e − e*| ≤ 10⁻³, a CSV, a plot and the REPORT section.
//!
//! The section is also written on its own between the markers `<!-- laws:begin -->` and
//! `<!-- laws:end -->` of an existing REPORT.md (`paper-repro laws`), so that it can be redone
//! in seconds without the report's long runs.

use crate::plot::{Chart, Series, save};
use bwcl::arith::Real;
use bwcl::models::hunt_crossley::DampingFormula;
use bwcl::observables::decimal::{self, Rounding};
use bwcl::observables::restitution::{Big, FormulaStudy, MIN_WIDTH, Verdict, evaluate, study};
use std::fmt::Write;
use std::path::Path;

pub const BEGIN: &str = "<!-- laws:begin -->";
pub const END: &str = "<!-- laws:end -->";

/// The study's range, grid and tolerance (issue #33: 100 values of e* in [0.05, 0.99]).
const LO: &str = "0.05";
const HI: &str = "0.99";
const POINTS: usize = 100;
/// The grid of `--quick` (the tests: the same study, coarser), and its narrowest pieces.
const QUICK_POINTS: usize = 12;
const QUICK_MIN_WIDTH: f64 = 1e-4;
const TOL: &str = "0.001";

pub struct Laws {
    pub studies: Vec<FormulaStudy>,
    /// Targets of the grid.
    pub points: usize,
    /// The narrowest pieces of the pavings.
    pub min_width: f64,
    pub seconds: f64,
}

/// The study on the grid, or the coarser one of `--quick`.
pub fn run(quick: bool) -> Result<Laws, String> {
    let t = std::time::Instant::now();
    let tol = Big::parse_decimal(TOL)?;
    let (points, min_width) = if quick {
        (QUICK_POINTS, QUICK_MIN_WIDTH)
    } else {
        (POINTS, MIN_WIDTH)
    };
    let studies = study(&DampingFormula::ALL, LO, HI, points, &tol, min_width)?;
    Ok(Laws {
        studies,
        points,
        min_width,
        seconds: t.elapsed().as_secs_f64(),
    })
}

/// laws_formula_errors.csv and the plot laws_formula_errors.{svg,png}.
pub fn write(out: &Path, laws: &Laws) -> Result<Vec<String>, String> {
    let mut csv = String::from("formula,e_star,error_lo,error_hi\n");
    let mut series = Vec::new();
    let greys = [0u8, 60, 110, 160, 200];
    for (i, s) in laws.studies.iter().enumerate() {
        let mut pts = Vec::new();
        for (t, p) in &s.points {
            let err = p.error.to_interval();
            writeln!(
                csv,
                "{},{t},{},{}",
                s.formula.key(),
                decimal::outward(err.inf(), Rounding::Down),
                decimal::outward(err.sup(), Rounding::Up)
            )
            .unwrap();
            pts.push((p.e_star.mid(), err.mid()));
        }
        series.push(Series::Line {
            label: format!("{} {}", s.formula.source(), s.formula.formula()),
            grey: greys[i % greys.len()],
            dashed: i >= greys.len(),
            points: pts,
        });
    }
    let path = out.join("laws_formula_errors.csv");
    std::fs::write(&path, &csv).map_err(|e| format!("writing '{}': {e}", path.display()))?;
    let mut files = vec![path.display().to_string()];
    let chart = Chart {
        title: "Hunt–Crossley damping formulas: the CoR error e − e* (proved)".into(),
        x_label: "target CoR e*".into(),
        y_label: "e − e*".into(),
        x_range: (0.0, 1.0),
        y_range: (-0.1, 0.7),
        series,
        legend_left: false,
    };
    files.extend(save(&chart, &out.join("laws_formula_errors"))?);
    Ok(files)
}

/// The proved runs of one verdict, inward decimals, or "none".
fn runs(s: &FormulaStudy, v: Verdict) -> String {
    let r: Vec<String> = s
        .segments
        .iter()
        .filter(|g| g.verdict == v)
        .map(|g| {
            let d = |x: f64, dir| decimal::directed(x, 4, dir).map(|d| d.plain()).unwrap();
            format!("[{}, {}]", d(g.lo, Rounding::Up), d(g.hi, Rounding::Down))
        })
        .collect();
    if r.is_empty() {
        "none".into()
    } else {
        r.join(" ∪ ")
    }
}

/// The error at the target `t` (a decimal), proved anew, as an outward interval, 3 digits.
fn error_at(s: &FormulaStudy, t: &str) -> String {
    let Ok(p) = Big::parse_decimal(t).and_then(|e| evaluate(s.formula, &e)) else {
        return "not proved".into();
    };
    let e = p.error.to_interval();
    let d = |x: f64, dir| {
        decimal::directed(x, 3, dir)
            .map(|d| d.scientific(3))
            .unwrap()
    };
    format!(
        "[{}, {}]",
        d(e.inf(), Rounding::Down),
        d(e.sup(), Rounding::Up)
    )
}

/// The REPORT section (between its markers).
pub fn render(r: &mut String, laws: &Laws) {
    writeln!(r, "{BEGIN}").unwrap();
    writeln!(r, "## Classical damping formulas, proved (issue #33)\n").unwrap();
    writeln!(
        r,
        "The Simon–Hunt–Crossley law F = k|δ|^(n−1)δ + χ|δ|^n δ̇ is the NDBWSHCCM without its \
         Bouc–Wen branch, with σ = χv0/k. A published formula χ(e*) tunes it for a target \
         CoR e*; each is a function σ(e*). The CoR the law really produces solves \
         G(σe) = G(−σ) with G(u) = −u − ln(1 − u), whatever n (src/models/hunt_crossley.rs; \
         Carvalho & Martins' exact relation). `bwcl laws` proves e(σ(e*)) and the error \
         e − e* in 128-bit interval arithmetic: at {} targets in [{LO}, {HI}], and over \
         the whole range the runs where |e − e*| ≤ {TOL} holds (every e* of the run, by \
         paving the range with pieces down to {:e} wide; ends printed inward). The rigorous \
         ODE engine agrees with the closed form at n = 1.5 (tests/laws.rs).\n",
        laws.points, laws.min_width
    )
    .unwrap();
    writeln!(
        r,
        "| formula | σ(e*) | e − e* at e* = 0.3 | at 0.5 | at 0.9 | max \\|e − e*\\| on the grid | \
         \\|e − e*\\| ≤ {TOL} proved for e* in |\n|---|---|---|---|---|---|---|"
    )
    .unwrap();
    for s in &laws.studies {
        let max = s
            .points
            .iter()
            .map(|(_, p)| p.error.to_interval().mag())
            .fold(0.0, f64::max);
        writeln!(
            r,
            "| {} | {} | {} | {} | {} | {} | {} |",
            s.formula.source(),
            s.formula.formula(),
            error_at(s, "0.3"),
            error_at(s, "0.5"),
            error_at(s, "0.9"),
            decimal::sci_up(max, 3),
            runs(s, Verdict::Within)
        )
        .unwrap();
    }
    let undecided: Vec<String> = laws
        .studies
        .iter()
        .filter(|s| s.segments.iter().any(|g| g.verdict == Verdict::Undecided))
        .map(|s| s.formula.key().to_string())
        .collect();
    writeln!(
        r,
        "\nErrors are 128-bit enclosures (narrower than 1e-30), rounded outward to 3 digits. \
         Undecided pieces at the {:e} floor: {}. \
         {} formulas × {} targets and the pavings in {:.1} s (2 cores). Data \
         `laws_formula_errors.csv`, plot `laws_formula_errors.svg/.png`; redo with \
         `cargo run --release --bin paper-repro -- laws`.",
        laws.min_width,
        if undecided.is_empty() {
            "none".to_string()
        } else {
            undecided.join(", ")
        },
        laws.studies.len(),
        laws.points,
        laws.seconds
    )
    .unwrap();
    writeln!(r, "{END}").unwrap();
}

/// Replaces the section between the markers of `report` (which must have them).
pub fn replace_section(report: &Path, laws: &Laws) -> Result<(), String> {
    let text = std::fs::read_to_string(report)
        .map_err(|e| format!("reading '{}': {e}", report.display()))?;
    let (Some(i), Some(j)) = (text.find(BEGIN), text.find(END)) else {
        return Err(format!(
            "'{}' has no {BEGIN} … {END} section: run paper-repro in full once",
            report.display()
        ));
    };
    let mut section = String::new();
    render(&mut section, laws);
    let section = section.trim_end_matches('\n');
    let new = format!("{}{}{}", &text[..i], section, &text[j + END.len()..]);
    std::fs::write(report, new).map_err(|e| format!("writing '{}': {e}", report.display()))
}
