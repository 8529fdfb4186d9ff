//! `bwcl.identify`: proved feasible sets of P* (set-membership identification), the paving as
//! the JSON report of `bwcl identify --format json` (every box end rounded outward), with the
//! GIL released and the boxes in parallel.

use super::cli::args::Command;
use super::cli::identify::{compute as pave, json_report};
use super::run::{compute, parse, py_error};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The paving of `bwcl identify <argv>` as its JSON text (see `bwcl.identify`).
#[pyfunction]
#[pyo3(signature = (argv, threads=None))]
pub fn identify(py: Python<'_>, argv: Vec<String>, threads: Option<usize>) -> PyResult<String> {
    let cli = parse(&argv)?;
    let Command::Identify(a) = cli.command else {
        return Err(PyValueError::new_err("identify: not an identify command"));
    };
    let bytes = compute(py, threads, || {
        pave(&a, false).and_then(|d| json_report(&d, a.resolution))
    })?
    .map_err(py_error)?;
    String::from_utf8(bytes).map_err(|e| PyValueError::new_err(format!("identify: {e}")))
}
