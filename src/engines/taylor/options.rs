//! The engine's tunables ([`TaylorOptions`]) and why a run proved nothing
//! ([`RigorError`], with its reasons).

use std::fmt;

/// Tunables of the rigorous engine, with documented defaults.
#[derive(Clone, Debug)]
pub struct TaylorOptions {
    /// Taylor order of a regular step. 16 measured fastest on the Table 1 sets at tol 10⁻¹⁵
    /// (benches/RESULTS.md §1b): 10% fewer instructions than 20, 9% less time (interleaved,
    /// one thread), the widest e enclosure 6.9e-13 against 6.7e-13.
    pub order: usize,
    /// How many low orders k < kd take the mean-value form x_k(x̂) + D_k(X)(X − x̂) (the Jacobian
    /// part of a step, computed on duals; see [`step::taylor_step`](super::step::taylor_step)); the
    /// higher orders use the coefficients over the box. 0:
    /// [`step::jacobian_orders`](super::step::jacobian_orders)`(order)`.
    pub mean_value_orders: usize,
    /// Target local error per step (absolute, nondimensional). 10⁻¹⁵ measured best on the
    /// Table 1 sets: smaller values take more steps near the branch points and end wider.
    /// 8·10⁻¹⁶ since the Y-jets' remainders got narrower (integral powers, 2026-11-26): against
    /// 10⁻¹⁵ the same time (per-case ratio to the session's start 0.826 vs 0.822, 3 alternating
    /// runs), e no wider than before the session on 25 of the 28 cases instead of 21, the widest
    /// e 3.83e-13 instead of 3.94e-13 (3.91e-13 before).
    pub tol: f64,
    /// Nondimensional time after which no separation is reported.
    pub horizon: f64,
    /// Widest enclosure of any state component before the engine gives up.
    pub max_width: f64,
    /// Most steps before the engine gives up.
    pub max_steps: usize,
    /// Shortest Taylor step tried before a low-order step is taken instead.
    pub min_taylor_step: f64,
    /// First trial length of a low-order step across a switching surface.
    pub low_order_step: f64,
    /// Shortest low-order step tried before the engine gives up crossing.
    pub min_low_order_step: f64,
    /// Most width a low-order step may add to the enclosure (or 10⁻³ of the width it has, when
    /// that is larger: an enclosure that is already wide, e.g. for a range of v0, is not
    /// refined by crossing in tiny steps; likewise the truncation tolerance is at least 10⁻⁴ of
    /// the width).
    pub cross_tol: f64,
    /// Longest stretch of time on which the separation condition may stay undecided (neither
    /// excluded nor proved, e.g. F → 0 at a branch point) before the engine reports a grazing
    /// separation instead of an enclosure; at least 100× the enclosure's width (a wide
    /// enclosure, e.g. for a range of v0, spreads T_s over a correspondingly long time).
    pub event_slack: f64,
    /// Carry the enclosure between Taylor steps as an affine set c + Σ g_j·u_j (see
    /// [`affine`](super::affine); it replaced Lohner's QR parallelepiped, hence the name); off: a
    /// box re-wrapped at every step (the mean-value form alone).
    pub qr: bool,
    /// Cross a branch point (a switching component of a power reaching 0) by one step in the
    /// crossing variable ([`singular`](super::singular)) instead of geometrically shrinking Taylor
    /// steps and a low-order step; off: the latter only. Taken by the f64-interval engine (inari).
    pub singular: bool,
    /// With `singular`: leave the start (two components at their branch points at once) by one step
    /// in the expansions of [`singular::start`](super::singular::start); off: Taylor steps from a
    /// low-order step.
    pub singular_start: bool,
    /// Stop with [`DEADLINE`] when a step starts after this instant (`None`: no limit): the
    /// time budget of a run, e.g. of each precision of the fallback
    /// ([`crate::observables::precision::decide`]).
    pub deadline: Option<std::time::Instant>,
    /// Where the box evaluation of F and V on a time interval of a piece does not decide the
    /// separation condition, also evaluate them as polynomials in time along a Taylor piece, then
    /// in a centred form of second order ([`event`](super::event)); off: the box and bisection
    /// alone (measured: the Hunt–Crossley limit σ = 12 is then undecidable at f64).
    pub event_forms: bool,
}

