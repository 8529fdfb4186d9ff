//! [`Ulp`] as a [`Real`]: the coefficient field of the rigorous engine's jets.

use super::dot::UlpDot;
use super::ulp::Ulp;
use crate::arith::Real;
use inari::Interval;

/// [`Ulp`] as a coefficient field of the rigorous engine's jets: +, −, ×, ÷ and integer
/// scalings here; powers, |·| and √ through inari's enclosures ([`super`]).
impl Real for Ulp {
    type Dot = UlpDot;
    type Prepared = ();
    fn prepare_exponent(_: &Self) {}
    fn from_int(k: i64) -> Self {
        let x = k as f64;
        assert!(x as i64 == k, "integer constant {k} is not exact in f64");
        Self::point(x)
    }
    fn from_exact_f64(x: f64) -> Self {
        Self::point(x)
    }
    fn parse_decimal(s: &str) -> Result<Self, String> {
        Interval::parse_decimal(s).map(Self::of)
    }
    fn unbounded() -> Self {
        Self::ENTIRE
    }
    #[inline]
    fn mul_int(&self, k: i64) -> Self {
        self.int_op(k, false)
    }
    #[inline]
    fn div_int(&self, k: i64) -> Self {
        self.int_op(k, true)
    }
    fn abs(&self) -> Self {
        if self.lo >= 0.0 {
            *self
        } else if self.hi <= 0.0 {
            -*self
        } else {
            Self {
                lo: 0.0,
                hi: self.hi.max(-self.lo),
            }
        }
    }
    fn sqrt(&self) -> Self {
        Self::of(Real::sqrt(&self.interval()))
    }
    fn ln(&self) -> Self {
        Self::of(Real::ln(&self.interval()))
    }
    fn pow_ln(w: &Self, q: &Self, signed: bool) -> Self {
        Self::of(<Interval as Real>::pow_ln(
            &w.interval(),
            &q.interval(),
            signed,
        ))
    }
    fn sgn(&self) -> Self {
        Self::of(Real::sgn(&self.interval()))
    }
    fn pow(&self, y: &Self) -> Self {
        Self::of(Real::pow(&self.interval(), &y.interval()))
    }
    fn spow(&self, q: &Self) -> Self {
        Self::of(Real::spow(&self.interval(), &q.interval()))
    }
    fn apow(&self, q: &Self) -> Self {
        Self::of(Real::apow(&self.interval(), &q.interval()))
    }
    #[inline]
    fn lo(&self) -> f64 {
        self.lo
    }
    #[inline]
    fn hi(&self) -> f64 {
        self.hi
    }
    fn mid(&self) -> f64 {
        self.interval().mid()
    }
}
