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
//! (the closed form the tests check the engines against). For β ≥ 1 (c̃ ≤ 1/2) D never returns
//! to 0: D = −T e^(−T) at β = 1, D = −(e^(r₊T) − e^(r₋T))/(r₊ − r₋) with r± = −β ± √(β² − 1) for
//! β > 1, both < 0 for every T > 0; so F = −D > 0 for T > 0, F(0) = 0 with V(0) = −1 < 0, and the
//! law never separates (T_s = +∞, e = 0 by the paper's convention:
//! [`CollisionModel::never_separates`]). F then decays like e^(r₊T) to the rounding level (≈ 1e-15
//! at T ≈ 35 for c̃ = 0.4), where neither engine could tell its sign.

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

    /// c̃ ≤ 1/2 for every value of c̃ (β = 1/(2c̃) ≥ 1): the closed form of the module doc.
    fn never_separates(&self) -> Option<&'static str> {
        (self.c.hi() <= 0.5)
            .then_some("c̃ ≤ 1/2, so the spring's deflection X − Y stays < 0 for every T > 0")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engines::taylor::{TaylorOptions, integrate_system, model_tape};
    use inari::{Interval, interval};

    /// The closed form is claimed for an enclosure only when every value of c̃ is ≤ 1/2 (the
    /// upper end; β = 1 at c̃ = 1/2 itself, D = −T e^(−T)).
    #[test]
    fn never_separates_only_where_every_value_is_at_most_a_half() {
        let f = |c: f64| LinearMaxwell::new(c).unwrap().never_separates().is_some();
        assert!(f(0.4) && f(0.5) && f(1e-300));
        assert!(!f(0.5f64.next_up()) && !f(0.6));
        let i = |lo: f64, hi: f64| {
            LinearMaxwell::new(interval!(lo, hi).unwrap())
                .unwrap()
                .never_separates()
                .is_some()
        };
        assert!(i(0.5, 0.5) && i(0.4, 0.5));
        assert!(!i(0.4, 0.6) && !i(0.5, 0.5f64.next_up()));
    }

    /// The engine's own verdict on [0, 15] without the closed form (the system the engine runs
    /// for the model, `model_tape`, but run through `integrate_system`, which does not ask the
    /// model): the condition proved to fail for c̃ ≤ 1/2 — and, as a negative control, the
    /// separation at T_s = π/ω found for c̃ = 0.55 (β = 1/1.1, ω = √(1 − β²)).
    #[test]
    fn the_engine_agrees_with_the_closed_form_where_it_can_tell() {
        let run = |c: &str| {
            let m = LinearMaxwell::new(Interval::parse_decimal(c).unwrap()).unwrap();
            let tape = model_tape(&m, true);
            let opts = TaylorOptions {
                horizon: 15.0,
                ..TaylorOptions::default()
            };
            (
                m.never_separates(),
                integrate_system(&tape, m.initial_state(), 3, &opts),
            )
        };
        for c in ["0.25", "0.4", "0.5"] {
            let (never, r) = run(c);
            assert!(never.is_some(), "c̃ = {c}");
            let e = r.err().unwrap_or_else(|| panic!("c̃ = {c} separated"));
            assert!(e.no_separation(), "c̃ = {c}: {}", e.reason);
            // the engine's proof covers [0, 15] only, not every time
            assert!(e.never_separates().is_none());
        }
        let (never, r) = run("0.55");
        assert!(never.is_none());
        let (_, ev) = r.expect("c̃ = 0.55 separates");
        let beta = 1.0 / 1.1_f64;
        let ts = std::f64::consts::PI / (1.0 - beta * beta).sqrt();
        assert!(
            (ev.ts.inf() - 1e-13..=ev.ts.sup() + 1e-13).contains(&ts),
            "{:?}",
            ev.ts
        );
    }
}
