//! Fast rigorous exp, ln and real powers of inari intervals.
//!
//! inari's `pow` is correct and tight but goes through MPFR (log by AGM), which dominated the
//! rigorous engine's time. These reduce the argument in interval arithmetic, evaluate the
//! series below by Horner's scheme in f64 with a running error bound (Higham §5.1), and add
//! proved bounds for the coefficients' rounding, the reduced argument's width and the
//! truncated tail, so every result encloses the exact value; they are a few ulps wider than
//! inari's.
//!
//! | function | reduction | series | tail bound |
//! |---|---|---|---|
//! | ln x, x > 0 | x = m·2^e (from the bits), m ∈ [1/√2, √2), s = (m−1)/(m+1), \|s\| < 0.1716 | ln m = 2 Σ_{i<n} s^(2i+1)/(2i+1) | 2\|s\|·s^(2n)/((2n+1)(1−s²)) |
//! | exp y | y = k ln 2 + r (ln 2 in two parts, Cody–Waite), k = round(y/ln 2), \|r\| ≤ 0.35 | e^r = Σ_{i<n} r^i/i! | \|r\|^n/n! · e^{\|r\|} ≤ 1.5 \|r\|^n/n! |
//! | x^q, x ≥ 0, q > 0 | x^q = exp(q · ln x) over the boxes (q·ln x over a box is the exact range of the product) | | relative width ≈ (\|q ln x\| + a few) ulps |

use super::ulp::Ulp;
use crate::arith::Real;
use inari::{Interval, const_interval};
use std::sync::OnceLock;

/// ln 2 = LN2_HI + lo (Cody & Waite): LN2_HI has its 21 low bits zero, so k·LN2_HI is exact
/// for |k| < 2^21; lo is enclosed once from a 256-bit MPFR value of ln 2.
const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);

fn ln2_lo() -> Interval {
    static LO: OnceLock<Interval> = OnceLock::new();
    *LO.get_or_init(|| {
        use rug::float::{Constant, Round};
        let lo = rug::Float::with_val(256, Constant::Log2) - LN2_HI;
        Interval::try_from((lo.to_f64_round(Round::Down), lo.to_f64_round(Round::Up))).unwrap()
    })
}

const ONE: Interval = const_interval!(1.0, 1.0);
/// Terms of the ln series: s² < 0.0295 ⇒ s^(2n) < 4.5·10⁻¹⁹ for n = 12.
const LN_TERMS: usize = 12;
/// Terms of the exp series: 0.35^16/16! < 3·10⁻²¹.
const EXP_TERMS: usize = 16;

/// x^n for x ≥ 0 by binary powering in interval arithmetic (inari's `powi` goes through
/// MPFR; for a nonnegative base each product is monotone, so this is as tight up to rounding).
pub fn powi_nonneg(x: Interval, n: u32) -> Interval {
    debug_assert!(x.inf() >= 0.0 || x.is_empty());
    if x.is_empty() {
        return x;
    }
    Ulp::of(x).powi_nonneg(n).interval()
}

/// 1/(2i+1) (ln series) and 1/i! (exp series), each the nearest double (relative error
/// ≤ u = 2^−53), from 256-bit MPFR.
#[allow(clippy::type_complexity)]
fn coefficients() -> &'static ([f64; LN_TERMS], [f64; EXP_TERMS]) {
    static T: OnceLock<([f64; LN_TERMS], [f64; EXP_TERMS])> = OnceLock::new();
    T.get_or_init(|| {
        use rug::Float;
        let odd = std::array::from_fn(|i| (Float::with_val(256, 1) / (2 * i as u32 + 1)).to_f64());
        let mut f = Float::with_val(256, 1);
        let inv_fact = std::array::from_fn(|i| {
            if i > 0 {
                f *= i as u32;
            }
            (Float::with_val(256, 1) / &f).to_f64()
        });
        (odd, inv_fact)
    })
}

/// Horner's scheme Σ c_i x^i in f64 (FMA) with Higham's running error bound (*Accuracy and
/// Stability*, §5.1): returns (p̂, β) where, for the polynomial with the f64 coefficients c_i,
/// |p̂ − Σ c_i x^i| ≤ u/(1 − u)·β_exact with β_exact = Σ_{i<n−1} |x|^i |ŷ_i| over the computed
/// partial results ŷ_i (each FMA step errs by at most u|ŷ_i|/(1 − u), and earlier errors are
/// multiplied by |x|), provided the ŷ_i are normal (true here: they are ≥ the smallest
/// coefficient). The computed β (sums of nonnegative terms) is ≥ β_exact·(1 − u)^n, so
/// u·β·(1 + 2^−40) bounds the error for n ≤ 2^10.
#[inline]
fn horner_running(c: &[f64], x: f64) -> (f64, f64) {
    let n = c.len();
    let ax = x.abs();
    let mut y = c[n - 1];
    let mut beta = 0.0_f64;
    for i in (0..n - 1).rev() {
        y = x.mul_add(y, c[i]);
        beta = ax.mul_add(beta, y.abs());
    }
    (y, beta)
}

/// u·(1 + 2^−40): the running error bound's factor (see [`horner_running`]), with room for the
/// rounding of the few operations that combine the bounds (each relative error ≤ u).
const U_SAFE: f64 = f64::EPSILON / 2.0 * (1.0 + 1.0 / 1_099_511_627_776.0);

/// A series S_N = Σ_{i<N} a_i t^i (exact coefficients a_i) evaluated over an interval
/// T = [t.lo, t.hi] of the reduced argument, with the bound of each error source, so that
/// [`Budget::enclosure`] contains the full series' value at every t* ∈ T. Each bound is
/// tested against the exact quantity it bounds (MPFR, tests below):
///
/// - `rounding` ≥ |value − Σ c_i t.lo^i| (Horner in f64, c_i the f64 coefficients);
/// - `coefficients` ≥ |Σ (a_i − c_i) t.lo^i|;
/// - `width` ≥ S_N(t.hi) − S_N(t.lo) ≥ S_N(t*) − S_N(t.lo) ≥ 0 (S_N increasing on T);
/// - `tail` ≥ |S_∞(t*) − S_N(t*)|, the truncated series (up to an underflow below 2^−1000,
///   which the outward steps of [`around`] cover).
#[derive(Clone, Copy, Debug)]
struct Budget {
    value: f64,
    rounding: f64,
    coefficients: f64,
    tail: f64,
    width: f64,
}

impl Budget {
    /// [value − e, value + e + width] rounded outwards, e = rounding + coefficients + tail.
    #[inline(always)]
    fn enclosure(self) -> Ulp {
        around(
            self.value,
            self.rounding + self.coefficients + self.tail,
            self.width,
        )
    }
}

