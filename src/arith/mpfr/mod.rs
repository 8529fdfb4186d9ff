//! [`Mpi<BITS>`]: intervals over MPFR floats (`rug::Float`) at a precision fixed by the type.
//!
//! The coefficient field of the rigorous engine at a chosen precision (`bwcl cor --rigorous
//! --digits D`, issue #15): the engine's algorithm is generic over [`Real`], and `Mpi<BITS>`
//! is its arithmetic when f64 intervals are too narrow a field (widths ≤ 1e−30 or 1e−60, cases
//! f64 cannot decide). The lead picks the tiers it is instantiated at (e.g. 128, 256, 384 bits);
//! the precision is the const parameter, so runs at different precisions share threads (no
//! global or thread-local precision).
//!
//! Rounding: both ends are `rug::Float`s of precision `BITS`. Every operation computes its lower
//! end with MPFR's correctly rounded operation in `Round::Down` (towards −∞) and its upper end in
//! `Round::Up` (towards +∞), never to nearest, so that the result encloses the exact real result
//! for every point of the arguments. Monotone functions (sqrt, ln, exp) take their ends from the
//! operand's ends; x^y is monotone in each argument on each side of x = 1, so its ends are at
//! corners of the box (which ones: from the signs of y and ln x, [`Mpi::pow`]). 0·∞ is 0 (the
//! operands are sets of reals); a divisor containing 0 gives [−∞, +∞].
//!
//! The empty interval has NaN ends ([`Mpi::is_empty`]); an interval never has the end −∞ on the
//! right or +∞ on the left. Decimal input is enclosed as written (exact value by `rug::Rational`,
//! rounded outward once); printed ends are rounded outward ([`Mpi::to_decimal`]).

mod enclosure;

use crate::arith::real::{PlainDot, Real};
use inari::Interval;
use rug::float::{Round, Special};
use rug::ops::{AddAssignRound, DivAssignRound, NegAssign, Pow, SubAssignRound};
use rug::{Float, Integer, Rational};
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

const DOWN: Round = Round::Down;
const UP: Round = Round::Up;

/// A decimal exponent beyond ±10⁶ is refused (the exact value as a rational would be costly).
const MAX_EXP10: i64 = 1_000_000;

/// An interval [lo, hi] of MPFR floats of precision `BITS` (or empty: NaN ends).
#[derive(Clone, Debug)]
pub struct Mpi<const BITS: u32> {
    lo: Float,
    hi: Float,
}

/// v rounded to `prec` bits in direction `r`.
#[inline]
fn rnd<T>(prec: u32, v: T, r: Round) -> Float
where
    Float: rug::ops::AssignRound<T, Round = Round, Ordering = Ordering>,
{
    Float::with_val_round(prec, v, r).0
}

/// a·b rounded by `r`, with 0·(±∞) = 0 (an end 0 times any real is 0).
#[inline]
fn mul_end(prec: u32, a: &Float, b: &Float, r: Round) -> Float {
    if a.is_zero() || b.is_zero() {
        Float::new(prec)
    } else {
        rnd(prec, a * b, r)
    }
}

/// The smaller / larger of two floats (neither NaN).
fn fmin(a: Float, b: Float) -> Float {
    if b < a { b } else { a }
}
fn fmax(a: Float, b: Float) -> Float {
    if b > a { b } else { a }
}

/// The exact value of a decimal literal: an optional sign, digits with at most one point (at
/// least one digit), an optional exponent `e`/`E` with optional sign and digits.
pub fn decimal_value(t: &str) -> Result<Rational, String> {
    let bad = || format!("'{t}' is not a decimal number");
    let (mant, exp) = match t.find(['e', 'E']) {
        Some(i) => (&t[..i], Some(&t[i + 1..])),
        None => (t, None),
    };
    let (neg, mant) = match mant.as_bytes().first() {
        Some(b'-') => (true, &mant[1..]),
        Some(b'+') => (false, &mant[1..]),
        _ => (false, mant),
    };
    let (ip, fp) = mant.split_once('.').unwrap_or((mant, ""));
    let digits = |s: &str| s.bytes().all(|c| c.is_ascii_digit());
    if ip.is_empty() && fp.is_empty() || !digits(ip) || !digits(fp) {
        return Err(bad());
    }
    // the exponent, saturated (a long exponent of a zero is still zero)
    let e: i64 = match exp {
        None => 0,
        Some(s) => {
            let (eneg, d) = match s.as_bytes().first() {
                Some(b'-') => (true, &s[1..]),
                Some(b'+') => (false, &s[1..]),
                _ => (false, s),
            };
            if d.is_empty() || !digits(d) {
                return Err(bad());
            }
            let m = d.parse::<i64>().unwrap_or(i64::MAX / 4).min(i64::MAX / 4);
            if eneg { -m } else { m }
        }
    };
    let all = format!("{ip}{fp}");
    let m = Integer::from_str_radix(&all, 10).map_err(|_| bad())?;
    if m == 0 {
        return Ok(Rational::new());
    }
    let e10 = e - fp.len() as i64;
    if e10.abs() > MAX_EXP10 {
        return Err(format!(
            "'{t}' is out of range (a decimal exponent beyond ±{MAX_EXP10})"
        ));
    }
    let p = Integer::from(10).pow(e10.unsigned_abs() as u32);
    let m = if neg { -m } else { m };
    Ok(if e10 >= 0 {
        Rational::from(m * p)
    } else {
        Rational::from((m, p))
    })
}

/// `x` in scientific notation with `digits` significant digits, rounded by `r`
/// (e.g. "6.25e4", "-1.0e-3").
fn scientific(x: &Float, digits: usize, r: Round) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    if x.is_infinite() {
        return if x.is_sign_negative() { "-inf" } else { "inf" }.into();
    }
    if x.is_zero() {
        return "0".into();
    }
    let (neg, s, exp) = x.to_sign_string_exp_round(10, Some(digits.max(1)), r);
    let exp = exp.expect("a finite non-zero float has an exponent") as i64 - 1;
    let sign = if neg { "-" } else { "" };
    let (first, rest) = s.split_at(1);
    if rest.is_empty() {
        format!("{sign}{first}e{exp}")
    } else {
        format!("{sign}{first}.{rest}e{exp}")
    }
}

impl<const B: u32> Mpi<B> {
    /// [lo, hi] from ends already at precision B and rounded outward; empty when not an
    /// interval of reals (a NaN end, lo > hi, lo = +∞ or hi = −∞).
    #[inline]
    fn checked(lo: Float, hi: Float) -> Self {
        let ok = lo <= hi && !(lo.is_infinite() && lo > 0) && !(hi.is_infinite() && hi < 0);
        if ok { Self { lo, hi } } else { Self::empty() }
    }

    /// [lo, hi] with the ends rounded to B bits outward (empty if not lo ≤ hi).
    pub fn new(mut lo: Float, mut hi: Float) -> Self {
        lo.set_prec_round(B, DOWN);
        hi.set_prec_round(B, UP);
        Self::checked(lo, hi)
    }

    /// The tightest interval at B bits containing x (x itself when representable).
    pub fn point(x: &Float) -> Self {
        Self::checked(rnd(B, x, DOWN), rnd(B, x, UP))
    }

    /// The empty set (NaN ends).
    pub fn empty() -> Self {
        Self {
            lo: Float::with_val(B, Special::Nan),
            hi: Float::with_val(B, Special::Nan),
        }
    }

    /// [−∞, +∞].
    pub fn entire() -> Self {
        Self {
            lo: Float::with_val(B, Special::NegInfinity),
            hi: Float::with_val(B, Special::Infinity),
        }
    }

    #[inline]
    pub fn is_empty(&self) -> bool {
        self.lo.is_nan()
    }

    /// The lower end (NaN when empty).
    #[inline]
    pub fn inf(&self) -> &Float {
        &self.lo
    }

    /// The upper end (NaN when empty).
    #[inline]
    pub fn sup(&self) -> &Float {
        &self.hi
    }

    /// The same set (exact for B ≥ 53, else rounded outward).
    pub fn from_interval(x: Interval) -> Self {
        if x.is_empty() {
            return Self::empty();
        }
        Self::checked(rnd(B, x.inf(), DOWN), rnd(B, x.sup(), UP))
    }

