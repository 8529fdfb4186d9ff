//! Arithmetic layer: the number traits at the root, one folder per family of numbers.
//!
//! | where | what | used by |
//! |---|---|---|
//! | [`real`], [`scalar`], [`enclosure`] | the traits: [`Real`] (a coefficient field, with its [`Exponent`] and [`Dot`] accumulator), [`Scalar`] (what the models are written against) and [`Enclosure`] (an interval type the rigorous engine runs on) | everything |
//! | [`float`] | `f64` as a `Real`, powers by tables ([`float::fastpow`]) | the f64 DOP853 engine |
//! | [`interval`] | inari intervals as a `Real`, exact enclosure of decimal input, ulp kernels ([`interval::ulp`]), sums of products ([`interval::dot`]), exp/ln/pow ([`interval::elementary`]) | the rigorous engine |
//! | [`mpfr`] | intervals over MPFR floats at a precision fixed by the type (`Mpi<BITS>`), as a `Real` and an `Enclosure` | the rigorous engine at `--digits D` |
//! | [`jet`] | truncated Taylor series ([`jet::series`]) and dual numbers ([`jet::dual`]) over any `Real` | the rigorous engine's jets and Jacobians, sensitivities, tests |
//!
//! Imports go downwards only: the families import the root traits, never each other's
//! internals (an interval's `Real` powers are inari's; the jets are generic).

pub mod enclosure;
pub mod float;
pub mod interval;
pub mod jet;
pub mod mpfr;
pub mod real;
pub mod scalar;

pub use enclosure::Enclosure;
pub use real::{Dot, Exponent, PlainDot, Real};
pub use scalar::Scalar;
