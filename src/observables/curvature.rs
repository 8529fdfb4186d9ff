//! Second derivatives of T_s and e in one input u over a range of it, proved: one run of the
//! second variational system (x, u, S, S₂) ([`SecondOrder`]), S = ∂x/∂u, S₂ = ∂²x/∂u²,
//!
//! ```text
//! Ṡ = D_x f·S + ∂_u f,     Ṡ₂ = D_x f·S₂ + D²f[S̃, S̃]   (S̃ = (S, 1)),   S(0) = S₂(0) = 0,
//! ```
//!
//! the field differentiated twice on hyper-duals (the models unchanged). D²f holds |Z|^(n−2)
//! and |X|^(p−2) (eq:BWHCL, eq:BWMCM_nd): unbounded at the branch points but integrable along
//! a path crossing them, which the engine's low-order step bounds, and the kink |V| makes S₂
//! jump ([`crate::engines::taylor::integrable`]), as |Z| does where n = 1 (SHC DSA: Z = 0 is
//! crossed in its variable with the jump at Z = 0, [`crate::engines::taylor::crossing`]). At
//! the separation (F = 0 crossed with
//! V > 0), with G(T, u) = F(x(T, u), u) and H(T, u) = V(x(T, u), u), the implicit function
//! theorem twice:
//!
//! ```text
//! T′ = −G_u/G_T,     T″ = −(G_uu + 2·G_uT·T′ + G_TT·T′²)/G_T,
//! e′ = H_u + H_T·T′,  e″ = H_uu + 2·H_uT·T′ + H_TT·T′² + H_T·T″
//! ```
//!
//! each factor enclosed over the event's state box (every T_s(u), every u). Where the
//! separation is V = 0 crossed upwards with F < 0 for the whole range, e ≡ 0. What it is for:
//! e(v) − L(v) ∈ [e″]·(v − v_k)(v − v_{k+1})/2 between proved point values (the band at a
//! thickness far below the first-order form's, issue #32 item 4), convexity over a range.

use super::sets::{AtEvent, Inputs, is_range, model_start, param_error, parameter_slots};
use crate::arith::Real;
use crate::arith::jet::dual::Dual;
use crate::engines::taylor::crossing;
use crate::engines::taylor::rec::Rec;
use crate::engines::taylor::tape::{SecondOrder, Tape};
use crate::engines::taylor::{
    Ended, Flow, RigorError, SeparationEvent, TaylorOptions, integrate_system,
    integrate_system_until,
};
use crate::models::{CollisionModel, Maxwell, ModelKind, NdParams, Shc};
use inari::Interval;

/// The hyper-dual numbers of the recording: value, two first derivatives, the second.
type H = Dual<Dual<Rec<Interval>, 1>, 1>;

/// T_s, e and their first and second derivatives in one input over a range of it.
#[derive(Clone, Copy, Debug)]
pub struct Curvature {
    /// The ranged input's index in [`Inputs::values`].
    pub input: usize,
    pub ts: Interval,
    pub e: Interval,
    pub ts1: Interval,
    pub e1: Interval,
    pub ts2: Interval,
    pub e2: Interval,
    /// Pieces of the proved flow.
    pub steps: usize,
}

fn fail(reason: &str, t: f64, width: f64) -> RigorError {
    RigorError {
        reason: reason.into(),
        t,
        width,
    }
}

/// [`Curvature`] of model `kind` over `inputs`, exactly one of which is a range.
pub fn curvature_over_range(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    opts: &TaylorOptions,
) -> Result<Curvature, RigorError> {
    inputs.nd(kind).map_err(param_error)?;
    let vals = inputs.values();
    let ranges: Vec<usize> = (0..vals.len()).filter(|&i| is_range(&vals[i])).collect();
    let [ju] = ranges[..] else {
        return Err(fail(
            &format!(
                "{} inputs are ranges; the second derivatives need exactly 1",
                ranges.len()
            ),
            0.0,
            0.0,
        ));
    };
    match kind {
        ModelKind::Shc => second::<_, 3, 10, 11>(Shc::new, kind, inputs, ju, opts),
        ModelKind::Maxwell => second::<_, 4, 13, 14>(Maxwell::new, kind, inputs, ju, opts),
    }
}

