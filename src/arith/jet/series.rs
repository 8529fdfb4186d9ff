//! Truncated Taylor series over any [`Real`], and the coefficient recurrences.
//!
//! A series u(t) = Σ_{k<K} u_k t^k. The recurrences (Moore; Griewank & Walther, ch. 13) give
//! the k-th coefficient of a result from coefficients 0..k of the operands and 0..k−1 of the
//! result, so that the rigorous engine can also run them one order at a time:
//!
//! | operation | k-th coefficient |
//! |---|---|
//! | c = a·b | c_k = Σ_{j=0}^{k} a_j b_{k−j} |
//! | c = a/b | c_k = (a_k − Σ_{j=1}^{k} b_j c_{k−j}) / b_0 |
//! | u = w^q, w_0 > 0 | u_0 = w_0^q, u_k = 1/(k w_0) Σ_{j=0}^{k−1} (q(k−j) − j) w_{k−j} u_j (from w u′ = q u w′) |
//! | L = ln w, then u = e^{qL} (several powers of one w) | k L_k = (k w_k − Σ_{0<j<k} j L_j w_{k−j})/w_0, u_k = (q/k) Σ_{j=1}^{k} j L_j u_{k−j} |
//! | \|w\| | s·w_k, s = sign(w_0) |
//! | \|w\|^(q−1) w | s·(s w)^q |
//! | \|w\|^q | (s w)^q |
//!
//! |·| and the real powers are analytic only where the sign s of w is fixed: a series whose
//! constant term's sign is not certain (an interval containing 0) has no expansion and yields
//! [`Real::unbounded`] coefficients — the honest answer. For `f64` a zero constant term takes the
//! sign of the first non-zero coefficient (the branch the function follows for t > 0). Odd
//! integer powers |w|^(q−1)w = w^q and even |w|^q = w^q are analytic everywhere and are
//! expanded by products.

use crate::arith::Dot;
use crate::arith::Real;
use crate::arith::Scalar;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// c_k of c = a·b.
#[inline]
pub fn mul_k<R: Real>(a: &[R], b: &[R], k: usize) -> R {
    let mut s = R::Dot::new();
    for j in 0..=k {
        s.add_prod(&a[j], &b[k - j]);
    }
    s.sum()
}

/// c_k of c = a/b, given c_0..c_{k−1}.
#[inline]
pub fn div_k<R: Real>(a: &[R], b: &[R], c: &[R], k: usize) -> R {
    let mut s = R::Dot::new();
    for j in 1..=k {
        s.add_prod(&b[j], &c[k - j]);
    }
    (a[k].clone() - s.sum()) / b[0].clone()
}

/// u_k of u = w^q (w_0 > 0), given u_0..u_{k−1} and the factors f_j = q(k − j) − j
/// (j < k, [`pow_factors`]); k ≥ 1:
/// u_k = 1/(k w_0) Σ_{j<k} f_j w_{k−j} u_j, each factor applied to its term inside the sum
/// ([`Dot::add_prod3`]). (Splitting it as q·Σ(k−j)w u − Σ j w u, two sums that nearly cancel
/// at high orders, was measured 25% wider and cost a third more steps.)
#[inline]
pub fn pow_k<R: Real>(w: &[R], u: &[R], f: &[R], k: usize) -> R {
    let mut d = R::Dot::new();
    for j in 0..k {
        d.add_prod3(&f[j], &w[k - j], &u[j]);
    }
    (d.sum() / w[0].clone()).div_int(k as i64)
}

/// The factors f_j = q(k − j) − j, j < k, of [`pow_k`] for order k.
pub fn pow_factors<R: Real>(q: &R, k: usize) -> impl Iterator<Item = R> + '_ {
    (0..k).map(move |j| q.mul_int((k - j) as i64) - R::from_int(j as i64))
}

