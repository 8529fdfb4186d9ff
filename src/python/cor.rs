//! `bwcl.cor`: T_s and e on the f64 DOP853 engine at the paper's settings (eq:main_t_s,
//! eq:main_cor), one case per impact speed, the cases in parallel.

use super::arrays::{put_bool, put_f64, put_f64_2d, put_i64, speed_lists};
use super::cli::CliError;
use super::cli::args::{Command, CorArgs, ParamArgs};
use super::cli::commands::float_row;
use super::cli::input;
use super::cli::law_runs;
use super::cli::output::{FloatRow, RowParams, derived_columns};
use super::run::{compute, compute_rows_progress, parse, py_error, stopped};
use numpy::PyReadonlyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The `cor` arguments of `argv` (plus the first --v0 list).
pub fn cor_args(argv: Vec<String>, lists: &Option<Vec<String>>) -> PyResult<CorArgs> {
    let mut argv = argv;
    if let Some(first) = lists.as_ref().and_then(|l| l.first()) {
        argv.push(format!("--v0={first}"));
    }
    match parse(&argv)?.command {
        Command::Cor(a) => Ok(a),
        _ => Err(PyValueError::new_err("not a cor command")),
    }
}

/// The validated cases of every parameter set (`sets`: the texts of a vectorised call, each in
/// place of the one source given, --base, --nd or --physical) and every --v0 list, set-major
/// (`make`: the cases of one set and list), built with the GIL released and Ctrl-C heard
/// ([`compute`]: a million speeds take a second). A bad set is named by its index.
pub fn per_list<C: Send>(
    py: Python<'_>,
    a: &CorArgs,
    lists: &Option<Vec<String>>,
    sets: &Option<Vec<String>>,
    make: impl Fn(&ParamArgs) -> Result<Vec<C>, CliError> + Send + Sync,
) -> PyResult<Vec<C>> {
    let one_set = |p: &ParamArgs, cases: &mut Vec<C>| -> Result<bool, CliError> {
        match lists {
            None => cases.extend(make(p)?),
            Some(lists) => {
                for text in lists {
                    if bwcl::engines::cancel::requested() {
                        return Ok(false);
                    }
                    let mut p = p.clone();
                    p.v0 = Some(text.clone());
                    cases.extend(make(&p)?);
                }
            }
        }
        Ok(true)
    };
    let built = compute(py, None, || {
        let mut cases = Vec::new();
        match sets {
            None => {
                if !one_set(&a.params, &mut cases)? {
                    return Ok(None);
                }
            }
            Some(sets) => {
                for (i, set) in sets.iter().enumerate() {
                    if bwcl::engines::cancel::requested() {
                        return Ok(None);
                    }
                    let p = with_set(&a.params, set);
                    // a bad set is named by its index (a bad speed is the speed's fault)
                    let done = one_set(&p, &mut cases).map_err(|e| match e {
                        CliError::Input(m) if !m.starts_with("--v0") => {
                            CliError::Input(format!("parameter set {i}: {m}"))
                        }
                        other => other,
                    })?;
                    if !done {
                        return Ok(None);
                    }
                }
            }
        }
        Ok(Some(cases))
    })?;
    built.map_err(py_error)?.ok_or_else(stopped)
}

/// `p` with `set` in place of its one parameter source (--base, --nd or --physical).
fn with_set(p: &ParamArgs, set: &str) -> ParamArgs {
    let mut p = p.clone();
    for source in [&mut p.base, &mut p.nd, &mut p.physical] {
        if source.is_some() {
            *source = Some(set.to_string());
        }
    }
    p
}

/// The parameters of the rows: an (n, 6) array for a Bouc–Wen model (an (n, 12) one of
/// bounds for enclosures), a dict of arrays by name for a classical law.
pub fn put_params<T: Copy, const W: usize>(
    d: &Bound<'_, PyDict>,
    params: Vec<&RowParams<T>>,
    flat: impl Fn(T) -> [f64; W],
) -> PyResult<()> {
    let mut six = Vec::new();
    let mut named: std::collections::BTreeMap<&str, Vec<f64>> = Default::default();
    // a law's rows give a dict, empty for Hooke's law (no nondimensional parameter)
    let law = params.iter().any(|p| matches!(p, RowParams::Law(_)));
    for p in params {
        match p {
            RowParams::BoucWen(p) => six.extend(
                [p.b, p.gamma, p.kappa, p.sigma, p.n, p.p]
                    .into_iter()
                    .flat_map(&flat),
            ),
            RowParams::Law(m) => {
                for (k, v) in m {
                    named.entry(k).or_default().extend(flat(*v));
                }
            }
        }
    }
    if !law {
        return put_f64_2d(d, "params", six, 6 * W);
    }
    let out = PyDict::new(d.py());
    for (k, v) in named {
        if W == 1 {
            put_f64(&out, k, v)?;
        } else {
            put_f64_2d(&out, k, v, W)?;
        }
    }
    d.set_item("params", out)
}

