//! Proved T_s and e over *sets* of parameters: any of a case's inputs — the nondimensional P,
//! the base set P* and v0, the physical parameters and v0 — given as ranges.
//!
//! The uncertain inputs u become components of the state with u̇ = 0, and the map from the
//! inputs to the nondimensional parameters (𝓟(P*, v0), the nondimensionalization) is recorded
//! on the tape with the model ([`crate::engines::taylor::rec`]): the affine set of the rigorous
//! engine then carries the solution's dependence on u (their symbols), and v0
//! keeps its correlation with the B, Γ and σ it enters. The models stay written once: they are
//! built with parameters of the recording type.
//!
//! For each uncertain input u_j one run of the system also carries the first variational
//! equation S = ∂x/∂u_j, Ṡ = D_x f·S + ∂_{u_j} f (the field differentiated on duals), from
//! S(0) = 0 — one derivative per run: with all of ∂x/∂u at once, Lohner's basis (the engine's set
//! before the affine set; not re-measured since) mixed the large S block into the directions of
//! x and the set wrapped (measured: "the enclosure grew too wide" with all six base
//! parameters). At the separation (F = 0 crossed with V > 0):
//!
//! ```text
//! dT_s/du = −(∂F/∂u)/(dF/dT),     de/du = ∂V/∂u + (dV/dT)·dT_s/du
//! ```
//!
//! (∂/∂u along the flow at fixed T, i.e. ∇F·S + ∂_u F; the implicit function theorem on
//! F(x(T, u), u) = 0), enclosed over the whole set: every state at T_s(u), u ∈ U, lies in the
//! event's state enclosure (each factor tightened by its time-centred form about the middle of
//! \[T_s\]). The mean-value form T_s(u) ∈ T_s(û) + Σ_j \[∂T_s/∂u_j\](U_j − û_j) (û a short point
//! near the centre, T_s(û) from a point run; likewise e) is then intersected with the hulls of
//! the runs. Where a derivative cannot be carried, the hull of the system with the parameters
//! as components alone is the result.
//!
//! Measured (benches/RESULTS.md, "Sets of parameters"): the hulls alone are 5–50× the true
//! spread; the mean-value form brings single ranges to 1.00–1.4×.

use crate::arith::Real;
use crate::arith::jet::dual::Dual;
use crate::engines::taylor::rec::Rec;
use crate::engines::taylor::tape::{Tape, Workspace};
use crate::engines::taylor::{RigorError, TaylorOptions, integrate_system};
use crate::models::scaling::{PhysicalParams, nd_from_base};
use crate::models::{Admissibility, CollisionModel, Maxwell, ModelKind, NdParams, ParamError, Shc};
use inari::Interval;
use rayon::prelude::*;

/// The inputs of a case, from which its nondimensional parameters are computed.
#[derive(Clone, Debug)]
pub enum Inputs<R> {
    /// The nondimensional set P itself (B, Γ, κ, σ, n, p).
    Nd(NdParams<R>),
    /// A base set P* and the impact speed: P = 𝓟(P*, v0).
    Base { base: NdParams<R>, v0: R },
    /// Physical parameters and the impact speed.
    Physical { phys: PhysicalParams<R>, v0: R },
}

/// Most uncertain inputs at once (the physical set and v0).
pub const MAX_UNCERTAIN: usize = 10;

fn nd_values<R: Clone>(p: &NdParams<R>) -> Vec<R> {
    vec![
        p.b.clone(),
        p.gamma.clone(),
        p.kappa.clone(),
        p.sigma.clone(),
        p.n.clone(),
        p.p.clone(),
    ]
}

fn nd_of<S>(v: &mut impl Iterator<Item = S>) -> NdParams<S> {
    let mut next = || v.next().expect("an input value");
    NdParams {
        b: next(),
        gamma: next(),
        kappa: next(),
        sigma: next(),
        n: next(),
        p: next(),
    }
}

impl<R: Real> Inputs<R> {
    /// The inputs in a fixed order (see [`Inputs::names`]).
    pub fn values(&self) -> Vec<R> {
        match self {
            Inputs::Nd(p) => nd_values(p),
            Inputs::Base { base, v0 } => {
                let mut v = nd_values(base);
                v.push(v0.clone());
                v
            }
            Inputs::Physical { phys, v0 } => vec![
                phys.m.clone(),
                phys.k.clone(),
                phys.c.clone(),
                phys.n.clone(),
                phys.p.clone(),
                phys.alpha.clone(),
                phys.beta.clone(),
                phys.gamma.clone(),
                phys.a.clone(),
                v0.clone(),
            ],
        }
    }

    /// The names of [`Inputs::values`].
    pub fn names(&self) -> &'static [&'static str] {
        match self {
            Inputs::Nd(_) => &["B", "Gamma", "kappa", "sigma", "n", "p"],
            Inputs::Base { .. } => &["B_b", "Gamma_b", "kappa", "sigma_b", "n", "p", "v0"],
            Inputs::Physical { .. } => {
                &["m", "k", "c", "n", "p", "alpha", "beta", "gamma", "A", "v0"]
            }
        }
    }

    /// The same kind of inputs with other values (in the order of [`Inputs::values`]).
    pub fn with_values<S: Real>(&self, vals: Vec<S>) -> Inputs<S> {
        let mut it = vals.into_iter();
        match self {
            Inputs::Nd(_) => Inputs::Nd(nd_of(&mut it)),
            Inputs::Base { .. } => {
                let base = nd_of(&mut it);
                Inputs::Base {
                    base,
                    v0: it.next().expect("v0"),
                }
            }
            Inputs::Physical { .. } => {
                let mut next = || it.next().expect("an input value");
                let phys = PhysicalParams {
                    m: next(),
                    k: next(),
                    c: next(),
                    n: next(),
                    p: next(),
                    alpha: next(),
                    beta: next(),
                    gamma: next(),
                    a: next(),
                };
                Inputs::Physical { phys, v0: next() }
            }
        }
    }

    /// The nondimensional parameters. The inputs were checked against 𝓟 as written, every
    /// value of the ranges ([`NdParams::parse`], [`PhysicalParams::parse`]); their enclosures
    /// (and those of sub-ranges, or of other number types) are checked as
    /// [`Admissibility::Written`].
    pub fn nd(&self, kind: ModelKind) -> Result<NdParams<R>, ParamError> {
        match self {
            Inputs::Nd(p) => NdParams::with_admissibility(
                kind,
                Admissibility::Written,
                p.b.clone(),
                p.gamma.clone(),
                p.kappa.clone(),
                p.sigma.clone(),
                p.n.clone(),
                p.p.clone(),
            ),
            Inputs::Base { base, v0 } => nd_from_base(kind, base, v0),
            Inputs::Physical { phys, v0 } => {
                phys.validate(kind)?;
                phys.nondimensionalize(kind, v0)
            }
        }
    }
}

