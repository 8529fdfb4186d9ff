//! Decimals of enclosure bounds rounded outward, exactly.
//!
//! A double is a dyadic rational m·2^q; its decimal expansion is exact but can be ~770 digits
//! long, and every shorter decimal lies on one side of it. For a bound, the side matters: a
//! printed lower bound must be ≤ the double (rounded toward −∞), an upper bound ≥ it (toward
//! +∞), or the printed interval no longer contains what was proved.
//!
//! Two forms, both computed exactly on rationals (`rug`), never through f64 formatting:
//! - [`directed`]: exactly D significant digits, the nearest D-digit decimal on the given side
//!   (the tightest at that count: one more step inward would cross the double);
//! - [`outward`]: the shortest decimal on the given side that still reads back (round to
//!   nearest) to the same double. This is the form for machine-read output (JSON, CSV,
//!   certificates): the printed decimal is a bound of the true value *and* a reader that parses
//!   it as a double gets the engine's bound bit for bit. Its distance to the double is at most
//!   half an ulp, and it has at most 18 significant digits (the half-ulp interval below a double
//!   is ≥ 2⁻⁵⁴ relative, wider than the 10⁻¹⁷ relative spacing of 18-digit decimals).
//!
//! The tighter choice "17 digits rounded outward" ([`directed`] with D = 17) is within one unit
//! of the 17th digit, but may read back to the neighbouring double: it is used where the
//! digits must line up (the table), not where a program reads the number back.

use rug::ops::DivRounding;
use rug::{Integer, Rational};

/// The direction of rounding of a bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rounding {
    /// Toward −∞: for a lower bound.
    Down,
    /// Toward +∞: for an upper bound (and for a width).
    Up,
}

impl Rounding {
    /// The other direction.
    pub fn flip(self) -> Self {
        match self {
            Rounding::Down => Rounding::Up,
            Rounding::Up => Rounding::Down,
        }
    }
}

/// A finite decimal `(−1)^neg · digits · 10^exp`, `digits` without leading zeros (empty for 0)
/// and without trailing zeros.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Decimal {
    pub neg: bool,
    pub digits: String,
    pub exp: i64,
}

impl Decimal {
    fn new(q: Integer, mut exp: i64) -> Self {
        let neg = q < 0;
        let mut digits = q.abs().to_string();
        if digits == "0" {
            return Decimal {
                neg: false,
                digits: String::new(),
                exp: 0,
            };
        }
        while digits.ends_with('0') {
            digits.pop();
            exp += 1;
        }
        Decimal { neg, digits, exp }
    }

    /// The decimal exponent of the leading digit (d.ddd × 10^e form); 0 for zero.
    pub fn sci_exp(&self) -> i64 {
        if self.digits.is_empty() {
            0
        } else {
            self.exp + self.digits.len() as i64 - 1
        }
    }

    /// The exact value.
    pub fn to_rational(&self) -> Rational {
        let m = Integer::from_str_radix(
            if self.digits.is_empty() {
                "0"
            } else {
                &self.digits
            },
            10,
        )
        .expect("digits");
        let m = if self.neg { -m } else { m };
        m * pow10(self.exp)
    }

    /// Scientific form with at least `min_digits` significant digits (trailing zeros added):
    /// `d.ddde<E>` as Rust's `{:.Ne}` writes it (`0e0` for zero).
    pub fn scientific(&self, min_digits: usize) -> String {
        let mut d = if self.digits.is_empty() {
            "0".to_string()
        } else {
            self.digits.clone()
        };
        while d.len() < min_digits.max(1) {
            d.push('0');
        }
        let sign = if self.neg { "-" } else { "" };
        let (head, tail) = d.split_at(1);
        let dot = if tail.is_empty() { "" } else { "." };
        format!("{sign}{head}{dot}{tail}e{}", self.sci_exp())
    }

    /// Plain form (`0.00123`, `1234.5`, `100`), no exponent.
    pub fn plain(&self) -> String {
        if self.digits.is_empty() {
            return "0".into();
        }
        let sign = if self.neg { "-" } else { "" };
        let n = self.digits.len() as i64;
        let body = if self.exp >= 0 {
            format!("{}{}", self.digits, "0".repeat(self.exp as usize))
        } else if -self.exp < n {
            let (a, b) = self.digits.split_at((n + self.exp) as usize);
            format!("{a}.{b}")
        } else {
            format!("0.{}{}", "0".repeat((-self.exp - n) as usize), self.digits)
        };
        format!("{sign}{body}")
    }

