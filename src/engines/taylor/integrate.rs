//! The engine's loop ([`super::integrate_system`]): step after step from the start until the
//! separation event is proved, the run cannot go on, or the caller's test says stop
//! ([`integrate_tape_until`]). A step in stages, in this order:
//! [`Run::check`] (the set still narrow, time left, the horizon not reached),
//! [`Run::survey`] (the field at the set: how soon a switching surface is reached, the longest
//! step, the kinks' sides), [`Run::singular_step`] (across a near branch point in one step),
//! [`Run::taylor_step`] (a Taylor step, cut before a proved kink crossing), else
//! [`Run::low_order_step`] (across the surface), then [`Run::scan`] (the new piece scanned for
//! the event, a pending stretch decided) and [`Run::advance`].

use super::affine::AffineSet;
use super::event::{self, SeparationEvent};
use super::flow::{self, Flow, Piece};
use super::options::WIDE_SET;
use super::options::{
    CANNOT_CROSS, DEADLINE, GREW_TOO_WIDE, NO_SEPARATION, RigorError, SWITCH_ON_AN_EXPRESSION,
    TaylorOptions, UNDECIDABLE,
};
use super::singular;
use super::step::{self, StepOut};
use super::tape::{Tape, Workspace};
use crate::arith::Enclosure;

/// The widest state a start step may end in (else the Taylor steps leave the start), at f64
/// precision: ≈ 18 ulps of 1; at a precision of machine epsilon ε it scales by ε/2⁻⁵², and
/// is at least `cross_tol`.
const START_WIDTH: f64 = 4e-15;

/// The widest component of the state (the first `n_state` components of `x`).
fn state_width<I: Enclosure, const N: usize>(x: &[I; N], n_state: usize) -> f64 {
    x[..n_state].iter().map(|c| c.wid_f64()).fold(0.0, f64::max)
}

/// The time for a component x to reach 0 at its fastest rate f (only for a component moving
/// towards 0).
fn reach<I: Enclosure>(x: &I, f: &I) -> Option<f64> {
    let toward = (x.lo() > 0.0 && f.lo() < 0.0) || (x.hi() < 0.0 && f.hi() > 0.0);
    toward.then(|| x.mig_f64() / f.mag_f64())
}

#[allow(clippy::type_complexity)]
pub(super) fn integrate_tape<I: Enclosure, const N: usize>(
    tape: &Tape<I, N>,
    x0: [I; N],
    n_state: usize,
    opts: &TaylorOptions,
) -> Result<(Flow<N, I>, SeparationEvent<N, I>), RigorError> {
    match integrate_tape_until(tape, x0, n_state, opts, &mut |_, _| false)? {
        Ended::Separated(flow, ev) => Ok((flow, ev)),
        Ended::Stopped { .. } => unreachable!("a test that never stops"),
    }
}

/// Where a run of `integrate_tape_until` ended.
pub enum Ended<const N: usize, I> {
    /// At the separation event, proved.
    Separated(Flow<N, I>, SeparationEvent<N, I>),
    /// Where the caller's test said stop, after the flow's last piece; the separation condition
    /// is proved to fail on [0, `cleared`).
    Stopped { flow: Flow<N, I>, cleared: f64 },
}

