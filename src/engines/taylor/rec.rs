//! The recording number type of the tape: each operation on a [`Rec`] appends to the tape.
//!
//! A `Rec` is either a constant (no tape yet: constants fold at once) or a node of a tape. It is
//! a [`Scalar`] over the coefficient field R (the models' parameters as constants, as for a
//! point parameter set) and itself a [`Real`], so a model can be built with `Rec` parameters:
//! a parameter given as a range becomes a variable of the tape (a state component with
//! ṗ = 0), and everything the model computes from it (κ_c = 1 − κ, 𝓟(P*, v0), the exponents
//! n and p) is recorded with it — the model stays written once.
//!
//! Each node carries `val`, an enclosure of its value where it is known without the state (a
//! constant, a parameter's range and what is computed from them; every real for what depends
//! on the state). `lo`, `hi` and so `sign`, `as_integer` read it: a model's checks on its
//! parameters (𝓟, the analytic integer exponents) see the whole range.
//!
//! Nodes that depend only on constants and parameters are *constant in time*: the tape expands
//! them as constants (their value at order 0, zeros above). `pow`, `ln` and `sqrt` are only
//! recorded on such nodes (the models use them on parameters only).

use super::op::Op;
use crate::arith::Dot;
use crate::arith::{Real, Scalar};
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::sync::{Arc, Mutex};

#[derive(Debug, Default)]
pub(super) struct Recorder<R> {
    pub ops: Vec<Op>,
    pub consts: Vec<R>,
    /// Per op: constant in time (depends only on constants and parameter variables).
    pub tconst: Vec<bool>,
}

/// The recording number type (see the module doc).
#[derive(Clone, Debug)]
pub struct Rec<R> {
    tape: Option<Arc<Mutex<Recorder<R>>>>,
    pub(super) idx: usize,
    val: R,
}

impl<R: Real> Rec<R> {
    /// A constant (on no tape until it meets a node).
    pub fn constant(c: R) -> Self {
        Self {
            tape: None,
            idx: usize::MAX,
            val: c,
        }
    }

    pub(super) fn var(tape: &Arc<Mutex<Recorder<R>>>, i: usize, val: Option<R>) -> Self {
        let mut t = tape.lock().expect("tape");
        t.ops.push(Op::Var(i));
        t.tconst.push(val.is_some());
        Self {
            tape: Some(tape.clone()),
            idx: t.ops.len() - 1,
            val: val.unwrap_or_else(R::unbounded),
        }
    }

    /// True for a constant (not a node).
    pub fn is_constant(&self) -> bool {
        self.tape.is_none()
    }

    /// The enclosure of the value known without the state (see the module doc).
    pub fn value(&self) -> &R {
        &self.val
    }

    /// This value as a node of `tape` (a constant is recorded as an [`Op::Const`]).
    pub(super) fn node_on(&self, tape: &Arc<Mutex<Recorder<R>>>) -> usize {
        match &self.tape {
            Some(_) => self.idx,
            None => {
                let mut t = tape.lock().expect("tape");
                t.consts.push(self.val.clone());
                let ci = t.consts.len() - 1;
                t.ops.push(Op::Const(ci));
                t.tconst.push(true);
                t.ops.len() - 1
            }
        }
    }

    fn push(tape: &Arc<Mutex<Recorder<R>>>, op: Op, tconst: bool, val: R) -> Self {
        let mut t = tape.lock().expect("tape");
        t.ops.push(op);
        t.tconst.push(tconst);
        Self {
            tape: Some(tape.clone()),
            idx: t.ops.len() - 1,
            val,
        }
    }

    fn push_const(tape: &Arc<Mutex<Recorder<R>>>, c: &R) -> usize {
        let mut t = tape.lock().expect("tape");
        t.consts.push(c.clone());
        t.consts.len() - 1
    }

    fn tconst(tape: &Arc<Mutex<Recorder<R>>>, i: usize) -> bool {
        tape.lock().expect("tape").tconst[i]
    }

    /// A unary operation: folded on a constant, recorded on a node.
    fn unary(&self, op: impl FnOnce(usize) -> Op, f: impl FnOnce(&R) -> R) -> Self {
        let val = f(&self.val);
        match &self.tape {
            None => Self::constant(val),
            Some(t) => {
                let tc = Self::tconst(t, self.idx);
                Self::push(t, op(self.idx), tc, val)
            }
        }
    }

