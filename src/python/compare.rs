//! `bwcl.compare`: every model fitted to the same CoR data, with its information criteria and
//! each classical law's proved feasible set — the JSON report of `bwcl compare --format json`,
//! with the GIL released.

use super::cli::args::Command;
use super::cli::compare::report;
use super::run::json_command;
use pyo3::prelude::*;

/// The report of `bwcl compare <argv>` as its JSON text (see `bwcl.compare`).
#[pyfunction]
#[pyo3(signature = (argv, threads=None))]
pub fn compare(py: Python<'_>, argv: Vec<String>, threads: Option<usize>) -> PyResult<String> {
    let pick = |c| match c {
        Command::Compare(a) => Some(a),
        _ => None,
    };
    json_command(py, &argv, threads, "compare", pick, |a| {
        report(a, false).map(|(bytes, _)| bytes)
    })
}