    /// The form of the crate's plain numbers: plain for 10⁻⁵ ≤ |x| < 10¹⁶ (and 0), exponent form
    /// (`1.5e-7`, `2e300`) otherwise. A valid JSON number.
    pub fn text(&self) -> String {
        let e = self.sci_exp();
        if self.digits.is_empty() || (-5..16).contains(&e) {
            self.plain()
        } else {
            self.scientific(1)
        }
    }
}

/// 10^e as an exact rational.
fn pow10(e: i64) -> Rational {
    let p = Integer::from(Integer::u_pow_u(10, e.unsigned_abs() as u32));
    if e >= 0 {
        Rational::from(p)
    } else {
        Rational::from((Integer::from(1), p))
    }
}

/// The exponent E with 10^E ≤ |r| < 10^(E+1), for r ≠ 0.
fn decade(r: &Rational) -> i64 {
    let a = Rational::from(r.abs_ref());
    // a first guess from the f64 value (exact up to ±1 away from the subnormal range)
    let mut e = a.to_f64().log10().floor();
    if !e.is_finite() {
        e = -330.0;
    }
    let mut e = e as i64;
    while pow10(e) > a {
        e -= 1;
    }
    while pow10(e + 1) <= a {
        e += 1;
    }
    e
}

/// The exact rational `r` rounded in direction `dir` to `digits` ≥ 1 significant digits.
pub fn directed_rational(r: &Rational, digits: usize, dir: Rounding) -> Decimal {
    if *r == 0 {
        return Decimal::new(Integer::new(), 0);
    }
    let exp = decade(r) - digits.max(1) as i64 + 1;
    let scaled = r / pow10(exp);
    let (num, den) = scaled.into_numer_denom();
    let q = match dir {
        Rounding::Down => num.div_floor(den),
        Rounding::Up => num.div_ceil(den),
    };
    Decimal::new(q, exp)
}

/// `x` with exactly `digits` significant digits, rounded in direction `dir` (the tightest such
/// decimal on that side). `None` for ±∞ and NaN.
pub fn directed(x: f64, digits: usize, dir: Rounding) -> Option<Decimal> {
    let r = Rational::from_f64(x)?;
    Some(directed_rational(&r, digits, dir))
}

/// The shortest decimal on side `dir` of `x` that reads back (round to nearest) to `x`: a
/// bound of everything `x` bounds, and `x` itself for a program that parses it. `None` for ±∞
/// and NaN.
pub fn outward_decimal(x: f64, dir: Rounding) -> Option<Decimal> {
    let r = Rational::from_f64(x)?;
    // ends at the latest when the decimal is x itself (at most 767 significant digits)
    (1..).find_map(|d| {
        let dec = directed_rational(&r, d, dir);
        let back: f64 = dec.scientific(1).parse().ok()?;
        (back == x).then_some(dec)
    })
}

/// [`outward_decimal`] as text ([`Decimal::text`]); `inf`, `-inf`, `NaN` for the non-finite.
pub fn outward(x: f64, dir: Rounding) -> String {
    match outward_decimal(x, dir) {
        Some(d) => d.text(),
        None => format!("{x}"),
    }
}

/// The exact decimal value of the double `x` (every double is a finite decimal: at most 767
/// significant digits, ≈ 50 for a value near 10): for a point that bounds sets on both of its
/// sides, such as where one row's refuted range of a parameter ends and the next one's begins.
/// `inf`, `-inf`, `NaN` for the non-finite.
pub fn exact(x: f64) -> String {
    let Some(r) = Rational::from_f64(x) else {
        return format!("{x}");
    };
    // rounded at 767 significant digits it is exact (Decimal drops the trailing zeros)
    directed_rational(&r, 767, Rounding::Down).text()
}

/// An upper bound of the width hi − lo as a double (the difference rounded up, exactly): what a
/// printed width is computed from. +∞ if a bound is not finite.
pub fn width_up(lo: f64, hi: f64) -> f64 {
    let w = hi - lo;
    match (
        Rational::from_f64(lo),
        Rational::from_f64(hi),
        Rational::from_f64(w),
    ) {
        (Some(l), Some(h), Some(wr)) if wr < Rational::from(&h - &l) => w.next_up(),
        (Some(_), Some(_), Some(_)) => w,
        _ => f64::INFINITY,
    }
}

/// `x` rounded up to `digits` significant digits in scientific form (`7.84e-13` for 3): a short
/// printed upper bound, e.g. of a width.
pub fn sci_up(x: f64, digits: usize) -> String {
    match directed(x, digits, Rounding::Up) {
        Some(d) => d.scientific(digits),
        None => format!("{x}"),
    }
}