/// The run of the system (x, u, S, S₂) and the derivatives at its separation.
fn second<M, const N: usize, const D: usize, const E: usize>(
    build: impl Fn(NdParams<H>) -> M,
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    ju: usize,
    opts: &TaylorOptions,
) -> Result<Curvature, RigorError>
where
    M: CollisionModel<H, N>,
{
    let lay = SecondOrder { n: N };
    assert_eq!(D, 3 * N + 1);
    let vals = inputs.values();
    let (params, mut x0) = parameter_slots::<N, D>(&vals, &[ju], 1);
    let c = |x: Interval| Rec::constant(x);
    let (one, zero) = (<Interval as Real>::one(), <Interval as Real>::zero());
    let hyper = |a: Rec<Interval>, b: Rec<Interval>, d: Rec<Interval>| H {
        v: Dual {
            v: a,
            d: [b.clone()],
        },
        d: [Dual { v: b, d: [d] }],
    };
    // the set validated as intervals above; on hyper-duals a derivative may still be unbounded
    // (∂²/∂n² of v0^(2n/(p+1)) for a base set at v0 = 1): an error, not a panic
    let mut recorded = Ok(());
    let tape = Tape::<Interval, D>::record_with(params, |v| {
        let hv: Vec<H> = (0..vals.len())
            .map(|i| {
                if i == ju {
                    hyper(v[lay.u()].clone(), c(one), c(zero))
                } else {
                    H::constant(Dual::constant(c(vals[i])))
                }
            })
            .collect();
        let nd = match inputs.with_values(hv).nd(kind) {
            Ok(nd) => nd,
            Err(e) => {
                recorded = Err(e);
                return vec![c(zero); D + 6];
            }
        };
        let m = build(nd);
        let xs: [H; N] =
            std::array::from_fn(|i| hyper(v[i].clone(), v[lay.s(i)].clone(), v[lay.s2(i)].clone()));
        let f = m.field(&xs);
        let (force, vel) = (m.force(&xs), m.velocity(&xs));
        let mut o: Vec<Rec<Interval>> = f.iter().map(|q| q.v.v.clone()).collect();
        o.push(c(zero));
        o.extend(f.iter().map(|q| q.v.d[0].clone()));
        o.extend(f.iter().map(|q| q.d[0].d[0].clone()));
        // outputs D.. : F, V, F_u, V_u, F_uu, V_uu
        o.extend([
            force.v.v.clone(),
            vel.v.v.clone(),
            force.v.d[0].clone(),
            vel.v.d[0].clone(),
            force.d[0].d[0].clone(),
            vel.d[0].d[0].clone(),
        ]);
        o
    })
    .with_second_order(lay);
    if let Err(e) = recorded {
        return Err(fail(
            &format!(
                "the second derivatives in {} are not bounded at the set ({})",
                inputs
                    .names()
                    .get(ju)
                    .copied()
                    .unwrap_or("the ranged input"),
                e.0
            ),
            0.0,
            0.0,
        ));
    }
    if let Some(j) = tape.jump_off_the_kinks() {
        return Err(fail(
            &format!(
                "the field's derivative jumps where state component {j} crosses 0 (a power of \
                 exponent 0 or of a varying exponent): the second derivatives are not carried \
                 across it"
            ),
            0.0,
            0.0,
        ));
    }
    // sgn x_j (|Z|^n with n = 1) may enter D_x f only: the jump of S₂ where x_j crosses 0
    // ([`crate::engines::taylor::integrable::kink_jump`]) needs f itself continuous there
    if let Some(j) = tape.sign_in_the_rates(N) {
        return Err(fail(
            &format!(
                "the field itself jumps where state component {j} crosses 0 (it takes its sign): \
                 the second derivatives are not carried across it"
            ),
            0.0,
            0.0,
        ));
    }
    model_start(
        &build,
        kind,
        inputs,
        |x| H::constant(Dual::constant(Rec::constant(x))),
        |s| *s.v.v.value(),
        &mut x0,
    )?;
    // the branch points crossed in their variables (the floor ∝ w^(q−1) of the crossings at
    // fixed times gone); where that fails, the run in time alone
    match through_branches::<N, D, E>(&tape, x0, ju, opts) {
        Err((e, true)) if !e.out_of_time() => {
            let (flow, ev) = integrate_system(&tape, x0, N, opts)?;
            at_separation(&tape, &flow, &ev, ju, zero_time(), flow.len())
        }
        r => r.map_err(|(e, _)| e),
    }
}

fn zero_time() -> Interval {
    Interval::try_from((0.0, 0.0)).unwrap()
}

