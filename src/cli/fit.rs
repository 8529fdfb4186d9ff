//! The `fit` and `cost` subcommands: parameter identification from measured CoR data (eq:J).

use super::args::{CostArgs, FitArgs, ReportFormat};
use super::input::nd_error;
use super::output::{self, ParamsOut, num};
use super::{CliError, EXIT_FAILED, EXIT_OK, note};
use bwcl::fit::nelder_mead::ProgressFn;
use bwcl::fit::{CorData, FitCurve, FitOptions, Progress, fit as run_fit, model_curve};
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::FloatOptions;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::io::IsTerminal;
use std::sync::Arc;

/// One point of the fitted curve.
#[derive(Serialize)]
struct CurvePoint {
    v0: f64,
    e_data: f64,
    /// null where the model could not be evaluated.
    e_model: Option<f64>,
}

/// One start of `fit`, as written to JSON.
#[derive(Serialize)]
struct StartOut {
    start: usize,
    #[serde(rename = "J")]
    j: f64,
    #[serde(rename = "P_star")]
    p_star: ParamsOut<f64>,
    iterations: u64,
    evaluations: usize,
    converged: bool,
}

#[derive(Serialize)]
struct FitOut {
    model: &'static str,
    /// The best base set, named B, Gamma, kappa, sigma (σ_b), n, p.
    #[serde(rename = "P_star")]
    p_star: ParamsOut<f64>,
    /// The same, as the --base argument B,Γ,κ,σ_b,n,p.
    base: String,
    #[serde(rename = "J")]
    j: f64,
    /// M, the number of data points.
    m: usize,
    /// J/√M: the root-mean-square residual (compare with the noise level of the data).
    rms: f64,
    p1: bool,
    seed: u64,
    evaluations: usize,
    seconds: f64,
    starts: Vec<StartOut>,
    curve: Vec<CurvePoint>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    errors: Vec<String>,
}

#[derive(Serialize)]
struct CostOut {
    model: &'static str,
    #[serde(rename = "P_star")]
    p_star: ParamsOut<f64>,
    #[serde(rename = "J")]
    j: f64,
    m: usize,
    rms: f64,
    curve: Vec<CurvePoint>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    errors: Vec<String>,
}

/// The set as the --base argument.
fn base_text(p: &NdParams<f64>) -> String {
    p.as_array().map(num).join(",")
}

pub(crate) fn read_data(path: &std::path::Path) -> Result<CorData, CliError> {
    CorData::read(path).map_err(|e| CliError::Input(format!("--data {e}")))
}

/// The settings of `fit` from its arguments: --init parsed and checked against --starts and
/// --p1 (the data are read separately).
pub(crate) fn fit_options(a: &FitArgs) -> Result<FitOptions, CliError> {
    let kind = ModelKind::from(a.model);
    let mut initial = Vec::new();
    if let Some(text) = &a.init {
        initial.push(
            NdParams::<f64>::parse(kind, text).map_err(|e| nd_error::<f64>("--init", text, e))?,
        );
    }
    if a.starts == 0 && initial.is_empty() {
        return Err(CliError::Input(
            "--starts 0 needs --init (there would be nothing to start from)".into(),
        ));
    }
    match (a.p1, kind, initial.first()) {
        (true, _, Some(p)) if p.p != 1.0 => {
            return Err(CliError::Input(format!(
                "--init has p = {} but --p1 fixes p = 1",
                num(p.p)
            )));
        }
        (false, ModelKind::Maxwell, Some(p)) if p.p == 1.0 => {
            return Err(CliError::Input(
                "--init has the maxwell p = 1, an isolated point of 𝓟: add --p1".into(),
            ));
        }
        _ => {}
    }
    let mut opts = FitOptions {
        starts: a.starts,
        seed: a.seed,
        max_iter: a.max_iter,
        p1: a.p1,
        initial,
        ..FitOptions::default()
    };
    opts.float.ode.max_steps = opts.float.ode.max_steps.min(FIT_MAX_STEPS);
    Ok(opts)
}

