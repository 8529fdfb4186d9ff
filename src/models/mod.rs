//! Models layer: the paper's laws and collision models, each written once, generic over the
//! arithmetic ([`Scalar`]).
//!
//! - [`bwhcl`]: the Bouc–Wen–Hertz law (eq:BWHCL);
//! - [`shc`]: BWSHCCM / NDBWSHCCM (eq:BWSHCCM, eq:BWSHCCM_nd), Lyapunov function, 𝓔;
//! - [`maxwell`]: BWMCM / NDBWMCM (eq:BWMCM, eq:BWMCM_nd, eq:BWMCM_nd_output), Lyapunov, 𝓔;
//! - [`params`]: parameter sets and the admissible set 𝓟;
//! - [`scaling`]: nondimensionalization both ways and the base-parameter map 𝓟(P*, v0).

pub mod bwhcl;
pub mod hunt_crossley;
pub mod maxwell;
pub mod params;
pub mod scaling;
pub mod shc;

pub use maxwell::Maxwell;
pub use params::{Admissibility, ModelKind, NdParams, ParamError};
pub use shc::Shc;

use crate::arith::{Real, Scalar};

/// A nondimensional collision model with N states: an autonomous field f, the contact force
/// F_P, the outputs X and V, the Lyapunov function 𝒱 and the equilibrium set 𝓔.
pub trait CollisionModel<R: Real, const N: usize>: Clone + Send + Sync {
    /// Which model this is.
    const KIND: ModelKind;
    /// The state symbols, in order.
    const STATE_NAMES: [&'static str; N];
    /// Components whose sign changes are the field's switching surfaces (where |·| has a kink
    /// or |·|^q a branch point): the rigorous engine never expands across them.
    const SWITCHING: [usize; 3];

    fn params(&self) -> &NdParams<R>;
    /// The initial state of the collision (X = Z = 0, V = −1; R = Y = Z = 0, W = −1).
    fn initial_state(&self) -> [R; N];
    /// The state function f (the right-hand side of the model's equation).
    fn field<T: Scalar<R>>(&self, s: &[T; N]) -> [T; N];
    /// The contact force F_P.
    fn force<T: Scalar<R>>(&self, s: &[T; N]) -> T;
    /// The relative position X (an output for the Maxwell model).
    fn position<T: Scalar<R>>(&self, s: &[T; N]) -> T;
    /// The relative velocity V (an output for the Maxwell model).
    fn velocity<T: Scalar<R>>(&self, s: &[T; N]) -> T;
    /// The Lyapunov function 𝒱 of the model's appendix.
    fn lyapunov<T: Scalar<R>>(&self, s: &[T; N]) -> T;
    /// 𝒱̇ in the appendix's closed form (not ⟨∇𝒱, f⟩: tests compare the two).
    fn lyapunov_rate<T: Scalar<R>>(&self, s: &[T; N]) -> T;
    /// The Euclidean distance from `s` to the equilibrium set 𝓔.
    fn equilibrium_distance(&self, s: &[R; N]) -> R;
    /// A point of 𝓔 (parametrised as in the appendix: `free` are X for the SHC model, (R, Y)
    /// for the Maxwell model; unused entries are ignored).
    fn equilibrium_point(&self, free: [R; 2]) -> [R; N];
}

/// (κ/κ_c)^(1/p): the slope of 𝓔 (thm:BWSHCCM_eq, thm:BWMCM_eq).
pub(crate) fn equilibrium_slope<R: Real>(p: &NdParams<R>) -> R {
    let kc = R::one() - p.kappa.clone();
    (p.kappa.clone() / kc).pow(&(R::one() / p.p.clone()))
}

/// Distance from (a, b, c) to the line {(t, −s t, 0)} … in the (a, b) plane plus |c|: the
/// component along the direction (1, −s)/√(1+s²) is free, so the distance² is
/// (b + s a)²/(1 + s²) + c².
pub(crate) fn distance_to_slope_line<R: Real>(a: &R, b: &R, c: &R, slope: &R) -> R {
    let d = b.clone() + slope.clone() * a.clone();
    (d.clone() * d / (R::one() + slope.clone() * slope.clone()) + c.clone() * c.clone()).sqrt()
}
