//! `bwcl.classical`: T_s and e of a classical collision law (float or proved), the JSON report
//! of `bwcl classical --format json` (bounds rounded outward), with the GIL released.

use super::cli::args::Command;
use super::cli::classical::report;
use super::run::{compute, parse, py_error};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The report of `bwcl classical <argv>` as its JSON text (see `bwcl.classical`).
#[pyfunction]
#[pyo3(signature = (argv, threads=None))]
pub fn classical(py: Python<'_>, argv: Vec<String>, threads: Option<usize>) -> PyResult<String> {
    let cli = parse(&argv)?;
    let Command::Classical(a) = cli.command else {
        return Err(PyValueError::new_err("classical: not a classical command"));
    };
    let (bytes, _) = compute(py, threads, || report(&a))?.map_err(py_error)?;
    String::from_utf8(bytes).map_err(|e| PyValueError::new_err(format!("classical: {e}")))
}