    /// The tightest f64 interval containing self.
    pub fn to_interval(&self) -> Interval {
        if self.is_empty() {
            return Interval::EMPTY;
        }
        Interval::try_from((self.lo.to_f64_round(DOWN), self.hi.to_f64_round(UP)))
            .unwrap_or(Interval::ENTIRE)
    }

    /// The smallest interval containing both.
    pub fn hull(&self, o: &Self) -> Self {
        if self.is_empty() {
            return o.clone();
        }
        if o.is_empty() {
            return self.clone();
        }
        Self {
            lo: fmin(self.lo.clone(), o.lo.clone()),
            hi: fmax(self.hi.clone(), o.hi.clone()),
        }
    }

    /// The common part (empty when disjoint).
    pub fn intersection(&self, o: &Self) -> Self {
        if self.is_empty() || o.is_empty() {
            return Self::empty();
        }
        Self::checked(
            fmax(self.lo.clone(), o.lo.clone()),
            fmin(self.hi.clone(), o.hi.clone()),
        )
    }

    /// self ⊆ o (the empty set is a subset of every interval).
    pub fn subset(&self, o: &Self) -> bool {
        self.is_empty() || !o.is_empty() && o.lo <= self.lo && self.hi <= o.hi
    }

    /// self lies strictly inside o at both ends (IEEE 1788: an infinite end of o may equal
    /// self's; the empty set is interior to every interval).
    pub fn interior(&self, o: &Self) -> bool {
        if self.is_empty() {
            return true;
        }
        if o.is_empty() {
            return false;
        }
        let left = o.lo < self.lo || o.lo.is_infinite() && o.lo < 0;
        let right = self.hi < o.hi || o.hi.is_infinite() && o.hi > 0;
        left && right
    }

    /// lo ≤ x ≤ hi.
    pub fn contains(&self, x: &Float) -> bool {
        self.lo <= *x && *x <= self.hi
    }

    /// A point at B bits inside self, the nearest to its midpoint ([−∞, +∞]: 0; a half-line:
    /// its finite end; empty: empty).
    pub fn mid_point(&self) -> Self {
        if self.is_empty() {
            return Self::empty();
        }
        let m = match (self.lo.is_finite(), self.hi.is_finite()) {
            (true, true) => {
                // RN(lo + hi)/2 = RN((lo + hi)/2) (halving is exact); clamped in case of overflow
                let mut m = Float::with_val(B, &self.lo + &self.hi);
                m /= 2u32;
                fmin(fmax(m, self.lo.clone()), self.hi.clone())
            }
            (false, false) => Float::new(B),
            (true, false) => self.lo.clone(),
            (false, true) => self.hi.clone(),
        };
        Self {
            lo: m.clone(),
            hi: m,
        }
    }

    /// An upper bound of hi − lo (NaN when empty).
    pub fn wid_f64(&self) -> f64 {
        rnd(53, &self.hi - &self.lo, UP).to_f64_round(UP)
    }

    /// An upper bound of (hi − lo)/2 (NaN when empty).
    pub fn rad_f64(&self) -> f64 {
        let mut w = rnd(53, &self.hi - &self.lo, UP);
        w.div_assign_round(2u32, UP);
        w.to_f64_round(UP)
    }

    /// An upper bound of max |x| over self (NaN when empty).
    pub fn mag_f64(&self) -> f64 {
        if self.is_empty() {
            return f64::NAN;
        }
        let (a, b) = (self.lo.to_f64_round(DOWN), self.hi.to_f64_round(UP));
        (-a).max(b)
    }

    /// A lower bound of min |x| over self (NaN when empty).
    pub fn mig_f64(&self) -> f64 {
        if self.is_empty() {
            f64::NAN
        } else if self.lo > 0 {
            self.lo.to_f64_round(DOWN)
        } else if self.hi < 0 {
            -self.hi.to_f64_round(UP)
        } else {
            0.0
        }
    }

    /// x² (tighter than x·x across 0).
    pub fn sqr(&self) -> Self {
        if self.is_empty() {
            return Self::empty();
        }
        let (lo, hi) = if self.lo >= 0 {
            (
                rnd(B, self.lo.square_ref(), DOWN),
                rnd(B, self.hi.square_ref(), UP),
            )
        } else if self.hi <= 0 {
            (
                rnd(B, self.hi.square_ref(), DOWN),
                rnd(B, self.lo.square_ref(), UP),
            )
        } else {
            let m = if -self.lo.clone() > self.hi {
                &self.lo
            } else {
                &self.hi
            };
            (Float::new(B), rnd(B, m.square_ref(), UP))
        };
        Self { lo, hi }
    }

    /// e^x.
    pub fn exp(&self) -> Self {
        if self.is_empty() {
            return Self::empty();
        }
        Self::checked(
            rnd(B, self.lo.exp_ref(), DOWN),
            rnd(B, self.hi.exp_ref(), UP),
        )
    }

    /// The ends as scientific decimals with `digits` significant digits, lo rounded down and
    /// hi rounded up (printed bounds are bounds); "NaN" for an empty interval.
    pub fn to_decimal(&self, digits: usize) -> (String, String) {
        (
            scientific(&self.lo, digits, DOWN),
            scientific(&self.hi, digits, UP),
        )
    }

    /// The product, from the operands' sign classes (two products, four across 0 × across 0).
    fn mul_ref(&self, o: &Self) -> Self {
        if self.is_empty() || o.is_empty() {
            return Self::empty();
        }
        let (a, b, c, d) = (&self.lo, &self.hi, &o.lo, &o.hi);
        let m = |x: &Float, y: &Float, r: Round| mul_end(B, x, y, r);
        let (lo, hi) = if *a >= 0 {
            if *c >= 0 {
                (m(a, c, DOWN), m(b, d, UP))
            } else if *d <= 0 {
                (m(b, c, DOWN), m(a, d, UP))
            } else {
                (m(b, c, DOWN), m(b, d, UP))
            }
        } else if *b <= 0 {
            if *c >= 0 {
                (m(a, d, DOWN), m(b, c, UP))
            } else if *d <= 0 {
                (m(b, d, DOWN), m(a, c, UP))
            } else {
                (m(a, d, DOWN), m(a, c, UP))
            }
        } else if *c >= 0 {
            (m(a, d, DOWN), m(b, d, UP))
        } else if *d <= 0 {
            (m(b, c, DOWN), m(a, c, UP))
        } else {
            (
                fmin(m(a, d, DOWN), m(b, c, DOWN)),
                fmax(m(a, c, UP), m(b, d, UP)),
            )
        };
        Self { lo, hi }
    }

    /// The quotient; [−∞, +∞] when the divisor contains 0.
    fn div_ref(&self, o: &Self) -> Self {
        if self.is_empty() || o.is_empty() {
            return Self::empty();
        }
        let (a, b, c, d) = (&self.lo, &self.hi, &o.lo, &o.hi);
        let q = |x: &Float, y: &Float, r: Round| rnd(B, x / y, r);
        let (lo, hi) = if *c > 0 {
            if *a >= 0 {
                (q(a, d, DOWN), q(b, c, UP))
            } else if *b <= 0 {
                (q(a, c, DOWN), q(b, d, UP))
            } else {
                (q(a, c, DOWN), q(b, c, UP))
            }
        } else if *d < 0 {
            if *a >= 0 {
                (q(b, d, DOWN), q(a, c, UP))
            } else if *b <= 0 {
                (q(b, c, DOWN), q(a, d, UP))
            } else {
                (q(b, d, DOWN), q(a, d, UP))
            }
        } else {
            return Self::entire();
        };
        Self { lo, hi }
    }