/// A point near the middle of [lo, hi] with a short exact decimal: the coarsest multiple of a
/// power of two inside (so the affine forms anchored there can be printed exactly).
pub fn short_centre(lo: f64, hi: f64) -> f64 {
    let m = lo + (hi - lo) / 2.0;
    if lo >= hi || lo.is_nan() || hi.is_nan() || !m.is_finite() {
        return m;
    }
    // steps 2^k from above the width down: the first multiple of 2^k in the middle half
    let mut k = (hi - lo).log2().ceil() as i32;
    for _ in 0..80 {
        let step = 2f64.powi(k);
        let c = (m / step).round() * step;
        if c > lo + (hi - lo) / 4.0 && c < hi - (hi - lo) / 4.0 {
            return c;
        }
        k -= 1;
    }
    m
}

/// True when an input is a range (wider than the enclosure of a decimal).
pub fn is_range(x: &Interval) -> bool {
    x.wid() > 4.0 * f64::EPSILON * x.mag()
}

/// Proved T_s and e for every input value in the ranges.
#[derive(Clone, Debug)]
pub struct SetEnclosure {
    pub ts: Interval,
    pub e: Interval,
    /// With one input given as a range: its index in [`Inputs::values`], and enclosures of
    /// dT_s/du and de/du over the whole range.
    pub slope: Option<Slope>,
    /// With one input given as a range: (its centre û, T_s(û), e(û)) proved by a point run,
    /// the anchor of the mean-value form T_s(u) ∈ T_s(û) + [dT_s/du](u − û) (likewise e).
    pub centre: Option<(f64, Interval, Interval)>,
    /// Pieces of the proved flow (Taylor and low-order steps).
    pub steps: usize,
}

/// The derivatives of T_s and e in one input, over a range of it.
#[derive(Clone, Copy, Debug)]
pub struct Slope {
    pub input: usize,
    pub ts: Interval,
    pub e: Interval,
}

pub(super) fn param_error(e: ParamError) -> RigorError {
    RigorError {
        reason: e.0,
        t: 0.0,
        width: 0.0,
    }
}

/// Encloses T_s and e of model `kind` for every value of `inputs` (ranges allowed in any of
/// them). No range: the point engine. Ranges: the variational system, one run per ranged input
/// (hull ∩ mean-value form, and with one range its slopes). One range whose crossing at T_s is
/// not transversal (F and its time derivative vanish together, as in the Hunt–Crossley limit,
/// where F = |X|^p(1 − σV) at X = 0, so dT_s/du = −F_u/F_t is 0/0): e by
/// `partial_form`, T_s by its hull, no slope. Where no derivative can be carried — the
/// S block grows too wide, or ∂f/∂u is unbounded near a branch point (n → 1:
/// ∂(|Z|^(n−1)Z)/∂n = |Z|^(n−1)Z·ln|Z|), or several ranges and a crossing that is not
/// transversal — the parameters as components alone: the hull, with no slope.
pub fn prove_over_set(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    opts: &TaylorOptions,
) -> Result<SetEnclosure, RigorError> {
    prove(kind, inputs, opts, true)
}

/// [`prove_over_set`] without the hull: a range whose slope cannot be carried is not proved
/// (the band, whose pieces are affine forms in v0, needs the slope; a failed piece is cut).
pub fn prove_over_set_with_slopes(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    opts: &TaylorOptions,
) -> Result<SetEnclosure, RigorError> {
    prove(kind, inputs, opts, false)
}

