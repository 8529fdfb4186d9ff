//! Engines layer: the integrators.
//!
//! - [`dop853`]: Hairer's Dormand–Prince 8(5,3) in f64 with dense output (fast);
//! - [`taylor`]: the rigorous interval Taylor integrator (proved enclosures);
//! - [`cancel`]: the request to stop running computations (Ctrl-C in Python) both poll.

pub mod cancel;
pub mod dop853;
pub mod taylor;