    /// x^y for x ⊆ [0, +∞]. x^y = e^(y ln x) and y·ln x is bilinear, so the ends are at corners
    /// of the box: the lower one where y·ln x is least (by the signs of y and ln x), the upper
    /// one where it is greatest. MPFR's conventions at the corners (0^0 = 1, 0^(y<0) = +∞,
    /// ∞^(y<0) = 0, 1^y = 1) are the limits along the box, so the ends remain bounds there.
    fn power(&self, y: &Self) -> Self {
        if self.is_empty() || y.is_empty() {
            return Self::empty();
        }
        // a zero end as +0: MPFR's (−0)^y is −∞ for an odd integer y < 0 (−0 arises as an
        // exact zero rounded down, e.g. x − x)
        let pos = |x: &Float| {
            if x.is_zero() {
                Float::new(B)
            } else {
                x.clone()
            }
        };
        let (a, b) = (&pos(&self.lo), &pos(&self.hi));
        let (c, d) = (&y.lo, &y.hi);
        let p = |x: &Float, e: &Float, r: Round| rnd(B, x.pow(e), r);
        let lo = if *c >= 0 {
            p(a, if *a >= 1 { c } else { d }, DOWN)
        } else if *d <= 0 {
            p(b, if *b >= 1 { c } else { d }, DOWN)
        } else {
            fmin(p(b, c, DOWN), p(a, d, DOWN))
        };
        let hi = if *c >= 0 {
            p(b, if *b >= 1 { d } else { c }, UP)
        } else if *d <= 0 {
            p(a, if *a >= 1 { d } else { c }, UP)
        } else {
            fmax(p(a, c, UP), p(b, d, UP))
        };
        Self::checked(lo, hi)
    }

    /// An end of |x|^(q−1)·x over x = a and every q in `q` (lower or upper).
    fn spow_at(a: &Float, q: &Self, upper: bool) -> Float {
        let m = Self::point(&Float::with_val(B, a.abs_ref())).power(q);
        match (*a >= 0, upper) {
            (true, false) => m.lo,
            (true, true) => m.hi,
            (false, false) => -m.hi,
            (false, true) => -m.lo,
        }
    }

    /// The greater of |lo| and |hi| (exact).
    fn mag(&self) -> Float {
        fmax(Float::with_val(B, self.lo.abs_ref()), self.hi.clone())
    }
}

/// Encloses a decimal literal exactly as written (tightest at B bits).
pub fn enclose_decimal<const B: u32>(s: &str) -> Result<Mpi<B>, String> {
    let t = s.trim();
    crate::arith::real::check_plain_decimal(t)?;
    let r = decimal_value(t)?;
    let x = Mpi::<B>::checked(rnd(B, &r, DOWN), rnd(B, &r, UP));
    if !x.is_finite() {
        return Err(format!("'{t}' is not a finite number"));
    }
    Ok(x)
}

/// Encloses `"a"` or the range `"a..b"` (every value between the two decimals).
pub fn enclose_decimal_or_range<const B: u32>(s: &str) -> Result<Mpi<B>, String> {
    let t = s.trim();
    match t.split_once("..") {
        None => enclose_decimal(t),
        Some((a, b)) => {
            let (a, b) = (enclose_decimal::<B>(a)?, enclose_decimal::<B>(b)?);
            if a.lo > b.hi {
                return Err(format!(
                    "the range '{t}' is empty (its start exceeds its end)"
                ));
            }
            Ok(a.hull(&b))
        }
    }
}

impl<const B: u32> Add for Mpi<B> {
    type Output = Self;
    #[inline]
    fn add(mut self, o: Self) -> Self {
        self.lo.add_assign_round(&o.lo, DOWN);
        self.hi.add_assign_round(&o.hi, UP);
        self
    }
}

impl<const B: u32> Sub for Mpi<B> {
    type Output = Self;
    #[inline]
    fn sub(mut self, o: Self) -> Self {
        self.lo.sub_assign_round(&o.hi, DOWN);
        self.hi.sub_assign_round(&o.lo, UP);
        self
    }
}

impl<const B: u32> Mul for Mpi<B> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        self.mul_ref(&o)
    }
}

impl<const B: u32> Div for Mpi<B> {
    type Output = Self;
    #[inline]
    fn div(self, o: Self) -> Self {
        self.div_ref(&o)
    }
}

impl<const B: u32> Neg for Mpi<B> {
    type Output = Self;
    #[inline]
    fn neg(mut self) -> Self {
        std::mem::swap(&mut self.lo, &mut self.hi);
        self.lo.neg_assign();
        self.hi.neg_assign();
        self
    }
}

/// "[lo, hi]" with about B·log₁₀2 significant digits, rounded outward.
impl<const B: u32> fmt::Display for Mpi<B> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let digits = (B as f64 * std::f64::consts::LOG10_2) as usize + 1;
        let (lo, hi) = self.to_decimal(digits);
        write!(f, "[{lo}, {hi}]")
    }
}