/// The loop, with a test `stop(flow, cleared)` after every piece that did not end the run
/// (`cleared` as in [`Ended::Stopped`]): the run ends there when it says so.
#[allow(clippy::type_complexity)]
pub(super) fn integrate_tape_until<I: Enclosure, const N: usize>(
    tape: &Tape<I, N>,
    x0: [I; N],
    n_state: usize,
    opts: &TaylorOptions,
    stop: &mut dyn FnMut(&Flow<N, I>, f64) -> bool,
) -> Result<Ended<N, I>, RigorError> {
    let mut run = Run::new(tape, x0, n_state, opts)?;
    for _ in 0..opts.max_steps {
        let w = run.check()?;
        let here = run.survey(w);
        let (singular_out, spare) = run.singular_step(&here);
        let taylor = run.taylor_step(&here, singular_out.is_some());
        let out = match taylor.or(singular_out) {
            Some(o) => o,
            None => run.low_order_step(w, spare)?,
        };
        if let Some(ev) = run.scan(out, w)? {
            return Ok(Ended::Separated(run.flow, ev));
        }
        // (every piece is cleared unless a stretch is pending)
        let cleared = run.pending.unwrap_or(run.t);
        if stop(&run.flow, cleared) {
            return Ok(Ended::Stopped {
                flow: run.flow,
                cleared,
            });
        }
    }
    Err(RigorError {
        reason: format!("more than {} steps", opts.max_steps),
        t: run.t,
        width: state_width(&run.x, n_state),
    })
}

/// The loop's state: what it sets up once, and the set, the time and the flow so far.
struct Run<'a, I: Enclosure, const N: usize> {
    tape: &'a Tape<I, N>,
    opts: &'a TaylorOptions,
    /// The model's state: the first components (see [`super::integrate_system`]).
    n_state: usize,
    switching: Vec<usize>,
    tapes: step::Tapes<N, I>,
    /// The orders that take the mean-value form (of a point set; see [`Run::survey`]).
    kd: usize,
    ws: step::Workspaces<N, I>,
    ev_ws: Workspace<I>,
    sing: Option<Option<singular::Singular<N, I>>>,
    sing_opts: singular::SingularOptions,
    ulps: f64,
    beyond_f64: bool,
    start_width: f64,
    x: [I; N],
    rep: Option<AffineSet<N, I>>,
    t: f64,
    flow: Flow<N, I>,
    h_low: f64,
    trace: bool,
    pending: Option<f64>,
}

/// The field at the set where a step starts, and what it says of the step.
struct Survey<const N: usize, I> {
    /// The state's width.
    w: f64,
    /// The field at the set.
    f: Vec<I>,
    /// A kink component reaches 0 at once: a low-order step takes it.
    kink_now: bool,
    h_max: f64,
    side: [i8; N],
    /// The orders that take the mean-value form.
    kd: usize,
}

impl<'a, I: Enclosure, const N: usize> Run<'a, I, N> {
    fn new(
        tape: &'a Tape<I, N>,
        x0: [I; N],
        n_state: usize,
        opts: &'a TaylorOptions,
    ) -> Result<Self, RigorError> {
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
        // S₂'s jumps are carried where a state component crosses 0 (`integrable::kink_jump`);
        // where an expression g does (|g|, sgn g, a power of g), nothing would carry them
        if tape.second_order().is_some() && tape.switch_on_an_expression().is_some() {
            return Err(RigorError {
                reason: SWITCH_ON_AN_EXPRESSION.to_string(),
                t: 0.0,
                width: 0.0,
            });
        }
        let kd = match opts.mean_value_orders {
            0 => step::jacobian_orders(opts.order),
            k => k.min(opts.order),
        };
        // widths that are a few ulps at f64 precision, scaled to the precision of `I` (exactly
        // the f64 constants for f64 intervals)
        let ulps = I::epsilon() / f64::EPSILON;
        Ok(Self {
            tape,
            opts,
            n_state,
            switching: tape.switching().to_vec(),
            tapes: step::Tapes::of(tape),
            kd,
            ws: step::Workspaces::default(),
            ev_ws: Workspace::default(),
            // the singular step across branch points (f64 intervals, point sets: a wide set
            // keeps its affine set through the Taylor steps), set up the first time it is
            // tried: its basis of exponents is costly for the variational tapes of wide sets,
            // which never use it (measured: 55 % of a band piece's time, SHC DSS
            // v0 ∈ [1, 1.0024], 1941 exponents)
            sing: None,
            sing_opts: singular::SingularOptions::at_precision(I::epsilon(), opts.tol),
            ulps,
            beyond_f64: I::epsilon() < f64::EPSILON,
            start_width: (START_WIDTH * ulps).max(opts.cross_tol.min(START_WIDTH)),
            x: x0,
            // the set at t as an affine set after a Taylor step (`opts.qr`), else None
            // (a box)
            rep: None,
            t: 0.0,
            flow: Flow::default(),
            h_low: opts.low_order_step,
            trace: std::env::var_os("BWCL_TRACE").is_some(),
            // start of a stretch where the separation condition was neither excluded nor proved
            pending: None,
        })
    }

