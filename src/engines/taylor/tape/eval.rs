//! The outputs' values at a point or over a box (an order-0 replay of the tape), the field
//! continued across kinks from a side; only the nodes the extra outputs need, for those.

use super::{Op, Tape};
use crate::arith::Real;
use crate::engines::taylor::op::operands;

impl<R: Real, const N: usize> Tape<R, N> {
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
    pub(super) fn op_value<'a>(
        &self,
        op: &Op,
        v: impl Fn(usize) -> &'a R,
        x: &[R; N],
        side: &[i8; N],
    ) -> R
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
}
