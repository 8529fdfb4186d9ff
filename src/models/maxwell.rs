//! The Bouc–Wen–Maxwell collision model, nondimensional (NDBWMCM, eq:BWMCM_nd,
//! eq:BWMCM_nd_output), states (R, Y, Z, W), outputs (X, V):
//!
//! ```text
//! Ṙ = κσ|Y|^(p−1)Y + κ_cσ|Z|^(p−1)Z
//! Ẏ = W
//! Ż = W − B|Z|^(n−1)Z|W| − Γ|Z|^n W
//! Ẇ = −Ṙ/σ − κpσ|Y|^(p−1)Ẏ − κ_c pσ|Z|^(p−1)Ż
//! X = R + Y,   V = Ṙ + Ẏ
//! R(0) = Y(0) = Z(0) = 0, W(0) = −1
//! ```
//!
//! The force is F_P = −κ|Y|^(p−1)Y − κ_c|Z|^(p−1)Z, so Ṙ = −σ F_P.

use super::bwhcl::BoucWenHertz;
use super::params::{ModelKind, NdParams};
use super::shc::half;
use super::{BoucWenModel, CollisionModel, distance_to_slope_line, equilibrium_slope};
use crate::arith::{Real, Scalar};

/// NDBWMCM with parameters P = (B, Γ, κ, σ, n, p).
#[derive(Clone, Debug)]
pub struct Maxwell<R: Real> {
    params: NdParams<R>,
    /// The BWHCL in nondimensional form: A = 1, β = B, γ = Γ, α = κ, k = 1.
    law: BoucWenHertz<R>,
    /// p − 1 = 0 (then the field is linear in Y and Z: |x|^0 = 1); p + 1, κpσ, κ_c pσ.
    linear: bool,
    p1: R,
    kps: R,
    kcps: R,
}

impl<R: Real> Maxwell<R> {
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
        let ps = params.p.clone() * params.sigma.clone();
        Self {
            linear: (params.p.clone() - R::one()).as_integer() == Some(0),
            p1: params.p.clone() + R::one(),
            kps: params.kappa.clone() * ps.clone(),
            kcps: law.alpha_c.clone() * ps,
            law,
            params,
        }
    }

    /// Ṙ = −σ F_P (first line of eq:BWMCM_nd).
    #[inline]
    fn r_rate<T: Scalar<R>>(&self, s: &[T; 4]) -> T {
        self.force(s).scale(&(-self.params.sigma.clone()))
    }

    /// (|x|^(p−1)x, |x|^(p−1)), the second `None` for p = 1 (the field is linear then and
    /// |x|^0 = 1 everywhere, 0 included).
    #[inline(always)]
    fn powers<T: Scalar<R>>(&self, x: &T) -> (T, Option<T>) {
        if self.linear {
            (x.clone(), None)
        } else {
            let (s, b) = x.spow_base_prepared(&self.law.p);
            (s, Some(b))
        }
    }

    /// The Maxwell model's Q = g₂ = V (sec:analysis_BWMCM).
    fn q<T: Scalar<R>>(&self, s: &[T; 4]) -> T {
        self.r_rate(s) + s[3].clone()
    }
}

impl<R: Real> CollisionModel<R, 4> for Maxwell<R> {
    const NAME: &'static str = "maxwell";
    const STATE_NAMES: [&'static str; 4] = ["R", "Y", "Z", "W"];

    fn initial_state(&self) -> [R; 4] {
        [R::zero(), R::zero(), R::zero(), -R::one()]
    }

    /// f(R, Y, Z, W) of eq:BWMCM_nd.
    #[inline(always)]
    fn field<T: Scalar<R>>(&self, s: &[T; 4]) -> [T; 4] {
        let [_, y, z, w] = s;
        let ((ys, yb), (zs, zb)) = (self.powers(y), self.powers(z));
        // Ṙ = −σ F_P, with F_P from the same powers; −Ṙ/σ = F_P is taken as F_P itself (the
        // same value; for an interval σ, or σ carried as a variable over a range, σ·(1/σ)
        // would widen every evaluation by σ's relative width)
        let fp = self.law.force_of(ys, zs);
        let dr = fp.scale(&(-self.params.sigma.clone()));
        let dz = self.law.hysteretic_rate(z, w);
        let mut dw = fp;
        match (yb, zb) {
            (Some(yb), Some(zb)) => {
                dw = dw - (yb * w.clone()).scale(&self.kps) - (zb * dz.clone()).scale(&self.kcps);
            }
            _ => {
                dw = dw - w.scale(&self.kps) - dz.scale(&self.kcps);
            }
        }
        [dr, w.clone(), dz, dw]
    }

    /// F_P(R, Y, Z, W) = −κ|Y|^(p−1)Y − κ_c|Z|^(p−1)Z.
    #[inline]
    fn force<T: Scalar<R>>(&self, s: &[T; 4]) -> T {
        self.law.force(&s[1], &s[2])
    }

    /// X = R + Y (eq:BWMCM_nd_output).
    fn position<T: Scalar<R>>(&self, s: &[T; 4]) -> T {
        s[0].clone() + s[1].clone()
    }

    /// V = Ṙ + Ẏ (eq:BWMCM_nd_output).
    fn velocity<T: Scalar<R>>(&self, s: &[T; 4]) -> T {
        self.q(s)
    }
}

impl<R: Real> BoucWenModel<R, 4> for Maxwell<R> {
    const KIND: ModelKind = ModelKind::Maxwell;

