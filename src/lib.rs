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
//! - [`observables`]: T_s, e, trajectories and hysteresis loops.

pub mod arith;
pub mod engines;
pub mod fit;
pub mod identify;
pub mod models;
pub mod observables;

// The Python bindings (src/python/) are the crate `bwcl-python` (bindings/Cargo.toml): they
// link this library as built for the tests.
