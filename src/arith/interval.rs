//! inari's `Interval` as a [`Real`]: every operation encloses the exact result.
//!
//! Decimal input is enclosed as written (inari parses `"[0.632]"` to the tightest interval
//! containing the decimal 0.632), never rounded to a double first.

use super::real::Real;
use inari::{Interval, const_interval};

/// [0, +∞), the domain of `pow`.
const NONNEG: Interval = const_interval!(0.0, f64::INFINITY);

/// Encloses a decimal literal exactly as written.
pub fn enclose_decimal(s: &str) -> Result<Interval, String> {
    let t = s.trim();
    // inari's grammar takes a bracketed literal; reject what is not a plain decimal first so that
    // e.g. "[1,2]" or "inf" are not silently accepted as parameters.
    let ok = !t.is_empty()
        && t.chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E'));
    if !ok {
        return Err(format!("'{t}' is not a decimal number"));
    }
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

/// x^q for x ≥ 0: the fast enclosure of [`super::elementary::pow`], else inari's (MPFR).
fn power(x: Interval, q: Interval) -> Interval {
    super::elementary::pow(x, q).unwrap_or_else(|| Interval::pow(x, q))
}

impl Real for Interval {
    fn from_int(k: i64) -> Self {
        let x = k as f64;
        assert!(x as i64 == k, "integer constant {k} is not exact in f64");
        Interval::try_from((x, x)).unwrap()
    }
    fn from_exact_f64(x: f64) -> Self {
        Interval::try_from((x, x)).unwrap_or(Interval::EMPTY)
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
                1 => return Interval::abs(*self),
                2 => return self.sqr(),
                _ => {}
            }
        }
        power(Interval::abs(*self).intersection(NONNEG), *q)
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