/// [p − e, p + e + w] rounded outwards: e, w ≥ 0 are bounds computed in round-to-nearest,
/// so both are first inflated by 1% (far more than their rounding errors: the result contains
/// [p − E, p + E + W] for any E ≤ 1.0078·e, W ≤ 1.0078·w).
#[inline]
fn around(p: f64, e: f64, w: f64) -> Ulp {
    let e = e * 1.01;
    let w = w * 1.01;
    Ulp {
        lo: (p - e).next_down(),
        hi: (p + (e + w)).next_up(),
    }
}

/// ln 2's low part as a [`Ulp`] interval.
fn ln2_lo_ulp() -> Ulp {
    static LO: OnceLock<Ulp> = OnceLock::new();
    *LO.get_or_init(|| Ulp::of(ln2_lo()))
}

fn pt(x: f64) -> Interval {
    Interval::try_from((x, x)).unwrap()
}

/// Q(z) = Σ_{i<N} z^i/(2i+1) (ln m = 2s·Q(s²)) over z ⊆ [0, 0.0295], Q increasing: Horner at
/// z.lo with its running error bound, the coefficients' rounding (≤ u·Q ≤ 1.04u), Q′ ≤ 0.35
/// times the width of z, and the tail Σ_{i≥N} z^i/(2i+1) ≤ z^N/((2N+1)(1 − z)).
#[inline(always)]
fn ln_series<const N: usize>(z: Ulp) -> Budget {
    const { assert!(N >= 1 && N <= LN_TERMS) };
    let (value, beta) = horner_running(&coefficients().0[..N], z.lo);
    let zh = z.hi;
    Budget {
        value,
        rounding: U_SAFE * beta,
        coefficients: 1.04 * U_SAFE,
        tail: zh.powi(N as i32) / ((2 * N + 1) as f64 * (1.0 - zh)),
        width: 0.35 * (z.hi - z.lo),
    }
}

/// P(r) = Σ_{i<N} r^i/i! over r ⊆ [−0.35, 0.35], P increasing: Horner at r.lo with its running
/// error bound, the coefficients' rounding (≤ u·e^|r| ≤ 1.42u), P′ ≤ e^0.35 < 1.42 times the
/// width of r, and the tail ≤ |r|^N/N!·e^|r| ≤ 1.5 |r|^N/N!.
#[inline(always)]
fn exp_series<const N: usize>(r: Ulp) -> Budget {
    const { assert!(N >= 1 && N <= EXP_TERMS) };
    let inv_fact = &coefficients().1;
    let (value, beta) = horner_running(&inv_fact[..N], r.lo);
    Budget {
        value,
        rounding: U_SAFE * beta,
        coefficients: 1.42 * U_SAFE,
        tail: 1.5 * r.mag().powi(N as i32) * inv_fact[N - 1] / N as f64,
        width: 1.42 * (r.hi - r.lo),
    }
}

/// An enclosure of ln x for a finite x > 0 (the series in [`Ulp`] arithmetic: no rounding-mode
/// switches inside the loop).
fn ln_point(x: f64) -> Interval {
    ln_point_n::<LN_TERMS>(x)
}

/// x = 2^e·m exactly, m ∈ [1/√2, √2), and an enclosure of s = (m − 1)/(m + 1), |s| < 0.1716
/// (ln x = e ln 2 + 2s·Q(s²)), for a finite x > 0.
#[inline(always)]
fn ln_reduction(x: f64) -> (i32, Ulp) {
    debug_assert!(x > 0.0 && x.is_finite());
    // subnormal x: scale by 2^64 first (exact), so that its exponent field is that of a normal
    let (x, e0) = if x < f64::MIN_POSITIVE {
        (x * 2f64.powi(64), -64)
    } else {
        (x, 0)
    };
    // x = m·2^e exactly from the bits: m ∈ [1, 2) (the mantissa with a zero exponent field)
    let bits = x.to_bits();
    let mut e = ((bits >> 52) & 0x7ff) as i32 - 1023 + e0;
    let mut m = f64::from_bits((bits & ((1u64 << 52) - 1)) | (1023u64 << 52));
    // recentre to m ∈ [1/√2, √2)
    if m > std::f64::consts::SQRT_2 {
        m /= 2.0;
        e += 1;
    }
    // m − 1 is exact (Sterbenz); s by a directed division
    (e, Ulp::point(m - 1.0) / (Ulp::point(m) + Ulp::point(1.0)))
}

/// [`ln_point`] with N terms of the series (the tests use fewer, where the tail dominates).
#[inline(always)]
fn ln_point_n<const N: usize>(x: f64) -> Interval {
    let (e, s) = ln_reduction(x);
    let series = ln_series::<N>(s * s).enclosure();
    // small parts first: e·lo + 2s·Q, then the exact e·LN2_HI
    let ef = Ulp::point(e as f64);
    ((ef * ln2_lo_ulp() + Ulp::point(2.0) * s * series) + Ulp::point(e as f64 * LN2_HI)).interval()
}

/// An enclosure of e^y for a finite y (the series in [`Ulp`] arithmetic).
fn exp_point(y: f64) -> Interval {
    exp_point_n::<EXP_TERMS>(y)
}

/// [`exp_point`] with N terms of the series (the tests use fewer, where the tail dominates).
#[inline(always)]
fn exp_point_n<const N: usize>(y: f64) -> Interval {
    if y == 0.0 {
        return ONE; // exact (so that 1^q, |−1|^q stay exact)
    }
    if y > 709.8 {
        return Interval::try_from((f64::MAX, f64::INFINITY)).unwrap();
    }
    if y < -745.2 {
        return Interval::try_from((0.0, f64::MIN_POSITIVE)).unwrap();
    }
    let (k, r) = exp_reduction(y);
    let v = exp_series::<N>(r).enclosure();
    // multiply by 2^k (split to stay in range; outward steps cover underflow)
    let k = k as i32;
    let (k1, k2) = (k / 2, k - k / 2);
    (v * Ulp::point(2f64.powi(k1)) * Ulp::point(2f64.powi(k2))).interval()
}

/// k = round(y/ln 2) and an enclosure of r = y − k ln 2, |r| ≤ 0.35 (e^y = 2^k·e^r), for
/// a finite y, |y| ≤ 746.
#[inline(always)]
fn exp_reduction(y: f64) -> (f64, Ulp) {
    let k = (y / std::f64::consts::LN_2).round();
    // y − k·LN2_HI is exact (Sterbenz, k·LN2_HI exact); then the small part
    (k, Ulp::point(y - k * LN2_HI) - Ulp::point(k) * ln2_lo_ulp())
}

/// An enclosure of ln X for X ⊆ (0, ∞) (ENTIRE if X reaches 0 or below, or is unbounded).
pub fn ln(x: Interval) -> Interval {
    if x.is_empty() || x.inf() <= 0.0 || !x.sup().is_finite() {
        return Interval::ENTIRE;
    }
    let lo = ln_point(x.inf());
    // a thin X: ln(x.sup) = ln(x.inf) + ln(1 + u) ≤ ln(x.inf) + u, u = (x.sup − x.inf)/x.inf
    let u = div_as_inari(sub_as_inari(pt(x.sup()), pt(x.inf())), pt(x.inf()));
    let hi = if u.sup() < 1e-3 {
        (Ulp::of(lo) + Ulp::of(u)).hi
    } else {
        ln_point(x.sup()).sup()
    };
    Interval::try_from((lo.inf(), hi)).unwrap()
}