/// The exact value of a decimal number as written (`-1.25e-3`, `0.1`, `7`); `None` if it is
/// not one. For tests and checkers that compare a printed bound with a double exactly.
pub fn parse_rational(s: &str) -> Option<Rational> {
    let s = s.trim();
    let (neg, s) = match s.strip_prefix('-') {
        Some(t) => (true, t),
        None => (false, s.strip_prefix('+').unwrap_or(s)),
    };
    let (mant, exp) = match s.find(['e', 'E']) {
        Some(i) => (&s[..i], s[i + 1..].parse::<i64>().ok()?),
        None => (s, 0),
    };
    let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
    if int.is_empty() && frac.is_empty()
        || !int.bytes().chain(frac.bytes()).all(|b| b.is_ascii_digit())
        || exp.abs() > 100_000
    {
        return None;
    }
    let digits = format!("{int}{frac}");
    let m = Integer::from_str_radix(&digits, 10).ok()?;
    let m = if neg { -m } else { m };
    Some(m * pow10(exp - frac.len() as i64))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// One step of `digits`-digit decimals at the place of `d`'s last digit, toward `x`.
    fn step(d: &Decimal, digits: usize) -> Rational {
        pow10(d.sci_exp() - digits as i64 + 1)
    }

    /// `dec` lies on side `dir` of `x`, and one step inward (at `digits` digits) would cross x.
    fn check_tight(x: f64, dec: &Decimal, digits: usize, dir: Rounding) {
        let r = Rational::from_f64(x).unwrap();
        let v = dec.to_rational();
        match dir {
            Rounding::Down => assert!(v <= r, "{x:e}: {} above", dec.scientific(1)),
            Rounding::Up => assert!(v >= r, "{x:e}: {} below", dec.scientific(1)),
        }
        assert!(
            dec.digits.len() <= digits,
            "{x:e}: {dec:?} has > {digits} digits"
        );
        if v != r {
            // the decade of the inward neighbour can be lower (10.0 → 9.99…): its step is the
            // smaller one; either way it must cross x
            let s = step(dec, digits);
            let s_low = pow10(dec.sci_exp() - digits as i64);
            for s in [s, s_low] {
                let inward = match dir {
                    Rounding::Down => Rational::from(&v + &s),
                    Rounding::Up => Rational::from(&v - &s),
                };
                let fits = directed_rational(&inward, digits, dir).to_rational() == inward;
                if fits {
                    match dir {
                        Rounding::Down => assert!(inward > r, "{x:e}: {dec:?} not tightest"),
                        Rounding::Up => assert!(inward < r, "{x:e}: {dec:?} not tightest"),
                    }
                }
            }
        }
    }

    fn check_outward(x: f64, dir: Rounding) {
        let dec = outward_decimal(x, dir).unwrap();
        let text = dec.text();
        // the text is the decimal, exactly
        assert_eq!(parse_rational(&text).unwrap(), dec.to_rational(), "{text}");
        assert_eq!(
            text.parse::<f64>().unwrap(),
            x,
            "{text} does not read back to {x:e}"
        );
        let n = dec.digits.len().max(1);
        assert!(n <= 18, "{x:e}: {text} has {n} digits");
        check_tight(x, &dec, n, dir);
        // and no shorter decimal on that side reads back
        if n > 1 {
            let shorter = directed(x, n - 1, dir).unwrap();
            assert_ne!(shorter.scientific(1).parse::<f64>().unwrap(), x, "{x:e}");
        }
    }

    fn check_all(x: f64) {
        for dir in [Rounding::Down, Rounding::Up] {
            check_outward(x, dir);
            for d in [1, 2, 5, 16, 17, 18] {
                check_tight(x, &directed(x, d, dir).unwrap(), d, dir);
            }
        }
    }

    fn special() -> Vec<f64> {
        let mut v = vec![
            0.0,
            -0.0,
            1.0,
            0.1,
            0.5,
            1e308,
            f64::MAX,
            f64::MIN_POSITIVE,
            f64::MIN_POSITIVE.next_down(),
            f64::from_bits(1),
            f64::from_bits(2),
            f64::from_bits(3),
            5e-324,
            2.2250738585072014e-308,
            0.3,
            2.0 / 3.0,
            1e23f64.next_down(),
            1e23,
            1e-5,
            1e16,
            123456789012345680.0,
            // the engine's bounds of the SHC DSS e at v0 = 0.1 (from the certificate)
            f64::from_bits(0x3fef4506a249c231),
            f64::from_bits(0x3fef4506a249c7b4),
            f64::from_bits(0x40096cc0a5d36a01),
        ];
        for k in -320..=308 {
            v.push(format!("1e{k}").parse().unwrap());
            // x.5 at some digit: a halfway case of round-to-nearest
            v.push(format!("1.5e{k}").parse().unwrap());
            v.push(format!("9.5e{k}").parse().unwrap());
        }
        for k in -1074..=1023 {
            let p = if k >= -1022 {
                f64::from_bits(((k + 1023) as u64) << 52)
            } else {
                f64::from_bits(1 << (k + 1074))
            };
            v.extend([p, p.next_down(), p.next_up()]);
        }
        // halfway cases of 17-digit rounding: exact doubles ending in 5 at the 18th digit
        for i in 0..200u64 {
            v.push((1u64 << 53) as f64 + 2.0 * i as f64 + 1.0);
            v.push(((1u64 << 52) + 2 * i + 1) as f64 * 0.5);
        }
        v.retain(|x| x.is_finite());
        let neg: Vec<f64> = v.iter().map(|x| -x).collect();
        v.extend(neg);
        v
    }

    #[test]
    fn decimal_special_values_outward_and_tightest() {
        for x in special() {
            check_all(x);
        }
    }

    #[test]
    fn decimal_random_doubles_outward_and_tightest() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        for i in 0..10_000 {
            let x = if i % 2 == 0 {
                // any bit pattern: subnormals, huge, tiny
                f64::from_bits(rng.random::<u64>())
            } else {
                // ordinary magnitudes, like enclosure bounds
                rng.random_range(-10.0..10.0)
            };
            if x.is_finite() {
                check_all(x);
            }
        }
    }

    #[test]
    fn decimal_directed_examples() {
        let s = |x: f64, d, dir| directed(x, d, dir).unwrap().scientific(d);
        // 0.1 = 0.1000000000000000055511151231257827…
        assert_eq!(s(0.1, 17, Rounding::Down), "1.0000000000000000e-1");
        assert_eq!(s(0.1, 17, Rounding::Up), "1.0000000000000001e-1");
        assert_eq!(s(-0.1, 17, Rounding::Down), "-1.0000000000000001e-1");
        assert_eq!(s(-0.1, 17, Rounding::Up), "-1.0000000000000000e-1");
        assert_eq!(s(0.5, 3, Rounding::Up), "5.00e-1");
        assert_eq!(s(9.99, 2, Rounding::Up), "1.0e1");
        assert_eq!(s(0.0, 17, Rounding::Down), "0.0000000000000000e0");
        assert_eq!(outward(0.1, Rounding::Down), "0.1");
        assert_eq!(outward(0.1, Rounding::Up), "0.10000000000000001");
        assert_eq!(outward(-0.1, Rounding::Down), "-0.10000000000000001");
        assert_eq!(outward(1e300, Rounding::Up), "1.0000000000000001e300");
        assert_eq!(outward(5e-324, Rounding::Down), "4e-324");
        assert_eq!(outward(-0.0, Rounding::Down), "0");
        assert_eq!(outward(f64::NEG_INFINITY, Rounding::Down), "-inf");
        assert!(directed(f64::NAN, 3, Rounding::Up).is_none());
    }

    #[test]
    fn decimal_width_up_is_an_upper_bound() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for _ in 0..10_000 {
            let lo: f64 = rng.random_range(-10.0..10.0);
            let hi = lo + rng.random_range(0.0..1e-10) * [1.0, 1e10][rng.random_range(0..2)];
            let w = width_up(lo, hi);
            let exact = Rational::from_f64(hi).unwrap() - Rational::from_f64(lo).unwrap();
            assert!(Rational::from_f64(w).unwrap() >= exact, "{lo:e} {hi:e}");
            assert!(
                Rational::from_f64(w.next_down()).unwrap() < exact,
                "{lo:e} {hi:e}"
            );
            assert!(parse_rational(&sci_up(w, 3)).unwrap() >= exact);
        }
        assert_eq!(sci_up(7.831e-13, 3), "7.84e-13");
        assert_eq!(width_up(1.0, f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn decimal_parse_rational_exact() {
        let q = |s| parse_rational(s).unwrap();
        assert_eq!(q("0.1"), Rational::from((1, 10)));
        assert_eq!(q("-1.25e-3"), Rational::from((-1, 800)));
        assert_eq!(q("12e2"), Rational::from(1200));
        assert_eq!(q("5."), Rational::from(5));
        for bad in [
            "", "e5", "1.2.3", "--1", "1e", "inf", "NaN", "0x10", "1e999999",
        ] {
            assert!(parse_rational(bad).is_none(), "{bad}");
        }
    }
}
