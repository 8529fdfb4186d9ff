//! A branch point of a ranged set crossed with the crossing component as the independent
//! variable (issue #32 item 4).
//!
//! A set of parameter values carried at fixed times crosses a branch point x_j = 0 (eq:BWHCL's
//! Z = 0) over a spread of times ∝ its width; the second variational system's S₂ holds
//! |t − t_c(u)|^(q−1) terms there (q the power's exponent), so a set carried in time keeps a
//! width ∝ w^(q−1) of its S₂ — the floor of e″ measured on SHC DSS (benches/RESULTS.md). With
//! s = ±x_j as the independent variable every member is at the same distance from the branch
//! point at every "time" s, and the singular powers' integrals are exact
//! ([`super::integrable`], rate ±1):
//!
//! 1. **entry**: every member from its own s₀ = ±x_j to the common s_a = sup s₀ by a low-order
//!    step of member-dependent length Δs ∈ [0, s_a − s₀] in dx/ds = f/ẋ_j (x_j then exactly
//!    ±s_a for every member; the time t a component);
//! 2. Taylor windows in s to −ε, the low-order step across s ∈ [−ε, ε] (the integrals of
//!    |x_j|^r exact), windows to s_b; where the tape takes sgn x_j (|Z|^n with n = 1, SHC
//!    DSA: D_x f jumps at x_j = 0, so S₂ does, each member at its own time), two steps, to
//!    s = 0 and from it, with the jump of S₂ between them ([`super::integrable`]'s formula on
//!    the members' states at x_j = 0);
//! 3. **exit**: every member from its own time t_b to the common t₁ = sup t_b by a low-order
//!    step of length Δt ∈ [0, t₁ − t_b]; the time integration goes on from t₁.
//!
//! Every box the crossing passes through is checked to keep the kink components (|V|) and the
//! other components whose sign the tape takes away from 0 (their jumps of S₂ are not carried
//! here) and the separation condition F ≤ 0 ∧ V ≥ 0 false (the separation is not inside the
//! crossing).

use super::Flow;
use super::RigorError;
use super::options::TaylorOptions;
use super::rec::Rec;
use super::tape::{SecondOrder, Tape};
use super::window::Window;
use crate::arith::Real;
use inari::Interval;

/// Where and how far from the branch point the crossing starts and ends.
#[derive(Clone, Copy, Debug)]
pub struct CrossingOptions {
    /// The entry starts once |x_j| ≥ max(`near`, `spread`·wid x_j) for the whole set, as late
    /// as the flow allows, at s_a; the exit is at s_b = max(`near`, |s_a|).
    pub near: f64,
    pub spread: f64,
    /// The half-width ε of the low-order step across x_j = 0.
    pub eps: f64,
}

impl Default for CrossingOptions {
    fn default() -> Self {
        Self {
            near: 2e-3,
            spread: 8.0,
            eps: 1e-6,
        }
    }
}

/// A crossing done: the set at the common time `t1`, and the pieces it took.
pub struct Crossed<const D: usize> {
    pub t1: f64,
    pub x1: [Interval; D],
    pub steps: usize,
}

fn fail(reason: &str, t: f64) -> RigorError {
    RigorError {
        reason: format!("crossing a branch point in its variable: {reason}"),
        t,
        width: 0.0,
    }
}

/// 2⁵³: a multiple of 2⁻⁵³ in (−1, 0) plus 1 is a double.
const TWO_53: f64 = 9_007_199_254_740_992.0;

fn pt(x: f64) -> Interval {
    Interval::try_from((x, x)).expect("a finite double")
}

/// The branch components: switching components of the model's state (the first `n_state`)
/// that are not kinks.
fn branch_components<const D: usize>(tape: &Tape<Interval, D>, n_state: usize) -> Vec<usize> {
    tape.switching()
        .iter()
        .copied()
        .filter(|&j| j < n_state && !tape.kinks().contains(&j))
        .collect()
}