fn prove(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    opts: &TaylorOptions,
    hull_fallback: bool,
) -> Result<SetEnclosure, RigorError> {
    let nd = inputs.nd(kind).map_err(param_error)?;
    let vals = inputs.values();
    let ranges: Vec<usize> = (0..vals.len()).filter(|&i| is_range(&vals[i])).collect();
    if ranges.is_empty() {
        return point(kind, nd, opts);
    }
    if ranges.len() > MAX_UNCERTAIN {
        return Err(RigorError {
            reason: format!(
                "{} inputs are ranges; at most {MAX_UNCERTAIN} can be",
                ranges.len()
            ),
            t: 0.0,
            width: 0.0,
        });
    }
    // one run per ranged input (its slope), each also a hull of T_s and e
    let one = |d: usize| match (kind, ranges.len()) {
        (ModelKind::Shc, 1) => variational::<_, 3, 1, 7>(Shc::new, kind, inputs, &ranges, d, opts),
        (ModelKind::Maxwell, 1) => {
            variational::<_, 4, 1, 9>(Maxwell::new, kind, inputs, &ranges, d, opts)
        }
        (ModelKind::Shc, _) => {
            variational::<_, 3, 10, 16>(Shc::new, kind, inputs, &ranges, d, opts)
        }
        (ModelKind::Maxwell, _) => {
            variational::<_, 4, 10, 18>(Maxwell::new, kind, inputs, &ranges, d, opts)
        }
    };
    let runs: Vec<VarRun> = match (0..ranges.len())
        .into_par_iter()
        .map(one)
        .collect::<Result<Vec<_>, _>>()
        .and_then(|runs| usable(runs, hull_fallback))
    {
        Ok(r) => r,
        // a derivative that cannot be carried: the hull of the parameters as components alone
        // (not once the time budget is spent)
        Err(e) if hull_fallback && !e.out_of_time() => {
            return hull_any(kind, inputs, &ranges, opts).map_err(|h| RigorError {
                reason: format!("{} (with slopes: {})", h.reason, e.reason),
                ..h
            });
        }
        Err(e) => return Err(e),
    };
    let mut ts_h = runs[0].ts;
    let mut e_h = runs[0].e;
    for r in &runs[1..] {
        ts_h = ts_h.intersection(r.ts);
        e_h = e_h.intersection(r.e);
    }
    let steps = runs.iter().map(|r| r.steps).max().unwrap_or(0);
    // the mean-value form around the centre û (each range at a short point near its middle)
    let mut cv = vals.clone();
    let mut du = Vec::with_capacity(ranges.len());
    for &j in &ranges {
        let uc = short_centre(vals[j].inf(), vals[j].sup());
        let c = Interval::try_from((uc, uc)).unwrap();
        cv[j] = c;
        du.push(vals[j] - c);
    }
    let centre = inputs
        .with_values(cv.clone())
        .nd(kind)
        .map_err(param_error)?;
    let c = point(kind, centre, opts)?;
    let (mut ts_mv, mut e_mv) = (c.ts, c.e);
    let mut slopes = Vec::with_capacity(runs.len());
    for (r, d) in runs.iter().zip(&du) {
        match r.slope {
            Some(s) => {
                ts_mv += s.ts * *d;
                e_mv += s.e * *d;
                slopes.push(s);
            }
            None => {
                // (one range: see `usable`) T_s keeps its hull
                ts_mv = Interval::ENTIRE;
                e_mv = partial_form(e_mv, r.dv_du, r.dv_dt, r.ts, *d);
            }
        }
    }
    let ts = ts_h.intersection(ts_mv);
    let e = e_h.intersection(e_mv);
    if std::env::var_os("BWCL_TRACE_SETS").is_some() {
        eprintln!(
            "hull ts {:e} e {:e}; mean-value ts {:e} e {:e}",
            ts_h.wid(),
            e_h.wid(),
            ts_mv.wid(),
            e_mv.wid()
        );
    }
    if ts.is_empty() || e.is_empty() {
        return Err(RigorError {
            reason: "the hull and the mean-value form do not meet (an internal error)".into(),
            t: 0.0,
            width: 0.0,
        });
    }
    let one = ranges.len() == 1 && slopes.len() == 1;
    Ok(SetEnclosure {
        ts,
        e,
        slope: one.then(|| slopes[0]),
        centre: one.then(|| (cv[ranges[0]].inf(), c.ts, c.e)),
        steps,
    })
}

/// The derivatives of T_s and e in every ranged input over a set, with the hulls of T_s and e
/// over it (the intersection of the runs' hulls): what a mean-value form about any point of
/// the set needs (set-membership identification re-centres it on sub-sets, see
/// `crate::identify`).
#[derive(Clone, Debug)]
pub struct SetSlopes {
    pub ts: Interval,
    pub e: Interval,
    /// Per ranged input (in the order of [`Inputs::values`]): its index and, where the
    /// crossing at T_s is transversal over the whole set, enclosures of dT_s/du and de/du.
    pub slopes: Vec<(usize, Option<Slope>)>,
}

/// The indices of the ranged inputs (1 to [`MAX_UNCERTAIN`] of them) of valid inputs: what a
/// run over a set needs.
pub(super) fn ranged(kind: ModelKind, inputs: &Inputs<Interval>) -> Result<Vec<usize>, RigorError> {
    inputs.nd(kind).map_err(param_error)?;
    let vals = inputs.values();
    let ranges: Vec<usize> = (0..vals.len()).filter(|&i| is_range(&vals[i])).collect();
    if ranges.is_empty() || ranges.len() > MAX_UNCERTAIN {
        return Err(RigorError {
            reason: format!(
                "{} inputs are ranges; 1 to {MAX_UNCERTAIN} can be",
                ranges.len()
            ),
            t: 0.0,
            width: 0.0,
        });
    }
    Ok(ranges)
}

/// [`SetSlopes`] of model `kind` over `inputs` (at least one range): one run of the variational
/// system per ranged input, in parallel. A run that fails fails the whole (the hull then comes
/// from [`prove_over_set`]).
pub fn slopes_over_set(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    opts: &TaylorOptions,
) -> Result<SetSlopes, RigorError> {
    let ranges = ranged(kind, inputs)?;
    // the fewest parameter slots that hold the ranges (each slot is a state component)
    let one = |d: usize| match (kind, ranges.len()) {
        (ModelKind::Shc, 1) => variational::<_, 3, 1, 7>(Shc::new, kind, inputs, &ranges, d, opts),
        (ModelKind::Shc, 2) => variational::<_, 3, 2, 8>(Shc::new, kind, inputs, &ranges, d, opts),
        (ModelKind::Shc, 3..=6) => {
            variational::<_, 3, 6, 12>(Shc::new, kind, inputs, &ranges, d, opts)
        }
        (ModelKind::Shc, _) => {
            variational::<_, 3, 10, 16>(Shc::new, kind, inputs, &ranges, d, opts)
        }
        (ModelKind::Maxwell, 1) => {
            variational::<_, 4, 1, 9>(Maxwell::new, kind, inputs, &ranges, d, opts)
        }
        (ModelKind::Maxwell, 2) => {
            variational::<_, 4, 2, 10>(Maxwell::new, kind, inputs, &ranges, d, opts)
        }
        (ModelKind::Maxwell, 3..=6) => {
            variational::<_, 4, 6, 14>(Maxwell::new, kind, inputs, &ranges, d, opts)
        }
        (ModelKind::Maxwell, _) => {
            variational::<_, 4, 10, 18>(Maxwell::new, kind, inputs, &ranges, d, opts)
        }
    };
    let runs = (0..ranges.len())
        .into_par_iter()
        .map(one)
        .collect::<Result<Vec<_>, _>>()?;
    let (mut ts, mut e) = (runs[0].ts, runs[0].e);
    for r in &runs[1..] {
        ts = ts.intersection(r.ts);
        e = e.intersection(r.e);
    }
    Ok(SetSlopes {
        ts,
        e,
        slopes: ranges
            .iter()
            .zip(&runs)
            .map(|(&j, r)| (j, r.slope))
            .collect(),
    })
}

