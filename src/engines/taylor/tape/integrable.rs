//! The field's integrable singular terms: the powers |w|^r (and sgn(w)|w|^r) of a state
//! component w with a constant exponent r < 0, which a second variational system has where the
//! model has |w|^q with 1 < q < 2 (∂²/∂w² of |Z|^n is n(n−1)|Z|^(n−2), eq:BWHCL). They are
//! unbounded where w = 0 but integrable along a path crossing it (r > −1), and the field is
//! affine in them: what [`crate::engines::taylor::integrable`] needs to bound a step across
//! w = 0, found on the tape (no trust in how the model was written).

use super::{Op, Tape};
use crate::arith::Real;
use crate::engines::taylor::op::operands;

/// A power node |w|^r or sgn(w)|w|^r with w the state component `var` and the constant r < 0.
#[derive(Clone, Debug)]
pub struct NegativePower<R> {
    pub node: usize,
    pub var: usize,
    pub r: R,
    pub signed: bool,
}

/// How a field component depends on a set of nodes ([`Tape::field_degrees`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Degree {
    /// Free of them.
    Free,
    /// Affine in each of them, with no product of two.
    Affine,
    /// Anything else (a product of two, a function of one).
    Other,
}

impl<R: Real, const N: usize> Tape<R, N> {
    /// The power nodes of a state component whose constant exponent is negative for all its
    /// values (recorded as |w|^(q−1)w or |w|^q with q − 1 < 0 or q < 0).
    pub fn negative_powers(&self) -> Vec<NegativePower<R>> {
        self.ops
            .iter()
            .enumerate()
            .filter_map(|(node, op)| {
                let (a, q, signed) = match *op {
                    Op::Spow(a, q) => (a, q, true),
                    Op::Apow(a, q) => (a, q, false),
                    Op::Twin(a, q, _, s) => (a, q, s),
                    _ => return None,
                };
                let r = self.consts[q].clone();
                match self.ops[a] {
                    Op::Var(var) if r.hi() < 0.0 => Some(NegativePower {
                        node,
                        var,
                        r,
                        signed,
                    }),
                    _ => None,
                }
            })
            .collect()
    }

    /// A node of a state component w whose value jumps where w = 0 (a power of exponent 0) or
    /// whose exponent is not known to be away from 0 (a variable exponent), w not a kink: the
    /// field's derivative there has a jump that neither the kinks' formula nor
    /// [`Tape::sign_jumps`] carries — a second variational system cannot cross it. Returns the
    /// component.
    pub fn jump_off_the_kinks(&self) -> Option<usize> {
        let var = |a: usize| match self.ops[a] {
            Op::Var(j) => Some(j),
            _ => None,
        };
        self.ops.iter().find_map(|op| {
            let j = match *op {
                Op::Spow(a, q) | Op::Apow(a, q) | Op::Twin(a, q, _, _) => {
                    let r = &self.consts[q];
                    var(a).filter(|_| r.lo() <= 0.0 && r.hi() >= 0.0)
                }
                Op::SpowV(a, _) | Op::ApowV(a, _) | Op::LnAbs(a) => var(a),
                _ => None,
            }?;
            (!self.kinks.contains(&j)).then_some(j)
        })
    }

    /// A node that switches on an expression varying in time rather than on a state component:
    /// |g|, sgn g, a non-entire power or ln|g| of a g that is neither a state component nor
    /// constant in time. The first-order steps stay sound there (a Taylor step never expands
    /// across a switch: its jet over a box where g may reach 0 fails, and the low-order steps
    /// only evaluate f), but the jumps of S₂ where g crosses 0 — which
    /// [`crate::engines::taylor::integrable::kink_jump`] and [`Tape::sign_jumps`] carry for
    /// state components only — would be missed: a second variational system must refuse it.
    /// `None` for the shipped models (every switch is on X, Z, V, Y or W).
    pub fn switch_on_an_expression(&self) -> Option<usize> {
        self.ops.iter().enumerate().find_map(|(i, op)| {
            let a = match *op {
                Op::Abs(a) | Op::Sign(a) | Op::SpowV(a, _) | Op::ApowV(a, _) | Op::LnAbs(a) => a,
                Op::Spow(a, q) | Op::Twin(a, q, _, true)
                    if !super::analytic_power(&self.consts[q], true) =>
                {
                    a
                }
                Op::Apow(a, q) | Op::Twin(a, q, _, false)
                    if !super::analytic_power(&self.consts[q], false) =>
                {
                    a
                }
                _ => return None,
            };
            (!self.tconst[a] && !matches!(self.ops[a], Op::Var(_))).then_some(i)
        })
    }

