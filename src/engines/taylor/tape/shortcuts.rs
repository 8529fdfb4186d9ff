//! What the recording finds to spare sums per Taylor order (the model is written as before):
//! powers that are the integral of a product the field computes anyway, products that are an
//! earlier product with a sign, and the powers of one operand sharing the series of its log.

#[cfg(test)]
use super::merges::lin_merges;
use super::powers::analytic_power;
use super::{Op, Tape};
use crate::arith::Real;

impl<R: Real, const N: usize> Tape<R, N> {
    /// How many powers are integrals of a product and how many products are sign copies of
    /// another ([`integral_powers`], [`sign_copies`]).
    #[cfg(test)]
    pub(crate) fn shortcuts(&self) -> (usize, usize) {
        (
            self.integral_of.iter().flatten().count(),
            self.sign_copy_of.iter().flatten().count(),
        )
    }

    /// The same tape computing every power by its recurrence (`integrals` off) and every
    /// product by its sum (`copies` off): the reference the shortcuts are tested against.
    #[cfg(test)]
    pub(crate) fn without_shortcuts(&self, integrals: bool, copies: bool) -> Self {
        let mut t = self.clone();
        if integrals {
            t.integral_of = vec![None; t.ops.len()];
            t.log_lead = log_leads(&t.ops, &t.consts, &t.tconst, &t.integral_of);
        }
        if copies {
            t.sign_copy_of = vec![None; t.ops.len()];
            t.lin_merges = lin_merges(&t.lins, &t.sign_copy_of, &t.mergeable);
        }
        t
    }
}

/// The powers u = |w|^(q−1)w of a state component w = x_v (a non-analytic, non-constant
/// power that no [`Op::Twin`] reads) whose derivative the field computes already, times a
/// constant: a node m = |w|^(q′)·ẇ (a product of |w|^(q′) and the node of the output ẋ_v)
/// with q′ ⊇ q − 1, so that for the true exponent q̂ ∈ q, q̂ − 1 ∈ q′ and
///
/// ```text
/// u̇ = q̂·|w|^(q̂−1)·ẇ  ∈  q·m,       u_k = q·m_{k−1}/k   (k ≥ 1)
/// ```
///
/// — one product and one quotient per order instead of a power recurrence (a sum over the
/// orders). The model's field keeps both (Maxwell: |Y|^(p−1)Y in the force and |Y|^(p−1)·W in
/// Ẇ, the same for Z with Ż). Returns, per node, the product's node for such a power.
pub(super) fn integral_powers<R: Real>(
    ops: &[Op],
    consts: &[R],
    tconst: &[bool],
    field: &[usize],
) -> Vec<Option<usize>> {
    let read_by_twin = |s: usize| {
        ops.iter()
            .any(|op| matches!(*op, Op::Twin(_, _, j, _) if j == s))
    };
    let base_of = |b: usize| match ops[b] {
        Op::Apow(a, c) | Op::Twin(a, c, _, false) => Some((a, c)),
        _ => None,
    };
    (0..ops.len())
        .map(|s| {
            let Op::Spow(a, q) = ops[s] else {
                return None;
            };
            let Op::Var(v) = ops[a] else {
                return None;
            };
            if tconst[s] || analytic_power(&consts[q], true) || read_by_twin(s) || v >= field.len()
            {
                return None;
            }
            let q1 = consts[q].clone() - R::one();
            (0..ops.len()).find(|&m| {
                let Op::Mul(x, y) = ops[m] else {
                    return false;
                };
                [(x, y), (y, x)].into_iter().any(|(b, d)| {
                    d == field[v]
                        && base_of(b).is_some_and(|(ab, c)| {
                            ab == a && !analytic_power(&consts[c], false) && consts[c].encloses(&q1)
                        })
                })
            })
        })
        .collect()
}

/// The powers of an operand share the series of ln|w| (one recurrence for the log, then one
/// single sum per power): per node that runs a power recurrence, the first such node of its
/// operand (see [`Tape::log_lead`]; an integral power runs none).
pub(super) fn log_leads<R: Real>(
    ops: &[Op],
    consts: &[R],
    tconst: &[bool],
    integral_of: &[Option<usize>],
) -> Vec<Option<usize>> {
    let recurrence = |i: usize| match ops[i] {
        _ if tconst[i] || integral_of[i].is_some() => None,
        Op::Spow(a, c) if !analytic_power(&consts[c], true) => Some(a),
        Op::Apow(a, c) if !analytic_power(&consts[c], false) => Some(a),
        Op::SpowV(a, _) | Op::ApowV(a, _) => Some(a),
        _ => None,
    };
    (0..ops.len())
        .map(|i| {
            let a = recurrence(i)?;
            (0..ops.len()).find(|&j| recurrence(j) == Some(a))
        })
        .collect()
}

