//! inari's `Interval` as a [`Real`]: every operation encloses the exact result.
//!
//! Decimal input is enclosed as written (inari parses `"[0.632]"` to the tightest interval
//! containing the decimal 0.632), never rounded to a double first.

pub mod dot;
pub mod elementary;
mod enclosure;
pub mod ulp;
mod ulp_real;

use crate::arith::real::Real;
use inari::{Interval, const_interval};
use ulp::int_op_bounds;

/// [0, +∞), the domain of `pow`.
const NONNEG: Interval = const_interval!(0.0, f64::INFINITY);

/// Encloses a decimal literal exactly as written.
pub fn enclose_decimal(s: &str) -> Result<Interval, String> {
    let t = s.trim();
    // inari's grammar takes a bracketed literal; reject what is not a plain decimal first so that
    // e.g. "[1,2]" or "inf" are not silently accepted as parameters.
    crate::arith::real::check_plain_decimal(t)?;
    let x: Interval = format!("[{t}]")
        .parse()
        .map_err(|_| format!("'{t}' is not a decimal number"))?;
    if x.is_empty() || !x.inf().is_finite() || !x.sup().is_finite() {
        return Err(format!("'{t}' is not a finite number"));
    }
    Ok(x)
}

/// Encloses `"a"` or the range `"a..b"` (every value between the two decimals).
pub fn enclose_decimal_or_range(s: &str) -> Result<Interval, String> {
    let t = s.trim();
    match t.split_once("..") {
        None => enclose_decimal(t),
        Some((a, b)) => {
            let (a, b) = (enclose_decimal(a)?, enclose_decimal(b)?);
            if a.inf() > b.sup() {
                return Err(format!(
                    "the range '{t}' is empty (its start exceeds its end)"
                ));
            }
            Ok(a.convex_hull(b))
        }
    }
}

/// Lower end of |x|^(q−1)·x over x ∈ [a, a] for every q in `q` (monotone in x).
fn spow_at(a: f64, q: Interval, upper: bool) -> f64 {
    let m = power(Interval::try_from((a.abs(), a.abs())).unwrap(), q);
    match (a >= 0.0, upper) {
        (true, false) => m.inf(),
        (true, true) => m.sup(),
        (false, false) => -m.sup(),
        (false, true) => -m.inf(),
    }
}

/// x^q for x ≥ 0: the fast enclosure of [`elementary::pow`], else inari's (MPFR).
fn power(x: Interval, q: Interval) -> Interval {
    elementary::pow(x, q).unwrap_or_else(|| Interval::pow(x, q))
}

/// [a, b]·k or [a, b]/k for an exact integer k ≠ 0 (k = 0 only for a product), rounded
/// outwards without switching the rounding mode; inari's operation where not finite.
#[inline]
fn int_op(x: Interval, k: i64, div: bool) -> Interval {
    let kf = k as f64;
    if k == 0 && !div {
        return if x.is_empty() {
            x
        } else {
            Interval::try_from((0.0, 0.0)).unwrap()
        };
    }
    if k.unsigned_abs() > 1 << 53 {
        // not always a double (2^53 + 1 rounds to 2^53): its enclosure around the nearest
        let ki = Interval::try_from((kf.next_down(), kf.next_up())).unwrap();
        return if div { x / ki } else { x * ki };
    }
    let (a, b) = if k > 0 {
        (x.inf(), x.sup())
    } else {
        (x.sup(), x.inf())
    };
    match (int_op_bounds(a, kf, div), int_op_bounds(b, kf, div)) {
        (Some((lo, _)), Some((_, hi))) => Interval::try_from((lo, hi)).unwrap(),
        _ => {
            let ki = Interval::try_from((kf, kf)).unwrap();
            if div { x / ki } else { x * ki }
        }
    }
}

