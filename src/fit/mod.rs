//! Parameter identification from CoR data (sec:ID of the paper).
//!
//! Given measured impact speeds ṽ0 ∈ ℝ_{>0}^M and CoRs ẽ ∈ [0, 1]^M, the quality of a base
//! parameter set P* ∈ ℙ* is the cost (eq:J)
//!
//! ```text
//! J(ṽ0, ẽ, P*) = sqrt( Σ_i (ẽ_i − e(𝓟(P*, ṽ0_i)))² )
//! ```
//!
//! - [`data`]: the `v0,e` CSV reader with line-numbered errors;
//! - [`cost`](mod@cost): J and the model's CoR curve, the speeds evaluated in parallel (rayon);
//! - [`reparam`]: the smooth bijection ℝ⁶ → 𝓟 (or ℝ⁵ → 𝓟 ∩ {p = 1}) that lets an
//!   unconstrained optimizer search inside the admissible set;
//! - [`space`]: which parameters are fixed and which free within bounds (`--fix`, `--bounds`);
//! - [`nelder_mead`]: the seeded multi-start Nelder–Mead minimization of J (argmin);
//! - [`weights`]: the residuals' errors (a `sigma` column, `--error`) and contact durations;
//! - [`minima`]: the end points clustered into distinct minima (hill–valley), with Δχ²;
//! - [`laws`]: the classical collision laws as one-parameter families over the speeds, and their
//!   fit (issue #33);
//! - [`criteria`]: AIC, AICc and BIC, to compare models fitted to the same data;
//! - [`chi2`]: the χ² quantile (regularized incomplete gamma function);
//! - [`uncertainty`]: Jacobian, covariance, standard errors, correlations and SVD at a fit;
//! - [`profile`]: J profiled along one parameter with the others re-optimized, and its
//!   likelihood-ratio interval.

pub mod chi2;
pub mod cost;
pub mod criteria;
pub mod data;
pub mod laws;
pub mod minima;
pub mod nelder_mead;
pub mod profile;
pub mod reparam;
pub mod space;
pub mod uncertainty;
pub mod weights;

pub use cost::{CostOptions, FitCurve, cost, model_curve};
pub use data::{CorData, DataError};
pub use nelder_mead::{FitOptions, FitResult, Progress, StartResult, fit};
pub use reparam::{Reparam, SpaceMap};
pub use weights::Weights;
