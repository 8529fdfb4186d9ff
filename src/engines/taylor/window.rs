//! The flow over a fixed time window: an enclosure of Φ(t1) from a set of states at t0, on a
//! stretch where the field is analytic.
//!
//! What it is for: comparisons with peers that integrate analytic fields only (kv's
//! `odelong_maffine`, `odelong_qr_lohner`: `benches/peers/`), and dense enclosures of the flow
//! over a given window from any start — a thin state or a box, e.g. a piece of the engine's own
//! dense output ([`super::Flow::enclose`]).
//!
//! A window [t0, t1] is meant to be a smooth stretch: every switching component (the operand
//! of a |·| or of a non-analytic power, eq:BWSHCCM_nd and eq:BWMCM_nd) keeps its sign on it, so
//! the field is analytic along the flow and every step is a Taylor step. The steps are the
//! engine's own, taken as [`super::integrate_system`] takes them between switching surfaces:
//!
//! ```text
//! h ≤ h_max = min(t1 − t, 0.9 · min_i |x_i| / |ẋ_i|)      (i: a branch-point component moving towards 0)
//! tol = max(opts.tol, 10⁻⁴ · width(X))
//! kd  = ⌈K/4⌉, or max(kd, K/2) for a wide set (width > WIDE_SET)
//! ```
//!
//! with [`step::taylor_step`] (order K, mean-value form on the kd lowest orders, a high-order
//! a-priori enclosure) and, with `opts.qr`, the set carried between steps as an affine set
//! ([`super::affine`]); the field is continued across the kinks of |·| from the
//! side of the start, and [`step::cut_at_kinks`] proves that no kink component reaches 0 on a
//! step. The last step ends at t1 exactly (a length h with fl(t + h) = t1).
//!
//! It fails, with a [`RigorError`] naming the component and the time, when a switching
//! component holds 0 at t0, when a kink component is proved to reach 0 inside the window (or
//! its crossing can be neither excluded nor proved), when a branch-point component approaches
//! 0 so that the steps shrink below `opts.min_taylor_step`, or when a step cannot be taken.

use super::affine::AffineSet;
use super::flow::Flow;
use super::options::WIDE_SET;
use super::step::{self, KinkCut, TaylorFail};
use super::tape::Tape;
use super::{DEADLINE, GREW_TOO_WIDE, RigorError, TaylorOptions};
use crate::arith::Enclosure;
use crate::models::CollisionModel;
use inari::Interval;

/// The start of the reason of a window that is not a smooth stretch: a switching component
/// holds 0 at t0, or reaches (or may reach) 0 inside the window.
pub const NOT_SMOOTH: &str = "the window is not a smooth stretch";
/// The start of the reason of a step that could not be taken for another cause (the flow too
/// fast for `opts.min_taylor_step`).
pub const NO_STEP: &str = "no Taylor step";
/// The start of the reason of a window or options that make no sense (t1 ≤ t0, order < 2, …).
pub const BAD_WINDOW: &str = "bad window";

/// A proved enclosure of the flow over [t0, t1].
#[derive(Clone, Debug)]
pub struct WindowEnclosure<const N: usize, I = Interval> {
    /// An enclosure of Φ(t1) for every start in the start set.
    pub x1: [I; N],
    /// The Taylor steps taken.
    pub steps: usize,
    /// The pieces from t0 to t1 (rigorous dense output on the window; [`Flow::enclose`]).
    pub flow: Flow<N, I>,
}

/// A model's field recorded once, to enclose its flow over windows ([`Window::enclose`]).
pub struct Window<const N: usize, I: Enclosure = Interval> {
    tape: Tape<I, N>,
    tapes: step::Tapes<N, I>,
    names: Option<[&'static str; N]>,
}

impl<const N: usize, I: Enclosure> Window<N, I> {
    /// The field f of `model` (the first N outputs the engine records in
    /// [`super::integrate_to_separation`]; a window needs no separation condition).
    pub fn new<M: CollisionModel<I, N>>(model: &M) -> Self {
        let mut w = Self::of_tape(Tape::record(|v| model.field(v).to_vec()));
        w.names = Some(M::STATE_NAMES);
        w
    }