    /// A unary operation that only parameters may take (`pow`, `ln`, `sqrt`).
    fn unary_param(&self, op: impl FnOnce(usize) -> Op, f: impl FnOnce(&R) -> R) -> Self {
        if let Some(t) = &self.tape {
            assert!(
                Self::tconst(t, self.idx),
                "the tape records pow, ln and sqrt only of parameters, not of the state"
            );
        }
        self.unary(op, f)
    }

    /// A binary operation: both constants fold; a constant operand of a node uses the
    /// operation's constant form (`with_const`, the constant's index, node first) where there
    /// is one, else it is recorded as a constant node.
    fn binary(
        a: &Self,
        b: &Self,
        f: impl FnOnce(&R, &R) -> R,
        nodes: impl FnOnce(usize, usize) -> Op,
        with_const: impl FnOnce(&Arc<Mutex<Recorder<R>>>, usize, &R, bool) -> Option<Op>,
    ) -> Self {
        let val = f(&a.val, &b.val);
        let tape = match (&a.tape, &b.tape) {
            (None, None) => return Self::constant(val),
            (Some(t), _) | (None, Some(t)) => t.clone(),
        };
        // node op constant (`false`) or constant op node (`true`)
        let special = match (&a.tape, &b.tape) {
            (Some(_), None) => with_const(&tape, a.idx, &b.val, false),
            (None, Some(_)) => with_const(&tape, b.idx, &a.val, true),
            _ => None,
        };
        let op = match special {
            Some(op) => op,
            None => nodes(a.node_on(&tape), b.node_on(&tape)),
        };
        let tc = {
            let t = tape.lock().expect("tape");
            match op {
                Op::Add(x, y) | Op::Sub(x, y) | Op::Mul(x, y) | Op::Div(x, y) => {
                    t.tconst[x] && t.tconst[y]
                }
                Op::Scale(x, _) | Op::Shift(x, _) | Op::Neg(x) => t.tconst[x],
                Op::Pow(x, y) | Op::SpowV(x, y) | Op::ApowV(x, y) => t.tconst[x] && t.tconst[y],
                Op::Spow(x, _) | Op::Apow(x, _) => t.tconst[x],
                _ => false,
            }
        };
        if matches!(op, Op::Pow(..)) {
            assert!(
                tc,
                "the tape records pow only of parameters, not of the state"
            );
        }
        Self::push(&tape, op, tc, val)
    }
}

impl<R: Real> Add for Rec<R> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::binary(
            &self,
            &o,
            |a, b| a.clone() + b.clone(),
            Op::Add,
            |t, n, c, _| Some(Op::Shift(n, Self::push_const(t, c))),
        )
    }
}

impl<R: Real> Sub for Rec<R> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        if self.tape.is_none() && o.tape.is_some() {
            // c − x = (−x) + c
            return self + (-o);
        }
        Self::binary(
            &self,
            &o,
            |a, b| a.clone() - b.clone(),
            Op::Sub,
            |t, n, c, _| Some(Op::Shift(n, Self::push_const(t, &-c.clone()))),
        )
    }
}

impl<R: Real> Mul for Rec<R> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self::binary(
            &self,
            &o,
            |a, b| a.clone() * b.clone(),
            Op::Mul,
            |t, n, c, _| Some(Op::Scale(n, Self::push_const(t, c))),
        )
    }
}

impl<R: Real> Div for Rec<R> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        Self::binary(
            &self,
            &o,
            |a, b| a.clone() / b.clone(),
            Op::Div,
            // x / c = x·(1/c), 1/c enclosed in R; c / x is a quotient of nodes
            |t, n, c, const_first| {
                (!const_first).then(|| Op::Scale(n, Self::push_const(t, &(R::one() / c.clone()))))
            },
        )
    }
}

impl<R: Real> Neg for Rec<R> {
    type Output = Self;
    fn neg(self) -> Self {
        self.unary(Op::Neg, |v| -v.clone())
    }
}

