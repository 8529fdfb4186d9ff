//! The number trait of coefficient fields: `f64`, inari `Interval` (and later MPFR intervals).
//!
//! A [`Real`] is a number that can stand for a parameter of a model (B, Γ, κ, σ, n, p) or for a
//! Taylor coefficient. Every operation of an interval implementation must enclose the exact
//! real result for every point of its arguments; the `f64` implementation rounds to nearest.

use super::exponent::Exponent;
use super::fastpow::Power;
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A field of numbers the models can be evaluated over.
///
/// | method | meaning | domain |
/// |---|---|---|
/// | `pow(y)` | x^y | x > 0 (x ≥ 0 when y > 0) |
/// | `spow(q)` | signed power \|x\|^(q−1)·x | q > 0 (0 at x = 0) |
/// | `apow(q)` | \|x\|^q | q ≥ 1 |
pub trait Real:
    Clone
    + Debug
    + Send
    + Sync
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + 'static
{
    /// The accumulator of Σ aⱼ·bⱼ (see [`super::dot`]): for intervals, one enclosure of the
    /// whole sum instead of a rounded operation per term.
    type Dot: super::dot::Dot<Self>;
    /// A small integer, exactly (|k| ≤ 2^53).
    fn from_int(k: i64) -> Self;
    /// An `f64` that is *exactly* the intended value (a grid point, a value computed in f64 on
    /// purpose). Never use it for a decimal the user wrote: see [`Real::parse_decimal`].
    fn from_exact_f64(x: f64) -> Self;
    /// The decimal literal `s` (e.g. `"0.632"`, `"1e-3"`) or a range `"a..b"`, enclosed as
    /// written: for intervals the tightest enclosure of the decimal value (of the whole range),
    /// for `f64` the nearest double (a range is refused).
    fn parse_decimal(s: &str) -> Result<Self, String>;
    fn zero() -> Self {
        Self::from_int(0)
    }
    fn one() -> Self {
        Self::from_int(1)
    }
    /// k·x for a small integer k (|k| ≤ 2^53). Types whose general product is costly override
    /// it (a dual: k·v + Σ k·dᵢ εᵢ, since the constant k has no derivative part).
    #[inline]
    fn mul_int(&self, k: i64) -> Self {
        self.clone() * Self::from_int(k)
    }
    /// x/k for a small non-zero integer k (|k| ≤ 2^53); overridden like [`Real::mul_int`].
    #[inline]
    fn div_int(&self, k: i64) -> Self {
        self.clone() / Self::from_int(k)
    }
    /// x·c for a constant c of the type (for a dual: one with a zero derivative part, such as
    /// a tape constant). Types whose general product is costly override it (a dual:
    /// c·v + Σ c·dᵢ εᵢ); the result is the same as `x * c`.
    #[inline]
    fn mul_constant(&self, c: &Self) -> Self {
        self.clone() * c.clone()
    }
    fn abs(&self) -> Self;
    fn sqrt(&self) -> Self;
    /// ln x for x > 0 (for an interval reaching 0 or below: every real).
    fn ln(&self) -> Self;
    /// sign(x): 1 for x > 0, −1 for x < 0; at 0 the interval types give [−1, 1] (the Clarke
    /// derivative of |x|), `f64` NaN (no derivative).
    fn sgn(&self) -> Self;
    /// ∂/∂q of the power: |w|^q·ln|w| (`signed`: |w|^(q−1)w·ln|w|), q ≥ 1; 0 at w = 0 (its
    /// limit). The default multiplies the power by ln|w| (every real where w reaches 0);
    /// intervals bound it there (|y^q ln y| ≤ 1/(e q) for y ≤ 1).
    fn pow_ln(w: &Self, q: &Self, signed: bool) -> Self {
        let u = if signed { w.spow(q) } else { w.apow(q) };
        u * w.abs().ln()
    }
    /// x^y for x > 0.
    fn pow(&self, y: &Self) -> Self;
    /// The signed power |x|^(q−1)·x, q ≥ 1 (the Hertzian law's nonlinearity).
    fn spow(&self, q: &Self) -> Self;
    /// |x|^q, q ≥ 1.
    fn apow(&self, q: &Self) -> Self;
    /// (|x|^(q−1)x, |x|^q) at once. The default computes each (tightest for intervals); `f64`
    /// shares one power evaluation.
    fn spow_apow(&self, q: &Self) -> (Self, Self) {
        (self.spow(q), self.apow(q))
    }
    /// (|x|^(q−1)x, |x|^(q−1)) at once, for q > 1.
    fn spow_base(&self, q: &Self) -> (Self, Self) {
        (self.spow(q), self.apow(&(q.clone() - Self::one())))
    }
    /// What an [`Exponent`] precomputes for q: the `f64` engine's power tables, `()` for
    /// types whose powers need nothing.
    type Prepared: Clone + Debug + Send + Sync;
    fn prepare_exponent(q: &Self) -> Self::Prepared;
    /// `spow` with a prepared exponent. The default is `spow(q.value())`; `f64` reads its
    /// tables (a few ulps from `spow`, see [`super::fastpow`]).
    #[inline]
    fn spow_prepared(&self, q: &Exponent<Self>) -> Self {
        self.spow(q.value())
    }
    /// `spow_apow` with a prepared exponent (default: `spow_apow(q.value())`).
    #[inline]
    fn spow_apow_prepared(&self, q: &Exponent<Self>) -> (Self, Self) {
        self.spow_apow(q.value())
    }
    /// `spow_base` with a prepared exponent (default: `spow_base(q.value())`).
    #[inline]
    fn spow_base_prepared(&self, q: &Exponent<Self>) -> (Self, Self) {
        self.spow_base(q.value())
    }
    /// Lower bound of the value (the value itself for `f64`).
    fn lo(&self) -> f64;
    /// Upper bound of the value (the value itself for `f64`).
    fn hi(&self) -> f64;
    /// A representative point (the midpoint for intervals).
    fn mid(&self) -> f64;
    /// True when the value is a finite number (or a bounded, non-empty interval).
    fn is_finite(&self) -> bool {
        self.lo().is_finite() && self.hi().is_finite()
    }
    /// +1 or −1 when every value is > 0 or < 0; `None` when the sign is not certain (0 included).
    fn sign(&self) -> Option<i8> {
        if self.lo() > 0.0 {
            Some(1)
        } else if self.hi() < 0.0 {
            Some(-1)
        } else {
            None
        }
    }
    /// A value that encloses every real (NaN for `f64`): the honest result of an expansion
    /// that does not exist.
    fn unbounded() -> Self;
    /// True when every value is an integer k with known parity (used to pick the analytic
    /// branch: |x|^(q−1)x = x^q for odd integer q, |x|^q = x^q for even integer q).
    fn as_integer(&self) -> Option<i64> {
        let (l, h) = (self.lo(), self.hi());
        if l == h && l.fract() == 0.0 && l.abs() < 1e15 {
            Some(l as i64)
        } else {
            None
        }
    }
}

/// A prepared exponent q of the `f64` engine: |x|^(q−1) exactly for q = 1 and q = 2,
/// otherwise by q − 1's tables ([`super::fastpow`], a few ulps).
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
    type Dot = super::dot::F64Dot;
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
