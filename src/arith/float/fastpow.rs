//! x^q for x > 0 on the f64 engine, by tables per exponent q.
//!
//! Every power in the models is |w|^q for a state component w and a fixed parameter q (n − 1,
//! p − 1, …), and the f64 DOP853 engine spends most of a CoR waiting for them: each stage's
//! argument depends on the previous stage's powers, so what counts is the latency of one
//! power. exp(q·ln x) chains two library calls (≈ 40 ns per SHC right-hand side on this
//! project's machine in a dependent-chain microbenchmark); with tables built once per q the
//! chain is a few integer operations, three loads and a degree-5 polynomial (9 floating-point
//! operations in all; a version with 8 more multiplications per power, meant to shorten the
//! chain, was 12% slower per CoR).
//!
//! With x = 2^k·m, m ∈ [√½, √2), the subinterval i of m (the top [`LOG_BITS`] bits of its
//! mantissa offset), a short reciprocal cᵢ⁻¹ of its centre and r = m·cᵢ⁻¹ − 1 (one FMA,
//! |r| < 0.001):
//!
//! ```text
//! x^q = 2^(kq) · (cᵢ⁻¹)^(−q) · (1 + r)^q,      (1 + r)^q = Σ_{j ≤ 5} C(q, j) r^j + O(r⁶)
//! ```
//!
//! E_k = 2^(kq) and P_i = (cᵢ⁻¹)^(−q) are tabulated by the library `powf` (each within an
//! ulp), the binomial series by Estrin's scheme; the truncation, |C(q, 6)|·r⁶ ≤ 28·10⁻¹⁸, is
//! below 0.3·2⁻⁵³ for q ∈ [[`Q_MIN`], [`Q_MAX`]]. Relative error: at most 12·2⁻⁵³ (tested against MPFR over
//! every subinterval; the two table entries, the two products, r and the series each round),
//! against (|q ln x| + 2)·2⁻⁵³ for exp(q·ln x). Outside the tabulated range (x ∉
//! [2^−64.5, 2^63.5): 0, subnormals, ∞, NaN; or q outside the range) the value is the
//! library `powf`.
//!
//! The tables are built on an exponent's first use (≈ 1150 calls of `powf`, ≈ 9 µs on this
//! project's machine) and kept in a registry; a model holds a [`Power`] per exponent (made
//! when the model is built, through [`super::Exponent`]), so the right-hand side reads its
//! tables with no lookup by q. A table is a pure function of q: a value never depends on
//! what else the process computed. Only the f64 engine uses this: interval powers are
//! enclosures ([`crate::arith::interval::elementary`]).

use std::collections::HashMap;
use std::sync::{Arc, LazyLock, Mutex};

/// Bits of m's mantissa that index the subinterval table.
pub const LOG_BITS: u32 = 9;
const NSUB: usize = 1 << LOG_BITS;
/// Bits of √½: x = 2^k·m with m ∈ [√½, √2) is read off x's bits minus this.
const OFF: u64 = 0x3fe6_a09e_667f_3bcd;
/// The smallest tabulated binary exponent k, and how many there are.
const K_MIN: i64 = -64;
const NK: usize = 128;
/// Exponents q with tables; others take the library `powf`.
pub const Q_MIN: f64 = -1.0;
pub const Q_MAX: f64 = 8.0;

/// The tables of one exponent q.
pub struct PowTable {
    q: f64,
    /// How many binary exponents k are tabulated: [`NK`], or 0 for q outside
    /// [[`Q_MIN`], [`Q_MAX`]] (every x then takes the library `powf`).
    nk: u64,
    /// cᵢ⁻¹, rounded to 24 bits.
    invc: [f64; NSUB],
    /// (cᵢ⁻¹)^(−q).
    pc: [f64; NSUB],
    /// 2^(kq) for k = K_MIN + j.
    ek: [f64; NK],
    /// C(q, j), j = 0 … 5.
    binom: [f64; 6],
}

impl PowTable {
    /// Builds the tables (≈ 1150 calls of `powf`; none for q outside [[`Q_MIN`], [`Q_MAX`]]).
    pub fn new(q: f64) -> Self {
        let mut t = PowTable {
            q,
            nk: NK as u64,
            invc: [0.0; NSUB],
            pc: [0.0; NSUB],
            ek: [0.0; NK],
            binom: [0.0; 6],
        };
        if !(Q_MIN..=Q_MAX).contains(&q) {
            t.nk = 0;
            return t;
        }
        let sub = 52 - LOG_BITS;
        for i in 0..NSUB {
            let lo = f64::from_bits(OFF + ((i as u64) << sub));
            let hi = f64::from_bits(OFF + ((i as u64 + 1) << sub));
            let ic = (2.0 / (lo + hi)) as f32 as f64;
            t.invc[i] = ic;
            t.pc[i] = ic.powf(-q);
        }
        for (j, e) in t.ek.iter_mut().enumerate() {
            *e = 2f64.powi((j as i64 + K_MIN) as i32).powf(q);
        }
        let mut c = 1.0;
        for (j, b) in t.binom.iter_mut().enumerate() {
            *b = c;
            c *= (q - j as f64) / (j as f64 + 1.0);
        }
        t
    }

