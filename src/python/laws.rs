//! `bwcl.laws`: the Hunt–Crossley damping formulas against the CoR the law really produces,
//! proved — the JSON report of `bwcl laws --format json` (every bound rounded outward), with
//! the GIL released and the formulas in parallel.

use super::cli::args::Command;
use super::cli::laws::report;
use super::run::json_command;
use pyo3::prelude::*;

/// The report of `bwcl laws <argv>` as its JSON text (see `bwcl.laws`).
#[pyfunction]
#[pyo3(signature = (argv, threads=None))]
pub fn laws(py: Python<'_>, argv: Vec<String>, threads: Option<usize>) -> PyResult<String> {
    let pick = |c| match c {
        Command::Laws(a) => Some(a),
        _ => None,
    };
    json_command(py, &argv, threads, "laws", pick, report)
}