/// T_s and e of every case (see `bwcl.cor`): a dict of NumPy arrays.
#[pyfunction]
#[pyo3(signature = (argv, v0_array=None, v0_tokens=None, sets=None, threads=None, progress=None))]
pub fn cor<'py>(
    py: Python<'py>,
    argv: Vec<String>,
    v0_array: Option<PyReadonlyArray1<'py, f64>>,
    v0_tokens: Option<Vec<String>>,
    sets: Option<Vec<String>>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let lists = speed_lists(v0_array, v0_tokens);
    let a = cor_args(argv, &lists)?;
    if a.engine.rigorous {
        return Err(PyValueError::new_err("--rigorous: use bwcl.cor_rigorous"));
    }
    let opts = input::float_options(&a.engine).map_err(py_error)?;
    let (rows, seconds, used) = match a.params.model.law() {
        Some(law) => {
            let cases = per_list(py, &a, &lists, &sets, |p| input::law_cases::<f64>(p, law))?;
            compute_rows_progress(py, threads, &cases, progress, |c| {
                law_runs::float_row(law, c, &opts, a.derived)
            })?
        }
        None => {
            let kind = input::bouc_wen_only(a.params.model, "cor").map_err(py_error)?;
            let cases = per_list(py, &a, &lists, &sets, input::cases::<f64>)?;
            compute_rows_progress(py, threads, &cases, progress, |c| {
                float_row(kind, c, &opts, a.derived)
            })?
        }
    };
    let d = PyDict::new(py);
    d.set_item("model", a.params.model.key())?;
    put_f64(
        &d,
        "v0",
        rows.iter().map(|r| r.v0.unwrap_or(f64::NAN)).collect(),
    )?;
    put_f64(
        &d,
        "ts",
        rows.iter().map(|r| r.ts.unwrap_or(f64::NAN)).collect(),
    )?;
    put_f64(
        &d,
        "e",
        rows.iter().map(|r| r.e.unwrap_or(f64::NAN)).collect(),
    )?;
    put_bool(&d, "separated", rows.iter().map(|r| r.separated).collect())?;
    put_i64(&d, "nfev", rows.iter().map(|r| r.nfev as i64).collect())?;
    put_i64(&d, "steps", rows.iter().map(|r| r.steps as i64).collect())?;
    put_params(&d, rows.iter().map(|r| &r.params).collect(), |x| [x])?;
    if a.params.physical.is_some() {
        put_f64(
            &d,
            "ts_seconds",
            rows.iter()
                .map(|r| r.ts_seconds.flatten().unwrap_or(f64::NAN))
                .collect(),
        )?;
        put_f64(
            &d,
            "t_c",
            rows.iter().map(|r| r.t_c.unwrap_or(f64::NAN)).collect(),
        )?;
    }
    if a.derived {
        // F_max, δ_max, ΔE (and in SI with --physical): NaN where not computed, with the reason
        let cols = derived_columns(a.params.physical.is_some());
        for (j, name) in cols.iter().enumerate() {
            let v = rows.iter().map(|r| {
                r.derived
                    .as_ref()
                    .and_then(|d| d.values()[j])
                    .unwrap_or(f64::NAN)
            });
            put_f64(&d, name, v.collect())?;
        }
        let why = |r: &FloatRow| r.derived.as_ref().and_then(|d| d.reason.clone());
        d.set_item("derived_reason", rows.iter().map(why).collect::<Vec<_>>())?;
    }
    let errors: Vec<Option<String>> = rows.into_iter().map(|r| r.error).collect();
    d.set_item("error", errors)?;
    d.set_item("horizon", opts.horizon)?;
    d.set_item("seconds", seconds)?;
    d.set_item("threads", used)?;
    Ok(d)
}