    fn params(&self) -> &NdParams<R> {
        &self.params
    }

    /// 𝒱 = (R + σQ)² + Q²/2 + κ/(p+1)|Y|^(p+1) + κ_c/(p+1)|Z|^(p+1) (sec:analysis_BWMCM).
    fn lyapunov<T: Scalar<R>>(&self, s: &[T; 4]) -> T {
        let [r, y, z, _] = s;
        let q = self.q(s);
        let a = r.clone() + q.scale(&self.params.sigma);
        let k = self.params.kappa.clone() / self.p1.clone();
        let kc = self.law.alpha_c.clone() / self.p1.clone();
        a.clone() * a
            + (q.clone() * q).scale(&half())
            + y.apow(&self.p1).scale(&k)
            + z.apow(&self.p1).scale(&kc)
    }

    /// 𝒱̇ = −σh² − κ_c|Z|^(p+n−1)(B|Z||W| + ΓZW), h = κ|Y|^(p−1)Y + κ_c|Z|^(p−1)Z.
    fn lyapunov_rate<T: Scalar<R>>(&self, s: &[T; 4]) -> T {
        let [_, _, z, w] = s;
        let pr = &self.params;
        let h = -self.force(s);
        let q = pr.p.clone() + pr.n.clone() - R::one();
        let hyst = (z.abs() * w.abs()).scale(&pr.b) + (z.clone() * w.clone()).scale(&pr.gamma);
        -(h.clone() * h).scale(&pr.sigma) - (z.apow(&q) * hyst).scale(&self.law.alpha_c)
    }

    /// Distance to 𝓔 = {(R, Y, −(κ/κ_c)^(1/p) Y, 0)} (thm:BWMCM_eq); R is free.
    fn equilibrium_distance(&self, s: &[R; 4]) -> R {
        distance_to_slope_line(&s[1], &s[2], &s[3], &equilibrium_slope(&self.params))
    }

    fn equilibrium_point(&self, free: [R; 2]) -> [R; 4] {
        let [r, y] = free;
        [
            r,
            y.clone(),
            -(equilibrium_slope(&self.params) * y),
            R::zero(),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model() -> Maxwell<f64> {
        Maxwell::new(
            NdParams::parse(ModelKind::Maxwell, "0.44,-0.418,0.113,0.00785,1.27,3.14").unwrap(),
        )
    }

    #[test]
    #[allow(clippy::approx_constant)] // 3.14 is the paper's p (Table 1), not π
    fn field_matches_the_paper_written_out() {
        let m = model();
        let (b, g, k, s, n, p) = (0.44, -0.418, 0.113, 0.00785, 1.27, 3.14_f64);
        let (r, y, z, w) = (0.1_f64, -0.4_f64, 0.3_f64, -0.7_f64);
        let sp = |x: f64, q: f64| x.abs().powf(q - 1.0) * x;
        let dr = k * s * sp(y, p) + (1.0 - k) * s * sp(z, p);
        let dz = w - b * sp(z, n) * w.abs() - g * z.abs().powf(n) * w;
        let dw = -dr / s
            - k * p * s * y.abs().powf(p - 1.0) * w
            - (1.0 - k) * p * s * z.abs().powf(p - 1.0) * dz;
        let f = m.field(&[r, y, z, w]);
        for (a, e) in f.iter().zip([dr, w, dz, dw]) {
            assert!((a - e).abs() < 1e-15 * (1.0 + e.abs()), "{a} vs {e}");
        }
        assert!((m.velocity(&[r, y, z, w]) - (dr + w)).abs() < 1e-16);
        assert_eq!(m.position(&[r, y, z, w]), r + y);
    }

    #[test]
    fn p_equal_one_is_linear() {
        let m =
            Maxwell::new(NdParams::<f64>::parse(ModelKind::Maxwell, "0.5,0.1,0.5,2,1,1").unwrap());
        let f = m.field(&[0.0, 0.0, 0.0, -1.0]);
        // Ṙ = 0, Ẏ = −1, Ż = −1, Ẇ = −κσ·(−1) − κ_cσ·(−1) = σ = 2
        assert_eq!(f, [0.0, -1.0, -1.0, 2.0]);
    }

    #[test]
    fn equilibria_are_fixed_points() {
        let m = model();
        for (r, y) in [(0.0, 0.0), (1.0, -0.5), (-3.0, 2.0)] {
            let e = m.equilibrium_point([r, y]);
            assert!(
                m.field(&e).iter().all(|c| f64::abs(*c) < 1e-13),
                "{e:?} {:?}",
                m.field(&e)
            );
            assert!(m.equilibrium_distance(&e) < 1e-14);
        }
    }
}
