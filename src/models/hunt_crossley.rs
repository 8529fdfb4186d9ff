//! The Simon–Hunt–Crossley collision law and the published choices of its damping.
//!
//! The law (the paper's review section, after Hunt & Crossley 1975):
//!
//! ```text
//! F = k|δ|^(n−1)δ + χ|δ|^n δ̇
//! ```
//!
//! With δ = L·X, t = (L/v0)·T and L = (m v0²/k)^(1/(n+1)) it is the NDBWSHCCM (eq:BWSHCCM_nd)
//! without its Bouc–Wen branch: X′ = V, V′ = −|X|^(n−1)X − σ|X|^n V from X = 0, V = −1, with
//!
//! ```text
//! σ = χ v0 / k.
//! ```
//!
//! **Its CoR in closed form.** While X < 0, V dV/dX = |X|^n (1 − σV), and X returns to 0 with
//! the force still ≥ 0 (1 − σV > 0, below), so ∫_{−1}^{e} V/(1 − σV) dV = 0; with u = σe
//!
//! ```text
//! H(σ, e) = G(σe) − G(−σ) = 0,    G(u) = −u − ln(1 − u)
//! ```
//!
//! (G(−σ) = σ − ln(1 + σ)). n does not enter: e depends on σ alone (Carvalho & Martins 2019
//! call this the exact restitution relation). For σ > 0, H(σ, ·) is increasing on (0, 1/σ)
//! (∂H/∂e = σ²e/(1 − σe) > 0) from −G(−σ) < 0 to +∞: one root e(σ) ∈ (0, min(1, 1/σ)),
//! and σe < 1 on the whole contact (V ≤ e there), which is the force's sign used above.
//!
//! **The damping formulas.** Each published χ(e*) is derived from an approximate energy balance
//! and aims the law at a target CoR e*; in the nondimensional form each is a function σ(e*)
//! (χ ∝ 1/v0 in all of them). [`DampingFormula`] lists them as the reviews tabulate them
//! (Flores & Lankarani 2016, *Contact Force Models for Multibody Dynamics*, ch. 3; Skrinjar et
//! al. 2018, *Mech. Mach. Theory*); the CoR the law really produces is e(σ(e*)), proved in
//! [`crate::observables::restitution`].

use super::ForceLaw;
use crate::arith::mpfr::Mpi;
use crate::arith::{Exponent, Real, Scalar};
use inari::Interval;

/// The law as a collision model, states (X, V):
///
/// ```text
/// X′ = V,   V′ = F = −|X|^(n−1)X − σ|X|^n V,   X(0) = 0, V(0) = −1
/// ```
///
/// Hertz's law is σ = 0, Hooke's (the linear spring) n = 1 and σ = 0. Admissible: n ≥ 1,
/// σ ≥ 0. Separation by the crate's rule T_s = inf{T ≥ 0 : F ≤ 0 ∧ V ≥ 0}: while X < 0,
/// F = |X|^n (1 − σV) > 0 (σV < 1 on the contact, above), so T_s is the return to X = 0, where
/// δ = 0 and F = 0 at once — Hunt & Crossley's own separation.
#[derive(Clone, Debug)]
pub struct HuntCrossley<R: Real> {
    pub sigma: R,
    pub n: Exponent<R>,
    /// σ ≠ 0: an undamped law (Hertz, Hooke) has no damping term, so that Hooke's field is
    /// linear (no |X| kink for the engines to cross at the separation).
    damped: bool,
}

impl<R: Real> HuntCrossley<R> {
    /// The law with damping σ ≥ 0 and exponent n ≥ 1 (every value of an enclosure); the
    /// refusal names the parameter and its bounds.
    pub fn new(sigma: R, n: R) -> Result<Self, String> {
        if !(sigma.lo() >= 0.0 && sigma.hi().is_finite()) {
            return Err(format!(
                "the damping σ must be ≥ 0 and finite (got {})",
                crate::models::params::show(&sigma)
            ));
        }
        if !(n.lo() >= 1.0 && n.hi().is_finite()) {
            return Err(format!(
                "the exponent n must be ≥ 1 and finite (got {})",
                crate::models::params::show(&n)
            ));
        }
        let damped = !(sigma.lo() == 0.0 && sigma.hi() == 0.0);
        Ok(Self {
            sigma,
            n: Exponent::new(n),
            damped,
        })
    }

    /// Hertz's law (σ = 0).
    pub fn hertz(n: R) -> Result<Self, String> {
        Self::new(R::zero(), n)
    }

    /// Hooke's law, the linear spring (n = 1, σ = 0).
    pub fn hooke() -> Self {
        Self::new(R::zero(), R::one()).expect("n = 1, σ = 0")
    }
}