impl Default for TaylorOptions {
    fn default() -> Self {
        Self {
            order: 16,
            mean_value_orders: 0,
            tol: 8e-16,
            horizon: 100.0,
            max_width: 0.1,
            max_steps: 20_000,
            min_taylor_step: 1e-8,
            low_order_step: 1e-7,
            min_low_order_step: 1e-14,
            cross_tol: 1e-16,
            event_slack: 1e-3,
            qr: true,
            singular: true,
            singular_start: true,
            deadline: None,
            event_forms: true,
        }
    }
}

/// Why the rigorous engine could not prove a result, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct RigorError {
    pub reason: String,
    /// The time reached (nondimensional) with the widest state enclosure there.
    pub t: f64,
    pub width: f64,
}

/// The reasons of [`RigorError`] that a narrower enclosure may remove (see
/// [`RigorError::precision_may_help`]).
pub const GREW_TOO_WIDE: &str = "the enclosure grew too wide";
pub const CANNOT_CROSS: &str = "cannot cross a switching surface with a proved low-order step";
pub const UNDECIDABLE: &str = "grazing or undecidable separation";
/// The reason a second variational system is refused when its field switches on an expression
/// of the state rather than on a state component
/// ([`Tape::switch_on_an_expression`](super::tape::Tape::switch_on_an_expression)).
pub const SWITCH_ON_AN_EXPRESSION: &str = "the field switches on an expression of the state \
     (|g|, sgn g or a power of g, g not a state component): the second derivatives are not \
     carried across its zeros";
/// The reason of a run stopped at [`TaylorOptions::deadline`].
pub const DEADLINE: &str = "the time budget ran out";
/// The start of the reason of a run that reached its horizon with the separation condition
/// proved to fail on all of [0, horizon]: a proved result (T_s > horizon), not a failure.
pub const NO_SEPARATION: &str = "no separation before the horizon";
/// In a [`NO_SEPARATION`] reason, before the closed form's argument that the model never
/// separates ([`crate::models::CollisionModel::never_separates`]): T_s = +∞.
pub const AT_NO_TIME: &str = "nor at any later time, by a closed form";

impl TaylorOptions {
    /// Whether [`TaylorOptions::deadline`] has passed, or a stop is requested
    /// ([`crate::engines::cancel`]: the run then stops as at its deadline).
    pub fn out_of_time(&self) -> bool {
        crate::engines::cancel::requested()
            || self
                .deadline
                .is_some_and(|d| std::time::Instant::now() >= d)
    }
}

impl RigorError {
    /// Whether the same case may be proved with narrower enclosures (at a higher precision):
    /// the enclosure grew too wide, a crossing's low-order step added too much width, or the
    /// separation condition was neither excluded nor proved at this width. Not for a horizon
    /// reached with the condition proved to fail, the step budget, bad options or parameters.
    pub fn precision_may_help(&self) -> bool {
        [GREW_TOO_WIDE, CANNOT_CROSS, UNDECIDABLE]
            .iter()
            .any(|r| self.reason.starts_with(r))
    }

    /// The run stopped at its deadline ([`DEADLINE`]).
    pub fn out_of_time(&self) -> bool {
        self.reason.starts_with(DEADLINE)
    }

    /// The run proved that the separation condition fails on all of [0, T] for T = `self.t`,
    /// the horizon ([`NO_SEPARATION`]): T_s > T.
    pub fn no_separation(&self) -> bool {
        self.reason.starts_with(NO_SEPARATION)
    }

    /// For a [`NO_SEPARATION`] proved for every time by the model's closed form ([`AT_NO_TIME`]):
    /// its argument (T_s = +∞).
    pub fn never_separates(&self) -> Option<&str> {
        let rest = self.reason.strip_prefix(NO_SEPARATION)?;
        let (_, why) = rest.split_once(AT_NO_TIME)?;
        Some(why.trim_start_matches(": ").trim_end_matches(')'))
    }
}

impl fmt::Display for RigorError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "not proved: {} (at T = {}, enclosure width {:e})",
            self.reason, self.t, self.width
        )
    }
}
impl std::error::Error for RigorError {}

/// The state width above which a set counts as wide: its affine set is kept through
/// low-order steps and kink cuts, and more orders take the mean-value form (see `integrate` and `window`).
/// Point sets (width ≲ 1e-12) keep the box re-wrap there: measured on the 28 Table 1 cases,
/// keeping the parallelepiped changed their e widths by 0.77–1.25× (no gain on balance); keeping
/// the affine set there (2026-11-28) added 10–25 % more pieces and widened e on 16 of 28.
pub(crate) const WIDE_SET: f64 = 1e-10;
