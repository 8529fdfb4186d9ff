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
use inari::Interval;

/// An accumulator of Σ aⱼ·bⱼ over a number type `R`.
pub trait Dot<R>: Sized {
    /// The empty sum.
    fn new() -> Self;
    /// Adds a·b.
    fn add_prod(&mut self, a: &R, b: &R);
    /// The sum (for an interval type: an enclosure of the exact sum of the exact products).
    fn sum(self) -> R;
}

/// The plain f64 sum, rounded to nearest term by term (as `s = s + a * b`).
#[derive(Clone, Copy, Debug, Default)]
pub struct F64Dot(f64);

impl Dot<f64> for F64Dot {
    #[inline]
    fn new() -> Self {
        Self(0.0)
    }
    #[inline]
    fn add_prod(&mut self, a: &f64, b: &f64) {
        self.0 += a * b;
    }
    #[inline]
    fn sum(self) -> f64 {
        self.0
    }
}

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
/// final subtraction is rounded outwards by one ulp at each operation (`next_down`/`next_up`).
/// The upper end is symmetric. A non-finite sum (an unbounded or empty argument, an overflow)
/// gives [−∞, +∞], which encloses everything; a product 0·∞ inside an endpoint product is
/// ignored by min/max, as the set-based product [0, 0]·[1, ∞] = {0} requires.
#[derive(Clone, Copy, Debug)]
pub struct IntervalDot {
    lo: f64,
    hi: f64,
    abs_lo: f64,
    abs_hi: f64,
    n: u32,
}

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
        }
    }
    /// Adds [a0, a1]·[b0, b1].
    #[inline]
    fn add_ends(&mut self, a0: f64, a1: f64, b0: f64, b1: f64) {
        let (p, q, r, s) = (a0 * b0, a0 * b1, a1 * b0, a1 * b1);
        let lo = p.min(q).min(r.min(s));
        let hi = p.max(q).max(r.max(s));
        self.lo += lo;
        self.hi += hi;
        self.abs_lo += lo.abs();
        self.abs_hi += hi.abs();
        self.n += 1;
    }
    /// The enclosure (lo, hi) of the sum; (−∞, +∞) when not finite.
    #[inline(always)]
    fn ends(self) -> (f64, f64) {
        let finite = self.lo.is_finite()
            && self.hi.is_finite()
            && self.abs_lo.is_finite()
            && self.abs_hi.is_finite();
        if !finite || self.n > MAX_TERMS {
            return (f64::NEG_INFINITY, f64::INFINITY);
        }
        // (n + 1)·u is exact; c·A is rounded up by a step (c·A ≥ 2^−1021·u·A is normal
        // unless A is tiny), then FLOOR added and rounded up again
        let c = (self.n as f64 + 1.0) * U;
        let err = |a: f64| {
            if a == 0.0 {
                FLOOR
            } else {
                ((c * a).next_up() + FLOOR).next_up()
            }
        };
        let lo = (self.lo - err(self.abs_lo)).next_down();
        let hi = (self.hi + err(self.abs_hi)).next_up();
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
    fn sum(self) -> Interval {
        Interval::try_from(self.ends()).unwrap_or(Interval::ENTIRE)
    }
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
    fn sum(self) -> Ulp {
        let (lo, hi) = self.0.ends();
        Ulp { lo, hi }
    }
}

/// A sum of products in a type's own arithmetic (for types without a faster accumulator).
#[derive(Clone, Debug)]
pub struct PlainDot<R>(Option<R>);

impl<R: super::Real> Dot<R> for PlainDot<R> {
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
    fn sum(self) -> R {
        self.0.unwrap_or_else(R::zero)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
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
    }
}
