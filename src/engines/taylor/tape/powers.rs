//! The real powers |w|^(q−1)w and |w|^q: which are entire, and the recurrences of the others
//! (through the operand's log where it is thin) with their per-node storage.

use crate::arith::Real;
use crate::arith::jet::series::{exp_log_k, log_k, pow_factors, pow_k};

/// True when the power is an entire function: |w|^(q−1)w with odd integer q ≥ 1, |w|^q with
/// even integer q ≥ 0.
pub fn analytic_power<R: Real>(q: &R, signed: bool) -> bool {
    match q.as_integer() {
        Some(k) if k >= 0 => (k % 2 == 1) == signed,
        _ => false,
    }
}

/// Coefficient k of |w|^(q−1)w or |w|^q for w = node `a` in the sign region s: ũ = (s w)^q,
/// ũ_0 = |w_0|^q; the node is s·ũ (signed) or ũ (absolute). For k ≥ 1:
/// - the operand's constant coefficient thin (relative width ≤ 10⁻⁶, every jet of a point or
///   of a proved step's box): node `lead` (the first power of w) runs [`log_k`] for
///   L = ln|w| (its k·L_k in `scratch.dw`), then each power ũ = exp(qL) runs [`exp_log_k`];
/// - over wider boxes (a range of v0) the power recurrence [`pow_k`] on w itself (it is linear
///   and homogeneous in w, so the sign s cancels), which encloses tighter there.
///
/// ũ itself is kept in `scratch.u` (for the recurrences and for a [`Op::Twin`](super::Op::Twin)).
#[allow(clippy::too_many_arguments)]
#[inline]
pub(super) fn pow_node<R: Real>(
    c: &[R],
    scratch: &mut PowScratch<R>,
    s: i8,
    a: usize,
    i: usize,
    lead: usize,
    k: usize,
    k1: usize,
    q: &R,
    signed: bool,
) -> R {
    let (w, at, lt) = (&c[a * k1..a * k1 + k + 1], i * k1, lead * k1);
    if k == 0 && lead == i {
        scratch.log_on[i] = w[0].hi() - w[0].lo() <= 1e-6 * w[0].lo().abs().min(w[0].hi().abs());
    }
    if k == 0 && !scratch.log_on[lead] {
        scratch.factors(i, q, k1 - 1);
    }
    let u = if k == 0 {
        branch_power(&w[0], s, q)
    } else if scratch.log_on[lead] {
        if i == lead {
            scratch.dw[lt + k] = log_k(w, &scratch.dw[lt..lt + k], k);
        }
        exp_log_k(&scratch.dw[lt..lt + k + 1], &scratch.u[at..at + k], q, k)
    } else {
        let row = k * (k - 1) / 2;
        pow_k(
            w,
            &scratch.u[at..at + k],
            &scratch.fac[i].1[row..row + k],
            k,
        )
    };
    scratch.u[at + k] = u.clone();
    if signed && s < 0 { -u } else { u }
}

/// ũ₀ = (s·w₀)^q: the order-0 value of a power of w₀ in the sign region s.
pub(super) fn branch_power<R: Real>(w0: &R, s: i8, q: &R) -> R {
    let w0 = if s > 0 { w0.clone() } else { -w0.clone() };
    Real::apow(&w0, q)
}

/// Per-node storage of the power recurrences: ũ_k, k·L_k (at the log's lead node), whether
/// the log runs in this jet (decided by the lead at order 0), and the factors q(k − j) − j of
/// [`pow_k`] (rows k = 1..K, row k at k(k − 1)/2), kept with the exponent they were computed
/// for. A workspace outlives a jet (the engine's serves every step of a tape, whose powers
/// with a parameter as exponent take that parameter's value; a caller may run another tape
/// in it), so a table is reused only for the same exponent, compared exactly
/// ([`Real::identical`]: an MPFR exponent on its own ends — 1.31 and 1.31 + 2⁻⁶⁰ have the same
/// f64 bounds at 256 bits).
#[derive(Debug)]
pub(super) struct PowScratch<R> {
    pub(super) u: Vec<R>,
    pub(super) dw: Vec<R>,
    pub(super) log_on: Vec<bool>,
    pub(super) fac: Vec<(Option<R>, Vec<R>)>,
}

impl<R: Real> PowScratch<R> {
    pub(super) fn new(n: usize, nops: usize) -> Self {
        Self {
            u: vec![R::zero(); n],
            dw: vec![R::zero(); n],
            log_on: vec![false; nops],
            fac: (0..nops).map(|_| (None, Vec::new())).collect(),
        }
    }

    /// Makes `fac[i]` the factor table of the exponent q up to order `order`.
    fn factors(&mut self, i: usize, q: &R, order: usize) {
        let len = order * (order + 1) / 2;
        let (key, table) = &mut self.fac[i];
        if table.len() < len || !key.as_ref().is_some_and(|k| k.identical(q)) {
            *key = Some(q.clone());
            *table = (1..=order).flat_map(|k| pow_factors(q, k)).collect();
        }
    }
}