impl<const B: u32> Real for Mpi<B> {
    type Dot = PlainDot<Self>;
    type Prepared = ();
    fn prepare_exponent(_: &Self) {}
    fn from_int(k: i64) -> Self {
        Self::checked(rnd(B, k, DOWN), rnd(B, k, UP))
    }
    /// x itself (rounded outward if B < 53); empty for a non-finite x.
    fn from_exact_f64(x: f64) -> Self {
        if !x.is_finite() {
            return Self::empty();
        }
        Self::checked(rnd(B, x, DOWN), rnd(B, x, UP))
    }
    fn parse_decimal(s: &str) -> Result<Self, String> {
        enclose_decimal_or_range(s)
    }
    fn mul_int(&self, k: i64) -> Self {
        if self.is_empty() {
            return Self::empty();
        }
        if k == 0 {
            return Self::from_int(0);
        }
        let (a, b) = if k > 0 {
            (&self.lo, &self.hi)
        } else {
            (&self.hi, &self.lo)
        };
        Self {
            lo: rnd(B, a * k, DOWN),
            hi: rnd(B, b * k, UP),
        }
    }
    /// x/k; [−∞, +∞] for k = 0.
    fn div_int(&self, k: i64) -> Self {
        if self.is_empty() {
            return Self::empty();
        }
        if k == 0 {
            return Self::entire();
        }
        let (a, b) = if k > 0 {
            (&self.lo, &self.hi)
        } else {
            (&self.hi, &self.lo)
        };
        Self {
            lo: rnd(B, a / k, DOWN),
            hi: rnd(B, b / k, UP),
        }
    }
    /// The product without cloning the operands.
    fn mul_constant(&self, c: &Self) -> Self {
        self.mul_ref(c)
    }
    fn abs(&self) -> Self {
        if self.is_empty() || self.lo >= 0 {
            self.clone()
        } else if self.hi <= 0 {
            -self.clone()
        } else {
            Self {
                lo: Float::new(B),
                hi: self.mag(),
            }
        }
    }
    /// √x over x ≥ 0 (the part below 0 is outside the domain; empty if x < 0).
    fn sqrt(&self) -> Self {
        if self.is_empty() || self.hi < 0 {
            return Self::empty();
        }
        let lo = if self.lo <= 0 {
            Float::new(B)
        } else {
            rnd(B, self.lo.sqrt_ref(), DOWN)
        };
        Self {
            lo,
            hi: rnd(B, self.hi.sqrt_ref(), UP),
        }
    }
    /// ln x; [−∞, +∞] when x reaches 0 or below.
    fn ln(&self) -> Self {
        if self.is_empty() {
            return Self::empty();
        }
        if self.lo <= 0 {
            return Self::entire();
        }
        Self::checked(rnd(B, self.lo.ln_ref(), DOWN), rnd(B, self.hi.ln_ref(), UP))
    }
    /// Away from 0 the product; where |w| reaches 0, g(y) = y^q ln y over y ∈ [0, |w|]:
    /// g ≥ −1/(e q) (its minimum, at y = e^(−1/q)), g ≤ 0 for y ≤ 1 and g ≤ |w|^q ln|w| above
    /// (as for `Interval`).
    fn pow_ln(w: &Self, q: &Self, signed: bool) -> Self {
        if w.is_empty() || q.is_empty() {
            return Self::empty();
        }
        if w.lo > 0 || w.hi < 0 {
            let u = if signed { w.spow(q) } else { w.apow(q) };
            return u * Real::abs(w).ln();
        }
        if q.lo < 1 || !w.is_finite() {
            return Self::entire();
        }
        let m = Self::point(&w.mag());
        let ql = Self::point(&q.lo);
        // g decreases on [0, e^(−1/q)] ⊇ [0, 0.3678] (q ≥ 1): below it the minimum is g(m),
        // most negative for the smallest q (m^q decreases in q); else −1/(e q_lo)
        let lo = if m.hi <= 0.3678 {
            let g = m.power(&ql) * m.ln();
            fmin(g.lo, Float::new(B))
        } else {
            let mut t = Float::with_val(B, -1);
            t.exp_round(UP);
            t.div_assign_round(&q.lo, UP);
            -t
        };
        let hi = if m.lo > 1 {
            (m.power(&Self::point(&q.hi)) * m.ln()).hi
        } else {
            Float::new(B)
        };
        let g = Self::checked(lo, hi);
        if signed {
            let a = g.mag();
            Self {
                lo: -a.clone(),
                hi: a,
            }
        } else {
            g
        }
    }
    fn sgn(&self) -> Self {
        if self.is_empty() {
            Self::empty()
        } else if self.lo > 0 {
            Self::from_int(1)
        } else if self.hi < 0 {
            Self::from_int(-1)
        } else {
            Self::checked(Float::with_val(B, -1), Float::with_val(B, 1))
        }
    }
    /// x^y for x ≥ 0; [−∞, +∞] when x reaches below 0.
    fn pow(&self, y: &Self) -> Self {
        if self.is_empty() || y.is_empty() {
            return Self::empty();
        }
        if self.lo < 0 {
            return Self::entire();
        }
        self.power(y)
    }
    fn spow(&self, q: &Self) -> Self {
        if self.is_empty() || q.is_empty() {
            return Self::empty();
        }
        match q.as_integer() {
            Some(1) => return self.clone(),
            Some(2) => return Real::abs(self).mul_ref(self),
            _ => {}
        }
        // one sign: ±|x|^q
        if self.lo >= 0 {
            return self.power(q);
        }
        if self.hi <= 0 {
            return -(-self.clone()).power(q);
        }
        // |x|^(q−1)x is increasing in x for q > 0: evaluate at the ends
        if !self.lo.is_finite() || !self.hi.is_finite() {
            return Self::entire();
        }
        Self::checked(
            Self::spow_at(&self.lo, q, false),
            Self::spow_at(&self.hi, q, true),
        )
    }
    /// |x|^q; with q reaching 0 the corners give [0, max(1, |x|^q)] (0^0 = 1, as the limit
    /// from q > 0 along x = 0 is 0 and along q = 0 is 1: both ends are in).
    fn apow(&self, q: &Self) -> Self {
        if self.is_empty() || q.is_empty() {
            return Self::empty();
        }
        match q.as_integer() {
            // |x|^0 = 1 (the factor |z|^(n−1) of n = 1)
            Some(0) => return Self::from_int(1),
            Some(1) => return Real::abs(self),
            Some(2) => return self.sqr(),
            _ => {}
        }
        Real::abs(self).power(q)
    }
    fn lo(&self) -> f64 {
        self.lo.to_f64_round(DOWN)
    }
    fn hi(&self) -> f64 {
        self.hi.to_f64_round(UP)
    }
    /// On the MPFR ends themselves (f64 bounds of two intervals a hair apart may coincide).
    fn encloses(&self, o: &Self) -> bool {
        o.subset(self)
    }
    fn mid(&self) -> f64 {
        if self.is_empty() {
            return f64::NAN;
        }
        match (self.lo.is_finite(), self.hi.is_finite()) {
            (true, true) => {
                let mut m = Float::with_val(B, &self.lo + &self.hi);
                m /= 2u32;
                m.to_f64().clamp(f64::MIN, f64::MAX)
            }
            (false, false) => 0.0,
            (true, false) => f64::MAX,
            (false, true) => f64::MIN,
        }
    }
    fn is_finite(&self) -> bool {
        !self.is_empty() && self.lo.is_finite() && self.hi.is_finite()
    }
    /// Decided on the MPFR ends (an f64 lo of 0 may hide a positive end such as 2^−2000).
    fn sign(&self) -> Option<i8> {
        if self.is_empty() {
            None
        } else if self.lo > 0 {
            Some(1)
        } else if self.hi < 0 {
            Some(-1)
        } else {
            None
        }
    }
    fn unbounded() -> Self {
        Self::entire()
    }
    /// k when the interval is the single integer k, |k| < 10^15.
    fn as_integer(&self) -> Option<i64> {
        if self.lo == self.hi && self.lo.is_integer() && *self.lo.as_abs() < 1e15 {
            self.lo.to_integer().and_then(|k| k.to_i64())
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    type M = Mpi<128>;

    /// A fixed-seed xorshift generator.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> u64 {
            crate::arith::interval::xorshift_step(&mut self.0)
        }
        /// In [0, n).
        fn below(&mut self, n: u64) -> u64 {
            self.next() % n
        }
    }

    /// A random float of B bits (full random mantissa) with binary exponent in [e0, e1).
    fn rand_float<const B: u32>(g: &mut Rng, e0: i32, e1: i32) -> Float {
        let mut m = Integer::new();
        for _ in 0..B.div_ceil(64) {
            m <<= 64;
            m += g.next();
        }
        m.keep_bits_mut(B);
        m.set_bit(B - 1, true);
        let mut x = Float::with_val(B, m);
        let e = e0 + g.below((e1 - e0) as u64) as i32;
        x >>= B as i32 - e;
        if g.next() & 1 == 1 { -x } else { x }
    }

    /// A random interval: both ends random (any sign), across 0, positive, negative, a point,
    /// tiny (2^−1000) or huge (2^1000) magnitudes, a zero end, mixed magnitudes.
    fn rand_interval<const B: u32>(g: &mut Rng) -> Mpi<B> {
        let kind = g.below(9);
        let (e0, e1) = match kind {
            5 => (-1010, -990),
            6 => (990, 1010),
            _ => (-8, 8),
        };
        let mut a = rand_float::<B>(g, e0, e1);
        let mut b = rand_float::<B>(g, e0, e1);
        match kind {
            1 => {
                // across 0
                a = -a.abs();
                b = b.abs();
            }
            2 => {
                a = a.abs();
                b = b.abs();
            }
            3 => {
                a = -a.abs();
                b = -b.abs();
            }
            4 => b = a.clone(),
            7 => {
                a = Float::new(B);
                b = b.abs();
            }
            8 => {
                // a tiny end and an ordinary one
                a = rand_float::<B>(g, -1000, -990);
            }
            _ => {}
        }
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        Mpi::new(a, b)
    }

    fn q(x: &Float) -> Rational {
        x.to_rational().unwrap()
    }

    /// Rationals a + (b − a)·t at t = 0, 1/7, 1/2, 5/6, 1 (the ends and interior points).
    fn samples(x: &Mpi<128>) -> Vec<Rational> {
        let (a, b) = (q(&x.lo), q(&x.hi));
        [(0, 1), (1, 7), (1, 2), (5, 6), (1, 1)]
            .iter()
            .map(|&(n, d)| &a + Rational::from((n, d)) * Rational::from(&b - &a))
            .collect()
    }

    /// r encloses [lo, hi] and its ends are those exactly rounded outward (tight).
    fn exact_and_tight(r: &M, lo: &Rational, hi: &Rational, what: &str) {
        assert!(
            r.lo <= *lo && *hi <= r.hi,
            "{what}: {r} does not enclose [{}, {}]",
            lo.to_f64(),
            hi.to_f64()
        );
        assert!(
            r.lo == rnd(128, lo, DOWN) && r.hi == rnd(128, hi, UP),
            "{what}: {r} is not the tightest"
        );
    }

    /// The exact range of a binary operation on the ends (min and max of the four values).
    fn corner_range(
        x: &M,
        y: &M,
        f: impl Fn(&Rational, &Rational) -> Rational,
    ) -> (Rational, Rational) {
        let v: Vec<Rational> = [
            (&x.lo, &y.lo),
            (&x.lo, &y.hi),
            (&x.hi, &y.lo),
            (&x.hi, &y.hi),
        ]
        .iter()
        .map(|(a, b)| f(&q(a), &q(b)))
        .collect();
        (
            v.iter().min().unwrap().clone(),
            v.iter().max().unwrap().clone(),
        )
    }

