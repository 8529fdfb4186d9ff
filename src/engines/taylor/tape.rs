//! A tape of the model's own operations, and Taylor coefficients computed from it.
//!
//! The model's field is evaluated once on [`Rec`] (a recording [`Scalar`]); the resulting list
//! of operations is then replayed order by order (the jet recurrences of
//! [`crate::arith::jet::series`]), so the K Taylor coefficients of the solution through a box cost
//! O(K²) per operation, not O(K³) as re-evaluating the field on truncated series would
//! (TaylorIntegration.jl's `jetcoeffs`, kv's psa). The model is written once: the tape is its
//! code, run on another number type.
//!
//! The solution's coefficients follow from x′ = f(x): x_{k+1} = f(x)_k / (k + 1).
//!
//! |·| and the real powers are expanded in the sign region of their operand: an operand whose
//! constant coefficient does not have a certain sign has no expansion, and the jet fails with
//! [`JetError::Branch`] naming the component — the caller then takes a low-order step across.
//!
//! Two identities of the models' fields save sums per order (the tape finds them; the model is
//! written as before): a power |w|^(q−1)w whose derivative q|w|^(q−1)ẇ the field computes as a
//! product anyway is that product's integral ([`integral_powers`]: Maxwell's |Y|^(p−1)Y and
//! |Z|^(p−1)Z), and a product of the other power of one series with x or |x| is an earlier
//! product with a sign ([`sign_copies`]: the hysteretic rate's |Z|^(n−1)Z·|V| and |Z|^n·V).
//! Measured on the 28 Table 1 cases (2026-11-26, 3 alternating runs): the integrals, Maxwell
//! per-case time 0.908–0.956 (pieces and widths change a little: the Y-jets' remainders are
//! narrower); the sign copies, median 0.985, the same enclosures bit for bit.
//!
//! A fused form that sums a product and its sign copy takes them as one term
//! (c + s·c′)·P ([`lin_merges`]): the hysteretic rate β|V||Z|^(n−1)Z + γV|Z|^n is
//! (β·s + γ)·V|Z|^n, and with β ≈ −γ (|β + γ| ≈ 0.01 in every Table 1 set) the two terms
//! nearly cancel while loading. Summed one by one over an a-priori box, their widths add up and
//! the recurrences compound them order by order: the remainder coefficient x_K(Y) of SHC DSS
//! came out 10³–10⁹ times wider than the range of x_K over Y (sampled), which cut the Taylor
//! steps by a factor 1.5–3.6 (h ∝ wid^(−1/K)). Measured on the 28 cases (2026-11-26, 7
//! alternating runs): pieces 67–199 → 67–120, per-case time 0.72–1.02 (median 0.89), e
//! narrower on 27 of 28 (benches/RESULTS.md, "Cancelling terms summed as one"). The power
//! recurrence itself amplifies a box's width as much at order 16 (z′ = −z^1.31 over
//! z ∈ [0.449, 0.451]: x_16 3·10⁶ times wider than its range), which no identity of the
//! field removes: in unloading the remainders stay 10³–10⁷ times wider than their range.

use super::linear::{Lin, fuse};
pub use super::rec::Rec;
use super::rec::Recorder;
use crate::arith::jet::series::{div_k, exp_log_k, log_k, mul_k, pow_factors, pow_k};
use crate::arith::{Dot, Real};
use std::borrow::{Borrow, Cow};
use std::sync::{Arc, Mutex};

/// One recorded operation; operands are indices of earlier nodes, constants index `consts`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Op {
    Var(usize),
    Add(usize, usize),
    Sub(usize, usize),
    Mul(usize, usize),
    Div(usize, usize),
    Neg(usize),
    Scale(usize, usize),
    Shift(usize, usize),
    Abs(usize),
    /// |w|^(q−1) w
    Spow(usize, usize),
    /// |w|^q
    Apow(usize, usize),
    /// The other one of a pair |w|^(q−1)w, |w|^q with the same w and q: (operand, q, the node
    /// that runs the recurrence, signed?). Both are s·ũ or ũ for the same series ũ = (s w)^q,
    /// so only one recurrence is run (set up by [`Tape::record`]).
    Twin(usize, usize, usize, bool),
    /// A constant (index into `consts`) as a node.
    Const(usize),
    /// sign(w) (piecewise constant; a switching operation like |·|).
    Sign(usize),
    /// |w|^(q−1) w with the exponent a node constant in time (a parameter given as a range).
    SpowV(usize, usize),
    /// |w|^q with the exponent a node constant in time.
    ApowV(usize, usize),
    /// x^y (x > 0), both constant in time.
    Pow(usize, usize),
    /// ln x (x > 0), constant in time.
    Ln(usize),
    /// √x, constant in time.
    Sqrt(usize),
    /// ln|w| (w ≠ 0 for its series; a branch point like a power).
    LnAbs(usize),
    /// (power node, ln|w| node): the power times ln|w|, ∂/∂q of a power |w|^q with a variable
    /// exponent; its interval value is bounded where w reaches 0 ([`Real::pow_ln`]).
    PowLn(usize, usize),
    /// A fused chain of linear operations c₀ + Σ cⱼ·x_{nⱼ} (index into the tape's forms; see
    /// [`super::linear`]): made by [`Tape::record_with`], never recorded.
    Lin(usize),
}

/// Why a jet does not exist.
#[derive(Clone, Debug, PartialEq)]
pub enum JetError {
    /// |·| or a real power of state component `var` (or of an intermediate, `var` = None)
    /// whose sign is not certain: a switching surface or branch point is inside the box.
    Branch { var: Option<usize> },
}

/// A recorded function ℝ^N → ℝ^M (the field, then any extra outputs).
#[derive(Clone, Debug)]
pub struct Tape<R, const N: usize> {
    ops: Vec<Op>,
    consts: Vec<R>,
    /// Node of each output; the first N are the field f.
    outputs: Vec<usize>,
    /// State components that are the operand of a non-analytic operation (switching surfaces).
    switching: Vec<usize>,
    /// Switching components that are kinks: the operand only of |·| (never of a non-analytic
    /// power), so the field continued from one side is analytic across x_i = 0.
    kinks: Vec<usize>,
    /// For each power node that runs a recurrence: the first such node of its operand (e.g.
    /// of |Z|^(p−1)Z and |Z|^n), which keeps the series of ln|w| for all of them (see
    /// [`pow_node`]); `None` for every other node.
    log_lead: Vec<Option<usize>>,
    /// For a power |w|^(q−1)w of a state component w whose field has the product
    /// |w|^(q′)·ẇ with q′ ∋ q − 1 (Maxwell's |Y|^(p−1)W and |Z|^(p−1)Ż, eq:BWMCM_nd): that
    /// product's node m. The power's series is then its integral (see [`Tape::jet_on`]), not a
    /// recurrence of its own; `None` for every other node.
    integral_of: Vec<Option<usize>>,
    /// For a product P′·A′ that equals an earlier product P·A up to sign — P, P′ the two
    /// powers |w|^(q−1)w, |w|^q of one series ([`Op::Twin`]), A, A′ each x or |x| for one
    /// x (the hysteretic rate's |Z|^(n−1)Z·|V| and |Z|^n·V, eq:BWHCL): (P·A's node, the
    /// nodes whose signs make the factor) — see [`sign_copies`]; `None` for every other node.
    sign_copy_of: Vec<Option<(usize, [usize; 2])>>,
    /// Per fused form: the pairs (j, j′) of its terms whose leaves are a product and its sign
    /// copy (the hysteretic rate's β|V||Z|^(n−1)Z + γV|Z|^n) — see [`lin_merges`]; in a jet
    /// the pair is one term (c_j ± c_j′)·x.
    lin_merges: Vec<Vec<(usize, usize)>>,
    /// Per node: a sign copy whose pair a fused form may merge ([`sign_copies`]' second
    /// result): every node of both products stands for one function (no two recorded
    /// operations of different origin were taken as one by the common subexpressions) and the
    /// two exponents are one recorded constant (or one exact point).
    mergeable: Vec<bool>,
    /// Per node: constant in time (only constants and parameter variables below it; see
    /// [`Tape::record_with`]). Expanded as constants: the value at order 0, zeros above.
    tconst: Vec<bool>,
    /// The parameter components (constant in time, [`Tape::record_with`]).
    params: Vec<usize>,
    /// The forms of the [`Op::Lin`] nodes.
    lins: Vec<Lin>,
    /// How a form is rounded (see [`Tape::fused`]).
    rounding: Rounding,
    /// The nodes the extra outputs (those after the field) depend on, made when first asked
    /// for ([`Tape::eval_extra`]).
    extra_needed: std::sync::OnceLock<Vec<bool>>,
}

/// How the tape rounds a fused linear form c₀ + Σ cⱼ·xⱼ ([`Tape::fused`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rounding {
    /// Each product and sum in turn, in the type's arithmetic (for intervals: each rounded
    /// outward, stepping only where the exact result lies outward): the chain's enclosure up
    /// to the order of its roundings (the forms distribute only constants a few ulps wide;
    /// measured on the 28 Table 1 cases: the same widths as the recorded tape).
    Each,
    /// Once: one sum of products by the type's [`Dot`] accumulator, with an a-priori bound of
    /// all its rounding errors ((n + 4)u of the terms' magnitudes for intervals): faster, and
    /// wider where the operands are thin — where the width is mostly rounding it can be
    /// several times the chain's (an adversarial review measured ≈ 4× at orders 2–8 of a point
    /// jet).
    Once,
}

/// A key identifying an operation up to its constants' values (for common subexpressions).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Key {
    Op(u8, usize, usize, u64, u64),
}

impl<R: Real, const N: usize> Tape<R, N> {
    /// Records `f` (returning the field's N components followed by any extra outputs).
    pub fn record(f: impl FnOnce(&[Rec<R>; N]) -> Vec<Rec<R>>) -> Self {
        Self::record_with(std::array::from_fn(|_| None), f)
    }

