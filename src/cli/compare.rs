//! The classical laws on data (issue #33, item 4): `fit --model <law>`, `identify --model <law>`
//! ([`bwcl::fit::laws`], [`bwcl::identify::laws`]) and `compare`, every model fitted to the
//! same CoR data with its information criteria ([`bwcl::fit::criteria`]) and, with `--error`,
//! each classical law's proved feasible set.

use super::args::{CompareArgs, FamilyArg, FitArgs, IdentifyArgs, ReportFormat};
use super::fit::{FIT_MAX_STEPS, read_data, search_weights};
use super::identify::Done;
use super::output::{self, num, outward};
use super::progress::Progress;
use super::{CliError, EXIT_FAILED, EXIT_OK, note};
use bwcl::arith::interval::enclose_decimal;
use bwcl::fit::criteria::Criteria;
use bwcl::fit::data::{CorData, echo};
use bwcl::fit::laws::{Law, LawFit, fit_law};
use bwcl::fit::weights::Weights;
use bwcl::fit::{FitOptions, fit as run_fit};
use bwcl::identify::laws::{LawOptions, LawPaving, LawProblem, Refutation, pave_law};
use bwcl::identify::paving::Status;
use bwcl::models::ModelKind;
use bwcl::observables::FloatOptions;
use bwcl::observables::decimal::{self, Rounding};
use inari::Interval;
use serde::Serialize;

/// The law's parameter names as a user may write them.
fn is_name(law: Law, n: &str) -> bool {
    match law {
        Law::HuntCrossley => matches!(n, "sigma_b" | "σ_b" | "sigma" | "σ"),
        Law::KelvinVoigt => matches!(n, "zeta" | "ζ"),
        Law::LinearMaxwell => matches!(n, "c"),
        _ => false,
    }
}

/// The bounds of `--bounds name=lo..hi` for the law (its defaults without the option), as the
/// doubles just outside the decimals written, clipped at the admissible floor when the decimal
/// is on it.
pub fn law_bounds(law: Law, text: Option<&str>) -> Result<(f64, f64), CliError> {
    let bad = |m: String| CliError::Input(format!("--bounds: {m}"));
    let Some(t) = text else {
        return Ok(law.default_bounds());
    };
    let Some(name) = law.parameter() else {
        return Err(bad(format!(
            "the law {} has no parameter that enters e (e = 1)",
            law.key()
        )));
    };
    let (n, r) = t
        .split_once('=')
        .ok_or_else(|| bad(format!("'{}' is not name=lo..hi", echo(t))))?;
    if !is_name(law, n.trim()) {
        return Err(bad(format!(
            "'{}' is not the parameter of the law {} (its parameter is {name})",
            echo(n.trim()),
            law.key()
        )));
    }
    let (a, b) = r
        .split_once("..")
        .ok_or_else(|| bad(format!("'{}' is not a range lo..hi", echo(r))))?;
    let end = |s: &str| enclose_decimal(s.trim()).map_err(|e| bad(format!("{name}: {e}")));
    let (lo, hi) = (end(a)?, end(b)?);
    let floor = law.floor().0;
    let lo = if lo.inf() < floor && lo.sup() >= floor && !law.floor().1 {
        floor
    } else {
        lo.inf()
    };
    let hi = hi.sup();
    law.check_bounds(lo, hi)
        .map_err(|m| bad(format!("'{}': {m}", echo(r))))?;
    Ok((lo, hi))
}

/// The weights of a law's fit: CoRs only.
fn law_weights(law: Law, data: &CorData, a: &super::args::SearchArgs) -> Result<Weights, CliError> {
    if data.tc.is_some() && !a.no_tc {
        return Err(CliError::Input(format!(
            "the data have a column tc: the law {} is fitted to CoRs alone (--no-tc to ignore \
             the column)",
            law.key()
        )));
    }
    let mut s = a.clone();
    s.no_tc = true;
    search_weights(data, &s)
}

fn float_opts() -> FloatOptions {
    let mut o = FloatOptions::default();
    o.ode.max_steps = o.ode.max_steps.min(FIT_MAX_STEPS);
    o
}

#[derive(Serialize)]
struct End {
    value: f64,
    /// The interval reaches past the search's bound here.
    open: bool,
}