/// T_s and e proved at one point of the inputs (no range): the point engine.
pub fn prove_at_point(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    opts: &TaylorOptions,
) -> Result<(Interval, Interval), RigorError> {
    let nd = inputs.nd(kind).map_err(param_error)?;
    point(kind, nd, opts).map(|r| (r.ts, r.e))
}

/// The hulls of T_s and e over a set of inputs (1 to [`MAX_UNCERTAIN`] ranges), with no
/// derivative carried: one run of the system with the ranged inputs as components of the state
/// (u̇ = 0), the fewest components that hold them. Wider than a mean-value form about a point
/// (5–50× the true spread on the sets of `benches/RESULTS.md`), but it needs no variational
/// block, so it is proved on sets where the slopes wrap (set-membership identification closes
/// or refutes a row with it where the row's slopes fail, see `crate::identify`).
pub fn hull_over_set(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    opts: &TaylorOptions,
) -> Result<(Interval, Interval), RigorError> {
    let ranges = ranged(kind, inputs)?;
    hull_any(kind, inputs, &ranges, opts).map(|r| (r.ts, r.e))
}

/// [`hull`] at the smallest dimension the engine is compiled at that holds the ranges: the
/// variational runs' (SHC 7, 8, 12, 16; Maxwell 9, 10, 14, 18) and SHC's 5, for the 2-D
/// slices of identification (each padding component costs: 2 ranges at D = 5 took 0.75× the
/// time of D = 7 on the 2-D floor of issue #31, the same boxes proved).
fn hull_any(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    ranges: &[usize],
    opts: &TaylorOptions,
) -> Result<SetEnclosure, RigorError> {
    match (kind, ranges.len()) {
        (ModelKind::Shc, 0..=2) => hull::<_, 3, 5>(Shc::new, kind, inputs, ranges, opts),
        (ModelKind::Shc, 3..=4) => hull::<_, 3, 7>(Shc::new, kind, inputs, ranges, opts),
        (ModelKind::Shc, 5) => hull::<_, 3, 8>(Shc::new, kind, inputs, ranges, opts),
        (ModelKind::Shc, 6..=9) => hull::<_, 3, 12>(Shc::new, kind, inputs, ranges, opts),
        (ModelKind::Shc, _) => hull::<_, 3, 16>(Shc::new, kind, inputs, ranges, opts),
        (ModelKind::Maxwell, 0..=5) => hull::<_, 4, 9>(Maxwell::new, kind, inputs, ranges, opts),
        (ModelKind::Maxwell, 6) => hull::<_, 4, 10>(Maxwell::new, kind, inputs, ranges, opts),
        (ModelKind::Maxwell, _) => hull::<_, 4, 14>(Maxwell::new, kind, inputs, ranges, opts),
    }
}

/// Proved ∂T_s/∂u and ∂e/∂u of input `j` at the inputs' values (a point, or a range: then over
/// all of it): one run of the variational system.
pub fn sensitivity(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    j: usize,
    opts: &TaylorOptions,
) -> Result<Slope, RigorError> {
    inputs.nd(kind).map_err(param_error)?;
    let r = match kind {
        ModelKind::Shc => variational::<_, 3, 1, 7>(Shc::new, kind, inputs, &[j], 0, opts),
        ModelKind::Maxwell => variational::<_, 4, 1, 9>(Maxwell::new, kind, inputs, &[j], 0, opts),
    }?;
    r.slope.ok_or_else(|| r.no_derivative())
}

fn point(
    kind: ModelKind,
    nd: NdParams<Interval>,
    opts: &TaylorOptions,
) -> Result<SetEnclosure, RigorError> {
    use super::rigorous::rigorous_impact;
    let r = match kind {
        ModelKind::Shc => rigorous_impact(&Shc::new(nd), opts).map(|r| (r.ts, r.e, r.flow.len())),
        ModelKind::Maxwell => {
            rigorous_impact(&Maxwell::new(nd), opts).map(|r| (r.ts, r.e, r.flow.len()))
        }
    }?;
    Ok(SetEnclosure {
        ts: r.0,
        e: r.1,
        slope: None,
        centre: None,
        steps: r.2,
    })
}

/// The parameter components of a system with D = N + slots + …: slot k holds input
/// `ranges[k]` (unused slots 0), as `record_with`'s declaration and in x(0) (the rest of x(0)
/// is 0 until [`model_start`] fills the model's state).
pub(super) fn parameter_slots<const N: usize, const D: usize>(
    vals: &[Interval],
    ranges: &[usize],
    slots: usize,
) -> ([Option<Interval>; D], [Interval; D]) {
    let zero = Interval::try_from((0.0, 0.0)).unwrap();
    let mut params: [Option<Interval>; D] = [None; D];
    let mut x0 = [zero; D];
    for slot in 0..slots {
        let v = ranges.get(slot).map_or(zero, |&j| vals[j]);
        params[N + slot] = Some(v);
        x0[N + slot] = v;
    }
    (params, x0)
}

