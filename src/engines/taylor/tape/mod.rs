//! A tape of the model's own operations, and Taylor coefficients computed from it.
//!
//! The model's field is evaluated once on [`Rec`] (a recording
//! [`Scalar`](crate::arith::Scalar)); the resulting list of operations is then replayed order
//! by order (the jet recurrences of [`crate::arith::jet::series`]), so the K Taylor
//! coefficients of the solution through a box cost O(K²) per operation, not O(K³) as
//! re-evaluating the field on truncated series would (TaylorIntegration.jl's `jetcoeffs`, kv's
//! psa). The model is written once: the tape is its code, run on another number type.
//!
//! The solution's coefficients follow from x′ = f(x): x_{k+1} = f(x)_k / (k + 1).
//!
//! |·| and the real powers are expanded in the sign region of their operand: an operand whose
//! constant coefficient does not have a certain sign has no expansion, and the jet fails with
//! [`JetError::Branch`] naming the component — the caller then takes a low-order step across.
//!
//! Two identities of the models' fields save sums per order (the tape finds them; the model is
//! written as before): a power |w|^(q−1)w whose derivative q|w|^(q−1)ẇ the field computes as a
//! product anyway is that product's integral (`shortcuts::integral_powers`: Maxwell's
//! |Y|^(p−1)Y and |Z|^(p−1)Z), and a product of the other power of one series with x or |x| is
//! an earlier product with a sign (`shortcuts::sign_copies`: the hysteretic rate's
//! |Z|^(n−1)Z·|V| and |Z|^n·V). Measured on the 28 Table 1 cases (2026-11-26, 3 alternating
//! runs): the integrals, Maxwell per-case time 0.908–0.956 (pieces and widths change a little:
//! the Y-jets' remainders are narrower); the sign copies, median 0.985, the same enclosures bit
//! for bit.
//!
//! A fused form that sums a product and its sign copy takes them as one term
//! (c + s·c′)·P (`merges::lin_merges`): the hysteretic rate β|V||Z|^(n−1)Z + γV|Z|^n is
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
//!
//! Files: `record.rs` (the tape made from the model's recorded operations: common
//! subexpressions, entire powers as products, twin powers, the switching components),
//! `shortcuts.rs` (what the recording finds to spare sums: integral powers, sign copies, the
//! powers' shared logarithm), `fused.rs` (the chains of linear operations fused into one form
//! each, and a form's value), `merges.rs` (a product and its sign copy as one term of a form),
//! `eval.rs` (the outputs' values at a point or over a box), `jet.rs` (the Taylor coefficients
//! by the recurrences), `powers.rs` (the real powers' recurrences and their storage). The
//! operations themselves are [`super::op`]'s, the recording number type [`super::rec`]'s.

mod eval;
mod fused;
mod integrable;
mod jet;
mod merges;
mod powers;
mod record;
mod shortcuts;
#[cfg(test)]
mod tests;

pub use super::op::Op;
pub use super::rec::Rec;
pub use integrable::{Degree, NegativePower};
pub use powers::analytic_power;

use super::linear::Lin;
use crate::arith::Real;
use powers::PowScratch;

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
    /// [`powers::pow_node`]); `None` for every other node.
    log_lead: Vec<Option<usize>>,
    /// For a power |w|^(q−1)w of a state component w whose field has the product
    /// |w|^(q′)·ẇ with q′ ∋ q − 1 (Maxwell's |Y|^(p−1)W and |Z|^(p−1)Ż, eq:BWMCM_nd): that
    /// product's node m. The power's series is then its integral (see [`Tape::jet_on`]), not a
    /// recurrence of its own; `None` for every other node.
    integral_of: Vec<Option<usize>>,
    /// For a product P′·A′ that equals an earlier product P·A up to sign — P, P′ the two
    /// powers |w|^(q−1)w, |w|^q of one series ([`Op::Twin`]), A, A′ each x or |x| for one
    /// x (the hysteretic rate's |Z|^(n−1)Z·|V| and |Z|^n·V, eq:BWHCL): (P·A's node, the
    /// nodes whose signs make the factor) — see [`shortcuts::sign_copies`]; `None` for every
    /// other node.
    sign_copy_of: Vec<Option<(usize, [usize; 2])>>,
    /// Per fused form: the pairs (j, j′) of its terms whose leaves are a product and its sign
    /// copy (the hysteretic rate's β|V||Z|^(n−1)Z + γV|Z|^n) — see [`merges::lin_merges`]; in a jet
    /// the pair is one term (c_j ± c_j′)·x.
    lin_merges: Vec<Vec<(usize, usize)>>,
    /// Per node: a sign copy whose pair a fused form may merge ([`shortcuts::sign_copies`]' second
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
    /// A second variational system's layout ([`SecondOrder`]), when the tape is one: a step
    /// across a kink adds the jump of S₂ there ([`crate::engines::taylor::integrable`]).
    second_order: Option<SecondOrder>,
}

/// The layout of a second variational system (x, u, S, S₂) for one parameter u: x the model's
/// n state components, then u, S = ∂x/∂u (n), S₂ = ∂²x/∂u² (n); D = 3n + 1 components.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SecondOrder {
    pub n: usize,
}

impl SecondOrder {
    /// The index of u.
    pub fn u(&self) -> usize {
        self.n
    }
    /// The index of S_i.
    pub fn s(&self, i: usize) -> usize {
        self.n + 1 + i
    }
    /// The index of (S₂)_i.
    pub fn s2(&self, i: usize) -> usize {
        2 * self.n + 1 + i
    }
}

/// How the tape rounds a fused linear form c₀ + Σ cⱼ·xⱼ ([`Tape::fused`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rounding {
    /// Each product and sum in turn, in the type's arithmetic (for intervals: each rounded
    /// outward, stepping only where the exact result lies outward): the chain's enclosure up
    /// to the order of its roundings (the forms distribute only constants a few ulps wide;
    /// measured on the 28 Table 1 cases: the same widths as the recorded tape).
    Each,
    /// Once: one sum of products by the type's [`Dot`](crate::arith::Dot) accumulator, with an
    /// a-priori bound of all its rounding errors ((n + 4)u of the terms' magnitudes for intervals):
    /// faster, and wider where the operands are thin — where the width is mostly rounding it can be
    /// several times the chain's (an adversarial review measured ≈ 4× at orders 2–8 of a point
    /// jet).
    Once,
}

impl<R: Real, const N: usize> Tape<R, N> {
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
            second_order: self.second_order,
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

    /// The tape marked as a second variational system with `layout` (its kink crossings then
    /// carry the jump of S₂). Panics unless the layout has N = 3n + 1 components and u is a
    /// parameter component.
    pub fn with_second_order(mut self, layout: SecondOrder) -> Self {
        assert_eq!(N, 3 * layout.n + 1, "(x, u, S, S2) has 3n + 1 components");
        assert!(self.params.contains(&layout.u()), "u is constant in time");
        self.second_order = Some(layout);
        self
    }

    /// The second variational system's layout, if the tape is one.
    pub fn second_order(&self) -> Option<SecondOrder> {
        self.second_order
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
