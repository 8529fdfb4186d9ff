//! Interval arithmetic with directed rounding recovered from round-to-nearest, for short hot
//! loops (the series of [`crate::arith::interval::elementary`], Horner evaluation of Taylor polynomials).
//!
//! inari rounds each endpoint in the right direction by switching the rounding mode (MXCSR)
//! around every operation; that switch costs more than the arithmetic. Here each endpoint is
//! computed in round-to-nearest together with its exact error, and moved one floating-point
//! number outwards only when the error points that way, which is exactly the directed rounding:
//!
//! - a sum s = fl(a + b): TwoSum (Knuth) gives e with a + b = s + e exactly (no underflow
//!   error for sums); rounded down is `next_down(s)` if e < 0, else s;
//! - a product p = fl(a·b): the FMA gives e = a·b − p exactly when |p| ≥ 2^−969 (the residual
//!   is then representable); below that, where the residual may not be, p is stepped outwards
//!   unconditionally (valid: the rounding error is under one spacing);
//! - an overflow to ±∞ in the wrong direction is replaced by ±f64::MAX, and 0·∞ counts as 0
//!   (the set-based product).
//!
//! So results equal inari's in the common case; a result below 2^−969 in magnitude (stepped out
//! unconditionally) or a quotient by a divisor touching 0 (every real) may be wider than
//! inari's, never narrower (tests below: enclosure of the exact rational results, and
//! `ulp_ops_hold_inari_and_the_exact_corners`).

use inari::Interval;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A closed interval [lo, hi] of finite or infinite f64 endpoints, lo ≤ hi (no empty set: the
/// callers convert from non-empty inari intervals and back).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ulp {
    pub lo: f64,
    pub hi: f64,
}

impl Ulp {
    /// The thin interval [x, x].
    #[inline]
    pub const fn point(x: f64) -> Self {
        Self { lo: x, hi: x }
    }
    /// [−∞, +∞].
    pub const ENTIRE: Self = Self {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };
    /// From an inari interval (the empty set, which only an operation outside its domain
    /// yields, becomes [−∞, +∞]: still an enclosure of whatever the caller meant).
    #[inline]
    pub fn of(x: Interval) -> Self {
        if x.is_empty() {
            return Self::ENTIRE;
        }
        Self {
            lo: x.inf(),
            hi: x.sup(),
        }
    }
    /// To an inari interval ([−∞, +∞] if an endpoint became NaN).
    #[inline]
    pub fn interval(self) -> Interval {
        Interval::try_from((self.lo, self.hi)).unwrap_or(Interval::ENTIRE)
    }
    /// max(|lo|, |hi|).
    #[inline]
    pub fn mag(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }
    /// x^n for x ≥ 0 by binary powering (each product of nonnegative factors is monotone).
    pub fn powi_nonneg(self, mut n: u32) -> Self {
        debug_assert!(self.lo >= 0.0);
        let (mut base, mut acc) = (self, Self::point(1.0));
        while n > 0 {
            if n & 1 == 1 {
                acc = acc * base;
            }
            base = base * base;
            n >>= 1;
        }
        acc
    }
}

/// 2^−969: above it a product's FMA residual is exact.
pub(crate) const RESIDUAL_EXACT: f64 = 2.004168360008973e-292;

/// a + b rounded towards −∞ (`up = false`) or +∞.
#[inline]
fn add_dir(a: f64, b: f64, up: bool) -> f64 {
    let s = a + b;
    if !s.is_finite() {
        return rare(s, false, a.is_finite() && b.is_finite(), up);
    }
    // TwoSum: a + b = s + e exactly — unless an intermediate overflows (a and b of opposite
    // signs near ±MAX, e.g. −3·2^970 + MAX: s − a = MAX + 2^970 rounds to ∞ and e is NaN;
    // found by an adversarial review, test `sum_at_max_keeps_the_exact_value`)
    let bb = s - a;
    let mut e = (a - (s - bb)) + (b - bb);
    if !e.is_finite() {
        e = halves_error(a, b, s);
        if e.is_nan() {
            // the error's sign unknown: one spacing outward covers it (|e| ≤ half a spacing)
            return if up { s.next_up() } else { s.next_down() };
        }
    }
    // the exact sum lies above s when e > 0: the upper end steps up (the lower down for e < 0)
    nudge(s, up, if up { e > 0.0 } else { e < 0.0 })
}

/// The sign-carrying error of s = fl(a + b) when TwoSum's intermediates overflow: TwoSum on
/// a/2 and b/2, where nothing overflows (a/2 + b/2 = s/2 + e/2 exactly: halving a normal
/// double is exact, and rounding commutes with the scaling by 2 at these magnitudes); NaN
/// where a halving or fl(a/2 + b/2) = s/2 does not hold (the caller then steps outward).
#[cold]
fn halves_error(a: f64, b: f64, s: f64) -> f64 {
    let (ha, hb) = (0.5 * a, 0.5 * b);
    let hs = ha + hb;
    if 2.0 * ha != a || 2.0 * hb != b || 2.0 * hs != s {
        return f64::NAN;
    }
    let hbb = hs - ha;
    (ha - (hs - hbb)) + (hb - hbb)
}

/// x if `m`, else y, from the bits (without a branch: `m` is data, see [`nudge`]).
#[inline(always)]
fn select(m: bool, x: f64, y: f64) -> f64 {
    let k = (m as u64).wrapping_neg();
    f64::from_bits((x.to_bits() & k) | (y.to_bits() & !k))
}

/// x moved to its neighbour towards +∞ (`up`) or −∞ when `go` holds, else x; x finite and
/// non-zero whenever `go` holds (a directed rounding steps only a result that was rounded,
/// which a zero never is: a sum or difference rounds to 0 only when exact, and the products
/// and quotients step only results of magnitude ≥ 2^−969).
///
/// Without branches: which side of the nearest result the exact one lies on is data — about
/// half of the ends step, in no pattern a branch predictor could learn — so a branch here
/// was mispredicted about half the time (measured: an order-16 jet of the SHC field on
/// varying boxes took 9.9 µs with branches, against 6.4 µs on one box repeated). From the
/// bits, with s = ±1 the sign of x: the neighbour towards +∞ is bits + s (away from 0 for
/// x > 0, towards 0 for x < 0), towards −∞ bits − s; the step is masked to 0 unless `go`.
#[inline(always)]
fn nudge(x: f64, up: bool, go: bool) -> f64 {
    let b = x.to_bits() as i64;
    // (b >> 63) is 0 for x > 0 and −1 for x < 0 (arithmetic shift): s = that | 1 = ±1
    let s = (b >> 63) | 1;
    let d = if up { s } else { -s };
    f64::from_bits(b.wrapping_add(d & -(go as i64)) as u64)
}

/// a·b rounded towards −∞ (`up = false`) or +∞; 0·∞ = 0.
#[inline(always)]
fn mul_dir(a: f64, b: f64, up: bool) -> f64 {
    let p = a * b;
    let m = p.abs();
    if (RESIDUAL_EXACT..=f64::MAX).contains(&m) {
        // the common case: finite, residual exact
        let e = a.mul_add(b, -p);
        nudge(p, up, if up { e > 0.0 } else { e < 0.0 })
    } else {
        rare(p, a == 0.0 || b == 0.0, a.is_finite() && b.is_finite(), up)
    }
}

/// An operation's directed result off the common case: 0 for an exact zero operand (0·∞ = 0
/// for a product), a finite result below 2^−969 stepped outwards unconditionally (its residual
/// may not be exact; the rounding error is under one spacing), ±MAX towards 0 for an overflow
/// of finite operands, else the rounded result itself (±∞, NaN).
#[cold]
fn rare(p: f64, zero_operand: bool, finite_operands: bool, up: bool) -> f64 {
    if zero_operand {
        return 0.0;
    }
    if p.is_finite() {
        return if up { p.next_up() } else { p.next_down() };
    }
    if finite_operands {
        if p > 0.0 && !up {
            return f64::MAX;
        }
        if p < 0.0 && up {
            return -f64::MAX;
        }
    }
    p
}

impl Add for Ulp {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self {
            lo: add_dir(self.lo, o.lo, false),
            hi: add_dir(self.hi, o.hi, true),
        }
    }
}

impl Sub for Ulp {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

impl Neg for Ulp {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self {
            lo: -self.hi,
            hi: -self.lo,
        }
    }
}

