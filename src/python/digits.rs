//! `bwcl.cor_rigorous(..., digits=D)`: T_s and e proved to D digits on MPFR intervals
//! ([`bwcl::observables::precision`]), as the CLI's `cor --rigorous --digits D`: the text
//! bounds carry every digit the width allows (lower rounded down, upper up), the float
//! bounds are the exact ends rounded outward to doubles, the widths rounded up.

use super::arrays::{put_bool, put_f64, put_f64_2d};
use super::cli::args::CorArgs;
use super::cli::input::Case;
use super::cli::precise::texts;
use super::run::{compute_rows, py_error};

use bwcl::observables::precision::{
    PreciseEnclosure, bits_for_digits, options_for_digits, outward_f64, outward_text, width_text,
};
use inari::Interval;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rug::Rational;

/// The exact ends as doubles rounded outward (NaN, NaN when there are none).
fn pair(p: Option<&[Rational; 2]>) -> [f64; 2] {
    p.and_then(outward_f64)
        .map_or([f64::NAN; 2], |x| [x.inf(), x.sup()])
}

/// An upper bound of a width as a double (the upper end of the point's outward doubles).
fn width_up(w: &Rational) -> f64 {
    pair(Some(&[w.clone(), w.clone()]))[1]
}

/// The dict of `cor_rigorous` (same keys) for `--digits`.
pub fn cor_digits<'py>(
    py: Python<'py>,
    a: &CorArgs,
    digits: usize,
    cases: Vec<Case<Interval>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = digits as u32;
    let bits = bits_for_digits(d)
        .ok_or_else(|| PyValueError::new_err(format!("--digits {digits}: must be in 1..=100")))?;
    let kind = super::cli::input::bouc_wen_only(a.params.model, "digits").map_err(py_error)?;
    let opts = super::cli::input::taylor_options(&a.engine).map_err(py_error)?;
    let v0s: Vec<Option<Interval>> = cases.iter().map(|c| c.v0).collect();
    let params: Vec<f64> = cases
        .iter()
        .flat_map(|c| {
            c.params
                .as_array()
                .into_iter()
                .flat_map(|x| [x.inf(), x.sup()])
                .collect::<Vec<f64>>()
        })
        .collect();
    let jobs = texts(cases).map_err(py_error)?;
    // (never less than the f64-interval engine proves: its enclosure, bits 53, with a reason;
    // no separation before the horizon is proved too)
    let (outs, seconds, used) = compute_rows(py, threads, &jobs, |(_, p)| {
        super::cli::precise::outcome(kind, p, digits, &opts, &a.engine)
    })?;
    let notes: Vec<Option<String>> = outs.iter().map(|o| o.note.clone()).collect();
    let no_sep: Vec<bool> = outs.iter().map(|o| o.no_separation).collect();
    let rows: Vec<Result<PreciseEnclosure, String>> = outs.into_iter().map(|o| o.res).collect();
    let ok = |r: &Result<PreciseEnclosure, String>| r.as_ref().ok().cloned();
    let proved: Vec<Option<PreciseEnclosure>> = rows.iter().map(ok).collect();
    let out = PyDict::new(py);
    out.set_item("model", kind.name())?;
    let v0_pairs: Vec<f64> = v0s
        .iter()
        .flat_map(|v| v.map_or([f64::NAN; 2], |x| [x.inf(), x.sup()]))
        .collect();
    put_f64_2d(&out, "v0", v0_pairs, 2)?;
    let flat = |f: &dyn Fn(&PreciseEnclosure) -> &[Rational; 2]| -> Vec<f64> {
        proved
            .iter()
            .flat_map(|p| pair(p.as_ref().map(f)))
            .collect()
    };
    put_f64_2d(&out, "ts", flat(&|p| &p.ts), 2)?;
    put_f64_2d(&out, "e", flat(&|p| &p.e), 2)?;
    let is = proved.iter().map(|p| p.is_some()).collect::<Vec<bool>>();
    put_bool(
        &out,
        "proved",
        is.iter().zip(&no_sep).map(|(a, b)| *a || *b).collect(),
    )?;
    put_bool(&out, "separated", is)?;
    put_f64(
        &out,
        "width_ts",
        proved
            .iter()
            .map(|p| p.as_ref().map_or(f64::NAN, |p| width_up(&p.width_ts())))
            .collect(),
    )?;
    put_f64(
        &out,
        "width_e",
        proved
            .iter()
            .map(|p| p.as_ref().map_or(f64::NAN, |p| width_up(&p.width_e())))
            .collect(),
    )?;
    put_f64_2d(&out, "params", params, 12)?;
    let v0_text: Vec<Option<(String, String)>> = v0s
        .iter()
        .map(|v| super::rigorous::v0_text(v.map(|x| [x.inf(), x.sup()])))
        .collect();
    out.set_item("v0_text", v0_text)?;
    let text = |f: &dyn Fn(&PreciseEnclosure) -> &[Rational; 2]| {
        proved
            .iter()
            .map(|p| p.as_ref().map(|p| outward_text(f(p), p.bits)))
            .collect::<Vec<_>>()
    };
    out.set_item("ts_text", text(&|p| &p.ts))?;
    out.set_item("e_text", text(&|p| &p.e))?;
    let wtext = |f: &dyn Fn(&PreciseEnclosure) -> Rational| {
        proved
            .iter()
            .map(|p| p.as_ref().map(|p| width_text(&f(p))))
            .collect::<Vec<_>>()
    };
    out.set_item("width_ts_text", wtext(&|p| p.width_ts()))?;
    out.set_item("width_e_text", wtext(&|p| p.width_e()))?;
    // a proved case's reason is the note of an f64 enclosure in place of the digits
    out.set_item(
        "reason",
        rows.iter()
            .zip(&notes)
            .map(|(r, n)| r.as_ref().err().cloned().or(n.clone()))
            .collect::<Vec<_>>(),
    )?;
    out.set_item(
        "bits",
        rows.iter()
            .map(|r| r.as_ref().map_or(bits, |p| p.bits))
            .collect::<Vec<_>>(),
    )?;
    out.set_item(
        "fallback",
        vec![None::<Vec<(u32, f64, bool, String)>>; rows.len()],
    )?;
    out.set_item("horizon", opts.horizon)?;
    // the order the runs used (rigorous_impact_digits derives it from D the same way)
    out.set_item("order", options_for_digits(d, &opts).order)?;
    out.set_item("seconds", seconds)?;
    out.set_item("threads", used)?;
    out.set_item("digits", digits)?;
    Ok(out)
}