/// Writes the model's initial state (it does not depend on the parameters) into x(0).
pub(super) fn model_start<R: Real, M: CollisionModel<R, N>, const N: usize, const D: usize>(
    build: impl Fn(NdParams<R>) -> M,
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    lift: impl Fn(Interval) -> R,
    value: impl Fn(&R) -> Interval,
    x0: &mut [Interval; D],
) -> Result<(), RigorError> {
    let vals = inputs.values();
    let m0 = build(
        inputs
            .with_values(vals.iter().map(|&x| lift(x)).collect())
            .nd(kind)
            .map_err(param_error)?,
    );
    for (i, s) in m0.initial_state().iter().enumerate() {
        x0[i] = value(s);
    }
    Ok(())
}

/// One run of the variational system: the hull of T_s and e over the set, and how they depend
/// on the run's input u.
struct VarRun {
    ts: Interval,
    e: Interval,
    /// The crossing at T_s is transversal: the total derivatives dT_s/du = −F_u/F_t and
    /// de/du = V_u + V_t·dT_s/du over the whole set.
    slope: Option<Slope>,
    /// ∂V/∂u and dV/dT over the event's box, for [`partial_form`] (which needs no
    /// transversality).
    dv_du: Interval,
    dv_dt: Interval,
    steps: usize,
}

/// e over a range of one input u, when T_s may have no derivative (F and F_t vanish together
/// at T_s, as in the Hunt–Crossley limit, where F = |X|^p(1 − σV) at X = 0): e(u) = V(T_s(u), u)
/// splits as
///
/// ```text
/// e(u) − e(û) = [V(T_s(u), u) − V(T_s(u), û)] + [V(T_s(u), û) − V(T_s(û), û)]
///             ∈ [∂V/∂u](u − û) + [dV/dT]([T_s] − [T_s])
/// ```
///
/// (the mean-value theorem in u at a fixed time, then in T at û), both enclosures over the
/// event's box: every time of [T_s] ∋ T_s(u), T_s(û), every u of the set. Near such a
/// separation dV/dT = F is small (V̇ = F in both models), so e keeps its dependence on u.
fn partial_form(
    e_c: Interval,
    dv_du: Interval,
    dv_dt: Interval,
    ts: Interval,
    du: Interval,
) -> Interval {
    // (interval subtraction: [T_s] − [T_s] = [−w, w], not 0)
    #[allow(clippy::eq_op)]
    let dts = ts - ts;
    e_c + dv_du * du + dv_dt * dts
}

impl VarRun {
    fn no_derivative(&self) -> RigorError {
        RigorError {
            reason: NO_DERIVATIVE.into(),
            t: self.ts.sup(),
            width: self.ts.wid(),
        }
    }
}

const NO_DERIVATIVE: &str =
    "the crossing at T_s is not transversal over the whole range (no derivative)";

/// The runs whose dependences combine into a mean-value form: all of them with a slope (their
/// total derivatives add up along u − û), or one range with [`partial_form`]; else `Err` (the
/// caller may take the hull). The partial form of one input among several would need the
/// other inputs' partial derivatives at once, and the band (`with_partial` false) needs the
/// slope.
fn usable(runs: Vec<VarRun>, with_partial: bool) -> Result<Vec<VarRun>, RigorError> {
    match runs.iter().find(|r| r.slope.is_none()) {
        Some(r) if !(with_partial && runs.len() == 1) => Err(r.no_derivative()),
        _ => Ok(runs),
    }
}

type V1 = Dual<Rec<Interval>, 1>;