/// The first branch point a flow crosses, watched piece by piece as the flow grows (a run can
/// stop there, [`super::integrate_system_until`]): once every branch component has left 0 (the
/// start's double branch point is not crossed here), the first piece whose box holds 0 in a
/// branch component j, among the pieces ending before `before` (a time up to which the
/// separation condition is proved to fail: the run's `cleared`, or inf T_s);
/// with the last piece end t_a before it where the whole set is far enough from 0 in j. Only
/// that first crossing is reported (none if no piece end before it was far enough).
pub struct BranchWatch {
    comps: Vec<usize>,
    armed: bool,
    done: bool,
    seen: usize,
    last_far: Vec<Option<f64>>,
    co: CrossingOptions,
}

impl BranchWatch {
    pub fn new<const D: usize>(
        tape: &Tape<Interval, D>,
        n_state: usize,
        co: &CrossingOptions,
    ) -> Self {
        Self {
            comps: branch_components(tape, n_state),
            armed: false,
            done: false,
            seen: 0,
            last_far: vec![None; D],
            co: *co,
        }
    }

    /// The pieces of `flow` not looked at yet that end before `before`: the branch component j
    /// and t_a of the first crossing (once).
    pub fn next<const D: usize>(
        &mut self,
        flow: &Flow<D, Interval>,
        before: f64,
    ) -> Option<(usize, f64)> {
        let co = self.co;
        let far = |x: &Interval| x.mig() >= co.near.max(co.spread * x.wid());
        while !self.done && self.seen < flow.pieces.len() {
            let p = &flow.pieces[self.seen];
            if p.t1() >= before {
                return None;
            }
            self.seen += 1;
            let Ok(span) = Interval::try_from((p.t0(), p.t1())) else {
                self.done = true;
                return None;
            };
            let whole = p.enclose(&span);
            let end = p.enclose(&pt(p.t1()));
            if !self.armed {
                self.armed = self.comps.iter().all(|&j| whole[j].mig() > 0.0);
                if !self.armed {
                    continue;
                }
            }
            if let Some(&j) = self.comps.iter().find(|&&j| whole[j].contains(0.0)) {
                self.done = true;
                return self.last_far[j].map(|t_a| (j, t_a));
            }
            for &j in &self.comps {
                if far(&end[j]) {
                    self.last_far[j] = Some(p.t1());
                }
            }
        }
        None
    }
}

/// The box keeps the kinks and the components whose sign the tape takes ([`Tape::sign_jumps`],
/// but for `except`: the crossing component inside the crossing in s, whose jump
/// [`across_zero`] adds) off 0, and the separation condition false (module doc). The entry and
/// exit steps in time carry no jump: there the crossing component too must stay off 0.
fn clear<const D: usize>(
    tape: &Tape<Interval, D>,
    n_state: usize,
    except: Option<usize>,
    x: &[Interval],
) -> bool {
    let b: [Interval; D] = std::array::from_fn(|i| x[i]);
    let o = tape.eval(&b);
    let (f, v) = (o[D], o[D + 1]);
    let kinks_off = tape
        .kinks()
        .iter()
        .chain(tape.sign_jumps().0.iter().filter(|&&k| Some(k) != except))
        .all(|&k| k >= n_state || !b[k].contains(0.0));
    kinks_off && (f.inf() > 0.0 || v.sup() < 0.0) && b.iter().all(|c| !c.is_empty())
}

/// A low-order step of variable length: every member moves by its own Δ ∈ [0, `len`] in the
/// field `g`; the result holds every member's state after its own Δ. With the a-priori box.
fn ranged_step<const E: usize>(
    x: &[Interval; E],
    len: f64,
    params: &[usize],
    g: &dyn Fn(&[Interval; E]) -> [Interval; E],
) -> Option<([Interval; E], [Interval; E])> {
    let span = Interval::try_from((0.0, len)).ok()?;
    let f0 = g(x);
    let widen = |c: Interval, k: f64| {
        let r = c.rad() * k + 1e-300 + c.mag() * 1e-15;
        c + Interval::try_from((-r, r)).unwrap_or(Interval::ENTIRE)
    };
    let mut y: [Interval; E] = std::array::from_fn(|i| {
        if params.contains(&i) {
            x[i]
        } else {
            widen(x[i] + span * f0[i], 0.5)
        }
    });
    for _ in 0..20 {
        let fy = g(&y);
        let yn: [Interval; E] = std::array::from_fn(|i| x[i] + span * fy[i]);
        let inside = (0..E).all(|i| {
            !yn[i].is_empty()
                && yn[i].is_common_interval()
                && if params.contains(&i) {
                    yn[i].subset(y[i])
                } else {
                    yn[i].interior(y[i])
                }
        });
        if inside {
            return Some((yn, y));
        }
        y = std::array::from_fn(|i| {
            if params.contains(&i) {
                x[i]
            } else {
                widen(yn[i].convex_hull(y[i]), 0.25)
            }
        });
    }
    None
}