impl Mul for Ulp {
    type Output = Self;
    /// Two products whenever one factor has a certain sign (the classic case table, extended
    /// to a factor across 0), else [min, max] of the four endpoint products; each product
    /// rounded in its direction.
    ///
    /// For y = [c, d] ≥ 0 the product x·y is increasing in x for every y, so its lower end
    /// is a·y at the best y: a·c for a ≥ 0, a·d for a < 0 (whatever the sign of b), and its
    /// upper end b·d for b ≥ 0, b·c for b < 0; y ≤ 0 and x of a certain sign are the mirror
    /// cases. The chosen pair is the exact minimum (maximum) of the four endpoint products,
    /// and directed rounding is monotone (for `mul_dir`, whose products below 2^−969 are
    /// stepped out unconditionally, too: such a product lies strictly between −2^−969 and
    /// 2^−969, beyond every rounded product outside that range), so the result equals the
    /// [min, max] of the four rounded products: the same enclosure in two products instead
    /// of eight (test `sign_table_equals_the_four_corners`). A product of a jet by a tape
    /// constant of one sign (κ, σ, q) or by the step [0, h] always takes this path.
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let (a, b, c, d) = (self.lo, self.hi, o.lo, o.hi);
        let pairs = if c >= 0.0 {
            // y ≥ 0
            Some((
                (a, if a >= 0.0 { c } else { d }),
                (b, if b >= 0.0 { d } else { c }),
            ))
        } else if d <= 0.0 {
            // y ≤ 0: lower end b·y at the best y, upper end a·y
            Some((
                (b, if b >= 0.0 { c } else { d }),
                (a, if a >= 0.0 { d } else { c }),
            ))
        } else if a >= 0.0 {
            // x ≥ 0, y across 0: [b·c, b·d]
            Some(((b, c), (b, d)))
        } else if b <= 0.0 {
            // x ≤ 0, y across 0: [a·d, a·c]
            Some(((a, d), (a, c)))
        } else {
            None
        };
        match pairs {
            Some((lo, hi)) => pair_dir(lo, hi, false),
            None => corners(self, o),
        }
    }
}

/// The case-table result of a product (`div = false`) or quotient: the lower end lo.0 ∘ lo.1
/// rounded down and the upper end hi.0 ∘ hi.1 rounded up. When both are in the common case of
/// [`mul_dir`] / [`div_dir`] (result in [2^−969, MAX], for a quotient also |dividend| ≥ 2^−969
/// and a finite divisor) both ends take one vector product or division and one fused residual:
/// the same nearest p, the same exact residual r and the same step as those functions (the
/// exact value lies above p when r > 0 for a product, when r/b > 0 for a quotient a/b), so bit
/// for bit their results; otherwise those functions themselves.
#[inline(always)]
fn pair_dir(lo: (f64, f64), hi: (f64, f64), div: bool) -> Ulp {
    #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
    {
        use std::arch::x86_64::*;
        // SAFETY: the intrinsics need SSE2 and FMA, which the cfg above guarantees at compile
        // time; they only read and write registers.
        let (p0, p1, r0, r1) = unsafe {
            let x = _mm_setr_pd(lo.0, hi.0);
            let y = _mm_setr_pd(lo.1, hi.1);
            let (p, r) = if div {
                let q = _mm_div_pd(x, y);
                (q, _mm_fnmadd_pd(q, y, x))
            } else {
                let p = _mm_mul_pd(x, y);
                (p, _mm_fmsub_pd(x, y, p))
            };
            let high = |v: __m128d| _mm_cvtsd_f64(_mm_unpackhi_pd(v, v));
            (_mm_cvtsd_f64(p), high(p), _mm_cvtsd_f64(r), high(r))
        };
        let normal = |p: f64| (RESIDUAL_EXACT..=f64::MAX).contains(&p.abs());
        let common = normal(p0)
            && normal(p1)
            && (!div
                || (lo.0.abs() >= RESIDUAL_EXACT
                    && hi.0.abs() >= RESIDUAL_EXACT
                    && lo.1.is_finite()
                    && hi.1.is_finite()));
        if common {
            let (below, above) = if div {
                (
                    r0 != 0.0 && (r0 < 0.0) == (lo.1 > 0.0),
                    r1 != 0.0 && (r1 > 0.0) == (hi.1 > 0.0),
                )
            } else {
                (r0 < 0.0, r1 > 0.0)
            };
            return Ulp {
                lo: nudge(p0, false, below),
                hi: nudge(p1, true, above),
            };
        }
    }
    let op = if div { div_dir } else { mul_dir };
    Ulp {
        lo: op(lo.0, lo.1, false),
        hi: op(hi.0, hi.1, true),
    }
}

/// x·y as [min, max] of the four endpoint products, each rounded in its direction (the
/// product when both factors reach across 0, where no pair of ends is known beforehand).
#[inline(always)]
fn corners(x: Ulp, y: Ulp) -> Ulp {
    let (a, b, c, d) = (x.lo, x.hi, y.lo, y.hi);
    Ulp {
        lo: mul_dir(a, c, false)
            .min(mul_dir(a, d, false))
            .min(mul_dir(b, c, false).min(mul_dir(b, d, false))),
        hi: mul_dir(a, c, true)
            .max(mul_dir(a, d, true))
            .max(mul_dir(b, c, true).max(mul_dir(b, d, true))),
    }
}

/// a/b rounded towards −∞ (`up = false`) or +∞, for b ≠ 0 finite or infinite.
#[inline(always)]
fn div_dir(a: f64, b: f64, up: bool) -> f64 {
    let q = a / b;
    let m = q.abs();
    if (RESIDUAL_EXACT..=f64::MAX).contains(&m) && a.abs() >= RESIDUAL_EXACT && b.is_finite() {
        // the remainder a − q·b is exact: sign(a/b − q) = sign(remainder)·sign(b)
        let r = (-q).mul_add(b, a);
        let above = if b > 0.0 { r > 0.0 } else { r < 0.0 };
        let below = if b > 0.0 { r < 0.0 } else { r > 0.0 };
        nudge(q, up, if up { above } else { below })
    } else {
        rare(q, a == 0.0, a.is_finite(), up)
    }
}

/// [a, b]/[c, d] for a divisor that reaches 0 ([`div_at_zero`]'s cases), every end a number.
///
/// The quotient set {x/y : x ∈ [a, b], y ∈ [c, d], y ≠ 0} (IEEE 1788, as inari): for a
/// divisor with one end at 0, y of one sign s and |y| ∈ (0, max |c|, |d|]: a dividend of one
/// sign gives the half-line from its end nearest 0 over the divisor's far end outward — for
/// y ∈ (0, d]: [a/d, +∞] (a ≥ 0), [−∞, b/d] (b ≤ 0); for y ∈ [c, 0): [−∞, a/c] (a ≥ 0),
/// [b/c, +∞] (b ≤ 0) — each end rounded outward; a dividend across 0, or a divisor across 0
/// or equal to [0, 0], gives [−∞, +∞]. Unlike IEEE 1788, [0, 0]/[c, d] is [−∞, +∞] too: where
/// y = 0 is possible the quotient may be 0/0, which no caller should read as 0.
#[cold]
fn div_at_zero(a: f64, b: f64, c: f64, d: f64) -> Ulp {
    let dividend_zero = a == 0.0 && b == 0.0;
    if dividend_zero || (c < 0.0 && d > 0.0) || (c == 0.0 && d == 0.0) {
        return Ulp::ENTIRE;
    }
    match (c == 0.0, a >= 0.0, b <= 0.0) {
        // y ∈ (0, d]
        (true, true, _) => Ulp {
            lo: div_dir(a, d, false),
            hi: f64::INFINITY,
        },
        (true, _, true) => Ulp {
            lo: f64::NEG_INFINITY,
            hi: div_dir(b, d, true),
        },
        // y ∈ [c, 0)
        (false, true, _) => Ulp {
            lo: f64::NEG_INFINITY,
            hi: div_dir(a, c, true),
        },
        (false, _, true) => Ulp {
            lo: div_dir(b, c, false),
            hi: f64::INFINITY,
        },
        _ => Ulp::ENTIRE,
    }
}

impl Div for Ulp {
    type Output = Self;
    /// For a divisor of certain sign, [min, max] of the endpoint quotients, each rounded in its
    /// direction; for a divisor with an end at 0 the half-line of `div_at_zero`, [−∞, +∞]
    /// when it lies across 0.
    #[inline]
    fn div(self, o: Self) -> Self {
        let (a, b, c, d) = (self.lo, self.hi, o.lo, o.hi);
        if a.is_nan() || b.is_nan() || c.is_nan() || d.is_nan() {
            return Self::ENTIRE;
        }
        if !(c > 0.0 || d < 0.0) {
            return div_at_zero(a, b, c, d);
        }
        // divisor of certain sign: x/y is monotone in x for every y (increasing for y > 0),
        // and in y for every x of one sign, so each end is one endpoint quotient whichever
        // the dividend's signs (a dividend across 0 included): for y > 0 the lower end a/d
        // (a ≥ 0) or a/c (a < 0), the upper b/c (b ≥ 0) or b/d; for y < 0 the lower b/d
        // (b ≥ 0) or b/c, the upper a/c (a ≥ 0) or a/d. The divisor's sign is the same over
        // a whole recurrence (w₀'s), the dividend's varies with the order: chosen by
        // [`select`], without branches.
        if c > 0.0 {
            pair_dir(
                (a, select(a >= 0.0, d, c)),
                (b, select(b >= 0.0, c, d)),
                true,
            )
        } else {
            pair_dir(
                (b, select(b >= 0.0, d, c)),
                (a, select(a >= 0.0, c, d)),
                true,
            )
        }
    }
}