/// The run from `x0`, each branch point it meets after the start's crossed in its variable
/// ([`crossing`]): the time run stops at the first piece that holds one, the set is carried
/// across it from t_a, and the run goes on from the common time after it. An error says
/// whether a crossing was tried (before the first one, the run is the fixed-time run itself).
#[allow(clippy::result_large_err)]
fn through_branches<const N: usize, const D: usize, const E: usize>(
    tape: &Tape<Interval, D>,
    x0: [Interval; D],
    ju: usize,
    opts: &TaylorOptions,
) -> Result<Curvature, (RigorError, bool)> {
    let co = crossing::CrossingOptions::default();
    let (mut x, mut t_off, mut steps) = (x0, zero_time(), 0);
    for k in 0..=MAX_CROSSINGS {
        let tried = k > 0;
        let mut watch = crossing::BranchWatch::new(tape, N, &co);
        let mut found = None;
        let mut stop = |flow: &Flow<D, Interval>, cleared: f64| {
            // (only before the separation: [0, cleared) is proved free of it)
            found = found.or_else(|| watch.next(flow, cleared));
            k < MAX_CROSSINGS && found.is_some()
        };
        let ended = integrate_system_until(tape, x, N, opts, &mut stop).map_err(|e| (e, tried))?;
        let (flow, (j, t_a)) = match ended {
            Ended::Separated(flow, ev) => {
                // the last pieces before the separation's earliest time, not looked at yet
                let late = if k < MAX_CROSSINGS {
                    watch.next(&flow, ev.ts.inf())
                } else {
                    None
                };
                match late {
                    Some(b) => (flow, b),
                    None => {
                        return at_separation(tape, &flow, &ev, ju, t_off, steps + flow.len())
                            .map_err(|e| (e, tried));
                    }
                }
            }
            Ended::Stopped { flow, .. } => (flow, found.expect("stopped at a branch point")),
        };
        let xa = flow
            .enclose(t_a)
            .ok_or_else(|| (fail("no set before the branch point", t_a, 0.0), true))?;
        let c = crossing::cross::<D, E>(tape, N, j, t_a, &xa, opts, &co).map_err(|e| (e, true))?;
        steps += flow.pieces.iter().take_while(|p| p.t1() <= t_a).count() + c.steps;
        t_off += Interval::try_from((c.t1, c.t1)).unwrap();
        x = c.x1;
    }
    unreachable!("the last run does not stop")
}

/// The most branch points crossed in their variables in one run.
const MAX_CROSSINGS: usize = 8;

/// The implicit function theorem twice at the separation (module doc), every factor over the
/// event's box, the first-order ones tightened by their time-centred forms about the middle
/// T_m of [T_s]: q(T_s) ∈ q(Φ(T_m)) + q′(Φ([T_s]))·([T_s] − T_m).
fn at_separation<const D: usize>(
    tape: &Tape<Interval, D>,
    flow: &Flow<D, Interval>,
    ev: &SeparationEvent<D, Interval>,
    input: usize,
    t_off: Interval,
    steps: usize,
) -> Result<Curvature, RigorError> {
    let no_jet = || {
        fail(
            "no second-order jet over the separation's box",
            ev.ts.sup(),
            ev.ts.wid(),
        )
    };
    let at = AtEvent::new(tape, flow, ev);
    if !at.jet {
        return Err(no_jet());
    }
    let o = &at.o;
    let coef = |j: usize, k: usize| at.coef(D + j, k);
    let (value, rate) = (|j: usize| at.value(D + j), |j: usize| at.rate(D + j));
    // (F, V, F_u, V_u, F_uu, V_uu) = outputs D + 0..6
    let (f, v) = (o[D], o[D + 1]);
    let (g_t, h_t) = (rate(0), rate(1));
    let (g_tt, h_tt) = (coef(0, 2).mul_int(2), coef(1, 2).mul_int(2));
    let (g_u, h_u, g_uu, h_uu) = (value(2), value(3), value(4), value(5));
    let (g_ut, h_ut) = (rate(2), rate(3));
    // T′, T″ of the crossing of the function c (F or V) whose zero is the separation
    let implicit =
        |c_u: Interval, c_t: Interval, c_uu: Interval, c_ut: Interval, c_tt: Interval| {
            let t1 = -c_u / c_t;
            let t2 = -(c_uu + c_ut.mul_int(2) * t1 + c_tt * t1 * t1) / c_t;
            (t1, t2)
        };
    let zero = <Interval as Real>::zero();
    let (ts1, ts2, e1, e2) = if v.inf() > 0.0 && g_t.sup() < 0.0 {
        // F = 0 crossed downwards with V > 0
        let (t1, t2) = implicit(g_u, g_t, g_uu, g_ut, g_tt);
        let e1 = h_u + h_t * t1;
        let e2 = h_uu + h_ut.mul_int(2) * t1 + h_tt * t1 * t1 + h_t * t2;
        (t1, t2, e1, e2)
    } else if f.sup() < 0.0 && h_t.inf() > 0.0 {
        // V = 0 crossed upwards with F < 0: e ≡ 0
        let (t1, t2) = implicit(h_u, h_t, h_uu, h_ut, h_tt);
        (t1, t2, zero, zero)
    } else {
        return Err(fail(
            "the separation's crossing is not transversal over the whole range",
            ev.ts.sup(),
            ev.ts.wid(),
        ));
    };
    let bounded = [ts1, ts2, e1, e2]
        .iter()
        .all(|x| !x.is_empty() && x.inf().is_finite() && x.sup().is_finite());
    if !bounded {
        return Err(no_jet());
    }
    Ok(Curvature {
        input,
        ts: ev.ts + t_off,
        e: ev.e,
        ts1,
        e1,
        ts2,
        e2,
        steps,
    })
}