/// The system (x, u, S) of the module doc: the K ranged inputs `js` as parameter components
/// (padded to KP slots, unused ones 0), and S = ∂x/∂u for the one input `js[d]` — D = N + KP + N
/// components (x, u, S); outputs F, V, ∂F/∂u, ∂V/∂u, dV/dT. (One derivative per run: with all of S
/// = ∂x/∂u at once, Lohner's basis, the engine's set before the affine set, mixed the large S
/// block into x's directions and wrapped.)
/// Returns the hull of (T_s, e) over the set, the dependence on `js[d]` and the steps.
fn variational<M, const N: usize, const KP: usize, const D: usize>(
    build: impl Fn(NdParams<V1>) -> M,
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    js: &[usize],
    d: usize,
    opts: &TaylorOptions,
) -> Result<VarRun, RigorError>
where
    M: CollisionModel<V1, N>,
{
    assert_eq!(D, N + KP + N);
    assert!(js.len() <= KP && d < js.len());
    let vals = inputs.values();
    let (params, mut x0) = parameter_slots::<N, D>(&vals, js, KP);
    let tape = Tape::<Interval, D>::record_with(params, |v| {
        let dv: Vec<V1> = (0..vals.len())
            .map(|i| match js.iter().position(|&j| j == i) {
                Some(slot) => Dual {
                    v: v[N + slot].clone(),
                    d: [Rec::constant(if slot == d {
                        Interval::one()
                    } else {
                        Interval::zero()
                    })],
                },
                None => V1::constant(Rec::constant(vals[i])),
            })
            .collect();
        let nd = inputs
            .with_values(dv)
            .nd(kind)
            .expect("validated as intervals");
        let m = build(nd);
        let xs: [V1; N] = std::array::from_fn(|i| Dual {
            v: v[i].clone(),
            d: [v[N + KP + i].clone()],
        });
        let f = m.field(&xs);
        let (force, vel) = (m.force(&xs), m.velocity(&xs));
        // dV/dT = ∇V·f, the inputs constants (each ranged one as its whole range, which holds
        // its value: no new work per step on the parameter components): evaluated on a box it
        // needs no jet, so it also bounds dV/dT where a branch point is in the box
        let nd0 = inputs
            .with_values(
                vals.iter()
                    .map(|&x| V1::constant(Rec::constant(x)))
                    .collect(),
            )
            .nd(kind)
            .expect("validated as intervals");
        let xt: [V1; N] = std::array::from_fn(|i| Dual {
            v: v[i].clone(),
            d: [f[i].v.clone()],
        });
        let vel_t = build(nd0).velocity(&xt);
        let mut o: Vec<Rec<Interval>> = f.iter().map(|c| c.v.clone()).collect();
        o.extend((0..KP).map(|_| Rec::constant(Interval::zero())));
        o.extend(f.iter().map(|c| c.d[0].clone()));
        o.extend([force.v, vel.v, force.d[0].clone(), vel.d[0].clone()]);
        o.push(vel_t.d[0].clone());
        o
    });
    // x(0) from the model, u(0) = U, S(0) = 0
    model_start(
        &build,
        kind,
        inputs,
        |x| V1::constant(Rec::constant(x)),
        |s| *s.v.value(),
        &mut x0,
    )?;
    let (flow, ev) = integrate_system(&tape, x0, N, opts)?;
    // the derivatives over the event's state enclosure, each tightened by its time-centred form
    let at = AtEvent::new(&tape, &flow, &ev);
    let (o, jet) = (&at.o, at.jet);
    let (value, rate) = (|j| at.value(j), |j| at.rate(j));
    let (df_du, dv_du) = (value(D + 2), value(D + 3));
    let slope = jet.then_some(()).and_then(|_| {
        let df_dt = rate(D);
        let dv_dt = rate(D + 1);
        let (f, v) = (o[D], o[D + 1]);
        if v.inf() > 0.0 && df_dt.sup() < 0.0 {
            // F = 0 crossed downwards with V > 0
            let dts = -df_du / df_dt;
            Some(Slope {
                input: js[d],
                ts: dts,
                e: dv_du + dv_dt * dts,
            })
        } else if f.sup() < 0.0 && dv_dt.inf() > 0.0 {
            // V = 0 crossed upwards with F < 0: e = 0
            Some(Slope {
                input: js[d],
                ts: -dv_du / dv_dt,
                e: Interval::zero(),
            })
        } else {
            None
        }
    });
    if std::env::var_os("BWCL_TRACE_SETS").is_some() {
        let w = |x: &[Interval]| {
            let v: Vec<String> = x.iter().map(|v| format!("{:.2e}", v.wid())).collect();
            v.join(" ")
        };
        eprintln!(
            "input {}: T_s width {:.2e}, state widths at T_s [{}], at the middle of T_s [{}]",
            js[d],
            ev.ts.wid(),
            w(&ev.state),
            at.at_m.as_ref().map(|s| w(s)).unwrap_or_default()
        );
        if let Some(s) = &slope {
            eprintln!(
                "  dT_s/du {:?} width {:.2e}; de/du {:?} width {:.2e}",
                s.ts.mid(),
                s.ts.wid(),
                s.e.mid(),
                s.e.wid()
            );
        }
    }
    Ok(VarRun {
        ts: ev.ts,
        e: ev.e,
        slope,
        dv_du,
        // with the jet its time-centred form; else ∇V·f on the event's box (no jet needed)
        dv_dt: if jet {
            rate(D + 1).intersection(o[D + 4])
        } else {
            o[D + 4]
        },
        steps: flow.len(),
    })
}

/// The tape's outputs at the separation over the event's state box (every T_s of the set),
/// each tightened by its time-centred form q(T_s) ∈ q(Φ(T_m)) + q′(Φ([T_s]))·([T_s] − T_m),
/// T_m the middle of [T_s] (the box of Φ at the point T_m has no spread in time); the jet of
/// order 2 over the event's box for the time derivatives.
pub(super) struct AtEvent<'a, const D: usize> {
    tape: &'a Tape<Interval, D>,
    /// The outputs over the event's box.
    pub o: Vec<Interval>,
    ws: Workspace<Interval>,
    /// The jet of order 2 over the event's box exists.
    pub jet: bool,
    /// The set at T_m.
    pub at_m: Option<[Interval; D]>,
    om: Option<Vec<Interval>>,
    dt: Interval,
    ws_m: Workspace<Interval>,
    jet_m: bool,
}

impl<'a, const D: usize> AtEvent<'a, D> {
    pub(super) fn new(
        tape: &'a Tape<Interval, D>,
        flow: &crate::engines::taylor::Flow<D, Interval>,
        ev: &crate::engines::taylor::SeparationEvent<D, Interval>,
    ) -> Self {
        let mut ws = Workspace::default();
        let o = tape.eval(&ev.state);
        let tm = ev.ts.mid();
        let dt = ev.ts - Interval::try_from((tm, tm)).unwrap();
        let at_m = flow.enclose(tm);
        let om = at_m.as_ref().map(|s| tape.eval(s));
        let mut ws_m = Workspace::default();
        let jet_m = at_m
            .as_ref()
            .is_some_and(|s| tape.jet(s, 1, &mut ws_m).is_ok());
        let jet = tape.jet(&ev.state, 2, &mut ws).is_ok();
        Self {
            tape,
            o,
            ws,
            jet,
            at_m,
            om,
            dt,
            ws_m,
            jet_m,
        }
    }

    /// The order-k coefficient in time of output j over the event's box (with the jet).
    pub(super) fn coef(&self, j: usize, k: usize) -> Interval {
        self.tape.output_coef(&self.ws, 2, j, k)
    }

    /// Output j at T_s.
    pub(super) fn value(&self, j: usize) -> Interval {
        match (&self.om, self.jet) {
            (Some(om), true) => (om[j] + self.coef(j, 1) * self.dt).intersection(self.o[j]),
            _ => self.o[j],
        }
    }

    /// The time derivative of output j at T_s.
    pub(super) fn rate(&self, j: usize) -> Interval {
        let whole = self.coef(j, 1);
        if self.jet_m {
            (self.tape.output_coef(&self.ws_m, 1, j, 1) + self.coef(j, 2).mul_int(2) * self.dt)
                .intersection(whole)
        } else {
            whole
        }
    }
}

