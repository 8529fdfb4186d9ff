//! `bwcl.cor_rigorous`: proved enclosures of T_s and e (the interval Taylor engine), each bound
//! as a double and as the decimal the CLI prints, rounded outward
//! ([`bwcl::observables::decimal`]); a case that is not proved carries its reason.

use super::arrays::{put_bool, put_f64, put_f64_2d, speed_lists};
use super::cli::args::CorArgs;
use super::cli::commands::rigorous_row;
use super::cli::input;
use super::cli::law_runs;
use super::cli::output::{RigorousRow, derived_columns, inner_pair};
use super::cor::{cor_args, per_list, put_params};
use super::run::{compute_rows_progress, py_error};
use bwcl::engines::taylor::TaylorOptions;
use bwcl::observables::decimal::{Rounding, outward};
use inari::Interval;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The bounds of an enclosure (NaN, NaN when there is none).
fn pair(b: Option<[f64; 2]>) -> [f64; 2] {
    b.unwrap_or([f64::NAN; 2])
}

/// The bounds as decimals rounded outward (lower down, upper up), as in the CLI's output.
pub(super) fn pair_text(b: Option<[f64; 2]>) -> Option<(String, String)> {
    b.map(|[lo, hi]| (outward(lo, Rounding::Down), outward(hi, Rounding::Up)))
}

/// The decimals of a range of v0 the result holds for, rounded inward ([`inner_pair`]).
pub(super) fn v0_text(b: Option<[f64; 2]>) -> Option<(String, String)> {
    b.map(|[lo, hi]| inner_pair(lo, hi).into())
}

/// Enclosures of T_s and e of every case (see `bwcl.cor_rigorous`): a dict of arrays and
/// lists.
#[pyfunction]
#[pyo3(signature = (argv, v0_tokens=None, sets=None, threads=None, progress=None))]
pub fn cor_rigorous<'py>(
    py: Python<'py>,
    argv: Vec<String>,
    v0_tokens: Option<Vec<String>>,
    sets: Option<Vec<String>>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let lists = speed_lists(None, v0_tokens);
    let a = cor_args(argv, &lists)?;
    if !a.engine.rigorous {
        return Err(PyValueError::new_err("not --rigorous: use bwcl.cor"));
    }
    if let Some(law) = a.params.model.law() {
        if a.digits.is_some() {
            input::bouc_wen_only(a.params.model, "digits").map_err(py_error)?;
        }
        law_runs::check_cor_options(&a).map_err(py_error)?;
        let opts = input::taylor_options(&a.engine).map_err(py_error)?;
        let cases = per_list(py, &a, &lists, &sets, |p| {
            input::law_cases::<Interval>(p, law)
        })?;
        let (rows, seconds, used) = compute_rows_progress(py, threads, &cases, progress, |c| {
            law_runs::rigorous_row(law, c, &opts, a.derived, a.engine.time_limit)
        })?;
        return rows_dict(py, &a, &opts, rows, seconds, used);
    }
    let cases = per_list(py, &a, &lists, &sets, input::cases::<Interval>)?;
    if let Some(digits) = a.digits {
        return super::digits::cor_digits(py, &a, digits, cases, threads);
    }
    let kind = input::bouc_wen_only(a.params.model, "cor").map_err(py_error)?;
    let opts = input::taylor_options(&a.engine).map_err(py_error)?;
    let pieces = input::pieces(&a.engine);
    let fallback = input::fallback(a.fallback_bits, a.fallback_seconds);
    let (rows, seconds, used) = compute_rows_progress(py, threads, &cases, progress, |c| {
        rigorous_row(
            kind,
            c,
            &opts,
            pieces,
            a.sensitivities,
            a.derived,
            &fallback,
            a.engine.time_limit,
        )
    })?;
    rows_dict(py, &a, &opts, rows, seconds, used)
}

