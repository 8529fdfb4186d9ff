//! Observables layer: the separation time T_s, the coefficient of restitution e, trajectories
//! and hysteresis loops, with the paper's exact definitions.
//!
//! - [`separation`]: T_s = inf{T ≥ 0 : F ≤ 0 ∧ V ≥ 0} (eq:main_t_s) and e = V(T_s)
//!   (eq:main_cor) on the f64 engine's dense output;
//! - [`trajectory`]: sampled trajectories and loops (F against X), nondimensional or physical;
//! - [`rigorous`]: proved enclosures of T_s and e from the rigorous engine;
//! - [`precision`]: the same at a chosen precision (D digits, MPFR intervals);
//! - [`decimal`]: their bounds as decimals rounded outward, exactly;
//! - [`derived`]: the peak force, the maximum indentation and the energy lost, float and
//!   proved.

pub mod band;
pub mod band_second;
pub mod curvature;
pub mod decimal;
pub mod derived;
pub mod precision;
pub mod restitution;
pub mod rigorous;
pub mod separation;
pub mod sets;
pub mod split;
pub mod trajectory;

pub use separation::{FloatOptions, Impact, ImpactError, impact};