#[derive(Serialize)]
struct LawFitOut {
    model: &'static str,
    /// θ's name (null for a law without parameter).
    parameter: Option<&'static str>,
    theta: Option<f64>,
    #[serde(rename = "J")]
    j: f64,
    bounds: Option<[f64; 2]>,
    se: Option<f64>,
    /// The likelihood-ratio 95 % interval of θ.
    interval: Option<[End; 2]>,
    minima: Vec<bwcl::fit::laws::LawMinimum>,
    s2: f64,
    reduced_chi2: f64,
    errors_given: bool,
    criteria: Criteria,
    v0: Vec<f64>,
    e_data: Vec<f64>,
    e_model: Vec<Option<f64>>,
    evaluations: usize,
    seconds: f64,
}

fn law_fit_out(f: &LawFit, data: &CorData, w: &Weights) -> LawFitOut {
    LawFitOut {
        model: f.law.key(),
        parameter: f.law.parameter(),
        theta: f.theta,
        j: f.j,
        bounds: f.bounds.map(|(a, b)| [a, b]),
        se: f.se,
        interval: f.interval.map(|[a, b]| {
            [
                End {
                    value: a.0,
                    open: a.1,
                },
                End {
                    value: b.0,
                    open: b.1,
                },
            ]
        }),
        minima: f.minima.clone(),
        s2: f.stats.s2,
        reduced_chi2: f.stats.reduced_chi2(f.j),
        errors_given: w.errors_given,
        criteria: Criteria::new(f.j, data.len(), f.stats.k, w.errors_given),
        v0: data.v0.clone(),
        e_data: data.e.clone(),
        e_model: f.e_model.clone(),
        evaluations: f.evaluations,
        seconds: f.elapsed.as_secs_f64(),
    }
}

/// θ with its interval as text: "0.123 (95 %: 0.11..0.13)".
fn theta_text(f: &LawFit) -> String {
    match (f.law.parameter(), f.theta) {
        (Some(n), Some(t)) => {
            let iv = f.interval.map_or(String::new(), |[a, b]| {
                format!(
                    " (95 %: {}{}..{}{})",
                    if a.1 { "≤" } else { "" },
                    num(a.0),
                    num(b.0),
                    if b.1 { "+" } else { "" }
                )
            });
            format!("{n} = {}{iv}", num(t))
        }
        _ => "e = 1".into(),
    }
}

/// `fit --model <law>`.
pub fn fit(a: &FitArgs, law: Law) -> Result<i32, CliError> {
    super::input::out_path(a.out.as_deref())?;
    for (given, opt) in [
        (a.init.is_some(), "--init"),
        (a.p1, "--p1"),
        (a.search.fix.is_some(), "--fix"),
    ] {
        if given {
            return Err(CliError::Input(format!(
                "{opt} is an option of the Bouc–Wen models, not of the law {}",
                law.key()
            )));
        }
    }
    let data = read_data(&a.data)?;
    let w = law_weights(law, &data, &a.search)?;
    let bounds = law_bounds(law, a.search.bounds.as_deref())?;
    let f = fit_law(law, &data, &w, Some(bounds), &float_opts()).map_err(CliError::Failed)?;
    let out = law_fit_out(&f, &data, &w);
    let bytes = match a.format {
        ReportFormat::Json => output::json(&out)?,
        ReportFormat::Table => {
            let m = data.len();
            let mut s = format!(
                "model {}: {}\nJ = {}  (M = {m}, J/√M = {}; reduced χ² = {}{})\n",
                law.key(),
                theta_text(&f),
                num(f.j),
                num(f.j / (m as f64).sqrt()),
                num(out.reduced_chi2),
                if w.errors_given { ", errors given" } else { "" }
            );
            if let Some(se) = f.se {
                s.push_str(&format!("standard error {}\n", num(se)));
            }
            if law == Law::HuntCrossley {
                s.push_str("(e does not depend on the Hertz exponent n: any n fits alike)\n");
            }
            if f.minima.len() > 1 {
                let rows: Vec<Vec<String>> = f
                    .minima
                    .iter()
                    .map(|mi| {
                        vec![
                            num(mi.theta),
                            format!("{:.6e}", mi.j),
                            format!("{:.3}", mi.delta_chi2),
                            if mi.indistinguishable { "yes" } else { "no" }.into(),
                        ]
                    })
                    .collect();
                s.push_str("\nminima:\n");
                s.push_str(&output::table(
                    &[
                        f.law.parameter().unwrap_or("θ"),
                        "J",
                        "Δχ²",
                        "within the noise",
                    ],
                    &rows,
                ));
            }
            if f.minima.first().is_some_and(|m| m.at_bound) {
                s.push_str("the best fit is at a bound of the search\n");
            }
            s.push_str(&format!(
                "{} cost evaluations in {:.2} s\n\ncurve:\n",
                f.evaluations,
                f.elapsed.as_secs_f64()
            ));
            let rows: Vec<Vec<String>> = (0..m)
                .map(|i| {
                    vec![
                        num(data.v0[i]),
                        num(data.e[i]),
                        f.e_model[i].map(num).unwrap_or_else(|| "failed".into()),
                        f.e_model[i]
                            .map(|e| format!("{:+.2e}", data.e[i] - e))
                            .unwrap_or_default(),
                    ]
                })
                .collect();
            s.push_str(&output::table(
                &["v0", "e_data", "e_model", "residual"],
                &rows,
            ));
            s.into_bytes()
        }
    };
    output::emit(a.out.as_deref(), &bytes)?;
    if f.e_model.iter().any(Option::is_none) {
        note("bwcl: the law could not be evaluated at some speeds (residual 1 in J)");
        return Ok(EXIT_FAILED);
    }
    Ok(EXIT_OK)
}