/// k·L_k of L = ln|w| (w_0 ≠ 0), given jL_j = j·L_j for 0 < j < k; k ≥ 1. From w′ = w L′:
/// k w_k = Σ_{j=1}^{k} j L_j w_{k−j}, so k L_k = (k w_k − Σ_{0<j<k} jL_j w_{k−j}) / w_0 (the
/// sign of w cancels: the same for |w| = ±w).
#[inline]
pub fn log_k<R: Real>(w: &[R], jl: &[R], k: usize) -> R {
    let mut d = R::Dot::new();
    for j in 1..k {
        d.add_prod(&jl[j], &w[k - j]);
    }
    (w[k].mul_int(k as i64) - d.sum()) / w[0].clone()
}

/// u_k of u = exp(q L) = |w|^q from jL_j = j·L_j (1 ≤ j ≤ k) and u_0..u_{k−1}; k ≥ 1.
/// From u′ = q L′ u: u_k = (q/k) Σ_{j=1}^{k} jL_j u_{k−j} — one sum per power once the log's
/// series is known, so several powers of one base cost one log recurrence plus one sum each
/// (and a single sum with no cancellation between sums).
#[inline]
pub fn exp_log_k<R: Real>(jl: &[R], u: &[R], q: &R, k: usize) -> R {
    let mut d = R::Dot::new();
    for j in 1..=k {
        d.add_prod(&jl[j], &u[k - j]);
    }
    d.sum().mul_constant(q).div_int(k as i64)
}

/// The branch sign of a series: that of its constant term, or for an exact zero (f64) that of
/// its first non-zero coefficient; `None` when it cannot be decided.
pub fn branch_sign<R: Real>(w: &[R]) -> Option<i8> {
    if let Some(s) = w[0].sign() {
        return Some(s);
    }
    if w[0].lo() == 0.0 && w[0].hi() == 0.0 {
        for c in &w[1..] {
            if c.lo() == 0.0 && c.hi() == 0.0 {
                continue;
            }
            return c.sign();
        }
    }
    None
}

/// The kind of a power node: which analytic formula expands it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PowKind {
    /// |w|^(q−1)·w
    Signed,
    /// |w|^q
    Absolute,
}

/// Coefficients 0..K of |w|^(q−1)w or |w|^q, given the branch sign `s` of w (`None`: no
/// expansion exists; everything but an exact constant term is unbounded).
pub fn pow_series<R: Real>(w: &[R], q: &R, kind: PowKind, s: Option<i8>) -> Vec<R> {
    let kk = w.len();
    if let Some(k) = q.as_integer() {
        let analytic = match kind {
            PowKind::Signed => k % 2 == 1,
            PowKind::Absolute => k % 2 == 0,
        };
        if analytic && k >= 0 {
            let mut u = vec![R::zero(); kk];
            u[0] = R::one();
            for _ in 0..k {
                u = (0..kk).map(|i| mul_k(&u, w, i)).collect();
            }
            return u;
        }
    }
    let Some(s) = s else {
        let mut u = vec![R::unbounded(); kk];
        u[0] = match kind {
            PowKind::Signed => w[0].spow(q),
            PowKind::Absolute => w[0].apow(q),
        };
        return u;
    };
    let sw: Vec<R> = if s > 0 {
        w.to_vec()
    } else {
        w.iter().map(|c| -c.clone()).collect()
    };
    let mut u = Vec::with_capacity(kk);
    u.push(sw[0].apow(q));
    if sw[0].lo() == 0.0 && sw[0].hi() == 0.0 && kk > 1 {
        // a zero base: the branch point itself, no Taylor expansion (unless q is a small
        // integer, handled above)
        u.extend((1..kk).map(|_| R::unbounded()));
    } else {
        for k in 1..kk {
            let f: Vec<R> = pow_factors(q, k).collect();
            let c = pow_k(&sw, &u, &f, k);
            u.push(c);
        }
    }
    if kind == PowKind::Signed && s < 0 {
        u.iter_mut().for_each(|c| *c = -c.clone());
    }
    u
}