impl<R: Real> ForceLaw<R> for HuntCrossley<R> {
    const NAME: &'static str = "hunt-crossley";

    /// F = −|X|^(n−1)X − σ|X|^n V.
    fn force_xv<T: Scalar<R>>(&self, x: &T, v: &T) -> T {
        if !self.damped {
            return -x.spow_prepared(&self.n);
        }
        let (xs, xa) = x.spow_apow_prepared(&self.n);
        -xs - (xa * v.clone()).scale(&self.sigma)
    }
}

/// eˣ over a type: what the damping formulas need beyond [`Real`].
pub trait Exp: Real {
    fn exp(&self) -> Self;
}

impl Exp for f64 {
    fn exp(&self) -> Self {
        f64::exp(*self)
    }
}

impl Exp for Interval {
    fn exp(&self) -> Self {
        Interval::exp(*self)
    }
}

impl<const B: u32> Exp for Mpi<B> {
    fn exp(&self) -> Self {
        Mpi::exp(self)
    }
}

/// A published choice of the Hunt–Crossley damping χ for a target CoR e* (σ = χ v0 / k).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DampingFormula {
    /// Hunt & Crossley (1975): σ = 3(1 − e*)/2.
    HuntCrossley,
    /// Herbert & McWhannell (1977): σ = 6(1 − e*)/((2e* − 1)² + 3).
    HerbertMcWhannell,
    /// Lee & Wang (1983): σ = 3(1 − e*)/4.
    LeeWang,
    /// Lankarani & Nikravesh (1990): σ = 3(1 − e*²)/4.
    LankaraniNikravesh,
    /// Gonthier et al. (2004): σ = (1 − e*²)/e*.
    Gonthier,
    /// Zhiying & Qishao (2006): σ = 3(1 − e*²)·exp(2(1 − e*))/4.
    ZhiyingQishao,
    /// Flores et al. (2011): σ = 8(1 − e*)/(5e*).
    Flores,
    /// Gharib & Hurmuzlu (2012): σ = 1/e* − 1.
    GharibHurmuzlu,
    /// Hu & Guo (2015): σ = 3(1 − e*)/(2e*).
    HuGuo,
    /// Carvalho & Martins (2019): the σ of the exact relation H(σ, e*) = 0 (module doc).
    CarvalhoMartins,
}

impl DampingFormula {
    /// Every formula, in order of publication.
    pub const ALL: [DampingFormula; 10] = [
        DampingFormula::HuntCrossley,
        DampingFormula::HerbertMcWhannell,
        DampingFormula::LeeWang,
        DampingFormula::LankaraniNikravesh,
        DampingFormula::Gonthier,
        DampingFormula::ZhiyingQishao,
        DampingFormula::Flores,
        DampingFormula::GharibHurmuzlu,
        DampingFormula::HuGuo,
        DampingFormula::CarvalhoMartins,
    ];

