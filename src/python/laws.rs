//! `bwcl.laws`: the Hunt–Crossley damping formulas against the CoR the law really produces,
//! proved — the JSON report of `bwcl laws --format json` (every bound rounded outward), with
//! the GIL released and the formulas in parallel.

use super::cli::args::Command;
use super::cli::laws::report;
use super::run::{compute, parse, py_error};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The report of `bwcl laws <argv>` as its JSON text (see `bwcl.laws`).
#[pyfunction]
#[pyo3(signature = (argv, threads=None))]
pub fn laws(py: Python<'_>, argv: Vec<String>, threads: Option<usize>) -> PyResult<String> {
    let cli = parse(&argv)?;
    let Command::Laws(a) = cli.command else {
        return Err(PyValueError::new_err("laws: not a laws command"));
    };
    let bytes = compute(py, threads, || report(&a))?.map_err(py_error)?;
    String::from_utf8(bytes).map_err(|e| PyValueError::new_err(format!("laws: {e}")))
}