/// The rows of `cor_rigorous` as the dict the Python side reads.
fn rows_dict<'py>(
    py: Python<'py>,
    a: &CorArgs,
    opts: &TaylorOptions,
    rows: Vec<RigorousRow>,
    seconds: f64,
    used: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("model", a.params.model.key())?;
    let flat =
        |f: &dyn Fn(&RigorousRow) -> [f64; 2]| -> Vec<f64> { rows.iter().flat_map(f).collect() };
    put_f64_2d(&d, "v0", flat(&|r| pair(r.v0)), 2)?;
    put_f64_2d(&d, "ts", flat(&|r| pair(r.ts)), 2)?;
    put_f64_2d(&d, "e", flat(&|r| pair(r.e)), 2)?;
    put_bool(&d, "proved", rows.iter().map(|r| r.proved).collect())?;
    put_bool(&d, "separated", rows.iter().map(|r| r.separated).collect())?;
    put_f64(
        &d,
        "width_ts",
        rows.iter()
            .map(|r| r.width_ts.unwrap_or(f64::NAN))
            .collect(),
    )?;
    put_f64(
        &d,
        "width_e",
        rows.iter().map(|r| r.width_e.unwrap_or(f64::NAN)).collect(),
    )?;
    if a.params.physical.is_some() {
        put_f64_2d(&d, "ts_seconds", flat(&|r| pair(r.ts_seconds.flatten())), 2)?;
    }
    put_params(&d, rows.iter().map(|r| &r.params).collect(), |x| x)?;
    let text = |f: &dyn Fn(&RigorousRow) -> Option<[f64; 2]>| {
        rows.iter().map(|r| pair_text(f(r))).collect::<Vec<_>>()
    };
    d.set_item(
        "v0_text",
        rows.iter().map(|r| v0_text(r.v0)).collect::<Vec<_>>(),
    )?;
    d.set_item("ts_text", text(&|r| r.ts))?;
    d.set_item("e_text", text(&|r| r.e))?;
    let up = |w: Option<f64>| w.map(|w| outward(w, Rounding::Up));
    d.set_item(
        "width_ts_text",
        rows.iter().map(|r| up(r.width_ts)).collect::<Vec<_>>(),
    )?;
    d.set_item(
        "width_e_text",
        rows.iter().map(|r| up(r.width_e)).collect::<Vec<_>>(),
    )?;
    d.set_item(
        "reason",
        rows.iter().map(|r| r.reason.clone()).collect::<Vec<_>>(),
    )?;
    // the precision that proved each case, and the precision fallback's runs (bits, seconds,
    // proved, reason) where it ran
    d.set_item("bits", rows.iter().map(|r| r.bits).collect::<Vec<_>>())?;
    d.set_item(
        "fallback",
        rows.iter()
            .map(|r| {
                r.fallback.as_ref().map(|runs| {
                    runs.iter()
                        .map(|f| (f.bits, f.seconds, f.proved, f.reason.clone()))
                        .collect::<Vec<_>>()
                })
            })
            .collect::<Vec<_>>(),
    )?;
    if a.derived {
        // F_max, δ_max, ΔE (and in SI with --physical): (n, 2) bounds, NaN where not
        // computed, the decimals rounded outward, and the reason where not computed
        let cols = derived_columns(a.params.physical.is_some());
        let at =
            |r: &RigorousRow, j: usize| r.derived.as_ref().and_then(|d| d.values()[j]).map(|p| p.0);
        for (j, name) in cols.iter().enumerate() {
            put_f64_2d(&d, name, flat(&|r| pair(at(r, j))), 2)?;
            d.set_item(format!("{name}_text"), text(&|r| at(r, j)))?;
        }
        let why = |r: &RigorousRow| r.derived.as_ref().and_then(|d| d.reason.clone());
        d.set_item("derived_reason", rows.iter().map(why).collect::<Vec<_>>())?;
    }
    if a.sensitivities {
        // per case: (input, ∂T_s/∂u, ∂e/∂u, reason), the bounds rounded outward
        let sens = rows
            .iter()
            .map(|r| {
                r.sensitivities.as_ref().map(|all| {
                    all.iter()
                        .map(|s| (s.input, s.dts, s.de, s.reason.clone()))
                        .collect::<Vec<_>>()
                })
            })
            .collect::<Vec<_>>();
        d.set_item("sensitivities", sens)?;
    }
    d.set_item("horizon", opts.horizon)?;
    d.set_item("order", opts.order)?;
    d.set_item("seconds", seconds)?;
    d.set_item("threads", used)?;
    Ok(d)
}