impl Real for Interval {
    type Dot = dot::IntervalDot;
    type Prepared = ();
    fn prepare_exponent(_: &Self) {}
    fn from_int(k: i64) -> Self {
        let x = k as f64;
        assert!(x as i64 == k, "integer constant {k} is not exact in f64");
        Interval::try_from((x, x)).unwrap()
    }
    fn from_exact_f64(x: f64) -> Self {
        Interval::try_from((x, x)).unwrap_or(Interval::EMPTY)
    }
    #[inline]
    fn mul_int(&self, k: i64) -> Self {
        int_op(*self, k, false)
    }
    #[inline]
    fn div_int(&self, k: i64) -> Self {
        int_op(*self, k, true)
    }
    /// The product in [`ulp::Ulp`] arithmetic (no mode switches), bit for bit inari's `*`.
    ///
    /// `Ulp` rounds each chosen endpoint product exactly as inari does except where its
    /// nearest value p has |p| < 2^−969 with non-zero factors (an underflow: stepped out by one
    /// spacing without a residual). Such an end e has |e| ≤ 2^−969, and so has the end of a
    /// four-corner [min, max] that such a corner decides; e = 0 only when p = ±2^−1074 is
    /// stepped towards 0, which needs a product of one strict sign (no endpoint 0). So every
    /// result that may differ has an end with |e| ≤ 2^−969, non-zero or with no endpoint 0;
    /// those rare results are recomputed by inari (test `constant_products_equal_inaris`).
    /// Used by the singular step's series (their terms times δ^α ranges) as well as the jets.
    #[inline]
    fn mul_constant(&self, c: &Self) -> Self {
        if self.is_empty() || c.is_empty() {
            return Interval::EMPTY;
        }
        let r = ulp::Ulp::of(*self) * ulp::Ulp::of(*c);
        let zero_end = self.inf() == 0.0 || self.sup() == 0.0 || c.inf() == 0.0 || c.sup() == 0.0;
        let tiny = |e: f64| e.abs() <= ulp::RESIDUAL_EXACT && (e != 0.0 || !zero_end);
        if tiny(r.lo) || tiny(r.hi) {
            return *self * *c;
        }
        r.interval()
    }
    fn parse_decimal(s: &str) -> Result<Self, String> {
        enclose_decimal_or_range(s)
    }
    fn unbounded() -> Self {
        Interval::ENTIRE
    }
    fn abs(&self) -> Self {
        Interval::abs(*self)
    }
    fn sqrt(&self) -> Self {
        Interval::sqrt(*self)
    }
    fn ln(&self) -> Self {
        elementary::ln(*self)
    }
    /// Away from 0 the product; where |w| reaches 0, g(y) = y^q ln y over y ∈ [0, |w|]:
    /// g ≥ −1/(e q) (its minimum, at y = e^(−1/q)), g ≤ 0 for y ≤ 1 and g ≤ |w|^q ln|w| above.
    fn pow_ln(w: &Self, q: &Self, signed: bool) -> Self {
        if w.is_empty() || q.is_empty() {
            return Interval::EMPTY;
        }
        if w.inf() > 0.0 || w.sup() < 0.0 {
            let u = if signed { w.spow(q) } else { w.apow(q) };
            return u * Real::ln(&Interval::abs(*w));
        }
        if q.inf() < 1.0 || !w.inf().is_finite() || !w.sup().is_finite() {
            return Interval::ENTIRE;
        }
        let m = Interval::abs(*w).sup();
        let ql = Interval::try_from((q.inf(), q.inf())).unwrap();
        // g decreases on [0, e^(−1/q)] ⊇ [0, 0.3678] (q ≥ 1): below it the minimum is g(m),
        // most negative for the smallest q (m^q decreases in q); else −1/(e q), 1/e < 0.36788
        let lo = if m <= 0.3678 {
            let mi = Interval::try_from((m, m)).unwrap();
            (power(mi, ql) * Real::ln(&mi)).inf().min(0.0)
        } else {
            (const_interval!(-0.36788, -0.36788) / ql).inf()
        };
        let hi = if m > 1.0 {
            let mi = Interval::try_from((m, m)).unwrap();
            (power(mi, Interval::try_from((q.sup(), q.sup())).unwrap()) * Real::ln(&mi)).sup()
        } else {
            0.0
        };
        let g = Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE);
        if signed {
            // sign(w)·g(|w|) with both signs of w
            let a = g.mag();
            Interval::try_from((-a, a)).unwrap_or(Interval::ENTIRE)
        } else {
            g
        }
    }
    fn sgn(&self) -> Self {
        if self.is_empty() {
            Interval::EMPTY
        } else if self.inf() > 0.0 {
            const_interval!(1.0, 1.0)
        } else if self.sup() < 0.0 {
            const_interval!(-1.0, -1.0)
        } else {
            const_interval!(-1.0, 1.0)
        }
    }
    fn pow(&self, y: &Self) -> Self {
        // inari intersects the base with [0, ∞) silently; a base reaching below 0 is a bug.
        if self.inf() < 0.0 {
            return Interval::ENTIRE;
        }
        power(*self, *y)
    }
    fn spow(&self, q: &Self) -> Self {
        if self.is_empty() || q.is_empty() {
            return Interval::EMPTY;
        }
        if let Some(k) = q.as_integer() {
            match k {
                1 => return *self,
                2 => return Interval::abs(*self) * *self,
                _ => {}
            }
        }
        // one sign: ±|x|^q
        if self.inf() >= 0.0 {
            return power(*self, *q);
        }
        if self.sup() <= 0.0 {
            return -power(-*self, *q);
        }
        // |x|^(q−1)x is increasing in x for q ≥ 1: evaluate at the ends.
        let (a, b) = (self.inf(), self.sup());
        if !a.is_finite() || !b.is_finite() {
            return Interval::ENTIRE;
        }
        Interval::try_from((spow_at(a, *q, false), spow_at(b, *q, true)))
            .unwrap_or(Interval::ENTIRE)
    }
    fn apow(&self, q: &Self) -> Self {
        if let Some(k) = q.as_integer() {
            match k {
                // |x|^0 = 1 (the factor |z|^(n−1) of n = 1)
                0 if !self.is_empty() => return const_interval!(1.0, 1.0),
                1 => return Interval::abs(*self),
                2 => return self.sqr(),
                _ => {}
            }
        }
        let a = Interval::abs(*self).intersection(NONNEG);
        if q.inf() <= 0.0 && a.inf() == 0.0 && !q.is_empty() && q.inf() >= 0.0 {
            // 0^q with q reaching 0 (|z|^(n−1) for n ∈ [1, …]): every value lies in [0, 1] below
            // |x| = 1, and below |x|^q above it
            let top = if !a.sup().is_finite() {
                f64::INFINITY
            } else if a.sup() > 1.0 {
                power(Interval::try_from((a.sup(), a.sup())).unwrap(), *q).sup()
            } else {
                1.0
            };
            return Interval::try_from((0.0, top.max(1.0))).unwrap_or(Interval::ENTIRE);
        }
        power(a, *q)
    }
    fn lo(&self) -> f64 {
        self.inf()
    }
    fn hi(&self) -> f64 {
        self.sup()
    }
    fn mid(&self) -> f64 {
        Interval::mid(*self)
    }
    fn is_finite(&self) -> bool {
        !self.is_empty() && self.inf().is_finite() && self.sup().is_finite()
    }
}

