//! The traits of a coefficient field: [`Real`], the [`Exponent`] its powers are prepared for,
//! and the [`Dot`] accumulator of its sums of products.
//!
//! A [`Real`] is a number that can stand for a parameter of a model (B, Γ, κ, σ, n, p) or for a
//! Taylor coefficient. Every operation of an interval implementation must enclose the exact
//! real result for every point of its arguments; the `f64` implementation rounds to nearest.
//! The implementations live in the families below this folder: [`super::float`] (`f64`),
//! [`super`] (inari intervals, their ulp kernels), [`super::jet`] (series, duals).

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
    /// The accumulator of Σ aⱼ·bⱼ (see [`Dot`]): for intervals, one enclosure of the
    /// whole sum instead of a rounded operation per term.
    type Dot: Dot<Self>;
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
    /// The other power of a pair of the same x and q (a tape's `Twin`): |x|^(q−1)x when
    /// `signed`, else |x|^q, given `other`, the pair's other power already computed. The
    /// default computes it anew (tightest for intervals); a type that knows the sign s of x
    /// for certain may return s·other (the two differ by that factor exactly).
    fn twin_pow(&self, q: &Self, other: &Self, signed: bool) -> Self {
        let _ = other;
        if signed { self.spow(q) } else { self.apow(q) }
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
    /// tables (a few ulps from `spow`, see [`crate::arith::float::fastpow`]).
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
    /// True when every value of `o` is a value of `self`, decided exactly. The default, from
    /// [`Real::lo`] and [`Real::hi`], is exact where those are the ends themselves (f64, f64
    /// intervals); a type whose ends are finer than f64 decides on its own ends
    /// ([`crate::arith::mpfr::Mpi`]), and one that cannot tell says false.
    fn encloses(&self, o: &Self) -> bool {
        self.lo() <= o.lo() && o.hi() <= self.hi()
    }
    /// True when `o` is the same number of the type as `self`, decided exactly: the same ends
    /// of an interval (an MPFR interval's own ends: two whose f64 bounds coincide may differ),
    /// the same value and derivative parts of a dual. What a cache keyed by a number compares
    /// (the factor tables of the tape's power recurrences). The default: each encloses the
    /// other ([`Real::encloses`]).
    fn identical(&self, o: &Self) -> bool {
        self.encloses(o) && o.encloses(self)
    }
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

// ---- exponents ----

/// A parameter q used as a power exponent, with its [`Real::Prepared`] data.
#[derive(Clone, Debug)]
pub struct Exponent<R: Real> {
    q: R,
    prepared: R::Prepared,
}

impl<R: Real> Exponent<R> {
    pub fn new(q: R) -> Self {
        let prepared = R::prepare_exponent(&q);
        Self { q, prepared }
    }

    /// q itself.
    #[inline]
    pub fn value(&self) -> &R {
        &self.q
    }

    /// What the arithmetic precomputed for q.
    #[inline]
    pub fn prepared(&self) -> &R::Prepared {
        &self.prepared
    }
}

// ---- sums of products ----

/// An accumulator of Σ aⱼ·bⱼ over a number type `R`.
pub trait Dot<R>: Sized {
    /// The empty sum.
    fn new() -> Self;
    /// Adds a·b.
    fn add_prod(&mut self, a: &R, b: &R);
    /// Adds f·a·b for a constant f of the type (a factor of a recurrence, such as the power
    /// recurrence's q(k − j) − j). Accumulators of interval types override it to take the
    /// three-way product in one pass (no directed rounding of f·a).
    #[inline]
    fn add_prod3(&mut self, f: &R, a: &R, b: &R)
    where
        R: Real,
    {
        self.add_prod(&a.mul_constant(f), b);
    }
    /// Adds c·x for a constant c of the type (a tape constant: for a dual, one with a zero
    /// derivative part). Accumulators whose general product is costly override it.
    #[inline]
    fn add_scaled(&mut self, c: &R, x: &R) {
        self.add_prod(c, x);
    }
    /// The sum (for an interval type: an enclosure of the exact sum of the exact products).
    fn sum(self) -> R;
}

/// A sum of products in a type's own arithmetic (for types without a faster accumulator).
#[derive(Clone, Debug)]
pub struct PlainDot<R>(Option<R>);

impl<R: Real> Dot<R> for PlainDot<R> {
    fn new() -> Self {
        Self(None)
    }
    fn add_prod(&mut self, a: &R, b: &R) {
        let p = a.clone() * b.clone();
        self.0 = Some(match self.0.take() {
            Some(s) => s + p,
            None => p,
        });
    }
    fn add_scaled(&mut self, c: &R, x: &R) {
        let p = x.mul_constant(c);
        self.0 = Some(match self.0.take() {
            Some(s) => s + p,
            None => p,
        });
    }
    fn sum(self) -> R {
        self.0.unwrap_or_else(R::zero)
    }
}

/// Refuses what is not a plain decimal literal (digits, '.', signs, an exponent), before an
/// interval type encloses it: "\[1,2\]", "inf" or "" are not parameters. `t` is trimmed.
pub fn check_plain_decimal(t: &str) -> Result<(), String> {
    let ok = !t.is_empty()
        && t.chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E'));
    if ok {
        Ok(())
    } else {
        Err(format!("'{t}' is not a decimal number"))
    }
}
