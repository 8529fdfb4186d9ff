//! A smooth bijection from an unconstrained space onto the admissible set 𝓟, so that an
//! unconstrained optimizer (Nelder–Mead) searches inside 𝓟 and never needs a penalty or NaN.
//!
//! ```text
//! B = exp(u1)                  B ∈ (0, ∞)
//! Γ = B tanh(u2)               Γ ∈ (−B, B)
//! κ = 1/(1 + exp(−u3))         κ ∈ (0, 1)
//! σ = exp(u4)                  σ ∈ (0, ∞)
//! n = 1 + exp(u5)              n ∈ (1, ∞)
//! p = 1 + exp(u6)  (shc)       p ∈ (1, ∞)
//! p = 2 + exp(u6)  (maxwell)   p ∈ (2, ∞)
//! ```
//!
//! Each coordinate map is a smooth increasing bijection of ℝ onto an open interval, so the
//! product is a smooth bijection ℝ⁶ → 𝓟° (the interior of 𝓟 in the (n, p) directions; B, Γ,
//! κ, σ are already open in 𝓟). The boundary values n = 1 and p = 1 (shc) or p = 2 (maxwell)
//! are limits u → −∞: in floating point they are reached to within exp(−30) ≈ 9e−14, which
//! no CoR data can tell apart. The Maxwell set is p ∈ [2, ∞) ∪ {1}: the isolated point p = 1
//! cannot be the image of a connected parameter space together with [2, ∞), so it is a separate
//! search ([`Reparam::p1`], the CLI's `--p1`): p is fixed to 1 and the map is ℝ⁵ → 𝓟 ∩ {p = 1}
//! through (u1, …, u5). `--p1` may be used with the shc model as well (p = 1 is its boundary).
//!
//! Floating point: for |u_i| beyond [`LIMITS`] the mathematical map is within about 1e−13 of
//! the boundary of 𝓟 (or overflows), and the f64 map saturates there (the input is clamped), so
//! the image of every finite u validates against 𝓟 ([`crate::models::NdParams::new`]).

use crate::models::{ModelKind, NdParams, ParamError};

/// The box [lo, hi] per coordinate outside which the f64 map saturates.
pub const LIMITS: [(f64, f64); 6] = [
    (-30.0, 30.0),
    (-18.0, 18.0),
    (-36.0, 36.0),
    (-30.0, 30.0),
    (-30.0, 6.0),
    (-30.0, 6.0),
];

/// The reparametrization of one model's 𝓟 (or of its p = 1 slice).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reparam {
    pub kind: ModelKind,
    /// Fix p = 1 (5 free coordinates).
    pub p1: bool,
}

fn logistic(x: f64) -> f64 {
    if x >= 0.0 {
        1.0 / (1.0 + (-x).exp())
    } else {
        let e = x.exp();
        e / (1.0 + e)
    }
}

impl Reparam {
    pub fn new(kind: ModelKind, p1: bool) -> Self {
        Self { kind, p1 }
    }

    /// The number of free coordinates: 6, or 5 with p = 1 fixed.
    pub fn dim(&self) -> usize {
        if self.p1 { 5 } else { 6 }
    }

    /// The lower end of p's open interval: 1 (shc) or 2 (maxwell).
    fn p_floor(&self) -> f64 {
        match self.kind {
            ModelKind::Shc => 1.0,
            ModelKind::Maxwell => 2.0,
        }
    }

    /// u ↦ P* ∈ 𝓟. Fails only for a wrong length or a NaN coordinate; every finite u gives a
    /// set that validates against 𝓟.
    pub fn to_params(&self, u: &[f64]) -> Result<NdParams<f64>, ParamError> {
        if u.len() != self.dim() {
            return Err(ParamError(format!(
                "{} coordinates given, the reparametrization has {}",
                u.len(),
                self.dim()
            )));
        }
        if u.iter().any(|x| x.is_nan()) {
            return Err(ParamError(format!("a coordinate is NaN: {u:?}")));
        }
        let c = |i: usize| u[i].clamp(LIMITS[i].0, LIMITS[i].1);
        let b = c(0).exp();
        let gamma = b * c(1).tanh();
        let kappa = logistic(c(2));
        let sigma = c(3).exp();
        let n = 1.0 + c(4).exp();
        let p = if self.p1 {
            1.0
        } else {
            self.p_floor() + c(5).exp()
        };
        NdParams::new(self.kind, b, gamma, kappa, sigma, n, p)
    }

    /// P* ↦ u, the inverse on 𝓟 (clamped to [`LIMITS`]: n = 1 or p at its floor map to the
    /// lower limit). Fails for a set outside 𝓟, and with `p1` for p ≠ 1 (or without it, for
    /// the Maxwell p = 1).
    pub fn from_params(&self, p: &NdParams<f64>) -> Result<Vec<f64>, ParamError> {
        p.validate(self.kind, crate::models::Admissibility::Open)?;
        if self.p1 && p.p != 1.0 {
            return Err(ParamError(format!(
                "p = {} but the p = 1 slice was asked",
                p.p
            )));
        }
        if !self.p1 && p.p < self.p_floor() {
            return Err(ParamError(format!(
                "p = {} is below {} (the maxwell p = 1 is a separate search: --p1)",
                p.p,
                self.p_floor()
            )));
        }
        let mut u = vec![
            p.b.ln(),
            (p.gamma / p.b).atanh(),
            (p.kappa / (1.0 - p.kappa)).ln(),
            p.sigma.ln(),
            (p.n - 1.0).ln(),
        ];
        if !self.p1 {
            u.push((p.p - self.p_floor()).ln());
        }
        for (i, x) in u.iter_mut().enumerate() {
            *x = x.clamp(LIMITS[i].0, LIMITS[i].1);
        }
        Ok(u)
    }
}