    /// The state components w, not kinks, of which the tape takes sgn(w) in D_x f: the
    /// derivative of |w| (eq:BWHCL's |Z|^n with n = 1) in a second variational system (with
    /// its layout, the sgn nodes that reach the rates of S; a sgn in D²f only, e.g. of
    /// |X|·X with p = 2, makes no jump of S₂). Where w crosses 0 there, S₂ jumps as at a kink
    /// ([`crate::engines::taylor::integrable::kink_jump`], the jump evaluated at w = 0);
    /// `(components, nodes)`.
    pub fn sign_jumps(&self) -> (Vec<usize>, Vec<usize>) {
        let (mut comps, mut nodes) = (Vec::new(), Vec::new());
        let in_df = |i: usize| match self.second_order {
            Some(lay) => self.reaches(i, (0..lay.n).map(|c| lay.s(c))),
            None => true,
        };
        for (i, j) in self.signs_of_state() {
            if !self.kinks.contains(&j) && in_df(i) {
                nodes.push(i);
                if !comps.contains(&j) {
                    comps.push(j);
                }
            }
        }
        comps.sort_unstable();
        (comps, nodes)
    }

    /// A state component, kink or not, whose sign enters the rates of the first `n` state
    /// components themselves (not only their derivatives): the field jumps there, and the
    /// jump of S₂ ([`crate::engines::taylor::integrable::kink_jump`]) assumes a continuous
    /// field. `None` when every sgn enters the derivatives only (|V|, |Z|^n with n = 1).
    pub fn sign_in_the_rates(&self, n: usize) -> Option<usize> {
        self.signs_of_state()
            .find_map(|(i, j)| self.reaches(i, 0..n.min(N)).then_some(j))
    }

    /// The nodes sgn(x_j) of a state component x_j: (node, j).
    fn signs_of_state(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.ops.iter().enumerate().filter_map(|(i, op)| match *op {
            Op::Sign(a) => match self.ops[a] {
                Op::Var(j) => Some((i, j)),
                _ => None,
            },
            _ => None,
        })
    }

    /// Whether node `i` enters one of the field components `outputs`.
    fn reaches(&self, i: usize, mut outputs: impl Iterator<Item = usize>) -> bool {
        let degs = self.field_degrees(&[i]);
        outputs.any(|c| degs[c] != Degree::Free)
    }

    /// Per field component, how it depends on `nodes`: [`Degree::Affine`] only through sums,
    /// differences, constant multiples, fused linear forms, products with factors free of
    /// them and quotients by divisors free of them.
    pub fn field_degrees(&self, nodes: &[usize]) -> [Degree; N] {
        use Degree::*;
        let mut deg = vec![Free; self.ops.len()];
        for (i, op) in self.ops.iter().enumerate() {
            deg[i] = if nodes.contains(&i) {
                Affine
            } else {
                match *op {
                    Op::Var(_) | Op::Const(_) => Free,
                    Op::Add(a, b) | Op::Sub(a, b) => deg[a].max(deg[b]),
                    Op::Mul(a, b) => match (deg[a], deg[b]) {
                        (Free, d) | (d, Free) => d,
                        _ => Other,
                    },
                    Op::Div(a, b) => match deg[b] {
                        Free => deg[a],
                        _ => Other,
                    },
                    Op::Neg(a) | Op::Scale(a, _) | Op::Shift(a, _) => deg[a],
                    Op::Lin(l) => self.lins[l]
                        .terms
                        .iter()
                        .map(|&(_, n)| deg[n])
                        .max()
                        .unwrap_or(Free),
                    // a twin power is computed from its pair's value
                    Op::Twin(a, _, j, _) => {
                        if deg[a] == Free && deg[j] == Free {
                            Free
                        } else {
                            Other
                        }
                    }
                    ref op => {
                        if operands(op).all(|a| deg[a] == Free) {
                            Free
                        } else {
                            Other
                        }
                    }
                }
            };
        }
        std::array::from_fn(|i| deg[self.outputs[i]])
    }

    /// The field at `x` with the values of the nodes in `repl` replaced (kinks continued from
    /// `side`).
    pub fn field_replacing(&self, x: &[R; N], side: &[i8; N], repl: &[(usize, R)]) -> [R; N] {
        let mut v: Vec<R> = Vec::with_capacity(self.ops.len());
        for (i, op) in self.ops.iter().enumerate() {
            let val = match repl.iter().find(|(n, _)| *n == i) {
                Some((_, r)) => r.clone(),
                None => self.op_value(op, |a| &v[a], x, side),
            };
            v.push(val);
        }
        std::array::from_fn(|i| v[self.outputs[i]].clone())
    }
}
