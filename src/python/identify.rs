//! `bwcl.identify`: proved feasible sets of P* (set-membership identification), the paving as
//! the JSON report of `bwcl identify --format json` (box ends rounded outward or, for a set a
//! claim is made on, inward), with the
//! GIL released and the boxes in parallel.

use super::cli::args::Command;
use super::cli::identify::{compute as pave, json_report, resolution};
use super::run::watched_command;
use pyo3::prelude::*;

/// The paving of `bwcl identify <argv>` as its JSON text (see `bwcl.identify`).
#[pyfunction]
#[pyo3(signature = (argv, threads=None, progress=None))]
pub fn identify(
    py: Python<'_>,
    argv: Vec<String>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let pick = |c| match c {
        Command::Identify(a) => Some(a),
        _ => None,
    };
    watched_command(
        py,
        &argv,
        threads,
        "identify",
        pick,
        progress,
        |a, watch| {
            let tell = |share: f64, message: String| watch.set(share, message);
            pave(a, false, Some(&tell)).and_then(|d| json_report(&d, resolution(a)))
        },
    )
}
