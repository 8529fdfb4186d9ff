//! `f64` as a [`Real`]: the coefficient field of the f64 DOP853 engine, rounded to nearest.
//!
//! - this file: `f64` as a [`Real`], its prepared exponents and its plain accumulator;
//! - [`fastpow`]: x^q by tables per exponent (low latency);
//! - [`golden`]: golden-section search for a minimum.

pub mod fastpow;
pub mod golden;

use crate::arith::real::{Dot, Exponent, Real};
use fastpow::Power;

/// Whether the decimal `text` is nonzero but its double `x` is 0: below the smallest positive
/// double, it would silently become 0.
pub fn read_as_zero(text: &str, x: f64) -> bool {
    let mantissa = text.trim().split(['e', 'E']).next().unwrap_or("");
    x == 0.0 && mantissa.chars().any(|c| matches!(c, '1'..='9'))
}

/// A prepared exponent q of the `f64` engine: |x|^(q−1) exactly for q = 1 and q = 2,
/// otherwise by q − 1's tables ([`fastpow`], a few ulps).
#[derive(Clone, Debug)]
pub enum F64Exponent {
    One,
    Two,
    Tables(Power),
}

impl F64Exponent {
    fn new(q: f64) -> Self {
        if q == 1.0 {
            F64Exponent::One
        } else if q == 2.0 {
            F64Exponent::Two
        } else {
            F64Exponent::Tables(Power::new(q - 1.0))
        }
    }
}

/// The `f64` powers: with a prepared exponent (the models' right-hand sides) by tables; the
/// others (Lyapunov functions, tests, one-off values) by the library `powf`.
impl Real for f64 {
    type Dot = F64Dot;
    type Prepared = F64Exponent;
    fn prepare_exponent(q: &f64) -> F64Exponent {
        F64Exponent::new(*q)
    }
    #[inline]
    fn from_int(k: i64) -> Self {
        k as f64
    }
    #[inline]
    fn from_exact_f64(x: f64) -> Self {
        x
    }
    fn parse_decimal(s: &str) -> Result<Self, String> {
        let t = s.trim();
        if t.contains("..") {
            return Err(format!("a range ({t}) needs the rigorous engine"));
        }
        let x: f64 = t.parse().map_err(|_| format!("'{t}' is not a number"))?;
        if !x.is_finite() {
            return Err(format!("'{t}' is not a finite number"));
        }
        if read_as_zero(t, x) {
            return Err(format!(
                "'{t}' is below the smallest positive double (it would be read as 0)"
            ));
        }
        Ok(x)
    }
    fn unbounded() -> Self {
        f64::NAN
    }
    #[inline]
    fn abs(&self) -> Self {
        f64::abs(*self)
    }
    #[inline]
    fn sqrt(&self) -> Self {
        f64::sqrt(*self)
    }
    fn ln(&self) -> Self {
        f64::ln(*self)
    }
    fn pow_ln(w: &Self, q: &Self, signed: bool) -> Self {
        if *w == 0.0 {
            return 0.0;
        }
        let u = if signed { w.spow(q) } else { w.apow(q) };
        u * w.abs().ln()
    }
    fn sgn(&self) -> Self {
        if *self > 0.0 {
            1.0
        } else if *self < 0.0 {
            -1.0
        } else {
            f64::NAN
        }
    }
    #[inline]
    fn pow(&self, y: &Self) -> Self {
        self.powf(*y)
    }
    #[inline]
    fn spow(&self, q: &Self) -> Self {
        if *q == 1.0 {
            *self
        } else if *q == 2.0 {
            self.abs() * self
        } else if *self == 0.0 {
            0.0
        } else {
            self.abs().powf(q - 1.0) * self
        }
    }
    #[inline]
    fn apow(&self, q: &Self) -> Self {
        if *q == 1.0 {
            self.abs()
        } else if *q == 2.0 {
            self * self
        } else {
            self.abs().powf(*q)
        }
    }
    /// One power: a = |x|^(q−1), then (a·x, a·|x|).
    #[inline]
    fn spow_apow(&self, q: &Self) -> (Self, Self) {
        if *q == 1.0 {
            (*self, self.abs())
        } else if *q == 2.0 {
            (self.abs() * self, self * self)
        } else if *self == 0.0 {
            (0.0, 0.0)
        } else {
            let a = self.abs().powf(q - 1.0);
            (a * self, a * self.abs())
        }
    }
    /// One power: a = |x|^(q−1), then (a·x, a).
    #[inline]
    fn spow_base(&self, q: &Self) -> (Self, Self) {
        if *q == 2.0 {
            (self.abs() * self, self.abs())
        } else if *self == 0.0 {
            (0.0, if *q == 1.0 { 1.0 } else { 0.0 })
        } else {
            let a = self.abs().powf(q - 1.0);
            (a * self, a)
        }
    }
    // The three prepared powers repeat the same match on purpose: one shared helper returning
    // (a, a·x) measured 3% slower per CoR (same values).
    #[inline(always)]
    fn spow_prepared(&self, q: &Exponent<f64>) -> f64 {
        match q.prepared() {
            F64Exponent::One => *self,
            F64Exponent::Two => self.abs() * self,
            F64Exponent::Tables(t) => {
                if *self == 0.0 {
                    0.0
                } else {
                    t.pow_and_mul(self.abs(), *self).1
                }
            }
        }
    }
    /// One power: a = |x|^(q−1), then (a·x, |a·x|).
    #[inline(always)]
    fn spow_apow_prepared(&self, q: &Exponent<f64>) -> (f64, f64) {
        match q.prepared() {
            F64Exponent::One => (*self, self.abs()),
            F64Exponent::Two => {
                let s = self.abs() * self;
                (s, s.abs())
            }
            F64Exponent::Tables(t) => {
                if *self == 0.0 {
                    (0.0, 0.0)
                } else {
                    // a ≥ 0: a·|x| = |a·x|, one multiplication fewer
                    let s = t.pow_and_mul(self.abs(), *self).1;
                    (s, s.abs())
                }
            }
        }
    }
    /// One power: a = |x|^(q−1), then (a·x, a).
    #[inline(always)]
    fn spow_base_prepared(&self, q: &Exponent<f64>) -> (f64, f64) {
        match q.prepared() {
            F64Exponent::One => (*self, 1.0),
            F64Exponent::Two => (self.abs() * self, self.abs()),
            F64Exponent::Tables(t) => {
                if *self == 0.0 {
                    (0.0, 0.0)
                } else {
                    let (a, s) = t.pow_and_mul(self.abs(), *self);
                    (s, a)
                }
            }
        }
    }
    #[inline]
    fn lo(&self) -> f64 {
        *self
    }
    #[inline]
    fn hi(&self) -> f64 {
        *self
    }
    #[inline]
    fn mid(&self) -> f64 {
        *self
    }
}