    /// The four operations (and −x, x·k, x/k, |x|, x², x·c) on random intervals: the exact rational
    /// result at the ends and at interior points lies inside, and the ends are the exact
    /// range's ends rounded outward (the tightest enclosure at 128 bits).
    #[test]
    fn arithmetic_encloses_the_exact_rational_range_tightly() {
        let mut g = Rng(0x9e3779b97f4a7c15);
        for i in 0..3000 {
            let (x, y) = (rand_interval::<128>(&mut g), rand_interval::<128>(&mut g));
            let s = x.clone() + y.clone();
            exact_and_tight(&s, &(q(&x.lo) + q(&y.lo)), &(q(&x.hi) + q(&y.hi)), "+");
            let d = x.clone() - y.clone();
            exact_and_tight(&d, &(q(&x.lo) - q(&y.hi)), &(q(&x.hi) - q(&y.lo)), "−");
            let p = x.clone() * y.clone();
            let (lo, hi) = corner_range(&x, &y, |a, b| Rational::from(a * b));
            exact_and_tight(&p, &lo, &hi, "×");
            let pc = x.mul_constant(&y);
            assert!(pc.lo == p.lo && pc.hi == p.hi);
            let quo = x.clone() / y.clone();
            let across = y.lo <= 0 && y.hi >= 0;
            if across {
                assert!(quo.lo.is_infinite() && quo.hi.is_infinite(), "÷ {y}: {quo}");
            } else {
                let (lo, hi) = corner_range(&x, &y, |a, b| Rational::from(a / b));
                exact_and_tight(&quo, &lo, &hi, "÷");
            }
            // interior points
            for a in samples(&x) {
                for b in samples(&y) {
                    let inside = |r: &M, v: Rational| r.lo <= v && v <= r.hi;
                    assert!(inside(&s, Rational::from(&a + &b)));
                    assert!(inside(&d, Rational::from(&a - &b)));
                    assert!(inside(&p, Rational::from(&a * &b)));
                    if b != 0 {
                        assert!(inside(&quo, Rational::from(&a / &b)));
                    }
                }
            }
            let n = -x.clone();
            exact_and_tight(&n, &-q(&x.hi), &-q(&x.lo), "−x");
            let k = [3i64, -7, 1 << 40, -1, 12345][i % 5];
            let kr = Rational::from(k);
            let (lo, hi) = if k > 0 {
                (q(&x.lo) * &kr, q(&x.hi) * &kr)
            } else {
                (q(&x.hi) * &kr, q(&x.lo) * &kr)
            };
            exact_and_tight(&x.mul_int(k), &lo, &hi, "x·k");
            let (lo, hi) = if k > 0 {
                (q(&x.lo) / &kr, q(&x.hi) / &kr)
            } else {
                (q(&x.hi) / &kr, q(&x.lo) / &kr)
            };
            exact_and_tight(&x.div_int(k), &lo, &hi, "x/k");
            let (a, b) = (q(&x.lo), q(&x.hi));
            let far = if a.clone().abs() > b.clone().abs() {
                a.clone()
            } else {
                b.clone()
            };
            let near = if x.lo <= 0 && x.hi >= 0 {
                Rational::new()
            } else if a.clone().abs() < b.clone().abs() {
                a.abs()
            } else {
                b.abs()
            };
            let (near_sq, far_sq) = (Rational::from(&near * &near), Rational::from(&far * &far));
            exact_and_tight(&x.sqr(), &near_sq, &far_sq, "x²");
            exact_and_tight(&Real::abs(&x), &near, &far.abs(), "|x|");
        }
    }

    /// The precision of the references: 4 × 128 bits.
    const P: u32 = 512;

    /// 512-bit points a + (b − a)·t (rounded to nearest: inside [a, b]).
    fn fsamples(x: &M) -> Vec<Float> {
        samples(x).iter().map(|r| Float::with_val(P, r)).collect()
    }

    /// r encloses [lo, hi] (the exact range's ends rounded outward at 512 bits: then r's ends,
    /// of 128 bits, bound the exact range exactly when they bound these) and is at most
    /// `ulps` ulps at 128 bits wider at each end.
    fn encloses_tightly(r: &M, lo: &Float, hi: &Float, ulps: usize, what: &str) {
        assert!(
            r.lo <= *lo && *hi <= r.hi,
            "{what}: {r} does not enclose [{}, {}]",
            lo.to_f64(),
            hi.to_f64()
        );
        let (mut l, mut h) = (rnd(128, lo, DOWN), rnd(128, hi, UP));
        for _ in 0..ulps {
            l.next_down();
            h.next_up();
        }
        assert!(
            r.lo >= l && r.hi <= h,
            "{what}: {r} is more than {ulps} ulps wider than [{}, {}]",
            lo.to_f64(),
            hi.to_f64()
        );
    }

    /// v (bounds of an exact value at 512 bits) lies in r.
    fn holds(r: &M, v: &(Float, Float)) -> bool {
        r.lo <= v.0 && v.1 <= r.hi
    }

    /// f(x) at 512 bits rounded down and up.
    fn at512(x: &Float, f: impl Fn(&Float, Round) -> Float) -> (Float, Float) {
        (f(x, DOWN), f(x, UP))
    }

    /// sqrt, ln, exp on random intervals against MPFR at 512 bits (monotone: the range is
    /// that of the ends), with interior points; each end within 1 ulp of the exact range.
    #[test]
    fn sqrt_ln_exp_enclose_mpfr_references_tightly() {
        let mut g = Rng(0x2545f4914f6cdd1d);
        let sqrt = |x: &Float, r| rnd(P, x.sqrt_ref(), r);
        let ln = |x: &Float, r| rnd(P, x.ln_ref(), r);
        let exp = |x: &Float, r| rnd(P, x.exp_ref(), r);
        for _ in 0..3000 {
            let x = rand_interval::<128>(&mut g);
            let s = x.sqrt();
            if x.hi < 0 {
                assert!(s.is_empty());
            } else {
                let lo = if x.lo <= 0 {
                    Float::new(P)
                } else {
                    sqrt(&x.lo, DOWN)
                };
                encloses_tightly(&s, &lo, &sqrt(&x.hi, UP), 1, "sqrt");
                for t in fsamples(&x).iter().filter(|t| **t >= 0) {
                    assert!(holds(&s, &at512(t, sqrt)), "sqrt {t}: {s}");
                }
            }
            let l = x.ln();
            if x.lo <= 0 {
                assert!(l.lo.is_infinite() && l.hi.is_infinite(), "ln {x}: {l}");
            } else {
                encloses_tightly(&l, &ln(&x.lo, DOWN), &ln(&x.hi, UP), 1, "ln");
                for t in fsamples(&x) {
                    assert!(holds(&l, &at512(&t, ln)), "ln {t}: {l}");
                }
            }
            let e = x.exp();
            encloses_tightly(&e, &exp(&x.lo, DOWN), &exp(&x.hi, UP), 1, "exp");
            for t in fsamples(&x) {
                assert!(holds(&e, &at512(&t, exp)), "exp {t}: {e}");
            }
        }
    }

    /// A random exponent interval in [lo, lo + 4): a point or a range, sometimes an integer.
    fn rand_exponent(g: &mut Rng, lo: i64) -> M {
        match g.below(6) {
            0 => M::from_int(lo + g.below(3) as i64),
            1 => M::parse_decimal("1.27").unwrap(),
            _ => {
                let a = Float::with_val(128, lo) + rand_float::<128>(g, -8, 2).abs();
                let b = if g.below(3) == 0 {
                    a.clone()
                } else {
                    Float::with_val(128, &a + rand_float::<128>(g, -12, 0).abs())
                };
                M::new(a, b)
            }
        }
    }