/// x − y for non-empty x, y in [`Ulp`] arithmetic (no rounding-mode switches): TwoSum gives the
/// exact error of each end, so the ends are inari's directed roundings bit for bit (test
/// `operations_enclose_the_exact_results` of [`super::ulp`] compares them).
#[inline]
fn sub_as_inari(x: Interval, y: Interval) -> Interval {
    (Ulp::of(x) - Ulp::of(y)).interval()
}

/// x/y for non-empty x, y in [`Ulp`] arithmetic where that is inari's quotient bit for bit,
/// else inari's. Accepted when x and y each have one sign (the case table: each end one
/// directed quotient), y is bounded, both ends of x are 0 or ≥ 2^−969 in magnitude and both
/// result ends lie strictly between 2^−969 and MAX in magnitude: then each end's nearest
/// quotient q has |q| ≥ 2^−969 and is finite, with a non-zero dividend ≥ 2^−969, the case in
/// which the residual a − q·b is exact and its sign decides the directed rounding exactly as
/// inari's rounding mode does (test `quotients_as_inari_equal_inaris`).
#[inline]
fn div_as_inari(x: Interval, y: Interval) -> Interval {
    use super::ulp::RESIDUAL_EXACT;
    let one_sign = |v: Interval| v.inf() >= 0.0 || v.sup() <= 0.0;
    let dividend = |a: f64| a == 0.0 || a.abs() >= RESIDUAL_EXACT;
    if !x.is_empty()
        && !y.is_empty()
        && one_sign(x)
        && (y.inf() > 0.0 || y.sup() < 0.0)
        && y.inf().is_finite()
        && y.sup().is_finite()
        && dividend(x.inf())
        && dividend(x.sup())
    {
        let r = Ulp::of(x) / Ulp::of(y);
        let normal = |e: f64| e.abs() > RESIDUAL_EXACT && e.abs() < f64::MAX;
        if normal(r.lo) && normal(r.hi) {
            return r.interval();
        }
    }
    x / y
}

/// An enclosure of e^Y.
pub fn exp(y: Interval) -> Interval {
    if y.is_empty() {
        return Interval::EMPTY;
    }
    if !y.inf().is_finite() || !y.sup().is_finite() {
        return Interval::try_from((0.0, f64::INFINITY)).unwrap();
    }
    let lo = exp_point(y.inf());
    // a thin Y: e^(y.sup) = e^(y.inf)·e^d ≤ e^(y.inf)/(1 − d), d = y.sup − y.inf < 1
    let d = sub_as_inari(pt(y.sup()), pt(y.inf()));
    let hi = if d.sup() < 1e-3 {
        div_as_inari(lo, sub_as_inari(ONE, d)).sup()
    } else {
        exp_point(y.sup()).sup()
    };
    Interval::try_from((lo.inf().max(0.0), hi)).unwrap()
}

/// An enclosure of x^q over X ⊆ [0, ∞), Q ⊆ (0, ∞), or X ⊆ (0, ∞), Q ⊆ (−∞, 0) (then
/// 1/x^(−q), the quotient rounded outward); `None` where this fast path does not apply (bases
/// reaching 0 or below with q reaching 0 or below, unbounded arguments; the callers then take
/// inari's, which computes through MPFR and cost a tenth of the singular steps' time for the
/// negative exponents of their binomial remainders and reciprocals).
pub fn pow(x: Interval, q: Interval) -> Option<Interval> {
    if !x.is_empty() && !q.is_empty() && x.inf() > 0.0 && q.sup() < 0.0 && q.inf().is_finite() {
        if q.inf() == -1.0 && q.sup() == -1.0 {
            return x.sup().is_finite().then(|| div_as_inari(ONE, x)); // one rounding, not exp·ln's
        }
        return pow(x, -q).map(|p| div_as_inari(ONE, p));
    }
    if x.is_empty()
        || q.is_empty()
        || x.inf() < 0.0
        || q.inf() <= 0.0
        || !x.sup().is_finite()
        || !q.sup().is_finite()
    {
        return None;
    }
    if x.sup() == 0.0 {
        return Some(pt(0.0));
    }
    if x.inf() == 0.0 {
        // 0 ≤ x^q ≤ sup: the largest value is at x.sup, with q at the end that maximizes it
        let hi = exp(q.mul_constant(&ln(pt(x.sup())))).sup();
        return Some(Interval::try_from((0.0, hi)).unwrap());
    }
    // q·ln x by the fast product, bit for bit inari's (no rounding-mode switches)
    Some(pow_memo(x, q))
}

/// The last [`MEMO_SLOTS`] results of a function of intervals, per thread, keyed by the
/// operands' ends (a function of the doubles: what it returns for a key is that function's
/// value bit for bit).
struct Memo {
    keys: [[u64; 4]; MEMO_SLOTS],
    values: [Interval; MEMO_SLOTS],
    next: usize,
}

/// Enough for the operands of one Taylor step's jets: the powers over X, over the a-priori
/// box and at the midpoint, then the duals' values over X again (≈ 3 operands each).
const MEMO_SLOTS: usize = 16;

impl Memo {
    const fn new() -> Self {
        Self {
            keys: [[u64::MAX; 4]; MEMO_SLOTS],
            values: [Interval::EMPTY; MEMO_SLOTS],
            next: 0,
        }
    }

    fn get_or(&mut self, key: [u64; 4], f: impl FnOnce() -> Interval) -> Interval {
        if let Some(i) = self.keys.iter().position(|k| *k == key) {
            return self.values[i];
        }
        let v = f();
        self.keys[self.next] = key;
        self.values[self.next] = v;
        self.next = (self.next + 1) % MEMO_SLOTS;
        v
    }
}

fn bits(x: Interval) -> [u64; 2] {
    [x.inf().to_bits(), x.sup().to_bits()]
}

/// [`ln`] with the last results remembered per thread ([`Memo`]): the powers of one operand
/// with several exponents — |Y|^(p−1)Y and |Y|^p, |Z|^(n−1)Z and |Z|^n — take the same
/// logarithm one after the other in each jet (exp and ln 14 % of a Maxwell CoR's time).
fn ln_memo(x: Interval) -> Interval {
    thread_local! {
        static MEMO: std::cell::RefCell<Memo> = const { std::cell::RefCell::new(Memo::new()) };
    }
    let [a, b] = bits(x);
    MEMO.with(|m| m.borrow_mut().get_or([a, b, 0, 0], || ln(x)))
}