    /// [`Tape::record`] of a system whose components `i` with `params[i] = Some(range)` are
    /// parameters: constant in time (their field component must be the constant 0), with
    /// values in `range` (what the model's checks on its parameters see, [`Rec`]).
    pub fn record_with(
        params: [Option<R>; N],
        f: impl FnOnce(&[Rec<R>; N]) -> Vec<Rec<R>>,
    ) -> Self {
        let rec = Arc::new(Mutex::new(Recorder {
            ops: Vec::new(),
            consts: Vec::new(),
            tconst: Vec::new(),
        }));
        let mut params = params.into_iter();
        let vars: [Rec<R>; N] = std::array::from_fn(|i| Rec::var(&rec, i, params.next().flatten()));
        let outs = f(&vars);
        assert!(outs.len() >= N, "the first N outputs must be the field");
        let outputs: Vec<usize> = outs.iter().map(|o| o.node_on(&rec)).collect();
        for (i, v) in vars.iter().enumerate() {
            let t = rec.lock().expect("tape");
            if t.tconst[v.idx] {
                let zero = matches!(t.ops[outputs[i]], Op::Const(c) if t.consts[c].lo() == 0.0 && t.consts[c].hi() == 0.0);
                assert!(zero, "the field of parameter component {i} must be 0");
            }
        }
        drop(outs);
        drop(vars);
        let Recorder {
            ops: raw,
            consts,
            tconst: raw_tconst,
        } = Arc::try_unwrap(rec)
            .expect("tape still shared")
            .into_inner()
            .expect("tape");
        // Common subexpressions (the force output repeats the field's powers): an operation on
        // the same operands with constants of the same value is recorded once.
        let cbits = |ci: usize| (consts[ci].lo().to_bits(), consts[ci].hi().to_bits());
        // the same constant, decided on the type's own ends (MPFR intervals whose f64 bounds
        // coincide may differ: such operations are not one)
        let same_const = |c: usize, d: usize| {
            c == d || (consts[c].encloses(&consts[d]) && consts[d].encloses(&consts[c]))
        };
        // one exact point, decided on the type's own ends
        let thin_point = |c: usize| {
            let k = &consts[c];
            k.lo() == k.hi() && R::from_exact_f64(k.lo()).encloses(k)
        };
        let mut ops: Vec<Op> = Vec::with_capacity(raw.len());
        let mut map = vec![0usize; raw.len()];
        let mut seen: std::collections::HashMap<Key, usize> = std::collections::HashMap::new();
        // Origins: each recorded operation's (kind, its operands' origins, its constant — the
        // recorded constant's index, or the exact point's bits), interned; a node that the
        // common subexpressions made of operations of different origin stands for more than
        // one function (sound for enclosures, not for the merged pairs).
        let mut origin_ids: std::collections::HashMap<OriginKey, u32> =
            std::collections::HashMap::new();
        let mut origin = vec![0u32; raw.len()];
        let mut first_origin: Vec<u32> = Vec::new();
        let mut ambiguous: Vec<bool> = Vec::new();
        for (i, op) in raw.iter().enumerate() {
            let constant = match (op_const(op), *op) {
                (Some(c), _) if thin_point(c) => (true, consts[c].lo().to_bits(), 0),
                (Some(c), _) => (false, c as u64, 0),
                (None, Op::Var(v)) => (false, u64::MAX - v as u64, 0),
                (None, _) => (false, u64::MAX, 1),
            };
            let mut args = [u32::MAX; 2];
            if !matches!(op, Op::Var(_) | Op::Const(_)) {
                for (slot, a) in args.iter_mut().zip(operands(op)) {
                    *slot = origin[a];
                }
            }
            let next = origin_ids.len() as u32;
            origin[i] = *origin_ids
                .entry((op_code(op), args, constant))
                .or_insert(next);
            let m = |a: usize| map[a];
            let (op, key) = match *op {
                Op::Var(v) => (Op::Var(v), Key::Op(0, v, 0, 0, 0)),
                Op::Add(a, b) => (Op::Add(m(a), m(b)), Key::Op(1, m(a), m(b), 0, 0)),
                Op::Sub(a, b) => (Op::Sub(m(a), m(b)), Key::Op(2, m(a), m(b), 0, 0)),
                Op::Mul(a, b) => (Op::Mul(m(a), m(b)), Key::Op(3, m(a), m(b), 0, 0)),
                Op::Div(a, b) => (Op::Div(m(a), m(b)), Key::Op(4, m(a), m(b), 0, 0)),
                Op::Neg(a) => (Op::Neg(m(a)), Key::Op(5, m(a), 0, 0, 0)),
                Op::Scale(a, c) => (
                    Op::Scale(m(a), c),
                    Key::Op(6, m(a), 0, cbits(c).0, cbits(c).1),
                ),
                Op::Shift(a, c) => (
                    Op::Shift(m(a), c),
                    Key::Op(7, m(a), 0, cbits(c).0, cbits(c).1),
                ),
                Op::Abs(a) => (Op::Abs(m(a)), Key::Op(8, m(a), 0, 0, 0)),
                Op::Spow(a, c) => (
                    Op::Spow(m(a), c),
                    Key::Op(9, m(a), 0, cbits(c).0, cbits(c).1),
                ),
                Op::Apow(a, c) => (
                    Op::Apow(m(a), c),
                    Key::Op(10, m(a), 0, cbits(c).0, cbits(c).1),
                ),
                Op::Const(c) => (Op::Const(c), Key::Op(11, 0, 0, cbits(c).0, cbits(c).1)),
                Op::Sign(a) => (Op::Sign(m(a)), Key::Op(12, m(a), 0, 0, 0)),
                Op::SpowV(a, b) => (Op::SpowV(m(a), m(b)), Key::Op(13, m(a), m(b), 0, 0)),
                Op::ApowV(a, b) => (Op::ApowV(m(a), m(b)), Key::Op(14, m(a), m(b), 0, 0)),
                Op::Pow(a, b) => (Op::Pow(m(a), m(b)), Key::Op(15, m(a), m(b), 0, 0)),
                Op::Ln(a) => (Op::Ln(m(a)), Key::Op(16, m(a), 0, 0, 0)),
                Op::Sqrt(a) => (Op::Sqrt(m(a)), Key::Op(17, m(a), 0, 0, 0)),
                Op::LnAbs(a) => (Op::LnAbs(m(a)), Key::Op(18, m(a), 0, 0, 0)),
                Op::PowLn(a, b) => (Op::PowLn(m(a), m(b)), Key::Op(19, m(a), m(b), 0, 0)),
                Op::Twin(..) | Op::Lin(_) => unreachable!("not recorded"),
            };
            // |w|^(q−1)w = w^q (q odd) and |w|^q = w^q (q even) are entire: for q ≥ 3 they are
            // recorded as products (square and multiply), which are exact as series and need no
            // sign of w (the power recurrence needs w_0 ≠ 0). q = 0, 1, 2 are handled in place.
            if let Op::Spow(a, c) | Op::Apow(a, c) = op
                && let Some(q) = consts[c].as_integer().filter(|&q| q >= 3)
                && analytic_power(&consts[c], matches!(op, Op::Spow(..)))
            {
                map[i] = entire_power(&mut ops, &mut seen, a, q as u64);
                note_origin(
                    &mut first_origin,
                    &mut ambiguous,
                    map[i],
                    origin[i],
                    ops.len(),
                );
                continue;
            }
            let hit =
                seen.get(&key)
                    .copied()
                    .filter(|&j| match (op_const(&op), op_const(&ops[j])) {
                        (Some(c), Some(d)) => same_const(c, d),
                        _ => true,
                    });
            map[i] = match hit {
                Some(j) => j,
                None => {
                    ops.push(op);
                    seen.entry(key).or_insert(ops.len() - 1);
                    ops.len() - 1
                }
            };
            note_origin(
                &mut first_origin,
                &mut ambiguous,
                map[i],
                origin[i],
                ops.len(),
            );
        }
        let outputs: Vec<usize> = outputs.iter().map(|&o| map[o]).collect::<Vec<usize>>();
        let mut tconst: Vec<bool> = Vec::with_capacity(ops.len());
        for op in &ops {
            let c = match *op {
                Op::Var(v) => raw_tconst[v],
                Op::Const(_) => true,
                _ => operands(op).all(|a| tconst[a]),
            };
            tconst.push(c);
        }
        // Twins: |w|^q after |w|^(q−1)w of the same w and q (or the reverse) reuse its series.
        for i in 0..ops.len() {
            let (a, c, signed) = match ops[i] {
                Op::Spow(a, c) if !tconst[i] => (a, c, true),
                Op::Apow(a, c) if !tconst[i] => (a, c, false),
                _ => continue,
            };
            if analytic_power(&consts[c], true) || analytic_power(&consts[c], false) {
                continue;
            }
            let twin = (0..i).find(|&j| match ops[j] {
                Op::Spow(b, d) | Op::Apow(b, d) => {
                    b == a
                        && cbits(d) == cbits(c)
                        && same_const(c, d)
                        && matches!(ops[j], Op::Spow(..)) != signed
                }
                _ => false,
            });
            if let Some(j) = twin {
                ops[i] = Op::Twin(a, c, j, signed);
            }
        }
        // the operands of non-analytic operations (a power with a variable exponent is never
        // taken as analytic)
        let non_analytic = |op: &Op| -> Option<(usize, bool)> {
            match *op {
                Op::Abs(a) | Op::Sign(a) => Some((a, true)),
                Op::Spow(a, q) | Op::Twin(a, q, _, true) if !analytic_power(&consts[q], true) => {
                    Some((a, false))
                }
                Op::Apow(a, q) | Op::Twin(a, q, _, false) if !analytic_power(&consts[q], false) => {
                    Some((a, false))
                }
                Op::SpowV(a, _) | Op::ApowV(a, _) | Op::LnAbs(a) => Some((a, false)),
                _ => None,
            }
        };
        let mut switching: Vec<usize> = ops
            .iter()
            .zip(&tconst)
            .filter(|&(_, &c)| !c)
            .filter_map(|(op, _)| non_analytic(op))
            .filter_map(|(a, _)| match ops[a] {
                Op::Var(i) => Some(i),
                _ => None,
            })
            .collect();
        switching.sort_unstable();
        switching.dedup();
        let kinks: Vec<usize> = switching
            .iter()
            .copied()
            .filter(|&v| {
                // v is the operand of |·| and sign only (a kink), never of a branch point
                ops.iter().zip(&tconst).all(|(op, &c)| {
                    c || match non_analytic(op) {
                        Some((a, kink)) => kink || !matches!(ops[a], Op::Var(i) if i == v),
                        None => true,
                    }
                })
            })
            .collect();
        let integral_of = integral_powers(&ops, &consts, &tconst, &outputs[..N.min(outputs.len())]);
        ambiguous.resize(ops.len(), false);
        let (sign_copy_of, mergeable) = sign_copies(
            &ops,
            &tconst,
            |c, d| cbits(c) == cbits(d) && same_const(c, d),
            |c, signed| analytic_power(&consts[c], signed),
            // one origin: no node of the pair stands for two functions, and the exponents are
            // one recorded constant or one exact point
            |nodes: &[usize], (c, d): (usize, usize)| {
                nodes.iter().all(|&n| n == NO_SIGN || !ambiguous[n])
                    && (c == d || (thin_point(c) && thin_point(d) && same_const(c, d)))
            },
        );
        let log_lead = log_leads(&ops, &consts, &tconst, &integral_of);
        Self {
            ops,
            consts,
            outputs,
            switching,
            kinks,
            log_lead,
            integral_of,
            sign_copy_of,
            lin_merges: Vec::new(),
            mergeable,
            params: (0..N).filter(|&v| tconst[v]).collect(),
            tconst,
            lins: Vec::new(),
            rounding: Rounding::Each,
            extra_needed: std::sync::OnceLock::new(),
        }
    }

