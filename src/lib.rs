//! # bwcl — verified numerics for the Bouc–Wen collision laws
//!
//! The models of Milehins & Marghitu, *The Bouc–Wen Model for Binary Direct Collinear Collisions
//! of Convex Viscoplastic Bodies* (the BWSHCCM and the BWMCM, nondimensional forms
//! NDBWSHCCM and NDBWMCM), with a fast f64 DOP853 engine and a rigorous interval Taylor engine
//! for the separation time T_s and the coefficient of restitution e.
//!
//! Layers (each uses only those above it):
//! - [`arith`]: number traits, intervals, Taylor series, dual numbers;
//! - [`models`]: the paper's laws and models, written once, generic over the arithmetic;
//! - [`engines`]: the f64 DOP853 integrator and the rigorous Taylor integrator;
//! - [`observables`]: T_s, e, trajectories and hysteresis loops;
//! - [`fit`], [`identify`]: the inverse problem (fits, their uncertainty, proved feasible sets);
//! - [`cli`]: the `bwcl` program (its parsers, checks, commands and rows), which the Python
//!   bindings reuse.

// the CLI's files name the library `bwcl::…`, as the program and the bindings did when each
// compiled them
extern crate self as bwcl;

pub mod arith;
// Left out of the unit tests' build: the CLI has no unit tests, no other module uses it, and
// tests/ runs it as a program (a quarter of that build's CPU time; issue #34, the test command).
#[cfg(not(test))]
pub mod cli;
pub mod engines;
pub mod fit;
pub mod identify;
pub mod models;
pub mod observables;

// The Python bindings (src/python/) are the crate `bwcl-python` (bindings/Cargo.toml): they
// link this library as built for the tests. The CLI is compiled here once, for the program
// and the bindings both, with the engines' generic code it uses (each of them compiled it,
// and that code, anew: issue #34, the test command's time).