/// [`pow`]'s general case exp(q·ln x) remembered per thread ([`Memo`]): the jet on duals over
/// X takes the same powers of X as the jet over X just before it.
fn pow_memo(x: Interval, q: Interval) -> Interval {
    thread_local! {
        static MEMO: std::cell::RefCell<Memo> = const { std::cell::RefCell::new(Memo::new()) };
    }
    let ([a, b], [c, d]) = (bits(x), bits(q));
    MEMO.with(|m| {
        m.borrow_mut()
            .get_or([a, b, c, d], || exp(q.mul_constant(&ln_memo(x))))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Float;
    use rug::ops::Pow;

    const PREC: u32 = 256;

    fn contains_exact(i: Interval, exact: &Float) -> bool {
        Float::with_val(PREC, i.inf()) <= *exact && *exact <= Float::with_val(PREC, i.sup())
    }

    /// [`sub_as_inari`] and [`div_as_inari`] are inari's `−` and `/` bit for bit, on ends of
    /// every kind (±0, ±∞, subnormal, tiny, huge, ±MAX, across 0), the Ulp route taken in most
    /// of them.
    #[test]
    fn quotients_as_inari_equal_inaris() {
        let mut next = crate::arith::interval::xorshift(0xa54ff53a5f1d36f1_u64);
        let special = crate::arith::interval::SPECIAL;
        let float = |r: u64| crate::arith::interval::operand(r, &special);
        let same = |a: Interval, b: Interval| {
            a.is_empty() == b.is_empty()
                && (a.is_empty() || (a.inf() == b.inf() && a.sup() == b.sup()))
        };
        let mut fast = 0;
        for _ in 0..400_000 {
            let (a, b, c, d) = (float(next()), float(next()), float(next()), float(next()));
            let (Ok(x), Ok(y)) = (
                Interval::try_from((a.min(b), a.max(b))),
                Interval::try_from((c.min(d), c.max(d))),
            ) else {
                continue;
            };
            assert!(same(sub_as_inari(x, y), x - y), "{x:?} − {y:?}");
            let q = div_as_inari(x, y);
            assert!(same(q, x / y), "{x:?} / {y:?}: {q:?} vs {:?}", x / y);
            let r = Ulp::of(x) / Ulp::of(y);
            if r.lo.abs() > 1e-200 && r.hi.abs() < 1e200 && (x.inf() >= 0.0 || x.sup() <= 0.0) {
                fast += 1;
            }
        }
        assert!(fast > 40_000, "{fast}");
    }

    #[test]
    fn ln_and_exp_enclose_256_bit_values_and_are_tight() {
        let mut seed = 0x2545F4914F6CDD1Du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for _ in 0..20_000 {
            let u = (next() >> 11) as f64 / (1u64 << 53) as f64;
            let x = (u * 80.0 - 40.0).exp2();
            let l = ln(pt(x));
            let exact = Float::with_val(PREC, x).ln();
            assert!(contains_exact(l, &exact), "ln({x}) = {exact} ∉ {l:?}");
            assert!(
                l.wid() <= 8.0 * f64::EPSILON * l.mag().max(1e-300) + 1e-300,
                "ln({x}) too wide: {l:?}"
            );
            let y = u * 1400.0 - 700.0;
            let e = exp(pt(y));
            let exact = Float::with_val(PREC, y).exp();
            assert!(contains_exact(e, &exact), "exp({y}) = {exact} ∉ {e:?}");
            assert!(
                e.wid() <= 16.0 * f64::EPSILON * e.mag(),
                "exp({y}) too wide: {e:?}"
            );
        }
        // around 1 and the reduction boundaries
        for x in [
            1.0,
            1.0 + f64::EPSILON,
            1.0 - f64::EPSILON / 2.0,
            std::f64::consts::SQRT_2,
            0.5,
            2.0,
        ] {
            assert!(
                contains_exact(ln(pt(x)), &Float::with_val(PREC, x).ln()),
                "{x}"
            );
        }
        assert!(exp(pt(0.0)).contains(1.0));
        // subnormal and extreme arguments
        for x in [5e-324, 1e-310, f64::MIN_POSITIVE, f64::MAX] {
            assert!(
                contains_exact(ln(pt(x)), &Float::with_val(PREC, x).ln()),
                "ln {x}"
            );
        }
        for y in [-745.0, -720.0, 709.0] {
            assert!(
                contains_exact(exp(pt(y)), &Float::with_val(PREC, y).exp()),
                "exp {y}"
            );
        }
    }

    #[test]
    #[allow(clippy::approx_constant)] // 3.14 is the paper's p (Table 1), not π
    fn pow_encloses_corners_and_interior_points() {
        let cases = [
            (0.3, 0.7, 1.27, 1.27),
            (1.5, 2.5, 0.31, 2.14),
            (1e-9, 1e-6, 3.14, 3.14),
            (0.0, 0.2, 1.3, 1.31),
            // negative exponents (the binomial remainders (1 + θε)^(q − K), reciprocals)
            (0.999, 1.003, -5.73, -5.73),
            (0.3, 0.7, -1.0, -1.0),
            (1.5, 2.5, -2.14, -0.31),
            (1e-9, 1e-6, -3.14, -3.14),
            (1e-300, 1e-200, -1.27, -1.27),
        ];
        for (a, b, c, d) in cases {
            let x = Interval::try_from((a, b)).unwrap();
            let q = Interval::try_from((c, d)).unwrap();
            let p = pow(x, q).unwrap();
            for xs in [a, 0.5 * (a + b), b] {
                for qs in [c, 0.5 * (c + d), d] {
                    let exact = Float::with_val(PREC, xs).pow(Float::with_val(PREC, qs));
                    assert!(contains_exact(p, &exact), "{xs}^{qs} = {exact} ∉ {p:?}");
                }
            }
            // no wider than inari's (MPFR) enclosure by more than the exponent's rounding: the
            // relative error of exp(q ln x) is about (|q ln x| + a few) ulps
            let tight = x.pow(q);
            let qm = c.abs().max(d.abs());
            let qlx = (qm * a.max(f64::MIN_POSITIVE).ln().abs()).max(qm * b.ln().abs());
            let slack = (qlx + 8.0) * 4.0 * f64::EPSILON * tight.mag();
            assert!(
                p.inf() >= tight.inf() - slack && p.sup() <= tight.sup() + slack,
                "{p:?} vs {tight:?}"
            );
        }
        assert!(pow(pt(-1.0), pt(2.0)).is_none());
        // q = −1: the quotient itself (one rounding), not exp(−ln x)
        let x = Interval::try_from((0.3, 0.7)).unwrap();
        let (r, d) = (pow(x, pt(-1.0)).unwrap(), div_as_inari(ONE, x));
        assert!(r.inf() == d.inf() && r.sup() == d.sup(), "{r:?} vs {d:?}");
        // a base reaching 0, an exponent across 0: not this path
        assert!(pow(Interval::try_from((0.0, 1.0)).unwrap(), pt(-1.0)).is_none());
        assert!(pow(pt(2.0), Interval::try_from((-1.0, 1.0)).unwrap()).is_none());
    }

    /// The remembered logarithms and powers are `ln`'s and exp(q·ln x)'s, bit for bit, over a
    /// sequence that repeats operands within and beyond the memo's slots (hits, evictions, thin
    /// and wide intervals, several exponents), and over operands that share one end (the same
    /// lower end with other upper ends and the reverse, for bases and for exponents), each
    /// right after the other: a key without one of the four ends returns another operand's
    /// value.
    #[test]
    fn remembered_logarithms_are_the_logarithms() {
        let iv = |a: f64, b: f64| Interval::try_from((a, b)).unwrap();
        let mut next = crate::arith::interval::xorshift(0x6a09_e667_f3bc_c908_u64);
        let pool: Vec<Interval> = (0..30)
            .map(|i| {
                let a = 0.1 + (next() >> 11) as f64 / (1u64 << 53) as f64 * 3.0;
                let w = [0.0, 1e-12, 0.5][i % 3];
                iv(a, a + w)
            })
            .chain([iv(2.0, 2.0), iv(2.0, 2.5), iv(1.5, 2.5), iv(2.5, 2.5)])
            .collect();
        // exponents: three of the pool, then one lower end with two upper ends, one upper end
        // with two lower ends
        let exponents = [
            pool[0],
            pool[1],
            pool[2],
            iv(1.27, 1.27),
            iv(1.27, 1.31),
            iv(1.2, 1.31),
        ];
        let same = |a: Interval, b: Interval| {
            a.inf().to_bits() == b.inf().to_bits() && a.sup().to_bits() == b.sup().to_bits()
        };
        let check = |x: Interval, q: Interval| {
            let (a, b) = (ln_memo(x), ln(x));
            assert!(same(a, b), "{x:?}: {a:?} vs {b:?}");
            let (c, d) = (pow_memo(x, q), exp(q.mul_constant(&ln(x))));
            assert!(same(c, d), "{x:?}^{q:?}: {c:?} vs {d:?}");
        };
        for _ in 0..2000 {
            let x = pool[(next() % pool.len() as u64) as usize];
            let q = exponents[(next() % exponents.len() as u64) as usize];
            check(x, q);
        }
        // operands sharing an end, one right after the other
        for x in &pool {
            for q in &exponents[3..] {
                check(*x, *q);
            }
        }
        for q in &exponents {
            for x in &pool[30..] {
                check(*x, *q);
            }
        }
    }

    /// x^q for q < 0 encloses the exact power (256 bits): at 2000 thin bases in [2⁻⁴⁰, 2⁴⁰]
    /// with q = −1 (the quotient 1/x, one outward rounding) and with q = −0.31, −1.27, −2.14,
    /// −5.73 (1/x^(−q), the quotient rounded outward), at 2000 thin bases in [2, 10⁴] with x^q
    /// in [2⁻¹⁰²⁴, 2⁻¹⁰²²] (subnormal quotients), and over exponent ranges with −1 at one end
    /// ([−1, −0.5], [−2, −1], [−1, −1 + 2⁻⁴⁰]: not the quotient) at their corners and interior
    /// points, for thin and wide bases on both sides of 1.
    #[test]
    fn negative_powers_enclose_the_exact_powers() {
        let mut next = crate::arith::interval::xorshift(0xbb67_ae85_84ca_a73b_u64);
        for _ in 0..2000 {
            let u = (next() >> 11) as f64 / (1u64 << 53) as f64;
            let x = (u * 80.0 - 40.0).exp2();
            for q in [-1.0, -0.31, -1.27, -2.14, -5.73] {
                let p = pow(pt(x), pt(q)).unwrap();
                let exact = Float::with_val(PREC, x).pow(Float::with_val(PREC, q));
                assert!(contains_exact(p, &exact), "{x}^{q} = {exact} ∉ {p:?}");
            }
        }
        // x^q just below the normal range (x^(−q) just below f64::MAX): a subnormal quotient,
        // which `div_as_inari` leaves to inari's division
        for _ in 0..2000 {
            let u = (next() >> 11) as f64 / (1u64 << 53) as f64;
            let x = 2.0 + u * 1e4;
            let e = 1022.0 + 2.0 * (next() >> 11) as f64 / (1u64 << 53) as f64;
            let q = -e * std::f64::consts::LN_2 / x.ln();
            let p = pow(pt(x), pt(q)).unwrap();
            let exact = Float::with_val(PREC, x).pow(Float::with_val(PREC, q));
            assert!(contains_exact(p, &exact), "{x}^{q} = {exact} ∉ {p:?}");
        }
        let near = -1.0 + 2f64.powi(-40);
        for (c, d) in [(-1.0, -0.5), (-2.0, -1.0), (-1.0, near)] {
            let q = Interval::try_from((c, d)).unwrap();
            for (a, b) in [(0.3, 0.7), (2.0, 2.0), (1.5, 2.5), (1e-9, 1e-6), (0.3, 0.3)] {
                let p = pow(Interval::try_from((a, b)).unwrap(), q).unwrap();
                for xs in [a, 0.5 * (a + b), b] {
                    for qs in [c, 0.5 * (c + d), d] {
                        let exact = Float::with_val(PREC, xs).pow(Float::with_val(PREC, qs));
                        assert!(contains_exact(p, &exact), "{xs}^{qs} = {exact} ∉ {p:?}");
                    }
                }
            }
        }
    }

    // ---- each explicit error term against the exact quantity it bounds ----

    use rug::Rational;

    /// Precision of the MPFR values of the transcendental parts (the polynomial parts are
    /// exact rationals): their error (≤ 2^−1190 here) is far below [`TOL`].
    const HI_PREC: u32 = 1200;
    /// Absolute tolerance of the tail checks: z^N or |r|^N underflowed in f64 (the tail bound is
    /// then 0), which the outward steps of `around` cover (they move ≥ 2^−54 from values ≥ 1/2).
    const TOL: f64 = 1e-300;

    fn q(x: f64) -> Rational {
        Rational::from_f64(x).unwrap()
    }

    /// Σ a_i t^i exactly.
    fn poly(a: &[Rational], t: &Rational) -> Rational {
        a.iter().rev().fold(Rational::new(), |acc, c| acc * t + c)
    }

    /// The exact coefficients 1/(2i+1) or 1/i! (`ln`), and their f64 roundings, first N.
    fn ln_coefficients(n: usize) -> (Vec<Rational>, Vec<Rational>) {
        let exact = (0..n)
            .map(|i| Rational::from((1, 2 * i as u32 + 1)))
            .collect();
        (exact, coefficients().0[..n].iter().map(|&c| q(c)).collect())
    }

    fn exp_coefficients(n: usize) -> (Vec<Rational>, Vec<Rational>) {
        let mut f = rug::Integer::from(1);
        let exact = (0..n)
            .map(|i| {
                if i > 0 {
                    f *= i as u32;
                }
                Rational::from((1, f.clone()))
            })
            .collect();
        (exact, coefficients().1[..n].iter().map(|&c| q(c)).collect())
    }

    /// The full series S_∞ at t: atanh(√z)/√z (ln) or e^r (exp).
    fn full_series(ln: bool, t: f64) -> Float {
        let t = Float::with_val(HI_PREC, t);
        if !ln {
            return t.exp();
        }
        if t == 0 {
            return Float::with_val(HI_PREC, 1);
        }
        let s = t.sqrt();
        Float::with_val(HI_PREC, s.clone().atanh() / s)
    }

    /// Largest ratio (exact quantity)/(its bound) seen per term: rounding, coefficients, width,
    /// tail (so a test can also show that its inputs reach where a bound is nearly tight).
    type Ratios = [f64; 4];

    fn ratio(exact: &Rational, bound: f64) -> f64 {
        if bound > 0.0 {
            exact.to_f64() / bound
        } else if *exact == 0 {
            0.0
        } else {
            f64::INFINITY
        }
    }

    /// Checks each term of `b` (the series of `ln` or `exp` with N terms over T = [t.lo, t.hi])
    /// against the exact error it bounds, and the enclosure against S_∞ at both ends of T. The
    /// terms are computed in round-to-nearest: each may fall short of its formula by a few
    /// ulps, which `around` covers for up to 2^−7 (tested below), so each is checked with that
    /// factor.
    fn check_budget(ln: bool, n: usize, t: Ulp, b: Budget, ratios: &mut Ratios) {
        let slack = |x: f64| q(x) * Rational::from((129, 128));
        let (exact, rounded) = if ln {
            ln_coefficients(n)
        } else {
            exp_coefficients(n)
        };
        let (lo, hi) = (q(t.lo), q(t.hi));
        let what = format!(
            "{} series, N = {n}, t = {t:?}: {b:?}",
            if ln { "ln" } else { "exp" }
        );
        // rounding: Horner in f64 against the exact polynomial with the f64 coefficients
        let p_rounded = poly(&rounded, &lo);
        let err = (q(b.value) - &p_rounded).abs();
        assert!(err <= slack(b.rounding), "rounding {err} > bound, {what}");
        ratios[0] = ratios[0].max(ratio(&err, b.rounding));
        // coefficients: the exact polynomial against the one with f64 coefficients, at t.lo
        let p_exact_lo = poly(&exact, &lo);
        let err = Rational::from(&p_exact_lo - &p_rounded).abs();
        assert!(
            err <= slack(b.coefficients),
            "coefficients {err} > bound, {what}"
        );
        ratios[1] = ratios[1].max(ratio(&err, b.coefficients));
        // width: S_N(t.hi) − S_N(t.lo) (S_N increasing)
        let p_exact_hi = poly(&exact, &hi);
        let rise = Rational::from(&p_exact_hi - &p_exact_lo);
        assert!(rise >= 0, "S_N decreasing, {what}");
        assert!(rise <= slack(b.width), "width {rise} > bound, {what}");
        ratios[2] = ratios[2].max(ratio(&rise, b.width));
        // tail: |S_∞ − S_N| at both ends (|tail| increases with |t|)
        let enclosure = b.enclosure();
        for (tf, p_exact) in [(t.lo, &p_exact_lo), (t.hi, &p_exact_hi)] {
            let full = full_series(ln, tf);
            let tail = Float::with_val(HI_PREC, &full - p_exact).abs();
            assert!(
                tail <= Float::with_val(HI_PREC, slack(b.tail)) + TOL,
                "tail {tail} > bound at t = {tf}, {what}"
            );
            if b.tail > 0.0 {
                ratios[3] = ratios[3].max((tail / b.tail).to_f64());
            }
            assert!(
                Float::with_val(HI_PREC, enclosure.lo) <= full
                    && full <= Float::with_val(HI_PREC, enclosure.hi),
                "S_∞({tf}) = {full} ∉ {enclosure:?}, {what}"
            );
        }
    }

    /// A xorshift generator of uniform numbers in [0, 1).
    fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Arguments of ln at the edges of its reduction: m next to √2 and 1/√2 (|s| largest),
    /// x next to 1 (s tiny), subnormals, the largest and smallest exponents, and random ones.
    fn ln_arguments() -> Vec<f64> {
        use std::f64::consts::SQRT_2;
        let mut v = vec![1.0, f64::MIN_POSITIVE, 5e-324, 1e-310, f64::MAX];
        for m in [
            SQRT_2,
            SQRT_2.next_down(),
            SQRT_2.next_up(),
            SQRT_2.next_up().next_up(),
            1.0 + f64::EPSILON,
            1.0 - f64::EPSILON / 2.0,
            1.0 + 1e-8,
            1.0 - 1e-8,
            1.5,
            1.999_999_999_999_999_8,
        ] {
            for e in [-1074, -1060, -1022, -1000, -30, -1, 0, 1, 30, 1000, 1023] {
                let x = m * 2f64.powi(e / 2) * 2f64.powi(e - e / 2);
                if x > 0.0 && x.is_finite() {
                    v.push(x);
                }
            }
        }
        let mut u = uniform(0x9E37_79B9_7F4A_7C15);
        for _ in 0..300 {
            v.push((u() * 2098.0 - 1074.0).exp2());
            // mantissas spread over the whole reduced range
            v.push((0.5 + u()) * SQRT_2 * (u() * 200.0 - 100.0).round().exp2());
        }
        v
    }

    /// Arguments of exp at the edges of its reduction: |r| next to ln2/2 (y = (k ± ½) ln 2) for
    /// small and the largest |k|, next to overflow (709.78) and the end of the subnormals
    /// (−745.13), tiny ones, and random ones.
    fn exp_arguments() -> Vec<f64> {
        let ln2 = std::f64::consts::LN_2;
        let mut v = vec![
            709.78,
            709.782_712_893_384,
            709.79,
            709.8,
            -708.4,
            -744.44,
            -745.0,
            -745.13,
            -745.2,
            1e-300,
            -1e-300,
            5e-324,
            0.346_5,
            -0.346_5,
        ];
        for k in [
            -1074.0, -1000.0, -500.0, -10.0, -1.0, 0.0, 1.0, 10.0, 500.0, 1023.0,
        ] {
            for h in [-0.5, 0.5] {
                let y: f64 = (k + h) * ln2;
                for y in [y.next_down(), y, y.next_up()] {
                    if (-745.2..=709.8).contains(&y) {
                        v.push(y);
                    }
                }
            }
        }
        let mut u = uniform(0xD1B5_4A32_D192_ED03);
        for _ in 0..300 {
            v.push(u() * 1454.0 - 745.0);
            v.push((u() - 0.5) * 2f64.powi(-(u() * 60.0) as i32));
        }
        v
    }

    /// Wide intervals [a, b] ⊆ [lo, hi] (the reduced argument of an interval input), including
    /// ones that end at the edges, where S_N′ is largest.
    fn wide_intervals(lo: f64, hi: f64, seed: u64) -> Vec<Ulp> {
        let mut v = vec![
            Ulp { lo, hi },
            Ulp { lo: hi * 0.9, hi },
            Ulp {
                lo: hi - (hi - lo) * 1e-6,
                hi,
            },
            Ulp { lo, hi: lo * 0.9 },
        ];
        let mut u = uniform(seed);
        for _ in 0..200 {
            let (a, b) = (lo + (hi - lo) * u(), lo + (hi - lo) * u());
            v.push(Ulp {
                lo: a.min(b),
                hi: a.max(b),
            });
        }
        v.retain(|t| t.lo <= t.hi);
        v
    }

    /// The largest z = s² of the ln reduction and |r| of the exp reduction.
    const Z_MAX: f64 = 0.029_437_251_522_859_43;
    const R_MAX: f64 = 0.346_573_590_279_972_7;

    fn check_ln_series<const N: usize>(args: &[f64], wide: &[Ulp]) -> Ratios {
        let mut ratios = [0.0; 4];
        for &x in args {
            let z = {
                let s = ln_reduction(x).1;
                s * s
            };
            check_budget(true, N, z, ln_series::<N>(z), &mut ratios);
        }
        for &z in wide {
            check_budget(true, N, z, ln_series::<N>(z), &mut ratios);
        }
        ratios
    }

    fn check_exp_series<const N: usize>(args: &[f64], wide: &[Ulp]) -> Ratios {
        let mut ratios = [0.0; 4];
        for &y in args {
            let r = exp_reduction(y).1;
            check_budget(false, N, r, exp_series::<N>(r), &mut ratios);
        }
        for &r in wide {
            check_budget(false, N, r, exp_series::<N>(r), &mut ratios);
        }
        ratios
    }

    #[test]
    fn each_error_term_of_the_series_bounds_its_exact_error() {
        let (xs, ys) = (ln_arguments(), exp_arguments());
        let wz = wide_intervals(0.0, Z_MAX, 1);
        let wr = wide_intervals(-R_MAX, R_MAX, 2);
        // the production counts, and small ones where the tail dominates
        let ln = [
            (LN_TERMS, check_ln_series::<LN_TERMS>(&xs, &wz)),
            (2, check_ln_series::<2>(&xs, &wz)),
            (3, check_ln_series::<3>(&xs, &wz)),
            (5, check_ln_series::<5>(&xs, &wz)),
        ];
        let exp = [
            (EXP_TERMS, check_exp_series::<EXP_TERMS>(&ys, &wr)),
            (2, check_exp_series::<2>(&ys, &wr)),
            (4, check_exp_series::<4>(&ys, &wr)),
            (6, check_exp_series::<6>(&ys, &wr)),
        ];
        // the inputs reach where the width and tail bounds of the production counts are nearly
        // tight (so a smaller constant in either would fail above), and the rounding bound is
        // not vacuous
        for (name, rows) in [("ln", ln), ("exp", exp)] {
            for (i, (n, [rounding, coefficients, width, tail])) in rows.into_iter().enumerate() {
                eprintln!(
                    "{name} N = {n}: exact/bound rounding {rounding:.3}, coefficients \
                     {coefficients:.2e}, width {width:.3}, tail {tail:.3}"
                );
                assert!(rounding > 0.5, "{name} N = {n}");
                if i == 0 {
                    assert!(width > 0.98, "{name} N = {n}");
                    assert!(
                        tail > if name == "ln" { 0.95 } else { 0.66 },
                        "{name} N = {n}"
                    );
                }
            }
        }
    }

    /// ln and exp with 2…6 terms, where the tail is far above an ulp, and with the production
    /// counts, against 256-bit MPFR at the edges of the reductions.
    #[test]
    fn small_term_counts_enclose_mpfr_values() {
        fn ln_n<const N: usize>(xs: &[f64]) {
            for &x in xs {
                let l = ln_point_n::<N>(x);
                let exact = Float::with_val(PREC, x).ln();
                assert!(
                    contains_exact(l, &exact),
                    "N = {N}: ln({x}) = {exact} ∉ {l:?}"
                );
            }
        }
        fn exp_n<const N: usize>(ys: &[f64]) {
            for &y in ys {
                let e = exp_point_n::<N>(y);
                let exact = Float::with_val(PREC, y).exp();
                assert!(
                    contains_exact(e, &exact),
                    "N = {N}: exp({y}) = {exact} ∉ {e:?}"
                );
            }
        }
        let (xs, ys) = (ln_arguments(), exp_arguments());
        ln_n::<2>(&xs);
        ln_n::<3>(&xs);
        ln_n::<4>(&xs);
        ln_n::<6>(&xs);
        ln_n::<LN_TERMS>(&xs);
        exp_n::<2>(&ys);
        exp_n::<3>(&ys);
        exp_n::<4>(&ys);
        exp_n::<6>(&ys);
        exp_n::<EXP_TERMS>(&ys);
    }

    /// The reductions' low part of ln 2 (e·lo, k·lo): at large |e| or |k| it moves the result
    /// by far more than the enclosure's width, and the enclosure holds the MPFR value.
    #[test]
    fn low_part_of_ln2_is_accounted_for() {
        let lo = ln2_lo();
        for x in [
            2f64.powi(1000),
            2f64.powi(-1000) * 1.3,
            5e-324,
            f64::MAX,
            3.0,
        ] {
            let l = ln(pt(x));
            let e = ln_reduction(x).0;
            assert!(contains_exact(l, &Float::with_val(PREC, x).ln()), "ln {x}");
            assert!(
                (lo.inf() * f64::from(e)).abs() > 4.0 * l.wid(),
                "ln {x}: e·lo too small"
            );
        }
        for y in [709.0, -700.0, -708.0, 600.5, 2.0] {
            let v = exp(pt(y));
            let k = exp_reduction(y).0;
            assert!(
                contains_exact(v, &Float::with_val(PREC, y).exp()),
                "exp {y}"
            );
            // e^(y − k·lo) against e^y: a relative change of k·lo
            assert!(
                (lo.inf() * k).abs() > 4.0 * v.wid() / v.mag(),
                "exp {y}: k·lo too small"
            );
        }
    }

    /// `around` contains [p − E, p + E + W] exactly for any E ≤ (1 + 2^−7)·e, W ≤ (1 + 2^−7)·w:
    /// both the outward steps (e far below an ulp of p) and the 1% inflation (e near p) matter.
    #[test]
    fn around_rounds_outwards_and_covers_the_bounds_rounding() {
        let slack = Rational::from((129, 128));
        let mut u = uniform(7);
        let mut cases = vec![
            (1.0, 2f64.powi(-60), 0.0),
            (1.0, 0.0, 2f64.powi(-60)),
            (1.0, 0.25, 0.0),
            (1.0, 0.0, 0.25),
            (0.75, 1e-3, 1e-3),
        ];
        for _ in 0..1000 {
            let p = 0.5 + u();
            let (e, w) = (
                (u() * -70.0).exp2(),
                (u() * -70.0).exp2() * (u() - 0.3).signum().max(0.0),
            );
            cases.push((p, e, w));
        }
        for (p, e, w) in cases {
            let a = around(p, e, w);
            let (pe, pw) = (q(e) * &slack, q(w) * &slack);
            let lo = q(p) - &pe;
            let hi = q(p) + &pe + pw;
            assert!(
                q(a.lo) <= lo && hi <= q(a.hi),
                "around({p}, {e}, {w}) = {a:?}"
            );
        }
    }

    /// ln and exp of thin and not-so-thin intervals (relative widths around the 10⁻³ switch of
    /// the shortcuts ln(b) ≤ ln(a) + (b − a)/a and e^b ≤ e^a/(1 − (b − a))): enclosures of the
    /// MPFR values at both ends, no looser than the shortcut's own error (u²/2, d²/2).
    #[test]
    fn thin_interval_shortcuts_enclose_and_stay_tight() {
        let mut u = uniform(11);
        let mut bases: Vec<f64> = vec![1.0, 1.0 - 1e-4, 1e-310, 3.5e300, 0.7];
        bases.extend((0..40).map(|_| (u() * 200.0 - 100.0).exp2()));
        let widths = [
            0.0, 1e-16, 1e-12, 1e-8, 1e-6, 1e-4, 5e-4, 9.9e-4, 9.999e-4, 1.0001e-3, 1.01e-3, 1e-2,
            0.1, 0.5, 2.0,
        ];
        let close = |got: f64, exact: &Float, slack: f64| {
            let d = Float::with_val(PREC, got) - exact;
            d.abs().to_f64() <= slack + 8.0 * f64::EPSILON * exact.to_f64().abs() + 1e-300
        };
        for &a in &bases {
            for &w in &widths {
                let b = a + a * w;
                if !b.is_finite() || b < a {
                    continue;
                }
                let l = ln(Interval::try_from((a, b)).unwrap());
                let (la, lb) = (Float::with_val(PREC, a).ln(), Float::with_val(PREC, b).ln());
                assert!(
                    contains_exact(l, &la) && contains_exact(l, &lb),
                    "ln [{a}, {b}]: {l:?}"
                );
                let uu = (b - a) / a;
                // the shortcut's error u − ln(1 + u) ≤ u²/2 only below the switch; above it, ulps
                let slack = if uu < 1e-3 { 0.51 * uu * uu } else { 0.0 };
                assert!(close(l.inf(), &la, 0.0), "ln [{a}, {b}] lo: {l:?}");
                assert!(close(l.sup(), &lb, slack), "ln [{a}, {b}] hi: {l:?}");
            }
        }
        let mut ys: Vec<f64> = vec![0.0, -700.0, 700.0, -744.0, 1e-5, -0.3];
        ys.extend((0..40).map(|_| u() * 1400.0 - 700.0));
        for &a in &ys {
            for &d in &widths {
                let b = a + d;
                if b > 709.0 {
                    continue;
                }
                let v = exp(Interval::try_from((a, b)).unwrap());
                let (ea, eb) = (
                    Float::with_val(PREC, a).exp(),
                    Float::with_val(PREC, b).exp(),
                );
                assert!(
                    contains_exact(v, &ea) && contains_exact(v, &eb),
                    "exp [{a}, {b}]: {v:?}"
                );
                let dd = b - a;
                assert!(close(v.inf(), &ea, 0.0), "exp [{a}, {b}] lo: {v:?}");
                let slack = if dd < 1e-3 {
                    0.51 * dd * dd * ea.to_f64()
                } else {
                    0.0
                };
                assert!(close(v.sup(), &eb, slack), "exp [{a}, {b}] hi: {v:?}");
            }
        }
    }

    /// ln 2 = LN2_HI + lo with LN2_HI's 21 low bits zero (k·LN2_HI exact for |k| ≤ 1075) and
    /// lo enclosed, not rounded: a point lo would move r by ≤ 1075·2^−87, far below what the
    /// enclosures above can see, so the enclosure of lo is checked here directly.
    #[test]
    fn ln2_is_split_exactly_and_its_low_part_enclosed() {
        assert_eq!(LN2_HI.to_bits() & ((1 << 21) - 1), 0);
        for k in [1074.0, 1075.0, -1075.0] {
            assert_eq!(q(k * LN2_HI), q(k) * q(LN2_HI), "k = {k}");
        }
        let lo = Float::with_val(HI_PREC, rug::float::Constant::Log2) - LN2_HI;
        let enclosure = ln2_lo();
        assert!(contains_exact(enclosure, &lo), "{lo} ∉ {enclosure:?}");
        assert_eq!(ln2_lo_ulp(), Ulp::of(enclosure));
        assert!(
            enclosure.inf() < enclosure.sup(),
            "lo is irrational: no thin enclosure"
        );
    }

    /// [`sub_as_inari`] and [`div_as_inari`] against inari's `−` and `/` on operands aimed at
    /// the thresholds (quotients near 2^−1074, 2^−1022, 2^−969 and MAX, dividends near 2^−969,
    /// subnormal divisors, sums near overflow).
    #[test]
    fn quotients_as_inari_on_threshold_operands() {
        use super::super::ulp::adversarial as ulp_adv;
        let mut g = ulp_adv::Gen::new(0x510e_527f_ade6_82d1);
        let mut fast = 0u64;
        for _ in 0..ulp_adv::iters(3_000_000) {
            let (a, c) = g.pair(true);
            let (b, d) = if g.next().is_multiple_of(3) {
                (a, c)
            } else {
                g.pair(true)
            };
            // one sign more often than not
            let (b, d) = if !g.next().is_multiple_of(4) {
                (b.abs().copysign(a), d.abs().copysign(c))
            } else {
                (b, d)
            };
            let (Ok(x), Ok(y)) = (
                Interval::try_from((a.min(b), a.max(b))),
                Interval::try_from((c.min(d), c.max(d))),
            ) else {
                continue;
            };
            let s = sub_as_inari(x, y);
            let e = x - y;
            assert!(
                s.inf() == e.inf() && s.sup() == e.sup(),
                "{x:?} − {y:?}: {s:?} vs {e:?}"
            );
            let s = sub_as_inari(x, x);
            let e = x - x;
            assert!(s.inf() == e.inf() && s.sup() == e.sup(), "{x:?} − itself");
            let r = div_as_inari(x, y);
            let e = x / y;
            assert!(
                r.is_empty() == e.is_empty()
                    && (r.is_empty() || (r.inf() == e.inf() && r.sup() == e.sup())),
                "{x:?} / {y:?}: {r:?} vs {e:?} ({:e} {:e} / {:e} {:e})",
                x.inf(),
                x.sup(),
                y.inf(),
                y.sup()
            );
            let u = Ulp::of(x) / Ulp::of(y);
            if u.interval() == e && (y.inf() > 0.0 || y.sup() < 0.0) {
                fast += 1;
            }
        }
        assert!(fast > ulp_adv::iters(3_000_000) / 6, "{fast}");
    }
}
