//! Engines layer: the integrators.
//!
//! - [`dop853`]: Hairer's Dormand–Prince 8(5,3) in f64 with dense output (fast);
//! - [`taylor`]: the rigorous interval Taylor integrator (proved enclosures).

pub mod dop853;
pub mod taylor;
