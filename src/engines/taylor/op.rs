//! The operations of a tape: what [`super::rec`] records, [`super::linear`] fuses and
//! [`super::tape`] replays — the instruction set the three share, below all of them.

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
    /// so only one recurrence is run (set up by [`Tape::record`](super::tape::Tape::record)).
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
    /// exponent; its interval value is bounded where w reaches 0
    /// ([`Real::pow_ln`](crate::arith::Real::pow_ln)).
    PowLn(usize, usize),
    /// A fused chain of linear operations c₀ + Σ cⱼ·x_{nⱼ} (index into the tape's forms; see
    /// [`super::linear`]): made by [`Tape::fused`](super::tape::Tape::fused), never recorded.
    Lin(usize),
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
