//! Arithmetic layer: the number traits and their implementations.
//!
//! - [`real`]: the coefficient fields (`f64`, inari intervals) and the [`Real`] trait;
//! - [`scalar`]: the [`Scalar`] trait the models are written against;
//! - [`interval`]: inari `Interval` as a `Real`, exact enclosure of decimal input;
//! - [`series`]: truncated Taylor series over any `Real`;
//! - [`dual`]: forward-mode dual numbers (gradients, Jacobians).

pub mod dual;
pub mod elementary;
pub mod interval;
pub mod real;
pub mod scalar;
pub mod series;

pub use real::Real;
pub use scalar::Scalar;
