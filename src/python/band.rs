//! `bwcl.band` (a proved CoR curve over a range of impact speeds) and `bwcl.prove_monotone`
//! (e(v0) strictly decreasing, proved or refuted): the JSON reports of `bwcl cor --rigorous
//! --band FILE.json` and `bwcl prove monotone --format json`, with the GIL released and the
//! progress told to a Python callback.

use super::cli::args::{Command, ProveCommand};
use super::cli::band::{band_report, monotone_report};
use super::run::{Watch, watched_command};
use pyo3::prelude::*;

/// The band of `bwcl cor <argv> --rigorous --band F.json` as the file's JSON text (see
/// `bwcl.band`); nothing is written.
#[pyfunction]
#[pyo3(signature = (argv, threads=None, progress=None))]
pub fn band(
    py: Python<'_>,
    argv: Vec<String>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let pick = |c| match c {
        Command::Cor(a) if a.band.is_some() => Some(a),
        _ => None,
    };
    watched_command(py, &argv, threads, "band", pick, progress, |a, watch| {
        band_report(a, true, Some(tell(watch))).map(|(bytes, _)| bytes)
    })
}

/// The report of `bwcl prove monotone <argv> --format json` (see `bwcl.prove_monotone`).
#[pyfunction]
#[pyo3(signature = (argv, threads=None, progress=None))]
pub fn prove_monotone(
    py: Python<'_>,
    argv: Vec<String>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let pick = |c| match c {
        Command::Prove(p) => match p.what {
            ProveCommand::Monotone(m) => Some(m),
        },
        _ => None,
    };
    watched_command(
        py,
        &argv,
        threads,
        "prove monotone",
        pick,
        progress,
        |a, watch| monotone_report(a, Some(tell(watch))).map(|(text, _)| text.into_bytes()),
    )
}

/// The progress of a band's pieces (share of the range settled, pieces) told to `watch`.
fn tell(watch: &Watch) -> bwcl::observables::band::Progress {
    let watch = watch.clone();
    bwcl::observables::band::Progress(std::sync::Arc::new(move |share: f64, pieces: usize| {
        let share = if share > 0.0 { share.min(1.0) } else { 0.0 };
        watch.set(
            share,
            format!(
                "{:.1} % of the range settled, {pieces} pieces",
                100.0 * share
            ),
        )
    }))
}