/// The layout of the second variational system where S₂ jumps as the members cross x_j = 0
/// (the t-tape takes sgn x_j, [`Tape::sign_jumps`]: |Z|^n with n = 1), else `None`.
fn jump_at_zero<const D: usize>(tape: &Tape<Interval, D>, j: usize) -> Option<SecondOrder> {
    tape.second_order()
        .filter(|_| tape.sign_jumps().0.contains(&j))
}

/// The low-order step across s ∈ [−ε, ε] (labels `l_m` = 1 − ε to `l_p` = 1 + ε) in the tape in
/// s. Where S₂ jumps at x_j = 0 (`jump`, [`jump_at_zero`]), each member at its own time: two
/// steps, to s = 0 and from it, with the jump ΔS₂ = (Df_before − Df_after)·(2S̃τ′ + f̃τ′²)
/// ([`integrable`](super::integrable)) added between them, evaluated on the members' states at
/// s = 0 (x_j = 0 exactly). Each step's field is bounded across its end at 0 (sgn x_j over a
/// box holding 0 is [−1, 1]).
#[allow(clippy::too_many_arguments)]
fn across_zero<const D: usize, const E: usize>(
    tape: &Tape<Interval, D>,
    wtape: &Tape<Interval, E>,
    jump: Option<SecondOrder>,
    j: usize,
    sg: f64,
    l_m: f64,
    x: &[Interval; E],
    l_p: f64,
) -> Option<Vec<super::step::StepOut<E>>> {
    let Some(lay) = jump else {
        return super::step::low_order_to(wtape, l_m, x, l_p).map(|a| vec![a]);
    };
    let to_zero = super::step::low_order_to(wtape, l_m, x, 1.0)?;
    let mut mid = to_zero.x1;
    // every member is at x_j = sg·(l − 1) = 0 exactly at the label l = 1 (`cross` made the
    // entry's label exact): the jump happens at this step's end
    if !mid[j].contains(0.0) {
        return None;
    }
    mid[j] = pt(0.0);
    let at: [Interval; D] = std::array::from_fn(|i| mid[i]);
    // jump_of's d = Df₋ − Df₊: before the crossing x_j has the sign −sg (s < 0)
    let d = super::integrable::sign_jump_at_zero(tape, lay, &at, j);
    for i in 0..lay.n {
        let di = if sg > 0.0 { d[i] } else { -d[i] };
        mid[lay.s2(i)] = mid[lay.s2(i)] + di;
    }
    if !mid.iter().all(|c| c.is_common_interval()) {
        return None;
    }
    let from_zero = super::step::low_order_to(wtape, 1.0, &mid, l_p)?;
    Some(vec![to_zero, from_zero])
}

