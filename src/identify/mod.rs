//! Set-membership identification (issue #31): which base sets P* are consistent with collision
//! data known to within errors, *proved*.
//!
//! ```text
//! F = {P* ∈ box ∩ 𝓟 : |e(𝓟(P*, v0_i)) − e_i| ≤ E_i  (and |tc(P*, v0_i) − tc_i| ≤ T_i) for every i}
//! ```
//!
//! is paved into boxes proved feasible (every constraint holds on the whole box), proved
//! infeasible (no point of the box satisfies every constraint) and undecided at the resolution.
//! The outer hull of F per parameter ("every P* consistent with the data has κ ∈ [a, b]") is the
//! hull of the boxes not proved infeasible; an F proved empty is a certificate that the model is
//! falsified by the data at that error.
//!
//! - [`problem`]: the constraints, the data's decimals enclosed;
//! - [`form`]: mean-value forms over boxes from proved slopes, and the contractor they give;
//! - [`guide`]: f64 guesses of which rows a rigorous attempt can decide on a box;
//! - [`paving`]: the work queue (SIVIA with contractors, in parallel);
//! - [`sample`]: an f64 inner estimate of F's hull (sampled feasible points, not proved).

pub mod form;
pub mod guide;
pub mod laws;
pub mod paving;
pub mod problem;
pub mod sample;
pub mod setup;

pub use paving::{Leaf, Options, Paving, Progress, Status, pave};
pub use problem::{Problem, Row, Target};
