//! The way of every call: the CLI's parser and checks, errors as Python exceptions, the
//! computation with the GIL released on a rayon pool, panics caught.

use super::cli::args::{Cli, Command};
use super::cli::{CliError, error_line, usage_message};
use bwcl::engines::cancel::Request;
use clap::Parser;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Condvar, Mutex, PoisonError};

/// Most threads of one call's pool.
pub const MAX_THREADS: usize = 1024;

/// How often a running call looks for signals (Ctrl-C).
const POLL: std::time::Duration = std::time::Duration::from_millis(10);

/// A CLI error as a Python exception: bad input → `ValueError`, a computation that failed on
/// valid input → `RuntimeError`; the message is the line the program prints after
/// "bwcl: error: ".
pub fn py_error(e: CliError) -> PyErr {
    match e {
        CliError::Input(m) => PyValueError::new_err(error_line(&m)),
        CliError::Failed(m) => PyRuntimeError::new_err(error_line(&m)),
    }
}

/// A JSON-report command of the CLI (`bwcl <argv> --format json` as the Python layer builds
/// it): parsed, checked to be the command `name` (`pick`), computed with the GIL released
/// (`threads` as in [`compute`]), its bytes as text.
pub fn json_command<A, P, R>(
    py: Python<'_>,
    argv: &[String],
    threads: Option<usize>,
    name: &str,
    pick: P,
    report: R,
) -> PyResult<String>
where
    A: Send + Sync,
    P: FnOnce(Command) -> Option<A>,
    R: FnOnce(&A) -> Result<Vec<u8>, CliError> + Send,
{
    watched_command(py, argv, threads, name, pick, None, |a, _| report(a))
}

/// The progress a computation reports as it goes: the share of its work settled (0..1) and a
/// message; only the latest is kept, for the polling loop of [`watched_command`] to show.
#[derive(Clone, Default)]
pub struct Watch(std::sync::Arc<Mutex<Option<(f64, String)>>>);

impl Watch {
    /// The share is clamped to [0, 1] (−0 read as 0).
    pub fn set(&self, share: f64, message: String) {
        let share = if share > 0.0 { share.min(1.0) } else { 0.0 };
        *self.0.lock().unwrap_or_else(PoisonError::into_inner) = Some((share, message));
    }
    fn take(&self) -> Option<(f64, String)> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner).take()
    }
}

/// [`json_command`] whose report tells its progress to a [`Watch`]: `progress(share,
/// message)` (a Python callable) is called with the latest at most every 0.1 s; an exception
/// it raises stops the computation and is raised.
pub fn watched_command<A, P, R>(
    py: Python<'_>,
    argv: &[String],
    threads: Option<usize>,
    name: &str,
    pick: P,
    progress: Option<Py<PyAny>>,
    report: R,
) -> PyResult<String>
where
    A: Send + Sync,
    P: FnOnce(Command) -> Option<A>,
    R: FnOnce(&A, &Watch) -> Result<Vec<u8>, CliError> + Send,
{
    let a = pick(parse(argv)?.command)
        .ok_or_else(|| PyValueError::new_err(format!("{name}: not a {name} command")))?;
    let watch = Watch::default();
    let mut shown: Option<std::time::Instant> = None;
    let poll = |py: Python<'_>| -> PyResult<()> {
        let Some(cb) = &progress else { return Ok(()) };
        if shown.is_some_and(|t| t.elapsed() < PROGRESS_EVERY) {
            return Ok(());
        }
        if let Some((share, message)) = watch.take() {
            shown = Some(std::time::Instant::now());
            cb.call1(py, (share, message))?;
        }
        Ok(())
    };
    let bytes = compute_polled(py, threads, || report(&a, &watch), poll)?.map_err(py_error)?;
    String::from_utf8(bytes).map_err(|e| PyValueError::new_err(format!("{name}: {e}")))
}

/// Parses the CLI's arguments (without the program name), as `bwcl` would.
pub fn parse(argv: &[String]) -> PyResult<Cli> {
    Cli::try_parse_from(std::iter::once("bwcl").chain(argv.iter().map(String::as_str)))
        .map_err(|e| PyValueError::new_err(error_line(&usage_message(&e))))
}

/// The text of a panic's payload.
fn panic_text(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "(no message)".into()
    }
}