/// A truncated Taylor series Σ_{k<K} c_k t^k with coefficients in `R`.
#[derive(Clone, Debug, PartialEq)]
pub struct Series<R> {
    pub c: Vec<R>,
}

impl<R: Real> Series<R> {
    /// The series of the variable t ↦ x0 + t (K coefficients).
    pub fn variable(x0: R, order: usize) -> Self {
        let mut c = vec![R::zero(); order + 1];
        c[0] = x0;
        if order >= 1 {
            c[1] = R::one();
        }
        Self { c }
    }
    /// A constant series.
    pub fn constant(x0: R, order: usize) -> Self {
        let mut c = vec![R::zero(); order + 1];
        c[0] = x0;
        Self { c }
    }
    pub fn from_coefficients(c: Vec<R>) -> Self {
        assert!(!c.is_empty());
        Self { c }
    }
    /// The truncation order K − 1.
    pub fn order(&self) -> usize {
        self.c.len() - 1
    }
    /// Evaluates Σ c_k t^k by Horner's rule.
    pub fn eval(&self, t: &R) -> R {
        let mut s = self.c[self.c.len() - 1].clone();
        for c in self.c.iter().rev().skip(1) {
            s = s * t.clone() + c.clone();
        }
        s
    }
    fn zip(&self, o: &Self, f: impl Fn(&R, &R) -> R) -> Self {
        assert_eq!(self.c.len(), o.c.len(), "series of different orders");
        Self {
            c: self.c.iter().zip(&o.c).map(|(a, b)| f(a, b)).collect(),
        }
    }
}

impl<R: Real> Add for Series<R> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        self.zip(&o, |a, b| a.clone() + b.clone())
    }
}
impl<R: Real> Sub for Series<R> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self.zip(&o, |a, b| a.clone() - b.clone())
    }
}
impl<R: Real> Neg for Series<R> {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            c: self.c.into_iter().map(|a| -a).collect(),
        }
    }
}
impl<R: Real> Mul for Series<R> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        assert_eq!(self.c.len(), o.c.len(), "series of different orders");
        Self {
            c: (0..self.c.len()).map(|k| mul_k(&self.c, &o.c, k)).collect(),
        }
    }
}
impl<R: Real> Div for Series<R> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        assert_eq!(self.c.len(), o.c.len(), "series of different orders");
        let mut c: Vec<R> = Vec::with_capacity(self.c.len());
        for k in 0..self.c.len() {
            let v = div_k(&self.c, &o.c, &c, k);
            c.push(v);
        }
        Self { c }
    }
}

