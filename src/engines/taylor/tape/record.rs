//! The tape made from the model's recorded operations ([`Tape::record_with`]): common
//! subexpressions, entire powers as products, twin powers sharing one recurrence, the
//! constants in time, the switching components and kinks, and the shortcuts
//! ([`super::shortcuts`]) found on the result.

use super::powers::analytic_power;
use super::shortcuts::{NO_SIGN, integral_powers, log_leads, sign_copies};
use super::{Op, Rec, Rounding, Tape};
use crate::arith::Real;
use crate::engines::taylor::op::operands;
use crate::engines::taylor::rec::Recorder;
use std::sync::{Arc, Mutex};

/// A key identifying an operation up to its constants' values (for common subexpressions).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Key {
    Op(u8, usize, usize, u64, u64),
}

impl<R: Real, const N: usize> Tape<R, N> {
    /// Records `f` (returning the field's N components followed by any extra outputs).
    pub fn record(f: impl FnOnce(&[Rec<R>; N]) -> Vec<Rec<R>>) -> Self {
        Self::record_with(Self::no_params(), f)
    }

    /// No component is a parameter (out of [`Tape::record`], which is generic over the
    /// recorded function).
    fn no_params() -> [Option<R>; N] {
        std::array::from_fn(|_| None)
    }

    /// [`Tape::record`] of a system whose components `i` with `params[i] = Some(range)` are
    /// parameters: constant in time (their field component must be the constant 0), with
    /// values in `range` (what the model's checks on its parameters see, [`Rec`]).
    pub fn record_with(
        params: [Option<R>; N],
        f: impl FnOnce(&[Rec<R>; N]) -> Vec<Rec<R>>,
    ) -> Self {
        let (rec, vars) = Self::recorder(params);
        let outs = f(&vars);
        Self::from_recording(rec, vars, outs)
    }

    /// A fresh recorder and its N variables (out of [`Tape::record_with`], which is generic over
    /// the recorded function: this is compiled once per arithmetic and dimension).
    fn recorder(params: [Option<R>; N]) -> (Arc<Mutex<Recorder<R>>>, [Rec<R>; N]) {
        let rec = Arc::new(Mutex::new(Recorder {
            ops: Vec::new(),
            consts: Vec::new(),
            tconst: Vec::new(),
        }));
        let mut params = params.into_iter();
        let vars: [Rec<R>; N] = std::array::from_fn(|i| Rec::var(&rec, i, params.next().flatten()));
        (rec, vars)
    }

    /// The tape from a recording: `vars` are the recorder's variables, `outs` the recorded
    /// function's outputs (the rest of [`Tape::record_with`], compiled once per arithmetic and
    /// dimension).
    fn from_recording(rec: Arc<Mutex<Recorder<R>>>, vars: [Rec<R>; N], outs: Vec<Rec<R>>) -> Self {
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
            second_order: None,
        }
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

/// A recorded operation's origin: (kind, its operands' origins, its constant: (exact point?,
/// the point's bits or the constant's index, 0) — see [`Tape::record_with`]).
type OriginKey = (u8, [u32; 2], (bool, u64, u64));

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