    /// x^y for x > 0 (tiny to huge) and y in [−3, 4) over boxes: the exact range (the least and
    /// greatest of the four corners, since y·ln x is bilinear) at 512 bits lies inside, with
    /// interior points, each end within 2 ulps.
    #[test]
    fn pow_encloses_the_range_over_boxes_tightly() {
        let mut g = Rng(0x853c49e6748fea9b);
        let pw = |x: &Float, y: &Float, r| rnd(P, x.pow(y), r);
        for _ in 0..2000 {
            let x0 = rand_interval::<128>(&mut g);
            let (mut a, mut b) = (Float::with_val(128, x0.lo.abs_ref()), x0.hi.clone().abs());
            if a > b {
                std::mem::swap(&mut a, &mut b);
            }
            if a == 0 {
                a = rand_float::<128>(&mut g, -1000, -990).abs();
            }
            let x = M::new(a, b);
            let y = rand_exponent(&mut g, -3);
            let r = Real::pow(&x, &y);
            let corners = |rd| {
                let v: Vec<Float> = [
                    (&x.lo, &y.lo),
                    (&x.lo, &y.hi),
                    (&x.hi, &y.lo),
                    (&x.hi, &y.hi),
                ]
                .iter()
                .map(|(u, e)| pw(u, e, rd))
                .collect();
                v
            };
            let lo = corners(DOWN).into_iter().reduce(fmin).unwrap();
            let hi = corners(UP).into_iter().reduce(fmax).unwrap();
            encloses_tightly(&r, &lo, &hi, 2, &format!("{x}^{y}"));
            for t in fsamples(&x) {
                for e in fsamples(&y) {
                    assert!(
                        holds(&r, &(pw(&t, &e, DOWN), pw(&t, &e, UP))),
                        "{t}^{e}: {r}"
                    );
                }
            }
        }
    }

    /// |x|^(q−1)x and |x|^q on random intervals (either sign, across 0, tiny, huge) for q in
    /// [1, 5) (points, ranges, integers): the exact range at 512 bits lies inside (signed:
    /// increasing in x, extreme over q at q's ends; absolute: 0 or the nearer end below, the
    /// farther above), with interior points, each end within 2 ulps (but q = 2 across 0, which
    /// is |x|·x).
    #[test]
    fn signed_and_absolute_powers_enclose_the_range_tightly() {
        let mut g = Rng(0xda3e39cb94b95bdb);
        // ±|x|^q at 512 bits, rounded by r
        let s = |x: &Float, e: &Float, signed: bool, r: Round| {
            let neg = signed && *x < 0;
            let xa = Float::with_val(P, x.abs_ref());
            let m = rnd(P, (&xa).pow(e), if neg { r.reverse() } else { r });
            if neg { -m } else { m }
        };
        for _ in 0..2000 {
            let x = rand_interval::<128>(&mut g);
            let qe = rand_exponent(&mut g, 1);
            let sp = x.spow(&qe);
            let lo = fmin(s(&x.lo, &qe.lo, true, DOWN), s(&x.lo, &qe.hi, true, DOWN));
            let hi = fmax(s(&x.hi, &qe.lo, true, UP), s(&x.hi, &qe.hi, true, UP));
            let across = x.lo < 0 && x.hi > 0;
            let ulps = if across && qe.as_integer() == Some(2) {
                usize::MAX / 2
            } else {
                2
            };
            let what = format!("spow({x}, {qe})");
            if ulps == 2 {
                encloses_tightly(&sp, &lo, &hi, ulps, &what);
            } else {
                assert!(sp.lo <= lo && hi <= sp.hi, "{what}: {sp}");
            }
            let ap = x.apow(&qe);
            let (fa, fb) = (x.lo.clone().abs(), x.hi.clone().abs());
            let (near, far) = if fa < fb { (fa, fb) } else { (fb, fa) };
            let lo = if across {
                Float::new(P)
            } else {
                fmin(s(&near, &qe.lo, false, DOWN), s(&near, &qe.hi, false, DOWN))
            };
            let hi = fmax(s(&far, &qe.lo, false, UP), s(&far, &qe.hi, false, UP));
            encloses_tightly(&ap, &lo, &hi, 2, &format!("apow({x}, {qe})"));
            for t in fsamples(&x) {
                for e in fsamples(&qe) {
                    let v = (s(&t, &e, true, DOWN), s(&t, &e, true, UP));
                    assert!(holds(&sp, &v), "spow({t}, {e}): {sp}");
                    let v = (s(&t, &e, false, DOWN), s(&t, &e, false, UP));
                    assert!(holds(&ap, &v), "apow({t}, {e}): {ap}");
                }
            }
            // the pairs are the same values
            let (a, b) = x.spow_apow(&qe);
            assert!(a.lo == sp.lo && a.hi == sp.hi && b.lo == ap.lo && b.hi == ap.hi);
        }
    }

    /// y^q·ln y (signed: sign(y)·|y|^q ln|y|) and |y|^q with q reaching 0 at sample points,
    /// computed at 512 bits with a margin of 2^−500 relative (far above the few ulps of error at
    /// 512 bits): inside pow_ln and apow, over boxes reaching 0 (the bounded forms) and away
    /// from it; a point away from 0 is within 8 ulps.
    #[test]
    fn power_log_and_zero_exponent_bounds_contain_samples() {
        let g = |y: &Float, e: &Float, log: bool| -> (Float, Float) {
            if *y == 0 || !log && *e == 0 {
                // exact: y^0 = 1; the limits at y = 0: y^q ln y → 0 (q ≥ 1), 0^q = 0 (q > 0)
                let v = if !log && *e == 0 { 1 } else { 0 };
                return (Float::with_val(P, v), Float::with_val(P, v));
            }
            let ya = Float::with_val(P, y.abs_ref());
            let p = Float::with_val(P, (&ya).pow(e));
            let v = if log { p * ya.ln() } else { p };
            let m: Float = Float::with_val(P, v.abs_ref()) >> 500i32;
            (Float::with_val(P, &v - &m), Float::with_val(P, &v + &m))
        };
        let iv = |a: &str, b: &str| M::parse_decimal(&format!("{a}..{b}")).unwrap();
        let boxes = [
            iv("0", "0"),
            iv("-1e-8", "1e-300"),
            iv("-0.2", "0.3"),
            iv("-0.5", "0.1"),
            iv("0", "0.9"),
            iv("-2.5", "1"),
            iv("0.4", "3"),
            iv("-3", "-0.05"),
            iv("-1e-1000", "1e-2000"),
        ];
        for (qa, qb) in [("1", "1"), ("1", "1.001"), ("1.27", "1.31"), ("2", "3.5")] {
            let qe = iv(qa, qb);
            for w in &boxes {
                let (u, s) = (M::pow_ln(w, &qe, false), M::pow_ln(w, &qe, true));
                for y in fsamples(w) {
                    for e in fsamples(&qe) {
                        let v = g(&y, &e, true);
                        let vs = if y < 0 {
                            (-v.1.clone(), -v.0.clone())
                        } else {
                            v.clone()
                        };
                        assert!(holds(&u, &v), "|w|^q ln|w|: {y} {e}: {u}");
                        assert!(holds(&s, &vs), "signed: {y} {e}: {s}");
                    }
                }
            }
        }
        // a point away from 0: the product of two tight enclosures
        let (w, qe) = (
            M::parse_decimal("0.5").unwrap(),
            M::parse_decimal("1.27").unwrap(),
        );
        let r = M::pow_ln(&w, &qe, true);
        let v = g(&w.lo, &Float::with_val(P, &qe.lo), true);
        encloses_tightly(&r, &v.0, &v.1, 8, "pow_ln(0.5, 1.27)");
        // |x|^q for q ∈ [0, 0.001] (|z|^(n−1) with n ∈ [1, 1.001]) over boxes reaching 0
        let qe = iv("0", "0.001");
        for w in [
            iv("0", "0"),
            iv("-1e-8", "1e-300"),
            iv("-0.2", "0.3"),
            iv("-2.5", "1"),
            iv("0", "4"),
        ] {
            let r = w.apow(&qe);
            for y in fsamples(&w) {
                for e in fsamples(&qe) {
                    assert!(holds(&r, &g(&y, &e, false)), "|y|^q: {y} {e}: {r}");
                }
            }
        }
        assert_eq!(
            iv("0", "0").apow(&qe).to_interval(),
            Interval::try_from((0.0, 1.0)).unwrap()
        );
        // sgn: ±1 off 0, the Clarke derivative [−1, 1] of |x| across it
        assert_eq!(
            iv("0.5", "2").sgn().to_interval(),
            Interval::try_from((1.0, 1.0)).unwrap()
        );
        assert_eq!(
            iv("-2", "-0.5").sgn().to_interval(),
            Interval::try_from((-1.0, -1.0)).unwrap()
        );
        assert_eq!(
            iv("-1", "1").sgn().to_interval(),
            Interval::try_from((-1.0, 1.0)).unwrap()
        );
    }

