//! Sums of products Σ aⱼ·bⱼ, the inner loop of every Taylor recurrence (c_k = Σ a_j b_{k−j},
//! the power and quotient recurrences).
//!
//! Each [`Real`](super::Real) names an accumulator ([`Dot`]). For `f64` it is the plain sum.
//! For inari intervals it is [`IntervalDot`]: inari's operations switch the rounding mode
//! (MXCSR) twice per operation, which made interval products half of the rigorous engine's time;
//! the accumulator instead runs in round-to-nearest and adds a proved bound of every rounding
//! error once, at the end (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed.,
//! §2.2 and Thm. 3.1; the same idea as Rump's fast interval dot products in INTLAB).
//! For duals the accumulator is one per component.

use super::ulp::Ulp;
use crate::arith::Dot;
use inari::Interval;

/// 2^−53, the unit roundoff of round-to-nearest binary64.
const U: f64 = f64::EPSILON / 2.0;
/// 2^−1021 ≥ n·2^−1074 for every admissible n: a bound of the products' absolute rounding
/// errors when their results are subnormal (each ≤ 2^−1075). A normal number on purpose:
/// arithmetic on subnormals takes a microcode assist costing ~100 cycles.
const FLOOR: f64 = 2.0 * f64::MIN_POSITIVE;

/// Σ \[aⱼ\]·\[bⱼ\] for inari intervals, enclosed without switching the rounding mode.
///
/// For each term the four endpoint products are rounded to nearest and their minimum ℓ̃ⱼ and
/// maximum h̃ⱼ kept. Rounding is monotone, so ℓ̃ⱼ = fl(ℓⱼ) for the exact lower end ℓⱼ = min of
/// the exact products (likewise h̃ⱼ), and |ℓⱼ − ℓ̃ⱼ| ≤ u|ℓ̃ⱼ| + 2^−1074 (u = 2^−53; the second
/// term covers underflow). The sums S = fl(Σ ℓ̃ⱼ) and A = fl(Σ |ℓ̃ⱼ|) are accumulated
/// recursively in round-to-nearest: |S − Σ ℓ̃ⱼ| ≤ γ_{n−1} Σ|ℓ̃ⱼ| (Higham Thm. 3.1, no underflow
/// term for sums) and Σ|ℓ̃ⱼ| ≤ A/(1 − γ_{n−1}), with γ_m = mu/(1 − mu). Hence
///
/// ```text
/// Σ ℓⱼ ≥ S − (γ_{n−1} + u)/(1 − γ_{n−1})·A − n·2^−1074 ≥ S − (n + 1)·u·A − 2^−1021,
/// ```
///
/// since (γ_{n−1} + u)/(1 − γ_{n−1}) ≤ nu/(1 − 2nu) ≤ (n + 1)u whenever n(n + 1) ≤ 2^52. The
/// rounding of the final correction S − (n + 1)uA − 2^−1021 is covered by a larger constant
/// ((n + 4)u, see `ends`): one fused multiply-add and one subtraction per end, rounded to
/// nearest. The upper end is symmetric.
///
/// **Three-way terms** \[f\]·\[a\]·\[b\] ([`Dot::add_prod3`], |f| ≤ 2^20) take the four endpoint
/// products of \[a\]·\[b\] rounded to nearest, their minimum p̃₀ and maximum p̃₁ (= fl of the exact
/// ends P₀, P₁, by monotonicity), then the four products fl(f_x·p̃_e) and their minimum t̃ (and
/// maximum). The exact lower end is a corner f_x·P_e, and with c = fl(f_x·p̃_e),
/// |f_x·P_e − c| ≤ |f_x|·(u|p̃_e| + 2^−1075) + u|c| + 2^−1075 ≤ (2u + u²)|c| + (2 + F)·2^−1075
/// (F = max|f_x|). Since c ↦ c − (2u + u²)|c| is increasing, the exact lower end is
/// ≥ t̃ − (2u + u²)|t̃| − (2 + F)·2^−1075. Such a term is counted twice in n: with N terms of
/// which m ≥ 1 are three-way, (γ_{N−1} + 2u + u²)/(1 − γ_{N−1}) ≤ (N + 2)u ≤ (N + m + 1)u for
/// N ≤ 2^24, and the underflow terms stay below 2^−1021 for F ≤ 2^20. A larger |f| takes the
/// two-product route (a·f enclosed first). A non-finite sum (an unbounded or empty argument, an overflow)
/// gives [−∞, +∞], which encloses everything; a product 0·∞ inside an endpoint product is
/// ignored by min/max, as the set-based product [0, 0]·[1, ∞] = {0} requires.
#[derive(Clone, Copy, Debug)]
pub struct IntervalDot {
    lo: f64,
    hi: f64,
    abs_lo: f64,
    abs_hi: f64,
    n: u32,
    /// How many of the n terms are exactly 0: a factor [0, 0] (counted by
    /// [`Dot::add_scaled`] only, the fused linear forms of a tape). When all are, the sum is
    /// exactly 0 and no rounding bound is added (e.g. a force F ≡ 0: its sign stays decidable).
    zeros: u32,
}

