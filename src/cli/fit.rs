//! The `fit` and `cost` subcommands: parameter identification from measured CoR data (eq:J).

use super::args::{CostArgs, FitArgs, JacobianArg, ReportFormat, SearchArgs};
use super::input::nd_error;
use super::output::{self, ParamsOut, json, num};
use super::{CliError, EXIT_FAILED, EXIT_OK, note};
use bwcl::fit::cost::weighted_cost;
use bwcl::fit::minima::Minimum;
use bwcl::fit::nelder_mead::{FitResult, ProgressFn};
use bwcl::fit::space::{NAMES, Slot, Space, parse_bounds, parse_fix};
use bwcl::fit::uncertainty::{JacobianMethod, Uncertainty, uncertainty};
use bwcl::fit::{CorData, FitCurve, FitOptions, Progress, Weights, fit as run_fit, model_curve};
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

/// One distinct minimum of `fit`, as written to JSON.
#[derive(Serialize)]
struct MinimumOut {
    #[serde(rename = "J")]
    j: f64,
    #[serde(rename = "P_star")]
    p_star: ParamsOut<f64>,
    base: String,
    /// The number of starts that ended in this basin, and which (1-based).
    basin_size: usize,
    starts: Vec<usize>,
    /// (J² − J_best²)/s².
    delta_chi2: f64,
    /// Δχ² ≤ χ²_0.95(k): statistically indistinguishable from the best.
    indistinguishable: bool,
    converged: bool,
    at_bound: Vec<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    uncertainty: Option<Uncertainty>,
}