/// `identify --model <law>`: the paving of the law's parameter (no --fix, --base; --free must
/// name the parameter).
pub fn identify(a: &IdentifyArgs, law: Law, bar: bool) -> Result<Done, CliError> {
    for (given, opt) in [
        (a.fix.is_some(), "--fix"),
        (a.base.is_some(), "--base"),
        (a.tc_error.is_some(), "--tc-error"),
    ] {
        if given {
            return Err(CliError::Input(format!(
                "{opt} is an option of the Bouc–Wen models, not of the law {}",
                law.key()
            )));
        }
    }
    let free: Vec<&'static str> = law.parameter().into_iter().collect();
    if let Some(f) = &a.free {
        let names: Vec<&str> = f
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .collect();
        if names.len() != free.len() || !names.iter().all(|n| is_name(law, n)) {
            return Err(CliError::Input(format!(
                "--free '{}': the law {} has {}",
                echo(f),
                law.key(),
                law.parameter()
                    .map_or("no free parameter".into(), |n| format!(
                        "the one parameter {n}"
                    ))
            )));
        }
    }
    let data = read_data(&a.data)?;
    let (lo, hi) = if law.parameter().is_some() {
        law_bounds(law, a.bounds.as_deref())?
    } else {
        if a.bounds.is_some() {
            law_bounds(law, a.bounds.as_deref())?;
        }
        (0.0, 0.0)
    };
    let prob = LawProblem::new(law, &data, a.error, a.no_tc).map_err(CliError::Input)?;
    let mut opts = LawOptions {
        resolution: super::identify::resolution(a) as f64,
        taylor: Default::default(),
        max_boxes: a.max_boxes as usize,
    };
    opts.taylor.deadline = Some(super::input::deadline(a.time_limit));
    let progress = bar.then(|| Progress::range("identify", a.time_limit));
    let cb = |p: bwcl::identify::Progress| {
        if let Some(b) = &progress {
            b.set(
                1.0 - p.undecided,
                format!(
                    "{:.1} % of the range decided, {} intervals done",
                    100.0 * (1.0 - p.undecided),
                    p.processed
                ),
            )
        }
    };
    let lp = pave_law(&prob, lo, hi, &opts, Some(&cb));
    let whole = lp.refutes_all(law);
    let LawPaving { paving, refuted } = lp;
    if let Some(b) = &progress {
        b.finish();
    }
    let start = if free.is_empty() {
        vec![]
    } else {
        vec![Interval::try_from((lo, hi)).expect("checked bounds")]
    };
    Ok(Done {
        model: law.key(),
        rows: prob.rows.len(),
        start,
        free,
        paving,
        refuted: Some((refuted, data, whole)),
        sampled: None,
    })
}

/// `identify --resolution` of a classical law when not given: 2^20 (a one-dimensional paving
/// is cheap; the hull is then within 1e−6 relative).
pub const LAW_RESOLUTION: f64 = (1u64 << 20) as f64;

