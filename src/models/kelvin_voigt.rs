//! The linear Kelvin–Voigt collision law (the paper's review section): a linear spring and a
//! linear dashpot in parallel,
//!
//! ```text
//! F = k δ + c δ̇.
//! ```
//!
//! With δ = L·X, t = T·√(m/k), L = v0·√(m/k) and the damping ratio ζ = c/(2√(mk)):
//!
//! ```text
//! X′ = V,   V′ = F = −X − 2ζV,   X(0) = 0, V(0) = −1
//! ```
//!
//! (F starts at 2ζ > 0: the dashpot's force jumps at the impact, the law's known flaw). The
//! separation is the crate's rule T_s = inf{T ≥ 0 : F ≤ 0 ∧ V ≥ 0}: the force vanishes before
//! the indentation does. For ζ < 1, with ω = √(1 − ζ²) and φ = atan2(2ζω, 1 − 2ζ²) ∈ (0, π),
//! X = −e^(−ζT) sin(ωT)/ω gives F = e^(−ζT) sin(ωT + φ)/ω, so
//!
//! ```text
//! T_s = (π − φ)/ω,   e = V(T_s) = e^(−ζ T_s)
//! ```
//!
//! (the closed form the tests check the engines against).

use super::ForceLaw;
use crate::arith::{Real, Scalar};

/// The linear Kelvin–Voigt law, nondimensional, with damping ratio ζ ≥ 0.
#[derive(Clone, Debug)]
pub struct KelvinVoigt<R: Real> {
    pub zeta: R,
    two_zeta: R,
}

impl<R: Real> KelvinVoigt<R> {
    /// The law with damping ratio ζ ≥ 0 (every value of an enclosure).
    pub fn new(zeta: R) -> Result<Self, String> {
        if !(zeta.lo() >= 0.0 && zeta.hi().is_finite()) {
            return Err(format!(
                "the damping ratio ζ must be ≥ 0 and finite (got {})",
                crate::models::params::show(&zeta)
            ));
        }
        let two_zeta = zeta.mul_int(2);
        Ok(Self { zeta, two_zeta })
    }
}

impl<R: Real> ForceLaw<R> for KelvinVoigt<R> {
    const NAME: &'static str = "kelvin-voigt";

    /// F = −X − 2ζV.
    fn force_xv<T: Scalar<R>>(&self, x: &T, v: &T) -> T {
        -x.clone() - v.scale(&self.two_zeta)
    }
}
