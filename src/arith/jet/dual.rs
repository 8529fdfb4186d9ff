//! Forward-mode dual numbers x + Σ dᵢ εᵢ (εᵢεⱼ = 0) over a [`Real`]: gradients and Jacobians of
//! the models' own code (∇𝒱 for the property tests, ∂f/∂x for the rigorous engine), not of a
//! second formula.
//!
//! | operation | derivative part |
//! |---|---|
//! | a·b | a′b + ab′ |
//! | a/b | (a′b − ab′)/b² |
//! | \|a\| | sgn(a)·a′ (at a = 0: [−1, 1]·a′ for intervals, Clarke's derivative) |
//! | \|a\|^(q−1)a | q\|a\|^(q−1)·a′ + \|a\|^(q−1)a·ln\|a\|·q′ |
//! | \|a\|^q | q\|a\|^(q−1)a·a′ + \|a\|^q·ln\|a\|·q′ |
//! | a^y (a > 0) | y a^(y−1)·a′ + a^y·ln a·y′ |
//! | ln a | a′/a |
//!
//! A derivative in the exponent (a model's n or p given as a range, carried as a variable by
//! the rigorous engine) needs ln|a|: at a = 0 it is unbounded, and so is the result's
//! derivative (an honest enclosure, never a wrong one).

use crate::arith::Dot;
use crate::arith::Real;
use crate::arith::Scalar;
use std::ops::{Add, Div, Mul, Neg, Sub};

#[derive(Clone, Debug, PartialEq)]
pub struct Dual<R, const M: usize> {
    pub v: R,
    pub d: [R; M],
}

/// [x, x, …, x] (one array constructor per number type and size, not one per call site: the
/// duals are instantiated for every arithmetic and dimension, and their call sites multiply
/// the code the compiler makes — issue #34, the test command's time).
fn filled<R: Clone, const M: usize>(x: R) -> [R; M] {
    std::array::from_fn(|_| x.clone())
}

/// The parts d with f applied to each, in place (for the same reason as [`filled`]).
fn map_parts<R, const M: usize>(mut d: [R; M], f: impl Fn(&R) -> R) -> [R; M] {
    for x in &mut d {
        *x = f(x);
    }
    d
}

/// The parts d and e combined by f, in d's place.
fn zip_parts<R, const M: usize>(mut d: [R; M], e: [R; M], f: impl Fn(&R, R) -> R) -> [R; M] {
    for (x, y) in d.iter_mut().zip(e) {
        *x = f(x, y);
    }
    d
}

impl<R: Real, const M: usize> Dual<R, M> {
    /// The i-th independent variable at value v.
    pub fn variable(v: R, i: usize) -> Self {
        let mut d: [R; M] = filled(R::zero());
        d[i] = R::one();
        Self { v, d }
    }
    pub fn constant(v: R) -> Self {
        Self {
            v,
            d: filled(R::zero()),
        }
    }
    /// Seeds a point as M independent variables.
    pub fn seed(x: &[R; M]) -> [Self; M] {
        std::array::from_fn(|i| Self::variable(x[i].clone(), i))
    }
    /// u = w^q (any of the powers) differentiated in the base only, plus the exponent's part
    /// u·ln|w|·q′ when q has a derivative (`ul` computes u·ln|w|, [`Real::pow_ln`]).
    fn with_exponent_part(mut self, q: &Self, ul: impl FnOnce() -> R) -> Self {
        if q.d.iter().all(|c| c.lo() == 0.0 && c.hi() == 0.0) {
            return self;
        }
        let ul = ul();
        for (d, dq) in self.d.iter_mut().zip(&q.d) {
            *d = d.clone() + ul.clone() * dq.clone();
        }
        self
    }
    fn chain(&self, v: R, dv: R) -> Self {
        let d = map_parts(self.d.clone(), |x| dv.clone() * x.clone());
        Self { v, d }
    }
}

impl<R: Real, const M: usize> Add for Dual<R, M> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let d = zip_parts(self.d, o.d, |x, y| x.clone() + y);
        Self { v: self.v + o.v, d }
    }
}
impl<R: Real, const M: usize> Sub for Dual<R, M> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        let d = zip_parts(self.d, o.d, |x, y| x.clone() - y);
        Self { v: self.v - o.v, d }
    }
}
impl<R: Real, const M: usize> Neg for Dual<R, M> {
    type Output = Self;
    fn neg(self) -> Self {
        let d = map_parts(self.d, |x| -x.clone());
        Self { v: -self.v, d }
    }
}
#[allow(clippy::suspicious_arithmetic_impl)]
impl<R: Real, const M: usize> Mul for Dual<R, M> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let d = zip_parts(self.d, o.d, |x, y| {
            x.clone() * o.v.clone() + self.v.clone() * y
        });
        Self { d, v: self.v * o.v }
    }
}
#[allow(clippy::suspicious_arithmetic_impl)]
impl<R: Real, const M: usize> Div for Dual<R, M> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let v = self.v.clone() / o.v.clone();
        let d = zip_parts(self.d, o.d, |x, y| {
            (x.clone() - v.clone() * y) / o.v.clone()
        });
        Self { d, v }
    }
}

