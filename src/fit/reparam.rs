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

use super::space::{NAMES, Slot, Space};
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

/// The reparametrization of a [`Space`] (`--fix`, `--bounds`): one coordinate per free
/// parameter, in the order of P*. A fixed parameter is held; a free one without bounds maps as
/// in [`Reparam`]; a bounded one through the logistic onto its bounds:
///
/// ```text
/// x = lo + (hi − lo) / (1 + exp(−u))                 x ∈ (lo, hi)
/// Γ = lo' + (hi' − lo') / (1 + exp(−u)),  lo' = max(lo, −B), hi' = min(hi, B)   (given B)
/// ```
///
/// and where Γ_b is fixed to g, B_b's interval starts at |g| instead of 0 (B = |g| + exp(u), or
/// a bounded B on [max(lo, |g|), hi]), so that every finite u lies in 𝓟. A bounded coordinate
/// is clamped to |u| ≤ 30 (the ends are reached to within 1e−13 of the range). A box whose Γ
/// range is empty for the given B (lo' ≥ hi') has no image there: `Err`.
#[derive(Clone, Debug, PartialEq)]
pub struct SpaceMap {
    pub space: Space,
}

/// |u| for a bounded coordinate.
const BOUNDED_LIMIT: f64 = 30.0;

fn logit(t: f64) -> f64 {
    (t / (1.0 - t)).ln()
}

impl SpaceMap {
    pub fn new(space: Space) -> Self {
        Self { space }
    }

    /// The unbounded search of [`Reparam`] (p fixed to 1 with `p1`).
    pub fn unbounded(kind: ModelKind, p1: bool) -> Self {
        let mut space = Space::unbounded(kind);
        if p1 {
            space.slots[5] = Slot::Fixed(1.0);
        }
        Self { space }
    }

    pub fn kind(&self) -> ModelKind {
        self.space.kind
    }

    /// The number of free coordinates k.
    pub fn dim(&self) -> usize {
        self.space.free().len()
    }

    /// The finite bounds of parameter `i`, if it is free and bounded.
    pub fn bounds(&self, i: usize) -> Option<(f64, f64)> {
        match self.space.slots[i] {
            Slot::Free { lo, hi } if lo.is_finite() && hi.is_finite() => Some((lo, hi)),
            _ => None,
        }
    }

    fn p_floor(&self) -> f64 {
        match self.kind() {
            ModelKind::Shc => 1.0,
            ModelKind::Maxwell => 2.0,
        }
    }

    /// B_b's lower end: |g| where Γ_b is fixed to g, else 0.
    fn b_floor(&self) -> f64 {
        match self.space.slots[1] {
            Slot::Fixed(g) => g.abs(),
            Slot::Free { .. } => 0.0,
        }
    }

    /// The interval a bounded parameter `i` maps onto (Γ_b's given B).
    fn range(&self, i: usize, b: f64) -> Option<(f64, f64)> {
        let (lo, hi) = self.bounds(i)?;
        Some(match i {
            0 => (lo.max(self.b_floor()), hi),
            1 => (lo.max(-b), hi.min(b)),
            _ => (lo, hi),
        })
    }

    /// u ↦ P*: every finite u of length k gives a set in 𝓟 and in the space's box (or `Err`
    /// where the box has no point for this B, or for a wrong length or a NaN).
    pub fn to_params(&self, u: &[f64]) -> Result<NdParams<f64>, ParamError> {
        let free = self.space.free();
        if u.len() != free.len() {
            return Err(ParamError(format!(
                "{} coordinates given, the space has {} free parameters",
                u.len(),
                free.len()
            )));
        }
        if u.iter().any(|x| x.is_nan()) {
            return Err(ParamError(format!("a coordinate is NaN: {u:?}")));
        }
        let mut x = [0.0; 6];
        let mut k = 0;
        for i in 0..6 {
            x[i] = match self.space.slots[i] {
                Slot::Fixed(v) => v,
                Slot::Free { .. } => {
                    let ui = u[k];
                    k += 1;
                    match self.range(i, x[0]) {
                        Some((lo, hi)) => {
                            if lo >= hi {
                                return Err(ParamError(format!(
                                    "{} has no admissible value in [{lo}, {hi}] for B_b = {}",
                                    NAMES[i], x[0]
                                )));
                            }
                            lo + (hi - lo) * logistic(ui.clamp(-BOUNDED_LIMIT, BOUNDED_LIMIT))
                        }
                        None => {
                            let c = ui.clamp(LIMITS[i].0, LIMITS[i].1);
                            match i {
                                0 => self.b_floor() + c.exp(),
                                1 => x[0] * c.tanh(),
                                2 => logistic(c),
                                3 => c.exp(),
                                4 => 1.0 + c.exp(),
                                _ => self.p_floor() + c.exp(),
                            }
                        }
                    }
                }
            };
        }
        NdParams::new(self.kind(), x[0], x[1], x[2], x[3], x[4], x[5])
    }

