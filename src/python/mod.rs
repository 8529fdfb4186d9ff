//! The Python extension module `bwcl._bwcl`: the crate `bwcl-python` (bindings/Cargo.toml),
//! built by maturin from `pyproject.toml`; the public API is the pure-Python package in
//! `python/bwcl/`.
//!
//! Every call goes the CLI's way: the keyword arguments arrive as the CLI's own arguments
//! (`--base=…`, `--v0=…`, `--rtol=…`), are parsed by its clap definitions and checked by its
//! input code ([`cli`], the same files as the `bwcl` program), so a bad value raises
//! `ValueError` with the one line the program prints. The cases then run on the library's
//! engines, with the GIL released and the speeds in parallel on rayon ([`run::compute`]); a
//! Rust panic becomes a `RuntimeError`, never an abort.
//!
//! - [`cor`]: T_s and e on the f64 DOP853 engine (eq:main_t_s, eq:main_cor);
//! - [`rigorous`]: their proved enclosures, rounded outward as floats and decimals;
//! - [`trajectory`]: the sampled trajectory and hysteresis loop, float or proved;
//! - [`fit`]: the cost J (eq:J) and the multi-start Nelder–Mead fit, with a progress callback;
//! - [`band`]: the proved CoR band over a range of speeds and `prove monotone`;
//! - [`identify`]: proved feasible sets of P* (set-membership identification);
//! - [`laws`]: the Hunt–Crossley damping formulas' errors, proved;
//! - [`classical`]: T_s and e of the classical collision laws;
//! - [`run`]: argument parsing, errors, the thread pool and the GIL.

// The CLI's parsers, checks and rows, as the library compiled them for the program.
use bwcl::cli;

mod arrays;
mod band;
mod classical;
mod compare;
mod cor;
mod digits;
mod fit;
mod identify;
mod laws;
mod rigorous;
mod run;
mod trajectory;

use pyo3::prelude::*;

/// The native part of the `bwcl` package (use the functions of `bwcl`, not these).
#[pymodule]
fn _bwcl(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // NumPy's C API is loaded now, at import: loaded at a call's first array, a pending
    // KeyboardInterrupt made the loading fail and the numpy crate panic
    let _ = numpy::PyArray1::<f64>::zeros(m.py(), 0, false);
    m.add_function(wrap_pyfunction!(cor::cor, m)?)?;
    m.add_function(wrap_pyfunction!(rigorous::cor_rigorous, m)?)?;
    m.add_function(wrap_pyfunction!(trajectory::trajectory, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit, m)?)?;
    m.add_function(wrap_pyfunction!(fit::cost, m)?)?;
    m.add_function(wrap_pyfunction!(identify::identify, m)?)?;
    m.add_function(wrap_pyfunction!(fit::profile, m)?)?;
    m.add_function(wrap_pyfunction!(laws::laws, m)?)?;
    m.add_function(wrap_pyfunction!(classical::classical, m)?)?;
    m.add_function(wrap_pyfunction!(compare::compare, m)?)?;
    m.add_function(wrap_pyfunction!(band::band, m)?)?;
    m.add_function(wrap_pyfunction!(band::prove_monotone, m)?)?;
    m.add_function(wrap_pyfunction!(run::panic_for_test, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MAX_SPEEDS_PER_PARSE", cli::input::MAX_SPEEDS)?;
    Ok(())
}
