//! `bwcl.classical`: T_s and e of a classical collision law (float or proved), the JSON report
//! of `bwcl classical --format json` (bounds rounded outward), with the GIL released.

use super::cli::args::Command;
use super::cli::classical::report;
use super::run::json_command;
use pyo3::prelude::*;

/// The report of `bwcl classical <argv>` as its JSON text (see `bwcl.classical`).
#[pyfunction]
#[pyo3(signature = (argv, threads=None))]
pub fn classical(py: Python<'_>, argv: Vec<String>, threads: Option<usize>) -> PyResult<String> {
    let pick = |c| match c {
        Command::Classical(a) => Some(a),
        _ => None,
    };
    json_command(py, &argv, threads, "classical", pick, |a| {
        report(a).map(|(bytes, _)| bytes)
    })
}