    /// x^q for x > 0 (the library `powf` outside the tables, see the module doc).
    #[inline(always)]
    pub fn pow(&self, x: f64) -> f64 {
        self.pow_and_mul(x, 1.0).0
    }

    /// (x^q, x^q·y) for x > 0. The product is formed as (2^(kq)·cᵢ^q·y)·Σ, whose first factor
    /// is ready before the series: one multiplication less after it than (x^q)·y (the
    /// right-hand side waits for this product: |x|^(q−1)·x).
    #[inline(always)]
    pub fn pow_and_mul(&self, x: f64, y: f64) -> (f64, f64) {
        let ix = x.to_bits();
        let tmp = ix.wrapping_sub(OFF);
        let i = ((tmp >> (52 - LOG_BITS)) as usize) & (NSUB - 1);
        let kk = ((tmp as i64) >> 52).wrapping_sub(K_MIN) as u64;
        // one test for everything outside the tables: x < 2^−64.5 (0 and subnormals
        // included), x ≥ 2^63.5 (∞ and NaN included), and a set sign bit (k then lands far
        // outside [K_MIN, K_MIN + NK), and the unsigned comparison rejects either side); every
        // x when q has no tables (nk = 0)
        if kk >= self.nk {
            let p = slow(x, self.q);
            return (p, p * y);
        }
        let m = f64::from_bits(ix.wrapping_sub(tmp & (0xfff << 52)));
        let r = m.mul_add(self.invc[i], -1.0);
        let e = self.ek[kk as usize & (NK - 1)] * self.pc[i];
        let b = &self.binom;
        let r2 = r * r;
        // Estrin's scheme, b[0] = 1: (1 + b₁r) + r²((b₂ + b₃r) + r²(b₄ + b₅r))
        let p01 = b[1].mul_add(r, 1.0);
        let p23 = b[3].mul_add(r, b[2]);
        let p45 = b[5].mul_add(r, b[4]);
        let s = p45.mul_add(r2, p23).mul_add(r2, p01);
        (e * s, (e * y) * s)
    }
}

/// Outside the tables: the library `powf` (with its special cases: 0^q, ∞^0, 1^NaN, …).
#[inline(never)]
fn slow(x: f64, q: f64) -> f64 {
    x.powf(q)
}

/// x ↦ x^q for one exponent q: a shared handle on q's tables. Made once per exponent of a
/// model (at its construction, [`super::Exponent`]) so that the right-hand side reads the
/// tables directly: no lookup by q on the hot path.
#[derive(Clone)]
pub struct Power(Arc<PowTable>);

impl Power {
    /// q's tables, from the process's registry (built on q's first use, ≈ 9 µs). For q outside
    /// [[`Q_MIN`], [`Q_MAX`]] nothing is tabulated and every value is the library `powf`.
    pub fn new(q: f64) -> Self {
        let key = q.to_bits();
        let mut reg = REGISTRY.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = reg.get(&key) {
            return Power(t.clone());
        }
        if reg.len() >= REGISTRY_CAP {
            // a fit that keeps varying n and p: start over (handles already given out keep
            // their tables alive, and a table is a pure function of q, so no value changes)
            reg.clear();
        }
        let t = Arc::new(PowTable::new(q));
        reg.insert(key, t.clone());
        Power(t)
    }

    /// x^q for x ≥ 0 (see the module doc for the method and its accuracy).
    #[inline(always)]
    pub fn pow(&self, x: f64) -> f64 {
        self.0.pow(x)
    }

    /// (x^q, x^q·y) for x ≥ 0, the product with one rounding more than x^q
    /// ([`PowTable::pow_and_mul`]).
    #[inline(always)]
    pub fn pow_and_mul(&self, x: f64, y: f64) -> (f64, f64) {
        self.0.pow_and_mul(x, y)
    }
}

impl std::fmt::Debug for Power {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Power({})", self.0.q)
    }
}

/// At most this many exponents are kept in the registry (≈ 9 KiB each).
const REGISTRY_CAP: usize = 1024;