impl Ulp {
    /// x·k or x/k for an exact integer k (k ≠ 0 for a quotient) by the exact-residual method
    /// of [`super`]; an integer beyond 2^53 in magnitude (not always a double: 2^53 + 1 would
    /// round to 2^53) by its enclosure [k̃⁻, k̃⁺] around the nearest double k̃ (noted by an
    /// adversarial review; every caller uses small k).
    #[inline]
    pub(crate) fn int_op(self, k: i64, div: bool) -> Self {
        if k == 0 && !div {
            return Self::point(0.0);
        }
        let kf = k as f64;
        if k.unsigned_abs() > 1 << 53 {
            // |k − k̃| ≤ half a spacing of k̃
            let ki = Self {
                lo: kf.next_down(),
                hi: kf.next_up(),
            };
            return if div { self / ki } else { self * ki };
        }
        let (a, b) = if k > 0 {
            (self.lo, self.hi)
        } else {
            (self.hi, self.lo)
        };
        if let Some(r) = int_op_common(a, b, kf, div) {
            return r;
        }
        match (int_op_bounds(a, kf, div), int_op_bounds(b, kf, div)) {
            (Some((lo, _)), Some((_, hi))) => Self { lo, hi },
            _ => {
                let ki = Self::point(kf);
                if div { self / ki } else { self * ki }
            }
        }
    }
}

/// [`Ulp::int_op`] in the common case, both nearest results p finite with |p| ≥ 2^−969 (so
/// both ends finite and non-zero): the same bounds as [`int_op_bounds`] on each end (the same
/// p, the same exact residual, the same step), with both ends in one vector division (or
/// product) and one fused residual; `None` otherwise. For |k| a power of two the quotient is
/// x·(1/k) with 1/k exact: the correct rounding of the same real number x/k, bit for bit the
/// quotient, without the division's latency. Measured on the rigorous engine (division by the
/// order k in every power and solution coefficient): see the commit introducing it.
#[inline(always)]
fn int_op_common(a: f64, b: f64, k: f64, div: bool) -> Option<Ulp> {
    let (pa, pb, ra, rb) = int_op_pair(a, b, k, div);
    let normal = |p: f64| (RESIDUAL_EXACT..=f64::MAX).contains(&p.abs());
    if !(normal(pa) && normal(pb)) {
        return None;
    }
    // sign of (exact − p): for a product x·k − p; for a quotient (x − p·k)/k
    let s = if div { k.signum() } else { 1.0 };
    Some(Ulp {
        lo: nudge(pa, false, ra * s < 0.0),
        hi: nudge(pb, true, rb * s > 0.0),
    })
}