    /// The same function with its chains of linear operations fused into one form each
    /// ([`super::linear`]), rounded as `rounding` says: fewer operations per Taylor order.
    /// Measured on an order-16 jet of SHC DSS over varying boxes (interleaved, one thread):
    /// 6.6 µs as recorded, 6.0 µs fused with [`Rounding::Each`], 5.6 µs with
    /// [`Rounding::Once`]; on duals of order 3, 4.1 → 3.6 µs with `Once`. Which tape the engine
    /// rounds how: [`super::step::Tapes::of`].
    ///
    /// A tape that is fused already is only given the new rounding.
    pub fn fused(&self, rounding: Rounding) -> Self {
        if !self.lins.is_empty() {
            let mut t = self.clone();
            t.rounding = rounding;
            return t;
        }
        let mut consts = self.consts.clone();
        let f = fuse(&self.ops, &mut consts, &self.tconst, &self.outputs);
        let keep = |i: usize| f.map[i].is_some();
        let mut t = Self {
            ops: f.ops,
            consts,
            outputs: self
                .outputs
                .iter()
                .map(|&o| f.map[o].expect("an output is computed"))
                .collect(),
            switching: self.switching.clone(),
            kinks: self.kinks.clone(),
            log_lead: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| self.log_lead[i].map(|l| f.map[l].expect("a power is computed")))
                .collect(),
            integral_of: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| self.integral_of[i].map(|m| f.map[m].expect("a product is computed")))
                .collect(),
            sign_copy_of: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| {
                    let (m, g) = self.sign_copy_of[i]?;
                    let node = |n: usize| {
                        if n == NO_SIGN {
                            Some(NO_SIGN)
                        } else {
                            f.map[n]
                        }
                    };
                    Some((f.map[m]?, [node(g[0])?, node(g[1])?]))
                })
                .collect(),
            tconst: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| self.tconst[i])
                .collect(),
            lin_merges: Vec::new(),
            mergeable: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| self.mergeable[i])
                .collect(),
            params: self.params.clone(),
            lins: f.lins,
            rounding,
            extra_needed: std::sync::OnceLock::new(),
        };
        t.lin_merges = lin_merges(&t.lins, &t.sign_copy_of, &t.mergeable);
        t
    }

    /// The same tape over another number type (constants converted by `f`).
    pub fn map<S: Real>(&self, f: impl Fn(&R) -> S) -> Tape<S, N> {
        Tape {
            ops: self.ops.clone(),
            consts: self.consts.iter().map(&f).collect(),
            outputs: self.outputs.clone(),
            switching: self.switching.clone(),
            kinks: self.kinks.clone(),
            log_lead: self.log_lead.clone(),
            integral_of: self.integral_of.clone(),
            sign_copy_of: self.sign_copy_of.clone(),
            lin_merges: self.lin_merges.clone(),
            mergeable: self.mergeable.clone(),
            tconst: self.tconst.clone(),
            params: self.params.clone(),
            lins: self.lins.clone(),
            rounding: self.rounding,
            extra_needed: std::sync::OnceLock::new(),
        }
    }

    /// The constant exponents q of the tape's powers |w|^(q−1)w and |w|^q (duplicates
    /// included): the generators of the singular step's expansions.
    pub fn power_exponents(&self) -> Vec<R> {
        self.ops
            .iter()
            .filter_map(|op| match *op {
                Op::Spow(_, q) | Op::Apow(_, q) | Op::Twin(_, q, _, _) => {
                    Some(self.consts[q].clone())
                }
                _ => None,
            })
            .collect()
    }

    /// True when the tape has powers with a variable exponent (a parameter given as a range).
    pub fn has_variable_exponents(&self) -> bool {
        self.ops
            .iter()
            .any(|op| matches!(op, Op::SpowV(..) | Op::ApowV(..)))
    }

    /// The parameter components: constant in time (see [`Tape::record_with`]).
    pub fn params(&self) -> &[usize] {
        &self.params
    }

    /// The switching components that are kinks of |·| only (see [`Tape::jet_on`]).
    pub fn kinks(&self) -> &[usize] {
        &self.kinks
    }

    /// The state components on which the field switches (|·| kinks, branch points).
    pub fn switching(&self) -> &[usize] {
        &self.switching
    }

    /// The operations (after common subexpressions and fusion).
    pub fn ops(&self) -> &[Op] {
        &self.ops
    }

    pub fn len(&self) -> usize {
        self.ops.len()
    }

    pub fn is_empty(&self) -> bool {
        self.ops.is_empty()
    }

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

    /// The same tape with every fused form's terms summed one by one (no [`lin_merges`]).
    #[cfg(test)]
    pub(crate) fn without_merges(&self) -> Self {
        let mut t = self.clone();
        t.lin_merges = vec![Vec::new(); t.lins.len()];
        t
    }

    /// How many term pairs the fused forms merge ([`lin_merges`]).
    #[cfg(test)]
    pub(crate) fn merges(&self) -> usize {
        self.lin_merges.iter().map(Vec::len).sum()
    }

    /// Evaluates all outputs at a point (order-0 replay) — plain interval evaluation for
    /// `R = Interval`, valid across switching surfaces.
    pub fn eval(&self, x: &[R; N]) -> Vec<R> {
        self.eval_on(x, &[0; N])
    }

    /// The extra outputs (after the field's N components) at a point, computing only the nodes
    /// they depend on (the event scan's F and V need the force, not the hysteretic rate: on the
    /// SHC tape about half the nodes and one power fewer).
    pub fn eval_extra(&self, x: &[R; N]) -> Vec<R> {
        let needed = self.extra_needed.get_or_init(|| {
            let mut need = vec![false; self.ops.len()];
            for &o in &self.outputs[N.min(self.outputs.len())..] {
                need[o] = true;
            }
            for i in (0..self.ops.len()).rev() {
                if !need[i] {
                    continue;
                }
                match self.ops[i] {
                    Op::Lin(l) => {
                        for &(_, n) in &self.lins[l].terms {
                            need[n] = true;
                        }
                    }
                    // a twin power may be computed from its pair's value (`Real::twin_pow`)
                    Op::Twin(a, _, j, _) => {
                        need[a] = true;
                        need[j] = true;
                    }
                    ref op => {
                        for a in operands(op) {
                            need[a] = true;
                        }
                    }
                }
                // a kink's or a sign's continuation reads its operand's op, nothing more
            }
            need
        });
        let v = self.node_values(x, &[0; N], Some(needed));
        self.outputs[N.min(self.outputs.len())..]
            .iter()
            .map(|&o| v[o].clone())
            .collect()
    }

    /// Every node's value at `x` (kinks continued from `side`); with `needed`, only the marked
    /// nodes (the others 0).
    fn node_values(&self, x: &[R; N], side: &[i8; N], needed: Option<&[bool]>) -> Vec<R> {
        let mut v: Vec<R> = Vec::with_capacity(self.ops.len());
        for (i, op) in self.ops.iter().enumerate() {
            v.push(if needed.is_none_or(|n| n[i]) {
                self.op_value(op, |a| &v[a], x, side)
            } else {
                R::zero()
            });
        }
        v
    }

    /// [`Tape::eval`] of the field continued across kinks from `side` (see [`Tape::jet_on`]).
    pub fn eval_on(&self, x: &[R; N], side: &[i8; N]) -> Vec<R> {
        let v = self.node_values(x, side, None);
        self.outputs.iter().map(|&o| v[o].clone()).collect()
    }

    /// The value of one operation from its operands' values `v` (state `x`, kinks continued
    /// from `side`).
    #[inline]
    fn op_value<'a>(&self, op: &Op, v: impl Fn(usize) -> &'a R, x: &[R; N], side: &[i8; N]) -> R
    where
        R: 'a,
    {
        match *op {
            Op::Var(i) => x[i].clone(),
            Op::Const(c) => self.consts[c].clone(),
            Op::Add(a, b) => v(a).clone() + v(b).clone(),
            Op::Sub(a, b) => v(a).clone() - v(b).clone(),
            Op::Mul(a, b) => v(a).clone() * v(b).clone(),
            Op::Div(a, b) => v(a).clone() / v(b).clone(),
            Op::Neg(a) => -v(a).clone(),
            Op::Scale(a, c) => v(a).clone() * self.consts[c].clone(),
            Op::Shift(a, c) => v(a).clone() + self.consts[c].clone(),
            Op::Abs(a) => match self.ops[a] {
                Op::Var(j) if side[j] > 0 => v(a).clone(),
                Op::Var(j) if side[j] < 0 => -v(a).clone(),
                _ => Real::abs(v(a)),
            },
            Op::Sign(a) => match self.ops[a] {
                Op::Var(j) if side[j] != 0 => R::from_int(side[j] as i64),
                _ => Real::sgn(v(a)),
            },
            Op::Spow(a, q) => Real::spow(v(a), &self.consts[q]),
            Op::Apow(a, q) => Real::apow(v(a), &self.consts[q]),
            Op::Twin(a, q, j, signed) => Real::twin_pow(v(a), &self.consts[q], v(j), signed),
            Op::SpowV(a, q) => Real::spow(v(a), v(q)),
            Op::ApowV(a, q) => Real::apow(v(a), v(q)),
            Op::Pow(a, b) => Real::pow(v(a), v(b)),
            Op::Ln(a) => Real::ln(v(a)),
            Op::Sqrt(a) => Real::sqrt(v(a)),
            Op::LnAbs(a) => Real::ln(&Real::abs(v(a))),
            Op::PowLn(p, _) => match self.ops[p] {
                Op::SpowV(a, q) => R::pow_ln(v(a), v(q), true),
                Op::ApowV(a, q) => R::pow_ln(v(a), v(q), false),
                _ => unreachable!("PowLn of a power with a variable exponent"),
            },
            Op::Lin(l) => self.lin_value(l, v, true),
        }
    }

    /// The value of the fused form `l` from its leaves' values `v`: c₀ + Σ cⱼ·v(nⱼ) as one sum
    /// of products (`shift`: with c₀, at order 0; a coefficient of order ≥ 1 is Σ cⱼ·v(nⱼ)).
    #[inline]
    fn lin_value<'a>(&self, l: usize, v: impl Fn(usize) -> &'a R, shift: bool) -> R
    where
        R: 'a,
    {
        let terms = self.lins[l]
            .terms
            .iter()
            .map(|&(c, n)| (&self.consts[c], n));
        self.form_sum(l, terms, v, shift)
    }

    /// c₀ + Σ cⱼ·v(nⱼ) over the (constant, leaf) `terms` of form `l` (`shift`: with its c₀),
    /// rounded as the tape says ([`Rounding`]): each product and sum in turn, or one sum of
    /// products.
    #[inline]
    fn form_sum<'a, C: Borrow<R>>(
        &self,
        l: usize,
        terms: impl Iterator<Item = (C, usize)>,
        v: impl Fn(usize) -> &'a R,
        shift: bool,
    ) -> R
    where
        R: 'a,
    {
        let lin = &self.lins[l];
        if self.rounding == Rounding::Each {
            let mut acc: Option<R> = None;
            for (c, n) in terms {
                let p = v(n).mul_constant(c.borrow());
                acc = Some(match acc {
                    Some(a) => a + p,
                    None => p,
                });
            }
            let acc = acc.unwrap_or_else(R::zero);
            return match lin.shift {
                Some(c) if shift => acc + self.consts[c].clone(),
                _ => acc,
            };
        }
        let mut d = <R::Dot as Dot<R>>::new();
        for (c, n) in terms {
            d.add_scaled(c.borrow(), v(n));
        }
        if shift && let Some(c) = lin.shift {
            d.add_scaled(&self.consts[c], &R::one());
        }
        d.sum()
    }

    /// [`Tape::lin_value`] of a form with sign-copy pairs ([`lin_merges`]), in a jet whose
    /// copies' signs are `sign` (set at order 0): each pair (j, j′) is the one term
    /// (c_j + s·c_j′)·x_{n_j}, s = ±1 the sign with which x_{n_j′} = s·x_{n_j}, and the
    /// constants' sum is enclosed in the type's arithmetic. For the true values
    /// c_j·x + c_j′·(s·x) = (c_j + s·c_j′)·x, so the term encloses the pair's sum; what it
    /// spares is the dependency: with β ≈ −γ (every Table 1 set: |β + γ| ≈ 0.01 against
    /// |β| ≈ 0.4–1.4) the two terms nearly cancel, and an interval sum of them is about
    /// (|β| + |γ|)/|β + γ| ≈ 100 times wider than their value's range — a width that the
    /// recurrences compound order by order over a wide box.
    fn merged_lin_value<'a>(
        &self,
        l: usize,
        v: impl Fn(usize) -> &'a R,
        shift: bool,
        sign: &[i8],
    ) -> R
    where
        R: 'a,
    {
        let lin = &self.lins[l];
        let merges = &self.lin_merges[l];
        // (constant, leaf) of each term left: a pair's first term with the summed constant
        let terms = lin.terms.iter().enumerate().filter_map(|(j, &(c, n))| {
            if merges.iter().any(|&(_, b)| b == j) {
                return None;
            }
            let c = &self.consts[c];
            Some(match merges.iter().find(|&&(a, _)| a == j) {
                Some(&(_, b)) => {
                    let (cb, m) = lin.terms[b];
                    let cb = self.consts[cb].clone();
                    let merged = if sign[m] < 0 {
                        c.clone() - cb
                    } else {
                        c.clone() + cb
                    };
                    (Cow::Owned(merged), n)
                }
                None => (Cow::Borrowed(c), n),
            })
        });
        self.form_sum(l, terms, v, shift)
    }

    /// The Taylor coefficients x_0..x_K of the solution of x′ = f(x), x(0) = x0 (a point or a
    /// box: for a box every coefficient encloses the coefficients of all solutions through it).
    /// Returns `coef[i][k]`.
    pub fn jet(
        &self,
        x0: &[R; N],
        order: usize,
        ws: &mut Workspace<R>,
    ) -> Result<[Vec<R>; N], JetError> {
        self.jet_on(x0, order, ws, &[0; N])
    }

    /// [`Tape::jet`] of the field continued across kinks: for each kink component i with
    /// `side[i]` = ±1, |x_i| is expanded as side\[i\]·x_i whatever the sign of x_i in the box —
    /// the analytic continuation of the field from that side (|·| of a kink component is the
    /// only non-analytic operation on it, see [`Tape::kinks`]). 0 = no continuation.
    pub fn jet_on(
        &self,
        x0: &[R; N],
        order: usize,
        ws: &mut Workspace<R>,
        side: &[i8; N],
    ) -> Result<[Vec<R>; N], JetError> {
        let k1 = order + 1;
        let nops = self.ops.len();
        ws.reset(nops, k1);
        let Workspace { c, scratch, sign } = ws;
        for k in 0..k1 {
            for (i, op) in self.ops.iter().enumerate() {
                if self.tconst[i] {
                    // a constant in time: its value, zeros above
                    c[i * k1 + k] = if k == 0 {
                        self.op_value(op, |a| &c[a * k1], x0, side)
                    } else {
                        R::zero()
                    };
                    continue;
                }
                let at = |n: usize, j: usize| &c[n * k1 + j];
                let val = match *op {
                    Op::Const(..) | Op::Pow(..) | Op::Ln(..) | Op::Sqrt(..) => {
                        unreachable!("constant in time")
                    }
                    Op::Sign(a) => {
                        if k == 0 {
                            sign[i] = match self.ops[a] {
                                Op::Var(v) if side[v] != 0 => side[v],
                                _ => self.sign_of(a, at(a, 0))?,
                            };
                            R::from_int(sign[i] as i64)
                        } else {
                            R::zero()
                        }
                    }
                    Op::LnAbs(a) => {
                        if k == 0 {
                            self.sign_of(a, at(a, 0))?;
                            Real::ln(&Real::abs(at(a, 0)))
                        } else {
                            // k·L_k by the log recurrence from j·L_j (j < k), then L_k
                            let jl: Vec<R> = (0..k).map(|j| at(i, j).mul_int(j as i64)).collect();
                            log_k(&c[a * k1..a * k1 + k + 1], &jl, k).div_int(k as i64)
                        }
                    }
                    Op::PowLn(p, l) => {
                        mul_k(&c[p * k1..p * k1 + k + 1], &c[l * k1..l * k1 + k + 1], k)
                    }
                    Op::SpowV(a, q) | Op::ApowV(a, q) => {
                        let signed = matches!(op, Op::SpowV(..));
                        if k == 0 {
                            sign[i] = self.sign_of(a, at(a, 0))?;
                        }
                        let lead = self.log_lead[i].expect("a recurrence power");
                        let qv = c[q * k1].clone();
                        pow_node(c, scratch, sign[i], a, i, lead, k, k1, &qv, signed)
                    }
                    Op::Var(v) => {
                        if k == 0 {
                            x0[v].clone()
                        } else {
                            c[self.outputs[v] * k1 + k - 1].div_int(k as i64)
                        }
                    }
                    Op::Lin(l) if !self.lin_merges[l].is_empty() => {
                        self.merged_lin_value(l, |n| at(n, k), k == 0, sign)
                    }
                    Op::Lin(l) => self.lin_value(l, |n| at(n, k), k == 0),
                    Op::Add(a, b) => at(a, k).clone() + at(b, k).clone(),
                    Op::Sub(a, b) => at(a, k).clone() - at(b, k).clone(),
                    Op::Neg(a) => -at(a, k).clone(),
                    Op::Mul(..) if self.sign_copy_of[i].is_some() => {
                        // ±(an earlier product): the sign from its factors' signs at order 0
                        let (m, g) = self.sign_copy_of[i].expect("checked");
                        if k == 0 {
                            sign[i] = g
                                .iter()
                                .map(|&n| if n == NO_SIGN { 1 } else { sign[n] })
                                .product();
                        }
                        let u = c[m * k1 + k].clone();
                        if sign[i] < 0 { -u } else { u }
                    }
                    Op::Mul(a, b) => {
                        mul_k(&c[a * k1..a * k1 + k + 1], &c[b * k1..b * k1 + k + 1], k)
                    }
                    Op::Div(a, b) => div_k(
                        &c[a * k1..a * k1 + k + 1],
                        &c[b * k1..b * k1 + k + 1],
                        &c[i * k1..i * k1 + k],
                        k,
                    ),
                    Op::Scale(a, q) => at(a, k).mul_constant(&self.consts[q]),
                    Op::Shift(a, q) => {
                        if k == 0 {
                            at(a, 0).clone() + self.consts[q].clone()
                        } else {
                            at(a, k).clone()
                        }
                    }
                    Op::Abs(a) => {
                        if k == 0 {
                            sign[i] = match self.ops[a] {
                                Op::Var(v) if side[v] != 0 => side[v],
                                _ => self.sign_of(a, at(a, 0))?,
                            };
                        }
                        if sign[i] > 0 {
                            at(a, k).clone()
                        } else {
                            -at(a, k).clone()
                        }
                    }
                    Op::Twin(_, _, j, signed) => {
                        if k == 0 {
                            sign[i] = sign[j];
                        }
                        let u = scratch.u[j * k1 + k].clone();
                        if signed && sign[j] < 0 { -u } else { u }
                    }
                    Op::Spow(a, q) if self.integral_of[i].is_some() => {
                        // u = |w|^(q−1)w with u̇ = q·|w|^(q−1)·ẇ = q·m: u_k = q·m_{k−1}/k
                        let qv = &self.consts[q];
                        if k == 0 {
                            sign[i] = self.sign_of(a, at(a, 0))?;
                            let u = branch_power(at(a, 0), sign[i], qv);
                            if sign[i] < 0 { -u } else { u }
                        } else {
                            let m = self.integral_of[i].expect("checked");
                            c[m * k1 + k - 1].mul_constant(qv).div_int(k as i64)
                        }
                    }
                    Op::Spow(a, q) | Op::Apow(a, q) => {
                        let signed = matches!(op, Op::Spow(..));
                        let qv = &self.consts[q];
                        // |w|^(q−1)w = w^q (q odd), |w|^q = w^q (q even) are entire: small
                        // exponents by products, exact as series; every other power by the
                        // power recurrence, which needs w_0 ≠ 0
                        match qv.as_integer().filter(|_| analytic_power(qv, signed)) {
                            Some(0) => {
                                if k == 0 {
                                    R::one()
                                } else {
                                    R::zero()
                                }
                            }
                            Some(1) => at(a, k).clone(),
                            Some(2) => {
                                mul_k(&c[a * k1..a * k1 + k + 1], &c[a * k1..a * k1 + k + 1], k)
                            }
                            _ => {
                                if k == 0 {
                                    sign[i] = self.sign_of(a, at(a, 0))?;
                                }
                                let lead = self.log_lead[i].expect("a recurrence power");
                                pow_node(c, scratch, sign[i], a, i, lead, k, k1, qv, signed)
                            }
                        }
                    }
                };
                c[i * k1 + k] = val;
            }
        }
        // x_k is stored at the Var nodes (indices 0..N, recorded first)
        Ok(std::array::from_fn(|v| c[v * k1..(v + 1) * k1].to_vec()))
    }

    /// Coefficient k of output `j` (0..N: the field; N..: the extra outputs) from the last
    /// [`Tape::jet`] run in `ws` with the same `order`.
    pub fn output_coef(&self, ws: &Workspace<R>, order: usize, j: usize, k: usize) -> R {
        ws.c[self.outputs[j] * (order + 1) + k].clone()
    }

    fn sign_of(&self, a: usize, w0: &R) -> Result<i8, JetError> {
        w0.sign().ok_or(JetError::Branch {
            var: match self.ops[a] {
                Op::Var(i) => Some(i),
                _ => None,
            },
        })
    }
}