/// The tables of the exponents in use, by the bits of q.
static REGISTRY: LazyLock<Mutex<HashMap<u64, Arc<PowTable>>>> =
    LazyLock::new(|| Mutex::new(HashMap::new()));

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Float;
    use rug::ops::Pow;

    /// x^q through q's registry handle.
    fn pow(x: f64, q: f64) -> f64 {
        Power::new(q).pow(x)
    }

    /// |a − b| / |b| in units of 2⁻⁵³ (half an ulp), b the MPFR value of x^q.
    fn ulps(x: f64, q: f64, a: f64) -> f64 {
        let b = Float::with_val(200, x).pow(Float::with_val(200, q));
        let d = (Float::with_val(200, a) - &b).abs() / b.abs();
        d.to_f64() / f64::EPSILON * 2.0
    }

    #[test]
    fn tables_are_within_6_ulps_of_mpfr_and_fall_back_outside() {
        let mut worst: f64 = 0.0;
        // a deterministic scan: every subinterval, exponents inside and outside the tables
        for q in [
            0.0, 0.27, 0.31, 0.94, 1.27, 2.14, 3.15, 4.14, -0.5, -1.0, 7.9,
        ] {
            let t = PowTable::new(q);
            let mut x = 2f64.powi(-70);
            while x < 2f64.powi(70) {
                let a = t.pow(x);
                let u = ulps(x, q, a);
                // inside the tables: 12·2⁻⁵³; outside: the library powf (< 1 ulp; the
                // bound is exp(q ln x)'s (|q ln x| + 2)·2⁻⁵³, which any sane pow meets)
                let tabulated = (2f64.powf(-64.5)..2f64.powf(63.5)).contains(&x);
                let bound = if tabulated {
                    12.0
                } else {
                    2.0 * ((q * x.ln()).abs() + 2.0)
                };
                assert!(u <= bound, "x = {x:e}, q = {q}: {a:e} is {u}·2⁻⁵³ off");
                if tabulated {
                    worst = worst.max(u);
                }
                x *= 1.003_7;
            }
        }
        assert!(worst > 0.0 && worst <= 12.0, "worst {worst}");
    }

    #[test]
    fn edge_values() {
        assert_eq!(pow(0.0, 0.31), 0.0);
        assert_eq!(pow(0.0, 0.0), 1.0);
        assert!((pow(1.0, 0.31) - 1.0).abs() <= 2.0 * f64::EPSILON);
        assert_eq!(pow(f64::INFINITY, 0.31), f64::INFINITY);
        assert!(pow(f64::NAN, 0.31).is_nan());
        // the library's special cases outside the tables
        assert_eq!(pow(f64::INFINITY, 0.0), 1.0);
        assert_eq!(pow(1.0, f64::NAN), 1.0);
        assert!((pow(4.0, 0.5) - 2.0).abs() <= 4.0 * f64::EPSILON);
        // subnormal, and q outside the tables
        let s = 1e-310;
        assert!(ulps(s, 0.31, pow(s, 0.31)) < 2.0 * (0.31 * 714.0 + 2.0));
        assert!(ulps(3.0, 20.5, pow(3.0, 20.5)) < 2.0 * (20.5 * 1.1 + 2.0));
        // every subinterval keeps |r| < 0.001 (the truncation bound of the module doc)
        let t = PowTable::new(0.31);
        let sub = 52 - LOG_BITS;
        for i in 0..NSUB {
            for j in [0u64, 1, 1 << (sub - 1), (1 << sub) - 1] {
                let m = f64::from_bits(OFF + ((i as u64) << sub) + j);
                assert!((m * t.invc[i] - 1.0).abs() < 0.001, "i = {i}");
            }
        }
    }

    #[test]
    /// More exponents than the registry holds, each used again: the same value as the
    /// exponent's own fresh tables every time (a value never depends on the registry's
    /// state), and accurate; a handle made before the registry starts over keeps working.
    fn powers_are_reproducible_with_more_exponents_than_the_registry_holds() {
        let n = REGISTRY_CAP + 5;
        let early = Power::new(1.234_5);
        for round in 0..3 {
            for j in 0..n {
                let q = -0.9 + j as f64 * (8.8 / n as f64);
                let x = 1.7 + round as f64;
                let a = Power::new(q).pow(x);
                assert_eq!(
                    a.to_bits(),
                    PowTable::new(q).pow(x).to_bits(),
                    "x = {x}, q = {q}"
                );
                assert!(ulps(x, q, a) <= 12.0, "x = {x}, q = {q}");
            }
        }
        assert_eq!(
            early.pow(3.0).to_bits(),
            PowTable::new(1.234_5).pow(3.0).to_bits()
        );
        // two handles on one exponent share its tables
        let (a, b) = (Power::new(0.77), Power::new(0.77));
        assert!(Arc::ptr_eq(&a.0, &b.0) && a.0.q == 0.77);
        // outside [Q_MIN, Q_MAX]: no tables, exactly the library powf
        for (x, q) in [(3.0, 20.5), (0.4, -2.5), (7.0, 8.5)] {
            assert_eq!(Power::new(q).pow(x).to_bits(), x.powf(q).to_bits());
        }
    }
}
