//! The rigorous interval Taylor integrator.
//!
//! Proves enclosures of the solution of a collision model, of T_s and of e: the true value is
//! inside every printed interval, with rounding and truncation (Lagrange remainders over
//! validated a-priori enclosures) accounted for. Rounding: inari's directed rounding at the
//! boundaries; inside the jets (the hot loops) [`crate::arith::interval::ulp::Ulp`] intervals, whose
//! directed rounding comes from exact error terms (TwoSum, FMA residuals) instead of
//! rounding-mode switches, and sums of products by [`crate::arith::interval::dot`] with a proved error
//! bound; the powers' exp and ln by Horner's scheme with a running error bound
//! ([`crate::arith::interval::elementary`]).
//!
//! Files, one per stage of a step (TaylorIntegration.jl's layout): [`tape`] (the model's own
//! code recorded once, Taylor coefficients by recurrences), [`step`] (a Taylor step with a
//! high-order a-priori enclosure; a low-order step across switching surfaces), [`event`]
//! (T_s by transversality and interval Newton), [`flow`] (rigorous dense output); the loop
//! over the stages in `integrate.rs`, the options and errors in `options.rs`.
//!
//! Layering, each module using only those before it (no cycles): [`op`] (a tape's
//! operations); [`rec`] and [`linear`] (recording them, fusing them); [`tape`]; [`flow`],
//! [`newton`], [`affine`], `options.rs`; [`step`] and [`event`]; [`singular`]; `integrate.rs`;
//! this file (the entry points).

pub mod affine;
mod boxes;
pub mod crossing;
pub mod event;
pub mod flow;
pub mod integrable;
mod integrate;
pub mod linear;
#[cfg(test)]
mod linear_review;
pub mod newton;
pub mod op;
mod options;
pub mod rec;
pub mod singular;
pub mod step;
pub mod tape;
pub mod window;

pub use event::SeparationEvent;
pub use flow::{Flow, Piece};
pub use integrate::Ended;
pub use options::{
    AT_NO_TIME, CANNOT_CROSS, DEADLINE, GREW_TOO_WIDE, NO_SEPARATION, RigorError,
    SWITCH_ON_AN_EXPRESSION, TaylorOptions, UNDECIDABLE,
};

use crate::arith::{Enclosure, Scalar};
use crate::models::CollisionModel;
use integrate::{integrate_tape, integrate_tape_until};
use tape::Tape;

/// Integrates `model` from its initial state and encloses T_s and e.
///
/// The loop: a Taylor step where the field is analytic on the step (its box keeps every
/// switching component's sign), otherwise a low-order step across the surface, each piece
/// scanned for the separation event before the next step.
///
/// The two independent halves of each Taylor step run as a `rayon::join` (see
/// [`step::taylor_step`]); called from outside rayon's pool, the integration moves into it so
/// that these joins stay cheap. `RAYON_NUM_THREADS=1` makes it single-threaded; the result is
/// identical either way.
///
/// Generic over the number type `I` ([`Enclosure`]): inari's `Interval` (f64 ends, the fast
/// path) or an interval at a chosen precision; the algorithm is the same.
#[allow(clippy::type_complexity)]
pub fn integrate_to_separation<I: Enclosure, M: CollisionModel<I, N> + Sync, const N: usize>(
    model: &M,
    opts: &TaylorOptions,
) -> Result<(Flow<N, I>, SeparationEvent<N, I>), RigorError> {
    if rayon::current_thread_index().is_some() {
        integrate(model, opts)
    } else {
        rayon::scope(|_| integrate(model, opts))
    }
}

#[allow(clippy::type_complexity)]
fn integrate<I: Enclosure, M: CollisionModel<I, N>, const N: usize>(
    model: &M,
    opts: &TaylorOptions,
) -> Result<(Flow<N, I>, SeparationEvent<N, I>), RigorError> {
    // proved from a closed form for all T: no separation before any horizon
    if let Some(why) = model.never_separates() {
        return Err(RigorError {
            reason: format!("{NO_SEPARATION} T = {} ({AT_NO_TIME}: {why})", opts.horizon),
            t: opts.horizon,
            width: 0.0,
        });
    }
    integrate_tape(&model_tape(model, true), model.initial_state(), N, opts)
}

/// The system the engine runs for a model: the field's N components, then the outputs F (N) and
/// V (N + 1) of the separation condition. Without `condition`, F is recorded as the constant 1:
/// for a model that never separates by its closed form
/// ([`CollisionModel::never_separates`]: F > 0 for every T > 0), whose flow is wanted past the
/// point where F's sign is at the rounding level.
pub fn model_tape<I: Enclosure, M: CollisionModel<I, N>, const N: usize>(
    model: &M,
    condition: bool,
) -> Tape<I, N> {
    Tape::<I, N>::record(|v| {
        let mut o = model.field(v).to_vec();
        o.push(if condition {
            model.force(v)
        } else {
            v[0].scale(&I::zero()).shift(&I::one())
        });
        o.push(model.velocity(v));
        o
    })
}

/// [`integrate_to_separation`] of a recorded system: the field's N components, then the
/// outputs F (N) and V (N + 1) of the separation condition, then any others; from `x0`. A
/// model with parameters given as ranges is such a system (the parameters as components with
/// ṗ = 0: [`crate::observables::sets`]). The first `n_state` components are the model's state:
/// the enclosure's width that steers the tolerances and stops a widening enclosure is theirs
/// (a parameter's range, or a derivative's scale, is not the state's uncertainty).
#[allow(clippy::type_complexity)]
pub fn integrate_system<I: Enclosure, const N: usize>(
    tape: &Tape<I, N>,
    x0: [I; N],
    n_state: usize,
    opts: &TaylorOptions,
) -> Result<(Flow<N, I>, SeparationEvent<N, I>), RigorError> {
    if rayon::current_thread_index().is_some() {
        integrate_tape(tape, x0, n_state, opts)
    } else {
        rayon::scope(|_| integrate_tape(tape, x0, n_state, opts))
    }
}

/// [`integrate_system`] with a test `stop(flow, cleared)` after every piece that did not end
/// the run ([`Ended`]): e.g. a run up to the first branch point it crosses
/// ([`crossing::BranchWatch`]).
#[allow(clippy::type_complexity)]
pub fn integrate_system_until<I: Enclosure, const N: usize>(
    tape: &Tape<I, N>,
    x0: [I; N],
    n_state: usize,
    opts: &TaylorOptions,
    stop: &mut (dyn FnMut(&Flow<N, I>, f64) -> bool + Send),
) -> Result<Ended<N, I>, RigorError> {
    if rayon::current_thread_index().is_some() {
        integrate_tape_until(tape, x0, n_state, opts, stop)
    } else {
        rayon::scope(|_| integrate_tape_until(tape, x0, n_state, opts, stop))
    }
}
