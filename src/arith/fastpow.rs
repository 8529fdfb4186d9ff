//! x^q for x > 0 on the f64 engine, by tables per exponent q.
//!
//! Every power in the models is |w|^q for a state component w and a fixed parameter q (n − 1,
//! p − 1, …), and the f64 DOP853 engine spends most of a CoR waiting for them: each stage's
//! argument depends on the previous stage's powers, so what counts is the latency of one
//! power. exp(q·ln x) chains two library calls (≈ 40 ns per SHC right-hand side on this
//! project's machine in a dependent-chain microbenchmark, ≈ 30 ns with these tables); with
//! tables built once per q the chain is a few integer operations, three loads and a degree-7
//! polynomial.
//!
//! With x = 2^k·m, m ∈ [√½, √2), the subinterval i of m (the top [`LOG_BITS`] bits of its
//! mantissa offset), a short reciprocal cᵢ⁻¹ of its centre and r = m·cᵢ⁻¹ − 1 (one FMA,
//! |r| < 0.004):
//!
//! ```text
//! x^q = 2^(kq) · (cᵢ⁻¹)^(−q) · (1 + r)^q,      (1 + r)^q = Σ_{j ≤ 7} C(q, j) r^j + O(r⁸)
//! ```
//!
//! E_k = 2^(kq) and P_i = (cᵢ⁻¹)^(−q) are tabulated by the library `powf` (each within an
//! ulp), the binomial series by Estrin's scheme; the truncation is below 2⁻⁶⁰ for
//! q ∈ [[`Q_MIN`], [`Q_MAX`]]. Relative error: at most 12·2⁻⁵³ (tested against MPFR over
//! every subinterval; the two table entries, the two products, r and the series each round),
//! against (|q ln x| + 2)·2⁻⁵³ for exp(q·ln x). Outside the tabulated range (x ∉
//! [2^−64.5, 2^63.5): 0, subnormals, ∞, NaN; or q outside the range) the value is the
//! library `powf`.
//!
//! The tables are built on an exponent's first use (≈ 6 µs) and kept (a global set of
//! `SLOTS` places, then a per-thread cache). Only the f64 engine uses this: interval powers
//! are enclosures ([`super::elementary`]).

use std::cell::Cell;
use std::sync::atomic::{AtomicPtr, Ordering};

/// Bits of m's mantissa that index the subinterval table.
pub const LOG_BITS: u32 = 7;
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
    /// cᵢ⁻¹, rounded to 24 bits.
    invc: [f64; NSUB],
    /// (cᵢ⁻¹)^(−q).
    pc: [f64; NSUB],
    /// 2^(kq) for k = K_MIN + j.
    ek: [f64; NK],
    /// C(q, j), j = 0 … 7.
    binom: [f64; 8],
}

impl PowTable {
    /// Builds the tables (≈ 260 calls of `powf`).
    pub fn new(q: f64) -> Self {
        let mut t = PowTable {
            q,
            invc: [0.0; NSUB],
            pc: [0.0; NSUB],
            ek: [0.0; NK],
            binom: [0.0; 8],
        };
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
        let ix = x.to_bits();
        let tmp = ix.wrapping_sub(OFF);
        let i = ((tmp >> (52 - LOG_BITS)) as usize) & (NSUB - 1);
        let kk = ((tmp as i64) >> 52).wrapping_sub(K_MIN) as u64;
        // one test for everything outside the tables: x < 2^−64.5 (0 and subnormals
        // included), x ≥ 2^63.5 (∞ and NaN included), and a set sign bit (k then lands far
        // outside [K_MIN, K_MIN + NK), and the unsigned comparison rejects either side)
        if kk >= NK as u64 {
            return slow(x, self.q);
        }
        let m = f64::from_bits(ix.wrapping_sub(tmp & (0xfff << 52)));
        let r = m.mul_add(self.invc[i], -1.0);
        let b = &self.binom;
        let r2 = r * r;
        let r4 = r2 * r2;
        let p01 = b[1].mul_add(r, b[0]);
        let p23 = b[3].mul_add(r, b[2]);
        let p45 = b[5].mul_add(r, b[4]);
        let p67 = b[7].mul_add(r, b[6]);
        let p03 = p23.mul_add(r2, p01);
        let p47 = p67.mul_add(r2, p45);
        let s = p47.mul_add(r4, p03);
        (self.ek[kk as usize] * self.pc[i]) * s
    }
}

/// Outside the tables: the library `powf` (with its special cases: 0^q, ∞^0, 1^NaN, …).
#[inline(never)]
fn slow(x: f64, q: f64) -> f64 {
    x.powf(q)
}

/// The process-wide tables: a direct-mapped set of [`SLOTS`] places, each exponent probed at
/// two. A table, once installed, is never replaced or freed (at most [`SLOTS`] of ≈ 3 KiB),
/// so the hot path is two loads and a compare. An exponent whose two places are taken goes
/// to its thread's [`Cache`]. Either way every q in [[`Q_MIN`], [`Q_MAX`]] is evaluated by its
/// own tables, so a result never depends on what else the process computed.
const SLOTS: usize = 1024;
static TABLES: [AtomicPtr<PowTable>; SLOTS] =
    [const { AtomicPtr::new(std::ptr::null_mut()) }; SLOTS];

/// The two places of an exponent (Fibonacci hashing of its bits).
#[inline(always)]
fn places(key: u64) -> [usize; 2] {
    let h = (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - SLOTS.trailing_zeros())) as usize;
    [h, h ^ 1]
}