/// The plain f64 sum, rounded to nearest term by term (as `s = s + a * b`).
#[derive(Clone, Copy, Debug, Default)]
pub struct F64Dot(f64);

impl Dot<f64> for F64Dot {
    #[inline]
    fn new() -> Self {
        Self(0.0)
    }
    #[inline]
    fn add_prod(&mut self, a: &f64, b: &f64) {
        self.0 += a * b;
    }
    #[inline]
    fn add_prod3(&mut self, f: &f64, a: &f64, b: &f64) {
        self.0 += f * a * b;
    }
    #[inline]
    fn sum(self) -> f64 {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::Scalar;
    use inari::Interval;

    /// |a − b| in units of 2⁻⁵³·|b|.
    fn rel(a: f64, b: f64) -> f64 {
        if b == 0.0 {
            a.abs()
        } else {
            ((a - b) / b).abs() / f64::EPSILON * 2.0
        }
    }

    #[test]
    fn f64_prepared_powers_are_the_powers_and_exact_for_q_1_and_2() {
        for q in [1.0, 2.0, 1.27, 1.31, 2.02, 3.15, 1.94, 0.8] {
            let e = Exponent::new(q);
            assert_eq!(*e.value(), q);
            for x in [-3.7, -1.0, -0.2, -1e-9, 0.0, 1e-300, 0.3, 1.0, 5.5, 1e30] {
                let base = if x == 0.0 {
                    0.0
                } else {
                    f64::abs(x).powf(q - 1.0)
                };
                let (s, a) = Real::spow_apow_prepared(&x, &e);
                let (s2, b) = Real::spow_base_prepared(&x, &e);
                let s3 = Real::spow_prepared(&x, &e);
                if q == 1.0 || q == 2.0 {
                    let (ws, wa, wb) = if q == 1.0 {
                        (x, x.abs(), 1.0)
                    } else {
                        (x.abs() * x, x * x, x.abs())
                    };
                    assert_eq!((s, a, s2, b, s3), (ws, wa, ws, wb, ws), "q = {q}, x = {x}");
                    continue;
                }
                // 12·2⁻⁵³ for the table, one more rounding for the product with x
                for (got, want) in [
                    (s, base * x),
                    (a, base * x.abs()),
                    (s2, base * x),
                    (s3, base * x),
                    (b, base),
                ] {
                    assert!(
                        rel(got, want) <= 16.0,
                        "q = {q}, x = {x}: {got:e} vs {want:e}"
                    );
                }
                assert!(a >= 0.0 && b >= 0.0 && s.signum() * x.signum() >= 0.0);
            }
        }
    }

    #[test]
    fn other_arithmetics_evaluate_with_q_itself() {
        let q = <Interval as Real>::parse_decimal("1.27").unwrap();
        let e = Exponent::new(q);
        for x in [
            inari::interval!(0.3, 0.4).unwrap(),
            inari::interval!(-0.2, 0.1).unwrap(),
            inari::interval!(-2.0, -1.5).unwrap(),
        ] {
            assert_eq!(Scalar::spow_prepared(&x, &e), Scalar::spow(&x, &q));
            assert_eq!(
                Scalar::spow_apow_prepared(&x, &e),
                Scalar::spow_apow(&x, &q)
            );
            assert_eq!(
                Scalar::spow_base_prepared(&x, &e),
                Scalar::spow_base(&x, &q)
            );
        }
    }
}
