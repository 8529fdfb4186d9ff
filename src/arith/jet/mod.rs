//! Jets over any [`Real`](super::Real): truncated Taylor series ([`series`]: the recurrences of
//! the rigorous engine's tapes) and forward-mode dual numbers ([`dual`]: gradients, Jacobians).

pub mod dual;
pub mod series;