/// Most DOP853 steps of one CoR inside `fit`: a well-posed case takes a few hundred to a few
/// thousand; a stiff trial set (B or σ_b in the millions) is then counted as a failure
/// (residual 1) instead of taking 10⁶ steps, which bounds the time of a fit.
const FIT_MAX_STEPS: usize = 50_000;

fn curve_points(c: &FitCurve) -> Vec<CurvePoint> {
    c.v0.iter()
        .zip(&c.e_data)
        .zip(&c.e_model)
        .map(|((&v0, &e_data), &e_model)| CurvePoint {
            v0,
            e_data,
            e_model,
        })
        .collect()
}

fn errors_text(c: &FitCurve) -> Vec<String> {
    c.errors
        .iter()
        .map(|(v, why)| format!("v0 = {}: {why}", num(*v)))
        .collect()
}

/// Aligned columns with a header.
fn table(head: &[&str], rows: &[Vec<String>]) -> String {
    let len = |s: &str| s.chars().count();
    let mut w: Vec<usize> = head.iter().map(|h| len(h)).collect();
    for r in rows {
        for (i, c) in r.iter().enumerate() {
            w[i] = w[i].max(len(c));
        }
    }
    let mut out = String::new();
    for cells in std::iter::once(head.iter().map(|s| s.to_string()).collect::<Vec<_>>())
        .chain(rows.iter().cloned())
    {
        let mut s = String::new();
        for (i, c) in cells.iter().enumerate() {
            if i > 0 {
                s.push_str("  ");
            }
            s.push_str(c);
            s.extend(std::iter::repeat_n(' ', w[i].saturating_sub(len(c))));
        }
        out.push_str(s.trim_end());
        out.push('\n');
    }
    out
}

fn curve_table(c: &FitCurve) -> String {
    let rows: Vec<Vec<String>> = curve_points(c)
        .iter()
        .map(|p| {
            vec![
                num(p.v0),
                num(p.e_data),
                p.e_model.map(num).unwrap_or_else(|| "failed".into()),
                p.e_model
                    .map(|e| format!("{:+.2e}", p.e_data - e))
                    .unwrap_or_default(),
            ]
        })
        .collect();
    table(&["v0", "e_data", "e_model", "residual"], &rows)
}

fn json<T: Serialize>(v: &T) -> Result<Vec<u8>, CliError> {
    let mut b =
        serde_json::to_vec_pretty(v).map_err(|e| CliError::Failed(format!("writing JSON: {e}")))?;
    b.push(b'\n');
    Ok(b)
}

