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
//! (T_s by transversality and interval Newton), [`flow`] (rigorous dense output).

pub mod event;
pub mod flow;
pub mod linear;
#[cfg(test)]
mod linear_review;
pub mod lohner;
pub mod newton;
pub mod rec;
pub mod singular;
pub mod step;
pub mod tape;
pub mod window;

pub use event::SeparationEvent;
pub use flow::{Flow, Piece};

use crate::arith::Enclosure;
use crate::models::CollisionModel;
use step::StepOut;
use tape::{Tape, Workspace};

use std::fmt;

/// Tunables of the rigorous engine, with documented defaults.
#[derive(Clone, Debug)]
pub struct TaylorOptions {
    /// Taylor order of a regular step. 16 measured fastest on the Table 1 sets at tol 10⁻¹⁵
    /// (benches/RESULTS.md §1b): 10% fewer instructions than 20, 9% less time (interleaved,
    /// one thread), the widest e enclosure 6.9e-13 against 6.7e-13.
    pub order: usize,
    /// How many low orders k < kd take the mean-value form x_k(x̂) + D_k(X)(X − x̂) (the
    /// Jacobian part of a step, computed on duals; see [`step::taylor_step`]); the higher
    /// orders use the coefficients over the box. 0: [`step::jacobian_orders`]`(order)`.
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
    /// Lohner's QR method: carry the enclosure as a parallelepiped c + A·r between Taylor steps
    /// (see [`lohner`]); off: a box re-wrapped at every step (the mean-value form alone).
    pub qr: bool,
    /// Cross a branch point (a switching component of a power reaching 0) by one step in the
    /// crossing variable ([`singular`]) instead of geometrically shrinking Taylor steps and a
    /// low-order step; off: the latter only. Taken by the f64-interval engine (inari).
    pub singular: bool,
    /// With `singular`: leave the start (two components at their branch points at once) by one
    /// step in the expansions of [`singular::start`]; off: Taylor steps from a low-order step.
    pub singular_start: bool,
    /// Stop with [`DEADLINE`] when a step starts after this instant (`None`: no limit): the
    /// time budget of a run, e.g. of each precision of the fallback
    /// ([`crate::observables::precision::decide`]).
    pub deadline: Option<std::time::Instant>,
    /// Where the box evaluation of F and V on a time interval of a piece does not decide the
    /// separation condition, also evaluate them as polynomials in time along a Taylor piece,
    /// then in a centred form of second order ([`event`]); off: the box and bisection alone
    /// (measured: the Hunt–Crossley limit σ = 12 is then undecidable at f64).
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
/// The reason of a run stopped at [`TaylorOptions::deadline`].
pub const DEADLINE: &str = "the time budget ran out";
/// The start of the reason of a run that reached its horizon with the separation condition
/// proved to fail on all of [0, horizon]: a proved result (T_s > horizon), not a failure.
pub const NO_SEPARATION: &str = "no separation before the horizon";

impl TaylorOptions {
    /// Whether [`TaylorOptions::deadline`] has passed.
    pub fn out_of_time(&self) -> bool {
        self.deadline
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
    let tape = Tape::<I, N>::record(|v| {
        let mut o = model.field(v).to_vec();
        o.push(model.force(v));
        o.push(model.velocity(v));
        o
    });
    integrate_tape(&tape, model.initial_state(), N, opts)
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

/// The state width above which a set counts as wide: its parallelepiped is kept through
/// low-order steps and kink cuts, and more orders take the mean-value form (see the loop).
/// Point sets (width ≲ 1e-12) keep the box re-wrap there: measured on the 28 Table 1 cases,
/// keeping the parallelepiped changed their e widths by 0.77–1.25× (no gain on balance).
const WIDE_SET: f64 = 1e-10;

/// The widest state a start step may end in (else the Taylor steps leave the start), at f64
/// precision: ≈ 18 ulps of 1; at a precision of machine epsilon ε it scales by ε/2⁻⁵², and
/// is at least `cross_tol`.
const START_WIDTH: f64 = 4e-15;

#[allow(clippy::type_complexity)]
fn integrate_tape<I: Enclosure, const N: usize>(
    tape: &Tape<I, N>,
    x0: [I; N],
    n_state: usize,
    opts: &TaylorOptions,
) -> Result<(Flow<N, I>, SeparationEvent<N, I>), RigorError> {
    let width = |x: &[I; N]| x[..n_state].iter().map(|c| c.wid_f64()).fold(0.0, f64::max);
    if opts.order < 2
        || opts.tol.is_nan()
        || opts.tol <= 0.0
        || !(opts.horizon > 0.0 && opts.horizon.is_finite())
    {
        return Err(RigorError {
            reason: format!("bad options: {opts:?}"),
            t: 0.0,
            width: 0.0,
        });
    }
    let switching: Vec<usize> = tape.switching().to_vec();
    let tapes = step::Tapes::of(tape);
    let kd = match opts.mean_value_orders {
        0 => step::jacobian_orders(opts.order),
        k => k.min(opts.order),
    };
    let mut ws = step::Workspaces::<N, I>::default();
    let mut ev_ws = Workspace::default();
    // the singular step across branch points (f64 intervals, point sets: a wide set keeps its
    // parallelepiped through the Taylor steps), set up the first time it is tried: its basis of
    // exponents is costly for the variational tapes of wide sets, which never use it (measured:
    // 55 % of a band piece's time, SHC DSS v0 ∈ [1, 1.0024], 1941 exponents)
    let mut sing: Option<Option<singular::Singular<N, I>>> = None;
    let sing_opts = singular::SingularOptions::at_precision(I::epsilon(), opts.tol);
    // widths that are a few ulps at f64 precision, scaled to the precision of `I` (exactly
    // the f64 constants for f64 intervals)
    let ulps = I::epsilon() / f64::EPSILON;
    let beyond_f64 = I::epsilon() < f64::EPSILON;
    let start_width = (START_WIDTH * ulps).max(opts.cross_tol.min(START_WIDTH));
    let mut x = x0;
    // the set at t as a parallelepiped after a Taylor step with QR (Lohner), else None (a box)
    let mut rep: Option<lohner::Parallelepiped<N, I>> = None;
    let mut t = 0.0_f64;
    let mut flow = Flow::default();
    let mut h_low = opts.low_order_step;
    let trace = std::env::var_os("BWCL_TRACE").is_some();
    // start of a stretch where the separation condition was neither excluded nor proved
    let mut pending: Option<f64> = None;
    for _ in 0..opts.max_steps {
        let w = width(&x);
        if !step::bounded(&x) || w > opts.max_width {
            return Err(RigorError {
                reason: GREW_TOO_WIDE.into(),
                t,
                width: w,
            });
        }
        if opts.out_of_time() {
            return Err(RigorError {
                reason: DEADLINE.into(),
                t,
                width: w,
            });
        }
        if t >= opts.horizon {
            // every piece so far was cleared, unless a stretch is still pending
            if let Some(p) = pending {
                return Err(RigorError {
                    reason: format!(
                        "{UNDECIDABLE}: the condition could neither be excluded nor proved on [{p}, {t}] (the horizon)"
                    ),
                    t,
                    width: w,
                });
            }
            return Err(RigorError {
                reason: format!(
                    "{NO_SEPARATION} T = {} (the condition was proved to fail up to it)",
                    opts.horizon
                ),
                t,
                width: w,
            });
        }
        // time for a switching component to reach 0 at its fastest (only components moving towards 0)
        let f = tape.eval(&x);
        let reach = |i: usize| {
            let toward =
                (x[i].lo() > 0.0 && f[i].lo() < 0.0) || (x[i].hi() < 0.0 && f[i].hi() > 0.0);
            toward.then(|| x[i].mig_f64() / f[i].mag_f64())
        };
        let mut h_surf = f64::INFINITY;
        for &i in switching.iter().filter(|i| !tape.kinks().contains(i)) {
            if let Some(h) = reach(i) {
                h_surf = h_surf.min(h);
            }
        }
        // a kink component reaching 0 within a hundredth of the shortest Taylor step at its
        // present rate: a Taylor step would be cut before the crossing, shorter than that
        // step, or its crossing left unresolved, at every length (interval Newton cannot
        // separate a crossing a few ulps ahead from t0) — measured at V = 0 (SHC) and W = 0
        // (Maxwell), x_i ≈ −2·10⁻¹⁴: ≈ 18 Taylor steps tried with halving lengths before the
        // low-order step, 15 % of a case's time. The low-order step is taken at once (a choice
        // of step only: every step is validated).
        // (point sets only: over a wide set the rate's sign says less)
        let kink_now = w <= WIDE_SET
            && tape
                .kinks()
                .iter()
                .any(|&i| reach(i).is_some_and(|h| h < 0.01 * opts.min_taylor_step));
        let h_max = (opts.horizon - t).min(if h_surf.is_finite() {
            0.9 * h_surf
        } else {
            f64::INFINITY
        });
        // kink components continue the field from the side they are on (a Taylor step may run
        // past the kink; it is then cut just before the proved crossing)
        let side: [i8; N] = std::array::from_fn(|i| {
            match (tape.kinks().contains(&i), crate::arith::Real::sign(&x[i])) {
                (true, Some(s)) => s,
                _ => 0,
            }
        });
        // a wide set (a range of parameters as components) is wrapped by the coefficients over
        // the box unless more orders take the mean-value form: measured with v0 ∈ [4, 4.01]
        // (SHC DSS), de/dv0 26× narrower with kd = K/2 than with K/4, at 10 % more time;
        // point sets (width ≲ 1e-12) keep kd
        let kd = if w > WIDE_SET && opts.mean_value_orders == 0 {
            kd.max(opts.order / 2)
        } else {
            kd
        };
        // one branch point near and approached: across it in one singular step
        let mut near = switching
            .iter()
            .filter(|i| sing_opts.kinks || !tape.kinks().contains(i))
            .filter_map(|&i| reach(i).map(|h| (i, h)))
            .filter(|&(_, h)| h < sing_opts.near);
        let first = flow.pieces.is_empty();
        // a singular step is taken when it adds little width and its piece clears the
        // separation condition; one refused for that is still a proved step, kept as the last
        // resort where no low-order step can cross either (at a precision beyond f64 the
        // low-order steps' tolerance is far below what a step of a few ulps of t adds)
        let mut spare: Option<StepOut<N, I>> = None;
        // (beyond f64 only: there the precision fallback re-runs a case that cannot cross)
        let mut offer = |o: StepOut<N, I>, ok: bool| {
            if ok {
                Some(o)
            } else {
                if beyond_f64 {
                    spare = Some(o);
                }
                None
            }
        };
        let singular_out = match (near.next(), near.next()) {
            // the start (the models start with two components at their branch points): one
            // step in the expansions of [`singular::start`], taken when it adds little width;
            // only for a point set — every component thin, the parameter components of a
            // range run included (its state starts as a point: without this its costly basis
            // was built for every range run, 4.8× the time of SHC DSS's band)
            _ if first
                && opts.singular
                && opts.singular_start
                && x.iter().all(|c| c.wid_f64() <= WIDE_SET) =>
            {
                sing.get_or_insert_with(|| singular::Singular::new(tape, sing_opts.clone()))
                    .as_mut()
                    .and_then(|s| s.try_start(t, &x))
                    .and_then(|o| {
                        let ok = width(&o.x1) <= start_width
                            && matches!(
                                event::scan_piece(tape, &mut ev_ws, &o.piece, opts.event_forms),
                                event::Verdict::Cleared
                            );
                        if trace {
                            eprintln!(
                                "  start step to t={:.6e}: width {:.1e}, {}",
                                o.piece.t1(),
                                width(&o.x1),
                                if ok { "taken" } else { "refused" }
                            );
                        }
                        offer(o, ok)
                    })
            }
            (Some((i, h)), None) if w <= WIDE_SET && opts.singular => sing
                .get_or_insert_with(|| singular::Singular::new(tape, sing_opts.clone()))
                .as_mut()
                .and_then(|s| {
                    let r = if opts.qr { rep.as_ref() } else { None };
                    s.try_step(t, &x, r, i, h).and_then(|o| {
                        // taken when it adds little width (the expansions' remainder grows like
                        // δ^M: too far from the surface the step is refused, and tried again
                        // nearer)
                        let ok = width(&o.x1) <= 1.25 * w + opts.cross_tol.max(1e-15 * ulps)
                            && matches!(
                                event::scan_piece(tape, &mut ev_ws, &o.piece, opts.event_forms),
                                event::Verdict::Cleared
                            );
                        s.taken(ok, h);
                        offer(o, ok)
                    })
                }),
            _ => None,
        };
        let mut hm = h_max;
        if kink_now {
            // the first Taylor step after the crossing starts from the coefficients' estimate,
            // not from the remainder ratio of the steps before the kink (the tiny trial steps
            // left a ratio < 1 behind: with it reset, the same first step as before on 19 of
            // the 28 Table 1 cases)
            ws.remainder_ratio = 0.0;
        }
        let taylor = loop {
            if singular_out.is_some() || kink_now {
                break None;
            }
            match step::taylor_step(
                &tapes,
                &mut ws,
                t,
                &x,
                opts.order,
                kd,
                opts.tol.max(1e-4 * w),
                hm,
                opts.min_taylor_step,
                &side,
                if opts.qr { rep.as_ref() } else { None },
            ) {
                Err(why) => {
                    flow.refused_taylor += 1;
                    if trace {
                        let why = match why {
                            step::TaylorFail::AtSurface => "at a switching surface",
                            step::TaylorFail::TooShort => "too short",
                        };
                        eprintln!("  no Taylor step at t={t:.6e}: {why} (h_max {hm:.3e})");
                    }
                    break None;
                }
                Ok(mut o) => match step::cut_at_kinks(tape, &o, &side) {
                    step::KinkCut::Whole => break Some(o),
                    step::KinkCut::Before(tc) if tc - t >= opts.min_taylor_step => {
                        // the step again, ending at the cut: its end set stays a
                        // parallelepiped (a truncated piece gives a box)
                        if o.rep.is_some()
                            && w > WIDE_SET
                            && let Ok(o2) = step::taylor_step(
                                &tapes,
                                &mut ws,
                                t,
                                &x,
                                opts.order,
                                kd,
                                opts.tol.max(1e-4 * w),
                                tc - t,
                                opts.min_taylor_step,
                                &side,
                                rep.as_ref(),
                            )
                            && matches!(step::cut_at_kinks(tape, &o2, &side), step::KinkCut::Whole)
                        {
                            break Some(o2);
                        }
                        o.piece.truncate(tc);
                        o.x1 = o.piece.enclose(&I::from_exact_f64(tc));
                        o.rep = None;
                        break Some(o);
                    }
                    // the crossing is right ahead: a low-order step takes it
                    step::KinkCut::Before(_) => {
                        flow.refused_taylor += 1;
                        break None;
                    }
                    step::KinkCut::Unresolved => {
                        flow.refused_taylor += 1;
                        hm = 0.5 * (o.piece.t1() - t);
                        if hm < opts.min_taylor_step {
                            break None;
                        }
                    }
                },
            }
        };
        let out = match taylor.or(singular_out) {
            Some(o) => o,
            None => {
                // across the surface: the longest low-order step whose added width stays ≤ cross_tol
                // a step of MIN_STEP_ULPS spacings of the doubles at t: about the shortest that
                // the time grid resolves (the search starts above it: beyond f64 the last
                // length that met the tolerance may lie below the grid)
                let floor = step::MIN_STEP_ULPS * step::time_spacing(t);
                let mut h = (h_low * 4.0).max(4.0 * floor);
                let mut at_floor: Option<StepOut<N, I>> = None;
                loop {
                    // (a step shorter than the spacing of doubles at t would not advance)
                    if h < opts.min_low_order_step || t + h <= t {
                        // none meets the tolerance: the last resorts, each a proved step — a
                        // refused singular step, or the shortest low-order step the time grid
                        // allows where what it adds stays below 10⁻³ ε_f64 of the state's
                        // magnitude (beyond f64 a step of a few ulps of t adds ≈ (h·|f|)²,
                        // above the tolerance; the f64 engine's own tolerance is larger)
                        if let Some(o) = spare.take().or(at_floor.take()) {
                            if trace {
                                eprintln!("  last resort at t={t:.6e}: width {:.1e}", width(&o.x1));
                            }
                            break o;
                        }
                        return Err(RigorError {
                            reason: CANNOT_CROSS.into(),
                            t,
                            width: w,
                        });
                    }
                    if let Some(mut o) = step::low_order_step(tape, t, &x, h) {
                        // the parallelepiped moved by τ·f(Y) (see Parallelepiped::shifted)
                        if let (Some(p), true, Piece::LowOrder { t0, t1, slope, .. }) =
                            (&rep, opts.qr && w > WIDE_SET, &o.piece)
                        {
                            let tau1 = flow::tau(&I::from_exact_f64(*t1), *t0);
                            let d: [I; N] =
                                std::array::from_fn(|i| tau1.clone() * slope[i].clone());
                            if let Some(p1) = p.shifted(&d) {
                                let h1 = p1.hull();
                                o.x1 = std::array::from_fn(|i| o.x1[i].intersection(&h1[i]));
                                o.rep = Some(p1);
                            }
                        }
                        let added = width(&o.x1) - w;
                        if added
                            <= opts.cross_tol.max(1e-3 * w)
                                + 4.0 * I::epsilon() * step::magnitude(&o.x1)
                        {
                            h_low = h;
                            break o;
                        }
                        if h < 4.0 * floor
                            && added <= 1e-3 * f64::EPSILON * step::magnitude(&o.x1).max(1.0)
                        {
                            at_floor = Some(o);
                        }
                    }
                    h *= 0.25;
                }
            }
        };
        let t1 = out.piece.t1();
        if t1 <= t {
            // every kind of step ends past its start (the Taylor steps by MIN_STEP_ULPS, the
            // low-order ones by their check above): never loop on a step of length 0
            return Err(RigorError {
                reason: format!("a step did not advance the time at T = {t} (an internal error)"),
                t,
                width: w,
            });
        }
        // the step's a-priori box holds the flow on the whole piece (on a piece cut before a
        // kink too: the continued flow equals the true one there): where F > 0 or V < 0 on it,
        // the piece is cleared without evaluating the piece itself (most of the contact)
        let verdict = if event::excluded(tape, &out.apriori) {
            event::Verdict::Cleared
        } else {
            event::scan_piece(tape, &mut ev_ws, &out.piece, opts.event_forms)
        };
        flow.pieces.push(out.piece);
        match (verdict, pending) {
            (event::Verdict::Found(ev), None) => return Ok((flow, ev)),
            // T_s was not excluded from [p, …) but is proved by here: T_s ∈ [p, ts.sup]
            (event::Verdict::Found(ev), Some(p)) => {
                let ev = event::between(tape, &flow, p, ev.ts.hi());
                return Ok((flow, ev));
            }
            (event::Verdict::Undecided(tt), None) => pending = Some(tt.lo()),
            _ => {}
        }
        if let Some(p) = pending {
            // the condition fails on [0, p) (every earlier time was cleared); once it provably
            // holds at a later time t1, T_s ∈ [p, t1]
            if event::holds(tape, &out.x1) {
                let ev = event::between(tape, &flow, p, t1);
                return Ok((flow, ev));
            }
            if t1 - p > opts.event_slack.max(100.0 * w) {
                return Err(RigorError {
                    reason: format!(
                        "{UNDECIDABLE}: the condition could neither be excluded nor proved on [{p}, {t1}]"
                    ),
                    t,
                    width: w,
                });
            }
        }
        if trace {
            let kind = if matches!(flow.pieces.last(), Some(Piece::Taylor { .. })) {
                "T"
            } else {
                "L"
            };
            eprintln!(
                "{kind} t={t:.6e} h={:.3e} w={:.3e} x={:?}",
                t1 - t,
                width(&out.x1),
                out.x1.iter().map(|c| c.mid()).collect::<Vec<f64>>()
            );
            let widths: Vec<String> = out
                .x1
                .iter()
                .map(|c| format!("{:.1e}", c.wid_f64()))
                .collect();
            eprintln!(
                "  widths {} (parallelepiped: {})",
                widths.join(" "),
                out.rep.is_some()
            );
        }
        t = t1;
        x = out.x1;
        rep = out.rep;
    }
    Err(RigorError {
        reason: format!("more than {} steps", opts.max_steps),
        t,
        width: width(&x),
    })
}