/// The system (x, u_1, …, u_K) padded to D − N ≥ K parameter components (u̇ = 0): the hulls
/// of T_s and e over the set, no derivative carried.
fn hull<M, const N: usize, const D: usize>(
    build: impl Fn(NdParams<Rec<Interval>>) -> M,
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    ranges: &[usize],
    opts: &TaylorOptions,
) -> Result<SetEnclosure, RigorError>
where
    M: CollisionModel<Rec<Interval>, N>,
{
    let slots = D - N;
    assert!(ranges.len() <= slots);
    let vals = inputs.values();
    let zero = Interval::try_from((0.0, 0.0)).unwrap();
    let (params, mut x0) = parameter_slots::<N, D>(&vals, ranges, slots);
    let tape = Tape::<Interval, D>::record_with(params, |v| {
        let rv: Vec<Rec<Interval>> = (0..vals.len())
            .map(|i| match ranges.iter().position(|&r| r == i) {
                Some(slot) => v[N + slot].clone(),
                None => Rec::constant(vals[i]),
            })
            .collect();
        let nd = inputs
            .with_values(rv)
            .nd(kind)
            .expect("validated as intervals");
        let m = build(nd);
        let xs: [Rec<Interval>; N] = std::array::from_fn(|i| v[i].clone());
        let mut o = m.field(&xs).to_vec();
        o.extend((0..slots).map(|_| Rec::constant(zero)));
        o.extend([m.force(&xs), m.velocity(&xs)]);
        o
    });
    model_start(&build, kind, inputs, Rec::constant, |s| *s.value(), &mut x0)?;
    let (flow, ev) = integrate_system(&tape, x0, N, opts)?;
    Ok(SetEnclosure {
        ts: ev.ts,
        e: ev.e,
        slope: None,
        centre: None,
        steps: flow.len(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(s: &str) -> Interval {
        Interval::parse_decimal(s).unwrap()
    }

    fn base(kind: ModelKind, text: &str, v0: &str) -> Inputs<Interval> {
        Inputs::Base {
            base: NdParams::parse(kind, text).unwrap(),
            v0: iv(v0),
        }
    }

    /// Which runs combine into a mean-value form ([`usable`]): all with a slope; or one range
    /// without a slope, by the partial form (not for the band, which needs the slope); never
    /// one without a slope among several (the partial form would need every input's partial
    /// derivatives at once) — there the caller must be told, with the reason.
    #[test]
    fn runs_without_a_slope_are_refused_where_no_form_holds() {
        let run = |input: usize, slope: bool| VarRun {
            ts: iv("3"),
            e: iv("0.5"),
            slope: slope.then(|| Slope {
                input,
                ts: iv("0.1"),
                e: iv("-0.2"),
            }),
            dv_du: iv("1"),
            dv_dt: iv("0.01"),
            steps: 10,
        };
        let ok = |runs: Vec<VarRun>, partial: bool| usable(runs, partial).map(|r| r.len());
        assert_eq!(ok(vec![run(0, true), run(1, true)], false), Ok(2));
        assert_eq!(ok(vec![run(0, true), run(1, true)], true), Ok(2));
        // one range, no slope: the partial form where allowed, else refused
        assert_eq!(ok(vec![run(0, false)], true), Ok(1));
        // among several, or for the band: refused with the reason
        for (runs, partial) in [
            (vec![run(0, true), run(1, false)], true),
            (vec![run(0, false), run(1, false)], true),
            (vec![run(0, false)], false),
            (vec![run(0, true), run(1, false)], false),
        ] {
            match usable(runs, partial) {
                Err(e) => assert_eq!(e.reason, NO_DERIVATIVE),
                Ok(r) => panic!("{} runs accepted (partial {partial})", r.len()),
            }
        }
    }

    /// The partial form on a closed form: V(T, u) = u + T and T_s(u) = u² on u ∈ [0, 1], so
    /// e(u) = u + u² fills [0, 2]; around û = 1/2 with [∂V/∂u] = [dV/dT] = 1 and [T_s] = [0, 1]
    /// the form must contain [0, 2] (without its time term it would be [1/4, 5/4]).
    #[test]
    fn the_partial_form_holds_on_a_closed_form() {
        let one = Interval::one();
        let iv = |a: f64, b: f64| Interval::try_from((a, b)).unwrap();
        let e = partial_form(iv(0.75, 0.75), one, one, iv(0.0, 1.0), iv(-0.5, 0.5));
        assert!(iv(0.0, 2.0).subset(e), "{e:?}");
    }

    /// The partial form of e (the one taken where T_s has no derivative), on a range where it
    /// is not needed but its time term matters: v0 ∈ [0.97, 1.03] of SHC DSS, where T_s spreads
    /// and dV/dT = F moves away from 0 across that window. Every sampled point enclosure (ends
    /// included, doubles compared exactly) lies inside, and the time term
    /// [dV/dT]([T_s] − [T_s]) is more than 5 % of the form's width (7 %, measured 2026-11-28:
    /// at [0.99, 1.01], used before, the affine set's tighter [dV/dT] left it 1 %).
    #[test]
    fn the_partial_form_contains_sampled_points() {
        let inp = base(ModelKind::Shc, "1.43,-1.42,0.632,0.00715,1.31,1.27", "1");
        let mut vals = inp.values();
        let (lo, hi) = (0.97, 1.03);
        vals[6] = Interval::try_from((lo, hi)).unwrap();
        let set = inp.with_values(vals.clone());
        let opts = TaylorOptions::default();
        let r = variational::<_, 3, 1, 7>(Shc::new, ModelKind::Shc, &set, &[6], 0, &opts).unwrap();
        let uc = short_centre(lo, hi);
        let c = Interval::try_from((uc, uc)).unwrap();
        let mut cv = vals.clone();
        cv[6] = c;
        let centre = point(
            ModelKind::Shc,
            inp.with_values(cv).nd(ModelKind::Shc).unwrap(),
            &opts,
        )
        .unwrap();
        let e = partial_form(centre.e, r.dv_du, r.dv_dt, r.ts, vals[6] - c);
        // the time term is a real part of it here
        let time = 2.0 * r.dv_dt.mag() * r.ts.wid();
        eprintln!("time term {time:e} of {:e}", e.wid());
        assert!(time > 0.05 * e.wid(), "time term {time:e} of {:e}", e.wid());
        for i in 0..=8 {
            let x = if i == 8 {
                hi
            } else {
                lo + (hi - lo) * i as f64 / 8.0
            };
            let mut v = vals.clone();
            v[6] = Interval::try_from((x, x)).unwrap();
            let p = prove_over_set(ModelKind::Shc, &inp.with_values(v), &opts).unwrap();
            assert!(
                p.e.subset(e),
                "v0 = {x}: {:?} not in the partial form {e:?}",
                p.e
            );
        }
    }

    /// (width of the enclosure, spread of 20 sampled point enclosures' midpoints) of T_s and e,
    /// and the enclosure, for input `j` of `inp` over `range`.
    fn measure(
        kind: ModelKind,
        inp: &Inputs<Interval>,
        j: usize,
        range: Interval,
        samples: usize,
    ) -> (
        Result<SetEnclosure, RigorError>,
        f64,
        f64,
        std::time::Duration,
    ) {
        let opts = TaylorOptions::default();
        let mut vals = inp.values();
        vals[j] = range;
        let t0 = std::time::Instant::now();
        let r = prove_over_set(kind, &inp.with_values(vals.clone()), &opts);
        let dt = t0.elapsed();
        let (mut elo, mut ehi, mut tlo, mut thi) = (1e9, -1e9, 1e9, -1e9);
        for i in 0..samples {
            let x = range.inf() + (range.sup() - range.inf()) * i as f64 / (samples - 1) as f64;
            vals[j] = Interval::try_from((x, x)).unwrap();
            let c = prove_over_set(kind, &inp.with_values(vals.clone()), &opts).unwrap();
            elo = f64::min(elo, c.e.mid());
            ehi = f64::max(ehi, c.e.mid());
            tlo = f64::min(tlo, c.ts.mid());
            thi = f64::max(thi, c.ts.mid());
        }
        (r, ehi - elo, thi - tlo, dt)
    }

    #[test]
    #[ignore]
    fn explore_params() {
        for (name, kind, b) in crate::models::params::TABLE1 {
            let inp = base(kind, b, "1");
            for j in 0..6 {
                let x = inp.values()[j];
                let m = x.mid();
                let rel: f64 = std::env::var("REL")
                    .ok()
                    .and_then(|s| s.parse().ok())
                    .unwrap_or(0.0);
                let h = if rel > 0.0 {
                    rel * m.abs() / 2.0
                } else {
                    0.0005
                };
                let range = if m == 1.0 {
                    Interval::try_from((1.0, 1.0 + 2.0 * h)).unwrap()
                } else {
                    Interval::try_from((m - h, m + h)).unwrap()
                };
                let (r, se, st, dt) = measure(kind, &inp, j, range, 20);
                match r {
                    Ok(r) => eprintln!(
                        "{name} {}: e ratio {:.3}, ts ratio {:.3}, steps {} in {dt:?}",
                        inp.names()[j],
                        r.e.wid() / se,
                        r.ts.wid() / st,
                        r.steps
                    ),
                    Err(e) => eprintln!("{name} {}: {e} in {dt:?}", inp.names()[j]),
                }
            }
        }
    }

    /// Width against the spread of 20 sampled point enclosures: `cargo test --release --lib
    /// sets::tests::explore -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn explore() {
        let opts = TaylorOptions::default();
        let cases = [
            (
                ModelKind::Shc,
                "1.43,-1.42,0.632,0.00715,1.31,1.27",
                "0.999..1.001",
            ),
            (
                ModelKind::Maxwell,
                "0.655,-0.64,0.519,0.0118,1.94,2.28",
                "0.999..1.001",
            ),
        ];
        for (kind, b, v) in cases {
            let inp = base(kind, b, v);
            let t0 = std::time::Instant::now();
            let r = prove_over_set(kind, &inp, &opts);
            let dt = t0.elapsed();
            let u = iv(v);
            let (mut elo, mut ehi, mut tlo, mut thi) = (1e9, -1e9, 1e9, -1e9);
            for i in 0..20 {
                let x = u.inf() + (u.sup() - u.inf()) * i as f64 / 19.0;
                let p = base(kind, b, &format!("{x}"));
                let c = prove_over_set(kind, &p, &opts).unwrap();
                elo = f64::min(elo, c.e.mid());
                ehi = f64::max(ehi, c.e.mid());
                tlo = f64::min(tlo, c.ts.mid());
                thi = f64::max(thi, c.ts.mid());
            }
            match r {
                Ok(r) => eprintln!(
                    "{kind:?} {v}: e {:?} ratio {:.3}, ts ratio {:.3}, slope {:?}, steps {} in {dt:?}",
                    r.e,
                    r.e.wid() / (ehi - elo),
                    r.ts.wid() / (thi - tlo),
                    r.slope,
                    r.steps
                ),
                Err(e) => eprintln!("{kind:?} {v}: {e} in {dt:?}"),
            }
        }
    }
}
#[cfg(test)]
mod explore_all {
    use super::*;
    #[test]
    #[ignore]
    fn all_six() {
        for (name, kind, b) in crate::models::params::TABLE1 {
            let inp = Inputs::Base {
                base: NdParams::parse(kind, b).unwrap(),
                v0: Interval::one(),
            };
            let mut vals = inp.values();
            for v in vals.iter_mut().take(6) {
                let m = v.mid();
                let h = 0.001 * m.abs();
                *v = Interval::try_from((m - h, m + h)).unwrap();
                if m == 1.0 {
                    *v = Interval::try_from((1.0, 1.0 + 2.0 * h)).unwrap();
                }
            }
            let t0 = std::time::Instant::now();
            let r = prove_over_set(
                kind,
                &inp.with_values(vals.clone()),
                &TaylorOptions::default(),
            );
            eprintln!(
                "{name}: {:?} in {:?}",
                r.as_ref().map(|r| (r.e, r.e.wid(), r.ts.wid())),
                t0.elapsed()
            );
        }
    }
}
