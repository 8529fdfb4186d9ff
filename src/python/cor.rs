//! `bwcl.cor`: T_s and e on the f64 DOP853 engine at the paper's settings (eq:main_t_s,
//! eq:main_cor), one case per impact speed, the cases in parallel.

use super::arrays::{put_bool, put_f64, put_f64_2d, put_i64, speed_lists};
use super::cli::args::{Command, CorArgs};
use super::cli::commands::float_row;
use super::cli::input::{self, Case};
use super::run::{compute_rows, parse, py_error};
use bwcl::arith::Real;
use bwcl::models::ModelKind;
use numpy::PyReadonlyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The `cor` arguments of `argv` (plus the first --v0 list) and the validated cases of every
/// list, in order.
pub fn cor_cases<R: Real>(
    argv: Vec<String>,
    lists: Option<Vec<String>>,
) -> PyResult<(CorArgs, Vec<Case<R>>)> {
    let mut argv = argv;
    if let Some(first) = lists.as_ref().and_then(|l| l.first()) {
        argv.push(format!("--v0={first}"));
    }
    let Command::Cor(a) = parse(&argv)?.command else {
        return Err(PyValueError::new_err("not a cor command"));
    };
    let mut cases = Vec::new();
    match &lists {
        None => cases = input::cases::<R>(&a.params).map_err(py_error)?,
        Some(lists) => {
            for text in lists {
                let mut p = a.params.clone();
                p.v0 = Some(text.clone());
                cases.extend(input::cases::<R>(&p).map_err(py_error)?);
            }
        }
    }
    Ok((a, cases))
}

/// T_s and e of every case (see `bwcl.cor`): a dict of NumPy arrays.
#[pyfunction]
#[pyo3(signature = (argv, v0_array=None, v0_tokens=None, threads=None))]
pub fn cor<'py>(
    py: Python<'py>,
    argv: Vec<String>,
    v0_array: Option<PyReadonlyArray1<'py, f64>>,
    v0_tokens: Option<Vec<String>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let lists = speed_lists(v0_array, v0_tokens);
    let (a, cases) = cor_cases::<f64>(argv, lists)?;
    if a.engine.rigorous {
        return Err(PyValueError::new_err("--rigorous: use bwcl.cor_rigorous"));
    }
    let kind = ModelKind::from(a.params.model);
    let opts = input::float_options(&a.engine).map_err(py_error)?;
    let (rows, seconds, used) = compute_rows(py, threads, &cases, |c| float_row(kind, c, &opts))?;
    let d = PyDict::new(py);
    d.set_item("model", kind.name())?;
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
    let params: Vec<f64> = rows
        .iter()
        .flat_map(|r| {
            let p = &r.params;
            [p.b, p.gamma, p.kappa, p.sigma, p.n, p.p]
        })
        .collect();
    put_f64_2d(&d, "params", params, 6)?;
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
    let errors: Vec<Option<String>> = rows.into_iter().map(|r| r.error).collect();
    d.set_item("error", errors)?;
    d.set_item("horizon", opts.horizon)?;
    d.set_item("seconds", seconds)?;
    d.set_item("threads", used)?;
    Ok(d)
}
