//! The Bouc–Wen–Hertz collision law (BWHCL, eq:BWHCL):
//!
//! ```text
//! ẋ = u
//! ż = A u − β |z|^(n−1) z |u| − γ |z|^n u
//! F = −α k |x|^(p−1) x − α_c k |z|^(p−1) z,        α_c = 1 − α
//! ```
//!
//! Input u (a relative velocity), internal state (x, z), output F (the contact force). Both
//! collision models are feedback interconnections of this law; their nondimensional forms are
//! the same law with A = 1, β = B, γ = Γ, α = κ, k = 1.

use crate::arith::{Exponent, Real, Scalar};

/// The parameters of the BWHCL. `alpha_c` is kept beside `alpha` so that 1 − α is computed once
/// (in the arithmetic of `R`, so it stays an enclosure for intervals); the exponents n and p
/// are prepared once ([`Exponent`]).
#[derive(Clone, Debug)]
pub struct BoucWenHertz<R: Real> {
    pub a: R,
    pub beta: R,
    pub gamma: R,
    pub n: Exponent<R>,
    pub p: Exponent<R>,
    pub alpha: R,
    pub alpha_c: R,
    pub k: R,
}

impl<R: Real> BoucWenHertz<R> {
    pub fn new(a: R, beta: R, gamma: R, n: R, p: R, alpha: R, k: R) -> Self {
        let alpha_c = R::one() - alpha.clone();
        Self {
            a,
            beta,
            gamma,
            n: Exponent::new(n),
            p: Exponent::new(p),
            alpha,
            alpha_c,
            k,
        }
    }

    /// ż = A u − β |z|^(n−1) z |u| − γ |z|^n u (eq:BWHCL, second line).
    #[inline(always)]
    pub fn hysteretic_rate<T: Scalar<R>>(&self, z: &T, u: &T) -> T {
        let (zs, za) = z.spow_apow_prepared(&self.n);
        u.scale(&self.a) - (zs * u.abs()).scale(&self.beta) - (za * u.clone()).scale(&self.gamma)
    }

    /// F = −α k |x|^(p−1) x − α_c k |z|^(p−1) z (eq:BWHCL, third line). With `k` = 1 this is the
    /// restoring part of F_P in both nondimensional models.
    #[inline]
    pub fn force<T: Scalar<R>>(&self, x: &T, z: &T) -> T {
        self.force_of(x.spow_prepared(&self.p), z.spow_prepared(&self.p))
    }

    /// The same force from the signed powers |x|^(p−1)x and |z|^(p−1)z, for callers that
    /// need the powers for something else too.
    #[inline(always)]
    pub fn force_of<T: Scalar<R>>(&self, xs: T, zs: T) -> T {
        -(xs.scale(&(self.alpha.clone() * self.k.clone()))
            + zs.scale(&(self.alpha_c.clone() * self.k.clone())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn law_at_known_points() {
        // A = 2, β = 0.5, γ = 0.25, n = 1, p = 1, α = 0.5, k = 4
        let law = BoucWenHertz::new(2.0, 0.5, 0.25, 1.0, 1.0, 0.5, 4.0);
        // z = 1, u = −1: ż = −2 − 0.5·1·1 − 0.25·1·(−1) = −2.25
        assert_eq!(law.hysteretic_rate(&1.0, &-1.0), -2.25);
        // F = −0.5·4·3 − 0.5·4·(−1) = −4
        assert_eq!(law.force(&3.0, &-1.0), -4.0);
        // p = 2: F = −α k |x| x − α_c k |z| z
        let law2 = BoucWenHertz::new(1.0, 0.0, 0.0, 1.0, 2.0, 0.25, 1.0);
        assert_eq!(law2.force(&-2.0, &1.0), -(0.25 * -4.0) - 0.75);
    }
}
