//! `bwcl.band` (a proved CoR curve over a range of impact speeds) and `bwcl.prove_monotone`
//! (e(v0) strictly decreasing, proved or refuted): the JSON reports of `bwcl cor --rigorous
//! --band FILE.json` and `bwcl prove monotone --format json`, with the GIL released.

use super::cli::args::{Command, ProveCommand};
use super::cli::band::{band_report, monotone_report};
use super::run::json_command;
use pyo3::prelude::*;

/// The band of `bwcl cor <argv> --rigorous --band F.json` as the file's JSON text (see
/// `bwcl.band`); nothing is written.
#[pyfunction]
#[pyo3(signature = (argv, threads=None))]
pub fn band(py: Python<'_>, argv: Vec<String>, threads: Option<usize>) -> PyResult<String> {
    let pick = |c| match c {
        Command::Cor(a) if a.band.is_some() => Some(a),
        _ => None,
    };
    json_command(py, &argv, threads, "band", pick, |a| {
        band_report(a, true).map(|(bytes, _)| bytes)
    })
}

/// The report of `bwcl prove monotone <argv> --format json` (see `bwcl.prove_monotone`).
#[pyfunction]
#[pyo3(signature = (argv, threads=None))]
pub fn prove_monotone(
    py: Python<'_>,
    argv: Vec<String>,
    threads: Option<usize>,
) -> PyResult<String> {
    let pick = |c| match c {
        Command::Prove(p) => match p.what {
            ProveCommand::Monotone(m) => Some(m),
        },
        _ => None,
    };
    json_command(py, &argv, threads, "prove monotone", pick, |a| {
        monotone_report(a).map(|(text, _)| text.into_bytes())
    })
}