/// The certificate of an empty F in words: which row refutes which range of θ.
pub fn certificate(law: Law, refuted: &[Refutation], data: &CorData) -> Vec<String> {
    refuted
        .iter()
        .map(|r| {
            let row = format!(
                "row {} (v0 = {}, e = {})",
                r.row + 1,
                num(data.v0[r.row]),
                num(data.e[r.row])
            );
            match law.parameter() {
                Some(n) => {
                    let (f, open) = law.floor();
                    // the ends exactly: a refuted range is a claim over its points, so a
                    // shortest decimal outward would claim points never examined (and inward
                    // would open a gap where the next row's range begins at the same double)
                    let lo = if r.lo == f && open {
                        format!("({}", decimal::exact(f))
                    } else {
                        format!("[{}", decimal::exact(r.lo))
                    };
                    let hi = if r.hi == f64::INFINITY {
                        "∞)".into()
                    } else {
                        format!("{}]", decimal::exact(r.hi))
                    };
                    format!("{row} refutes {n} ∈ {lo}, {hi}")
                }
                None => format!("{row} refutes e = 1"),
            }
        })
        .collect()
}

/// One model's line of the comparison.
#[derive(Serialize)]
struct CompareRow {
    model: &'static str,
    /// The fitted parameters, as text.
    parameters: String,
    #[serde(flatten)]
    criteria: Criteria,
    delta_aic: f64,
    delta_bic: f64,
    /// With --error: the proved feasible set of a classical law ("empty", the hull, or
    /// undecided); null for the Bouc–Wen models (see `bwcl identify`) and without --error.
    feasible: Option<String>,
    /// The refutations of an empty feasible set.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    certificate: Vec<String>,
    /// The certificate covers every admissible value of the parameter (not only the box).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    refuted_everywhere: bool,
    seconds: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    failed: Option<String>,
}

#[derive(Serialize)]
struct CompareOut {
    data: String,
    m: usize,
    errors_given: bool,
    /// The bound of --error used by the feasible sets.
    error: Option<f64>,
    rows: Vec<CompareRow>,
}

/// The feasible set of a law at ±E for every row (a `sigma` column, which weights the fits, is
/// not used here: the text says ±E), in words, with its certificate and whether it covers the
/// whole admissible set.
fn feasible(
    law: Law,
    data: &CorData,
    e: f64,
    time_limit: Option<f64>,
) -> (String, Vec<String>, bool) {
    let mut at_e = data.clone();
    at_e.sigma = None;
    let prob = match LawProblem::new(law, &at_e, Some(e), true) {
        Ok(p) => p,
        Err(m) => return (format!("not run: {m}"), vec![], false),
    };
    let (lo, hi) = if law.parameter().is_some() {
        law.default_bounds()
    } else {
        (0.0, 0.0)
    };
    let mut opts = LawOptions {
        resolution: LAW_RESOLUTION,
        taylor: Default::default(),
        max_boxes: 1_000_000,
    };
    opts.taylor.deadline = Some(super::input::deadline(time_limit));
    let lp = pave_law(&prob, lo, hi, &opts, None);
    let whole = lp.refutes_all(law);
    let LawPaving { paving, refuted } = lp;
    let open = if paving.stopped.is_some() {
        " (stopped: the rest undecided)"
    } else {
        ""
    };
    match (paving.hull(), law.parameter()) {
        (None, _) => (
            format!(
                "empty (proved{}){open}",
                if whole { "" } else { " in the default box" }
            ),
            certificate(law, &refuted, data),
            whole,
        ),
        (Some(_), None) => match paving.boxes[0].status {
            Status::Feasible => ("e = 1 fits (proved)".into(), vec![], false),
            _ => ("undecided".into(), vec![], false),
        },
        (Some(h), Some(n)) => {
            let fh = if paving.counts()[0] > 0 {
                "some proved feasible"
            } else {
                "none proved feasible"
            };
            // an end of F at the box's end may continue past it (unless it is the floor)
            let (f, open_floor) = law.floor();
            let past_lo = h[0].0 <= lo && (lo > f || open_floor);
            let past_hi = h[0].1 >= hi;
            let beyond = if past_lo || past_hi {
                format!("; F may reach past the searched {}..{}", num(lo), num(hi))
            } else {
                String::new()
            };
            (
                format!(
                    "{n} ∈ [{}, {}] ({fh}{beyond}){open}",
                    outward(h[0].0, Rounding::Down),
                    outward(h[0].1, Rounding::Up)
                ),
                vec![],
                false,
            )
        }
    }
}

