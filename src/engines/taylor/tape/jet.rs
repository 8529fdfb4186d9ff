//! The Taylor coefficients of the solution through a point or a box, by the recurrences of
//! the tape's operations order by order.

use super::powers::{analytic_power, branch_power, pow_node};
use super::shortcuts::NO_SIGN;
use super::{JetError, Op, Tape, Workspace};
use crate::arith::Real;
use crate::arith::jet::series::{div_k, log_k, mul_k};

impl<R: Real, const N: usize> Tape<R, N> {
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