    /// The name used on the command line (`--formulas`).
    pub fn key(self) -> &'static str {
        match self {
            DampingFormula::HuntCrossley => "hunt-crossley",
            DampingFormula::HerbertMcWhannell => "herbert-mcwhannell",
            DampingFormula::LeeWang => "lee-wang",
            DampingFormula::LankaraniNikravesh => "lankarani-nikravesh",
            DampingFormula::Gonthier => "gonthier",
            DampingFormula::ZhiyingQishao => "zhiying-qishao",
            DampingFormula::Flores => "flores",
            DampingFormula::GharibHurmuzlu => "gharib-hurmuzlu",
            DampingFormula::HuGuo => "hu-guo",
            DampingFormula::CarvalhoMartins => "carvalho-martins",
        }
    }

    /// Authors and year, as a table names the formula.
    pub fn source(self) -> &'static str {
        match self {
            DampingFormula::HuntCrossley => "Hunt & Crossley 1975",
            DampingFormula::HerbertMcWhannell => "Herbert & McWhannell 1977",
            DampingFormula::LeeWang => "Lee & Wang 1983",
            DampingFormula::LankaraniNikravesh => "Lankarani & Nikravesh 1990",
            DampingFormula::Gonthier => "Gonthier et al. 2004",
            DampingFormula::ZhiyingQishao => "Zhiying & Qishao 2006",
            DampingFormula::Flores => "Flores et al. 2011",
            DampingFormula::GharibHurmuzlu => "Gharib & Hurmuzlu 2012",
            DampingFormula::HuGuo => "Hu & Guo 2015",
            DampingFormula::CarvalhoMartins => "Carvalho & Martins 2019",
        }
    }

    /// σ(e*) as a formula, for tables.
    pub fn formula(self) -> &'static str {
        match self {
            DampingFormula::HuntCrossley => "3(1−e)/2",
            DampingFormula::HerbertMcWhannell => "6(1−e)/((2e−1)²+3)",
            DampingFormula::LeeWang => "3(1−e)/4",
            DampingFormula::LankaraniNikravesh => "3(1−e²)/4",
            DampingFormula::Gonthier => "(1−e²)/e",
            DampingFormula::ZhiyingQishao => "3(1−e²)exp(2(1−e))/4",
            DampingFormula::Flores => "8(1−e)/(5e)",
            DampingFormula::GharibHurmuzlu => "1/e−1",
            DampingFormula::HuGuo => "3(1−e)/(2e)",
            DampingFormula::CarvalhoMartins => "root of H(σ,e)=0",
        }
    }

    /// The formula named `key` ([`DampingFormula::key`]).
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.key() == key)
    }

    /// σ(e*) over the arithmetic `R`, e* ∈ (0, 1]; `None` for [`DampingFormula::CarvalhoMartins`],
    /// whose σ is the root of an equation (see [`crate::observables::restitution::exact_sigma`]).
    pub fn sigma<R: Exp>(self, e: &R) -> Option<R> {
        let one = R::one();
        let c = one.clone() - e.clone();
        let c2 = one.clone() - e.clone() * e.clone();
        Some(match self {
            DampingFormula::HuntCrossley => c.mul_int(3).div_int(2),
            DampingFormula::HerbertMcWhannell => {
                let d = e.mul_int(2) - one;
                c.mul_int(6) / (d.clone() * d + R::from_int(3))
            }
            DampingFormula::LeeWang => c.mul_int(3).div_int(4),
            DampingFormula::LankaraniNikravesh => c2.mul_int(3).div_int(4),
            DampingFormula::Gonthier => c2 / e.clone(),
            DampingFormula::ZhiyingQishao => (c2.mul_int(3) * c.mul_int(2).exp()).div_int(4),
            DampingFormula::Flores => c.mul_int(8) / e.mul_int(5),
            DampingFormula::GharibHurmuzlu => one / e.clone() - R::one(),
            DampingFormula::HuGuo => c.mul_int(3) / e.mul_int(2),
            DampingFormula::CarvalhoMartins => return None,
        })
    }
}

/// G(u) = −u − ln(1 − u), u < 1 (module doc).
pub fn g<R: Real>(u: &R) -> R {
    -u.clone() - (R::one() - u.clone()).ln()
}

/// H(σ, e) = G(σe) − G(−σ): zero exactly at the CoR e of the law with damping σ (module doc).
pub fn restitution_residual<R: Real>(sigma: &R, e: &R) -> R {
    g(&(sigma.clone() * e.clone())) - g(&-sigma.clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formulas_at_hand_computed_points() {
        // e* = 0.5: 0.75, 6·0.5/3 = 1, 0.375, 0.5625, 1.5, 0.5625·e, 1.6, 1, 1.5
        let want = [
            0.75,
            1.0,
            0.375,
            0.5625,
            1.5,
            0.5625 * std::f64::consts::E,
            1.6,
            1.0,
            1.5,
        ];
        for (f, w) in DampingFormula::ALL.iter().zip(want) {
            let s = f.sigma(&0.5_f64).unwrap();
            assert!((s - w).abs() < 1e-15, "{f:?}: {s} against {w}");
        }
        assert!(DampingFormula::CarvalhoMartins.sigma(&0.5_f64).is_none());
        // every formula is 0 at e* = 1 (no damping for a perfectly elastic target)
        for f in &DampingFormula::ALL[..9] {
            assert_eq!(f.sigma(&1.0_f64), Some(0.0), "{f:?}");
        }
    }

    #[test]
    fn keys_round_trip() {
        for f in DampingFormula::ALL {
            assert_eq!(DampingFormula::from_key(f.key()), Some(f));
        }
        assert_eq!(DampingFormula::from_key("hertz"), None);
    }

    #[test]
    fn residual_vanishes_on_the_small_damping_expansion() {
        // e = 1 − 2σ/3 + O(σ²): H(σ, 1 − 2σ/3) = O(σ⁴) for small σ, and H changes sign there
        let s = 1e-3_f64;
        let h = |e: f64| restitution_residual(&s, &e);
        assert!(h(1.0 - 2.0 * s / 3.0).abs() < 1e-11);
        assert!(h(1.0 - 2.0 * s / 3.0 - 1e-5) < 0.0);
        assert!(h(1.0 - 2.0 * s / 3.0 + 1e-5) > 0.0);
    }
}