impl<R: Real, const M: usize> Scalar<R> for Dual<R, M> {
    fn scale(&self, c: &R) -> Self {
        self.chain(self.v.clone() * c.clone(), c.clone())
    }
    fn shift(&self, c: &R) -> Self {
        Self {
            v: self.v.clone() + c.clone(),
            d: self.d.clone(),
        }
    }
    fn abs(&self) -> Self {
        let s = match self.v.sign() {
            Some(s) => R::from_int(s as i64),
            None => Real::sgn(&self.v),
        };
        self.chain(Real::abs(&self.v), s)
    }
    fn spow(&self, q: &R) -> Self {
        // d/dx |x|^(q−1)x = q|x|^(q−1) = q·(|x|^(q−1)x)/x for x ≠ 0: no second power
        let u = Real::spow(&self.v, q);
        let dq = if q.identical(&R::one()) {
            // |x|^0·x = x: the derivative is 1 everywhere, 0 included (not |x|^0, whose own
            // derivative 0·|x|^(−1) would put a power −1 of x on a recorded tape). `identical`,
            // not the value alone: an exponent 1 with derivative parts (on hyper-duals, the
            // differentiated input itself) takes the general form, whose derivative in q it is
            R::one()
        } else if self.v.sign().is_some() {
            q.clone() * u.clone() / self.v.clone()
        } else {
            q.clone() * Real::apow(&self.v, &(q.clone() - R::one()))
        };
        self.chain(u, dq)
    }
    fn apow(&self, q: &R) -> Self {
        // d/dx |x|^q = q|x|^(q−2)x = q·|x|^q/x (x ≠ 0), q·spow(x, q − 1) (q > 1), sign(x) (q = 1)
        let u = Real::apow(&self.v, q);
        let dq = if q.identical(&R::one()) {
            match self.v.sign() {
                Some(s) => R::from_int(s as i64),
                None => Real::sgn(&self.v),
            }
        } else if self.v.sign().is_some() {
            q.clone() * u.clone() / self.v.clone()
        } else {
            q.clone() * Real::spow(&self.v, &(q.clone() - R::one()))
        };
        self.chain(u, dq)
    }
}

/// Duals over a field are a field for the tape's recurrences; `pow`/`spow`/`apow`
/// differentiate in the base and, when it has a derivative, in the exponent.
/// Σ aⱼ·bⱼ over duals, one accumulator per component: (Σ aⱼbⱼ).v = Σ aⱼ.v·bⱼ.v and
/// (Σ aⱼbⱼ).dᵢ = Σ (aⱼ.v·bⱼ.dᵢ + aⱼ.dᵢ·bⱼ.v).
pub struct DualDot<R: Real, const M: usize> {
    v: R::Dot,
    d: [R::Dot; M],
}

impl<R: Real, const M: usize> Dot<Dual<R, M>> for DualDot<R, M> {
    #[inline]
    fn new() -> Self {
        Self {
            v: R::Dot::new(),
            d: std::array::from_fn(|_| R::Dot::new()),
        }
    }
    #[inline]
    fn add_prod(&mut self, a: &Dual<R, M>, b: &Dual<R, M>) {
        self.v.add_prod(&a.v, &b.v);
        for i in 0..M {
            self.d[i].add_prod(&a.v, &b.d[i]);
            self.d[i].add_prod(&a.d[i], &b.v);
        }
    }
    /// c·x for a constant c (zero derivative part): c·v + Σ c·dᵢ εᵢ, without the products by
    /// c's zero parts; a c with a derivative part takes the full product.
    #[inline]
    fn add_scaled(&mut self, c: &Dual<R, M>, x: &Dual<R, M>) {
        if c.d.iter().all(|z| z.lo() == 0.0 && z.hi() == 0.0) {
            self.v.add_scaled(&c.v, &x.v);
            for i in 0..M {
                self.d[i].add_scaled(&c.v, &x.d[i]);
            }
        } else {
            self.add_prod(c, x);
        }
    }
    #[inline]
    fn sum(self) -> Dual<R, M> {
        let mut it = self.d.into_iter();
        Dual {
            v: self.v.sum(),
            d: std::array::from_fn(|_| it.next().unwrap().sum()),
        }
    }
}