/// Crosses the branch point x_j = 0 from the set `xa` at t_a (module doc): the set at the
/// common time after it. `E` = `D` + 1 (the state and t).
pub fn cross<const D: usize, const E: usize>(
    tape: &Tape<Interval, D>,
    n_state: usize,
    j: usize,
    t_a: f64,
    xa: &[Interval; D],
    opts: &TaylorOptions,
    co: &CrossingOptions,
) -> Result<Crossed<D>, RigorError> {
    assert_eq!(E, D + 1);
    let sg = match Real::sign(&xa[j]) {
        Some(s) => -f64::from(s),
        None => return Err(fail("the set holds the branch point at its start", t_a)),
    };
    let sgi = pt(sg);
    // x_j moves towards 0 (ds/dt = sg·ẋ_j > 0 over the set)
    if (sgi * tape.eval(xa)[j]).inf() <= 0.0 {
        return Err(fail("the set does not move towards the branch point", t_a));
    }
    let params: Vec<usize> = tape.params().to_vec();
    // the tape in s: dx/ds = f·sg/f_j (x_j: sg exactly), dt/ds = sg/f_j
    let rtape = tape.map(|c| Rec::constant(*c));
    let mut params_e: [Option<Interval>; E] = [None; E];
    for &i in &params {
        params_e[i] = Some(xa[i]);
    }
    let wtape = Tape::<Interval, E>::record_with(params_e, |v| {
        let x: [Rec<Interval>; D] = std::array::from_fn(|i| v[i].clone());
        let f = rtape.eval(&x);
        let fj = f[j].clone();
        let mut o: Vec<Rec<Interval>> = (0..D)
            .map(|i| {
                if i == j {
                    Rec::constant(sgi)
                } else if params.contains(&i) {
                    Rec::constant(pt(0.0))
                } else {
                    f[i].clone() * Rec::constant(sgi) / fj.clone()
                }
            })
            .collect();
        o.push(Rec::constant(sgi) / fj);
        o
    });
    let in_s = |y: &[Interval; E]| -> [Interval; E] {
        let v = wtape.eval(y);
        std::array::from_fn(|i| v[i])
    };
    let mut steps = 0;
    // 1. entry: to the common s_a
    let s0 = sgi * xa[j];
    // where S₂ jumps at x_j = 0 (sgn x_j on the tape), the label 1 + s_a exact: x_j = sg·(l − 1)
    // exactly at every label l, 0 at l = 1 (s_a rounded up to a multiple of 2⁻⁵³: every member
    // still moves forward to it)
    let jump = jump_at_zero(tape, j);
    let s_a = if jump.is_some() {
        (s0.sup() * TWO_53).ceil() / TWO_53
    } else {
        s0.sup()
    };
    let ds = (pt(s_a) - s0).sup();
    let xe: [Interval; E] = std::array::from_fn(|i| if i < D { xa[i] } else { pt(t_a) });
    let (mut x_entry, y) = ranged_step(&xe, ds, &params, &in_s)
        .ok_or_else(|| fail("no entry step to a common distance", t_a))?;
    if !clear(tape, n_state, None, &y) {
        return Err(fail("a kink or the separation inside the entry", t_a));
    }
    x_entry[j] = sgi * pt(s_a);
    steps += 1;
    // 2. windows in s (labels 1 + s: no time label near 0) and the step across 0
    let win = Window::of_tape(wtape.clone());
    // (the exit as far from 0 as the entry: the members' spread in time after the crossing is
    // about their spread in x_j before it, over the rate)
    let s_b = co.near.max(-s_a);
    let (l_a, l_m, l_p, l_b) = (1.0 + s_a, 1.0 - co.eps, 1.0 + co.eps, 1.0 + s_b);
    if l_a.is_nan() || l_a >= l_m {
        return Err(fail("the set starts too near the branch point", t_a));
    }
    let w1 = win.enclose(x_entry, l_a, l_m, opts)?;
    let across = across_zero(tape, &wtape, jump, j, sg, l_m, &w1.x1, l_p)
        .ok_or_else(|| fail("no step across the branch point", t_a))?;
    let w2 = win.enclose(across.last().expect("a step").x1, l_p, l_b, opts)?;
    let boxes_clear = w1
        .flow
        .pieces
        .iter()
        .chain(across.iter().map(|a| &a.piece))
        .chain(w2.flow.pieces.iter())
        .all(|p| {
            Interval::try_from((p.t0(), p.t1()))
                .is_ok_and(|span| clear(tape, n_state, Some(j), &p.enclose(&span)))
        })
        && across
            .iter()
            .all(|a| clear(tape, n_state, Some(j), &a.apriori));
    if !boxes_clear {
        return Err(fail("a kink or the separation inside the crossing", t_a));
    }
    steps += w1.steps + across.len() + w2.steps;
    // 3. exit: to the common time t1
    let xb = w2.x1;
    let t1 = xb[D].sup();
    let dt = (pt(t1) - xb[D]).sup();
    let in_t = |y: &[Interval; E]| -> [Interval; E] {
        let yd: [Interval; D] = std::array::from_fn(|i| y[i]);
        let f = tape.eval(&yd);
        std::array::from_fn(|i| if i < D { f[i] } else { pt(1.0) })
    };
    let xbt: [Interval; E] = std::array::from_fn(|i| if i < D { xb[i] } else { pt(0.0) });
    let (x_t1, y) = ranged_step(&xbt, dt, &params, &in_t)
        .ok_or_else(|| fail("no exit step to a common time", t1))?;
    if !clear(tape, n_state, None, &y) {
        return Err(fail("a kink or the separation inside the exit", t1));
    }
    steps += 1;
    Ok(Crossed {
        t1,
        x1: std::array::from_fn(|i| x_t1[i]),
        steps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::Scalar;

    fn iv(lo: f64, hi: f64) -> Interval {
        Interval::try_from((lo, hi)).unwrap()
    }

    fn c(x: f64) -> Rec<Interval> {
        Rec::constant(iv(x, x))
    }

    /// ż = u, ẏ = |z|^(−1/2) (z the branch component, u ∈ `u` a parameter), the outputs F
    /// and V the constants `fv`.
    fn closed_form(u: Interval, fv: (f64, f64)) -> Tape<Interval, 3> {
        closed_form_with(u, |_| c(fv.0), fv.1)
    }

    /// [`closed_form`] with F = `force`(z), V = `v`.
    fn closed_form_with(
        u: Interval,
        force: impl Fn(&Rec<Interval>) -> Rec<Interval>,
        v: f64,
    ) -> Tape<Interval, 3> {
        let mut params = [None; 3];
        params[2] = Some(u);
        Tape::<Interval, 3>::record_with(params, |x| {
            vec![
                x[2].clone() + x[0].scale(&iv(0.0, 0.0)),
                Scalar::<Interval>::apow(&x[0], &iv(-0.5, -0.5)),
                c(0.0),
                force(&x[0]),
                c(v),
            ]
        })
    }

    /// The crossing of z = 0 from the set `xa` at t_a = 0.5 (the last component a parameter).
    fn crossing<const D: usize, const E: usize>(
        tape: &Tape<Interval, D>,
        xa: &[Interval; D],
    ) -> Result<Crossed<D>, RigorError> {
        let co = CrossingOptions {
            near: 1e-3,
            ..CrossingOptions::default()
        };
        let opts = TaylorOptions {
            max_width: 1.0,
            ..TaylorOptions::default()
        };
        cross::<D, E>(tape, D - 1, 0, 0.5, xa, &opts, &co)
    }

    /// ż = u, ẏ = |z|^(−1/2) (z the branch component, u a parameter), F = 1, V = −1 (no
    /// separation): y(t) = (2/u)(sgn z(t)·√|z(t)| − sgn z0·√|z0|), z(t) = z0 + ut.
    #[test]
    fn a_branch_point_crossed_in_its_variable_holds_every_member() {
        let tape = closed_form(iv(0.9, 1.1), (1.0, -1.0));
        assert_eq!(tape.switching(), &[0]);
        // the members: z0 ∈ [−0.012, −0.010], y0 = 0, u ∈ [0.9, 1.1] at t_a = 0.5
        let xa = [iv(-0.012, -0.010), iv(0.0, 0.0), iv(0.9, 1.1)];
        let c = crossing::<3, 4>(&tape, &xa).unwrap_or_else(|e| panic!("{}", e.reason));
        let dt = c.t1 - 0.5;
        assert!(dt > 0.0);
        let k = |z: f64| 2.0 * z.signum() * z.abs().sqrt();
        for z0 in [-0.012, -0.011, -0.010] {
            for u in [0.9, 1.0, 1.1] {
                let z = z0 + u * dt;
                let y = (k(z) - k(z0)) / u;
                assert!(
                    c.x1[0].contains(z),
                    "z {:?} misses {z} (z0 {z0}, u {u})",
                    c.x1[0]
                );
                assert!(
                    c.x1[1].contains(y),
                    "y {:?} misses {y} (z0 {z0}, u {u})",
                    c.x1[1]
                );
            }
        }
        // (the members spread over ≈ 0.1: u ± 10 %)
        assert!(c.x1[1].wid() < 0.3, "{:?}", c.x1[1]);
    }

    /// The watch over a flow with z = −0.3 + t in pieces of 0.1 (z = 0 inside [0.2, 0.3]):
    /// the crossing from t_a = 0.2, reported only once the piece holding it ends before
    /// `before` (the separation may not be excluded after it), and once only.
    #[test]
    fn the_watch_reports_a_branch_point_only_before_the_separation() {
        use super::super::flow::Piece;
        let tape = closed_form(iv(0.9, 1.1), (1.0, -1.0));
        let mut flow = Flow::<3, Interval>::default();
        for k in 0..4 {
            let t0 = 0.1 * k as f64;
            flow.pieces.push(Piece::LowOrder {
                t0,
                t1: 0.1 * (k + 1) as f64,
                x0: [iv(-0.3, -0.3) + iv(t0, t0), iv(0.0, 0.0), iv(0.9, 1.1)],
                slope: [iv(1.0, 1.0), iv(0.0, 0.0), iv(0.0, 0.0)],
            });
        }
        let co = CrossingOptions::default();
        let mut watch = BranchWatch::new(&tape, 2, &co);
        assert_eq!(watch.next(&flow, 0.25), None);
        assert_eq!(watch.next(&flow, 1.0), Some((0, 0.2)));
        assert_eq!(watch.next(&flow, 1.0), None);
        assert_eq!(
            BranchWatch::new(&tape, 2, &co).next(&flow, 1.0),
            Some((0, 0.2))
        );
    }

    /// The crossing's own checks, each on the closed-form system above changed so that it
    /// must refuse: the reason.
    fn refused<const D: usize, const E: usize>(
        tape: &Tape<Interval, D>,
        xa: [Interval; D],
    ) -> String {
        match crossing::<D, E>(tape, &xa) {
            Ok(c) => panic!("crossed to t1 = {}: {:?}", c.t1, c.x1),
            Err(e) => e.reason,
        }
    }

    /// ż = u < 0 from z0 < 0: the set moves away from the branch point (crossed "in s" it would
    /// run backwards in time).
    #[test]
    fn a_set_moving_away_from_the_branch_point_is_not_crossed() {
        let r = refused::<3, 4>(
            &closed_form(iv(-1.1, -0.9), (1.0, -1.0)),
            [iv(-0.012, -0.010), iv(0.0, 0.0), iv(-1.1, -0.9)],
        );
        assert!(r.contains("does not move towards"), "{r}");
    }

    /// F = −1, V = 1: the separation condition holds all along; no crossing may pass it.
    #[test]
    fn a_crossing_through_the_separation_is_refused() {
        let r = refused::<3, 4>(
            &closed_form(iv(0.9, 1.1), (-1.0, 1.0)),
            [iv(-0.012, -0.010), iv(0.0, 0.0), iv(0.9, 1.1)],
        );
        assert!(r.contains("separation"), "{r}");
    }

    /// F = −z − 0.005, V = 1: clear at the entry (z ≤ −0.010), the separation condition holds
    /// once z ≥ −0.005, inside the windows in s: refused by their boxes' check.
    #[test]
    fn a_separation_inside_the_windows_in_s_is_refused() {
        let tape = closed_form_with(iv(0.9, 1.1), |z| c(-0.005) - z.clone(), 1.0);
        let r = refused::<3, 4>(&tape, [iv(-0.012, -0.010), iv(0.0, 0.0), iv(0.9, 1.1)]);
        assert!(r.contains("separation inside the crossing"), "{r}");
    }

    /// k̇ = 1 from k0 = −0.001 with |k| in the field: the kink k = 0 is crossed while the set
    /// enters the crossing (the jump of S₂ at a kink is not carried by the crossing; the
    /// windows in s refuse a kink on their own, the entry and exit steps by this check).
    #[test]
    fn a_crossing_over_a_kink_is_refused() {
        let mut params = [None; 4];
        params[3] = Some(iv(0.9, 1.1));
        let tape = Tape::<Interval, 4>::record_with(params, |v| {
            vec![
                v[3].clone() + v[0].scale(&iv(0.0, 0.0)),
                Scalar::<Interval>::apow(&v[0], &iv(-0.5, -0.5))
                    + Scalar::<Interval>::abs(&v[2]).scale(&iv(1e-3, 1e-3)),
                c(1.0) + v[2].scale(&iv(0.0, 0.0)),
                c(0.0),
                c(1.0),
                c(-1.0),
            ]
        });
        let r = refused::<4, 5>(
            &tape,
            [
                iv(-0.012, -0.010),
                iv(0.0, 0.0),
                iv(-0.001, -0.001),
                iv(0.9, 1.1),
            ],
        );
        assert!(r.contains("kink or the separation inside the entry"), "{r}");
    }
}