/// The operand nodes of an operation (of a recorded one: a fused form's operands are its
/// terms).
pub(super) fn operands(op: &Op) -> impl Iterator<Item = usize> {
    let (a, b) = match *op {
        Op::Lin(_) => unreachable!("the operands of a fused form are its terms"),
        Op::Var(_) | Op::Const(_) => (None, None),
        Op::Add(a, b)
        | Op::Sub(a, b)
        | Op::Mul(a, b)
        | Op::Div(a, b)
        | Op::SpowV(a, b)
        | Op::ApowV(a, b)
        | Op::PowLn(a, b)
        | Op::Pow(a, b) => (Some(a), Some(b)),
        Op::Neg(a)
        | Op::Scale(a, _)
        | Op::Shift(a, _)
        | Op::Abs(a)
        | Op::Sign(a)
        | Op::Spow(a, _)
        | Op::Apow(a, _)
        | Op::Twin(a, ..)
        | Op::Ln(a)
        | Op::LnAbs(a)
        | Op::Sqrt(a) => (Some(a), None),
    };
    a.into_iter().chain(b)
}

/// The operation with its node indices (operands, and a twin's recurrence node) mapped by `m`.
pub(super) fn remap(op: Op, m: impl Fn(usize) -> usize) -> Op {
    match op {
        Op::Var(_) | Op::Const(_) | Op::Lin(_) => op,
        Op::Add(a, b) => Op::Add(m(a), m(b)),
        Op::Sub(a, b) => Op::Sub(m(a), m(b)),
        Op::Mul(a, b) => Op::Mul(m(a), m(b)),
        Op::Div(a, b) => Op::Div(m(a), m(b)),
        Op::SpowV(a, b) => Op::SpowV(m(a), m(b)),
        Op::ApowV(a, b) => Op::ApowV(m(a), m(b)),
        Op::PowLn(a, b) => Op::PowLn(m(a), m(b)),
        Op::Pow(a, b) => Op::Pow(m(a), m(b)),
        Op::Neg(a) => Op::Neg(m(a)),
        Op::Scale(a, c) => Op::Scale(m(a), c),
        Op::Shift(a, c) => Op::Shift(m(a), c),
        Op::Abs(a) => Op::Abs(m(a)),
        Op::Sign(a) => Op::Sign(m(a)),
        Op::Spow(a, c) => Op::Spow(m(a), c),
        Op::Apow(a, c) => Op::Apow(m(a), c),
        Op::Twin(a, c, j, s) => Op::Twin(m(a), c, m(j), s),
        Op::Ln(a) => Op::Ln(m(a)),
        Op::LnAbs(a) => Op::LnAbs(m(a)),
        Op::Sqrt(a) => Op::Sqrt(m(a)),
    }
}