impl<R: Real, const M: usize> Real for Dual<R, M> {
    type Dot = DualDot<R, M>;
    type Prepared = ();
    fn prepare_exponent(_: &Self) {}
    fn from_int(k: i64) -> Self {
        Self::constant(R::from_int(k))
    }
    fn from_exact_f64(x: f64) -> Self {
        Self::constant(R::from_exact_f64(x))
    }
    fn parse_decimal(s: &str) -> Result<Self, String> {
        R::parse_decimal(s).map(Self::constant)
    }
    fn unbounded() -> Self {
        Self {
            v: R::unbounded(),
            d: filled(R::unbounded()),
        }
    }
    #[inline]
    fn mul_int(&self, k: i64) -> Self {
        Self {
            v: self.v.mul_int(k),
            d: map_parts(self.d.clone(), |x| x.mul_int(k)),
        }
    }
    #[inline]
    fn div_int(&self, k: i64) -> Self {
        Self {
            v: self.v.div_int(k),
            d: map_parts(self.d.clone(), |x| x.div_int(k)),
        }
    }
    #[inline]
    fn mul_constant(&self, c: &Self) -> Self {
        if c.d.iter().all(|x| x.lo() == 0.0 && x.hi() == 0.0) {
            Self {
                v: self.v.mul_constant(&c.v),
                d: map_parts(self.d.clone(), |x| x.mul_constant(&c.v)),
            }
        } else {
            self.clone() * c.clone()
        }
    }
    fn abs(&self) -> Self {
        <Self as Scalar<R>>::abs(self)
    }
    fn sqrt(&self) -> Self {
        let s = self.v.sqrt();
        let ds = R::one() / (R::from_int(2) * s.clone());
        self.chain(s, ds)
    }
    fn ln(&self) -> Self {
        let dl = R::one() / self.v.clone();
        self.chain(self.v.ln(), dl)
    }
    fn sgn(&self) -> Self {
        Self::constant(self.v.sgn())
    }
    /// The value only (the derivative of ∂(w^q)/∂q is not needed: unbounded).
    fn pow_ln(w: &Self, q: &Self, signed: bool) -> Self {
        Self {
            v: R::pow_ln(&w.v, &q.v, signed),
            d: filled(R::unbounded()),
        }
    }
    fn pow(&self, y: &Self) -> Self {
        // d/dx x^y = y x^(y−1)
        let dq = y.v.clone() * self.v.pow(&(y.v.clone() - R::one()));
        let u = self.chain(self.v.pow(&y.v), dq);
        u.with_exponent_part(y, || R::pow_ln(&self.v, &y.v, false))
    }
    fn spow(&self, q: &Self) -> Self {
        let u = <Self as Scalar<R>>::spow(self, &q.v);
        u.with_exponent_part(q, || R::pow_ln(&self.v, &q.v, true))
    }
    fn apow(&self, q: &Self) -> Self {
        let u = <Self as Scalar<R>>::apow(self, &q.v);
        u.with_exponent_part(q, || R::pow_ln(&self.v, &q.v, false))
    }
    fn lo(&self) -> f64 {
        self.v.lo()
    }
    fn hi(&self) -> f64 {
        self.v.hi()
    }
    fn mid(&self) -> f64 {
        self.v.mid()
    }
    /// Not decided for duals (no caller needs it): false.
    fn encloses(&self, _: &Self) -> bool {
        false
    }
    /// The same value and derivative parts, each decided by `R`.
    fn identical(&self, o: &Self) -> bool {
        self.v.identical(&o.v) && self.d.iter().zip(&o.d).all(|(a, b)| a.identical(b))
    }
    fn is_finite(&self) -> bool {
        self.v.is_finite() && self.d.iter().all(|c| c.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_of_powers() {
        let q = 1.7;
        for x in [-2.0_f64, -0.3, 0.4, 3.0] {
            let d = Dual::<f64, 1>::variable(x, 0);
            let s = Scalar::<f64>::spow(&d, &q);
            assert!((s.d[0] - q * x.abs().powf(q - 1.0)).abs() < 1e-14);
            let a = Scalar::<f64>::apow(&d, &q);
            assert!(
                (a.d[0] - q * x.abs().powf(q - 1.0) * x.signum()).abs() < 1e-14,
                "{x}"
            );
            let b = (d.clone() * d.clone() / Scalar::<f64>::shift(&d, &1.0)).d[0];
            let e = (2.0 * x * (x + 1.0) - x * x) / ((x + 1.0) * (x + 1.0));
            assert!((b - e).abs() < 1e-13);
        }
    }

    /// The dual (v; d₀, d₁) of point intervals.
    fn dual(v: f64, d0: f64, d1: f64) -> Dual<inari::Interval, 2> {
        let p = |x: f64| inari::Interval::try_from((x, x)).unwrap();
        Dual {
            v: p(v),
            d: [p(d0), p(d1)],
        }
    }

    /// Σ f·a·b over duals (the three-way terms of the power recurrence) is the product rule
    /// applied to each term, for a constant factor f and for one with derivatives; checked on
    /// exactly representable values.
    #[test]
    fn three_way_terms_of_duals_follow_the_product_rule() {
        use crate::arith::Dot;
        let (a, b) = (dual(2.0, 1.0, 0.5), dual(3.0, 0.0, -1.0));
        // f constant: 5ab + ab = 6ab, (6ab)' = 6(a′b + ab′)
        let mut s = DualDot::<inari::Interval, 2>::new();
        s.add_prod3(&dual(5.0, 0.0, 0.0), &a, &b);
        s.add_prod(&a, &b);
        let s = s.sum();
        // f = (5, 1, 0): (fab)' = f′ab + fa′b + fab′
        let mut t = DualDot::<inari::Interval, 2>::new();
        t.add_prod3(&dual(5.0, 1.0, 0.0), &a, &b);
        let t = t.sum();
        for (got, want) in [
            (s.v, 36.0),
            (s.d[0], 18.0),
            (s.d[1], -3.0),
            (t.v, 30.0),
            (t.d[0], 21.0),
            (t.d[1], -2.5),
        ] {
            assert!(got.contains(want) && got.wid() < 1e-12, "{got:?} ∌ {want}");
        }
    }

    /// c·x added by `add_scaled` (a tape constant c, the fused linear forms) is the product
    /// c·x: for a constant c without the products by its zero derivative parts, for a c with
    /// derivatives by the full product rule.
    #[test]
    fn scaled_terms_of_duals_are_the_products() {
        use crate::arith::Dot;
        let x = dual(3.0, 0.5, -2.0);
        // 4x − 0.5x = 3.5x; then (2 + ε₀)·x: v 6, d (2·0.5 + 3, 2·(−2))
        let mut s = DualDot::<inari::Interval, 2>::new();
        s.add_scaled(&dual(4.0, 0.0, 0.0), &x);
        s.add_scaled(&dual(-0.5, 0.0, 0.0), &x);
        let s = s.sum();
        let mut t = DualDot::<inari::Interval, 2>::new();
        t.add_scaled(&dual(2.0, 1.0, 0.0), &x);
        let t = t.sum();
        for (got, want) in [
            (s.v, 10.5),
            (s.d[0], 1.75),
            (s.d[1], -7.0),
            (t.v, 6.0),
            (t.d[0], 4.0),
            (t.d[1], -4.0),
        ] {
            assert!(got.contains(want) && got.wid() < 1e-12, "{got:?} ∌ {want}");
        }
    }

    /// A power whose exponent has a derivative (n or p given as a range): ∂/∂q |x|^q =
    /// |x|^q ln|x|, ∂/∂q |x|^(q−1)x = |x|^(q−1)x ln|x|, ∂/∂y a^y = a^y ln a, against the closed
    /// forms; and the base derivative stays q|x|^(q−1)(sign x).
    #[test]
    fn derivatives_in_the_exponent() {
        for x in [-2.0_f64, -0.3, 0.4, 3.0] {
            let q = Dual::<f64, 2>::variable(1.7, 1);
            let d = Dual::<f64, 2>::variable(x, 0);
            let a = Real::apow(&d, &q);
            let s = Real::spow(&d, &q);
            let l = x.abs().ln();
            let close = |got: f64, want: f64| (got - want).abs() <= 1e-13 * (1.0 + want.abs());
            assert!(close(a.d[1], x.abs().powf(1.7) * l), "{x}: {:?}", a.d);
            assert!(close(s.d[1], x.abs().powf(0.7) * x * l), "{x}: {:?}", s.d);
            assert!(close(a.d[0], 1.7 * x.abs().powf(0.7) * x.signum()), "{x}");
            assert!(close(s.d[0], 1.7 * x.abs().powf(0.7)), "{x}");
            if x > 0.0 {
                let p = Real::pow(&d, &q);
                assert!(close(p.d[1], x.powf(1.7) * x.ln()), "{x}");
                assert!(close(p.d[0], 1.7 * x.powf(0.7)), "{x}");
            }
        }
    }
}