/// A progress bar on stderr, hidden when stderr is not a terminal.
fn progress_bar(len: u64) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len);
    bar.set_style(
        ProgressStyle::with_template(
            "fit {bar:32} {pos}/{len} iterations, {elapsed} elapsed, ~{eta} left  {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}

pub fn fit(a: &FitArgs) -> Result<i32, CliError> {
    let kind = ModelKind::from(a.model);
    let data = read_data(&a.data)?;
    let opts = fit_options(a)?;
    let n_starts = (opts.starts + opts.initial.len()) as u64;
    let budget = opts.max_iter * (1 + opts.restarts as u64);
    let bar = progress_bar(n_starts * budget);
    let done = Arc::new(std::sync::atomic::AtomicU64::new(0));
    let progress: ProgressFn = {
        let bar = bar.clone();
        Arc::new(move |p| match p {
            Progress::Iteration { .. } => bar.inc(1),
            Progress::StartDone {
                j,
                iterations,
                budget,
                ..
            } => {
                // a start that stopped early leaves its unused budget: count it as done
                bar.inc(budget.saturating_sub(iterations));
                let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                bar.set_message(format!("{k}/{n_starts} starts, last J = {j:.4e}"));
            }
        })
    };
    let res = run_fit(kind, &data, &opts, Some(progress)).map_err(CliError::Failed)?;
    bar.finish_and_clear();
    let best = &res.best;
    let curve = model_curve(kind, &best.base, &data, &FloatOptions::default());
    let m = data.len();
    let bytes = match a.format {
        ReportFormat::Json => json(&FitOut {
            model: kind.name(),
            p_star: super::commands::params_f64(&best.base),
            base: base_text(&best.base),
            j: curve.j,
            m,
            rms: curve.j / (m as f64).sqrt(),
            p1: a.p1,
            seed: a.seed,
            evaluations: res.evaluations,
            seconds: res.elapsed.as_secs_f64(),
            starts: res
                .starts
                .iter()
                .map(|s| StartOut {
                    start: s.start + 1,
                    j: s.j,
                    p_star: super::commands::params_f64(&s.base),
                    iterations: s.iterations,
                    evaluations: s.evaluations,
                    converged: s.converged,
                })
                .collect(),
            curve: curve_points(&curve),
            errors: errors_text(&curve),
        })?,
        ReportFormat::Table => {
            let mut s = format!(
                "model {}: P* (B,Γ,κ,σ_b,n,p) = {}\nJ = {}  (M = {m}, J/√M = {})\n\
                 {} cost evaluations ({} CoRs) in {:.2} s, {} start(s), seed {}\n\nstarts:\n",
                kind.name(),
                base_text(&best.base),
                num(curve.j),
                num(curve.j / (m as f64).sqrt()),
                res.evaluations,
                res.evaluations * m,
                res.elapsed.as_secs_f64(),
                n_starts,
                a.seed
            );
            let mut starts = res.starts.clone();
            starts.sort_by(|x, y| x.j.total_cmp(&y.j));
            let rows: Vec<Vec<String>> = starts
                .iter()
                .map(|st| {
                    let mut r = vec![(st.start + 1).to_string(), format!("{:.6e}", st.j)];
                    r.extend(st.base.as_array().map(|x| format!("{x:.6}")));
                    r.push(st.iterations.to_string());
                    r.push(if st.converged { "yes" } else { "budget" }.into());
                    r
                })
                .collect();
            s.push_str(&table(
                &[
                    "start",
                    "J",
                    "B",
                    "Γ",
                    "κ",
                    "σ_b",
                    "n",
                    "p",
                    "iterations",
                    "converged",
                ],
                &rows,
            ));
            s.push_str("\ncurve:\n");
            s.push_str(&curve_table(&curve));
            s.into_bytes()
        }
    };
    output::emit(None, &bytes)?;
    failures(&curve)
}

pub fn cost(a: &CostArgs) -> Result<i32, CliError> {
    let kind = ModelKind::from(a.model);
    let base =
        NdParams::<f64>::parse(kind, &a.base).map_err(|e| nd_error::<f64>("--base", &a.base, e))?;
    let data = read_data(&a.data)?;
    let curve = model_curve(kind, &base, &data, &FloatOptions::default());
    let m = data.len();
    let bytes = match a.format {
        ReportFormat::Json => json(&CostOut {
            model: kind.name(),
            p_star: super::commands::params_f64(&base),
            j: curve.j,
            m,
            rms: curve.j / (m as f64).sqrt(),
            curve: curve_points(&curve),
            errors: errors_text(&curve),
        })?,
        ReportFormat::Table => format!(
            "model {}: P* (B,Γ,κ,σ_b,n,p) = {}\nJ = {}  (M = {m}, J/√M = {})\n\n{}",
            kind.name(),
            base_text(&base),
            num(curve.j),
            num(curve.j / (m as f64).sqrt()),
            curve_table(&curve)
        )
        .into_bytes(),
    };
    output::emit(None, &bytes)?;
    failures(&curve)
}

/// Exit 1 when the model could not be evaluated at some speed (J is then an upper bound).
fn failures(c: &FitCurve) -> Result<i32, CliError> {
    if c.errors.is_empty() {
        Ok(EXIT_OK)
    } else {
        note(&format!(
            "bwcl: the model could not be evaluated at {} speed(s); each counts with residual 1 \
             in J (the reason is in the output)",
            c.errors.len()
        ));
        Ok(EXIT_FAILED)
    }
}
