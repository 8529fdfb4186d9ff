//! `bwcl.fit` and `bwcl.cost`: J (eq:J) of a base set on measured CoR data, and the seeded
//! multi-start Nelder–Mead fit of P* inside 𝓟, with a progress callback.

use super::arrays::put_f64;
use super::cli::CliError;
use super::cli::args::{Command, CostArgs, FitArgs, ProfileArgs};
use super::cli::fit::{fit_options, fit_out, fit_uncertainty, read_data, search_weights};
use super::cli::input::nd_error;
use super::run::{compute, parse, py_error};
use bwcl::fit::nelder_mead::ProgressFn;
use bwcl::fit::{CorData, FitCurve, Progress, fit as run_fit, model_curve};
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::FloatOptions;
use numpy::PyReadonlyArray1;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// A CLI error's message.
fn cli_text(e: CliError) -> String {
    match e {
        CliError::Input(m) | CliError::Failed(m) => m,
    }
}

/// The data: the arrays when given (checked pair by pair), else the CSV file of --data.
fn data_of(
    path: &std::path::Path,
    v0: Option<PyReadonlyArray1<'_, f64>>,
    e: Option<PyReadonlyArray1<'_, f64>>,
) -> PyResult<CorData> {
    match (v0, e) {
        (Some(v), Some(e)) => CorData::new(v.as_array().to_vec(), e.as_array().to_vec())
            .map_err(|err| PyValueError::new_err(format!("data: {err}"))),
        (None, None) => read_data(path).map_err(py_error),
        _ => Err(PyValueError::new_err(
            "data: give both v0 and e (or a CSV file)",
        )),
    }
}

/// The curve of J: data, model (NaN where it could not be evaluated) and the failures.
fn put_curve(d: &Bound<'_, PyDict>, c: &FitCurve) -> PyResult<()> {
    let m = c.v0.len();
    d.set_item("J", c.j)?;
    d.set_item("m", m)?;
    d.set_item("rms", c.j / (m as f64).sqrt())?;
    put_f64(d, "v0", c.v0.clone())?;
    put_f64(d, "e_data", c.e_data.clone())?;
    put_f64(
        d,
        "e_model",
        c.e_model.iter().map(|e| e.unwrap_or(f64::NAN)).collect(),
    )?;
    let errors: Vec<(f64, String)> = c.errors.clone();
    d.set_item("errors", errors)
}

fn base_tuple(p: &NdParams<f64>) -> [f64; 6] {
    p.as_array()
}

/// J of a base set on the data (see `bwcl.cost`).
#[pyfunction]
#[pyo3(signature = (argv, v0=None, e=None, threads=None))]
pub fn cost<'py>(
    py: Python<'py>,
    argv: Vec<String>,
    v0: Option<PyReadonlyArray1<'py, f64>>,
    e: Option<PyReadonlyArray1<'py, f64>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let Command::Cost(a): Command = parse(&argv)?.command else {
        return Err(PyValueError::new_err("not a cost command"));
    };
    let a: CostArgs = a;
    let kind = ModelKind::from(a.model);
    let base = NdParams::<f64>::parse(kind, &a.base)
        .map_err(|e| py_error(nd_error::<f64>("--base", &a.base, e)))?;
    let data = data_of(&a.data, v0, e)?;
    let curve = compute(py, threads, || {
        model_curve(kind, &base, &data, &FloatOptions::default())
    })?;
    let d = PyDict::new(py);
    d.set_item("model", kind.name())?;
    d.set_item("base", base_tuple(&base))?;
    put_curve(&d, &curve)?;
    Ok(d)
}

