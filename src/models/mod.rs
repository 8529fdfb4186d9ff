//! Models layer: the paper's laws and collision models, each written once, generic over the
//! arithmetic ([`Scalar`]).
//!
//! - [`bwhcl`]: the Bouc–Wen–Hertz law (eq:BWHCL);
//! - [`shc`]: BWSHCCM / NDBWSHCCM (eq:BWSHCCM, eq:BWSHCCM_nd), Lyapunov function, 𝓔;
//! - [`maxwell`]: BWMCM / NDBWMCM (eq:BWMCM, eq:BWMCM_nd, eq:BWMCM_nd_output), Lyapunov, 𝓔;
//! - [`hunt_crossley`]: the classical Simon–Hunt–Crossley law (Hertz and Hooke as its special
//!   cases), its published damping formulas and its exact restitution relation;
//! - [`kelvin_voigt`]: the linear Kelvin–Voigt law;
//! - [`linear_maxwell`]: the linear Maxwell law;
//! - [`classical`]: the classical laws' parameters (nondimensional, base or physical) and
//!   the model each gives at an impact speed;
//! - [`params`]: parameter sets and the admissible set 𝓟;
//! - [`scaling`]: nondimensionalization both ways and the base-parameter map 𝓟(P*, v0).

pub mod bwhcl;
pub mod classical;
pub mod hunt_crossley;
pub mod kelvin_voigt;
pub mod linear_maxwell;
pub mod maxwell;
pub mod params;
pub mod scaling;
pub mod shc;

pub use maxwell::Maxwell;
pub use params::{Admissibility, ModelKind, NdParams, ParamError};
pub use shc::Shc;

use crate::arith::{Real, Scalar};

/// A nondimensional collision model with N states: an autonomous field f from an initial
/// state, the contact force F and the outputs X and V — what the engines integrate and what
/// T_s = inf{T ≥ 0 : F ≤ 0 ∧ V ≥ 0} and e = V(T_s) are read from. The Bouc–Wen models add their
/// parameters, Lyapunov function and equilibrium set ([`BoucWenModel`]); the classical laws
/// ([`hunt_crossley`], [`kelvin_voigt`], [`linear_maxwell`]) are collision models only.
pub trait CollisionModel<R: Real, const N: usize>: Clone + Send + Sync {
    /// The model's name in output (as in the CLI: "shc", "maxwell", "hunt-crossley", …).
    const NAME: &'static str;
    /// The state symbols, in order.
    const STATE_NAMES: [&'static str; N];

    /// The initial state of the collision (the contact starts at X = 0 with V = −1).
    fn initial_state(&self) -> [R; N];
    /// The state function f (the right-hand side of the model's equation).
    fn field<T: Scalar<R>>(&self, s: &[T; N]) -> [T; N];
    /// The contact force F.
    fn force<T: Scalar<R>>(&self, s: &[T; N]) -> T;
    /// The relative position X (an output for the Maxwell model).
    fn position<T: Scalar<R>>(&self, s: &[T; N]) -> T;
    /// The relative velocity V (an output for the Maxwell model).
    fn velocity<T: Scalar<R>>(&self, s: &[T; N]) -> T;
    /// Why the separation condition F ≤ 0 ∧ V ≥ 0 never holds (T_s = +∞), proved from a closed
    /// form for every value of the parameters' enclosures; `None` where no such proof is known.
    /// The engines then report no separation without integrating the condition, whose F can
    /// decay to the rounding level (the linear Maxwell law with c̃ ≤ 1/2).
    fn never_separates(&self) -> Option<&'static str> {
        None
    }
}

/// A law whose contact force depends on the relative motion alone (no internal state): states
/// (X, V), X′ = V, V′ = F(X, V) from X = 0, V = −1 — Hooke, Hertz, Hunt–Crossley, linear
/// Kelvin–Voigt. Each such law gives only F; this is its [`CollisionModel`].
pub trait ForceLaw<R: Real>: Clone + Send + Sync {
    /// The law's name in output.
    const NAME: &'static str;
    /// The contact force F(X, V).
    fn force_xv<T: Scalar<R>>(&self, x: &T, v: &T) -> T;
}

impl<R: Real, L: ForceLaw<R>> CollisionModel<R, 2> for L {
    const NAME: &'static str = L::NAME;
    const STATE_NAMES: [&'static str; 2] = ["X", "V"];

    fn initial_state(&self) -> [R; 2] {
        [R::zero(), -R::one()]
    }

    fn field<T: Scalar<R>>(&self, s: &[T; 2]) -> [T; 2] {
        [s[1].clone(), self.force(s)]
    }

    fn force<T: Scalar<R>>(&self, s: &[T; 2]) -> T {
        self.force_xv(&s[0], &s[1])
    }

    fn position<T: Scalar<R>>(&self, s: &[T; 2]) -> T {
        s[0].clone()
    }

    fn velocity<T: Scalar<R>>(&self, s: &[T; 2]) -> T {
        s[1].clone()
    }
}

/// The paper's two Bouc–Wen collision models: a [`CollisionModel`] with the parameter set P,
/// the Lyapunov function 𝒱 of its appendix and its equilibrium set 𝓔.
pub trait BoucWenModel<R: Real, const N: usize>: CollisionModel<R, N> {
    /// Which model this is.
    const KIND: ModelKind;

    fn params(&self) -> &NdParams<R>;
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