    /// Before a step: the set still bounded and narrow enough, time left in the budget, the
    /// horizon not reached (there the run ends: no separation proved, or a stretch undecided).
    /// Returns the state's width.
    fn check(&self) -> Result<f64, RigorError> {
        let (opts, t) = (self.opts, self.t);
        let w = state_width(&self.x, self.n_state);
        if !step::bounded(&self.x) || w > opts.max_width {
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
            if let Some(p) = self.pending {
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
        Ok(w)
    }

    /// The field at the set (state width `w`), how soon a switching surface is reached, the
    /// longest step, the sides the kinks are continued from and the mean-value orders.
    fn survey(&self, w: f64) -> Survey<N, I> {
        let (tape, opts, x, t) = (self.tape, self.opts, &self.x, self.t);
        // time for a switching component to reach 0 at its fastest (only components moving towards 0)
        let f = tape.eval(x);
        let mut h_surf = f64::INFINITY;
        for &i in self.switching.iter().filter(|i| !tape.kinks().contains(i)) {
            if let Some(h) = reach(&x[i], &f[i]) {
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
                .any(|&i| reach(&x[i], &f[i]).is_some_and(|h| h < 0.01 * opts.min_taylor_step));
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
            self.kd.max(opts.order / 2)
        } else {
            self.kd
        };
        Survey {
            w,
            f,
            kink_now,
            h_max,
            side,
            kd,
        }
    }

    /// Across a branch point in one singular step: the start step, or a step across the one
    /// branch point near and approached. Returns the step if it is taken, and (beyond f64) one
    /// refused, kept as the last resort of [`Run::low_order_step`].
    #[allow(clippy::type_complexity)]
    fn singular_step(
        &mut self,
        here: &Survey<N, I>,
    ) -> (Option<StepOut<N, I>>, Option<StepOut<N, I>>) {
        let (tape, opts, t, w) = (self.tape, self.opts, self.t, here.w);
        // (not for a second variational system: the expansions hold no negative exponents of
        // S₂'s |w|^(q−2), nor the kinks' jumps of S₂)
        if tape.second_order().is_some() {
            return (None, None);
        }
        let n_state = self.n_state;
        let width = |x: &[I; N]| state_width(x, n_state);
        // one branch point near and approached: across it in one singular step
        let mut near = self
            .switching
            .iter()
            .filter(|i| self.sing_opts.kinks || !tape.kinks().contains(i))
            .filter_map(|&i| reach(&self.x[i], &here.f[i]).map(|h| (i, h)))
            .filter(|&(_, h)| h < self.sing_opts.near);
        let first = self.flow.pieces.is_empty();
        // the step's piece clears the separation condition
        let ev_ws = &mut self.ev_ws;
        let mut clears = |piece: &Piece<N, I>| {
            matches!(
                event::scan_piece(tape, ev_ws, piece, opts.event_forms),
                event::Verdict::Cleared
            )
        };
        // a singular step is taken when it adds little width and its piece clears the
        // separation condition; one refused for that is still a proved step, kept as the last
        // resort where no low-order step can cross either (at a precision beyond f64 the
        // low-order steps' tolerance is far below what a step of a few ulps of t adds)
        let mut spare: Option<StepOut<N, I>> = None;
        // (beyond f64 only: there the precision fallback re-runs a case that cannot cross)
        let beyond_f64 = self.beyond_f64;
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
                && self.x.iter().all(|c| c.wid_f64() <= WIDE_SET) =>
            {
                self.sing
                    .get_or_insert_with(|| singular::Singular::new(tape, self.sing_opts.clone()))
                    .as_mut()
                    .and_then(|s| s.try_start(t, &self.x))
                    .and_then(|o| {
                        let ok = width(&o.x1) <= self.start_width && clears(&o.piece);
                        if self.trace {
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
            (Some((i, h)), None) if w <= WIDE_SET && opts.singular => self
                .sing
                .get_or_insert_with(|| singular::Singular::new(tape, self.sing_opts.clone()))
                .as_mut()
                .and_then(|s| {
                    let r = if opts.qr { self.rep.as_ref() } else { None };
                    s.try_step(t, &self.x, r, i, h).and_then(|o| {
                        // taken when it adds little width (the expansions' remainder grows like
                        // δ^M: too far from the surface the step is refused, and tried again
                        // nearer)
                        let ok = width(&o.x1) <= 1.25 * w + opts.cross_tol.max(1e-15 * self.ulps)
                            && clears(&o.piece);
                        s.taken(ok, h);
                        offer(o, ok)
                    })
                }),
            _ => None,
        };
        (singular_out, spare)
    }

    /// A Taylor step from the set (none where a singular step was taken or a kink is just
    /// ahead), cut just before a proved kink crossing, shortened where its crossing is
    /// unresolved.
    fn taylor_step(&mut self, here: &Survey<N, I>, singular_taken: bool) -> Option<StepOut<N, I>> {
        let (tape, opts, t, w) = (self.tape, self.opts, self.t, here.w);
        let mut hm = here.h_max;
        if here.kink_now {
            // the first Taylor step after the crossing starts from the coefficients' estimate,
            // not from the remainder ratio of the steps before the kink (the tiny trial steps
            // left a ratio < 1 behind: with it reset, the same first step as before on 19 of
            // the 28 Table 1 cases)
            self.ws.remainder_ratio = 0.0;
        }
        if singular_taken || here.kink_now {
            return None;
        }
        loop {
            match self.try_taylor(here, hm, opts.qr) {
                Err(why) => {
                    self.flow.refused_taylor += 1;
                    if self.trace {
                        let why = match why {
                            step::TaylorFail::AtSurface => "at a switching surface",
                            step::TaylorFail::TooShort => "too short",
                        };
                        eprintln!("  no Taylor step at t={t:.6e}: {why} (h_max {hm:.3e})");
                    }
                    break None;
                }
                Ok(mut o) => match step::cut_at_kinks(tape, &o, &here.side) {
                    step::KinkCut::Whole => break Some(o),
                    step::KinkCut::Before(tc) if tc - t >= opts.min_taylor_step => {
                        // the step again, ending at the cut: its end set stays a
                        // affine set (a truncated piece gives a box)
                        if o.rep.is_some()
                            && w > WIDE_SET
                            && let Ok(o2) = self.try_taylor(here, tc - t, true)
                            && matches!(
                                step::cut_at_kinks(tape, &o2, &here.side),
                                step::KinkCut::Whole
                            )
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
                        self.flow.refused_taylor += 1;
                        break None;
                    }
                    step::KinkCut::Unresolved => {
                        self.flow.refused_taylor += 1;
                        hm = 0.5 * (o.piece.t1() - t);
                        if hm < opts.min_taylor_step {
                            break None;
                        }
                    }
                },
            }
        }
    }

    /// [`step::taylor_step`] from the set, at most `h` long; from its affine set, if it has
    /// one, with `with_rep`.
    fn try_taylor(
        &mut self,
        here: &Survey<N, I>,
        h: f64,
        with_rep: bool,
    ) -> Result<StepOut<N, I>, step::TaylorFail> {
        let opts = self.opts;
        step::taylor_step(
            &self.tapes,
            &mut self.ws,
            self.t,
            &self.x,
            opts.order,
            here.kd,
            opts.tol.max(1e-4 * here.w),
            h,
            opts.min_taylor_step,
            &here.side,
            if with_rep { self.rep.as_ref() } else { None },
        )
    }

    /// Across the surface (state width `w`): the longest low-order step whose added width
    /// stays ≤ cross_tol, else a last resort (`spare`: a refused singular step).
    fn low_order_step(
        &mut self,
        w: f64,
        mut spare: Option<StepOut<N, I>>,
    ) -> Result<StepOut<N, I>, RigorError> {
        let (tape, opts, t) = (self.tape, self.opts, self.t);
        let n_state = self.n_state;
        let width = |x: &[I; N]| state_width(x, n_state);
        // across the surface: the longest low-order step whose added width stays ≤ cross_tol
        // a step of MIN_STEP_ULPS spacings of the doubles at t: about the shortest that
        // the time grid resolves (the search starts above it: beyond f64 the last
        // length that met the tolerance may lie below the grid)
        let floor = step::MIN_STEP_ULPS * step::time_spacing(t);
        let mut h = (self.h_low * 4.0).max(4.0 * floor);
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
                    if self.trace {
                        eprintln!("  last resort at t={t:.6e}: width {:.1e}", width(&o.x1));
                    }
                    break Ok(o);
                }
                return Err(RigorError {
                    reason: CANNOT_CROSS.into(),
                    t,
                    width: w,
                });
            }
            if let Some(mut o) = step::low_order_step(tape, t, &self.x, h) {
                // the affine set moved by τ·f(Y) (see AffineSet::shifted) — unless the step
                // moved the set by more than that (a piece starting elsewhere than the set: the
                // integrable singular terms or the kink jump of a second variational system,
                // [`super::integrable`]); the set is then dropped
                let moved_more = matches!(&o.piece, Piece::LowOrder { x0, .. }
                    if x0.iter().zip(self.x.iter()).any(|(a, b)| !a.identical(b)));
                if let (Some(p), true, false, Piece::LowOrder { t0, t1, slope, .. }) =
                    (&self.rep, opts.qr && w > WIDE_SET, moved_more, &o.piece)
                {
                    let tau1 = flow::tau(&I::from_exact_f64(*t1), *t0);
                    let d: [I; N] = std::array::from_fn(|i| tau1.clone() * slope[i].clone());
                    if let Some(p1) = p.shifted(&d) {
                        let h1 = p1.hull();
                        o.x1 = std::array::from_fn(|i| o.x1[i].intersection(&h1[i]));
                        o.rep = Some(p1);
                    }
                }
                let added = width(&o.x1) - w;
                if added
                    <= opts.cross_tol.max(1e-3 * w) + 4.0 * I::epsilon() * step::magnitude(&o.x1)
                {
                    self.h_low = h;
                    break Ok(self.across_kinks(&o, w).unwrap_or(o));
                }
                if h < 4.0 * floor && added <= 1e-3 * f64::EPSILON * step::magnitude(&o.x1).max(1.0)
                {
                    at_floor = Some(o);
                }
            }
            h *= 0.25;
        }
    }

    /// For a second variational system, a low-order step `o` that ends with a kink component
    /// straddling 0 where it started on one side: the step that carries every member across
    /// instead, if one validates and adds at most 10× the tolerance of the state's width —
    /// its S₂ then gets the jump ΔS₂ itself, not hull(0, ΔS₂) twice
    /// ([`super::integrable::kink_jump`]).
    fn across_kinks(&self, o: &StepOut<N, I>, w: f64) -> Option<StepOut<N, I>> {
        let lay = self.tape.second_order()?;
        let (x, t) = (&self.x, self.t);
        let Piece::LowOrder { slope, .. } = &o.piece else {
            return None;
        };
        // the time every member needs to cross, at the slowest rate over the step
        let need = self
            .tape
            .kinks()
            .iter()
            .filter(|&&k| k < lay.n)
            .filter_map(|&k| {
                let s = crate::arith::Real::sign(&x[k])?;
                let after = crate::arith::Real::sign(&o.x1[k]);
                (after != Some(-s) && slope[k].mig_f64() > 0.0)
                    .then(|| x[k].mag_f64() / slope[k].mig_f64())
            })
            .fold(0.0, f64::max);
        if need == 0.0 {
            return None;
        }
        let width = |x: &[I; N]| state_width(x, self.n_state);
        let tol = self.opts.cross_tol.max(1e-3 * w);
        [1.25, 2.0, 4.0].iter().find_map(|&f| {
            let c = step::low_order_step(self.tape, t, x, f * need)?;
            let crossed = self.tape.kinks().iter().filter(|&&k| k < lay.n).all(|&k| {
                match crate::arith::Real::sign(&x[k]) {
                    Some(s) => {
                        crate::arith::Real::sign(&o.x1[k]) == Some(s)
                            || crate::arith::Real::sign(&c.x1[k]) == Some(-s)
                    }
                    None => true,
                }
            });
            (crossed && width(&c.x1) - w <= 10.0 * tol).then_some(c)
        })
    }

    /// The step's piece into the flow, scanned for the separation event (state width `w` at
    /// the step's start): T_s proved ends the run, and so does a stretch left undecided for too
    /// long; else the set moves to the piece's end ([`Run::advance`]).
    fn scan(
        &mut self,
        out: StepOut<N, I>,
        w: f64,
    ) -> Result<Option<SeparationEvent<N, I>>, RigorError> {
        let (tape, opts, t) = (self.tape, self.opts, self.t);
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
            event::scan_piece(tape, &mut self.ev_ws, &out.piece, opts.event_forms)
        };
        self.flow.pieces.push(out.piece);
        match (verdict, self.pending) {
            (event::Verdict::Found(ev), None) => return Ok(Some(ev)),
            // T_s was not excluded from [p, …) but is proved by here: T_s ∈ [p, ts.sup]
            (event::Verdict::Found(ev), Some(p)) => {
                let ev = event::between(tape, &self.flow, p, ev.ts.hi());
                return Ok(Some(ev));
            }
            (event::Verdict::Undecided(tt), None) => self.pending = Some(tt.lo()),
            _ => {}
        }
        if let Some(p) = self.pending {
            // the condition fails on [0, p) (every earlier time was cleared); once it provably
            // holds at a later time t1, T_s ∈ [p, t1]
            if event::holds(tape, &out.x1) {
                let ev = event::between(tape, &self.flow, p, t1);
                return Ok(Some(ev));
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
        self.advance(t1, out.x1, out.rep);
        Ok(None)
    }

    /// The set moves to the end t1 of the step just scanned (its box `x1` and affine set
    /// `rep`), the step traced with `BWCL_TRACE`.
    fn advance(&mut self, t1: f64, x1: [I; N], rep: Option<AffineSet<N, I>>) {
        let t = self.t;
        if self.trace {
            let kind = if matches!(self.flow.pieces.last(), Some(Piece::Taylor { .. })) {
                "T"
            } else {
                "L"
            };
            eprintln!(
                "{kind} t={t:.6e} h={:.3e} w={:.3e} x={:?}",
                t1 - t,
                state_width(&x1, self.n_state),
                x1.iter().map(|c| c.mid()).collect::<Vec<f64>>()
            );
            let widths: Vec<String> = x1.iter().map(|c| format!("{:.1e}", c.wid_f64())).collect();
            eprintln!(
                "  widths {} (affine set: {})",
                widths.join(" "),
                rep.is_some()
            );
        }
        self.t = t1;
        self.x = x1;
        self.rep = rep;
    }
}
