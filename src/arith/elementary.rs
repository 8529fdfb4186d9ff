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

/// [p − e, p + e + w] rounded outwards: e, w ≥ 0 are bounds computed in round-to-nearest,
/// so both are first inflated by 1% (far more than their rounding errors).
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

/// An enclosure of ln x for a finite x > 0 (the series in [`Ulp`] arithmetic: no rounding-mode
/// switches inside the loop).
fn ln_point(x: f64) -> Interval {
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
    let s = Ulp::point(m - 1.0) / (Ulp::point(m) + Ulp::point(1.0));
    let z = s * s;
    // Q(z) = Σ_{i<n} z^i/(2i+1), increasing in z ∈ [0, 0.0295]: Horner at z.lo with its running
    // error bound, the coefficients' rounding (≤ u·Q ≤ 1.04u), Q′ ≤ 0.35 times the width of z,
    // and the tail Σ_{i≥n} z^i/(2i+1) ≤ z^n/((2n+1)(1 − z))
    let odd = &coefficients().0;
    let (q, beta) = horner_running(odd, z.lo);
    let zh = z.hi;
    let tail = zh.powi(LN_TERMS as i32) / ((2 * LN_TERMS + 1) as f64 * (1.0 - zh));
    let series = around(
        q,
        U_SAFE * beta + 1.04 * U_SAFE + tail,
        0.35 * (z.hi - z.lo),
    );
    // small parts first: e·lo + 2s·Σ, then the exact e·LN2_HI
    let ef = Ulp::point(e as f64);
    ((ef * ln2_lo_ulp() + Ulp::point(2.0) * s * series) + Ulp::point(e as f64 * LN2_HI)).interval()
}

/// An enclosure of e^y for a finite y (the series in [`Ulp`] arithmetic).
fn exp_point(y: f64) -> Interval {
    if y == 0.0 {
        return ONE; // exact (so that 1^q, |−1|^q stay exact)
    }
    if y > 709.8 {
        return Interval::try_from((f64::MAX, f64::INFINITY)).unwrap();
    }
    if y < -745.2 {
        return Interval::try_from((0.0, f64::MIN_POSITIVE)).unwrap();
    }
    let k = (y / std::f64::consts::LN_2).round();
    // y − k·LN2_HI is exact (Sterbenz, k·LN2_HI exact); then the small part
    let r = Ulp::point(y - k * LN2_HI) - Ulp::point(k) * ln2_lo_ulp();
    // P(r) = Σ_{i<n} r^i/i!, increasing in r: Horner at r.lo with its running error bound,
    // the coefficients' rounding (≤ u·e^|r| ≤ 1.42u), P′ ≤ e^0.35 < 1.42 times the width of
    // r, and the tail ≤ 1.5 |r|^n/n!
    let inv_fact = &coefficients().1;
    let (p, beta) = horner_running(inv_fact, r.lo);
    let tail = 1.5 * r.mag().powi(EXP_TERMS as i32) * inv_fact[EXP_TERMS - 1] / EXP_TERMS as f64;
    let v = around(
        p,
        U_SAFE * beta + 1.42 * U_SAFE + tail,
        1.42 * (r.hi - r.lo),
    );
    // multiply by 2^k (split to stay in range; outward steps cover underflow)
    let k = k as i32;
    let (k1, k2) = (k / 2, k - k / 2);
    (v * Ulp::point(2f64.powi(k1)) * Ulp::point(2f64.powi(k2))).interval()
}

/// An enclosure of ln X for X ⊆ (0, ∞) (ENTIRE if X reaches 0 or below, or is unbounded).
pub fn ln(x: Interval) -> Interval {
    if x.is_empty() || x.inf() <= 0.0 || !x.sup().is_finite() {
        return Interval::ENTIRE;
    }
    let lo = ln_point(x.inf());
    // a thin X: ln(x.sup) = ln(x.inf) + ln(1 + u) ≤ ln(x.inf) + u, u = (x.sup − x.inf)/x.inf
    let u = (pt(x.sup()) - pt(x.inf())) / pt(x.inf());
    let hi = if u.sup() < 1e-3 {
        (lo + u).sup()
    } else {
        ln_point(x.sup()).sup()
    };
    Interval::try_from((lo.inf(), hi)).unwrap()
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
    let d = pt(y.sup()) - pt(y.inf());
    let hi = if d.sup() < 1e-3 {
        (lo / (ONE - d)).sup()
    } else {
        exp_point(y.sup()).sup()
    };
    Interval::try_from((lo.inf().max(0.0), hi)).unwrap()
}

/// An enclosure of x^q over X ⊆ [0, ∞), Q ⊆ (0, ∞); `None` where this fast path does not
/// apply (0 or negative bases with q reaching 0, unbounded arguments).
pub fn pow(x: Interval, q: Interval) -> Option<Interval> {
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
        let hi = exp(q * ln(pt(x.sup()))).sup();
        return Some(Interval::try_from((0.0, hi)).unwrap());
    }
    Some(exp(q * ln(x)))
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
            let qlx = (d * a.max(f64::MIN_POSITIVE).ln().abs()).max(d * b.ln().abs());
            let slack = (qlx + 8.0) * 4.0 * f64::EPSILON * tight.mag();
            assert!(
                p.inf() >= tight.inf() - slack && p.sup() <= tight.sup() + slack,
                "{p:?} vs {tight:?}"
            );
        }
        assert!(pow(pt(-1.0), pt(2.0)).is_none());
    }
}
