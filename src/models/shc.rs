//! The Bouc–Wen–Simon–Hunt–Crossley collision model, nondimensional (NDBWSHCCM,
//! eq:BWSHCCM_nd), states (X, Z, V):
//!
//! ```text
//! Ẋ = V
//! Ż = V − B |Z|^(n−1) Z |V| − Γ |Z|^n V
//! V̇ = −κ |X|^(p−1) X − κ_c |Z|^(p−1) Z − σ |X|^p V  =  F_P(X, Z, V)
//! X(0) = 0, Z(0) = 0, V(0) = −1
//! ```

use super::bwhcl::BoucWenHertz;
use super::params::{ModelKind, NdParams};
use super::{BoucWenModel, CollisionModel, distance_to_slope_line, equilibrium_slope};
use crate::arith::{Real, Scalar};

/// NDBWSHCCM with parameters P = (B, Γ, κ, σ, n, p).
#[derive(Clone, Debug)]
pub struct Shc<R: Real> {
    params: NdParams<R>,
    /// The BWHCL in nondimensional form: A = 1, β = B, γ = Γ, α = κ, k = 1.
    law: BoucWenHertz<R>,
    /// p + 1, for 𝒱.
    p1: R,
}

impl<R: Real> Shc<R> {
    /// The model for an already validated parameter set.
    pub fn new(params: NdParams<R>) -> Self {
        let law = BoucWenHertz::new(
            R::one(),
            params.b.clone(),
            params.gamma.clone(),
            params.n.clone(),
            params.p.clone(),
            params.kappa.clone(),
            R::one(),
        );
        let p1 = params.p.clone() + R::one();
        Self { params, law, p1 }
    }
}

impl<R: Real> CollisionModel<R, 3> for Shc<R> {
    const NAME: &'static str = "shc";
    const STATE_NAMES: [&'static str; 3] = ["X", "Z", "V"];

    fn initial_state(&self) -> [R; 3] {
        [R::zero(), R::zero(), -R::one()]
    }

    /// f(X, Z, V) of eq:BWSHCCM_nd.
    #[inline(always)]
    fn field<T: Scalar<R>>(&self, s: &[T; 3]) -> [T; 3] {
        let [_, z, v] = s;
        [v.clone(), self.law.hysteretic_rate(z, v), self.force(s)]
    }

    /// F_P(X, Z, V) = −κ|X|^(p−1)X − κ_c|Z|^(p−1)Z − σ|X|^p V.
    #[inline(always)]
    fn force<T: Scalar<R>>(&self, s: &[T; 3]) -> T {
        let [x, z, v] = s;
        let (xs, xa) = x.spow_apow_prepared(&self.law.p);
        self.law.force_of(xs, z.spow_prepared(&self.law.p))
            - (xa * v.clone()).scale(&self.params.sigma)
    }

    fn position<T: Scalar<R>>(&self, s: &[T; 3]) -> T {
        s[0].clone()
    }

    fn velocity<T: Scalar<R>>(&self, s: &[T; 3]) -> T {
        s[2].clone()
    }
}

impl<R: Real> BoucWenModel<R, 3> for Shc<R> {
    const KIND: ModelKind = ModelKind::Shc;

    fn params(&self) -> &NdParams<R> {
        &self.params
    }

    /// 𝒱 = κ/(p+1)|X|^(p+1) + κ_c/(p+1)|Z|^(p+1) + V²/2 (sec:analysis_BWSHCCM).
    fn lyapunov<T: Scalar<R>>(&self, s: &[T; 3]) -> T {
        let [x, z, v] = s;
        let k = self.params.kappa.clone() / self.p1.clone();
        let kc = self.law.alpha_c.clone() / self.p1.clone();
        x.apow(&self.p1).scale(&k)
            + z.apow(&self.p1).scale(&kc)
            + (v.clone() * v.clone()).scale(&half())
    }

    /// 𝒱̇ = −σ|X|^p V² − κ_c |Z|^(p+n−1) (B|Z||V| + Γ Z V) (sec:analysis_BWSHCCM).
    fn lyapunov_rate<T: Scalar<R>>(&self, s: &[T; 3]) -> T {
        let [x, z, v] = s;
        let pr = &self.params;
        let q = pr.p.clone() + pr.n.clone() - R::one();
        let hyst = (z.abs() * v.abs()).scale(&pr.b) + (z.clone() * v.clone()).scale(&pr.gamma);
        -(x.apow(&pr.p) * v.clone() * v.clone()).scale(&pr.sigma)
            - (z.apow(&q) * hyst).scale(&self.law.alpha_c)
    }

    /// Distance to 𝓔 = {(X, −(κ/κ_c)^(1/p) X, 0)} (thm:BWSHCCM_eq).
    fn equilibrium_distance(&self, s: &[R; 3]) -> R {
        distance_to_slope_line(&s[0], &s[1], &s[2], &equilibrium_slope(&self.params))
    }

    fn equilibrium_point(&self, free: [R; 2]) -> [R; 3] {
        let x = free[0].clone();
        [x.clone(), -(equilibrium_slope(&self.params) * x), R::zero()]
    }
}

pub(crate) fn half<R: Real>() -> R {
    R::one() / R::from_int(2)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model() -> Shc<f64> {
        Shc::new(NdParams::parse(ModelKind::Shc, "1.43,-1.42,0.632,0.00715,1.31,1.27").unwrap())
    }

    #[test]
    fn field_at_a_hand_computed_point() {
        let m = model();
        let (x, z, v) = (0.3_f64, -0.2_f64, 0.5_f64);
        let f = m.field(&[x, z, v]);
        let zn = z.abs().powf(1.31);
        assert!((f[0] - v).abs() < 1e-16);
        let dz = v - 1.43 * (zn / z.abs() * z) * v.abs() + 1.42 * zn * v;
        assert!((f[1] - dz).abs() < 1e-15);
        let dv =
            -0.632 * x.powf(1.27) - 0.368 * (-(0.2_f64.powf(1.27))) - 0.00715 * x.powf(1.27) * v;
        assert!((f[2] - dv).abs() < 1e-15, "{} vs {dv}", f[2]);
    }

    #[test]
    fn equilibria_are_fixed_points() {
        let m = model();
        for x in [-2.0, -0.1, 0.0, 0.7, 3.0] {
            let e = m.equilibrium_point([x, 0.0]);
            assert!(m.field(&e).iter().all(|c| f64::abs(*c) < 1e-14), "{e:?}");
            assert!(m.equilibrium_distance(&e) < 1e-14);
        }
        assert!((m.equilibrium_distance(&[0.0, 0.0, 2.0]) - 2.0).abs() < 1e-15);
    }
}
