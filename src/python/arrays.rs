//! Rust vectors as NumPy arrays, and the speeds of a call as the CLI's --v0 lists.

use super::cli::input::MAX_SPEEDS;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `vals` as a 1-D float64 array under `key`.
pub fn put_f64(d: &Bound<'_, PyDict>, key: &str, vals: Vec<f64>) -> PyResult<()> {
    d.set_item(key, vals.into_pyarray(d.py()))
}

/// Rows of `k` values (row-major) as an (n, k) float64 array under `key`.
pub fn put_f64_2d(d: &Bound<'_, PyDict>, key: &str, vals: Vec<f64>, k: usize) -> PyResult<()> {
    let n = vals.len() / k.max(1);
    let a = Array2::from_shape_vec((n, k), vals)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    d.set_item(key, a.into_pyarray(d.py()))
}

/// `vals` as a 1-D bool array under `key`.
pub fn put_bool(d: &Bound<'_, PyDict>, key: &str, vals: Vec<bool>) -> PyResult<()> {
    d.set_item(key, vals.into_pyarray(d.py()))
}

/// `vals` as a 1-D int64 array under `key`.
pub fn put_i64(d: &Bound<'_, PyDict>, key: &str, vals: Vec<i64>) -> PyResult<()> {
    d.set_item(key, vals.into_pyarray(d.py()))
}

/// The --v0 lists of a call: the speeds as the CLI's tokens (a double written so that it reads
/// back exactly), cut into lists of at most [`MAX_SPEEDS`] (the program's limit per list; the
/// bindings take more by parsing each list alone). `None` when the call has no speeds (--nd).
pub fn speed_lists(
    array: Option<PyReadonlyArray1<'_, f64>>,
    tokens: Option<Vec<String>>,
) -> Option<Vec<String>> {
    let tokens: Vec<String> = match (array, tokens) {
        (Some(a), _) => a.as_array().iter().map(|x| format!("{x:?}")).collect(),
        (None, Some(t)) => t,
        (None, None) => return None,
    };
    if tokens.is_empty() {
        // the CLI's message for an empty --v0
        return Some(vec![String::new()]);
    }
    Some(tokens.chunks(MAX_SPEEDS).map(|c| c.join(",")).collect())
}