/// The tests' pseudo-random 64-bit words (xorshift64 from `seed`): operands for comparing a
/// fast path with the operation it claims to equal.
/// The tests' special operands (both signs are drawn by [`operand`]): zero, ∞, the largest
/// and smallest normal and the smallest subnormal doubles, where FMA residuals stop being exact
/// (and three times that), tiny and unit values.
#[cfg(test)]
pub(crate) const SPECIAL: [f64; 11] = [
    0.0,
    f64::INFINITY,
    f64::MAX,
    f64::MIN_POSITIVE,
    5e-324,
    ulp::RESIDUAL_EXACT,
    ulp::RESIDUAL_EXACT * 3.0,
    1e-160,
    1e-150,
    1.0,
    3.0,
];

/// A test operand from a random word `r`: one of `special` (a quarter of the time), a double
/// of any exponent (subnormal to huge), or one within 2^±30; either sign.
#[cfg(test)]
pub(crate) fn operand(r: u64, special: &[f64]) -> f64 {
    let m = 1.0 + (r >> 12) as f64 / (1u64 << 52) as f64;
    let x = match r % 4 {
        0 => special[(r >> 8) as usize % special.len()],
        1 => m * 2f64.powi((r >> 3) as i32 % 2098 - 1075),
        _ => m * 2f64.powi((r >> 3) as i32 % 60 - 30),
    };
    if r & 4 != 0 { -x } else { x }
}