/// Runs `f` with the GIL released, on a pool of `threads` threads (the global rayon pool for
/// `None`); a panic (in `f` or in one of its rayon tasks, which rayon carries back here)
/// becomes a `RuntimeError`, and Ctrl-C a `KeyboardInterrupt` within a step of the engines
/// (the computation stopped, nothing of it returned).
pub fn compute<T, F>(py: Python<'_>, threads: Option<usize>, f: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> T + Send,
{
    compute_polled(py, threads, f, |_| Ok(()))
}

/// [`compute`], calling `poll` with the GIL held at every look for signals (every 10 ms while
/// the computation runs): an exception it returns stops the computation as Ctrl-C does, and
/// is raised.
pub fn compute_polled<T, F, P>(
    py: Python<'_>,
    threads: Option<usize>,
    f: F,
    mut poll: P,
) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> T + Send,
    P: FnMut(Python<'_>) -> PyResult<()>,
{
    let pool = match threads {
        None => None,
        Some(k) if (1..=MAX_THREADS).contains(&k) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(k)
                .build()
                .map_err(|e| PyRuntimeError::new_err(format!("cannot start {k} threads: {e}")))?,
        ),
        Some(k) => {
            return Err(PyValueError::new_err(format!(
                "threads = {k} must be a whole number in 1..={MAX_THREADS}"
            )));
        }
    };
    // called from a worker of the shared pool (a progress callback of `fit` runs there and may
    // call bwcl itself): the computation runs here, with the GIL released. Waiting for it on a
    // thread of its own would block this worker outside the pool, and with every worker so
    // blocked nothing would run the computations' jobs (a hang; signals are looked for by the
    // outer call on Python's main thread)
    if pool.is_none() && rayon::current_thread_index().is_some() {
        return py
            .detach(|| catch_unwind(AssertUnwindSafe(f)))
            .map_err(|p| {
                PyRuntimeError::new_err(format!(
                    "bwcl: internal error (a bug, please report it): {}",
                    panic_text(p.as_ref())
                ))
            });
    }
    // the computation on its own thread; this one (Python's, usually the main thread) waits
    // for its end with the GIL released, looking for signals every 10 ms meanwhile (a call
    // that ends sooner returns at once): on KeyboardInterrupt (or any exception a signal
    // handler raises) every engine is asked to stop ([`bwcl::engines::cancel`]), the
    // computation's end awaited and its result dropped
    let ended = (Mutex::new(false), Condvar::new());
    let run = || {
        let out = catch_unwind(AssertUnwindSafe(|| match &pool {
            Some(p) => p.install(f),
            None => f(),
        }));
        *ended.0.lock().unwrap_or_else(PoisonError::into_inner) = true;
        ended.1.notify_all();
        out
    };
    // whether the computation ended, waiting for it at most POLL
    let wait = || {
        let done = ended.0.lock().unwrap_or_else(PoisonError::into_inner);
        let (done, _) = ended
            .1
            .wait_timeout_while(done, POLL, |d| !*d)
            .unwrap_or_else(PoisonError::into_inner);
        *done
    };
    let (out, interrupted) = std::thread::scope(|s| {
        let worker = s.spawn(run);
        let mut interrupted: Option<(PyErr, Request)> = None;
        while !py.detach(wait) {
            if interrupted.is_none()
                && let Err(e) = py.check_signals().and_then(|()| poll(py))
            {
                interrupted = Some((e, Request::new()));
            }
        }
        let out = worker.join().unwrap_or_else(Err);
        (out, interrupted.map(|(e, _request)| e))
    });
    if let Some(e) = interrupted {
        return Err(e);
    }
    out.map_err(|p| {
        PyRuntimeError::new_err(format!(
            "bwcl: internal error (a bug, please report it): {}",
            panic_text(p.as_ref())
        ))
    })
}

/// [`compute`] of one row per case, in parallel: (the rows in order, the seconds the rows
/// took, the threads of the pool that ran them).
pub fn compute_rows<C, R, F>(
    py: Python<'_>,
    threads: Option<usize>,
    cases: &[C],
    row: F,
) -> PyResult<(Vec<R>, f64, usize)>
where
    C: Sync,
    R: Send,
    F: Fn(&C) -> R + Sync + Send,
{
    compute_rows_progress(py, threads, cases, None, row)
}

/// Least time between two calls of a progress callback.
const PROGRESS_EVERY: std::time::Duration = std::time::Duration::from_millis(100);

/// [`compute_rows`], calling `progress(done, total)` (a Python callable) as the rows finish,
/// at most every 0.1 s; an exception it raises stops the computation and is raised.
pub fn compute_rows_progress<C, R, F>(
    py: Python<'_>,
    threads: Option<usize>,
    cases: &[C],
    progress: Option<Py<PyAny>>,
    row: F,
) -> PyResult<(Vec<R>, f64, usize)>
where
    C: Sync,
    R: Send,
    F: Fn(&C) -> R + Sync + Send,
{
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let done = AtomicUsize::new(0);
    let total = cases.len();
    let mut shown = (usize::MAX, std::time::Instant::now());
    let poll = |py: Python<'_>| -> PyResult<()> {
        let Some(cb) = &progress else { return Ok(()) };
        let now = done.load(Ordering::Relaxed);
        if now != shown.0 && (shown.0 == usize::MAX || shown.1.elapsed() >= PROGRESS_EVERY) {
            shown = (now, std::time::Instant::now());
            cb.call1(py, (now, total))?;
        }
        Ok(())
    };
    compute_polled(
        py,
        threads,
        || {
            let start = std::time::Instant::now();
            // once a stop is requested the cases left are not started
            let rows: Option<Vec<R>> = cases
                .par_iter()
                .map(|c| {
                    (!bwcl::engines::cancel::requested()).then(|| {
                        let r = row(c);
                        done.fetch_add(1, Ordering::Relaxed);
                        r
                    })
                })
                .collect();
            rows.map(|rows| {
                (
                    rows,
                    start.elapsed().as_secs_f64(),
                    rayon::current_num_threads(),
                )
            })
        },
        poll,
    )?
    .ok_or_else(stopped)
}

/// The error of a call cut short by a stop another call requested (Ctrl-C during it): the
/// call that was interrupted raises KeyboardInterrupt instead.
pub fn stopped() -> PyErr {
    PyRuntimeError::new_err("stopped: Ctrl-C interrupted a bwcl call while this one ran")
}

/// Panics inside a rayon task with the GIL released: the tests check that this raises
/// `RuntimeError` instead of aborting the interpreter.
#[pyfunction]
pub fn panic_for_test(py: Python<'_>, threads: Option<usize>) -> PyResult<usize> {
    use rayon::prelude::*;
    compute(py, threads, || {
        (0..4usize)
            .into_par_iter()
            .map(|i| if i == 3 { panic!("a test panic") } else { i })
            .sum()
    })
}