#[derive(Serialize)]
pub struct FitOut {
    model: &'static str,
    /// The best base set, named B, Gamma, kappa, sigma (σ_b), n, p.
    #[serde(rename = "P_star")]
    p_star: ParamsOut<f64>,
    /// The same, as the --base argument B,Γ,κ,σ_b,n,p.
    base: String,
    /// J = sqrt(Σ r²) of the weighted residuals (the paper's J with unit errors).
    #[serde(rename = "J")]
    j: f64,
    chi2: f64,
    /// J²/(M_res − k).
    reduced_chi2: f64,
    /// The number of residuals (M, or 2M with contact durations) and of free parameters.
    m_res: usize,
    k: usize,
    /// The scale of Δχ² and of the covariance: J_best²/(M_res − k), or 1 with given errors.
    s2: f64,
    errors_given: bool,
    uses_tc: bool,
    free: Vec<&'static str>,
    fixed: std::collections::BTreeMap<&'static str, f64>,
    bounds: std::collections::BTreeMap<&'static str, [f64; 2]>,
    converged: bool,
    at_bound: Vec<&'static str>,
    /// The distinct minima, best first.
    minima: Vec<MinimumOut>,
    /// How many minima are statistically indistinguishable from the best (itself included).
    indistinguishable: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    uncertainty: Option<Uncertainty>,
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
pub fn base_text(p: &NdParams<f64>) -> String {
    p.as_array().map(num).join(",")
}

pub fn read_data(path: &std::path::Path) -> Result<CorData, CliError> {
    CorData::read(path).map_err(|e| CliError::Input(format!("--data {e}")))
}

/// The Bouc–Wen model of `--model` (a classical law refused where only they apply).
pub fn bouc_wen(m: super::args::FamilyArg) -> Result<ModelKind, CliError> {
    m.kind().ok_or_else(|| {
        CliError::Input(format!(
            "--model {}: a classical law is fitted by `bwcl fit --model {0}` or `bwcl compare` \
             (bwcl.compare in Python)",
            m.key()
        ))
    })
}

/// The settings of `fit` from its arguments: --init parsed and checked against --starts and
/// --p1 (the data are read separately).
pub fn fit_options(a: &FitArgs) -> Result<FitOptions, CliError> {
    let kind = bouc_wen(a.model)?;
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
    if a.p1 && kind == ModelKind::Shc {
        return Err(CliError::Input(
            "--p1 searches the maxwell model's isolated p = 1; the shc model's p ≥ 1 is one \
             interval (fix it with --fix p=1)"
                .into(),
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
        space: search_space(kind, &a.search)?,
        cluster: !a.no_cluster,
        ..FitOptions::default()
    };
    opts.float.ode.max_steps = opts.float.ode.max_steps.min(FIT_MAX_STEPS);
    // --p1 against --fix/--bounds p, or nothing left free: bad input
    opts.space_map(kind).map_err(CliError::Input)?;
    if let (Some(p), Ok(map)) = (opts.initial.first(), opts.space_map(kind)) {
        map.from_params(p)
            .map_err(|e| CliError::Input(format!("--init: {e}")))?;
    }
    Ok(opts)
}

/// A fit needs at least as many data rows as free parameters: fewer leave P* undetermined
/// (a family of exact fits), refused as bad input.
pub fn check_determined(
    kind: ModelKind,
    opts: &FitOptions,
    data: &CorData,
) -> Result<(), CliError> {
    let free = opts
        .space_map(kind)
        .map_err(CliError::Input)?
        .space
        .free()
        .len();
    if data.len() < free {
        return Err(CliError::Input(format!(
            "underdetermined: {} data row(s) for {free} free parameters (fix some with --fix, or \
             give more rows)",
            data.len()
        )));
    }
    Ok(())
}

/// The space of --fix and --bounds (`None` without either).
pub fn search_space(kind: ModelKind, a: &SearchArgs) -> Result<Option<Space>, CliError> {
    if a.fix.is_none() && a.bounds.is_none() {
        return Ok(None);
    }
    let fix = match &a.fix {
        Some(t) => parse_fix(t).map_err(|e| CliError::Input(format!("--fix: {e}")))?,
        None => Vec::new(),
    };
    let bounds = match &a.bounds {
        Some(t) => parse_bounds(t).map_err(|e| CliError::Input(format!("--bounds: {e}")))?,
        None => Vec::new(),
    };
    let free = |_| {
        Ok(Slot::Free {
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
        })
    };
    Space::build(kind, &fix, &bounds, free)
        .map(Some)
        .map_err(|e| CliError::Input(format!("--fix/--bounds: {e}")))
}

/// The residuals' errors of --error, --tc-error, --no-tc and the data's columns.
pub fn search_weights(data: &CorData, a: &SearchArgs) -> Result<Weights, CliError> {
    Weights::new(data, a.error, a.tc_error, !a.no_tc).map_err(CliError::Input)
}

fn minimum_out(m: &Minimum, unc: Option<Uncertainty>) -> MinimumOut {
    MinimumOut {
        j: m.j,
        p_star: super::commands::params_f64(&m.base),
        base: base_text(&m.base),
        basin_size: m.starts.len(),
        starts: m.starts.iter().map(|s| s + 1).collect(),
        delta_chi2: m.delta_chi2,
        indistinguishable: m.indistinguishable,
        converged: m.converged,
        at_bound: m.at_bound.clone(),
        uncertainty: unc,
    }
}

/// The uncertainty at a point of a fit (see `bwcl::fit::uncertainty`).
pub fn fit_uncertainty(
    res: &FitResult,
    base: &NdParams<f64>,
    data: &CorData,
    method: JacobianArg,
) -> Result<Uncertainty, CliError> {
    let method = match method {
        JacobianArg::Proved => JacobianMethod::Proved,
        JacobianArg::Central => JacobianMethod::Central,
    };
    uncertainty(
        res.kind,
        base,
        &res.map.space.free(),
        data,
        &res.weights,
        res.stats.s2,
        method,
        &FloatOptions::default(),
    )
    .map_err(CliError::Failed)
}

/// The uncertainty as aligned text.
pub fn uncertainty_table(u: &Uncertainty) -> String {
    let mut s = String::from("\nuncertainty at the best fit");
    s.push_str(&format!(
        " (s² = {}; Jacobian: {}):\n",
        num(u.s2),
        if u.jacobian_source.iter().all(|c| c == "proved") {
            "proved sensitivities".to_string()
        } else if u.jacobian_source.iter().all(|c| *c == u.jacobian_source[0]) {
            u.jacobian_source[0].clone()
        } else {
            u.names
                .iter()
                .zip(&u.jacobian_source)
                .map(|(n, c)| format!("{n} {c}"))
                .collect::<Vec<_>>()
                .join("; ")
        }
    ));
    let rows: Vec<Vec<String>> = u
        .names
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let mut r = vec![
                n.to_string(),
                format!("{:.6e}", u.theta[i]),
                format!("{:.3e}", u.std_errors[i]),
            ];
            r.extend(u.correlation[i].iter().map(|c| format!("{c:+.3}")));
            r
        })
        .collect();
    let mut head = vec!["param", "value", "std error"];
    head.extend(u.names.iter().copied());
    s.push_str(&table(&head, &rows));
    s.push_str("\nsingular values of the Jacobian and their directions:\n");
    let rows: Vec<Vec<String>> = u
        .singular_values
        .iter()
        .zip(&u.directions)
        .map(|(sv, d)| {
            let mut r = vec![format!("{sv:.3e}")];
            r.extend(d.iter().map(|x| format!("{x:+.3}")));
            r
        })
        .collect();
    let mut head = vec!["σ"];
    head.extend(u.names.iter().copied());
    s.push_str(&table(&head, &rows));
    s.push_str(&format!("condition number {:.3e}\n", u.condition_number));
    if u.poorly_determined.is_empty() {
        s.push_str("every direction is determined (σ/σ_max ≥ 1e-3)\n");
    } else {
        s.push_str("poorly determined combinations (σ/σ_max < 1e-3):\n");
        for p in &u.poorly_determined {
            s.push_str(&format!("  {p}\n"));
        }
    }
    s
}

/// Most DOP853 steps of one CoR inside `fit`: a well-posed case takes a few hundred to a few
/// thousand; a stiff trial set (B or σ_b in the millions) is then counted as a failure
/// (residual 1) instead of taking 10⁶ steps, which bounds the time of a fit.
pub const FIT_MAX_STEPS: usize = 50_000;

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
pub fn table(head: &[&str], rows: &[Vec<String>]) -> String {
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
    let mut out = table(&["v0", "e_data", "e_model", "residual"], &rows);
    // why a speed failed: the note on stderr points here
    if !c.errors.is_empty() {
        out.push_str("\nfailed (each counts with residual 1 in J):\n");
        for line in errors_text(c) {
            out.push_str(&format!("  {line}\n"));
        }
    }
    out
}

/// A progress bar on stderr, hidden when stderr is not a terminal.
pub fn progress_bar(len: u64) -> ProgressBar {
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
    super::input::out_path(a.out.as_deref())?;
    let kind = match (a.model.kind(), a.model.law()) {
        (Some(kind), _) => kind,
        (_, Some(law)) => return super::compare::fit(a, law),
        _ => unreachable!("a model or a law"),
    };
    let data = read_data(&a.data)?;
    let mut opts = fit_options(a)?;
    opts.weights = Some(search_weights(&data, &a.search)?);
    check_determined(kind, &opts, &data)?;
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
    let j = weighted_cost(
        kind,
        &best.base,
        &data,
        &res.weights,
        &FloatOptions::default(),
    );
    let m = data.len();
    let unc = if a.uncertainty {
        Some(fit_uncertainty(&res, &best.base, &data, a.jacobian)?)
    } else {
        None
    };
    let n_indist = res.minima.iter().filter(|m| m.indistinguishable).count();
    let best_min = res.minima.first();
    let converged = best_min.is_none_or(|m| m.converged);
    let at_bound = best_min.map(|m| m.at_bound.clone()).unwrap_or_default();
    let bytes = match a.format {
        ReportFormat::Json => json(&fit_out(a, &res, &data, unc.clone())?)?,
        ReportFormat::Table => {
            let mut s = format!(
                "model {}: P* (B,Γ,κ,σ_b,n,p) = {}\nJ = {}  (M = {m}, J/√M = {}; χ² = {}, \
                 reduced χ² = {} with M_res = {}, k = {}{})\n\
                 {} cost evaluations ({} CoRs) in {:.2} s, {} start(s), seed {}\n",
                kind.name(),
                base_text(&best.base),
                num(j),
                num(curve.j / (m as f64).sqrt()),
                num(j * j),
                num(res.stats.reduced_chi2(j)),
                res.stats.m_res,
                res.stats.k,
                if res.weights.errors_given {
                    ", errors given"
                } else {
                    ""
                },
                res.evaluations,
                res.evaluations * m,
                res.elapsed.as_secs_f64(),
                n_starts,
                a.seed
            );
            if !converged {
                s.push_str("the best fit did not converge (its last run used the whole iteration budget)\n");
            }
            if !at_bound.is_empty() {
                s.push_str(&format!(
                    "the best fit is at bound: {}\n",
                    at_bound.join(", ")
                ));
            }
            s.push_str(&format!(
                "\nminima ({} distinct, {} within the noise: Δχ² ≤ χ²_0.95({}) = {:.3}; s² = {}):\n",
                res.minima.len(),
                n_indist,
                res.stats.k,
                res.stats.crit,
                num(res.stats.s2)
            ));
            s.push_str(&minima_table(&res.minima));
            if let Some(u) = &unc {
                s.push_str(&uncertainty_table(u));
            }
            s.push_str("\nstarts:\n");
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
    output::emit(a.out.as_deref(), &bytes)?;
    if n_indist > 1 {
        note(&format!(
            "bwcl: warning: the data do not determine P*: {n_indist} minima within the noise \
             (Δχ² ≤ {:.3}; see the minima table)",
            res.stats.crit
        ));
    }
    failures(&curve)
}

/// The JSON report of `fit`: with the uncertainty at the best point given, the uncertainty at
/// every other minimum too (by central differences: see `bwcl::fit::uncertainty`).
pub fn fit_out(
    a: &FitArgs,
    res: &FitResult,
    data: &CorData,
    unc: Option<Uncertainty>,
) -> Result<FitOut, CliError> {
    let kind = res.kind;
    let best = &res.best;
    let curve = model_curve(kind, &best.base, data, &FloatOptions::default());
    let j = weighted_cost(
        kind,
        &best.base,
        data,
        &res.weights,
        &FloatOptions::default(),
    );
    let m = data.len();
    let n_indist = res.minima.iter().filter(|m| m.indistinguishable).count();
    let best_min = res.minima.first();
    let converged = best_min.is_none_or(|m| m.converged);
    let at_bound = best_min.map(|m| m.at_bound.clone()).unwrap_or_default();
    let space = &res.map.space;
    let mut minima = Vec::new();
    for (i, mi) in res.minima.iter().enumerate() {
        let u = match (&unc, i) {
            (Some(u), 0) => Some(u.clone()),
            // the other minima by central differences: the proved Jacobian costs M·k runs of
            // the variational system per point, which would multiply the fit's time
            (Some(_), _) => Some(fit_uncertainty(res, &mi.base, data, JacobianArg::Central)?),
            (None, _) => None,
        };
        minima.push(minimum_out(mi, u));
    }
    Ok(FitOut {
        model: kind.name(),
        p_star: super::commands::params_f64(&best.base),
        base: base_text(&best.base),
        j,
        chi2: j * j,
        reduced_chi2: res.stats.reduced_chi2(j),
        m_res: res.stats.m_res,
        k: res.stats.k,
        s2: res.stats.s2,
        errors_given: res.weights.errors_given,
        uses_tc: res.weights.tc.is_some(),
        free: space.free_names(),
        fixed: (0..6)
            .filter_map(|i| match space.slots[i] {
                Slot::Fixed(v) => Some((NAMES[i], v)),
                Slot::Free { .. } => None,
            })
            .collect(),
        bounds: (0..6)
            .filter_map(|i| res.map.bounds(i).map(|(lo, hi)| (NAMES[i], [lo, hi])))
            .collect(),
        converged,
        at_bound: at_bound.clone(),
        minima,
        indistinguishable: n_indist,
        uncertainty: unc,
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
    })
}

/// The minima as aligned text.
fn minima_table(minima: &[Minimum]) -> String {
    let rows: Vec<Vec<String>> = minima
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let mut r = vec![
                (i + 1).to_string(),
                format!("{:.6e}", m.j),
                format!("{:.3}", m.delta_chi2),
                if m.indistinguishable { "yes" } else { "no" }.into(),
                m.starts.len().to_string(),
            ];
            r.extend(m.base.as_array().map(|x| format!("{x:.6}")));
            r.push(if m.converged { "yes" } else { "budget" }.into());
            r.push(if m.at_bound.is_empty() {
                String::new()
            } else {
                format!("at bound: {}", m.at_bound.join(","))
            });
            r
        })
        .collect();
    table(
        &[
            "minimum",
            "J",
            "Δχ²",
            "within noise",
            "starts",
            "B",
            "Γ",
            "κ",
            "σ_b",
            "n",
            "p",
            "converged",
            "",
        ],
        &rows,
    )
}

pub fn cost(a: &CostArgs) -> Result<i32, CliError> {
    super::input::out_path(a.out.as_deref())?;
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
    output::emit(a.out.as_deref(), &bytes)?;
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