#[cfg(test)]
pub(crate) fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
    move || xorshift_step(&mut seed)
}

/// One step of xorshift64 on the state `s`: the next word.
#[cfg(test)]
pub(crate) fn xorshift_step(s: &mut u64) -> u64 {
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    *s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// k beyond 2^53 (2^53 + 1 is not a double): x·k and x/k hold the exact results.
    #[test]
    fn integer_scalings_beyond_two_to_the_53_hold_the_exact_results() {
        use rug::Rational;
        let q = |x: f64| Rational::from_f64(x).unwrap();
        let two53: i64 = 1 << 53;
        for k in [two53 + 1, -(two53 + 3), 3 * two53 + 5, i64::MAX, -two53] {
            for x in [1.0, -0.75, 3.0e-200] {
                let xi = Interval::try_from((x, x)).unwrap();
                for div in [false, true] {
                    let r = super::int_op(xi, k, div);
                    let kq = Rational::from(k);
                    let exact = if div { q(x) / kq } else { q(x) * kq };
                    assert!(
                        q(r.inf()) <= exact && exact <= q(r.sup()),
                        "{x:e}, {k}: {r:?}"
                    );
                }
            }
        }
    }

    /// x·k and x/k by the residual method enclose the exact rational result, are at most one
    /// ulp wide per end, and equal inari's where inari is exact.
    #[test]
    fn integer_products_and_quotients_enclose_the_exact_value() {
        use rug::Rational;
        let q = |x: f64| Rational::from_f64(x).unwrap();
        let mut seed = 0x2545f4914f6cdd1d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let specials = [
            0.0,
            1.0,
            -1.0,
            0.1,
            -0.3,
            1e-300,
            f64::from_bits(1),
            5e-324 * 3.0,
            2.2250738585072014e-308,
            1.7976931348623157e308,
            1e308,
            1.0 / 3.0,
        ];
        for i in 0..20000 {
            let r = next();
            let x = if i < specials.len() * 8 {
                specials[i % specials.len()]
            } else {
                let m = 1.0 + (r >> 12) as f64 / (1u64 << 52) as f64;
                let e = (r % 2000) as i32 - 1000;
                if r & 1 == 0 {
                    m * 2f64.powi(e)
                } else {
                    -m * 2f64.powi(e)
                }
            };
            let k = [1i64, 2, 3, 7, 20, 21, -1, -3, 1 << 40, 12345][(next() % 10) as usize];
            let iv = Interval::try_from((x, x)).unwrap();
            let exact_mul = q(x) * Rational::from(k);
            let m = iv.mul_int(k);
            if m.sup().is_finite() && m.inf().is_finite() {
                assert!(
                    q(m.inf()) <= exact_mul && exact_mul <= q(m.sup()),
                    "{x:e}·{k}: {m:?}"
                );
                let ulps = if m.mag() < ulp::RESIDUAL_EXACT { 2 } else { 1 };
                let mut hi = m.inf();
                (0..ulps).for_each(|_| hi = hi.next_up());
                assert!(m.sup() <= hi, "{x:e}·{k}: {m:?}");
            } else {
                assert!(
                    m.contains(x * k as f64)
                        || m.sup() == f64::INFINITY
                        || m.inf() == f64::NEG_INFINITY
                );
            }
            let exact_div = q(x) / Rational::from(k);
            let d = iv.div_int(k);
            assert!(
                q(d.inf()) <= exact_div && exact_div <= q(d.sup()),
                "{x:e}/{k}: {d:?}"
            );
            assert!(
                d.wid() <= 2.0 * (x / k as f64).abs() * f64::EPSILON + 2e-323,
                "{x:e}/{k}: {d:?}"
            );
        }
        // wide and unbounded operands
        let w = Interval::try_from((-1.5, 2.5)).unwrap();
        assert_eq!(w.mul_int(-2), Interval::try_from((-5.0, 3.0)).unwrap());
        assert_eq!(w.div_int(2), Interval::try_from((-0.75, 1.25)).unwrap());
        assert_eq!(w.mul_int(0), Interval::try_from((0.0, 0.0)).unwrap());
        assert_eq!(Interval::ENTIRE.mul_int(3), Interval::ENTIRE);
        assert_eq!(
            Interval::ENTIRE.mul_int(0),
            Interval::try_from((0.0, 0.0)).unwrap()
        );
        assert!(Interval::EMPTY.mul_int(3).is_empty() && Interval::EMPTY.div_int(3).is_empty());
    }

    #[test]
    fn decimal_is_enclosed_not_rounded() {
        let x = enclose_decimal("0.632").unwrap();
        assert!(
            x.inf() < x.sup(),
            "0.632 is not a double: its enclosure has width"
        );
        assert!(x.contains(0.632));
        assert_eq!(enclose_decimal("0.5").unwrap().wid(), 0.0);
        assert!(enclose_decimal("abc").is_err());
        assert!(enclose_decimal("[1,2]").is_err());
        let r = enclose_decimal_or_range("0.9..1.1").unwrap();
        assert!(r.inf() <= 0.9 && r.sup() >= 1.1);
        assert!(enclose_decimal_or_range("2..1").is_err());
    }

    #[test]
    fn signed_power_encloses_pointwise_values() {
        let q = enclose_decimal("1.27").unwrap();
        for &(a, b) in &[(-2.0, -0.5), (-0.3, 0.7), (0.1, 3.0)] {
            let x = Interval::try_from((a, b)).unwrap();
            let y = x.spow(&q);
            for i in 0..=20 {
                let t = a + (b - a) * i as f64 / 20.0;
                let v = t.abs().powf(1.27 - 1.0) * t;
                assert!(
                    y.inf() <= v + 1e-15 && v - 1e-15 <= y.sup(),
                    "{t}: {v} ∉ {y:?}"
                );
            }
        }
        // a tight check: spow([−1, −1], 3) = −1 exactly
        let m1 = Interval::try_from((-1.0, -1.0)).unwrap();
        assert_eq!(m1.spow(&Interval::from_int(3)), m1);
    }

    /// spow and apow of intervals of either sign, over an exponent interval, against MPFR
    /// (256 bits) at the extreme points (both are monotone in x on each sign and in q): the
    /// enclosure holds the exact range and is at most a few ulps wider at each end.
    #[test]
    fn signed_and_absolute_powers_are_tight_against_mpfr() {
        use rug::Float;
        use rug::ops::Pow;
        let pw = |x: f64, e: f64, signed: bool| -> Float {
            let m = Float::with_val(256, x.abs()).pow(Float::with_val(256, e));
            if signed && x < 0.0 { -m } else { m }
        };
        let near = |enc: f64, exact: &Float| {
            let e = exact.to_f64();
            (enc - e).abs() <= 8.0 * f64::EPSILON * e.abs() + 1e-300
        };
        let exps = [
            enclose_decimal("1.27").unwrap(),
            enclose_decimal("2.5").unwrap(),
            enclose_decimal_or_range("0.8..1.3").unwrap(),
            Interval::from_int(2),
            Interval::from_int(3),
        ];
        for q in exps {
            for (a, b) in [
                (-0.3, 0.7),
                (-2.0, 0.5),
                (-2.0, -0.5),
                (0.1, 3.0),
                (-1.5, 2.5),
            ] {
                let x = Interval::try_from((a, b)).unwrap();
                // signed: increasing in x; the extremes over q at q's ends
                let s = x.spow(&q);
                let lo = pw(a, q.inf(), true).min(&pw(a, q.sup(), true));
                let hi = pw(b, q.inf(), true).max(&pw(b, q.sup(), true));
                assert!(s.inf() <= lo && hi <= s.sup(), "spow({x:?}, {q:?}) = {s:?}");
                // (q = 2 across 0 is |x|·x, which overestimates: [−0.21, 0.49] ⊋ [−0.09, 0.49])
                let dependent = q.as_integer() == Some(2) && a < 0.0 && b > 0.0;
                assert!(
                    dependent || near(s.inf(), &lo) && near(s.sup(), &hi),
                    "spow({x:?}, {q:?}) = {s:?}"
                );
                // absolute: 0 inside a straddling x, else the nearer end
                let ap = x.apow(&q);
                let far = if a.abs() > b.abs() { a } else { b };
                let hi = pw(far, q.inf(), false).max(&pw(far, q.sup(), false));
                let lo = if a < 0.0 && b > 0.0 {
                    Float::with_val(256, 0)
                } else {
                    let n = if a.abs() < b.abs() { a } else { b };
                    pw(n, q.inf(), false).min(&pw(n, q.sup(), false))
                };
                assert!(
                    ap.inf() <= lo && hi <= ap.sup(),
                    "apow({x:?}, {q:?}) = {ap:?}"
                );
                assert!(
                    near(ap.inf(), &lo) && near(ap.sup(), &hi),
                    "apow({x:?}, {q:?}) = {ap:?}"
                );
            }
        }
    }

    /// The fast product ([`Real::mul_constant`]) is inari's `*` bit for bit, on endpoints of
    /// every kind: ±0, ±∞, subnormal, products that underflow (where `Ulp` alone would be one
    /// spacing wider), tiny, huge, ±MAX, thin and across 0.
    #[test]
    fn constant_products_equal_inaris() {
        let mut next = crate::arith::interval::xorshift(0x3c6ef372fe94f82b_u64);
        let special = crate::arith::interval::SPECIAL;
        let float = |r: u64| crate::arith::interval::operand(r, &special);
        let (mut tiny, mut n) = (0, 0);
        for i in 0..400_000 {
            let (a, b, c, d) = (float(next()), float(next()), float(next()), float(next()));
            let Ok(x) = Interval::try_from((a.min(b), a.max(b))) else {
                continue;
            };
            let y = if i % 3 == 0 {
                (c, c)
            } else {
                (c.min(d), c.max(d))
            };
            let Ok(y) = Interval::try_from(y) else {
                continue;
            };
            let (m, e) = (x.mul_constant(&y), x * y);
            assert!(
                m.is_empty() == e.is_empty()
                    && (m.is_empty() || (m.inf() == e.inf() && m.sup() == e.sup())),
                "{x:?} · {y:?}: {m:?} vs inari {e:?}"
            );
            let u = ulp::Ulp::of(x) * ulp::Ulp::of(y);
            if u.interval() != e {
                tiny += 1;
            }
            n += 1;
        }
        // the underflow fallback was exercised
        assert!(n > 300_000 && tiny > 100, "{n} {tiny}");
    }

    /// mul_constant (in `Ulp` arithmetic) encloses the exact product of the ends and equals
    /// inari's product; pow refuses a base below 0; the small integer exponents are exact;
    /// empty operands stay empty; unbounded operands of x/k take inari's quotient.
    #[test]
    fn constant_products_and_power_special_cases() {
        use rug::Rational;
        let iv = |a: f64, b: f64| Interval::try_from((a, b)).unwrap();
        let q = |x: f64| Rational::from_f64(x).unwrap();
        for (x, c) in [
            (iv(0.1, 0.7), iv(3.0, 3.0)),
            (iv(-0.3, 0.7), iv(-2.5, 1.0 / 3.0)),
            (iv(-5.0, -0.1), iv(0.1, 0.2)),
            (iv(1e-20, 3e-20), iv(-1e-10, -1e-11)),
        ] {
            let m = x.mul_constant(&c);
            assert_eq!(m, x * c, "{x:?} · {c:?}");
            let ends = [q(x.inf()) * q(c.inf()), q(x.inf()) * q(c.sup())];
            let ends2 = [q(x.sup()) * q(c.inf()), q(x.sup()) * q(c.sup())];
            for e in ends.iter().chain(&ends2) {
                assert!(
                    q(m.inf()) <= *e && *e <= q(m.sup()),
                    "{x:?} · {c:?} = {m:?}"
                );
            }
        }
        let one = Interval::from_int(1);
        assert!(Interval::EMPTY.mul_constant(&one).is_empty());
        assert!(one.mul_constant(&Interval::EMPTY).is_empty());
        // pow: the base must be ≥ 0
        assert_eq!(
            Real::pow(&iv(-1.0, 2.0), &Interval::from_int(2)),
            Interval::ENTIRE
        );
        for (x, k, lo, hi) in [(iv(0.0, 2.0), 3, 0.0, 8.0), (iv(0.5, 2.0), 2, 0.25, 4.0)] {
            let p = Real::pow(&x, &Interval::from_int(k));
            assert!(
                p.inf() <= lo && lo - p.inf() < 1e-14 && hi <= p.sup() && p.sup() - hi < 1e-14,
                "{x:?}^{k} = {p:?}"
            );
        }
        // the exact small exponents
        for x in [iv(-0.3, 0.7), iv(-2.0, -0.5), iv(0.1, 3.0)] {
            assert_eq!(x.spow(&one), x);
            assert_eq!(x.apow(&one), Interval::abs(x));
            assert_eq!(x.apow(&Interval::from_int(2)), x.sqr());
            assert!(x.spow(&Interval::EMPTY).is_empty() && Interval::EMPTY.spow(&one).is_empty());
        }
        // unbounded operands: spow gives the whole line; x·k, x/k take inari's operation
        let inf = f64::INFINITY;
        let q = enclose_decimal("1.27").unwrap();
        assert_eq!(iv(-inf, 1.0).spow(&q), Interval::ENTIRE);
        assert_eq!(iv(-1.0, inf).spow(&q), Interval::ENTIRE);
        assert_eq!(iv(1.0, inf).div_int(4), iv(0.25, inf));
        assert_eq!(iv(-inf, 1.0).div_int(-4), iv(-0.25, inf));
        assert_eq!(iv(1.0, inf).mul_int(-4), iv(-inf, -4.0));
    }

    /// pow_ln (∂/∂q of the powers, for exponents given as ranges) and |x|^q with q reaching 0
    /// contain y^q·ln y and y^q at sample points, computed with MPFR (256 bits) and compared
    /// exactly with the bounds; boxes reaching 0 (the bounded forms) and away from it.
    #[test]
    fn power_log_and_zero_exponent_bounds_contain_mpfr_samples() {
        use rug::Float;
        use rug::ops::Pow;
        let inside = |x: &Float, e: Interval| *x >= e.inf() && *x <= e.sup();
        let exact = |y: f64, q: f64, log: bool| -> Float {
            let yf = Float::with_val(256, y.abs());
            if y == 0.0 {
                // the limits: y^q ln y → 0 (q ≥ 1); 0^q = 0 (q > 0), 1 at q = 0
                return Float::with_val(256, if !log && q == 0.0 { 1.0 } else { 0.0 });
            }
            let p = yf.clone().pow(Float::with_val(256, q));
            if log { p * yf.ln() } else { p }
        };
        let boxes = [
            (0.0, 0.0),
            (-1e-8, 1e-300),
            (-0.2, 0.3),
            (-0.5, 0.1),
            (0.0, 0.9),
            (-2.5, 1.0),
            (0.4, 3.0),
            (-3.0, -0.05),
        ];
        for (qa, qb) in [(1.0, 1.0), (1.0, 1.001), (1.27, 1.31), (2.0, 3.5)] {
            let q = Interval::try_from((qa, qb)).unwrap();
            for (a, b) in boxes {
                let w = Interval::try_from((a, b)).unwrap();
                let (u, s) = (
                    <Interval as Real>::pow_ln(&w, &q, false),
                    <Interval as Real>::pow_ln(&w, &q, true),
                );
                for i in 0..=40 {
                    let y = a + (b - a) * i as f64 / 40.0;
                    for qq in [qa, (qa + qb) / 2.0, qb] {
                        let g = exact(y, qq, true);
                        let sg = if y < 0.0 { -g.clone() } else { g.clone() };
                        assert!(inside(&g, u), "|w|^q ln|w|: y {y}, q {qq}: {g} ∉ {u:?}");
                        assert!(inside(&sg, s), "signed: y {y}, q {qq}: {sg} ∉ {s:?}");
                    }
                }
            }
        }
        // |x|^q for q ∈ [0, 0.001] (|z|^(n−1) with n ∈ [1, 1.001]) over boxes reaching 0
        let q = Interval::try_from((0.0, 0.001)).unwrap();
        for (a, b) in [
            (0.0, 0.0),
            (-1e-8, 1e-300),
            (-0.2, 0.3),
            (-2.5, 1.0),
            (0.0, 4.0),
        ] {
            let w = Interval::try_from((a, b)).unwrap();
            let r = w.apow(&q);
            for i in 0..=40 {
                let y = a + (b - a) * i as f64 / 40.0;
                for qq in [0.0, 0.0005, 0.001] {
                    let g = exact(y, qq, false);
                    assert!(inside(&g, r), "|y|^q: y {y}, q {qq}: {g} ∉ {r:?}");
                }
            }
        }
        // and sgn: ±1 off 0, the Clarke derivative [−1, 1] of |x| across it
        let sg = |a: f64, b: f64| Interval::try_from((a, b)).unwrap().sgn();
        assert_eq!(sg(0.5, 2.0), Interval::from_int(1));
        assert_eq!(sg(-2.0, -0.5), Interval::from_int(-1));
        assert_eq!(sg(-1.0, 1.0), Interval::try_from((-1.0, 1.0)).unwrap());
    }

    /// [`Real::mul_constant`] against inari's `*` on operands aimed at the thresholds of the
    /// `Ulp` product and of its fallback (products near 2^−1074, 2^−1022, 2^−969 and MAX;
    /// signed zeros, ±∞, thin and across 0): equal values, and equal bits up to the sign of a
    /// zero end.
    #[test]
    fn constant_products_on_threshold_operands() {
        use ulp::adversarial as ulp_adv;
        let mut g = ulp_adv::Gen::new(0x1f83_d9ab_fb41_bd6b);
        let mut fallback = 0u64;
        let mut n = 0u64;
        for _ in 0..ulp_adv::iters(3_000_000) {
            let (a, c) = g.pair(false);
            let (b, d) = if g.next().is_multiple_of(3) {
                (a, c)
            } else {
                g.pair(false)
            };
            let (b, d) = match g.next() % 8 {
                0 => (b, 0.0),
                1 => (-0.0, d),
                _ => (b, d),
            };
            let (Ok(x), Ok(y)) = (
                Interval::try_from((a.min(b), a.max(b))),
                Interval::try_from((c.min(d), c.max(d))),
            ) else {
                continue;
            };
            n += 1;
            let (m, e) = (x.mul_constant(&y), x * y);
            assert!(
                m.inf() == e.inf() && m.sup() == e.sup(),
                "{x:?} · {y:?}: {m:?} vs inari {e:?} ({:e} {:e} · {:e} {:e})",
                x.inf(),
                x.sup(),
                y.inf(),
                y.sup()
            );
            if (ulp::Ulp::of(x) * ulp::Ulp::of(y)).interval() != e {
                fallback += 1;
            }
        }
        assert!(
            n > ulp_adv::iters(3_000_000) * 2 / 3 && fallback > 1000,
            "{n} {fallback}"
        );
    }
}