    /// P* ↦ u, the inverse on the space (clamped like [`Reparam::from_params`]). Fails for a
    /// set outside 𝓟, a fixed parameter not at its value, or a bounded one outside its bounds.
    pub fn from_params(&self, p: &NdParams<f64>) -> Result<Vec<f64>, ParamError> {
        p.validate(self.kind(), crate::models::Admissibility::Open)?;
        let x = p.as_array();
        let mut u = Vec::new();
        for i in 0..6 {
            match self.space.slots[i] {
                Slot::Fixed(v) => {
                    if x[i] != v {
                        return Err(ParamError(format!(
                            "{} = {} but it is fixed to {v}",
                            NAMES[i], x[i]
                        )));
                    }
                }
                Slot::Free { .. } => u.push(match self.range(i, x[0]) {
                    Some((lo, hi)) => {
                        if !(x[i] >= lo && x[i] <= hi) {
                            return Err(ParamError(format!(
                                "{} = {} is outside its bounds [{lo}, {hi}]",
                                NAMES[i], x[i]
                            )));
                        }
                        logit((x[i] - lo) / (hi - lo)).clamp(-BOUNDED_LIMIT, BOUNDED_LIMIT)
                    }
                    None => {
                        let v = match i {
                            0 => (x[0] - self.b_floor()).ln(),
                            1 => (x[1] / x[0]).atanh(),
                            2 => logit(x[2]),
                            3 => x[3].ln(),
                            4 => (x[4] - 1.0).ln(),
                            _ => {
                                if x[5] < self.p_floor() {
                                    return Err(ParamError(format!(
                                        "p = {} is below {} (the maxwell p = 1 is a separate \
                                         search: --p1)",
                                        x[5],
                                        self.p_floor()
                                    )));
                                }
                                (x[5] - self.p_floor()).ln()
                            }
                        };
                        if v.is_nan() {
                            return Err(ParamError(format!(
                                "{} = {} has no coordinate",
                                NAMES[i], x[i]
                            )));
                        }
                        v.clamp(LIMITS[i].0, LIMITS[i].1)
                    }
                }),
            }
        }
        Ok(u)
    }

    /// The names of the bounded free parameters whose value lies within `rel` (relative to the
    /// bound range) of a bound: "at bound".
    pub fn at_bounds(&self, p: &NdParams<f64>, rel: f64) -> Vec<&'static str> {
        let x = p.as_array();
        (0..6)
            .filter(|&i| {
                self.bounds(i).is_some_and(|(lo, hi)| {
                    let tol = rel * (hi - lo);
                    x[i] - lo <= tol || hi - x[i] <= tol
                })
            })
            .map(|i| NAMES[i])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::space::parse_bounds;

    fn free(_: usize) -> Result<Slot, String> {
        Ok(Slot::Free {
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
        })
    }

    #[test]
    fn unbounded_space_is_the_old_map() {
        for p1 in [false, true] {
            let old = Reparam::new(ModelKind::Shc, p1);
            let new = SpaceMap::unbounded(ModelKind::Shc, p1);
            assert_eq!(old.dim(), new.dim());
            let u: Vec<f64> = [0.3, -1.2, 0.4, -4.0, -0.7, 0.2][..old.dim()].to_vec();
            let a = old.to_params(&u).unwrap();
            assert_eq!(a.as_array(), new.to_params(&u).unwrap().as_array());
            let back = new.from_params(&a).unwrap();
            for (x, y) in back.iter().zip(&u) {
                assert!((x - y).abs() < 1e-12, "{back:?} {u:?}");
            }
        }
    }

    #[test]
    fn bounded_and_fixed_coordinates_stay_inside() {
        let k = ModelKind::Shc;
        let b = parse_bounds("B_b=0.8..1.6,Gamma_b=-1.6..1,sigma_b=0.001..0.1,n=1..1.4").unwrap();
        let s = Space::build(k, &[(2, 0.632)], &b, free).unwrap();
        let m = SpaceMap::new(s);
        assert_eq!(m.dim(), 5);
        for &t in &[-100.0, -3.0, 0.0, 2.0, 100.0] {
            let u = [t, -t, t * 0.5, t, -t * 0.3];
            let p = m.to_params(&u).unwrap();
            assert_eq!(p.kappa, 0.632);
            assert!((0.8..=1.6).contains(&p.b) && p.gamma.abs() < p.b && p.gamma <= 1.0);
            assert!((0.001..=0.1).contains(&p.sigma) && (1.0..=1.4).contains(&p.n));
            let back = m.from_params(&p).unwrap();
            if t.abs() < 10.0 {
                for (x, y) in back.iter().zip(&u) {
                    assert!((x - y).abs() < 1e-8, "{back:?} {u:?}");
                }
            }
        }
        // Γ fixed: B starts above |Γ|
        let s = Space::build(k, &[(1, -1.42)], &[], free).unwrap();
        let p = SpaceMap::new(s)
            .to_params(&[-30.0, 0.0, 0.0, 0.0, 0.0])
            .unwrap();
        assert!(p.b > 1.42 && p.gamma == -1.42);
        let at = SpaceMap::new(Space::build(k, &[], &[(2, 0.4, 0.8)], free).unwrap());
        let p = at.to_params(&[0.0, 0.0, 40.0, 0.0, 0.0, 0.0]).unwrap();
        assert_eq!(at.at_bounds(&p, 1e-6), vec!["kappa"]);
        let p = at.to_params(&[0.0, 0.0, 1.0, 0.0, 0.0, 0.0]).unwrap();
        assert!(at.at_bounds(&p, 1e-6).is_empty());
    }
}
