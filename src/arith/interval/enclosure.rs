//! inari's `Interval` as an [`Enclosure`]: the rigorous engine's f64 fast path. The jets run on
//! [`Ulp`] (inari's enclosures without rounding-mode switches), sums of products on
//! [`interval_dot`], powers of a nonnegative base on [`powi_nonneg`].

use super::dot::interval_dot;
use super::elementary::powi_nonneg;
use super::ulp::Ulp;
use crate::arith::enclosure::Enclosure;
use inari::Interval;

impl Enclosure for Interval {
    type Jet = Ulp;
    #[inline]
    fn to_jet(&self) -> Ulp {
        Ulp::of(*self)
    }
    #[inline]
    fn from_jet(j: Ulp) -> Self {
        j.interval()
    }
    #[inline]
    fn from_bounds(lo: f64, hi: f64) -> Option<Self> {
        Interval::try_from((lo, hi)).ok()
    }
    #[inline]
    fn empty() -> Self {
        Interval::EMPTY
    }
    #[inline]
    fn entire() -> Self {
        Interval::ENTIRE
    }
    #[inline]
    fn is_empty(&self) -> bool {
        Interval::is_empty(*self)
    }
    #[inline]
    fn hull(&self, other: &Self) -> Self {
        self.convex_hull(*other)
    }
    #[inline]
    fn intersection(&self, other: &Self) -> Self {
        Interval::intersection(*self, *other)
    }
    #[inline]
    fn subset(&self, other: &Self) -> bool {
        Interval::subset(*self, *other)
    }
    #[inline]
    fn interior(&self, other: &Self) -> bool {
        Interval::interior(*self, *other)
    }
    #[inline]
    fn same(&self, other: &Self) -> bool {
        self == other
    }
    #[inline]
    fn mid_point(&self) -> Self {
        let m = self.mid();
        Interval::try_from((m, m)).unwrap_or(Interval::ENTIRE)
    }
    #[inline]
    fn inf_point(&self) -> Self {
        let m = self.inf();
        Interval::try_from((m, m)).unwrap_or(Interval::ENTIRE)
    }
    #[inline]
    fn sup_point(&self) -> Self {
        let m = self.sup();
        Interval::try_from((m, m)).unwrap_or(Interval::ENTIRE)
    }
    #[inline]
    fn exp(&self) -> Self {
        Interval::exp(*self)
    }
    /// inari's `powi`.
    fn powi_signed(&self, k: u32) -> Self {
        Interval::powi(*self, k as i32)
    }
    /// The ends moved by r in round-to-nearest (a candidate set: any widening will do).
    fn widen(&self, rel: f64, abs: f64) -> Self {
        let r = rel * self.wid() + abs;
        Interval::try_from((self.inf() - r, self.sup() + r)).unwrap_or(Interval::ENTIRE)
    }
    #[inline]
    fn epsilon() -> f64 {
        f64::EPSILON
    }
    #[inline]
    fn wid_f64(&self) -> f64 {
        self.wid()
    }
    #[inline]
    fn rad_f64(&self) -> f64 {
        self.rad()
    }
    #[inline]
    fn mag_f64(&self) -> f64 {
        self.mag()
    }
    #[inline]
    fn mag_log2(&self) -> f64 {
        self.mag().log2()
    }
    #[inline]
    fn mig_f64(&self) -> f64 {
        self.mig()
    }
    #[inline]
    fn nonneg(&self) -> Self {
        Interval::intersection(*self, inari::const_interval!(0.0, f64::INFINITY))
    }
    #[inline]
    fn powi_nonneg(&self, n: u32) -> Self {
        powi_nonneg(*self, n)
    }
    #[inline]
    fn dot(terms: impl IntoIterator<Item = (Self, Self)>) -> Self {
        interval_dot(terms)
    }
}