/// The models' parameters as constants of the tape (a point parameter set).
impl<R: Real> Scalar<R> for Rec<R> {
    fn scale(&self, c: &R) -> Self {
        self.clone() * Self::constant(c.clone())
    }
    fn shift(&self, c: &R) -> Self {
        self.clone() + Self::constant(c.clone())
    }
    fn abs(&self) -> Self {
        Real::abs(self)
    }
    fn spow(&self, q: &R) -> Self {
        Real::spow(self, &Self::constant(q.clone()))
    }
    fn apow(&self, q: &R) -> Self {
        Real::apow(self, &Self::constant(q.clone()))
    }
    /// Both powers on one recorded constant: the tape then knows that they have one exponent,
    /// not only two equal enclosures of it ([`super::tape::Tape`]'s merged pairs need that).
    fn spow_apow(&self, q: &R) -> (Self, Self) {
        let (s, a) = (Real::spow(&self.val, q), Real::apow(&self.val, q));
        match &self.tape {
            None => (Self::constant(s), Self::constant(a)),
            Some(t) => {
                let c = Self::push_const(t, q);
                let tc = Self::tconst(t, self.idx);
                (
                    Self::push(t, Op::Spow(self.idx, c), tc, s),
                    Self::push(t, Op::Apow(self.idx, c), tc, a),
                )
            }
        }
    }
}

/// Σ aⱼbⱼ recorded as products and sums.
pub struct RecDot<R>(Option<Rec<R>>);

impl<R: Real> Dot<Rec<R>> for RecDot<R> {
    fn new() -> Self {
        Self(None)
    }
    fn add_prod(&mut self, a: &Rec<R>, b: &Rec<R>) {
        let p = a.clone() * b.clone();
        self.0 = Some(match self.0.take() {
            None => p,
            Some(s) => s + p,
        });
    }
    fn sum(self) -> Rec<R> {
        self.0.unwrap_or_else(|| Rec::constant(R::zero()))
    }
}

/// The powers of a node with a constant exponent use the tape's constant forms (the same tape
/// as a point parameter set gives); with a parameter node as exponent, [`Op::SpowV`] and
/// [`Op::ApowV`].
fn power<R: Real>(
    x: &Rec<R>,
    q: &Rec<R>,
    f: impl FnOnce(&R, &R) -> R,
    with_const: fn(usize, usize) -> Op,
    nodes: fn(usize, usize) -> Op,
) -> Rec<R> {
    Rec::binary(
        x,
        q,
        f,
        nodes,
        // node^constant: the constant form; constant^node: nodes
        |t, n, c, const_first| (!const_first).then(|| with_const(n, Rec::push_const(t, c))),
    )
}

impl<R: Real> Real for Rec<R> {
    type Dot = RecDot<R>;
    type Prepared = ();
    fn prepare_exponent(_: &Self) {}
    fn from_int(k: i64) -> Self {
        Self::constant(R::from_int(k))
    }
    fn from_exact_f64(x: f64) -> Self {
        Self::constant(R::from_exact_f64(x))
    }
    fn parse_decimal(s: &str) -> Result<Self, String> {
        R::parse_decimal(s).map(Self::constant)
    }
    fn unbounded() -> Self {
        Self::constant(R::unbounded())
    }
    fn abs(&self) -> Self {
        self.unary(Op::Abs, Real::abs)
    }
    fn sqrt(&self) -> Self {
        self.unary_param(Op::Sqrt, Real::sqrt)
    }
    fn ln(&self) -> Self {
        self.unary_param(Op::Ln, Real::ln)
    }
    fn sgn(&self) -> Self {
        self.unary(Op::Sign, Real::sgn)
    }
    /// |w|^q ln|w| of a state component: [`Op::PowLn`] of the power's node and ln|w|'s (so the
    /// interval evaluation bounds it at w = 0); of parameters, the product itself.
    fn pow_ln(w: &Self, q: &Self, signed: bool) -> Self {
        let u = if signed {
            Real::spow(w, q)
        } else {
            Real::apow(w, q)
        };
        let Some(t) = w.tape.clone().filter(|t| !Self::tconst(t, w.idx)) else {
            return u * Real::ln(&Real::abs(w));
        };
        let l = Self::push(&t, Op::LnAbs(w.idx), false, R::unbounded());
        let val = R::unbounded();
        let p = u.node_on(&t);
        Self::push(&t, Op::PowLn(p, l.idx), false, val)
    }
    fn pow(&self, y: &Self) -> Self {
        Self::binary(self, y, |a, b| a.pow(b), Op::Pow, |_, _, _, _| None)
    }
    fn spow(&self, q: &Self) -> Self {
        power(self, q, |a, b| a.spow(b), Op::Spow, Op::SpowV)
    }
    fn apow(&self, q: &Self) -> Self {
        power(self, q, |a, b| a.apow(b), Op::Apow, Op::ApowV)
    }
    fn lo(&self) -> f64 {
        self.val.lo()
    }
    fn hi(&self) -> f64 {
        self.val.hi()
    }
    fn mid(&self) -> f64 {
        self.val.mid()
    }
}