    /// Decimals are enclosed as written (the exact rational inside, one ulp wide when not
    /// representable), ranges take both ends, and what is not a plain decimal is refused with
    /// the same messages as the f64 intervals.
    #[test]
    fn decimals_are_enclosed_as_written_and_non_decimals_refused() {
        let x = M::parse_decimal("0.632").unwrap();
        let exact = Rational::from((632, 1000));
        assert!(x.lo < exact && exact < x.hi, "{x}");
        let mut up = x.lo.clone();
        up.next_up();
        assert_eq!(x.hi, up, "0.632 is one ulp wide");
        // at other precisions too
        let y = Mpi::<256>::parse_decimal(" 0.632 ").unwrap();
        assert!(y.lo < exact && exact < y.hi && y.wid_f64() < 1e-75);
        let r = M::parse_decimal("0.632..0.64").unwrap();
        assert!(r.lo == rnd(128, &exact, DOWN) && r.hi == rnd(128, &Rational::from((64, 100)), UP));
        let point = |s: &str, v: Rational| {
            let x = M::parse_decimal(s).unwrap();
            assert!(x.lo == v && x.hi == v, "{s}: {x}");
        };
        point("0.5", Rational::from((1, 2)));
        point("+.5", Rational::from((1, 2)));
        point("5.", Rational::from(5));
        point("-1.5e3", Rational::from(-1500));
        point("25E-2", Rational::from((1, 4)));
        point("0e99999999999999999999", Rational::new());
        // below the f64 range: a positive enclosure, not 0
        let t = M::parse_decimal("1e-400").unwrap();
        assert!(t.lo > 0 && t.lo < Rational::from((1, Integer::from(10).pow(400))));
        let err = |s: &str| M::parse_decimal(s).unwrap_err();
        assert_eq!(err("inf"), "'inf' is not a decimal number");
        assert_eq!(err("[1,2]"), "'[1,2]' is not a decimal number");
        assert_eq!(
            err("1..0"),
            "the range '1..0' is empty (its start exceeds its end)"
        );
        for bad in [
            "", "nan", "1e", "1.2.3", "--1", "e5", ".", "1e5.5", "1-2", "0x1p3", "..5",
        ] {
            assert!(M::parse_decimal(bad).is_err(), "{bad:?} accepted");
        }
        assert!(err("1e5000000").contains("out of range"));
    }

    /// The printed ends are bounds: parsed back exactly, lo's decimal ≤ lo and hi's ≥ hi, at
    /// every number of digits; and they differ from the ends by less than a unit in the last
    /// printed digit.
    #[test]
    fn printed_decimals_are_outward_bounds() {
        let mut g = Rng(0x6a09e667f3bcc909);
        let mut xs: Vec<M> = (0..400).map(|_| rand_interval::<128>(&mut g)).collect();
        xs.push(M::parse_decimal("0.632").unwrap());
        xs.push(M::parse_decimal("-0.632").unwrap());
        for x in &xs {
            for d in [1, 2, 3, 17, 40, 60] {
                let (ls, hs) = x.to_decimal(d);
                let (l, h) = (decimal_value(&ls).unwrap(), decimal_value(&hs).unwrap());
                assert!(l <= q(&x.lo) && q(&x.hi) <= h, "{x} at {d}: {ls}, {hs}");
                let digits = |s: &str| {
                    s.split('e')
                        .next()
                        .unwrap()
                        .chars()
                        .filter(|c| c.is_ascii_digit())
                        .count()
                };
                assert!(x.lo == 0 || digits(&ls) == d, "{ls} has not {d} digits");
                // within one unit of the last digit: |x| · 10^(1−d)
                let tol = |v: &Rational| {
                    v.clone().abs() * Rational::from((1, Integer::from(10).pow(d as u32 - 1)))
                };
                assert!(q(&x.lo) - &l <= tol(&q(&x.lo)), "{ls} is far below {x}");
                assert!(
                    Rational::from(&h - &q(&x.hi)) <= tol(&q(&x.hi)),
                    "{hs} is far above {x}"
                );
            }
        }
        assert_eq!(
            M::parse_decimal("0.632").unwrap().to_decimal(3),
            ("6.31e-1".into(), "6.33e-1".into())
        );
        assert_eq!(
            M::from_int(-25).to_decimal(4),
            ("-2.500e1".into(), "-2.500e1".into())
        );
        assert_eq!(M::entire().to_decimal(3), ("-inf".into(), "inf".into()));
        assert_eq!(format!("{}", M::from_int(0)), "[0, 0]");
        let shown = format!("{}", M::parse_decimal("0.632").unwrap());
        assert!(
            shown.starts_with("[6.3199999") && shown.contains(", 6.3200000"),
            "{shown}"
        );
    }

    /// sign() is decided on the MPFR ends: [2^−2000, 1] is positive though its f64 lower
    /// bound is 0 (the default, from lo(), would say None).
    #[test]
    fn sign_is_decided_on_the_mpfr_ends() {
        let tiny: Float = Float::with_val(128, 1) >> 2000i32;
        let x = M::new(tiny.clone(), Float::with_val(128, 1));
        assert_eq!(x.lo(), 0.0);
        assert_eq!(x.sign(), Some(1));
        assert_eq!((-x.clone()).sign(), Some(-1));
        assert_eq!((-x.clone()).hi(), 0.0);
        assert_eq!(M::new(-tiny, Float::with_val(128, 1)).sign(), None);
        assert_eq!(M::empty().sign(), None);
        assert_eq!(crate::arith::jet::series::branch_sign(&[x]), Some(1));
    }