    /// A recorded system: its first N outputs are the field (any others are ignored).
    pub fn of_tape(tape: Tape<I, N>) -> Self {
        Self {
            tapes: step::Tapes::of(&tape),
            tape,
            names: None,
        }
    }

    /// The recorded field.
    pub fn tape(&self) -> &Tape<I, N> {
        &self.tape
    }

    fn name(&self, i: usize) -> String {
        match &self.names {
            Some(n) => n[i].to_string(),
            None => format!("x[{i}]"),
        }
    }

    /// Encloses Φ(t1) for every start in the box `x0` at t0 (see the module doc). Like
    /// [`super::integrate_system`], called from outside rayon's pool it moves into the pool
    /// (the halves of each step are a `rayon::join`; `RAYON_NUM_THREADS=1`: one thread).
    pub fn enclose(
        &self,
        x0: [I; N],
        t0: f64,
        t1: f64,
        opts: &TaylorOptions,
    ) -> Result<WindowEnclosure<N, I>, RigorError> {
        if rayon::current_thread_index().is_some() {
            self.run(x0, t0, t1, opts)
        } else {
            rayon::scope(|_| self.run(x0, t0, t1, opts))
        }
    }

    fn run(
        &self,
        x0: [I; N],
        t0: f64,
        t1: f64,
        opts: &TaylorOptions,
    ) -> Result<WindowEnclosure<N, I>, RigorError> {
        let fail = |reason: String, t: f64, x: &[I; N]| RigorError {
            reason,
            t,
            width: step::width(x),
        };
        if !(t0.is_finite() && t1.is_finite() && t0 < t1)
            || opts.order < 2
            || opts.tol.is_nan()
            || opts.tol <= 0.0
        {
            return Err(fail(
                format!(
                    "{BAD_WINDOW}: [{t0}, {t1}] with order {} and tol {:e}",
                    opts.order, opts.tol
                ),
                t0,
                &x0,
            ));
        }
        let tape = &self.tape;
        let kinks = tape.kinks();
        // the window keeps the sign of every switching component: its start must have one;
        // the kink components continue the field from that side all along
        if let Some(&i) = tape.switching().iter().find(|&&i| x0[i].sign().is_none()) {
            return Err(fail(
                format!(
                    "{NOT_SMOOTH}: the switching component {} = [{:e}, {:e}] holds 0 at the start T = {t0}",
                    self.name(i),
                    x0[i].lo(),
                    x0[i].hi()
                ),
                t0,
                &x0,
            ));
        }
        let side: [i8; N] = std::array::from_fn(|i| match x0[i].sign() {
            Some(s) if kinks.contains(&i) => s,
            _ => 0,
        });
        let kd0 = match opts.mean_value_orders {
            0 => step::jacobian_orders(opts.order),
            k => k.min(opts.order),
        };
        let mut ws = step::Workspaces::<N, I>::default();
        let mut flow = Flow::default();
        let mut x = x0;
        let mut rep: Option<AffineSet<N, I>> = None;
        let mut t = t0;
        let mut steps = 0;
        while t < t1 {
            if steps >= opts.max_steps {
                return Err(fail(format!("more than {} steps", opts.max_steps), t, &x));
            }
            let w = step::width(&x);
            if !step::bounded(&x) || w > opts.max_width {
                return Err(fail(GREW_TOO_WIDE.into(), t, &x));
            }
            if opts.out_of_time() {
                return Err(fail(DEADLINE.into(), t, &x));
            }
            // the time for a branch-point component to reach 0 at its fastest (those moving
            // towards 0), as integrate_tape reads it
            let f = tape.eval(&x);
            let (mut h_surf, mut nearest) = (f64::INFINITY, 0);
            for &i in tape.switching().iter().filter(|i| !kinks.contains(i)) {
                let toward =
                    (x[i].lo() > 0.0 && f[i].lo() < 0.0) || (x[i].hi() < 0.0 && f[i].hi() > 0.0);
                if toward && x[i].mig_f64() / f[i].mag_f64() < h_surf {
                    (h_surf, nearest) = (x[i].mig_f64() / f[i].mag_f64(), i);
                }
            }
            // (the end of this stretch: t1, or a power of 2 on the way where no length lands
            // on t1 from t)
            let (target, to_end) = landing(t, t1).ok_or_else(|| {
                fail(
                    format!("no step length from T = {t} lands on {t1} (an internal error)"),
                    t,
                    &x,
                )
            })?;
            let surface_binds = 0.9 * h_surf < to_end;
            let mut hm = if surface_binds { 0.9 * h_surf } else { to_end };
            // the end binds: tried at full length (step::Workspaces::end_binds)
            ws.end_binds = !surface_binds;
            let h_min = if surface_binds {
                opts.min_taylor_step
            } else {
                // the last stretch may be shorter than the shortest Taylor step of a run
                opts.min_taylor_step.min(to_end)
            };
            let kd = if w > WIDE_SET && opts.mean_value_orders == 0 {
                kd0.max(opts.order / 2)
            } else {
                kd0
            };
            if !surface_binds && to_end < step::MIN_STEP_ULPS * step::time_spacing(t) {
                // closer to t1 than any Taylor step can advance (a few ulps: a previous step
                // ended just short of t1): a low-order step to t1 itself, checked to keep
                // every switching component's sign
                let o = step::low_order_to(tape, t, &x, target)
                    .filter(|o| {
                        tape.switching()
                            .iter()
                            .all(|&i| o.apriori[i].sign().is_some())
                    })
                    .ok_or_else(|| {
                        fail(
                            format!(
                                "{NO_STEP}: no low-order step over the last {to_end:e} to T = {target}"
                            ),
                            t,
                            &x,
                        )
                    })?;
                (t, x, rep) = (o.piece.t1(), o.x1, None);
                flow.pieces.push(o.piece);
                steps += 1;
                continue;
            }
            let out = loop {
                let o = step::taylor_step(
                    &self.tapes,
                    &mut ws,
                    t,
                    &x,
                    opts.order,
                    kd,
                    opts.tol.max(1e-4 * w),
                    hm,
                    h_min,
                    &side,
                    if opts.qr { rep.as_ref() } else { None },
                );
                let o = match o {
                    Ok(o) => o,
                    Err(why) => {
                        let why = match why {
                            TaylorFail::AtSurface => "the jet does not exist on the start box",
                            TaylorFail::TooShort => "no step validates above the shortest length",
                        };
                        let reason = if surface_binds {
                            format!(
                                "{NOT_SMOOTH}: {} approaches its switching surface 0 (within {h_surf:.3e} of T = {t} at its present rate, before the window's end {t1}): {why}",
                                self.name(nearest)
                            )
                        } else {
                            format!("{NO_STEP} from T = {t} (h ≤ {hm:.3e}): {why}")
                        };
                        return Err(fail(reason, t, &x));
                    }
                };
                // the kink components whose a-priori box on the step reaches 0
                let near_kinks = || {
                    let k: Vec<String> = kinks
                        .iter()
                        .filter(|&&i| o.apriori[i].sign().is_none())
                        .map(|&i| self.name(i))
                        .collect();
                    k.join(" or ")
                };
                match step::cut_at_kinks(tape, &o, &side) {
                    KinkCut::Whole => break o,
                    KinkCut::Before(tc) => {
                        return Err(fail(
                            format!(
                                "{NOT_SMOOTH}: the kink component {} reaches 0 at a proved T ∈ [{tc}, {}], inside [{t0}, {t1}]",
                                near_kinks(),
                                o.piece.t1()
                            ),
                            t,
                            &x,
                        ));
                    }
                    // neither excluded nor enclosed on this step: a shorter one, as
                    // integrate_tape tries
                    KinkCut::Unresolved => {
                        flow.refused_taylor += 1;
                        hm = 0.5 * (o.piece.t1() - t);
                        if hm < h_min {
                            return Err(fail(
                                format!(
                                    "{NOT_SMOOTH}: the kink component {} may reach 0 after T = {t} (neither excluded nor proved down to steps of {h_min:e})",
                                    near_kinks()
                                ),
                                t,
                                &x,
                            ));
                        }
                    }
                }
            };
            (t, x, rep) = (out.piece.t1(), out.x1, out.rep);
            flow.pieces.push(out.piece);
            steps += 1;
        }
        Ok(WindowEnclosure { x1: x, steps, flow })
    }
}

/// Encloses the flow of `model` over [t0, t1] from the box `x0` ([`Window::enclose`]; records
/// the field on every call: to integrate many windows, keep a [`Window`]).
pub fn enclose_window<I: Enclosure, M: CollisionModel<I, N>, const N: usize>(
    model: &M,
    x0: [I; N],
    t0: f64,
    t1: f64,
    opts: &TaylorOptions,
) -> Result<WindowEnclosure<N, I>, RigorError> {
    Window::new(model).enclose(x0, t0, t1, opts)
}

/// Where the steps from t head for t1 (t < t1 doubles): (t1, h) with fl(t + h) = t1 when
/// such a length exists ([`end_length`]); else a stop on the way, (b, h) with fl(t + h) = b, b
/// a power of 2 (or 0) in (t, t1) from which every length t1 − b is exact: 0 where t < 0 < t1,
/// the start of t1's binade for t1 > 0, the end of |t1|'s binade (−2^(e+1), |t1| ∈ [2^e,
/// 2^(e+1))) for t1 < 0. There may be no length h with fl(t + h) = t1 when the sum crosses
/// into a coarser binade: on ties to even, fl(t + h) skips every other double there (≈ 5 % of
/// random windows from [0.1, 1] to [1, 4]).
fn landing(t: f64, t1: f64) -> Option<(f64, f64)> {
    if let Some(h) = end_length(t, t1) {
        return Some((t1, h));
    }
    // 2^e for |x| ∈ [2^e, 2^(e+1)) (normal x), from the exponent bits: log₂ may round up
    let binade = |x: f64| f64::from_bits(x.abs().to_bits() & 0x7ff0_0000_0000_0000);
    let b = if t < 0.0 && t1 > 0.0 {
        0.0
    } else if t1 > 0.0 {
        binade(t1)
    } else {
        -2.0 * binade(t1)
    };
    (t < b && b < t1).then(|| end_length(t, b).map(|h| (b, h)))?
}

/// A step length h ≥ 0 with fl(t + h) = t1 (t < t1 doubles): fl(t1 − t), moved by an ulp or
/// two where the sum rounds to a neighbour of t1 (a tie, or t1 a power of 2). `None` if there
/// is none near (see [`landing`]).
fn end_length(t: f64, t1: f64) -> Option<f64> {
    let mut h = t1 - t;
    for _ in 0..4 {
        let s = t + h;
        if s == t1 {
            return Some(h);
        }
        h = if s < t1 { h.next_up() } else { h.next_down() };
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::Real;
    use crate::models::params::TABLE1;
    use crate::models::scaling::nd_from_base;
    use crate::models::{Admissibility, Maxwell, ModelKind, NdParams, Shc};
    use crate::observables::rigorous::rigorous_impact;

    /// 𝓟(P*, 1) of a Table 1 set.
    fn table1_at_1(name: &str) -> (ModelKind, NdParams<Interval>) {
        let (_, kind, base) = TABLE1.iter().find(|c| c.0 == name).expect("a Table 1 set");
        let b = NdParams::<Interval>::parse(*kind, base).unwrap();
        let one = Interval::from_exact_f64(1.0);
        (*kind, nd_from_base(*kind, &b, &one).unwrap())
    }

    /// (a): the window [0.5, 1.5] from the engine's own dense output at 0.5 meets its dense
    /// output at 1.5 and is no more than 100× as wide, component by component.
    fn agrees_with_the_dense_output<M: CollisionModel<Interval, N>, const N: usize>(model: &M) {
        let opts = TaylorOptions::default();
        let full = rigorous_impact(model, &opts).expect("a proved impact");
        let x0 = full.flow.enclose(0.5).unwrap();
        let dense = full.flow.enclose(1.5).unwrap();
        let win = enclose_window(model, x0, 0.5, 1.5, &opts).unwrap();
        assert_eq!(win.flow.t_end(), 1.5);
        assert_eq!(win.flow.len(), win.steps);
        for (i, (a, b)) in win.x1.iter().zip(&dense).enumerate() {
            assert!(
                !a.intersection(b).is_empty(),
                "{i}: {a} and {b} are disjoint"
            );
            assert!(a.wid() <= 100.0 * b.wid(), "{i}: {a} against {b}");
        }
        // the window's own dense output: from t0 to t1, meeting the end box at t1
        let e = win.flow.enclose(1.5).unwrap();
        assert!((0..N).all(|i| !e[i].intersection(win.x1[i]).is_empty()));
        assert!(win.flow.enclose(0.5).is_some() && win.flow.enclose(0.4).is_none());
    }

    #[test]
    fn shc_window_agrees_with_the_dense_output() {
        agrees_with_the_dense_output(&Shc::new(table1_at_1("SHC DSS").1));
    }

    #[test]
    fn maxwell_window_agrees_with_the_dense_output() {
        agrees_with_the_dense_output(&Maxwell::new(table1_at_1("Maxwell DSS").1));
    }

    /// (b): B = Γ = σ = 0, κ = 1/2, n = p = 1 (the harmonic case of eq:BWSHCCM_nd): from
    /// X = Z, Ẋ = Ż = V and V̇ = −X, so X = Z = −sin T, V = −cos T through the model's start;
    /// the window [0.5, 1.5] (X, Z, V < 0 on it) from that state at 0.5 holds it at 1.5.
    #[test]
    fn harmonic_window_holds_the_closed_form() {
        let p = NdParams::<Interval>::with_admissibility(
            ModelKind::Shc,
            Admissibility::Closed,
            Interval::from_exact_f64(0.0),
            Interval::from_exact_f64(0.0),
            Interval::from_exact_f64(0.5),
            Interval::from_exact_f64(0.0),
            Interval::from_exact_f64(1.0),
            Interval::from_exact_f64(1.0),
        )
        .unwrap();
        let at = |t: f64| {
            let t = Interval::from_exact_f64(t);
            let s = -t.sin();
            [s, s, -t.cos()]
        };
        let win = enclose_window(
            &Shc::new(p.clone()),
            at(0.5),
            0.5,
            1.5,
            &TaylorOptions::default(),
        )
        .unwrap();
        let exact = at(1.5);
        for (e, w) in exact.iter().zip(win.x1) {
            assert!(e.subset(&w) && w.wid() < 1e-14, "{w} against {e}");
        }
        // a box of radius r = 1e-9 around the start: the flow over the window is linear,
        // (X, Z, V) ↦ (X (c+1)/2 + Z (c−1)/2 + V s, the same with X and Z swapped,
        // −(X + Z) s/2 + V c) with c = cos 1, s = sin 1 (X − Z is constant, (X+Z)/2 and V
        // rotate), so the box's image has the widths 2r (1 + s, 1 + s, s + c): the enclosure
        // holds the image of the start box's corners and is not much wider
        let r = 1e-9;
        let x0 = at(0.5).map(|c| c + Interval::try_from((-r, r)).unwrap());
        let win = enclose_window(&Shc::new(p), x0, 0.5, 1.5, &TaylorOptions::default()).unwrap();
        let (c, s) = (1f64.cos(), 1f64.sin());
        let optimum = [2.0 * r * (1.0 + s), 2.0 * r * (1.0 + s), 2.0 * r * (s + c)];
        for ((e, w), o) in exact.iter().zip(win.x1).zip(optimum) {
            let ratio = w.wid() / o;
            assert!(
                e.subset(&w) && ratio > 0.999 && ratio < 1.5,
                "{w} against {e} ({ratio} × the image's width)"
            );
        }
    }

    /// (c): on SHC DSS, v0 = 1, V crosses 0 near T ≈ 1.60: the window [0.5, 2] is refused
    /// with the component named; a start box holding 0 in a switching component too.
    #[test]
    fn a_window_across_v_equal_0_is_refused() {
        let model = Shc::new(table1_at_1("SHC DSS").1);
        let opts = TaylorOptions::default();
        let full = rigorous_impact(&model, &opts).unwrap();
        let x0 = full.flow.enclose(0.5).unwrap();
        let e = enclose_window(&model, x0, 0.5, 2.0, &opts).unwrap_err();
        assert!(e.reason.starts_with(NOT_SMOOTH), "{e}");
        assert!(e.reason.contains('V'), "{e}");
        assert!(e.t > 1.0 && e.t < 1.61, "{e}");
        let mut x0 = x0;
        x0[2] = Interval::try_from((-1e-3, 1e-3)).unwrap();
        let e = enclose_window(&model, x0, 0.5, 1.5, &opts).unwrap_err();
        assert!(
            e.reason.starts_with(NOT_SMOOTH) && e.reason.contains("V ="),
            "{e}"
        );
        let e = enclose_window(&model, full.flow.enclose(0.5).unwrap(), 1.5, 0.5, &opts);
        assert!(e.unwrap_err().reason.starts_with(BAD_WINDOW));
    }

    #[test]
    fn end_lengths_land_on_the_end() {
        for (t, t1) in [
            (0.5, 1.5),
            (0.1, 1.0),
            (1e-300, 2.0),
            (0.3, 4.0),
            (3.0, 4.0),
        ] {
            let h = end_length(t, t1).unwrap();
            assert_eq!(t + h, t1, "{t} {t1}");
        }
    }

    /// No length from 0.6758… lands on 3.4657… (fl(t + h) skips it on ties to even): the
    /// window stops at 2 on the way, and still ends at t1 (x′ = 1, whose one step would span the
    /// whole window: x(t1) = 1 + t1 − t0 exactly, compared as rationals).
    #[test]
    fn a_window_whose_end_no_length_lands_on_stops_on_the_way() {
        use rug::Rational;
        // (log₂ of 8 − 2⁻⁵⁰ rounds to 3: the stop is 4, from the exponent bits; below 0 the stop
        // is the end of |t1|'s binade)
        for (t, t1, b) in [
            (2.0000000000000004, 7.999999999999999, 4.0),
            (-2.4759292541837827, -0.6265375351775712, -1.0),
        ] {
            assert_eq!(end_length(t, t1), None);
            let (stop, h) = landing(t, t1).unwrap();
            assert_eq!((stop, t + h), (b, b));
            assert_eq!(b + end_length(b, t1).unwrap(), t1);
        }
        let (t0, t1) = (0.6758310236303944, 3.4657351028000467);
        assert_eq!(end_length(t0, t1), None);
        assert_eq!(landing(t0, t1).map(|l| l.0), Some(2.0));
        let one = Interval::from_exact_f64(1.0);
        let win = Window::of_tape(Tape::<Interval, 1>::record(|v| {
            let c = |x: f64| super::super::rec::Rec::constant(Interval::from_exact_f64(x));
            vec![v[0].clone() * c(0.0) + c(1.0)]
        }));
        let w = win
            .enclose([one], t0, t1, &TaylorOptions::default())
            .unwrap_or_else(|e| panic!("{}", e.reason));
        assert_eq!(w.flow.t_end(), t1);
        assert!(w.flow.pieces.iter().any(|p| p.t1() == 2.0), "{}", w.steps);
        let exact =
            Rational::from(1) + Rational::from_f64(t1).unwrap() - Rational::from_f64(t0).unwrap();
        let (lo, hi) = (
            Rational::from_f64(w.x1[0].inf()).unwrap(),
            Rational::from_f64(w.x1[0].sup()).unwrap(),
        );
        assert!(lo <= exact && exact <= hi, "{:?}", w.x1[0]);
        assert!(w.x1[0].wid() < 1e-14, "{:?}", w.x1[0]);
    }
}