/// `bwcl compare`.
pub fn compare(a: &CompareArgs) -> Result<i32, CliError> {
    super::input::out_path(a.out.as_deref())?;
    let (bytes, failures) = report(a, true)?;
    output::emit(a.out.as_deref(), &bytes)?;
    if failures > 0 {
        note(&format!(
            "bwcl: compare: {failures} model(s) could not be fitted (the reason is in the output)"
        ));
        return Ok(EXIT_FAILED);
    }
    Ok(EXIT_OK)
}

/// The comparison's output (table or JSON) and the number of models that could not be
/// fitted; a progress bar on a terminal when `bar` is set.
pub fn report(a: &CompareArgs, bar: bool) -> Result<(Vec<u8>, usize), CliError> {
    let data = read_data(&a.data)?;
    if let Some(e) = a.error
        && !(e.is_finite() && e > 0.0)
    {
        return Err(CliError::Input(format!(
            "--error {e} must be a finite number > 0"
        )));
    }
    let models: Vec<FamilyArg> = match &a.models {
        None => FamilyArg::ALL.to_vec(),
        Some(t) => t
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .map(|s| {
                FamilyArg::from_key(s).ok_or_else(|| {
                    CliError::Input(format!(
                        "--models: '{}' is not a model (one of {})",
                        echo(s),
                        FamilyArg::ALL.map(FamilyArg::key).join(", ")
                    ))
                })
            })
            .collect::<Result<_, _>>()?,
    };
    if models.is_empty() {
        return Err(CliError::Input("--models names no model".into()));
    }
    let search = super::args::SearchArgs {
        fix: None,
        bounds: None,
        error: None,
        tc_error: None,
        no_tc: true,
    };
    let w = search_weights(&data, &search)?;
    let m = data.len();
    let bar = bar.then(|| Progress::range("compare", None));
    let mut rows = Vec::new();
    let mut failures = 0;
    for (i, fam) in models.iter().enumerate() {
        if let Some(b) = &bar {
            b.set(
                i as f64 / models.len() as f64,
                format!("fitting {} ({}/{})", fam.key(), i + 1, models.len()),
            );
        }
        let t0 = std::time::Instant::now();
        let (fit, k): (Result<(String, f64), String>, usize) = match fam.law() {
            Some(law) => (
                fit_law(law, &data, &w, None, &float_opts()).map(|f| (theta_text(&f), f.j)),
                usize::from(law.parameter().is_some()),
            ),
            None => {
                let kind = fam.kind().expect("a Bouc–Wen model");
                let mut o = FitOptions {
                    starts: a.starts,
                    seed: a.seed,
                    weights: Some(w.clone()),
                    ..FitOptions::default()
                };
                o.float.ode.max_steps = o.float.ode.max_steps.min(FIT_MAX_STEPS);
                (
                    run_fit(kind, &data, &o, None).map(|r| {
                        (
                            format!("P* = {}", super::fit::base_text(&r.best.base)),
                            r.best.j,
                        )
                    }),
                    6,
                )
            }
        };
        let (feasible, certificate, refuted_everywhere) = match (fam.law(), a.error) {
            (Some(law), Some(e)) => {
                let (f, c, w) = feasible(law, &data, e, a.time_limit);
                (Some(f), c, w)
            }
            _ => (None, vec![], false),
        };
        let (parameters, j, failed) = match fit {
            Ok((p, j)) => (p, j, None),
            Err(why) => {
                failures += 1;
                ("-".into(), f64::NAN, Some(why))
            }
        };
        rows.push(CompareRow {
            model: fam.key(),
            parameters,
            criteria: Criteria::new(j, m, k, w.errors_given),
            delta_aic: f64::NAN,
            delta_bic: f64::NAN,
            feasible,
            certificate,
            refuted_everywhere,
            seconds: t0.elapsed().as_secs_f64(),
            failed,
        });
    }
    if let Some(b) = &bar {
        b.finish();
    }
    let best = |f: fn(&Criteria) -> f64| {
        rows.iter()
            .map(|r| f(&r.criteria))
            .filter(|x| !x.is_nan())
            .fold(f64::INFINITY, f64::min)
    };
    let (ba, bb) = (best(|c| c.aic), best(|c| c.bic));
    for r in &mut rows {
        r.delta_aic = r.criteria.aic - ba;
        r.delta_bic = r.criteria.bic - bb;
    }
    rows.sort_by(|x, y| x.criteria.aic.total_cmp(&y.criteria.aic));
    let out = CompareOut {
        data: a.data.display().to_string(),
        m,
        errors_given: w.errors_given,
        error: a.error,
        rows,
    };
    let bytes = match a.format {
        ReportFormat::Json => output::json(&out)?,
        ReportFormat::Table => compare_table(&out).into_bytes(),
    };
    Ok((bytes, failures))
}

