//! Boxes of a step: the span [0, h], inclusion with the parameter components kept, guesses of
//! a-priori boxes (inflated, parameters kept) — shared by the Taylor and low-order steps
//! ([`super::step`]) and the step across integrable singular terms ([`super::integrable`]).

use crate::arith::Enclosure;

/// [0, h].
pub(super) fn span<I: Enclosure>(h: f64) -> I {
    I::from_bounds(0.0, h).expect("a step length")
}

/// a ⊆ int b, except for the parameter components (ṗ = 0 exactly: a ⊆ b).
pub(super) fn subset<const N: usize, I: Enclosure>(
    a: &[I; N],
    b: &[I; N],
    params: &[usize],
) -> bool {
    (0..N).all(|i| {
        if params.contains(&i) {
            a[i].subset(&b[i])
        } else {
            a[i].interior(&b[i])
        }
    })
}

/// A guess of an a-priori box with the parameter components kept at their values in x (a
/// parameter is constant: inflating it would leave its admissible range, e.g. n < 1).
pub(super) fn keep_params<const N: usize, I: Enclosure>(
    mut y: [I; N],
    x: &[I; N],
    params: &[usize],
) -> [I; N] {
    for &i in params {
        y[i] = x[i].clone();
    }
    y
}

/// Inflates a box: mid ± (factor·rad + abs).
pub(super) fn inflate<const N: usize, I: Enclosure>(y: &[I; N], factor: f64, abs: f64) -> [I; N] {
    std::array::from_fn(|i| {
        let r = y[i].rad_f64() * factor + abs + y[i].mag_f64() * (1e-15 * eps_scale::<I>());
        // an empty or unbounded component (r NaN or ∞) stays unbounded: the test then fails
        match I::from_bounds(-r, r) {
            Some(b) => y[i].clone() + b,
            None => I::entire(),
        }
    })
}

/// The type's machine epsilon relative to f64's (exactly 1 for inari intervals): the relative
/// floors of the f64 engine (a guess's inflation, the smallest tolerance) scaled to the
/// precision.
#[inline]
pub fn eps_scale<I: Enclosure>() -> f64 {
    I::epsilon() / f64::EPSILON
}

pub(super) fn hull<const N: usize, I: Enclosure>(a: &[I; N], b: &[I; N]) -> [I; N] {
    std::array::from_fn(|i| a[i].hull(&b[i]))
}
