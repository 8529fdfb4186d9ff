//! Arithmetic layer: the number traits and their implementations.
//!
//! - [`real`]: the coefficient fields (`f64`, inari intervals) and the [`Real`] trait;
//! - [`scalar`]: the [`Scalar`] trait the models are written against;
//! - [`interval`]: inari `Interval` as a `Real`, exact enclosure of decimal input;
//! - [`series`]: truncated Taylor series over any `Real`;
//! - [`dual`]: forward-mode dual numbers (gradients, Jacobians);
//! - [`exponent`]: a model's power exponent with what its arithmetic precomputes for it;
//! - [`fastpow`]: x^q for the f64 engine by tables per exponent (low latency);
//! - [`dot`]: accumulators of sums of products (the recurrences' inner loop);
//! - [`ulp`]: interval operations by outward ulp steps (no rounding-mode switches).

pub mod dot;
pub mod dual;
pub mod elementary;
pub mod exponent;
pub mod fastpow;
pub mod interval;
pub mod mpfr;
pub mod real;
pub mod scalar;
pub mod series;
pub mod ulp;

pub use exponent::Exponent;
pub use real::Real;
pub use scalar::Scalar;