    /// The set operations, the f64 bounds (outward), the conversions, and the special cases
    /// of unbounded, empty and zero operands.
    #[test]
    fn set_operations_bounds_and_special_operands() {
        let iv = |a: &str, b: &str| M::parse_decimal(&format!("{a}..{b}")).unwrap();
        let f = |x: f64| Float::with_val(128, x);
        let (a, b) = (iv("0.1", "0.5"), iv("0.3", "2"));
        let h = a.hull(&b);
        assert!(h.lo == a.lo && h.hi == b.hi);
        let i = a.intersection(&b);
        assert!(i.lo == b.lo && i.hi == a.hi);
        assert!(a.intersection(&iv("0.6", "1")).is_empty());
        assert!(i.subset(&a) && i.subset(&b) && !a.subset(&b) && M::empty().subset(&a));
        assert!(iv("0.2", "0.4").interior(&a) && !a.interior(&a) && !iv("0.1", "0.4").interior(&a));
        assert!(a.interior(&M::entire()) && M::entire().interior(&M::entire()));
        assert!(a.contains(&f(0.25)) && !a.contains(&f(0.6)) && !M::empty().contains(&f(0.0)));
        let m = a.mid_point();
        assert!(m.lo == m.hi && a.contains(&m.lo));
        assert!(
            (q(&m.lo) - Rational::from((3, 10))).abs()
                < Rational::from((1, Integer::from(1) << 127))
        );
        assert_eq!(M::entire().mid_point().lo, 0);
        // f64 bounds, outward
        let x = M::parse_decimal("0.1").unwrap();
        assert!(x.lo() < 0.1 && x.hi() >= 0.1 || x.lo() <= 0.1 && x.hi() > 0.1);
        assert!(x.lo() == 0.1f64.next_down() || x.hi() == 0.1f64.next_up());
        assert!(x.wid_f64() > 0.0 && x.wid_f64() < 1e-38 && x.rad_f64() < x.wid_f64());
        assert_eq!(iv("-3", "2").mag_f64(), 3.0);
        assert_eq!(iv("-3", "2").mig_f64(), 0.0);
        assert_eq!(iv("-3", "-2").mig_f64(), 2.0);
        assert_eq!(x.mid(), 0.1);
        let big = M::parse_decimal("1e400").unwrap();
        assert!(big.is_finite() && big.lo() == f64::MAX && big.hi() == f64::INFINITY);
        // conversions
        let fi = Interval::try_from((0.1, 0.7)).unwrap();
        assert_eq!(M::from_interval(fi).to_interval(), fi);
        assert!(x.to_interval().contains(0.1) && x.to_interval().wid() > 0.0);
        assert!(M::from_interval(Interval::EMPTY).is_empty());
        assert_eq!(
            M::from_interval(Interval::ENTIRE).to_interval(),
            Interval::ENTIRE
        );
        assert!(M::new(f(2.0), f(1.0)).is_empty());
        assert!(
            M::from_exact_f64(f64::NAN).is_empty() && M::from_exact_f64(f64::INFINITY).is_empty()
        );
        assert_eq!(
            M::from_exact_f64(0.1).to_interval(),
            Interval::try_from((0.1, 0.1)).unwrap()
        );
        assert_eq!(M::from_int(3).as_integer(), Some(3));
        assert_eq!(M::from_int(-4).as_integer(), Some(-4));
        assert_eq!(iv("3", "3.5").as_integer(), None);
        assert_eq!(M::parse_decimal("1.5").unwrap().as_integer(), None);
        // unbounded and zero operands: 0·∞ = 0, a divisor across 0 gives everything
        let ent = M::entire();
        let zero = M::from_int(0);
        let z = zero.clone() * ent.clone();
        assert!(z.lo == 0 && z.hi == 0);
        let half = M::new(f(0.0), Float::with_val(128, Special::Infinity));
        let p = half.clone() * iv("-1", "2");
        assert!(p.lo.is_infinite() && p.hi.is_infinite() && p.lo < 0);
        assert!(!(iv("1", "2") / iv("0", "1")).is_finite());
        assert!(!(iv("1", "2").div_int(0)).is_finite());
        let d = iv("1", "2") / M::new(f(1.0), Float::with_val(128, Special::Infinity));
        assert!(d.lo == 0 && d.hi == 2);
        let s = half.clone() + iv("-1", "2");
        assert!(s.lo == -1 && s.hi.is_infinite());
        assert!(iv("1", "2").mul_int(0).lo == 0 && ent.mul_int(0).hi == 0);
        // domains: pow needs x ≥ 0, sqrt and ln keep the part in their domain
        assert!(!Real::pow(&iv("-1", "2"), &M::from_int(2)).is_finite());
        let r = Real::pow(&iv("0", "2"), &iv("0", "3"));
        assert!(r.lo == 0 && r.hi == 8, "{r}");
        let r = Real::pow(&iv("0", "0.5"), &iv("0", "1"));
        assert!(r.lo == 0 && r.hi == 1, "{r}");
        let r = Real::pow(&iv("0", "2"), &iv("-1", "1"));
        assert!(r.lo == 0 && r.hi.is_infinite(), "{r}");
        // a lower end −0 (an exact zero rounded down: 1 − 1) is 0: (−0)^(−1) is not −∞ here
        let z = M::from_int(1) - M::from_int(1);
        assert!(z.lo.is_zero() && z.lo.is_sign_negative());
        let x = M::new(z.lo.clone(), f(2.0));
        for e in [iv("-1", "1"), M::from_int(-1), iv("-3", "-1")] {
            let r = Real::pow(&x, &e);
            assert!(r.hi.is_infinite() && r.hi > 0, "{x}^{e} = {r}");
        }
        assert!(x.apow(&M::from_int(-1)).hi.is_infinite());
        let r = iv("-1", "4").sqrt();
        assert!(r.lo == 0 && r.hi == 2);
        assert!(iv("-2", "-1").sqrt().is_empty());
        assert!(!iv("0", "1").ln().is_finite());
        let q = M::parse_decimal("1.27").unwrap();
        assert!(
            !M::new(Float::with_val(128, Special::NegInfinity), f(1.0))
                .spow(&q)
                .is_finite()
        );
        // the exact small exponents
        let x = iv("-0.3", "0.7");
        assert!(x.spow(&M::one()).lo == x.lo && x.apow(&M::from_int(0)).lo == 1);
        assert!(x.apow(&M::from_int(2)).lo == 0 && x.apow(&M::from_int(2)).hi == x.sqr().hi);
        // empty operands stay empty
        let e = M::empty();
        for r in [
            e.clone() + a.clone(),
            a.clone() - e.clone(),
            e.clone() * a.clone(),
            a.clone() / e.clone(),
            -e.clone(),
            e.sqrt(),
            e.ln(),
            e.exp(),
            e.sqr(),
            Real::abs(&e),
            e.spow(&q),
            e.apow(&q),
            a.spow(&e),
            Real::pow(&a, &e),
            M::pow_ln(&e, &q, true),
            e.mul_int(3),
            e.div_int(3),
            e.sgn(),
        ] {
            assert!(r.is_empty() && !r.is_finite(), "{r}");
        }
    }

    /// Series<Mpi<128>>: the Taylor coefficients of |x|^1.5 at x0 = 0.7 (and of
    /// |x|^0.5·x at x0 = −0.7) are binom(1.5, k)·0.7^(1.5−k) (times −(−1)^k), computed at 512
    /// bits from the exact 7/10: inside, and at most 1e−30 relative wide; across 0 the
    /// coefficients are unbounded (a branch point has no expansion).
    #[test]
    fn taylor_series_of_a_fractional_power_against_mpfr() {
        use crate::arith::Scalar;
        use crate::arith::jet::series::Series;
        let order = 12;
        let qe = M::parse_decimal("1.5").unwrap();
        let u = Scalar::apow(
            &Series::variable(M::parse_decimal("0.7").unwrap(), order),
            &qe,
        );
        let v = Scalar::spow(
            &Series::variable(M::parse_decimal("-0.7").unwrap(), order),
            &qe,
        );
        let x0 = Float::with_val(P, &Rational::from((7, 10)));
        let mut binom = Rational::from(1);
        for k in 0..=order {
            let e = Float::with_val(P, &(Rational::from((3, 2)) - Rational::from(k)));
            let c = Float::with_val(P, &binom) * Float::with_val(P, (&x0).pow(&e));
            let m: Float = Float::with_val(P, c.abs_ref()) >> 500i32;
            let want = (Float::with_val(P, &c - &m), Float::with_val(P, &c + &m));
            assert!(holds(&u.c[k], &want), "k = {k}: {} ∌ {}", u.c[k], c);
            let rel = u.c[k].wid_f64() / c.to_f64().abs();
            assert!(rel < 1e-30, "k = {k}: relative width {rel:e}");
            // |x|^0.5·x at −0.7 + t = −(0.7 − t)^1.5: c_k·(−1)^(k+1)
            let sv = if k % 2 == 0 {
                (-want.1.clone(), -want.0.clone())
            } else {
                want.clone()
            };
            assert!(holds(&v.c[k], &sv), "signed k = {k}: {}", v.c[k]);
            binom *= Rational::from((3, 2)) - Rational::from(k);
            binom /= Rational::from(k + 1);
        }
        let w = Series::variable(M::parse_decimal("-0.1..0.1").unwrap(), 3);
        assert!(!Scalar::apow(&w, &qe).c[1].is_finite());
    }

    /// The SHC model's field f(X, Z, V) of eq:BWSHCCM_nd evaluated over Mpi<128> lies inside
    /// the same field over f64 intervals and is at least 10^20 times narrower.
    #[test]
    fn model_field_over_mpfr_lies_inside_the_interval_field() {
        use crate::models::{CollisionModel, ModelKind, NdParams, Shc};
        let text = "1.43,-1.42,0.632,0.00715,1.31,1.27";
        let fm = Shc::<M>::new(NdParams::parse(ModelKind::Shc, text).unwrap());
        let fi = Shc::<Interval>::new(NdParams::parse(ModelKind::Shc, text).unwrap());
        for s in [[0.3, -0.2, 0.5], [-0.01, 0.02, -0.9], [0.7, 0.65, 0.1]] {
            let ym = fm.field(&s.map(M::from_exact_f64));
            let yi = fi.field(&s.map(Interval::from_exact_f64));
            for (m, i) in ym.iter().zip(&yi) {
                assert!(m.lo >= i.inf() && m.hi <= i.sup(), "{s:?}: {m} ⊄ {i:?}");
                assert!(m.wid_f64() * 1e20 <= i.wid(), "{s:?}: {m} vs {i:?}");
            }
            // the force has width from the powers and the decimal parameters
            assert!(yi[2].wid() > 0.0);
        }
    }
}