/// A sign copy: (the earlier product's node, [the node holding s, the |·| node or
/// [`NO_SIGN`]]), or `None`.
type SignCopy = Option<(usize, [usize; 2])>;

/// "No node": a sign of +1 in [`Tape::sign_copy_of`].
pub(super) const NO_SIGN: usize = usize::MAX;

/// The products P′·A′ that equal an earlier product P·A up to sign, with the nodes whose
/// signs (set at order 0 of a jet) give that sign. P and P′ are the two powers |w|^(q−1)w and
/// |w|^q of one w with one exponent q (`same_exponent`: the same constant bits, as
/// [`Op::Twin`]s are paired) — a Twin and its lead, or an entire power and the other (q = 1:
/// w and |w|, SHC DSA's n = 1) — so P′/P = s, the sign of w, which the power node running a
/// recurrence holds (an entire power holds none); A and A′ are x and |x| = s_x·x (an
/// [`Op::Abs`], which holds s_x) or the same node. Then
///
/// ```text
/// P′·A′ = s·(s_x or 1)·P·A      (exactly: a change of sign, in any arithmetic)
/// ```
///
/// and the second product's series is the first's, negated or not — one sum per order fewer.
/// Returns, per node, (P·A's node, [the node holding s, the |·| node or `NO_SIGN`]).
///
/// The second result says per copy whether a fused form may take the pair as one term
/// ([`super::merges::lin_merges`]): `one_origin(nodes, (q, q′))` for every node of both products
/// and their exponents. A copy holds for enclosures whatever the origins (each node's series
/// encloses every function it stands for); a merged pair c·P + c′·P′ = (c + s·c′)·P needs P′ = s·P
/// as functions.
pub(super) fn sign_copies(
    ops: &[Op],
    tconst: &[bool],
    same_exponent: impl Fn(usize, usize) -> bool,
    analytic: impl Fn(usize, bool) -> bool,
    one_origin: impl Fn(&[usize], (usize, usize)) -> bool,
) -> (Vec<SignCopy>, Vec<bool>) {
    // (w, q, signed?, holds the sign of w?) of a power node. Only nodes that vary in time: a
    // jet sets the sign of those at order 0, a constant's never (a parameter range may even
    // reach 0)
    let power = |n: usize| match ops[n] {
        _ if tconst[n] => None,
        Op::Spow(a, q) => Some((a, q, true, !analytic(q, true))),
        Op::Apow(a, q) => Some((a, q, false, !analytic(q, false))),
        Op::Twin(a, q, _, signed) => Some((a, q, signed, true)),
        _ => None,
    };
    // (x, the |·| node or NO_SIGN) of a factor; None for |·| of a constant in time
    let base = |n: usize| match ops[n] {
        Op::Abs(_) if tconst[n] => None,
        Op::Abs(x) => Some((x, n)),
        _ => Some((n, NO_SIGN)),
    };
    // a power factor and the other factor of a product
    let split = |m: usize| match ops[m] {
        Op::Mul(a, b) if !tconst[m] => {
            if let Some(p) = power(a) {
                Some((a, p, base(b)?))
            } else {
                Some((b, power(b)?, base(a)?))
            }
        }
        _ => None,
    };
    let mut out: Vec<Option<(usize, [usize; 2])>> = vec![None; ops.len()];
    let mut mergeable = vec![false; ops.len()];
    for j in 0..ops.len() {
        let Some((pj, (wj, qj, sj, hj), (xj, absj))) = split(j) else {
            continue;
        };
        out[j] = (0..j).filter(|&i| out[i].is_none()).find_map(|i| {
            let (pi, (wi, qi, si, hi), (xi, absi)) = split(i)?;
            // the same w, q and x; the powers differ (else it is one product, which the
            // recording made one node already)
            if wi != wj || !same_exponent(qi, qj) || xi != xj || si == sj {
                return None;
            }
            // P′/P = s: the sign of w, held by a power node that runs a recurrence
            let holder = if hj {
                pj
            } else if hi {
                pi
            } else {
                return None;
            };
            let abs = match (absi, absj) {
                (NO_SIGN, NO_SIGN) => NO_SIGN,
                (NO_SIGN, a) | (a, NO_SIGN) => a,
                // |x| in both: s_x² = 1
                _ => NO_SIGN,
            };
            let nodes = [i, j, pi, pj, wi, xi, absi, absj];
            mergeable[j] = one_origin(&nodes, (qi, qj));
            Some((i, [holder, abs]))
        });
    }
    (out, mergeable)
}
