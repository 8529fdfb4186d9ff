//! The linear Maxwell collision law (the paper's review section): a linear spring and a linear
//! dashpot in series,
//!
//! ```text
//! F = k δ₁ = c δ̇₂,   δ = δ₁ + δ₂.
//! ```
//!
//! With δ = L·X, t = T·√(m/k), L = v0·√(m/k), the dashpot's displacement δ₂ = L·Y and
//! c̃ = c/√(mk):
//!
//! ```text
//! X′ = V,   Y′ = (X − Y)/c̃,   V′ = F = −(X − Y),   X(0) = Y(0) = 0, V(0) = −1
//! ```
//!
//! The force starts at 0 (no jump, unlike Kelvin–Voigt's). Separation by the crate's rule
//! T_s = inf{T ≥ 0 : F ≤ 0 ∧ V ≥ 0}. The spring's deflection D = X − Y solves
//! D″ + 2βD′ + D = 0 with β = 1/(2c̃), D(0) = 0, D′(0) = −1, so for β < 1 (c̃ > 1/2), with
//! ω = √(1 − β²), D = −e^(−βT) sin(ωT)/ω: F = −D ≤ 0 again first at T = π/ω, where
//! V = D′ + D/c̃ = e^(−βπ/ω) > 0:
//!
//! ```text
//! T_s = π/ω,   e = e^(−βπ/ω)
//! ```
//!
//! (the closed form the tests check the engines against).

use super::CollisionModel;
use crate::arith::{Real, Scalar};

/// The linear Maxwell law, nondimensional, with dashpot c̃ = c/√(mk) > 0.
#[derive(Clone, Debug)]
pub struct LinearMaxwell<R: Real> {
    pub c: R,
    inv_c: R,
}

impl<R: Real> LinearMaxwell<R> {
    /// The law with c̃ > 0 (every value of an enclosure).
    pub fn new(c: R) -> Result<Self, String> {
        if !(c.lo() > 0.0 && c.hi().is_finite()) {
            return Err(format!(
                "the dashpot c̃ must be > 0 and finite (got {})",
                super::params::show(&c)
            ));
        }
        let inv_c = R::one() / c.clone();
        Ok(Self { c, inv_c })
    }
}

impl<R: Real> CollisionModel<R, 3> for LinearMaxwell<R> {
    const NAME: &'static str = "linear-maxwell";
    const STATE_NAMES: [&'static str; 3] = ["X", "Y", "V"];

    fn initial_state(&self) -> [R; 3] {
        [R::zero(), R::zero(), -R::one()]
    }

    fn field<T: Scalar<R>>(&self, s: &[T; 3]) -> [T; 3] {
        let d = s[0].clone() - s[1].clone();
        [s[2].clone(), d.scale(&self.inv_c), -d]
    }

    /// F = −(X − Y).
    fn force<T: Scalar<R>>(&self, s: &[T; 3]) -> T {
        s[1].clone() - s[0].clone()
    }

    fn position<T: Scalar<R>>(&self, s: &[T; 3]) -> T {
        s[0].clone()
    }

    fn velocity<T: Scalar<R>>(&self, s: &[T; 3]) -> T {
        s[2].clone()
    }
}
