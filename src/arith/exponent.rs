//! An exponent of the models' powers (n, p of eq:BWHCL), prepared once.
//!
//! The right-hand sides raise state components to the same few parameters at every
//! evaluation: |z|^(n−1)z, |x|^(p−1)x, … An [`Exponent`] carries the parameter q together
//! with whatever its arithmetic precomputes for q ([`Real::Prepared`]): the `f64` engine's
//! power tables for |x|^(q−1) ([`super::fastpow`]), nothing for the interval types. The
//! models build their exponents when they are built, and call the `*_prepared` powers of
//! [`super::Scalar`]; every other arithmetic evaluates those exactly like `spow`, `apow`,
//! `spow_apow` and `spow_base` with q itself.

use super::real::Real;

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