/// The smallest and largest of the four endpoint products a_i·b_j, each rounded to nearest; a
/// NaN product (0·∞) is left out, as the set-based product [0, 0]·[1, ∞] = {0} requires (all
/// four NaN: (+∞, −∞), which makes the sum non-finite). With AVX the four products are one
/// vector operation.
#[inline(always)]
fn corner_range(a0: f64, a1: f64, b0: f64, b1: f64) -> (f64, f64) {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    {
        use std::arch::x86_64::*;
        // SAFETY: the intrinsics need AVX, which the cfg above guarantees at compile time;
        // they only read and write registers.
        unsafe {
            let p = _mm256_mul_pd(
                _mm256_setr_pd(a0, a0, a1, a1),
                _mm256_setr_pd(b0, b1, b0, b1),
            );
            let nan = _mm256_cmp_pd::<_CMP_UNORD_Q>(p, p);
            let pmin = _mm256_blendv_pd(p, _mm256_set1_pd(f64::INFINITY), nan);
            let pmax = _mm256_blendv_pd(p, _mm256_set1_pd(f64::NEG_INFINITY), nan);
            let m = _mm_min_pd(
                _mm256_castpd256_pd128(pmin),
                _mm256_extractf128_pd::<1>(pmin),
            );
            let x = _mm_max_pd(
                _mm256_castpd256_pd128(pmax),
                _mm256_extractf128_pd::<1>(pmax),
            );
            (
                _mm_cvtsd_f64(_mm_min_sd(m, _mm_unpackhi_pd(m, m))),
                _mm_cvtsd_f64(_mm_max_sd(x, _mm_unpackhi_pd(x, x))),
            )
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
    {
        corner_range_scalar(a0, a1, b0, b1)
    }
}

/// [`corner_range`] without vector instructions (`f64::min`/`max` skip a NaN operand; four
/// NaN products give (NaN, NaN), which makes the sum non-finite just the same).
#[inline(always)]
#[cfg_attr(all(target_arch = "x86_64", target_feature = "avx"), allow(dead_code))]
fn corner_range_scalar(a0: f64, a1: f64, b0: f64, b1: f64) -> (f64, f64) {
    let (p, q, r, s) = (a0 * b0, a0 * b1, a1 * b0, a1 * b1);
    (p.min(q).min(r.min(s)), p.max(q).max(r.max(s)))
}

/// The largest |f| of a three-way term taken in one pass (see [`IntervalDot`]); a NaN end
/// fails the test and takes the two-product route.
const F_MAX: f64 = (1u64 << 20) as f64;

/// The most terms one accumulator takes: n(n + 1) ≤ 2^52 with a wide margin.
const MAX_TERMS: u32 = 1 << 24;

impl IntervalDot {
    #[inline]
    fn empty() -> Self {
        Self {
            lo: 0.0,
            hi: 0.0,
            abs_lo: 0.0,
            abs_hi: 0.0,
            n: 0,
            zeros: 0,
        }
    }
    /// Adds [a0, a1]·[b0, b1].
    #[inline]
    fn add_ends(&mut self, a0: f64, a1: f64, b0: f64, b1: f64) {
        let (lo, hi) = corner_range(a0, a1, b0, b1);
        self.lo += lo;
        self.hi += hi;
        self.abs_lo += lo.abs();
        self.abs_hi += hi.abs();
        self.n += 1;
    }
    /// Adds [f0, f1]·[a0, a1]·[b0, b1] (|f| ≤ 2^20: see the type's documentation).
    #[inline]
    fn add_ends3(&mut self, f0: f64, f1: f64, a0: f64, a1: f64, b0: f64, b1: f64) {
        let (plo, phi) = corner_range(a0, a1, b0, b1);
        let (lo, hi) = corner_range(f0, f1, plo, phi);
        self.lo += lo;
        self.hi += hi;
        self.abs_lo += lo.abs();
        self.abs_hi += hi.abs();
        self.n += 2;
    }
    /// Adds [a0, a1]·[b0, b1], counting it among the exact zeros when a factor is [0, 0] (its
    /// set product is {0}, whatever the other factor).
    #[inline]
    fn add_ends_zero(&mut self, a0: f64, a1: f64, b0: f64, b1: f64) {
        self.add_ends(a0, a1, b0, b1);
        let zero = (a0 == 0.0 && a1 == 0.0) || (b0 == 0.0 && b1 == 0.0);
        self.zeros += zero as u32;
    }
    /// The enclosure (lo, hi) of the sum; (−∞, +∞) when not finite.
    #[inline(always)]
    fn ends(self) -> (f64, f64) {
        if self.n > 0 && self.zeros == self.n {
            // every term exactly 0: the exact sum (an empty sum keeps the bound below: measured,
            // the exact 0 there changed a path of Maxwell DSS v0 = 0.1 and left e 1.35× wider)
            return (0.0, 0.0);
        }
        let finite = self.lo.is_finite()
            && self.hi.is_finite()
            && self.abs_lo.is_finite()
            && self.abs_hi.is_finite();
        if !finite || self.n > MAX_TERMS {
            return (f64::NEG_INFINITY, f64::INFINITY);
        }
        // one fused step per end, no directed rounding: E = fl(c·A + 2^−1020) with
        // c = (n + 4)u (exact) and lo = fl(S − E). RN gives E ≥ (cA + 2^−1020)(1 − u) (normal)
        // and lo ≤ (S − E) + u(|S| + E) (exact when subnormal); with |S| ≤ 2A this is
        // ≤ S − (n + 1)uA − 2^−1021 as soon as (n + 4)(1 − 2u) ≥ n + 3, true for n ≤ 2^24.
        // The upper end is symmetric.
        let c = (self.n as f64 + 4.0) * U;
        let lo = self.lo - c.mul_add(self.abs_lo, 2.0 * FLOOR);
        let hi = self.hi + c.mul_add(self.abs_hi, 2.0 * FLOOR);
        (lo, hi)
    }
}

impl Dot<Interval> for IntervalDot {
    #[inline]
    fn new() -> Self {
        Self::empty()
    }
    #[inline]
    fn add_prod(&mut self, a: &Interval, b: &Interval) {
        self.add_ends(a.inf(), a.sup(), b.inf(), b.sup());
    }
    #[inline]
    fn add_prod3(&mut self, f: &Interval, a: &Interval, b: &Interval) {
        if f.mag() <= F_MAX {
            self.add_ends3(f.inf(), f.sup(), a.inf(), a.sup(), b.inf(), b.sup());
        } else {
            self.add_prod(&(*a * *f), b);
        }
    }
    #[inline]
    fn add_scaled(&mut self, c: &Interval, x: &Interval) {
        self.add_ends_zero(c.inf(), c.sup(), x.inf(), x.sup());
    }
    #[inline]
    fn sum(self) -> Interval {
        Interval::try_from(self.ends()).unwrap_or(Interval::ENTIRE)
    }
}

/// Σ aⱼ·bⱼ over inari intervals by one [`IntervalDot`] (the small matrix–vector products of a
/// step: Jacobians, the affine set's J·g_j and offsets Σ g_j·u_j). A constant term c could enter
/// as (c, 1), but its rounding bound then scales with |c|: a large c is added after the sum.
#[inline]
pub fn interval_dot(terms: impl IntoIterator<Item = (Interval, Interval)>) -> Interval {
    let mut d = IntervalDot::empty();
    for (a, b) in terms {
        d.add_ends(a.inf(), a.sup(), b.inf(), b.sup());
    }
    d.sum()
}

/// The same accumulator over [`Ulp`] intervals (endpoints read directly).
#[derive(Clone, Copy, Debug)]
pub struct UlpDot(IntervalDot);

impl Dot<Ulp> for UlpDot {
    #[inline]
    fn new() -> Self {
        Self(IntervalDot::empty())
    }
    #[inline]
    fn add_prod(&mut self, a: &Ulp, b: &Ulp) {
        self.0.add_ends(a.lo, a.hi, b.lo, b.hi);
    }
    #[inline]
    fn add_prod3(&mut self, f: &Ulp, a: &Ulp, b: &Ulp) {
        if f.lo.abs().max(f.hi.abs()) <= F_MAX {
            self.0.add_ends3(f.lo, f.hi, a.lo, a.hi, b.lo, b.hi);
        } else {
            self.add_prod(&(*a * *f), b);
        }
    }
    #[inline]
    fn add_scaled(&mut self, c: &Ulp, x: &Ulp) {
        self.0.add_ends_zero(c.lo, c.hi, x.lo, x.hi);
    }
    #[inline]
    fn sum(self) -> Ulp {
        let (lo, hi) = self.0.ends();
        Ulp { lo, hi }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::PlainDot;
    use rug::Rational;

    /// The exact interval Σ [aⱼ]·[bⱼ] (finite endpoints), as rationals.
    fn exact(terms: &[(Interval, Interval)]) -> (Rational, Rational) {
        let mut lo = Rational::new();
        let mut hi = Rational::new();
        for (a, b) in terms {
            let ends = |x: &Interval| {
                [
                    Rational::from_f64(x.inf()).unwrap(),
                    Rational::from_f64(x.sup()).unwrap(),
                ]
            };
            let mut ps: Vec<Rational> = Vec::new();
            for x in ends(a) {
                for y in ends(b) {
                    ps.push(Rational::from(&x * &y));
                }
            }
            lo += ps.iter().min().unwrap();
            hi += ps.iter().max().unwrap();
        }
        (lo, hi)
    }

    fn encloses(r: Interval, (lo, hi): &(Rational, Rational)) -> bool {
        let below = r.inf() == f64::NEG_INFINITY || Rational::from_f64(r.inf()).unwrap() <= *lo;
        let above = r.sup() == f64::INFINITY || *hi <= Rational::from_f64(r.sup()).unwrap();
        below && above
    }

    fn iv(a: f64, b: f64) -> Interval {
        Interval::try_from((a, b)).unwrap()
    }

    fn dot(terms: &[(Interval, Interval)]) -> Interval {
        let mut d = IntervalDot::new();
        for (a, b) in terms {
            d.add_prod(a, b);
        }
        d.sum()
    }

    /// A deterministic pseudo-random stream (xorshift) of doubles over many binades, of both
    /// signs, with exact zeros and thin intervals among them.
    struct Gen(u64);
    impl Gen {
        fn next(&mut self) -> u64 {
            crate::arith::interval::xorshift_step(&mut self.0)
        }
        fn float(&mut self, binades: i32) -> f64 {
            let r = self.next();
            let m = 1.0 + (r >> 12) as f64 / (1u64 << 52) as f64;
            let e = (r % (2 * binades as u64 + 1)) as i32 - binades;
            let s = if r & (1 << 11) != 0 { -1.0 } else { 1.0 };
            if r.is_multiple_of(17) {
                0.0
            } else {
                s * m * 2f64.powi(e)
            }
        }
        fn interval(&mut self, binades: i32) -> Interval {
            let a = self.float(binades);
            match self.next() % 4 {
                0 => iv(a, a),
                1 => iv(a, a.next_up().next_up()),
                _ => {
                    let b = self.float(binades);
                    iv(a.min(b), a.max(b))
                }
            }
        }
    }

    #[test]
    fn encloses_the_exact_sum_of_random_products() {
        let mut g = Gen(0x9e3779b97f4a7c15);
        for binades in [2, 30, 300, 1000] {
            for n in [1, 2, 3, 7, 21, 60] {
                for _ in 0..200 {
                    let terms: Vec<(Interval, Interval)> = (0..n)
                        .map(|_| (g.interval(binades), g.interval(binades)))
                        .collect();
                    let r = dot(&terms);
                    let e = exact(&terms);
                    assert!(encloses(r, &e), "{terms:?} → {r:?}");
                }
            }
        }
    }

    /// The exact Σ [fⱼ]·[aⱼ]·[bⱼ] (finite endpoints), as rationals: min and max over the eight
    /// endpoint products of each term.
    fn exact3(terms: &[(Interval, Interval, Interval)]) -> (Rational, Rational) {
        let mut lo = Rational::new();
        let mut hi = Rational::new();
        let ends = |x: &Interval| {
            [
                Rational::from_f64(x.inf()).unwrap(),
                Rational::from_f64(x.sup()).unwrap(),
            ]
        };
        for (f, a, b) in terms {
            let mut ps: Vec<Rational> = Vec::new();
            for x in ends(f) {
                for y in ends(a) {
                    for z in ends(b) {
                        ps.push(Rational::from(&x * &y) * &z);
                    }
                }
            }
            lo += ps.iter().min().unwrap();
            hi += ps.iter().max().unwrap();
        }
        (lo, hi)
    }

    #[test]
    fn three_way_terms_enclose_the_exact_sum() {
        // factors like the power recurrence's q(k − j) − j (thin, either sign, up to 2^20) and
        // beyond 2^20 (the two-product route), mixed with two-way terms in one accumulator;
        // Interval and Ulp accumulators give the same endpoints
        let mut g = Gen(0x2545f4914f6cdd1d);
        for binades in [2, 30, 300, 1000] {
            for n in [1, 2, 5, 21] {
                for _ in 0..200 {
                    let terms: Vec<(Interval, Interval, Interval)> = (0..n)
                        .map(|i| {
                            let f = if i % 3 == 2 {
                                g.interval(binades)
                            } else {
                                let m = (g.next() % (1 << 21)) as f64 - (1 << 20) as f64;
                                let x = m + 0.3;
                                iv(x, x.next_up())
                            };
                            (f, g.interval(binades), g.interval(binades))
                        })
                        .collect();
                    let mut d = IntervalDot::new();
                    let mut du = UlpDot::new();
                    let mut pairs = Vec::new();
                    for (j, (f, a, b)) in terms.iter().enumerate() {
                        if j % 4 == 3 {
                            // a two-way term in the same sum: [f]·[a] enclosed first (inari)
                            d.add_prod(&(*f * *a), b);
                            du.add_prod(&Ulp::of(*f * *a), &Ulp::of(*b));
                            pairs.push((*f * *a, *b));
                        } else {
                            d.add_prod3(f, a, b);
                            du.add_prod3(&Ulp::of(*f), &Ulp::of(*a), &Ulp::of(*b));
                        }
                    }
                    let r = d.sum();
                    assert_eq!(r, du.sum().interval());
                    if pairs.iter().any(|(x, _)| !x.is_common_interval()) {
                        // f·a overflowed: the sum is [−∞, +∞], which encloses everything
                        assert!(r.is_entire(), "{terms:?} → {r:?}");
                        continue;
                    }
                    let triples: Vec<_> = terms
                        .iter()
                        .enumerate()
                        .filter(|(j, _)| j % 4 != 3)
                        .map(|(_, t)| *t)
                        .collect();
                    let (l3, h3) = exact3(&triples);
                    let (l2, h2) = exact(&pairs);
                    let e = (l3 + l2, h3 + h2);
                    assert!(encloses(r, &e), "{terms:?} → {r:?}");
                }
            }
        }
    }

    /// Many three-way terms whose recursive sum rounds the same way at every step (N copies
    /// of a double below 1): the sum's error grows like N²u while a bound that did not count
    /// the terms stays ~4u·A. Each three-way term counts twice in n (see [`IntervalDot`]).
    #[test]
    fn many_three_way_terms_count_in_the_error_bound() {
        let one = iv(1.0, 1.0);
        for (x, n) in [(0.1, 100), (0.3, 300), (0.7, 1000), (1.0 / 3.0, 300)] {
            let terms: Vec<(Interval, Interval, Interval)> =
                (0..n).map(|_| (one, iv(x, x), one)).collect();
            let mut d = IntervalDot::new();
            let mut du = UlpDot::new();
            for (f, a, b) in &terms {
                d.add_prod3(f, a, b);
                du.add_prod3(&Ulp::of(*f), &Ulp::of(*a), &Ulp::of(*b));
            }
            let e = exact3(&terms);
            let (r, ru) = (d.sum(), du.sum().interval());
            assert!(encloses(r, &e), "{n} × {x}: {r:?}");
            assert!(encloses(ru, &e), "{n} × {x} (Ulp): {ru:?}");
        }
    }

    /// The plain accumulator sums the products in the type's own arithmetic.
    #[test]
    fn plain_sums_are_the_sums_of_products() {
        let mut d = PlainDot::<Interval>::new();
        d.add_prod(&iv(1.0, 2.0), &iv(3.0, 3.0));
        d.add_prod(&iv(-1.0, -1.0), &iv(2.0, 2.0));
        d.add_prod(&iv(0.5, 0.5), &iv(-4.0, 2.0));
        assert_eq!(d.sum(), iv(-1.0, 5.0));
        assert_eq!(PlainDot::<Interval>::new().sum(), iv(0.0, 0.0));
    }

    #[test]
    fn three_way_terms_are_tight_on_thin_data() {
        // the width is that of the rounding errors: ≤ (2n + 1)·u·Σ|terms| (n = 21)
        let mut g = Gen(777);
        for _ in 0..200 {
            let terms: Vec<(Interval, Interval, Interval)> = (0..21)
                .map(|j| {
                    let (a, b) = (g.float(3), g.float(3));
                    let f = 1.27 * (21 - j) as f64 - j as f64;
                    (iv(f, f), iv(a, a), iv(b, b))
                })
                .collect();
            let mut d = IntervalDot::new();
            for (f, a, b) in &terms {
                d.add_prod3(f, a, b);
            }
            let r = d.sum();
            let scale: f64 = terms
                .iter()
                .map(|(f, a, b)| (f.sup() * a.sup() * b.sup()).abs())
                .sum();
            assert!(r.wid() <= 2.0 * 44.0 * f64::EPSILON * scale, "{r:?}");
            let (lo, hi) = exact3(&terms);
            assert!(encloses(r, &(lo, hi)), "{r:?}");
        }
    }

    #[test]
    fn vector_and_scalar_corner_ranges_agree() {
        // including 0·∞ (left out), all-NaN products and signed zeros
        let mut g = Gen(4242);
        let special = [
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1.0,
            -2.5,
            f64::MAX,
        ];
        for i in 0..20_000 {
            let mut pick = |j: u64| {
                if (i + j).is_multiple_of(5) {
                    special[(g.next() % special.len() as u64) as usize]
                } else {
                    g.float(300)
                }
            };
            let (a0, a1, b0, b1) = (pick(0), pick(1), pick(2), pick(3));
            let (l, h) = corner_range(a0, a1, b0, b1);
            let (ls, hs) = corner_range_scalar(a0, a1, b0, b1);
            let same = |x: f64, y: f64| {
                x == y || (x.is_nan() && y.is_infinite()) || x.is_nan() && y.is_nan()
            };
            assert!(
                same(ls, l) && same(hs, h),
                "{a0} {a1} {b0} {b1}: ({l}, {h}) vs ({ls}, {hs})"
            );
        }
    }

    #[test]
    fn encloses_subnormal_products_and_cancellation() {
        let t = f64::from_bits(1);
        let cases: Vec<Vec<(Interval, Interval)>> = vec![
            // every product underflows (rounds to 0 or to a subnormal)
            vec![
                (iv(t, 3.0 * t), iv(0.3, 0.7)),
                (iv(1e-160, 1e-160), iv(1e-160, 3e-160)),
            ],
            // catastrophic cancellation: 1 + 2^-60 − 1
            vec![
                (iv(1.0, 1.0), iv(1.0, 1.0)),
                (
                    iv(2f64.powi(-30), 2f64.powi(-30)),
                    iv(2f64.powi(-30), 2f64.powi(-30)),
                ),
                (iv(-1.0, -1.0), iv(1.0, 1.0)),
            ],
            // products that round: (1 + 2^-52)² and 0.1·0.3
            vec![
                (
                    iv(1.0 + f64::EPSILON, 1.0 + f64::EPSILON),
                    iv(1.0 + f64::EPSILON, 1.0 + f64::EPSILON),
                ),
                (iv(0.1, 0.1), iv(-0.3, -0.3)),
            ],
        ];
        for terms in cases {
            let r = dot(&terms);
            assert!(encloses(r, &exact(&terms)), "{terms:?} → {r:?}");
        }
    }

    #[test]
    fn is_as_tight_as_inari_within_a_few_ulps() {
        // thin data: the enclosure is a few ulps wide, like inari's term-by-term result
        let mut g = Gen(12345);
        for _ in 0..500 {
            let terms: Vec<(Interval, Interval)> = (0..21)
                .map(|_| {
                    let a = g.float(3);
                    let b = g.float(3);
                    (iv(a, a), iv(b, b))
                })
                .collect();
            let r = dot(&terms);
            let inari = terms.iter().fold(iv(0.0, 0.0), |s, (a, b)| s + *a * *b);
            let scale: f64 = terms.iter().map(|(a, b)| (a.sup() * b.sup()).abs()).sum();
            assert!(
                r.wid() <= 2.0 * 22.0 * f64::EPSILON * scale + 1e-300,
                "{r:?}"
            );
            assert!(
                inari.wid() <= 2.0 * 22.0 * f64::EPSILON * scale + 1e-300,
                "{inari:?}"
            );
        }
    }

    #[test]
    fn unbounded_and_empty_arguments_give_the_whole_line() {
        let one = iv(1.0, 1.0);
        assert_eq!(dot(&[(one, Interval::ENTIRE)]), Interval::ENTIRE);
        assert_eq!(dot(&[(one, iv(1.0, f64::INFINITY))]), Interval::ENTIRE);
        assert_eq!(
            dot(&[(iv(f64::MAX, f64::MAX), iv(2.0, 2.0))]),
            Interval::ENTIRE
        );
        assert!(dot(&[(Interval::EMPTY, one)]).is_entire());
        // the set-based 0·∞ = 0 inside a term does not hide the other terms
        let z = dot(&[(iv(0.0, 0.0), iv(1.0, f64::INFINITY))]);
        assert!(z.contains(0.0) && z.wid() < 1e-300, "{z:?}");
        let e = dot(&[]);
        assert!(e.contains(0.0) && e.wid() < 1e-300, "{e:?}");
        // finite sums whose sum of magnitudes overflows (on one side only): no error bound
        let m = f64::MAX;
        let c = dot(&[(iv(-m, 0.0), one), (iv(0.6 * m, 0.6 * m), one)]);
        assert_eq!(c, Interval::ENTIRE, "{c:?}");
        // as many terms as the error bound is proved for, then one more
        let mut d = IntervalDot::new();
        for _ in 0..MAX_TERMS {
            d.add_prod(&one, &one);
        }
        let full = d.sum();
        assert!(
            full.contains(MAX_TERMS as f64) && full.wid() < 1.0,
            "{full:?}"
        );
        d.add_prod(&one, &one);
        assert_eq!(d.sum(), Interval::ENTIRE);
    }
}
