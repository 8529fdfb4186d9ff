//! [`Mpi`] (an interval over MPFR floats of `B` bits) as an [`Enclosure`]: the rigorous engine
//! at a chosen precision. The jets run on the type itself; sums of products on its plain
//! accumulator (each product and sum rounded outward).

use super::Mpi;
use crate::arith::enclosure::Enclosure;
use crate::arith::real::Real;
use rug::Float;

impl<const B: u32> Enclosure for Mpi<B> {
    type Jet = Self;
    #[inline]
    fn to_jet(&self) -> Self {
        self.clone()
    }
    #[inline]
    fn from_jet(j: Self) -> Self {
        j
    }
    fn from_bounds(lo: f64, hi: f64) -> Option<Self> {
        // a double is exact at B ≥ 53 bits (and rounded outward by `new` below that)
        (lo <= hi).then(|| Mpi::new(Float::with_val(53, lo), Float::with_val(53, hi)))
    }
    fn empty() -> Self {
        Mpi::empty()
    }
    fn entire() -> Self {
        Mpi::entire()
    }
    #[inline]
    fn is_empty(&self) -> bool {
        Mpi::is_empty(self)
    }
    #[inline]
    fn hull(&self, other: &Self) -> Self {
        Mpi::hull(self, other)
    }
    #[inline]
    fn intersection(&self, other: &Self) -> Self {
        Mpi::intersection(self, other)
    }
    #[inline]
    fn subset(&self, other: &Self) -> bool {
        Mpi::subset(self, other)
    }
    #[inline]
    fn interior(&self, other: &Self) -> bool {
        Mpi::interior(self, other)
    }
    fn same(&self, other: &Self) -> bool {
        (self.is_empty() && other.is_empty())
            || (!self.is_empty()
                && !other.is_empty()
                && self.inf() == other.inf()
                && self.sup() == other.sup())
    }
    #[inline]
    fn mid_point(&self) -> Self {
        Mpi::mid_point(self)
    }
    fn inf_point(&self) -> Self {
        Mpi::point(self.inf())
    }
    fn sup_point(&self) -> Self {
        Mpi::point(self.sup())
    }
    fn exp(&self) -> Self {
        Mpi::exp(self)
    }
    fn epsilon() -> f64 {
        2f64.powi(1 - B as i32)
    }
    #[inline]
    fn wid_f64(&self) -> f64 {
        Mpi::wid_f64(self)
    }
    #[inline]
    fn rad_f64(&self) -> f64 {
        Mpi::rad_f64(self)
    }
    #[inline]
    fn mag_f64(&self) -> f64 {
        Mpi::mag_f64(self)
    }
    /// The binary exponent e of the larger end (|x| < 2^e).
    fn mag_log2(&self) -> f64 {
        let e = |x: &Float| {
            if x.is_infinite() || x.is_nan() {
                f64::INFINITY
            } else {
                x.get_exp().map_or(f64::NEG_INFINITY, f64::from)
            }
        };
        e(self.inf()).max(e(self.sup()))
    }
    #[inline]
    fn mig_f64(&self) -> f64 {
        Mpi::mig_f64(self)
    }
    /// x^n for x ≥ 0 by binary powering (each product of nonnegative factors is monotone).
    fn powi_nonneg(&self, mut n: u32) -> Self {
        let (mut base, mut acc) = (self.clone(), Self::one());
        while n > 0 {
            if n & 1 == 1 {
                acc = acc * base.clone();
            }
            n >>= 1;
            if n > 0 {
                base = base.sqr();
            }
        }
        acc
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Rational;
    use rug::ops::Pow;

    type M = Mpi<128>;

    #[test]
    fn points_widths_and_powers_enclose_the_exact_values() {
        let x = M::from_bounds(0.25, 0.75).unwrap();
        let m = x.mid_point();
        assert!(m.inf() == m.sup() && *m.inf() == 0.5);
        assert!(x.inf_point().same(&M::from_exact_f64(0.25)));
        assert!(x.wid_f64() >= 0.5 && x.rad_f64() >= 0.25 && x.mag_f64() >= 0.75);
        assert!(x.mig_f64() <= 0.25);
        assert!(M::from_bounds(1.0, 0.0).is_none());
        // (1/3)^7 at 128 bits: contains the exact rational, about 2^-128 relative wide
        let third = M::one() / M::from_int(3);
        let p = third.powi_nonneg(7);
        let exact = Rational::from((1, 2187));
        assert!(*p.inf() <= exact && exact <= *p.sup(), "{p:?}");
        assert!(p.wid_f64() < 1e-36 * 1e-3 + 1e-39);
        assert!(M::epsilon() == 2f64.powi(-127));
        let nn = M::from_bounds(-1.0, 2.0).unwrap().nonneg();
        assert!(nn.same(&M::from_bounds(0.0, 2.0).unwrap()));
    }

    /// [a, b]^k by the trait's default `powi_signed` (the singular step's u^k on a range of
    /// any sign, at MPFR precision): contains the exact range (from the ends' exact powers
    /// and 0 for even k across 0, as rationals) and is no wider than it plus a few ulps — for
    /// intervals below, across and above 0, thin and touching 0, k = 0 … 7.
    #[test]
    fn signed_powers_enclose_the_exact_range_tightly() {
        let ends = [
            (-1.5, -0.25),
            (-0.75, 2.0),
            (-2.0, 0.5),
            (0.125, 3.0),
            (-1.0, 0.0),
            (0.0, 1.0),
            (-0.3, -0.3),
            (0.1, 0.1),
            (-1e-30, 1e-30),
        ];
        for (a, b) in ends {
            let x = M::from_bounds(a, b).unwrap();
            for k in 0..=7u32 {
                let p = x.powi_signed(k);
                let (ra, rb) = (
                    Rational::from_f64(a).unwrap().pow(k),
                    Rational::from_f64(b).unwrap().pow(k),
                );
                let mut lo = ra.clone().min(rb.clone());
                let mut hi = ra.max(rb);
                if k == 0 {
                    // x^0 = 1 (across 0 the default gives [0, 1]: sound, not tight)
                    (lo, hi) = (Rational::from(1), Rational::from(1));
                } else if k % 2 == 0 && a < 0.0 && b > 0.0 {
                    lo = Rational::new();
                }
                assert!(
                    *p.inf() <= lo && hi <= *p.sup(),
                    "[{a}, {b}]^{k}: {p:?} ∌ [{lo}, {hi}]"
                );
                let slack = Rational::from_f64(1e-30 * (1.0 + a.abs().max(b.abs()).powi(k as i32)))
                    .unwrap();
                let exact_w = Rational::from(&hi - &lo);
                let w = p.sup().to_rational().unwrap() - p.inf().to_rational().unwrap();
                let tight = k == 0 && a < 0.0 && b > 0.0 || w <= exact_w + slack;
                assert!(tight, "[{a}, {b}]^{k}: {p:?} wider than [{lo}, {hi}]");
            }
        }
    }
}
