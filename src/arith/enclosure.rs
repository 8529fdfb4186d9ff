//! The trait of the rigorous engine's number: [`Enclosure`], an interval type with the set
//! operations, points and widths the engine needs on top of [`Real`].
//!
//! The engine (`crate::engines::taylor`) is written once against it and runs on inari's
//! `Interval` (f64 ends: [`super::interval`]) or on an interval over MPFR floats at a chosen
//! precision. What builds an enclosure uses the type's own ends (`hull`, `intersection`,
//! `mid_point`, `inf_point`, …); only control decisions (step sizes, tolerances, which branch
//! to take) read outward `f64` bounds (`lo`/`hi` of [`Real`], `wid_f64`, `mag_f64`, …), and
//! the times of step boundaries are exact doubles ([`Enclosure::from_bounds`]).
//!
//! The Taylor coefficients run on the associated [`Enclosure::Jet`] type: for inari's
//! `Interval` the ulp intervals (the same enclosures without rounding-mode switches), for a
//! type without a faster twin the type itself.

use super::real::{Dot, Real};

/// An interval number type the rigorous engine runs on. Every operation encloses the exact
/// set result; the `f64` views are outward (a lower bound rounded down, an upper bound or a
/// width rounded up) unless they say otherwise.
pub trait Enclosure: Real {
    /// The number type of the jets (Taylor coefficients, duals), converted to and from `Self`
    /// without loss of enclosure.
    type Jet: Real;
    /// `self` as a jet number (an enclosure of the same set).
    fn to_jet(&self) -> Self::Jet;
    /// A jet number as `Self` (an enclosure of the same set).
    fn from_jet(j: Self::Jet) -> Self;
    /// [lo, hi] for exact doubles lo ≤ hi (a time span, a ball ±r); `None` when that is not an
    /// interval (lo > hi, a NaN).
    fn from_bounds(lo: f64, hi: f64) -> Option<Self>;
    /// The empty set.
    fn empty() -> Self;
    /// Every real (the honest value of a failed conversion).
    fn entire() -> Self {
        Self::unbounded()
    }
    fn is_empty(&self) -> bool;
    /// The smallest interval containing both.
    fn hull(&self, other: &Self) -> Self;
    fn intersection(&self, other: &Self) -> Self;
    /// self ⊆ other.
    fn subset(&self, other: &Self) -> bool;
    /// self ⊆ int(other).
    fn interior(&self, other: &Self) -> bool;
    /// The same set as `other` (both ends equal).
    fn same(&self, other: &Self) -> bool;
    /// A point of the type inside (near the middle of) a non-empty bounded interval.
    fn mid_point(&self) -> Self;
    /// The lower end as a point of the type (exact).
    fn inf_point(&self) -> Self;
    /// The upper end as a point of the type (exact).
    fn sup_point(&self) -> Self;
    /// The machine epsilon of the ends (2^−52 for f64 ends, 2^(1−p) at p bits): the scale of
    /// the engine's relative floors.
    fn epsilon() -> f64;
    /// The width, rounded up.
    fn wid_f64(&self) -> f64;
    /// The radius, rounded up.
    fn rad_f64(&self) -> f64;
    /// max |x|, rounded up.
    fn mag_f64(&self) -> f64;
    /// log₂ max |x|, rounded up (+∞ when unbounded): the size of a number beyond f64's range.
    fn mag_log2(&self) -> f64;
    /// min |x|, rounded down.
    fn mig_f64(&self) -> f64;
    /// self ∩ [0, ∞).
    fn nonneg(&self) -> Self {
        self.intersection(&Self::from_bounds(0.0, f64::INFINITY).expect("[0, ∞]"))
    }
    /// x^n for x ≥ 0.
    fn powi_nonneg(&self, n: u32) -> Self;
    /// e^x.
    fn exp(&self) -> Self;
    /// x^k for any sign of x: [a, b]^k from the powers of the ends' magnitudes (k even: from 0
    /// when the interval holds 0).
    fn powi_signed(&self, k: u32) -> Self {
        if self.is_empty() {
            return Self::empty();
        }
        let (a, b) = (self.inf_point(), self.sup_point());
        let odd = k % 2 == 1;
        if a.lo() >= 0.0 {
            return self.powi_nonneg(k);
        }
        // the negative end's power: (−a)^k with a < 0, negated for odd k
        let pa = (-a).powi_nonneg(k);
        let pa = if odd { -pa } else { pa };
        if b.hi() <= 0.0 {
            let pb = (-b).powi_nonneg(k);
            let pb = if odd { -pb } else { pb };
            return pa.hull(&pb);
        }
        let pb = b.powi_nonneg(k);
        let r = pa.hull(&pb);
        if odd { r } else { r.hull(&Self::zero()) }
    }
    /// [inf − r, sup + r] with r = rel·width + abs: a larger set (a candidate of a fixed-point
    /// iteration, whose own inclusion test decides; not an enclosure of a result).
    fn widen(&self, rel: f64, abs: f64) -> Self {
        let r = rel * self.wid_f64() + abs;
        match Self::from_bounds(-r, r) {
            Some(b) if !self.is_empty() => self.clone() + b,
            _ => Self::entire(),
        }
    }
    /// Σ aⱼ·bⱼ, one enclosure of the exact sum (the type's [`Dot`] accumulator).
    fn dot(terms: impl IntoIterator<Item = (Self, Self)>) -> Self {
        let mut d = <Self::Dot as Dot<Self>>::new();
        for (a, b) in terms {
            d.add_prod(&a, &b);
        }
        d.sum()
    }
}