/// x^q for x ≥ 0 (see the module doc for the method and its accuracy). Inlined: the first
/// place is tried here, everything else (`pow_elsewhere`) out of line.
#[inline(always)]
pub fn pow(x: f64, q: f64) -> f64 {
    let key = q.to_bits();
    let ps = places(key);
    // SAFETY: a non-null pointer in TABLES came from `Box::into_raw` and is never freed.
    if let Some(t) = unsafe { TABLES[ps[0]].load(Ordering::Acquire).as_ref() }
        && t.q.to_bits() == key
    {
        return t.pow(x);
    }
    pow_elsewhere(x, q, ps)
}

/// [`pow`] when q's tables are not at its first place: at the second, installed now, or in
/// this thread's cache; the library `powf` for q outside the tabulated range.
#[inline(never)]
fn pow_elsewhere(x: f64, q: f64, ps: [usize; 2]) -> f64 {
    if !(Q_MIN..=Q_MAX).contains(&q) {
        return slow(x, q);
    }
    let key = q.to_bits();
    // SAFETY: as in `pow`.
    if let Some(t) = unsafe { TABLES[ps[1]].load(Ordering::Acquire).as_ref() }
        && t.q.to_bits() == key
    {
        return t.pow(x);
    }
    if let Some(t) = install(q, ps) {
        return t.pow(x);
    }
    // during this thread's teardown (the cache already destroyed) the tables are built for
    // this one call: the same value, only slower
    CACHE
        .try_with(|c| c.pow(x, q))
        .unwrap_or_else(|_| PowTable::new(q).pow(x))
}

/// Builds q's tables into the first free place of the two, if there is one.
#[cold]
fn install(q: f64, ps: [usize; 2]) -> Option<&'static PowTable> {
    let free = ps
        .into_iter()
        .find(|&p| TABLES[p].load(Ordering::Acquire).is_null())?;
    let new = Box::into_raw(Box::new(PowTable::new(q)));
    if TABLES[free]
        .compare_exchange(
            std::ptr::null_mut(),
            new,
            Ordering::AcqRel,
            Ordering::Acquire,
        )
        .is_ok()
    {
        // SAFETY: just installed, never freed.
        return Some(unsafe { &*new });
    }
    // another thread took the place first: `new` is ours alone
    // SAFETY: not installed anywhere.
    drop(unsafe { Box::from_raw(new) });
    None
}

/// Tables per thread for exponents without a global place (a fit that keeps varying n and p
/// fills the global set with its first exponents).
const WAYS: usize = 16;

/// The key of an empty way: a NaN's bits, never a tabulated exponent's.
const EMPTY: u64 = u64::MAX;

/// A thread's tables, fully associative, replaced round-robin.
struct Cache {
    keys: [Cell<u64>; WAYS],
    tables: [Cell<*mut PowTable>; WAYS],
    next: Cell<usize>,
}

impl Cache {
    /// x^q by q's tables, built in place of the oldest on a miss (no reference to a table
    /// leaves this function, so a later eviction cannot leave one dangling).
    fn pow(&self, x: f64, q: f64) -> f64 {
        let key = q.to_bits();
        let j = match (0..WAYS).find(|&j| self.keys[j].get() == key && key != EMPTY) {
            Some(j) => j,
            None => {
                let j = self.next.get();
                self.next.set((j + 1) % WAYS);
                let old = self.tables[j].replace(Box::into_raw(Box::new(PowTable::new(q))));
                self.keys[j].set(key);
                if !old.is_null() {
                    // SAFETY: from `Box::into_raw`, owned by this cache alone, its key gone;
                    // no reference to it exists outside this function.
                    drop(unsafe { Box::from_raw(old) });
                }
                j
            }
        };
        // SAFETY: non-null (set with its key), alive until replaced by a later call, and
        // `PowTable::pow` does not call back into the cache.
        unsafe { &*self.tables[j].get() }.pow(x)
    }
}

impl Drop for Cache {
    fn drop(&mut self) {
        for t in &self.tables {
            let p = t.get();
            if !p.is_null() {
                // SAFETY: from `Box::into_raw`, owned by this cache alone.
                drop(unsafe { Box::from_raw(p) });
            }
        }
    }
}

thread_local! {
    static CACHE: Cache = const {
        Cache {
            keys: [const { Cell::new(EMPTY) }; WAYS],
            tables: [const { Cell::new(std::ptr::null_mut()) }; WAYS],
            next: Cell::new(0),
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Float;
    use rug::ops::Pow;

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
        // every subinterval centre keeps |r| < 0.004 (the truncation bound of the module doc)
        let t = PowTable::new(0.31);
        for i in 0..NSUB {
            for j in [0u64, 1, 1 << 44, (1 << 45) - 1] {
                let m = f64::from_bits(OFF + ((i as u64) << 45) + j);
                assert!((m * t.invc[i] - 1.0).abs() < 0.004, "i = {i}");
            }
        }
    }

    #[test]
    /// `pow` with more exponents than the global set and a thread's cache hold, each used
    /// again: the same value as the exponent's own tables every time (a result never depends
    /// on the caches' state), and accurate.
    fn pow_is_reproducible_with_more_exponents_than_the_cache_holds() {
        for round in 0..3 {
            for j in 0..(SLOTS + WAYS + 5) {
                let q = -0.9 + j as f64 * (8.8 / (SLOTS + WAYS + 5) as f64);
                let x = 1.7 + round as f64;
                let a = pow(x, q);
                assert_eq!(
                    a.to_bits(),
                    PowTable::new(q).pow(x).to_bits(),
                    "x = {x}, q = {q}"
                );
                assert!(ulps(x, q, a) <= 12.0, "x = {x}, q = {q}");
            }
        }
    }
}