/// Records w^q (q ≥ 1) as products of earlier nodes by square and multiply (at most
/// 2·log₂ q products, shared with equal products already recorded); returns the node of w^q.
fn entire_power(
    ops: &mut Vec<Op>,
    seen: &mut std::collections::HashMap<Key, usize>,
    w: usize,
    q: u64,
) -> usize {
    let mut mul = |a: usize, b: usize| {
        *seen.entry(Key::Op(3, a, b, 0, 0)).or_insert_with(|| {
            ops.push(Op::Mul(a, b));
            ops.len() - 1
        })
    };
    // w^q = Π over the set bits of q of w^(2^j)
    let (mut acc, mut sq, mut e) = (None::<usize>, w, q);
    while e > 0 {
        if e & 1 == 1 {
            acc = Some(acc.map_or(sq, |a| mul(a, sq)));
        }
        e >>= 1;
        if e > 0 {
            sq = mul(sq, sq);
        }
    }
    acc.expect("q ≥ 1")
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
fn integral_powers<R: Real>(
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
fn log_leads<R: Real>(
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

/// A recorded operation's origin: (kind, its operands' origins, its constant: (exact point?,
/// the point's bits or the constant's index, 0) — see [`Tape::record_with`]).
type OriginKey = (u8, [u32; 2], (bool, u64, u64));

/// A sign copy: (the earlier product's node, [the node holding s, the |·| node or
/// [`NO_SIGN`]]), or `None`.
type SignCopy = Option<(usize, [usize; 2])>;

/// "No node": a sign of +1 in [`Tape::sign_copy_of`].
const NO_SIGN: usize = usize::MAX;

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
/// ([`lin_merges`]): `one_origin(nodes, (q, q′))` for every node of both products and their
/// exponents. A copy holds for enclosures whatever the origins (each node's series encloses
/// every function it stands for); a merged pair c·P + c′·P′ = (c + s·c′)·P needs P′ = s·P as
/// functions.
fn sign_copies(
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

/// Notes that recorded operation of origin `origin` is node `node` (of `nops`): a node first
/// noted with one origin and then with another stands for two functions.
fn note_origin(
    first: &mut Vec<u32>,
    ambiguous: &mut Vec<bool>,
    node: usize,
    origin: u32,
    nops: usize,
) {
    first.resize(nops, u32::MAX);
    ambiguous.resize(nops, false);
    if first[node] == u32::MAX {
        first[node] = origin;
    } else if first[node] != origin {
        ambiguous[node] = true;
    }
}

/// The constant (index into `consts`) a recorded operation takes, if any.
fn op_const(op: &Op) -> Option<usize> {
    match *op {
        Op::Scale(_, c) | Op::Shift(_, c) | Op::Spow(_, c) | Op::Apow(_, c) | Op::Const(c) => {
            Some(c)
        }
        _ => None,
    }
}

/// A number per kind of operation (for the origins of [`Tape::record_with`]).
fn op_code(op: &Op) -> u8 {
    match op {
        Op::Var(_) => 0,
        Op::Add(..) => 1,
        Op::Sub(..) => 2,
        Op::Mul(..) => 3,
        Op::Div(..) => 4,
        Op::Neg(_) => 5,
        Op::Scale(..) => 6,
        Op::Shift(..) => 7,
        Op::Abs(_) => 8,
        Op::Spow(..) => 9,
        Op::Apow(..) => 10,
        Op::Twin(..) => 11,
        Op::Const(_) => 12,
        Op::Sign(_) => 13,
        Op::SpowV(..) => 14,
        Op::ApowV(..) => 15,
        Op::Pow(..) => 16,
        Op::Ln(_) => 17,
        Op::Sqrt(_) => 18,
        Op::LnAbs(_) => 19,
        Op::PowLn(..) => 20,
        Op::Lin(_) => 21,
    }
}

/// Per fused form: the pairs (j, j′) of its terms whose leaves are a product and a sign copy
/// of it ([`sign_copies`]: x_{n_j′} = ±x_{n_j} in every jet), each term in at most one pair.
fn lin_merges(
    lins: &[Lin],
    sign_copy_of: &[Option<(usize, [usize; 2])>],
    mergeable: &[bool],
) -> Vec<Vec<(usize, usize)>> {
    lins.iter()
        .map(|lin| {
            let mut pairs: Vec<(usize, usize)> = Vec::new();
            for (b, &(_, m)) in lin.terms.iter().enumerate() {
                let Some((base, _)) = sign_copy_of.get(m).copied().flatten() else {
                    continue;
                };
                if !mergeable.get(m).copied().unwrap_or(false) {
                    continue;
                }
                let used = |j: usize| pairs.iter().any(|&(x, y)| x == j || y == j);
                if let Some(a) = (0..lin.terms.len())
                    .find(|&a| a != b && lin.terms[a].1 == base && !used(a) && !used(b))
                {
                    pairs.push((a, b));
                }
            }
            pairs
        })
        .collect()
}

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
/// ũ itself is kept in `scratch.u` (for the recurrences and for a [`Op::Twin`]).
#[allow(clippy::too_many_arguments)]
#[inline]
fn pow_node<R: Real>(
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
fn branch_power<R: Real>(w0: &R, s: i8, q: &R) -> R {
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
struct PowScratch<R> {
    u: Vec<R>,
    dw: Vec<R>,
    log_on: Vec<bool>,
    fac: Vec<(Option<R>, Vec<R>)>,
}

impl<R: Real> PowScratch<R> {
    fn new(n: usize, nops: usize) -> Self {
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

/// Reusable storage for [`Tape::jet`], for any tape and order (a power's factor table is
/// remade for another exponent, see `PowScratch`).
#[derive(Debug)]
pub struct Workspace<R> {
    c: Vec<R>,
    scratch: PowScratch<R>,
    sign: Vec<i8>,
}

impl<R> Default for Workspace<R> {
    fn default() -> Self {
        Self {
            c: Vec::new(),
            scratch: PowScratch {
                u: Vec::new(),
                dw: Vec::new(),
                log_on: Vec::new(),
                fac: Vec::new(),
            },
            sign: Vec::new(),
        }
    }
}

impl<R: Real> Workspace<R> {
    fn reset(&mut self, nops: usize, k1: usize) {
        let n = nops * k1;
        if self.c.len() != n {
            self.c = vec![R::zero(); n];
            self.scratch = PowScratch::new(n, nops);
        }
        if self.sign.len() != nops {
            self.sign = vec![1; nops];
        }
        if self.scratch.log_on.len() != nops {
            self.scratch = PowScratch::new(n, nops);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::Scalar;
    use crate::arith::jet::series::Series;
    use crate::models::{CollisionModel, Maxwell, ModelKind, NdParams, Shc};
    use inari::Interval;

    /// Coefficients by the slow route: Picard on truncated series, re-evaluating the model on
    /// `Series` K times.
    fn series_jet<M: CollisionModel<f64, N>, const N: usize>(
        m: &M,
        x0: [f64; N],
        order: usize,
    ) -> [Vec<f64>; N] {
        let mut x: [Vec<f64>; N] = std::array::from_fn(|i| {
            let mut v = vec![0.0; order + 1];
            v[0] = x0[i];
            v
        });
        for k in 0..order {
            let s: [Series<f64>; N] =
                std::array::from_fn(|i| Series::from_coefficients(x[i].clone()));
            let f = m.field(&s);
            for i in 0..N {
                x[i][k + 1] = f[i].c[k] / (k as f64 + 1.0);
            }
        }
        x
    }

    #[test]
    fn entire_powers_expand_at_zero() {
        // s′ = 1, y′ = |s|^(q−1)s (q odd) or |s|^q (q even) from s = 0: y = t^(q+1)/(q+1). The
        // power's operand starts at 0, where the power recurrence does not exist: entire powers
        // must be expanded as products (they panicked for q ≥ 3, issue #12)
        let zero = Interval::try_from((0.0, 0.0)).unwrap();
        let one = Interval::try_from((1.0, 1.0)).unwrap();
        for q in [3_u32, 4, 5, 6, 10, 11, 50] {
            let qi = Interval::try_from((q as f64, q as f64)).unwrap();
            let signed = q % 2 == 1;
            let tape = Tape::<Interval, 2>::record(|v| {
                let p = if signed {
                    Scalar::<Interval>::spow(&v[0], &qi)
                } else {
                    Scalar::<Interval>::apow(&v[0], &qi)
                };
                vec![v[1].scale(&zero).shift(&one), p]
            });
            assert!(tape.switching().is_empty(), "q = {q}: an entire power");
            let order = 60;
            let mut ws = Workspace::default();
            let j = tape.jet(&[zero, zero], order, &mut ws).unwrap();
            for (k, c) in j[1].iter().enumerate() {
                let exact = if k == q as usize + 1 {
                    1.0 / (q as f64 + 1.0)
                } else {
                    0.0
                };
                assert!(
                    c.inf() <= exact && exact <= c.sup() && c.wid() <= 1e-14,
                    "q = {q}, k = {k}: {c:?} vs {exact}"
                );
            }
        }
    }

    #[test]
    fn tape_jet_equals_series_jet() {
        let shc = Shc::<f64>::new(
            NdParams::parse(ModelKind::Shc, "1.43,-1.42,0.632,0.00715,1.31,1.27").unwrap(),
        );
        let tape = Tape::<f64, 3>::record(|v| shc.field(v).to_vec());
        assert_eq!(tape.switching(), &[0, 1, 2]);
        // |V| is a kink; X and Z are branch points of the real powers
        assert_eq!(tape.kinks(), &[2]);
        let x0 = [-0.3, -0.2, 0.4];
        let a = tape.jet(&x0, 12, &mut Workspace::default()).unwrap();
        let b = series_jet(&shc, x0, 12);
        for i in 0..3 {
            for k in 0..=12 {
                assert!(
                    (a[i][k] - b[i][k]).abs() <= 1e-12 * (1.0 + b[i][k].abs()),
                    "{i} {k}: {} {}",
                    a[i][k],
                    b[i][k]
                );
            }
        }
        let mx = Maxwell::<f64>::new(
            NdParams::parse(ModelKind::Maxwell, "0.44,-0.418,0.113,0.00785,1.27,3.14").unwrap(),
        );
        let tape = Tape::<f64, 4>::record(|v| mx.field(v).to_vec());
        assert_eq!(tape.switching(), &[1, 2, 3]);
        assert_eq!(tape.kinks(), &[3]);
        let x0 = [0.1, -0.3, -0.2, 0.4];
        let a = tape.jet(&x0, 10, &mut Workspace::default()).unwrap();
        let b = series_jet(&mx, x0, 10);
        for i in 0..4 {
            for k in 0..=10 {
                assert!(
                    (a[i][k] - b[i][k]).abs() <= 1e-12 * (1.0 + b[i][k].abs()),
                    "{i} {k}"
                );
            }
        }
    }

    /// The jets the engine runs on [`Ulp`](crate::arith::interval::ulp::Ulp) intervals enclose the same
    /// coefficients as those on inari intervals (endpoints within one ulp; equal almost always),
    /// and both enclose the f64 jet, at random thin points and small boxes of both models.
    #[test]
    fn ulp_jets_match_inari_jets() {
        use crate::arith::interval::ulp::Ulp;
        use inari::Interval;
        fn check<M, const N: usize>(m: &M, mf: &impl CollisionModel<f64, N>, seed: u64)
        where
            M: CollisionModel<Interval, N>,
        {
            let tape = Tape::<Interval, N>::record(|v| m.field(v).to_vec());
            let fast = tape.map(|c| Ulp::of(*c));
            let ftape = Tape::<f64, N>::record(|v| mf.field(v).to_vec());
            let mut r = crate::arith::interval::xorshift(seed);
            let mut next = move || (r() >> 11) as f64 / (1u64 << 53) as f64;
            let (mut equal, mut total) = (0, 0);
            for case in 0..200 {
                let x: [f64; N] = std::array::from_fn(|_| {
                    let v = 0.05 + next();
                    if next() < 0.5 { -v } else { v }
                });
                let r = if case % 2 == 0 { 0.0 } else { 1e-9 * next() };
                let xi: [Interval; N] = x.map(|v| Interval::try_from((v - r, v + r)).unwrap());
                let side = [0i8; N];
                let a = tape
                    .jet_on(&xi, 16, &mut Workspace::default(), &side)
                    .unwrap();
                let b = fast
                    .jet_on(&xi.map(Ulp::of), 16, &mut Workspace::default(), &side)
                    .unwrap();
                let f = ftape.jet(&x, 16, &mut Workspace::default()).unwrap();
                for i in 0..N {
                    for k in 0..=16 {
                        let (ai, bi) = (a[i][k], b[i][k]);
                        total += 1;
                        if ai.inf() == bi.lo && ai.sup() == bi.hi {
                            equal += 1;
                        }
                        assert!(
                            bi.lo >= ai.inf().next_down() && bi.hi <= ai.sup().next_up(),
                            "x = {x:?} ± {r}, component {i}, order {k}: {ai:?} vs {bi:?}"
                        );
                        let tol = 1e-9 * (1.0 + f[i][k].abs());
                        assert!(
                            ai.inf() - tol <= f[i][k] && f[i][k] <= ai.sup() + tol,
                            "f64 coefficient {} outside {ai:?}",
                            f[i][k]
                        );
                    }
                }
            }
            assert!(
                equal * 10 >= total * 9,
                "only {equal} of {total} endpoints equal"
            );
        }
        let shc = "1.43,-1.42,0.632,0.00715,1.31,1.27";
        check(
            &Shc::new(NdParams::<Interval>::parse(ModelKind::Shc, shc).unwrap()),
            &Shc::new(NdParams::<f64>::parse(ModelKind::Shc, shc).unwrap()),
            7,
        );
        let mx = "0.44,-0.418,0.113,0.00785,1.27,3.14";
        check(
            &Maxwell::new(NdParams::<Interval>::parse(ModelKind::Maxwell, mx).unwrap()),
            &Maxwell::new(NdParams::<f64>::parse(ModelKind::Maxwell, mx).unwrap()),
            11,
        );
    }

    /// Points of every sign pattern of the state (components ±[0.05, 1.05]) by a xorshift.
    fn sign_pattern_points<const N: usize>(seed: u64, n: usize) -> Vec<[f64; N]> {
        let mut r = crate::arith::interval::xorshift(seed);
        let mut next = move || (r() >> 11) as f64 / (1u64 << 53) as f64;
        (0..n)
            .map(|case| {
                std::array::from_fn(|i| {
                    let v = 0.05 + next();
                    if (case >> i) & 1 == 1 { -v } else { v }
                })
            })
            .collect()
    }

    /// The shortcuts change how a jet is computed, not what it encloses. On both models'
    /// tapes (recorded and fused, as the engine runs them) at points of every sign pattern,
    /// to order 16: the jets with the shortcuts contain the 256-bit jets of the same tape
    /// without them (intervals ~1e-70 wide, compared exactly), and the sign copies alone give
    /// the jets of the sums bit for bit (a change of sign is exact) where the fused forms sum
    /// the copy's term on its own ([`Tape::without_merges`]). Maxwell's tape has two integral
    /// powers (|Y|^(p−1)Y, |Z|^(p−1)Z) and one sign copy, SHC's one sign copy; the fused
    /// forms merge one pair of terms in each.
    #[test]
    fn shortcut_jets_enclose_the_jets_of_the_sums() {
        use crate::arith::mpfr::Mpi;
        type M = Mpi<256>;
        fn check<const N: usize>(
            tape: &Tape<Interval, N>,
            reference: &Tape<M, N>,
            shortcuts: (usize, usize),
            seed: u64,
        ) {
            assert_eq!(tape.shortcuts(), shortcuts);
            // (tape, merged pairs: the recorded tape has no fused forms)
            for (t, merges) in [
                (tape.clone(), 0),
                (tape.fused(Rounding::Each), 1),
                (tape.fused(Rounding::Once), 1),
            ] {
                assert_eq!(t.shortcuts(), shortcuts, "fused");
                assert_eq!(t.merges(), merges, "merged pairs");
                let sums = t.without_shortcuts(false, true);
                let copies = t.without_merges();
                let side = [0i8; N];
                for x in sign_pattern_points::<N>(seed, 2 << N) {
                    let xi = x.map(|v| Interval::try_from((v, v)).unwrap());
                    let a = t.jet_on(&xi, 16, &mut Workspace::default(), &side).unwrap();
                    let c = copies
                        .jet_on(&xi, 16, &mut Workspace::default(), &side)
                        .unwrap();
                    let b = sums
                        .jet_on(&xi, 16, &mut Workspace::default(), &side)
                        .unwrap();
                    let r = reference
                        .jet_on(
                            &x.map(M::from_exact_f64),
                            16,
                            &mut Workspace::default(),
                            &side,
                        )
                        .unwrap();
                    for i in 0..N {
                        for k in 0..=16 {
                            assert!(
                                c[i][k].inf() == b[i][k].inf() && c[i][k].sup() == b[i][k].sup(),
                                "sign copy at {x:?}, {i}, order {k}: {:?} vs {:?}",
                                c[i][k],
                                b[i][k]
                            );
                            for (what, j) in [("merged", &a), ("copies", &c)] {
                                assert!(
                                    r[i][k].subset(&M::from_interval(j[i][k])),
                                    "{what}: x = {x:?}, component {i}, order {k}: {:?} not in \
                                     {:?}",
                                    r[i][k].to_interval(),
                                    j[i][k]
                                );
                            }
                        }
                    }
                }
            }
        }
        let (shc, mx) = (
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "0.44,-0.418,0.113,0.00785,1.27,3.14",
        );
        let m = Shc::new(NdParams::<Interval>::parse(ModelKind::Shc, shc).unwrap());
        let mm = Shc::new(NdParams::<M>::parse(ModelKind::Shc, shc).unwrap());
        let tape = Tape::<Interval, 3>::record(|v| m.field(v).to_vec());
        let reference =
            Tape::<M, 3>::record(|v| mm.field(v).to_vec()).without_shortcuts(true, true);
        check(&tape, &reference, (0, 1), 5);
        let m = Maxwell::new(NdParams::<Interval>::parse(ModelKind::Maxwell, mx).unwrap());
        let mm = Maxwell::new(NdParams::<M>::parse(ModelKind::Maxwell, mx).unwrap());
        let tape = Tape::<Interval, 4>::record(|v| m.field(v).to_vec());
        let reference =
            Tape::<M, 4>::record(|v| mm.field(v).to_vec()).without_shortcuts(true, true);
        check(&tape, &reference, (2, 1), 9);
    }

    /// A merged pair of terms ([`lin_merges`]) over a box: the hysteretic rate's
    /// β|V||Z|^(n−1)Z + γV|Z|^n of SHC DSS (β + γ = 0.01) on two a-priori boxes of its flow
    /// (v0 = 1, 2; 2–15 % wide): in loading (V, Z < 0: the terms cancel) and in unloading
    /// (V > 0, Z < 0: they add). The order-16 jet with the pair merged contains the 256-bit jets at 40
    /// points of the box (the end corners included), and in loading its coefficient of Ż is
    /// at least 10⁴ times narrower than with the terms summed one by one (measured: 6.7e6
    /// times, 1.9e3 → 2.8e-4); in unloading, where nothing cancels, as wide (to 1 %).
    #[test]
    fn merged_pairs_spare_the_cancellation_over_a_box() {
        use crate::arith::mpfr::Mpi;
        type M = Mpi<256>;
        let shc = "1.43,-1.42,0.632,0.00715,1.31,1.27";
        let m = Shc::new(NdParams::<Interval>::parse(ModelKind::Shc, shc).unwrap());
        let mm = Shc::new(NdParams::<M>::parse(ModelKind::Shc, shc).unwrap());
        let reference = Tape::<M, 3>::record(|v| mm.field(v).to_vec())
            .without_shortcuts(true, true)
            .fused(Rounding::Each)
            .without_merges();
        let tape = Tape::<Interval, 3>::record(|v| m.field(v).to_vec()).fused(Rounding::Each);
        assert_eq!(tape.merges(), 1);
        let sums = tape.without_merges();
        let mut next = crate::arith::interval::xorshift(0x7a3c_91e5_0d42_b861);
        let loading = [(-0.9338, -0.8820), (-0.9301, -0.8787), (-0.5788, -0.4976)];
        let unloading = [(-0.949, -0.929), (-0.490, -0.423), (0.431, 0.463)];
        for (bx, min_gain) in [(loading, 1e4), (unloading, 1.0 / 1.01)] {
            let y = bx.map(|(a, b)| Interval::try_from((a, b)).unwrap());
            let side = [0i8; 3];
            let a = tape
                .jet_on(&y, 16, &mut Workspace::default(), &side)
                .unwrap();
            let b = sums
                .jet_on(&y, 16, &mut Workspace::default(), &side)
                .unwrap();
            let gain = b[1][16].wid() / a[1][16].wid();
            assert!(
                gain >= min_gain,
                "{bx:?}: {:e} vs {:e}",
                a[1][16].wid(),
                b[1][16].wid()
            );
            for case in 0..40 {
                let x: [f64; 3] = std::array::from_fn(|i| {
                    let (lo, hi) = bx[i];
                    match case {
                        0 => lo,
                        1 => hi,
                        _ => lo + (hi - lo) * ((next() >> 11) as f64 / (1u64 << 53) as f64),
                    }
                });
                let r = reference
                    .jet_on(
                        &x.map(M::from_exact_f64),
                        16,
                        &mut Workspace::default(),
                        &side,
                    )
                    .unwrap();
                for i in 0..3 {
                    for k in 0..=16 {
                        assert!(
                            r[i][k].subset(&M::from_interval(a[i][k])),
                            "x = {x:?}, component {i}, order {k}: {:?} not in {:?}",
                            r[i][k].to_interval(),
                            a[i][k]
                        );
                    }
                }
            }
        }
    }

    /// A pair is merged only where its two products are one function up to sign — not where
    /// the common subexpressions made one node of operations that only have equal enclosures
    /// (found by an adversarial review): (A) exponents n, p ∈ [1.1, 1.3] recorded apart (the
    /// true n = 1.1, p = 1.3), (B) x = κ₁v and κ₂v with κ₁, κ₂ ∈ [0.9, 1.1] (true 0.9 and
    /// 1.1). There the merged form would be 10–20 times too narrow (order 1: [0.0041, 0.0047]
    /// against the true 0.0904); now nothing merges and every jet contains the 256-bit jet of
    /// the truth. One range recorded by `spow_apow` (one constant: one exponent) merges, and
    /// contains the truth for q at either end of the range. (C) At 256 bits, exponents 1.31 and
    /// 1.31 + 2⁻⁶⁰ (equal f64 bounds) are two nodes, not one power and its Twin as before,
    /// whose order-1 coefficient missed the exact value.
    #[test]
    fn merged_pairs_need_one_origin() {
        use crate::arith::mpfr::Mpi;
        type M = Mpi<256>;
        let iv = |a: f64, b: f64| Interval::try_from((a, b)).unwrap();
        let (b, g) = (
            Interval::parse_decimal("1.43").unwrap(),
            Interval::parse_decimal("-1.42").unwrap(),
        );
        let (bm, gm) = (
            M::parse_decimal("1.43").unwrap(),
            M::parse_decimal("-1.42").unwrap(),
        );
        // β·|z|^(n−1)z·|x₁| + γ·|z|^p·x₂ with x₁ = κ₁v, x₂ = κ₂v (κ = None: v itself), the
        // powers recorded apart or (`pair`) by one spow_apow of n
        fn field<R: Real>(
            v: &[Rec<R>; 2],
            (n, p): (&R, &R),
            k: Option<(&R, &R)>,
            (b, g): (&R, &R),
            pair: bool,
        ) -> Vec<Rec<R>> {
            let (x1, x2) = match k {
                Some((k1, k2)) => (v[1].scale(k1), v[1].scale(k2)),
                None => (v[1].clone(), v[1].clone()),
            };
            let (s, a) = if pair {
                Scalar::<R>::spow_apow(&v[0], n)
            } else {
                (Scalar::<R>::spow(&v[0], n), Scalar::<R>::apow(&v[0], p))
            };
            let rate = (s * Real::abs(&x1)).scale(b) + (a * x2).scale(g);
            vec![rate, -v[0].clone()]
        }
        let check = |tape: &Tape<Interval, 2>, truth: &Tape<M, 2>, merges: usize, what: &str| {
            let truth = truth.without_shortcuts(true, true);
            for rounding in [Rounding::Each, Rounding::Once] {
                let t = tape.fused(rounding);
                assert_eq!(t.merges(), merges, "{what}");
                for x in sign_pattern_points::<2>(31, 8) {
                    let a = t
                        .jet(&x.map(|c| iv(c, c)), 6, &mut Workspace::default())
                        .unwrap();
                    let r = truth
                        .jet(&x.map(M::from_exact_f64), 6, &mut Workspace::default())
                        .unwrap();
                    for i in 0..2 {
                        for k in 0..=6 {
                            assert!(
                                r[i][k].subset(&M::from_interval(a[i][k])),
                                "{what}, {rounding:?}: x = {x:?}, {i}, order {k}"
                            );
                        }
                    }
                }
            }
        };
        let (r1, r2) = (iv(1.1, 1.3), iv(1.1, 1.3));
        let (lo, hi) = (
            M::parse_decimal("1.1").unwrap(),
            M::parse_decimal("1.3").unwrap(),
        );
        // (A)
        let tape = Tape::<Interval, 2>::record(|v| field(v, (&r1, &r2), None, (&b, &g), false));
        let truth = Tape::<M, 2>::record(|v| field(v, (&lo, &hi), None, (&bm, &gm), false));
        check(&tape, &truth, 0, "exponents apart");
        // one constant: merged, and the truth for either end of the range inside
        let tape = Tape::<Interval, 2>::record(|v| field(v, (&r1, &r1), None, (&b, &g), true));
        for q in [&lo, &hi] {
            let truth = Tape::<M, 2>::record(|v| field(v, (q, q), None, (&bm, &gm), true));
            check(&tape, &truth, 1, "one exponent");
        }
        // (B)
        let q = Interval::parse_decimal("1.31").unwrap();
        let qm = M::parse_decimal("1.31").unwrap();
        let (k1, k2) = (iv(0.9, 1.1), iv(0.9, 1.1));
        let (k1m, k2m) = (
            M::parse_decimal("0.9").unwrap(),
            M::parse_decimal("1.1").unwrap(),
        );
        let tape =
            Tape::<Interval, 2>::record(|v| field(v, (&q, &q), Some((&k1, &k2)), (&b, &g), true));
        let truth =
            Tape::<M, 2>::record(|v| field(v, (&qm, &qm), Some((&k1m, &k2m)), (&bm, &gm), true));
        check(&tape, &truth, 0, "κ₁, κ₂ apart");
        // (C) at 256 bits
        let q2 = qm.clone() + M::from_exact_f64(2f64.powi(-60));
        assert_eq!((q2.lo(), q2.hi()), (qm.lo(), qm.hi()));
        let tape = Tape::<M, 2>::record(|v| field(v, (&qm, &q2), None, (&bm, &gm), false));
        assert_eq!(tape.shortcuts(), (0, 0), "1.31 and 1.31 + 2⁻⁶⁰ at 256 bits");
        assert!(!tape.ops().iter().any(|op| matches!(op, Op::Twin(..))));
        let z = [M::from_exact_f64(0.5), M::from_exact_f64(1.0)];
        let exact = Real::spow(&z[0], &qm) * bm.clone() + Real::apow(&z[0], &q2) * gm.clone();
        for t in [tape.clone(), tape.fused(Rounding::Each)] {
            let a = t.jet(&z, 2, &mut Workspace::default()).unwrap();
            assert!(exact.subset(&a[0][1]), "order 1 at 256 bits");
        }
    }

    /// A power is taken as the integral of a product only where the product is |w|^(q′)·ẇ
    /// with q′ ⊇ q − 1 and ẇ the field's own component: y′ = w, w′ = −|y|^(q−1)y − c·B with
    /// B = |y|^(q′)·w (q′ = q − 1: the integral; q′ = q − 1/2, B = |y|^(q−1)·y or ·v: not), and
    /// the jets enclose the 256-bit jets of the sums either way (a wrongly taken integral
    /// would not: with q′ = q − 1/2 the coefficients differ from order 2 on).
    #[test]
    fn integral_powers_only_where_the_product_is_the_derivative() {
        use crate::arith::mpfr::Mpi;
        type M = Mpi<256>;
        fn toy<R: Real>(shift: &str, partner: usize) -> Tape<R, 3> {
            let q = R::parse_decimal("2.3").unwrap();
            let qb = q.clone() - R::parse_decimal(shift).unwrap();
            let c = R::parse_decimal("0.7").unwrap();
            let one = R::one();
            Tape::<R, 3>::record(|v| {
                let u = Scalar::<R>::spow(&v[0], &q);
                let b = Scalar::<R>::apow(&v[0], &qb) * v[partner].clone();
                vec![v[1].clone(), -u - b.scale(&c), v[2].scale(&one)]
            })
        }
        for (shift, partner, integrals) in [("1", 1, 1), ("0.5", 1, 0), ("1", 2, 0), ("1", 0, 0)] {
            let tape = toy::<Interval>(shift, partner);
            assert_eq!(
                tape.shortcuts().0,
                integrals,
                "q′ = q − {shift}, partner component {partner}"
            );
            let reference = toy::<M>(shift, partner).without_shortcuts(true, true);
            for x in sign_pattern_points::<3>(3, 16) {
                let xi = x.map(|v| Interval::try_from((v, v)).unwrap());
                let a = tape.jet(&xi, 12, &mut Workspace::default()).unwrap();
                let r = reference
                    .jet(&x.map(M::from_exact_f64), 12, &mut Workspace::default())
                    .unwrap();
                for i in 0..3 {
                    for k in 0..=12 {
                        assert!(
                            r[i][k].subset(&M::from_interval(a[i][k])),
                            "q′ = q − {shift}, x = {x:?}, component {i}, order {k}"
                        );
                    }
                }
            }
        }
        // the check that guards it: with q′ = q − 1/2 taken as an integral (the containment
        // test skipped), the jets exclude the true coefficients
        let mut wrong = toy::<Interval>("0.5", 1);
        let s = wrong
            .ops
            .iter()
            .position(|op| matches!(op, Op::Spow(..)))
            .unwrap();
        let m = wrong
            .ops
            .iter()
            .position(|op| matches!(op, Op::Mul(..)))
            .unwrap();
        wrong.integral_of[s] = Some(m);
        wrong.log_lead = log_leads(&wrong.ops, &wrong.consts, &wrong.tconst, &wrong.integral_of);
        let reference = toy::<M>("0.5", 1).without_shortcuts(true, true);
        let x = [0.4, -0.3, 0.2];
        let a = wrong
            .jet(
                &x.map(|v| Interval::try_from((v, v)).unwrap()),
                12,
                &mut Workspace::default(),
            )
            .unwrap();
        let r = reference
            .jet(&x.map(M::from_exact_f64), 12, &mut Workspace::default())
            .unwrap();
        assert!(
            (0..3).any(|i| (0..=12).any(|k| !r[i][k].subset(&M::from_interval(a[i][k])))),
            "a wrong integral went unnoticed"
        );
    }

    /// The shortcuts' preconditions, each on a field where it decides (found by an adversarial
    /// review): a power a Twin reads (its series is needed) is no integral; a |·| of a
    /// parameter (its sign is never set by a jet) makes no sign copy; P·|x| and P′·|x| copy
    /// with the power's sign alone; at 256 bits an exponent q′ = (q − 1) + 10⁻⁶⁰, whose f64
    /// bounds are those of q − 1, is no integral. Every jet contains the 256-bit jet of the
    /// sums (exactly), and the copies give the sums' jets bit for bit. Exponent 1: x·|y| and
    /// |x|·y copy each other and merge in a fused form, while 1 and 1 + 2⁻³⁰ do neither.
    #[test]
    fn shortcuts_are_not_taken_where_they_do_not_hold() {
        use crate::arith::mpfr::Mpi;
        type M = Mpi<256>;
        fn twin<R: Real>() -> Tape<R, 2> {
            let q = R::parse_decimal("2.3").unwrap();
            let qb = q.clone() - R::one();
            let c = R::parse_decimal("0.7").unwrap();
            Tape::<R, 2>::record(|v| {
                let (u, ua) = Scalar::<R>::spow_apow(&v[0], &q);
                let b = Scalar::<R>::apow(&v[0], &qb) * v[1].clone();
                vec![v[1].clone(), -u - ua - b.scale(&c)]
            })
        }
        fn abs_pair<R: Real>(param: Option<R>) -> Tape<R, 2> {
            let q = R::parse_decimal("1.5").unwrap();
            let two = R::from_int(2);
            Tape::<R, 2>::record_with([None, param], |v| {
                let (p, pa) = Scalar::<R>::spow_apow(&v[0], &q);
                let a = p * Real::abs(&v[1]);
                let b = pa * Real::abs(&v[1]);
                vec![a + b.scale(&two), Rec::constant(R::zero())]
            })
        }
        fn enclosed<const N: usize>(
            tape: &Tape<Interval, N>,
            reference: &Tape<M, N>,
            points: &[[f64; N]],
            what: &str,
        ) {
            enclosed_as(tape, reference, points, what, true)
        }
        // `bitwise`: the copies are the sums' jets bit for bit (not for exponent 1, where the
        // sums take |x| by the power recurrence and the copy ±x·|y| exactly)
        fn enclosed_as<const N: usize>(
            tape: &Tape<Interval, N>,
            reference: &Tape<M, N>,
            points: &[[f64; N]],
            what: &str,
            bitwise: bool,
        ) {
            let sums = tape.without_shortcuts(false, true);
            let reference = reference.without_shortcuts(true, true);
            for x in points {
                let xi = x.map(|v| Interval::try_from((v, v)).unwrap());
                let a = tape.jet(&xi, 10, &mut Workspace::default()).unwrap();
                let b = sums.jet(&xi, 10, &mut Workspace::default()).unwrap();
                let r = reference
                    .jet(&x.map(M::from_exact_f64), 10, &mut Workspace::default())
                    .unwrap();
                for i in 0..N {
                    for k in 0..=10 {
                        assert!(
                            !bitwise
                                || (a[i][k].inf() == b[i][k].inf()
                                    && a[i][k].sup() == b[i][k].sup()),
                            "{what}: a copy differs at {x:?}, {i}, {k}"
                        );
                        assert!(
                            r[i][k].subset(&M::from_interval(a[i][k])),
                            "{what}: x = {x:?}, component {i}, order {k}"
                        );
                    }
                }
            }
        }
        let points = sign_pattern_points::<2>(13, 8);
        let tape = twin::<Interval>();
        assert_eq!(tape.shortcuts(), (0, 0), "a power its twin reads");
        enclosed(&tape, &twin::<M>(), &points, "twin");
        let tape = abs_pair::<Interval>(None);
        assert_eq!(tape.shortcuts(), (0, 1), "P·|x| and P′·|x|");
        enclosed(&tape, &abs_pair::<M>(None), &points, "P·|x|");
        for p in [-1.0, 0.5] {
            let tape = abs_pair::<Interval>(Some(Interval::try_from((p, p)).unwrap()));
            assert_eq!(tape.shortcuts(), (0, 0), "|·| of a parameter");
            let xs: Vec<[f64; 2]> = points.iter().map(|x| [x[0], p]).collect();
            enclosed(
                &tape,
                &abs_pair::<M>(Some(M::from_exact_f64(p))),
                &xs,
                "|parameter|",
            );
        }
        // at 256 bits: q′ a hair above q − 1
        let q = M::parse_decimal("2.3").unwrap();
        let qb = q.clone() - M::one() + M::parse_decimal("1e-60").unwrap();
        assert_eq!(qb.lo(), (q.clone() - M::one()).lo());
        assert_eq!(qb.hi(), (q.clone() - M::one()).hi());
        let c = M::parse_decimal("0.7").unwrap();
        let rec = || {
            Tape::<M, 2>::record(|v| {
                let u = Scalar::<M>::spow(&v[0], &q);
                let b = Scalar::<M>::apow(&v[0], &qb) * v[1].clone();
                vec![v[1].clone(), -u - b.scale(&c)]
            })
        };
        assert_eq!(rec().shortcuts(), (0, 0), "q′ ⊉ q − 1 at 256 bits");
        let x = [M::from_exact_f64(0.4), M::from_exact_f64(-0.3)];
        let a = rec().jet(&x, 8, &mut Workspace::default()).unwrap();
        let r = rec()
            .without_shortcuts(true, true)
            .jet(&x, 8, &mut Workspace::default())
            .unwrap();
        assert!((0..2).all(|i| (0..=8).all(|k| r[i][k].subset(&a[i][k]))));
        // exponent 1 (SHC DSA's n = 1): x·|y| and |x|·y are copies (|x|⁰x = x holds no sign,
        // |x| does), merged in the fused form; a hair off (q′ = 1 + 2⁻³⁰) they are not
        // (`swap`: |x|·y recorded first, so that the copy's power x holds no sign)
        fn unit_pair<R: Real>(q2: &R, swap: bool) -> Tape<R, 2> {
            let one = R::one();
            let (b, g) = (
                R::parse_decimal("0.63").unwrap(),
                R::parse_decimal("-0.611").unwrap(),
            );
            Tape::<R, 2>::record(|v| {
                let pair = |first: bool| {
                    if first {
                        Scalar::<R>::spow(&v[0], &one) * Real::abs(&v[1])
                    } else {
                        Scalar::<R>::apow(&v[0], q2) * v[1].clone()
                    }
                };
                let (p, pa) = if swap {
                    let pa = pair(false);
                    (pair(true), pa)
                } else {
                    (pair(true), pair(false))
                };
                vec![v[1].clone() - p.scale(&b) - pa.scale(&g), -v[0].clone()]
            })
        }
        for swap in [false, true] {
            let tape = unit_pair::<Interval>(&Interval::one(), swap);
            assert_eq!(tape.shortcuts(), (0, 1), "x·|y| and |x|·y");
            enclosed_as(
                &tape,
                &unit_pair::<M>(&M::one(), swap),
                &points,
                "exponent 1",
                false,
            );
            let fused = tape.fused(Rounding::Each);
            assert_eq!(fused.merges(), 1, "x·|y| and |x|·y in one form");
            let reference = unit_pair::<M>(&M::one(), swap).without_shortcuts(true, true);
            for x in &points {
                let a = fused
                    .jet(
                        &x.map(|v| Interval::try_from((v, v)).unwrap()),
                        10,
                        &mut Workspace::default(),
                    )
                    .unwrap();
                let r = reference
                    .jet(&x.map(M::from_exact_f64), 10, &mut Workspace::default())
                    .unwrap();
                assert!(
                    (0..2).all(|i| (0..=10).all(|k| r[i][k].subset(&M::from_interval(a[i][k])))),
                    "merged at {x:?}"
                );
            }
        }
        let off = 1.0 + 2f64.powi(-30);
        let tape = unit_pair::<Interval>(&Interval::try_from((off, off)).unwrap(), false);
        assert_eq!(tape.shortcuts(), (0, 0), "exponents 1 and 1 + 2⁻³⁰");
        assert_eq!(tape.fused(Rounding::Each).merges(), 0);
        enclosed(
            &tape,
            &unit_pair::<M>(&M::from_exact_f64(off), false),
            &points,
            "exponent 1 + 2⁻³⁰",
        );
    }

    /// The extra outputs computed alone (only the nodes they need) are the full evaluation's,
    /// bit for bit, on the engine's tapes of both models (the field, then F and V) and their
    /// fused forms, over points and boxes of each sign pattern; the SHC tape skips nodes.
    #[test]
    fn extra_outputs_alone_equal_the_full_evaluation() {
        fn check<M: CollisionModel<Interval, N>, const N: usize>(m: &M) -> usize {
            let tape = Tape::<Interval, N>::record(|v| {
                let mut o = m.field(v).to_vec();
                o.push(m.force(v));
                o.push(m.velocity(v));
                o
            });
            let mut next = crate::arith::interval::xorshift(0x2545_f491_4f6c_dd1d_u64);
            let mut unit = move || (next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            let mut checked = 0;
            for t in [
                tape.clone(),
                tape.fused(Rounding::Each),
                tape.fused(Rounding::Once),
            ] {
                for _ in 0..300 {
                    let x: [Interval; N] = std::array::from_fn(|_| {
                        let (a, w) = (unit() * 2.0, unit().abs() * [0.0, 1e-9, 0.3][checked % 3]);
                        Interval::try_from((a, a + w)).unwrap()
                    });
                    let full = t.eval(&x);
                    let extra = t.eval_extra(&x);
                    assert_eq!(extra.len(), 2);
                    for (a, b) in full[N..].iter().zip(&extra) {
                        assert!(
                            a.inf().to_bits() == b.inf().to_bits()
                                && a.sup().to_bits() == b.sup().to_bits()
                                || (a.is_empty() && b.is_empty()),
                            "{x:?}: {a:?} vs {b:?}"
                        );
                    }
                    checked += 1;
                }
            }
            tape.eval_extra(&std::array::from_fn(|_| {
                Interval::try_from((0.5, 0.5)).unwrap()
            }));
            tape.extra_needed
                .get()
                .unwrap()
                .iter()
                .filter(|&&n| !n)
                .count()
        }
        let shc = "1.43,-1.42,0.632,0.00715,1.31,1.27";
        let skipped = check(&Shc::new(
            NdParams::<Interval>::parse(ModelKind::Shc, shc).unwrap(),
        ));
        assert!(
            skipped > 0,
            "the SHC scan skips the hysteretic rate's nodes"
        );
        let mx = "0.44,-0.418,0.113,0.00785,1.27,3.14";
        check(&Maxwell::new(
            NdParams::<Interval>::parse(ModelKind::Maxwell, mx).unwrap(),
        ));
    }

    /// Asserts that the jets of `tape` to `order` over each box (a point where lo = hi) contain
    /// the 256-bit jets of `reference` (compared exactly) at the box's two end corners and at
    /// `samples` points drawn in it.
    fn jets_contain_the_reference<const N: usize>(
        tape: &Tape<Interval, N>,
        reference: &Tape<crate::arith::mpfr::Mpi<256>, N>,
        boxes: &[[(f64, f64); N]],
        order: usize,
        samples: usize,
        what: &str,
    ) {
        use crate::arith::mpfr::Mpi;
        let mut r = crate::arith::interval::xorshift(0x243f_6a88_85a3_08d3);
        let mut next = move || (r() >> 11) as f64 / (1u64 << 53) as f64;
        for bx in boxes {
            let y = bx.map(|(a, b)| Interval::try_from((a, b)).unwrap());
            let a = tape.jet(&y, order, &mut Workspace::default()).unwrap();
            let thin = bx.iter().all(|(lo, hi)| lo == hi);
            for case in 0..if thin { 1 } else { 2 + samples } {
                let x: [f64; N] = std::array::from_fn(|i| {
                    let (lo, hi) = bx[i];
                    match case {
                        0 => lo,
                        1 => hi,
                        _ => lo + (hi - lo) * next(),
                    }
                });
                let e = reference
                    .jet(
                        &x.map(Mpi::<256>::from_exact_f64),
                        order,
                        &mut Workspace::default(),
                    )
                    .unwrap();
                for i in 0..N {
                    for k in 0..=order {
                        assert!(
                            e[i][k].subset(&Mpi::<256>::from_interval(a[i][k])),
                            "{what}: box {bx:?}, x = {x:?}, component {i}, order {k}: {:?} not \
                             in {:?}",
                            e[i][k].to_interval(),
                            a[i][k]
                        );
                    }
                }
            }
        }
    }

    /// The points of [`sign_pattern_points`] as thin boxes, and boxes around each of
    /// relative width `rel`.
    fn points_and_boxes<const N: usize>(seed: u64, rel: f64) -> Vec<[(f64, f64); N]> {
        let points = sign_pattern_points::<N>(seed, 2 << N);
        let thin = points.iter().map(|x| x.map(|v| (v, v)));
        let wide = points.iter().map(|x| {
            x.map(|v| {
                let d = v.abs() * rel;
                (v - d, v + d)
            })
        });
        thin.chain(wide).collect()
    }

    /// One fused form that sums a product and two sign copies of it merges one pair, and each
    /// term at most once ([`lin_merges`]): z′ = c₁·P + c₂·P′ + c₃·P″ with P = |z|^(q−1)z·x,
    /// P′ = |z|^q·x = s_z·P and P″ = |z|^q·|x| = s_z·s_x·P (the powers by one spow_apow,
    /// recorded in that order), x′ = −z; the three terms summed in each of the six orders, and
    /// P twice (P, P′, P, P″: two pairs, each P in one). The tapes fused both ways contain the
    /// 256-bit jets of the sums at points of every sign pattern and over boxes around them.
    /// Pairing a term of P twice dropped the second copy's term from the jet.
    #[test]
    fn a_product_and_two_sign_copies_merge_one_pair() {
        use crate::arith::mpfr::Mpi;
        type M = Mpi<256>;
        fn field<R: Real>(v: &[Rec<R>; 2], order: &[usize]) -> Vec<Rec<R>> {
            let q = R::parse_decimal("1.31").unwrap();
            let c = ["1.43", "-1.42", "0.37", "-0.55"].map(|c| R::parse_decimal(c).unwrap());
            let (s, a) = Scalar::<R>::spow_apow(&v[0], &q);
            let p = [
                s * v[1].clone(),
                a.clone() * v[1].clone(),
                a * Real::abs(&v[1]),
            ];
            let rate = order
                .iter()
                .zip(&c)
                .map(|(&j, c)| p[j].scale(c))
                .reduce(|a, b| a + b)
                .unwrap();
            vec![rate, -v[0].clone()]
        }
        let boxes = points_and_boxes::<2>(41, 0.02);
        let orders: [&[usize]; 7] = [
            &[0, 1, 2],
            &[0, 2, 1],
            &[1, 0, 2],
            &[1, 2, 0],
            &[2, 0, 1],
            &[2, 1, 0],
            &[0, 1, 0, 2],
        ];
        for order in orders {
            let tape = Tape::<Interval, 2>::record(|v| field(v, order));
            let reference = Tape::<M, 2>::record(|v| field(v, order)).without_shortcuts(true, true);
            for rounding in [Rounding::Each, Rounding::Once] {
                let t = tape.fused(rounding);
                let what = format!("{order:?}, {rounding:?}");
                jets_contain_the_reference(&t, &reference, &boxes, 8, 6, &what);
                // the shape: one form of all the terms, two copies, one pair per copy of P
                assert_eq!(t.lins.len(), 1, "{what}: one form");
                assert_eq!(t.lins[0].terms.len(), order.len(), "{what}: its terms");
                assert_eq!(t.shortcuts(), (0, 2), "{what}: P′ and P″ copies of P");
                assert_eq!(t.merges(), order.len() - 2, "{what}: merged pairs");
            }
        }
    }

    /// A product is a sign copy of another only where their other factors are one x (x or
    /// |x|; [`sign_copies`]): with z′ = c₁·|z|^(q−1)z·A + c₂·|z|^q·B, x′ = −z, y′ = z − y/2,
    /// the pairs (A, B) = (x, x), (x, |x|), (|x|, x), (|x|, |x|) are copies (and merge in the
    /// fused form), the same with y for B are not. Every tape, recorded and fused, contains
    /// the 256-bit jets of the sums at points of every sign pattern and over boxes around
    /// them. Taken as a copy, |z|^q·y had the series of ±|z|^(q−1)z·x.
    #[test]
    fn sign_copies_need_one_other_factor() {
        use crate::arith::mpfr::Mpi;
        type M = Mpi<256>;
        fn field<R: Real>(v: &[Rec<R>; 3], (abs_a, abs_b): (bool, bool), b: usize) -> Vec<Rec<R>> {
            let q = R::parse_decimal("1.31").unwrap();
            let (c1, c2) = (
                R::parse_decimal("1.43").unwrap(),
                R::parse_decimal("-1.42").unwrap(),
            );
            let factor = |n: usize, abs: bool| {
                if abs { Real::abs(&v[n]) } else { v[n].clone() }
            };
            let (s, a) = Scalar::<R>::spow_apow(&v[0], &q);
            let rate = (s * factor(1, abs_a)).scale(&c1) + (a * factor(b, abs_b)).scale(&c2);
            let half = R::parse_decimal("0.5").unwrap();
            vec![rate, -v[0].clone(), v[0].clone() - v[2].scale(&half)]
        }
        let boxes = points_and_boxes::<3>(43, 0.02);
        for abs in [(false, false), (false, true), (true, false), (true, true)] {
            for (b, copies) in [(1, 1), (2, 0)] {
                let what = format!("|·| {abs:?}, other factor component {b}");
                let tape = Tape::<Interval, 3>::record(|v| field(v, abs, b));
                let reference =
                    Tape::<M, 3>::record(|v| field(v, abs, b)).without_shortcuts(true, true);
                jets_contain_the_reference(&tape, &reference, &boxes, 8, 4, &what);
                let fused = tape.fused(Rounding::Each);
                jets_contain_the_reference(&fused, &reference, &boxes, 8, 4, &what);
                assert_eq!(tape.shortcuts(), (0, copies), "{what}: copies");
                assert_eq!(fused.merges(), copies, "{what}: merged");
            }
        }
    }

    /// A power's factor table q(k − j) − j ([`pow_k`]) is kept in the workspace with the
    /// exponent it was made for, compared on the type's own ends ([`Real::identical`]), so a
    /// workspace reused for another exponent with the same f64 bounds (1.31 and 1.31 + 2⁻⁶⁰ at
    /// 256 bits) makes a table of its own. One workspace runs the jets of y′ = |x|^q and of
    /// y′ = |x|^(q−1)x (x′ = 1) to order 8, the exponent switching between the two at each jet:
    /// as two tapes of constant exponents, and as one tape whose exponent is a parameter
    /// component (the engine's reuse: one workspace for every step of a tape). Every jet is the
    /// jet of a fresh workspace bit for bit and contains the 512-bit binomial series
    /// y_{k+1} = s^(k+1)·C(q, k)·|x₀|^(q−k)/(k + 1) (s^k for |x|^q; s = sign x₀). The bases
    /// x₀ = ±2⁻¹²⁰⁰·(1 + j/8) lie below f64's range: their f64 bounds (0 and ±2⁻¹⁰⁷⁴) are not
    /// thin, so the jet of the point takes the power recurrence with the table (over a box the
    /// box's width would hide 2⁻⁶⁰), and its coefficients are tight to ~2⁻²⁴⁰ relative. With
    /// the table keyed by the f64 bounds the second exponent's jets missed the series.
    #[test]
    fn a_reused_workspace_makes_the_factor_table_of_each_exponent() {
        use crate::arith::mpfr::Mpi;
        type M = Mpi<256>;
        type W = Mpi<512>;
        let q = [
            M::parse_decimal("1.31").unwrap(),
            M::parse_decimal("1.31").unwrap() + M::from_exact_f64(2f64.powi(-60)),
        ];
        assert_eq!(
            (q[0].lo(), q[0].hi()),
            (q[1].lo(), q[1].hi()),
            "equal f64 bounds"
        );
        assert!(!q[0].identical(&q[1]) && q[0].identical(&q[0].clone()));
        let qw = [
            W::parse_decimal("1.31").unwrap(),
            W::parse_decimal("1.31").unwrap() + W::from_exact_f64(2f64.powi(-60)),
        ];
        // y′ = the power of x with exponent `q` (None: the parameter component 2), x′ = 1
        let range = Mpi::hull(&q[0], &q[1]);
        let toy = |q: Option<&M>, signed: bool| {
            let range = q.is_none().then(|| range.clone());
            Tape::<M, 3>::record_with([None, None, range], |v| {
                let e = q.map_or_else(|| v[2].clone(), |q| Rec::constant(q.clone()));
                let p = if signed {
                    Real::spow(&v[0], &e)
                } else {
                    Real::apow(&v[0], &e)
                };
                vec![Rec::constant(M::one()), p, Rec::constant(M::zero())]
            })
        };
        // y_0..y_8 at 512 bits
        let series = |x0: &W, q: &W, signed: bool| -> Vec<W> {
            let s = x0.sign().unwrap();
            let a = Real::abs(x0);
            let (mut binomial, mut a_k) = (W::one(), W::one());
            let mut y = vec![W::zero()];
            for k in 0..8_i64 {
                let signs = if (k + i64::from(signed)) % 2 == 1 {
                    s
                } else {
                    1
                };
                let u = binomial.clone() * Real::apow(&a, q) / a_k.clone();
                y.push(u.mul_int(i64::from(signs)).div_int(k + 1));
                binomial = binomial * (q.clone() - W::from_int(k)) / W::from_int(k + 1);
                a_k = a_k * a.clone();
            }
            y
        };
        let tiny = 2f64.powi(-600);
        for signed in [true, false] {
            let consts = [toy(Some(&q[0]), signed), toy(Some(&q[1]), signed)];
            let param = toy(None, signed);
            assert_eq!(consts[0].ops(), consts[1].ops(), "one shape");
            let (mut ws, mut ws_param) = (Workspace::default(), Workspace::default());
            for (n, (j, s)) in [(0, 1.0), (3, -1.0), (7, 1.0), (1, -1.0)]
                .iter()
                .enumerate()
            {
                let m = tiny * (1.0 + f64::from(*j) / 8.0) * s;
                let x0 = M::from_exact_f64(tiny) * M::from_exact_f64(m);
                let x0w = W::from_exact_f64(tiny) * W::from_exact_f64(m);
                assert_eq!((x0.lo() == 0.0, x0.hi() == 0.0), (*s > 0.0, *s < 0.0));
                // the exponent switches at every jet, in both orders
                for i in [n % 2, 1 - n % 2] {
                    let x = [x0.clone(), M::zero(), q[i].clone()];
                    let exact = series(&x0w, &qw[i], signed);
                    for (t, ws) in [(&consts[i], &mut ws), (&param, &mut ws_param)] {
                        let a = t.jet(&x, 8, ws).unwrap();
                        let b = t.jet(&x, 8, &mut Workspace::default()).unwrap();
                        for k in 0..=8 {
                            let (a, b, e) = (&a[1][k], &b[1][k], &exact[k]);
                            let what =
                                format!("q{i}, x₀ = 2⁻⁶⁰⁰·{m:e}, signed {signed}, order {k}");
                            assert!(
                                a.inf() <= e.inf() && e.sup() <= a.sup(),
                                "{what}: {a} vs {e}"
                            );
                            assert!(a.inf() == b.inf() && a.sup() == b.sup(), "{what}: reused");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn switching_components_and_branch_points_are_found() {
        let lin = Shc::<f64>::new(
            NdParams::with_admissibility(
                ModelKind::Shc,
                crate::models::Admissibility::Closed,
                0.0,
                0.0,
                0.5,
                0.0,
                1.0,
                1.0,
            )
            .unwrap(),
        );
        let tape = Tape::<f64, 3>::record(|v| lin.field(v).to_vec());
        // n = p = 1: |X| (in σ|X|^p V) and |Z| (in Γ|Z|^n V) and |V| are kinks, even with zero factors
        assert_eq!(tape.switching(), &[0, 1, 2]);
        // only |V| is a plain |·|; |X|^p, |Z|^n with p = n = 1 are powers, treated (safely) as
        // branch points
        assert_eq!(tape.kinks(), &[2]);
        let shc = Shc::<f64>::new(
            NdParams::parse(ModelKind::Shc, "1.43,-1.42,0.632,0.00715,1.31,1.27").unwrap(),
        );
        let tape = Tape::<f64, 3>::record(|v| shc.field(v).to_vec());
        // at the start X = Z = 0: the first branch met (Z's power in the Bouc–Wen rate, or X's)
        let e = tape.jet(&[0.0, 0.0, -1.0], 5, &mut Workspace::default());
        assert!(
            matches!(e, Err(JetError::Branch { var: Some(0 | 1) })),
            "{e:?}"
        );
    }
}