impl<R: Real> Scalar<R> for Series<R> {
    fn scale(&self, c: &R) -> Self {
        Self {
            c: self.c.iter().map(|a| a.clone() * c.clone()).collect(),
        }
    }
    fn shift(&self, c: &R) -> Self {
        let mut s = self.clone();
        s.c[0] = s.c[0].clone() + c.clone();
        s
    }
    fn abs(&self) -> Self {
        match branch_sign(&self.c) {
            Some(1) => self.clone(),
            Some(_) => -self.clone(),
            None => {
                let mut c = vec![R::unbounded(); self.c.len()];
                c[0] = Real::abs(&self.c[0]);
                Self { c }
            }
        }
    }
    fn spow(&self, q: &R) -> Self {
        Self {
            c: pow_series(&self.c, q, PowKind::Signed, branch_sign(&self.c)),
        }
    }
    fn apow(&self, q: &R) -> Self {
        Self {
            c: pow_series(&self.c, q, PowKind::Absolute, branch_sign(&self.c)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use inari::Interval;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + b.abs())
    }

    #[test]
    fn power_series_of_one_plus_t() {
        // (1 + t)^q = Σ binom(q, k) t^k
        let q = 1.27;
        let w = Series::variable(1.0, 8);
        let u = w.apow(&q);
        let mut b = 1.0;
        for k in 0..=8 {
            assert!(close(u.c[k], b, 1e-14), "k={k}: {} vs {b}", u.c[k]);
            b *= (q - k as f64) / (k as f64 + 1.0);
        }
        // |w|^(q−1)w at w = −1 − t: −(1 + t)^q
        let mut m = vec![0.0; 9];
        m[0] = -1.0;
        m[1] = -1.0;
        let v = Series::from_coefficients(m).spow(&q);
        assert!(v.c.iter().zip(&u.c).all(|(a, b)| close(*a, -b, 1e-14)));
    }

    #[test]
    fn products_quotients_and_integer_powers() {
        let a = Series::from_coefficients(vec![1.0, 2.0, 3.0]);
        let b = Series::from_coefficients(vec![2.0, -1.0, 0.5]);
        let c = a.clone() * b.clone();
        assert_eq!(c.c, vec![2.0, 3.0, 4.5]);
        let d = c / b;
        assert!(d.c.iter().zip(&a.c).all(|(x, y)| close(*x, *y, 1e-15)));
        // |w|^2 = w² for any sign, even through 0
        let w = Series::variable(0.0, 3);
        assert_eq!(w.apow(&2.0).c, vec![0.0, 0.0, 1.0, 0.0]);
        // |w|^(3−1) w = w³
        assert_eq!(w.spow(&3.0).c, vec![0.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn interval_series_enclose_float_series_and_refuse_branch_points() {
        let q: Interval = "[1.31]".parse().unwrap();
        let w = Series::variable(Interval::try_from((0.49, 0.51)).unwrap(), 6);
        let u = w.spow(&q);
        let f = Series::variable(0.5, 6).spow(&1.31);
        for (i, fc) in u.c.iter().zip(&f.c) {
            assert!(i.contains(*fc), "{fc} ∉ {i:?}");
        }
        // a base straddling 0: no expansion, unbounded coefficients
        let z = Series::variable(Interval::try_from((-0.1, 0.1)).unwrap(), 3);
        assert!(z.apow(&q).c[1].is_entire());
        assert!(z.abs().c[2].is_entire());
    }

    /// The recurrences of the rigorous engine's powers on w = 2 + t (w₀ ≠ 1, so that a
    /// product and a quotient by w₀ differ): k·L_k of ln(2 + t) is (−1)^(k+1)/2^k, and
    /// (2 + t)³ = 8 + 12t + 6t² + t³ both by exp(3L) and by the power recurrence.
    #[test]
    fn log_exp_and_power_recurrences_on_two_plus_t() {
        use inari::Interval;
        let p = |x: f64| Interval::try_from((x, x)).unwrap();
        let n = 6;
        let mut w = vec![p(2.0), p(1.0)];
        w.resize(n + 1, p(0.0));
        let near = |got: Interval, want: f64| got.contains(want) && got.wid() < 1e-12;
        let mut jl = vec![p(0.0); n + 1];
        for k in 1..=n {
            jl[k] = log_k(&w[..=k], &jl[..k], k);
            let want = if k % 2 == 1 { 1.0 } else { -1.0 } / 2f64.powi(k as i32);
            assert!(near(jl[k], want), "k·L_{k} = {:?}, want {want}", jl[k]);
        }
        let q = p(3.0);
        let cube = [8.0, 12.0, 6.0, 1.0, 0.0, 0.0, 0.0];
        let (mut ue, mut up) = (vec![p(8.0)], vec![p(8.0)]);
        for k in 1..=n {
            ue.push(exp_log_k(&jl[..=k], &ue[..k], &q, k));
            let f: Vec<Interval> = pow_factors(&q, k).collect();
            up.push(pow_k(&w[..=k], &up[..k], &f, k));
            assert!(near(ue[k], cube[k]), "exp(3L)_{k} = {:?}", ue[k]);
            assert!(near(up[k], cube[k]), "pow_{k} = {:?}", up[k]);
        }
    }
}