/// (p_a, p_b, r_a, r_b): the nearest p = x·k (`div`: x/k) of x = a and x = b, and the residuals
/// x·k − p (`div`: x − p·k), each one rounding of the exact residual (exact where
/// [`int_op_common`] uses them).
#[inline(always)]
fn int_op_pair(a: f64, b: f64, k: f64, div: bool) -> (f64, f64, f64, f64) {
    #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
    {
        use std::arch::x86_64::*;
        // SAFETY: the intrinsics need SSE2 and FMA, which the cfg above guarantees at compile
        // time; they only read and write registers.
        unsafe {
            let x = _mm_setr_pd(a, b);
            let kk = _mm_set1_pd(k);
            let (p, r) = if div {
                let m = k.abs().to_bits() & ((1u64 << 52) - 1) == 0;
                let p = if m && k.abs() <= 2f64.powi(60) {
                    // 1/k exact (k = ±2^j, j ≤ 60)
                    _mm_mul_pd(x, _mm_set1_pd(1.0 / k))
                } else {
                    _mm_div_pd(x, kk)
                };
                (p, _mm_fnmadd_pd(p, kk, x))
            } else {
                let p = _mm_mul_pd(x, kk);
                (p, _mm_fmsub_pd(x, kk, p))
            };
            let hi = |v: __m128d| _mm_cvtsd_f64(_mm_unpackhi_pd(v, v));
            (_mm_cvtsd_f64(p), hi(p), _mm_cvtsd_f64(r), hi(r))
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
    {
        if div {
            let (pa, pb) = (a / k, b / k);
            (pa, pb, (-pa).mul_add(k, a), (-pb).mul_add(k, b))
        } else {
            let (pa, pb) = (a * k, b * k);
            (pa, pb, a.mul_add(k, -pa), b.mul_add(k, -pb))
        }
    }
}

/// The nearest value p of x·k (`div`: x/k) and which side of it the exact value lies on, from
/// the exact residual (FMA: x·k − p, or x − p·k for a quotient, both representable above
/// 2^−969); returns (lower, upper) bounds, or None when not finite.
#[inline]
pub(crate) fn int_op_bounds(x: f64, k: f64, div: bool) -> Option<(f64, f64)> {
    let p = if div { x / k } else { x * k };
    if !p.is_finite() || !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some((0.0, 0.0));
    }
    if p.abs() < RESIDUAL_EXACT {
        return Some((p.next_down(), p.next_up()));
    }
    // sign of (exact − p): for a product x·k − p; for a quotient (x − p·k)/k
    let r = if div {
        (-p).mul_add(k, x) * k.signum()
    } else {
        x.mul_add(k, -p)
    };
    Some(if r > 0.0 {
        (p, p.next_up())
    } else if r < 0.0 {
        (p.next_down(), p)
    } else {
        (p, p)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::Real;
    use rug::Rational;

    fn q(x: f64) -> Rational {
        Rational::from_f64(x).unwrap()
    }

    fn contains(r: Ulp, lo: &Rational, hi: &Rational) -> bool {
        q(r.lo) <= *lo && *hi <= q(r.hi)
    }

    /// [`nudge`] is `next_up` / `next_down` where it steps and the identity where it does not,
    /// for finite non-zero doubles of every kind (subnormal, the normal threshold, ±MAX, whose
    /// step outwards is ±∞) and random ones of both signs.
    #[test]
    fn nudge_steps_like_next_up_and_next_down() {
        let mut next = crate::arith::interval::xorshift(0x2545f4914f6cdd1d_u64);
        let mut xs = vec![
            f64::from_bits(1),
            f64::MIN_POSITIVE,
            f64::MIN_POSITIVE.next_down(),
            f64::MIN_POSITIVE.next_up(),
            1.0,
            1.0f64.next_down(),
            2.0,
            f64::MAX,
            f64::MAX.next_down(),
            RESIDUAL_EXACT,
        ];
        for _ in 0..20_000 {
            let x = f64::from_bits(next() & !(1 << 63));
            if x.is_finite() && x != 0.0 {
                xs.push(x);
            }
        }
        for x in xs.iter().flat_map(|&x| [x, -x]) {
            assert_eq!(
                nudge(x, true, true).to_bits(),
                x.next_up().to_bits(),
                "up {x:e}"
            );
            assert_eq!(
                nudge(x, false, true).to_bits(),
                x.next_down().to_bits(),
                "down {x:e}"
            );
            assert_eq!(nudge(x, true, false).to_bits(), x.to_bits());
            assert_eq!(nudge(x, false, false).to_bits(), x.to_bits());
        }
    }

    /// Every operation encloses the exact result of exact endpoints over many binades
    /// (subnormal and overflowing results included), and equals inari's directed rounding.
    #[test]
    fn operations_enclose_the_exact_results() {
        let mut next = crate::arith::interval::xorshift(0x9e3779b97f4a7c15_u64);
        let float = move |r: u64| {
            let m = 1.0 + (r >> 12) as f64 / (1u64 << 52) as f64;
            let e = (r % 2098) as i32 - 1075;
            let x = m * 2f64.powi(e);
            if r & 2048 != 0 { -x } else { x }
        };
        for i in 0..50_000 {
            let (a, b, c, d) = (float(next()), float(next()), float(next()), float(next()));
            let x = Ulp {
                lo: a.min(b),
                hi: a.max(b),
            };
            let y = if i % 3 == 0 {
                Ulp::point(c)
            } else {
                Ulp {
                    lo: c.min(d),
                    hi: c.max(d),
                }
            };
            let ends = |u: Ulp| [q(u.lo), q(u.hi)];
            // sum and difference
            let s = x + y;
            if s.lo.is_finite() && s.hi.is_finite() {
                let lo = q(x.lo) + q(y.lo);
                let hi = q(x.hi) + q(y.hi);
                assert!(contains(s, &lo, &hi), "{x:?} + {y:?} = {s:?}");
            }
            let dif = x - y;
            if dif.lo.is_finite() && dif.hi.is_finite() {
                let lo = q(x.lo) - q(y.hi);
                let hi = q(x.hi) - q(y.lo);
                assert!(contains(dif, &lo, &hi), "{x:?} − {y:?} = {dif:?}");
            }
            let to = |u: Ulp| Interval::try_from((u.lo, u.hi)).unwrap();
            assert_eq!(s.interval(), to(x) + to(y), "{x:?} + {y:?}");
            assert_eq!(dif.interval(), to(x) - to(y), "{x:?} − {y:?}");
            let p = x * y;
            let ip = to(x) * to(y);
            // equal to inari's, but for a product below 2^−969 (stepped out unconditionally):
            // then at most one spacing wider
            assert!(ip.subset(p.interval()), "{x:?} · {y:?}: {p:?} vs {ip:?}");
            assert!(
                p.lo >= ip.inf().next_down() && p.hi <= ip.sup().next_up(),
                "{x:?} · {y:?}: {p:?} vs {ip:?}"
            );
            // quotient (divisor of certain sign)
            if y.lo > 0.0 || y.hi < 0.0 {
                let d = x / y;
                let id = to(x) / to(y);
                assert!(id.subset(d.interval()), "{x:?} / {y:?}: {d:?} vs {id:?}");
                assert!(
                    d.lo >= id.inf().next_down() && d.hi <= id.sup().next_up(),
                    "{x:?} / {y:?}: {d:?} vs {id:?}"
                );
                if d.lo.is_finite() && d.hi.is_finite() {
                    let qs: Vec<Rational> = ends(x)
                        .iter()
                        .flat_map(|u| ends(y).into_iter().map(move |v| Rational::from(u / &v)))
                        .collect();
                    let lo = qs.iter().min().unwrap();
                    let hi = qs.iter().max().unwrap();
                    assert!(contains(d, lo, hi), "{x:?} / {y:?} = {d:?}");
                }
            } else {
                // a divisor reaching 0: the half-line around inari's quotient set (or the
                // whole line)
                let d = x / y;
                let id = to(x) / to(y);
                assert!(id.subset(d.interval()), "{x:?} / {y:?}: {d:?} vs {id:?}");
            }
            if p.lo.is_finite() && p.hi.is_finite() {
                let mut ps = Vec::new();
                for u in ends(x) {
                    for v in ends(y) {
                        ps.push(Rational::from(&u * &v));
                    }
                }
                let lo = ps.iter().min().unwrap().clone();
                let hi = ps.iter().max().unwrap().clone();
                assert!(contains(p, &lo, &hi), "{x:?} · {y:?} = {p:?}");
            }
        }
        assert_eq!(
            Ulp::point(0.0)
                * Ulp {
                    lo: 1.0,
                    hi: f64::INFINITY
                },
            Ulp::point(0.0)
        );
        assert_eq!(Ulp::point(2.0).powi_nonneg(0), Ulp::point(1.0));
        // x^n by binary powering encloses the exact power (a few exponents, both parities)
        for n in [1u32, 2, 5, 6, 13] {
            let x = Ulp { lo: 0.7, hi: 1.3 };
            let p = x.powi_nonneg(n);
            let rp = |x: f64| (0..n).fold(Rational::from(1), |acc, _| acc * q(x));
            let (lo, hi) = (rp(0.7), rp(1.3));
            assert!(contains(p, &lo, &hi), "[0.7, 1.3]^{n} = {p:?}");
            assert!(
                p.hi < 1.3f64.powi(n as i32) * (1.0 + 1e-14),
                "[0.7, 1.3]^{n} = {p:?}"
            );
        }
        let c = Ulp::point(1.0 / 3.0).powi_nonneg(3);
        let t = q(1.0 / 3.0);
        let t3 = Rational::from(&t * &t) * &t;
        assert!(contains(c, &t3, &t3), "{c:?}");
    }

    /// The product's sign table (two products when one factor has a certain sign) equals the
    /// [min, max] of the four rounded endpoint products, on endpoints of every kind: both
    /// signs, ±0, ±∞, subnormal, tiny and huge, thin and wide, across 0. The only allowed
    /// difference: where a corner's rounded product lies below 2^−969 (stepped out without a
    /// residual) the table may be narrower (it skips a corner that is not the exact extreme),
    /// never wider.
    #[test]
    fn sign_table_equals_the_four_corners() {
        let mut next = crate::arith::interval::xorshift(0x2545f4914f6cdd1d_u64);
        let special = [
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            1.0,
            RESIDUAL_EXACT,
            1e-160,
        ];
        let float = move |r: u64| -> f64 {
            let x = match r % 4 {
                0 => special[(r >> 8) as usize % special.len()],
                1 => {
                    let m = 1.0 + (r >> 12) as f64 / (1u64 << 52) as f64;
                    m * 2f64.powi((r >> 3) as i32 % 2098 - 1075)
                }
                _ => {
                    let m = 1.0 + (r >> 12) as f64 / (1u64 << 52) as f64;
                    m * 2f64.powi((r >> 3) as i32 % 40 - 20)
                }
            };
            if r & 4 != 0 { -x } else { x }
        };
        let four = |x: Ulp, y: Ulp| corners(x, y);
        let tiny = |x: Ulp, y: Ulp| {
            [(x.lo, y.lo), (x.lo, y.hi), (x.hi, y.lo), (x.hi, y.hi)]
                .iter()
                .any(|&(u, v)| u != 0.0 && v != 0.0 && (u * v).abs() < RESIDUAL_EXACT)
        };
        let (mut seen_across, mut equal) = (0, 0);
        for _ in 0..400_000 {
            let (a, b, c, d) = (float(next()), float(next()), float(next()), float(next()));
            let x = Ulp {
                lo: a.min(b),
                hi: a.max(b),
            };
            let y = if next().is_multiple_of(4) {
                Ulp::point(c)
            } else {
                Ulp {
                    lo: c.min(d),
                    hi: c.max(d),
                }
            };
            let (t, f) = (x * y, four(x, y));
            if (x.lo < 0.0 && x.hi > 0.0) || (y.lo < 0.0 && y.hi > 0.0) {
                seen_across += 1;
            }
            if t == f {
                equal += 1;
                continue;
            }
            assert!(
                tiny(x, y) && f.lo <= t.lo && t.hi <= f.hi,
                "{x:?} · {y:?}: table {t:?}, four corners {f:?}"
            );
        }
        assert!(
            seen_across > 100_000 && equal > 390_000,
            "{seen_across} {equal}"
        );
    }

    /// The two-ended vector route of the case tables ([`pair_dir`]) gives bit for bit the ends
    /// of the scalar directed operations [`mul_dir`] and [`div_dir`], on operands of every
    /// kind (±0, ±∞, subnormal, tiny, huge, ±MAX, both signs; divisors non-zero).
    #[test]
    fn pair_route_equals_the_scalar_directed_operations() {
        let mut next = crate::arith::interval::xorshift(0xbb67ae8584caa73b_u64);
        let special = crate::arith::interval::SPECIAL;
        let float = |r: u64| crate::arith::interval::operand(r, &special);
        let mut vector = 0;
        for _ in 0..500_000 {
            let (a, b, c, d) = (float(next()), float(next()), float(next()), float(next()));
            let m = pair_dir((a, b), (c, d), false);
            assert_eq!(
                (m.lo.to_bits(), m.hi.to_bits()),
                (
                    mul_dir(a, b, false).to_bits(),
                    mul_dir(c, d, true).to_bits()
                ),
                "{a:e}·{b:e}, {c:e}·{d:e}"
            );
            if b != 0.0 && d != 0.0 {
                let q = pair_dir((a, b), (c, d), true);
                let (lo, hi) = (div_dir(a, b, false), div_dir(c, d, true));
                assert!(
                    (q.lo.to_bits(), q.hi.to_bits()) == (lo.to_bits(), hi.to_bits())
                        || (q.lo.is_nan() && lo.is_nan())
                        || (q.hi.is_nan() && hi.is_nan()),
                    "{a:e}/{b:e} → {:e} vs {lo:e}, {c:e}/{d:e} → {:e} vs {hi:e}",
                    q.lo,
                    q.hi
                );
                let fin = |x: f64| (RESIDUAL_EXACT..=f64::MAX).contains(&x.abs());
                if fin(a / b) && fin(c / d) && fin(a) && fin(c) && fin(b) && fin(d) {
                    vector += 1;
                }
            }
        }
        assert!(vector > 100_000, "{vector}");
    }

    /// A result that overflows is bounded on its finite side by ±MAX, not by ±∞ (an upper end
    /// −∞ or a lower end +∞ would exclude the exact, finite value). Checked on the `Ulp` ends
    /// themselves: [`Ulp::interval`] would turn such an end pair into [−∞, +∞].
    #[test]
    fn overflow_keeps_the_finite_side_at_max() {
        let m = f64::MAX;
        let (pos, neg) = (
            Ulp {
                lo: m,
                hi: f64::INFINITY,
            },
            Ulp {
                lo: f64::NEG_INFINITY,
                hi: -m,
            },
        );
        let (p, n2, h) = (Ulp::point(m), Ulp::point(2.0), Ulp::point(0.5));
        assert_eq!(p + p, pos);
        assert_eq!(-p - p, neg);
        assert_eq!(p * n2, pos);
        assert_eq!(-p * n2, neg);
        assert_eq!(p * -n2, neg);
        assert_eq!(p / h, pos);
        assert_eq!(-p / h, neg);
        assert_eq!(p / -h, neg);
        assert_eq!(p.mul_int(3), pos);
        assert_eq!(p.mul_int(-3), neg);
    }

    /// Results that are exact doubles are returned exactly (no outward step): the residual
    /// decides the step, and a zero residual means none. Quotients of both divisor signs and
    /// every case of the sign table.
    #[test]
    fn exact_results_are_not_widened() {
        let u = |lo: f64, hi: f64| Ulp { lo, hi };
        for (x, y, quo) in [
            (u(3.0, 6.0), u(1.5, 1.5), u(2.0, 4.0)),
            (u(3.0, 6.0), u(-1.5, -1.5), u(-4.0, -2.0)),
            (u(-6.0, -3.0), u(1.5, 1.5), u(-4.0, -2.0)),
            (u(-6.0, -3.0), u(-1.5, -1.5), u(2.0, 4.0)),
            (u(-6.0, 3.0), u(1.5, 3.0), u(-4.0, 2.0)),
            (u(-6.0, 3.0), u(-3.0, -1.5), u(-2.0, 4.0)),
            (u(3.0, 6.0), u(1.5, 3.0), u(1.0, 4.0)),
            (u(3.0, 6.0), u(-3.0, -1.5), u(-4.0, -1.0)),
        ] {
            assert_eq!(x / y, quo, "{x:?} / {y:?}");
        }
        for (x, y, prod) in [
            (u(1.5, 3.0), u(2.0, 4.0), u(3.0, 12.0)),
            (u(1.5, 3.0), u(-4.0, -2.0), u(-12.0, -3.0)),
            (u(-3.0, -1.5), u(2.0, 4.0), u(-12.0, -3.0)),
            (u(-3.0, -1.5), u(-4.0, -2.0), u(3.0, 12.0)),
            (u(-3.0, 1.5), u(2.0, 4.0), u(-12.0, 6.0)),
            (u(-3.0, 1.5), u(-4.0, 2.0), u(-6.0, 12.0)),
        ] {
            assert_eq!(x * y, prod, "{x:?} · {y:?}");
        }
        assert_eq!(u(0.25, 0.5) + u(1.0, 2.0), u(1.25, 2.5));
        assert_eq!(u(0.25, 0.5) - u(1.0, 2.0), u(-1.75, -0.5));
    }

    /// A divisor with an end at 0: the half-line of the quotient set, as inari's division
    /// (IEEE 1788), rounded outward — checked against inari and, for finite ends, the exact
    /// rational quotients of the dividend's end nearest 0 and the divisor's far end; across 0,
    /// [0, 0] or a dividend [0, 0]: the whole line.
    #[test]
    fn quotients_by_a_divisor_at_zero_are_half_lines() {
        let u = |lo: f64, hi: f64| Ulp { lo, hi };
        let mut next = crate::arith::interval::xorshift(0x9e3779b97f4a7c15);
        let mut unit = || (next() >> 11) as f64 / (1u64 << 53) as f64;
        let mut cases = vec![
            (u(1.0, 2.0), u(0.0, 3.0)),
            (u(0.0, 2.0), u(0.0, 3.0)),
            (u(-2.0, -1.0), u(0.0, 3.0)),
            (u(-2.0, 0.0), u(0.0, 3.0)),
            (u(1.0, 2.0), u(-3.0, 0.0)),
            (u(-2.0, -1.0), u(-3.0, 0.0)),
            (u(1.0, f64::INFINITY), u(0.0, 3.0)),
            (u(0.1, 0.3), u(0.0, 0.7)),
            (u(-0.3, -0.1), u(-0.7, 0.0)),
            (u(1e-300, 1e300), u(0.0, 1e-300)),
        ];
        for _ in 0..2000 {
            let (x0, x1) = (unit() * 10.0 - 5.0, unit() * 10.0 - 5.0);
            let (a, b) = (x0.min(x1), x0.max(x1));
            let d = unit() * 4.0;
            cases.push((u(a, b), if unit() < 0.5 { u(0.0, d) } else { u(-d, 0.0) }));
        }
        for (x, y) in cases {
            let r = x / y;
            let reference = Ulp::of(x.interval() / y.interval());
            let zero_dividend = x.lo == 0.0 && x.hi == 0.0;
            if zero_dividend || (y.lo == 0.0 && y.hi == 0.0) {
                assert_eq!(r, Ulp::ENTIRE, "{x:?} / {y:?}");
                continue;
            }
            // inari's enclosure, at most an ulp wider (the residual method steps the quotient
            // of tiny operands unconditionally)
            assert!(
                reference.interval().subset(r.interval())
                    && r.lo >= reference.lo.next_down()
                    && r.hi <= reference.hi.next_up()
                    && r.lo.is_finite() == reference.lo.is_finite()
                    && r.hi.is_finite() == reference.hi.is_finite(),
                "{x:?} / {y:?}: {r:?}, inari gives {reference:?}"
            );
            // the finite end: the exact quotient of the dividend's end nearest 0 and the
            // divisor's far end lies on the right side of it, within an ulp
            let far = if y.lo == 0.0 { y.hi } else { y.lo };
            if r.lo.is_finite() {
                let near = if y.lo == 0.0 { x.lo } else { x.hi };
                if near.is_finite() && far != 0.0 {
                    let exact = q(near) / q(far);
                    assert!(q(r.lo) <= exact && exact - q(r.lo) <= q(r.lo.next_up() - r.lo).abs());
                }
            }
            if r.hi.is_finite() {
                let near = if y.lo == 0.0 { x.hi } else { x.lo };
                if near.is_finite() && far != 0.0 {
                    let exact = q(near) / q(far);
                    assert!(
                        exact <= q(r.hi) && q(r.hi) - exact <= q(r.hi - r.hi.next_down()).abs()
                    );
                }
            }
        }
        // across 0: the whole line
        assert_eq!(u(1.0, 2.0) / u(-1.0, 1.0), Ulp::ENTIRE);
        assert_eq!(u(0.0, 0.0) / u(0.0, 1.0), Ulp::ENTIRE);
    }

    /// |x| is [x] for x ≥ 0, −[x] for x ≤ 0, [0, max(−lo, hi)] across 0.
    #[test]
    fn abs_is_the_exact_range() {
        let u = |lo: f64, hi: f64| Ulp { lo, hi };
        assert_eq!(Real::abs(&u(1.0, 2.0)), u(1.0, 2.0));
        assert_eq!(Real::abs(&u(0.0, 2.0)), u(0.0, 2.0));
        assert_eq!(Real::abs(&u(-3.0, -2.0)), u(2.0, 3.0));
        assert_eq!(Real::abs(&u(-3.0, 0.0)), u(0.0, 3.0));
        assert_eq!(Real::abs(&u(-3.0, 2.0)), u(0.0, 3.0));
        assert_eq!(Real::abs(&u(-2.0, 3.0)), u(0.0, 3.0));
    }

    /// The common case of x·k and x/k (both ends at once, 1/k for |k| a power of two) gives
    /// bit for bit the ends of the one-end-at-a-time route [`int_op_bounds`], on ends of every
    /// kind (±0, ±∞, subnormal, tiny, huge, ±MAX) and integers of both signs (powers of two up
    /// to 2^53 included); where both results are finite, they enclose the exact rational ends.
    #[test]
    fn integer_scalings_equal_the_one_end_route() {
        let mut next = crate::arith::interval::xorshift(0x6a09e667f3bcc908_u64);
        let special = crate::arith::interval::SPECIAL;
        let float = |r: u64| crate::arith::interval::operand(r, &special);
        let one_end = |x: Ulp, k: i64, div: bool| {
            let kf = k as f64;
            let (a, b) = if k > 0 { (x.lo, x.hi) } else { (x.hi, x.lo) };
            match (int_op_bounds(a, kf, div), int_op_bounds(b, kf, div)) {
                (Some((lo, _)), Some((_, hi))) => Some(Ulp { lo, hi }),
                _ => None,
            }
        };
        let mut ks: Vec<i64> = (1..=20).chain([1 << 40, 1 << 53, 3 << 50]).collect();
        ks.extend(ks.clone().iter().map(|k| -k));
        let mut common = 0;
        for i in 0..300_000 {
            let (a, b) = (float(next()), float(next()));
            let x = if i % 5 == 0 {
                Ulp::point(a)
            } else {
                Ulp {
                    lo: a.min(b),
                    hi: a.max(b),
                }
            };
            let k = ks[(next() % ks.len() as u64) as usize];
            for div in [false, true] {
                let r = x.int_op(k, div);
                if let Some(e) = one_end(x, k, div) {
                    assert_eq!(r, e, "{x:?} {} {k}", if div { "/" } else { "·" });
                    common += 1;
                }
                if r.lo.is_finite() && r.hi.is_finite() && x.lo.is_finite() && x.hi.is_finite() {
                    let kq = Rational::from(k);
                    let f = |v: f64| {
                        if div { q(v) / &kq } else { q(v) * &kq }
                    };
                    let (u, v) = (f(x.lo), f(x.hi));
                    let (lo, hi) = if k > 0 { (u, v) } else { (v, u) };
                    assert!(contains(r, &lo, &hi), "{x:?} {k} {div}: {r:?}");
                }
            }
        }
        assert!(common > 300_000, "{common}");
    }

    /// x·k and x/k for an integer k enclose the exact rational ends, equal the inari
    /// implementation ([`super`]), and x·0 = 0.
    #[test]
    fn integer_scalings_enclose_the_exact_value() {
        let mut next = crate::arith::interval::xorshift(0x853c49e6748fea9b_u64);
        let float = |r: u64| {
            let m = 1.0 + (r >> 12) as f64 / (1u64 << 52) as f64;
            let e = (r % 2000) as i32 - 1000;
            if r & 2048 != 0 {
                -m * 2f64.powi(e)
            } else {
                m * 2f64.powi(e)
            }
        };
        for _ in 0..20_000 {
            let (a, b) = (float(next()), float(next()));
            let x = Ulp {
                lo: a.min(b),
                hi: a.max(b),
            };
            let k = [1i64, 2, 3, 7, 20, -1, -3, -12345, 1 << 40][(next() % 9) as usize];
            let kq = Rational::from(k);
            let (xl, xh) = (q(x.lo), q(x.hi));
            let m = x.mul_int(k);
            let (ml, mh) = (Rational::from(&xl * &kq), Rational::from(&xh * &kq));
            let (lo, hi) = if k > 0 { (ml, mh) } else { (mh, ml) };
            if m.lo.is_finite() && m.hi.is_finite() {
                assert!(contains(m, &lo, &hi), "{x:?}·{k} = {m:?}");
            }
            assert_eq!(m.interval(), Real::mul_int(&x.interval(), k), "{x:?}·{k}");
            let d = x.div_int(k);
            let (dl, dh) = (Rational::from(&xl / &kq), Rational::from(&xh / &kq));
            let (lo, hi) = if k > 0 { (dl, dh) } else { (dh, dl) };
            assert!(contains(d, &lo, &hi), "{x:?}/{k} = {d:?}");
            assert_eq!(d.interval(), Real::div_int(&x.interval(), k), "{x:?}/{k}");
        }
        assert_eq!(Ulp { lo: -2.0, hi: 3.0 }.mul_int(0), Ulp::point(0.0));
        assert_eq!(
            Ulp { lo: -2.0, hi: 3.0 }.mul_int(-2),
            Ulp { lo: -6.0, hi: 4.0 }
        );
        assert_eq!(
            Ulp { lo: -2.0, hi: 3.0 }.div_int(-2),
            Ulp { lo: -1.5, hi: 1.0 }
        );
        // unbounded operands take the fallback through the interval operations
        let inf = f64::INFINITY;
        let d = Ulp { lo: 1.0, hi: inf }.div_int(3);
        assert!(q(d.lo) <= (1, 3) && d.hi == inf, "{d:?}");
        assert!(d.lo >= (1.0f64 / 3.0).next_down(), "{d:?}");
        let d = Ulp { lo: 1.0, hi: inf }.div_int(-3);
        assert!(d.lo == -inf && q(d.hi) >= (-1, 3), "{d:?}");
        assert!(d.hi <= (-1.0f64 / 3.0).next_up(), "{d:?}");
        assert_eq!(
            Ulp { lo: -inf, hi: 2.0 }.mul_int(-3),
            Ulp { lo: -6.0, hi: inf }
        );
        assert_eq!(
            Ulp { lo: -inf, hi: 2.0 }.mul_int(3),
            Ulp { lo: -inf, hi: 6.0 }
        );
    }
}

/// Adversarial checks of the fast paths (sign table, `pair_dir`, `int_op_common`) on operands
/// aimed at the thresholds: products and quotients whose exponent lands near 2^−1074, 2^−1022,
/// 2^−969 and the overflow threshold, mantissas with few bits (exact results, ties) and with
/// all bits set, signed zeros, ±∞, ±MAX and the neighbours of every threshold.
#[cfg(test)]
pub(crate) mod adversarial {
    use super::*;
    use rug::Rational;

    fn q(x: f64) -> Rational {
        Rational::from_f64(x).unwrap()
    }

    pub(crate) struct Gen(u64);

    /// The sample count: `default`, or BWCL_ADVERSARIAL_ITERS for a longer run.
    pub(crate) fn iters(default: u64) -> u64 {
        std::env::var("BWCL_ADVERSARIAL_ITERS")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(default)
    }

    impl Gen {
        /// A generator from `seed`, mixed with BWCL_ADVERSARIAL_SEED when set (other samples).
        pub(crate) fn new(seed: u64) -> Self {
            let extra: u64 = std::env::var("BWCL_ADVERSARIAL_SEED")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(0);
            Gen((seed ^ extra.wrapping_mul(0x9e37_79b9_7f4a_7c15)) | 1)
        }
        pub(crate) fn next(&mut self) -> u64 {
            crate::arith::interval::xorshift_step(&mut self.0)
        }
        /// a mantissa in [1, 2): random, few bits, all bits, or 1 + one ulp
        fn mant(&mut self) -> f64 {
            let r = self.next();
            let bits = match r % 5 {
                0 | 1 => self.next() >> 12,
                2 => (self.next() >> 12) & !((1u64 << (52 - (r >> 8) % 8)) - 1),
                3 => ((1u64 << 52) - 1) ^ ((self.next() >> 60) & 3),
                _ => (r >> 8) % 3,
            };
            f64::from_bits((1023u64 << 52) | bits)
        }
        /// m·2^e (rounded when e is below the normal range), either sign
        pub(crate) fn with_exp(&mut self, e: i32) -> f64 {
            let m = self.mant();
            let e = e.clamp(-1200, 1023);
            let x = if e < -1022 {
                m * 2f64.powi(-1022) * 2f64.powi(e + 1022)
            } else {
                m * 2f64.powi(e)
            };
            if self.next() & 1 == 0 { -x } else { x }
        }
        pub(crate) fn special(&mut self) -> f64 {
            let t = RESIDUAL_EXACT;
            let s = [
                0.0,
                -0.0,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::MAX,
                f64::MAX.next_down(),
                f64::MIN_POSITIVE,
                f64::MIN_POSITIVE.next_down(),
                f64::MIN_POSITIVE.next_up(),
                5e-324,
                1e-323,
                t,
                t.next_up(),
                t.next_down(),
                1.0,
                3.0,
                2f64.powi(-511),
                2f64.powi(512),
                2f64.powi(-537),
            ];
            let x = s[(self.next() % s.len() as u64) as usize];
            if self.next() & 1 == 0 { -x } else { x }
        }
        /// any float: special, or m·2^e over the whole range
        pub(crate) fn any(&mut self) -> f64 {
            match self.next() % 4 {
                0 => self.special(),
                1 => {
                    let e = (self.next() % 2100) as i32 - 1076;
                    self.with_exp(e)
                }
                _ => {
                    let e = (self.next() % 80) as i32 - 40;
                    self.with_exp(e)
                }
            }
        }
        /// a target exponent for a product or quotient: near 2^−1074, 2^−1022, 2^−969, MAX
        pub(crate) fn target(&mut self) -> i32 {
            let base = [-1075, -1023, -970, 1023, -1050, -1000][(self.next() % 6) as usize];
            base + (self.next() % 7) as i32 - 3
        }
        /// (x, y) with x·y (`div`: x/y) near a threshold, or arbitrary
        pub(crate) fn pair(&mut self, div: bool) -> (f64, f64) {
            if self.next().is_multiple_of(4) {
                return (self.any(), self.any());
            }
            let t = self.target();
            let ex = (self.next() % 2090) as i32 - 1070;
            // y's exponent so that ex ± ey ≈ t, kept inside the representable range
            let ey = if div { ex - t } else { t - ex };
            if !(-1074..=1023).contains(&ey) {
                let ey = ey.clamp(-1074, 1023);
                let ex = if div { t + ey } else { t - ey };
                return (self.with_exp(ex), self.with_exp(ey));
            }
            (self.with_exp(ex), self.with_exp(ey))
        }
    }

    fn ulp(a: f64, b: f64) -> Ulp {
        Ulp {
            lo: a.min(b),
            hi: a.max(b),
        }
    }

    /// The exact [min, max] of the four endpoint products (`div`: quotients), for finite ends.
    fn exact_extremes(x: Ulp, y: Ulp, div: bool) -> Option<(Rational, Rational)> {
        if ![x.lo, x.hi, y.lo, y.hi].iter().all(|v| v.is_finite()) {
            return None;
        }
        let mut v = Vec::new();
        for u in [x.lo, x.hi] {
            for w in [y.lo, y.hi] {
                v.push(if div { q(u) / q(w) } else { q(u) * q(w) });
            }
        }
        let lo = v.iter().min().unwrap().clone();
        let hi = v.iter().max().unwrap().clone();
        Some((lo, hi))
    }

    /// Integers beyond 2^53 are not always doubles (2^53 + 1 rounds to 2^53): x·k and x/k hold
    /// the exact rational results for such k of both signs, and for k = ±2^53 exactly.
    #[test]
    fn integer_scalings_beyond_two_to_the_53_hold_the_exact_results() {
        let two53: i64 = 1 << 53;
        for k in [
            two53 + 1,
            two53 + 3,
            -(two53 + 1),
            3 * two53 + 5,
            i64::MAX,
            two53,
            -two53,
        ] {
            for x in [1.0, -0.75, 3.0e-200, 1.5e200] {
                let kq = Rational::from(k);
                for div in [false, true] {
                    let r = Ulp::point(x).int_op(k, div);
                    let exact = if div {
                        q(x) / kq.clone()
                    } else {
                        q(x) * kq.clone()
                    };
                    assert!(
                        r.lo.is_finite()
                            && r.hi.is_finite()
                            && q(r.lo) <= exact
                            && exact <= q(r.hi),
                        "{x:e} {} {k}: {r:?}",
                        if div { "/" } else { "·" }
                    );
                }
            }
        }
    }

    /// Found by an adversarial review (a bug older than the review): TwoSum's b' = s − a
    /// overflows when b = ±MAX and a is an opposite-signed odd multiple of 2^970 whose sum
    /// rounds (ties to even) away from a by half a spacing: s − a = ±(MAX + 2^970) rounds to
    /// ±∞, the error term was NaN and the end was not stepped, so the sum [MAX − 2^971, …]
    /// excluded the exact MAX − 3·2^970 (inari: MAX − 2^972). Now [`add_dir`] takes the error
    /// from the halves ([`halves_error`]); the sums equal inari's.
    #[test]
    fn sum_at_max_keeps_the_exact_value() {
        let max = f64::MAX;
        let a = 3.0 * 2f64.powi(970);
        for (x, y) in [(-a, max), (max, -a)] {
            let s = Ulp::point(x) + Ulp::point(y);
            let exact = q(x) + q(y);
            assert!(
                q(s.lo) <= exact && exact <= q(s.hi),
                "{x:e} + {y:e} = {s:?}"
            );
            let i = Interval::try_from((x, x)).unwrap() + Interval::try_from((y, y)).unwrap();
            assert_eq!(s.interval(), i, "{x:e} + {y:e}");
        }
        // the mirror case: an upper end at −MAX
        for (x, y) in [(a, -max), (-max, a)] {
            let s = Ulp::point(x) + Ulp::point(y);
            let exact = q(x) + q(y);
            assert!(
                q(s.lo) <= exact && exact <= q(s.hi),
                "{x:e} + {y:e} = {s:?}"
            );
        }
    }

    /// The product table and quotient table enclose the exact ranges, and the product table
    /// equals the four corners (narrower only where a corner underflows); pair_dir equals
    /// mul_dir/div_dir bit for bit; every directed operation in its common case equals inari's.
    #[test]
    fn fast_products_and_quotients_on_threshold_operands() {
        let mut g = Gen::new(0x9c1f_23d4_77a1_0b35);
        let (mut n_q, mut n_common) = (0u64, 0u64);
        for i in 0..iters(2_000_000) {
            let div = i % 2 == 1;
            let (a, c) = g.pair(div);
            let (b, d) = if g.next().is_multiple_of(3) {
                (a, c)
            } else {
                g.pair(div)
            };
            // pair_dir against the scalar operations, bits compared
            let m = pair_dir((a, c), (b, d), div);
            let (lo, hi) = if div {
                (div_dir(a, c, false), div_dir(b, d, true))
            } else {
                (mul_dir(a, c, false), mul_dir(b, d, true))
            };
            assert!(
                (m.lo.to_bits() == lo.to_bits() || (m.lo.is_nan() && lo.is_nan()))
                    && (m.hi.to_bits() == hi.to_bits() || (m.hi.is_nan() && hi.is_nan())),
                "{a:e} {c:e} {b:e} {d:e} div={div}: {m:?} vs {lo:e} {hi:e}"
            );
            // the scalar operation in its common case is inari's directed rounding
            if a.is_finite() && c.is_finite() && c != 0.0 {
                let p = if div { a / c } else { a * c };
                let common = (RESIDUAL_EXACT..=f64::MAX).contains(&p.abs())
                    && (!div || a.abs() >= RESIDUAL_EXACT);
                if common {
                    n_common += 1;
                    let (ia, ic) = (
                        Interval::try_from((a, a)).unwrap(),
                        Interval::try_from((c, c)).unwrap(),
                    );
                    let r = if div { ia / ic } else { ia * ic };
                    let (l, h) = if div {
                        (div_dir(a, c, false), div_dir(a, c, true))
                    } else {
                        (mul_dir(a, c, false), mul_dir(a, c, true))
                    };
                    assert!(
                        l == r.inf() && h == r.sup(),
                        "{a:e} {} {c:e}: [{l:e}, {h:e}] vs inari {r:?}",
                        if div { "/" } else { "·" }
                    );
                }
            }
            // interval operations: enclosure of the exact range, the table against the corners
            let (x, y) = (ulp(a, b), ulp(c, d));
            if x.lo.is_nan() || y.lo.is_nan() {
                continue;
            }
            if div {
                if !(y.lo > 0.0 || y.hi < 0.0) {
                    continue;
                }
                let r = x / y;
                if let Some((lo, hi)) = exact_extremes(x, y, true)
                    && r.lo.is_finite()
                    && r.hi.is_finite()
                {
                    n_q += 1;
                    assert!(
                        q(r.lo) <= lo && hi <= q(r.hi),
                        "{x:?} / {y:?} = {r:?} misses [{lo}, {hi}]"
                    );
                }
            } else {
                let r = x * y;
                let f = corners(x, y);
                let tiny = [(x.lo, y.lo), (x.lo, y.hi), (x.hi, y.lo), (x.hi, y.hi)]
                    .iter()
                    .any(|&(u, v)| u != 0.0 && v != 0.0 && (u * v).abs() < RESIDUAL_EXACT);
                assert!(
                    r == f || (tiny && f.lo <= r.lo && r.hi <= f.hi),
                    "{x:?} · {y:?}: {r:?} vs corners {f:?}"
                );
                if let Some((lo, hi)) = exact_extremes(x, y, false)
                    && r.lo.is_finite()
                    && r.hi.is_finite()
                {
                    assert!(
                        q(r.lo) <= lo && hi <= q(r.hi),
                        "{x:?} · {y:?} = {r:?} misses [{lo}, {hi}]"
                    );
                }
                // an infinite end from finite operands only where the exact end is beyond ±MAX
                if let Some((lo, hi)) = exact_extremes(x, y, false) {
                    let max = q(f64::MAX);
                    assert!(
                        (r.lo != f64::NEG_INFINITY || lo < -max.clone())
                            && (r.hi != f64::INFINITY || hi > max),
                        "{x:?} · {y:?} = {r:?}"
                    );
                }
            }
        }
        assert!(
            n_q > 300_000.min(iters(2_000_000) / 7) && n_common > 500_000.min(iters(2_000_000) / 4),
            "{n_q} {n_common}"
        );
    }

    /// x·k and x/k: the common route equals the one-end route bit for bit, encloses the exact
    /// value, and equals inari's directed operation where the result is in the residual range;
    /// k over small integers, powers of two up to 2^62, i64::MIN, and large odd integers.
    #[test]
    fn integer_scalings_on_threshold_operands() {
        let mut g = Gen::new(0x5be0_cd19_137e_2179);
        let ks: Vec<i64> = (1..=40)
            .chain((0..63).map(|j| 1i64 << j))
            .chain([
                (1 << 53) - 1,
                3 << 50,
                12345,
                1 << 60,
                1 << 61,
                (1 << 62) + (1 << 10),
            ])
            .flat_map(|k| [k, -k])
            .chain([i64::MIN])
            .collect();
        let mut n = 0u64;
        for i in 0..iters(2_000_000) {
            let div = i % 2 == 1;
            let k = ks[(g.next() % ks.len() as u64) as usize];
            let kf = k as f64;
            assert_eq!(kf as i128, k as i128);
            // x near k·2^t (quotient) or 2^t/k (product) for a threshold t
            let lk = kf.abs().log2().floor() as i32;
            let t = g.target();
            let mk = |g: &mut Gen| match g.next() % 3 {
                0 => g.any(),
                _ => g.with_exp(if div { t + lk } else { t - lk }),
            };
            let (a, b) = (mk(&mut g), mk(&mut g));
            if a.is_nan() || b.is_nan() {
                continue;
            }
            let x = if g.next().is_multiple_of(3) {
                Ulp::point(a)
            } else {
                ulp(a, b)
            };
            let r = x.int_op(k, div);
            let (u, v) = if k > 0 { (x.lo, x.hi) } else { (x.hi, x.lo) };
            if let Some(c) = int_op_common(u, v, kf, div) {
                let lo = int_op_bounds(u, kf, div).unwrap().0;
                let hi = int_op_bounds(v, kf, div).unwrap().1;
                assert!(
                    c.lo.to_bits() == lo.to_bits() && c.hi.to_bits() == hi.to_bits(),
                    "{x:?} {k} div={div}: {c:?} vs [{lo:e}, {hi:e}]"
                );
                n += 1;
                // inari's directed results
                let ix = Interval::try_from((x.lo, x.hi)).unwrap();
                let ik = Interval::try_from((kf, kf)).unwrap();
                let e = if div { ix / ik } else { ix * ik };
                assert!(
                    c.lo == e.inf() && c.hi == e.sup(),
                    "{x:?} {k} div={div}: {c:?} vs {e:?}"
                );
            }
            if x.lo.is_finite() && x.hi.is_finite() && r.lo.is_finite() && r.hi.is_finite() {
                let kq = Rational::from(k);
                let f = |w: f64| if div { q(w) / &kq } else { q(w) * &kq };
                let (p, s) = (f(u), f(v));
                assert!(
                    q(r.lo) <= p && s <= q(r.hi),
                    "{x:?} {k} div={div}: {r:?} misses [{p}, {s}]"
                );
            }
        }
        assert!(n > 400_000.min(iters(2_000_000) / 5), "{n}");
    }
}

#[cfg(test)]
/// An adversarial review's probes (2026-11-25): every operation and chains of them against
/// inari's results and the exact corners.
mod against_inari {
    use super::adversarial::{Gen, iters};
    use super::*;
    use rug::Rational;

    fn q(x: f64) -> Rational {
        Rational::from_f64(x).unwrap()
    }

    /// a random non-empty inari interval: special ends, arbitrary, across 0, one end ±0,
    /// thin, or with an infinite end
    fn rand_iv(g: &mut Gen) -> Interval {
        loop {
            let r = g.next() % 8;
            let (a, b) = match r {
                0 => (g.special(), g.special()),
                1 => (g.any(), g.any()),
                2 => {
                    let (u, v) = (g.any().abs(), g.any().abs());
                    (-u, v)
                }
                3 => {
                    let z = if g.next() & 1 == 0 { 0.0 } else { -0.0 };
                    (z, g.any())
                }
                4 => {
                    let x = g.any();
                    (x, x)
                }
                5 => {
                    let dv = g.next() & 1 == 0;
                    g.pair(dv)
                }
                6 => {
                    let x = g.any();
                    let inf = if g.next() & 1 == 0 {
                        f64::INFINITY
                    } else {
                        f64::NEG_INFINITY
                    };
                    (x, inf)
                }
                _ => {
                    let e1 = (g.next() % 20) as i32 - 10;
                    let x = g.with_exp(e1);
                    let e2 = (g.next() % 20) as i32 - 60;
                    (x, x + g.with_exp(e2))
                }
            };
            if a.is_nan() || b.is_nan() {
                continue;
            }
            let (lo, hi) = (a.min(b), a.max(b));
            if let Ok(x) = Interval::try_from((lo, hi)) {
                return x;
            }
        }
    }

    /// the exact [min, max] over the four corners (finite ends only)
    fn corners_exact(x: Interval, y: Interval, op: u8) -> Option<(Rational, Rational)> {
        let e = [x.inf(), x.sup(), y.inf(), y.sup()];
        if !e.iter().all(|v| v.is_finite()) {
            return None;
        }
        let mut v = Vec::new();
        for u in [x.inf(), x.sup()] {
            for w in [y.inf(), y.sup()] {
                v.push(match op {
                    0 => q(u) + q(w),
                    1 => q(u) - q(w),
                    2 => q(u) * q(w),
                    _ => q(u) / q(w),
                });
            }
        }
        Some((
            v.iter().min().unwrap().clone(),
            v.iter().max().unwrap().clone(),
        ))
    }

    /// every Ulp operation on inari intervals holds inari's result (a sound reference) and the
    /// exact corner extremes; counts where it is strictly wider than inari
    #[test]
    fn ulp_ops_hold_inari_and_the_exact_corners() {
        let n = iters(400_000);
        let mut g = Gen::new(0x7a3b_91c4_d2e5_f607);
        let mut wider = [0u64; 4];
        for i in 0..n {
            let x = rand_iv(&mut g);
            let mut y = rand_iv(&mut g);
            // for quotients, mostly a divisor of certain sign
            if !g.next().is_multiple_of(4) {
                let (c, d) = (y.inf(), y.sup());
                if c <= 0.0 && d >= 0.0 {
                    let m1 = c.abs().min(d.abs()).clamp(5e-324, f64::MAX);
                    let m2 = c.abs().max(d.abs()).max(m1);
                    y = if g.next() & 1 == 0 {
                        Interval::try_from((m1, m2)).unwrap()
                    } else {
                        Interval::try_from((-m2, -m1)).unwrap()
                    };
                }
            }
            for op in 0..4u8 {
                let (ux, uy) = (Ulp::of(x), Ulp::of(y));
                let u = match op {
                    0 => ux + uy,
                    1 => ux - uy,
                    2 => ux * uy,
                    _ => ux / uy,
                };
                let r = match op {
                    0 => x + y,
                    1 => x - y,
                    2 => x * y,
                    _ => x / y,
                };
                assert!(
                    !u.lo.is_nan() && !u.hi.is_nan(),
                    "{i} op {op}: {x:?} {y:?} -> NaN {u:?}"
                );
                assert!(u.lo <= u.hi, "{i} op {op}: {x:?} {y:?} -> {u:?}");
                if !r.is_empty() {
                    assert!(
                        u.lo <= r.inf() && r.sup() <= u.hi,
                        "{i} op {op}: {x:?} {y:?}: ulp {u:?} inari {r:?}"
                    );
                    if u.lo < r.inf() || r.sup() < u.hi {
                        wider[op as usize] += 1;
                    }
                }
                if op == 3 && !(y.inf() > 0.0 || y.sup() < 0.0) {
                    continue;
                }
                if let Some((lo, hi)) = corners_exact(x, y, op) {
                    assert!(
                        (u.lo == f64::NEG_INFINITY || q(u.lo) <= lo)
                            && (u.hi == f64::INFINITY || hi <= q(u.hi)),
                        "{i} op {op}: {x:?} {y:?}: ulp {u:?} exact [{lo}, {hi}]"
                    );
                }
            }
        }
        eprintln!("samples {n}: strictly wider than inari (add, sub, mul, div): {wider:?}");
    }

    /// chains of Ulp operations (intermediates never converted back) hold the chain of inari's
    #[test]
    fn ulp_chains_hold_inari_chains() {
        let n = iters(100_000);
        let mut g = Gen::new(0x1234_5678_9abc_def1);
        for i in 0..n {
            let mut x = rand_iv(&mut g);
            let mut u = Ulp::of(x);
            for step in 0..6 {
                let y = rand_iv(&mut g);
                let uy = Ulp::of(y);
                let op = g.next() % 4;
                let (nu, nx) = match op {
                    0 => (u + uy, x + y),
                    1 => (u - uy, x - y),
                    2 => (u * uy, x * y),
                    _ => (u / uy, x / y),
                };
                u = nu;
                x = nx;
                if x.is_empty() {
                    break;
                }
                assert!(
                    !u.lo.is_nan()
                        && !u.hi.is_nan()
                        && u.lo <= u.hi
                        && u.lo != f64::INFINITY
                        && u.hi != f64::NEG_INFINITY,
                    "{i} step {step}: {u:?}"
                );
                let back = u.interval();
                assert!(
                    x.subset(back),
                    "{i} step {step} op {op}: y {y:?}: ulp {u:?} inari {x:?}"
                );
            }
        }
    }
}