fn compare_table(o: &CompareOut) -> String {
    let mut s = format!(
        "{} rows of {}; criteria {} (only differences between models mean anything)\n\n",
        o.m,
        o.data,
        if o.errors_given {
            "with the data's errors (χ² absolute)"
        } else {
            "with one unknown error for all rows (σ² fitted: K = k + 1)"
        }
    );
    let head: Vec<&str> = {
        let mut h = vec!["model", "k", "J", "AIC", "AICc", "BIC", "ΔAIC", "ΔBIC"];
        if o.error.is_some() {
            h.push("feasible set at ±E (proved)");
        }
        h.push("parameters");
        h
    };
    let f = |x: f64| {
        if x.is_finite() {
            format!("{x:.2}")
        } else {
            x.to_string()
        }
    };
    let rows: Vec<Vec<String>> = o
        .rows
        .iter()
        .map(|r| {
            let c = &r.criteria;
            let mut v = vec![
                r.model.to_string(),
                c.k.to_string(),
                if c.j.is_nan() {
                    "failed".into()
                } else {
                    format!("{:.4e}", c.j)
                },
                f(c.aic),
                f(c.aicc),
                f(c.bic),
                f(r.delta_aic),
                f(r.delta_bic),
            ];
            if o.error.is_some() {
                v.push(
                    r.feasible
                        .clone()
                        .unwrap_or_else(|| "- (bwcl identify)".into()),
                );
            }
            v.push(r.failed.clone().unwrap_or_else(|| r.parameters.clone()));
            v
        })
        .collect();
    s.push_str(&output::table(&head, &rows));
    for r in o.rows.iter().filter(|r| !r.certificate.is_empty()) {
        s.push_str(&format!(
            "\n{} {} law fits these data to ±{}: {}\n",
            if r.refuted_everywhere {
                "no"
            } else {
                "in the default box, no"
            },
            r.model,
            o.error.map(num).unwrap_or_default(),
            r.certificate.join("; ")
        ));
    }
    s
}

impl FamilyArg {
    pub const ALL: [FamilyArg; 7] = [
        FamilyArg::Shc,
        FamilyArg::Maxwell,
        FamilyArg::HuntCrossley,
        FamilyArg::KelvinVoigt,
        FamilyArg::LinearMaxwell,
        FamilyArg::Hertz,
        FamilyArg::Hooke,
    ];

    /// The Bouc–Wen model, `None` for a classical law.
    pub fn kind(self) -> Option<ModelKind> {
        match self {
            FamilyArg::Shc => Some(ModelKind::Shc),
            FamilyArg::Maxwell => Some(ModelKind::Maxwell),
            _ => None,
        }
    }

    /// The classical law, `None` for a Bouc–Wen model.
    pub fn law(self) -> Option<Law> {
        match self {
            FamilyArg::Hooke => Some(Law::Hooke),
            FamilyArg::Hertz => Some(Law::Hertz),
            FamilyArg::HuntCrossley => Some(Law::HuntCrossley),
            FamilyArg::KelvinVoigt => Some(Law::KelvinVoigt),
            FamilyArg::LinearMaxwell => Some(Law::LinearMaxwell),
            _ => None,
        }
    }

    pub fn key(self) -> &'static str {
        match (self.kind(), self.law()) {
            (Some(k), _) => k.name(),
            (_, Some(l)) => l.key(),
            _ => unreachable!("a model or a law"),
        }
    }

    pub fn from_key(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.key() == s)
    }
}