thread_local! {
    /// Whether this thread is inside the fit's progress callback (see `fit`).
    static IN_CALLBACK: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// The fit (see `bwcl.fit`). `progress(done, total, starts_done, starts, last_j)` is called
/// after every Nelder–Mead iteration (with the GIL taken for the call); an exception it raises
/// stops the calls and is raised when the fit returns.
#[pyfunction]
#[pyo3(signature = (argv, v0=None, e=None, progress=None, threads=None))]
pub fn fit<'py>(
    py: Python<'py>,
    argv: Vec<String>,
    v0: Option<PyReadonlyArray1<'py, f64>>,
    e: Option<PyReadonlyArray1<'py, f64>>,
    progress: Option<Py<PyAny>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let Command::Fit(a): Command = parse(&argv)?.command else {
        return Err(PyValueError::new_err("not a fit command"));
    };
    let a: FitArgs = a;
    let Some(kind) = a.model.kind() else {
        // (the CLI's message names its own commands; `pythonic` garbled them)
        return Err(PyValueError::new_err(format!(
            "model {}: bwcl.fit fits the Bouc–Wen models; a classical law is fitted by \
             bwcl.compare(data, models=\"{0}\") (or `bwcl fit --model {0}` on the command line)",
            a.model.key()
        )));
    };
    let data = data_of(&a.data, v0, e)?;
    let mut opts = fit_options(&a).map_err(py_error)?;
    opts.weights = Some(search_weights(&data, &a.search).map_err(py_error)?);
    super::cli::fit::check_determined(kind, &opts, &data).map_err(py_error)?;
    let n_starts = (opts.starts + opts.initial.len()) as u64;
    let total = n_starts * opts.max_iter * (1 + opts.restarts as u64);
    let raised: Arc<Mutex<Option<PyErr>>> = Arc::new(Mutex::new(None));
    let callback: Option<ProgressFn> = progress.map(|cb| {
        let done = AtomicU64::new(0);
        let starts_done = AtomicU64::new(0);
        let last_j = Mutex::new(f64::NAN);
        let raised = raised.clone();
        let f: ProgressFn = Arc::new(move |p| {
            match p {
                Progress::Iteration { .. } => {
                    done.fetch_add(1, Ordering::Relaxed);
                }
                Progress::StartDone {
                    j,
                    iterations,
                    budget,
                    ..
                } => {
                    // a start that stopped early leaves its unused budget: counted as done
                    done.fetch_add(budget.saturating_sub(iterations), Ordering::Relaxed);
                    starts_done.fetch_add(1, Ordering::Relaxed);
                    if let Ok(mut l) = last_j.lock() {
                        *l = j;
                    }
                }
            }
            // no lock is held while Python runs, and a call never nests in one on the same
            // thread: a callback that calls bwcl itself (bwcl.cor on the shared pool) may have
            // its worker run another start's iteration meanwhile, whose report would otherwise
            // wait on the outer call's lock for ever (a hang that Ctrl-C could not stop)
            if IN_CALLBACK.get() || raised.lock().map_or(true, |e| e.is_some()) {
                return;
            }
            let j = last_j.lock().map(|l| *l).unwrap_or(f64::NAN);
            let args = (
                done.load(Ordering::Relaxed).min(total),
                total,
                starts_done.load(Ordering::Relaxed),
                n_starts,
                j,
            );
            IN_CALLBACK.set(true);
            let called = Python::attach(|py| cb.call1(py, args).map(|_| ()));
            IN_CALLBACK.set(false);
            if let (Err(e), Ok(mut err)) = (called, raised.lock())
                && err.is_none()
            {
                *err = Some(e);
            }
        });
        f
    });
    let res = compute(py, threads, || {
        let res = run_fit(kind, &data, &opts, callback)?;
        let curve = model_curve(kind, &res.best.base, &data, &FloatOptions::default());
        // the report of the CLI's JSON: minima, statistics and (uncertainty=True) the
        // uncertainty at every minimum
        let unc = if a.uncertainty {
            Some(fit_uncertainty(&res, &res.best.base, &data, a.jacobian).map_err(cli_text)?)
        } else {
            None
        };
        let report = fit_out(&a, &res, &data, unc)
            .map_err(cli_text)
            .and_then(|o| serde_json::to_string(&o).map_err(|e| e.to_string()))?;
        Ok::<_, String>((res, curve, report))
    })?;
    if let Some(e) = raised.lock().ok().and_then(|mut e| e.take()) {
        return Err(e);
    }
    let (res, curve, report) = res.map_err(PyRuntimeError::new_err)?;
    let d = PyDict::new(py);
    d.set_item("model", kind.name())?;
    d.set_item("base", base_tuple(&res.best.base))?;
    put_curve(&d, &curve)?;
    d.set_item("p1", a.p1)?;
    d.set_item("seed", a.seed)?;
    d.set_item("evaluations", res.evaluations)?;
    d.set_item("seconds", res.elapsed.as_secs_f64())?;
    let starts = pyo3::types::PyList::empty(py);
    for s in &res.starts {
        let sd = PyDict::new(py);
        sd.set_item("start", s.start + 1)?;
        sd.set_item("J", s.j)?;
        sd.set_item("base", base_tuple(&s.base))?;
        sd.set_item("initial", base_tuple(&s.initial))?;
        sd.set_item("iterations", s.iterations)?;
        sd.set_item("evaluations", s.evaluations)?;
        sd.set_item("converged", s.converged)?;
        starts.append(sd)?;
    }
    d.set_item("starts", starts)?;
    d.set_item("report", report)?;
    Ok(d)
}

/// The profiles (see `bwcl.profile`): the CLI's JSON report as a string.
#[pyfunction]
#[pyo3(signature = (argv, v0=None, e=None, threads=None))]
pub fn profile<'py>(
    py: Python<'py>,
    argv: Vec<String>,
    v0: Option<PyReadonlyArray1<'py, f64>>,
    e: Option<PyReadonlyArray1<'py, f64>>,
    threads: Option<usize>,
) -> PyResult<String> {
    let Command::Profile(a): Command = parse(&argv)?.command else {
        return Err(PyValueError::new_err("not a profile command"));
    };
    let a: ProfileArgs = a;
    let data = data_of(&a.data, v0, e)?;
    let out = compute(py, threads, || {
        super::cli::profile::compute(&a, &data, &indicatif::ProgressBar::hidden())
    })?;
    let out = out.map_err(py_error)?;
    serde_json::to_string(&out).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}
