//! Derived outputs of a collision, read from the same solution as T_s and e:
//!
//! ```text
//! F_max = max_{0 ≤ T ≤ T_s} F(Φ(T))        the peak contact force
//! δ_max = max_{0 ≤ T ≤ T_s} (−X(Φ(T)))     the maximum indentation (X(0) = 0, V(0) = −1:
//!                                          the bodies overlap where X < 0)
//! ΔE    = (1 − e²)/2                       the kinetic energy of the relative motion lost
//!                                          between impact and separation (½ at impact)
//! ```
//!
//! nondimensional, and in SI with the scales of a physical set ([`Scales`]): F_max·f_c \[N\],
//! δ_max·x_c \[m\], ΔE·f_c·x_c = ½ m v0² (1 − e²) \[J\] (f_c·x_c = m v_c², v_c = v0), and the
//! contact duration T_s·T_c \[s\].
//!
//! **Proved** ([`derived_rigorous`]): the maxima are enclosed by a branch and bound over the
//! proved flow ([`Flow`]) of the rigorous run. An upper bound covers [0, sup T_s] (the flow
//! reaches past T_s, and [0, T_s] ⊆ [0, sup T_s]); a lower bound is the value at points
//! T ≤ inf T_s (inside [0, T_s] for the true T_s). On a cell [a, b] of a piece the upper bound is
//! the better of the plain enclosure q(Φ([a, b])) and the mean-value form
//! q(Φ(m)) + ([a, b] − m)·q̇(Φ([a, b])), q̇ = ∇q·f evaluated by dual numbers through the model's
//! own force and position (Clarke's derivative where |·| has a kink: q∘Φ is Lipschitz, so
//! q(Φ(t)) − q(Φ(m)) = ∫ q̇ stays in the form). The cell with the highest upper bound is bisected
//! until the gap to the lower bound is at the floor of the flow's widths, or a budget is spent:
//! the result is always an enclosure, its width says how far it got.
//!
//! **Float** ([`derived_float`]): the same maxima on the DOP853 dense output (each step sampled,
//! the best sample refined by golden section), and the same ΔE.

use super::rigorous::Enclosure as Proved;
use super::separation::{FloatOptions, ImpactError};
use crate::arith::float::golden::golden_min;
use crate::arith::jet::dual::Dual;
use crate::arith::{Enclosure, Real, Scalar};
use crate::engines::dop853::Dop853;
use crate::engines::taylor::flow::{Flow, Piece, point};
use crate::models::CollisionModel;
use crate::models::scaling::Scales;
use inari::Interval;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A quantity whose maximum over the contact is a derived output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Peak {
    /// The contact force F.
    Force,
    /// The indentation −X.
    Indentation,
}

impl Peak {
    /// The quantity at state `s`, in the arithmetic `T` (the model's own force and position).
    pub fn of<R: Real, T: Scalar<R>, M: CollisionModel<R, N>, const N: usize>(
        self,
        m: &M,
        s: &[T; N],
    ) -> T {
        match self {
            Peak::Force => m.force(s),
            Peak::Indentation => -m.position(s),
        }
    }

    /// Its rate along the flow, d/dT q(Φ) = ∇q(Φ)·f(Φ), over the box `s` (forward-mode duals
    /// seeded with the field).
    pub fn rate<M: CollisionModel<I, N>, I: Enclosure, const N: usize>(
        self,
        m: &M,
        s: &[I; N],
    ) -> I {
        let f = m.field(s);
        let d: [Dual<I, 1>; N] = std::array::from_fn(|i| Dual {
            v: s[i].clone(),
            d: [f[i].clone()],
        });
        self.of(m, &d).d[0].clone()
    }
}

/// The derived outputs of one collision (nondimensional; [`Derived::in_si`] for SI).
#[derive(Clone, Debug, PartialEq)]
pub struct Derived<R> {
    /// F_max, the peak contact force.
    pub peak_force: R,
    /// δ_max, the maximum indentation.
    pub max_indentation: R,
    /// ΔE = (1 − e²)/2, the kinetic energy lost (½ m v0² (1 − e²) in SI).
    pub energy_lost: R,
}

impl<R: Real> Derived<R> {
    /// In SI with the scales of a physical set: N, m, J.
    pub fn in_si(&self, s: &Scales<R>) -> Derived<R> {
        Derived {
            peak_force: self.peak_force.clone() * s.f_c.clone(),
            max_indentation: self.max_indentation.clone() * s.x_c.clone(),
            energy_lost: self.energy_lost.clone() * (s.f_c.clone() * s.x_c.clone()),
        }
    }
}

/// ΔE = (1 − e²)/2.
pub fn energy_lost<R: Real>(e: &R) -> R {
    (R::one() - e.clone() * e.clone()) / R::from_int(2)
}

/// ΔE = (1 − e²)/2 for an enclosure of e (e² as the square of the interval, not a product of
/// two independent ones).
pub fn energy_lost_interval(e: Interval) -> Interval {
    (point(1.0) - e.sqr()) / point(2.0)
}

/// The budget of the branch and bound.
#[derive(Clone, Debug)]
pub struct PeakOptions {
    /// Stop when the gap between the bounds is at most this times max(1, |lower bound|).
    pub rel_gap: f64,
    /// Stop bisecting a cell shorter than this (in T): below it the flow's own width, not the
    /// cell's, sets the gap.
    pub min_cell: f64,
    /// At most this many bisections.
    pub max_bisections: usize,
}

impl Default for PeakOptions {
    fn default() -> Self {
        Self {
            rel_gap: 1e-15,
            min_cell: 1e-9,
            max_bisections: 4000,
        }
    }
}

/// A cell [a, b] of piece `piece`: `ub` encloses a set whose sup bounds q(Φ(t)) on it, `u` is
/// that sup rounded up (the heap's order: a max-heap on `u`).
struct Cell<I> {
    u: f64,
    ub: I,
    piece: usize,
    a: f64,
    b: f64,
}

impl<I> PartialEq for Cell<I> {
    fn eq(&self, o: &Self) -> bool {
        self.u.total_cmp(&o.u) == Ordering::Equal
    }
}
impl<I> Eq for Cell<I> {}
impl<I> PartialOrd for Cell<I> {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl<I> Ord for Cell<I> {
    fn cmp(&self, o: &Self) -> Ordering {
        self.u.total_cmp(&o.u)
    }
}

/// An upper bound of an enclosure, rounded up: +∞ for an empty one (inari's sup of ∅ is −∞,
/// which would discard a cell that was not bounded at all).
fn upper_of<I: Enclosure>(x: &I) -> f64 {
    if x.is_empty() { f64::INFINITY } else { x.hi() }
}

/// A lower bound of an enclosure, rounded down: −∞ for an empty one.
fn lower_of<I: Enclosure>(x: &I) -> f64 {
    if x.is_empty() {
        f64::NEG_INFINITY
    } else {
        x.lo()
    }
}

/// The cell [a, b] (a ≤ b inside the piece) with its upper bound of q(Φ(t)): the plain
/// enclosure and the mean-value form about the midpoint, intersected.
fn cell<M: CollisionModel<I, N>, I: Enclosure, const N: usize>(
    m: &M,
    q: Peak,
    piece: (usize, &Piece<N, I>),
    a: f64,
    b: f64,
) -> Cell<I> {
    let t = I::from_bounds(a, b).expect("a ≤ b, finite");
    let bx = piece.1.enclose(&t);
    let mut ub = q.of(m, &bx);
    if b > a {
        let mid = I::from_exact_f64(a + (b - a) / 2.0);
        let centre = q.of(m, &piece.1.enclose(&mid));
        let mvf = centre + (t - mid) * q.rate(m, &bx);
        // both hold q(Φ(t)) for every t in the cell: so does their intersection (an empty one
        // would mean an unsound enclosure, and bounds nothing: +∞)
        ub = if ub.is_empty() {
            mvf
        } else if mvf.is_empty() {
            ub
        } else {
            ub.intersection(&mvf)
        };
    }
    Cell {
        u: upper_of(&ub),
        ub,
        piece: piece.0,
        a,
        b,
    }
}

/// Encloses max_{0 ≤ T ≤ T_s} q(Φ(T)) on the proved `flow` (over the engine's number `I`:
/// inari intervals or MPFR ones) of a run whose T_s is in `ts` (module doc). Fails when the
/// flow does not reach sup T_s or a bound is not finite.
pub fn peak_enclosure<M: CollisionModel<I, N>, I: Enclosure, const N: usize>(
    m: &M,
    flow: &Flow<N, I>,
    ts: &I,
    q: Peak,
    opts: &PeakOptions,
) -> Result<I, String> {
    let (ts_lo, ts_hi) = (ts.lo(), ts.hi());
    if ts.is_empty() || !(ts_lo >= flow.t_start() && ts_hi <= flow.t_end()) {
        return Err(format!(
            "the proved flow [{}, {}] does not cover [0, T_s] with T_s in [{ts_lo}, {ts_hi}]",
            flow.t_start(),
            flow.t_end()
        ));
    }
    // a point t ≤ inf T_s lies in [0, T_s]: its value bounds the maximum from below (`best`,
    // with `best_lo` its lower end rounded down)
    let mut best = I::empty();
    let mut best_lo = f64::NEG_INFINITY;
    let see = |piece: &Piece<N, I>, t: f64, best: &mut I, best_lo: &mut f64| {
        if t <= ts_lo {
            let v = q.of(m, &piece.enclose(&I::from_exact_f64(t)));
            let lo = lower_of(&v);
            if lo > *best_lo {
                *best_lo = lo;
                *best = v;
            }
        }
    };
    let mut heap = BinaryHeap::new();
    for (i, p) in flow.pieces.iter().enumerate() {
        let a = p.t0();
        if a > ts_hi {
            break;
        }
        // (b = a: T_s at a piece boundary, the cell is that point)
        let b = p.t1().min(ts_hi);
        see(p, a, &mut best, &mut best_lo);
        see(p, b, &mut best, &mut best_lo);
        see(p, a + (b - a) / 2.0, &mut best, &mut best_lo);
        if a < ts_lo && ts_lo < b {
            see(p, ts_lo, &mut best, &mut best_lo);
        }
        heap.push(cell(m, q, (i, p), a, b));
    }
    // (a cell whose upper bound is below a proved value cannot hold the maximum: decided on the
    // f64 views, and where they cannot tell, on the enclosures' own ends)
    let may_hold = |c: &Cell<I>, best: &I, best_lo: f64| {
        c.u >= best_lo && (c.ub.sup_point() - best.inf_point()).hi() >= 0.0
    };
    let mut bisections = 0;
    while let Some(top) = heap.peek() {
        let gap = (top.ub.sup_point() - best.inf_point()).hi();
        let mid = top.a + (top.b - top.a) / 2.0;
        // the top cell bounds the maximum: when it is not split further, nothing lowers that
        if gap <= opts.rel_gap * best_lo.abs().max(1.0)
            || bisections >= opts.max_bisections
            || top.b - top.a <= opts.min_cell
            || !(top.a < mid && mid < top.b)
        {
            break;
        }
        let c = heap.pop().expect("peeked");
        bisections += 1;
        let p = &flow.pieces[c.piece];
        see(p, mid, &mut best, &mut best_lo);
        for (a, b) in [(c.a, mid), (mid, c.b)] {
            see(p, a + (b - a) / 2.0, &mut best, &mut best_lo);
            let child = cell(m, q, (c.piece, p), a, b);
            if may_hold(&child, &best, best_lo) {
                heap.push(child);
            }
        }
    }
    let what = match q {
        Peak::Force => "force",
        Peak::Indentation => "indentation",
    };
    let mut hi = I::empty();
    for c in heap.iter() {
        if may_hold(c, &best, best_lo) {
            if c.ub.is_empty() {
                return Err(format!("the {what} is not bounded on [{}, {}]", c.a, c.b));
            }
            hi = hi.hull(&c.ub.sup_point());
        }
    }
    let lo = best.inf_point();
    if best.is_empty() || hi.is_empty() || !(lo.is_finite() && hi.is_finite()) {
        return Err(format!(
            "the maximum of the {what} is not bounded (lower {best_lo}, upper {})",
            upper_of(&hi)
        ));
    }
    let r = lo.hull(&hi);
    if lo.lo() > hi.hi() {
        return Err(format!(
            "the bounds of the maximum of the {what} cross ({} > {}): not proved",
            lo.lo(),
            hi.hi()
        ));
    }
    Ok(r)
}

/// The derived outputs of a proved run: F_max and δ_max enclosed on its flow, ΔE from its e.
pub fn derived_rigorous<M: CollisionModel<Interval, N>, const N: usize>(
    m: &M,
    enc: &Proved<N>,
    opts: &PeakOptions,
) -> Result<Derived<Interval>, String> {
    Ok(Derived {
        peak_force: peak_enclosure(m, &enc.flow, &enc.ts, Peak::Force, opts)?,
        max_indentation: peak_enclosure(m, &enc.flow, &enc.ts, Peak::Indentation, opts)?,
        energy_lost: energy_lost_interval(enc.e),
    })
}

/// Samples per step of the float search.
const SAMPLES: usize = 4;

/// F_max and δ_max on the f64 engine over [0, `ts`] (the T_s of [`super::impact`] with the same
/// options), and ΔE from `e`.
pub fn derived_float<M: CollisionModel<f64, N>, const N: usize>(
    model: &M,
    opts: &FloatOptions,
    ts: f64,
    e: f64,
) -> Result<Derived<f64>, ImpactError> {
    if !(ts.is_finite() && ts > 0.0) {
        return Err(ImpactError::BadHorizon(ts));
    }
    let qs = [Peak::Force, Peak::Indentation];
    let y0 = model.initial_state();
    let mut best = qs.map(|q| q.of(model, &y0));
    let mut solver = Dop853::new(
        |_t, y: &[f64; N]| model.field(y),
        0.0,
        y0,
        ts,
        opts.ode.clone(),
    )?;
    while solver.step()? {
        let dense = solver.dense_output();
        let (t0, t1) = (dense.t_old(), dense.t_new());
        let h = (t1 - t0) / SAMPLES as f64;
        for (k, q) in qs.iter().enumerate() {
            let g = |t: f64| q.of(model, &dense.eval(t));
            // the best sample of the step; refined only where it beats the best so far
            let (mut tb, mut gb) = (t1, q.of(model, solver.y()));
            for i in 0..SAMPLES {
                let t = t0 + h * i as f64;
                let v = g(t);
                if v > gb {
                    (tb, gb) = (t, v);
                }
            }
            // (a step whose best sample ties the best so far may hold the maximum between
            // its first samples: refined too)
            if gb >= best[k] - 1e-9 * (1.0 + best[k].abs()) {
                // the maximum of g (unimodal there) on the step's part around the best sample,
                // its ends included: golden section on −g
                let (lo, hi) = ((tb - h).max(t0), (tb + h).min(t1));
                let (glo, ghi) = (g(lo), g(hi));
                let ends = if glo >= ghi { (lo, -glo) } else { (hi, -ghi) };
                let narrow = |a: f64, b: f64| b - a <= 4.0 * f64::EPSILON * b.abs().max(1.0);
                let (_, v, _) = golden_min(|t| -g(t), lo, hi, ends, narrow, 82);
                let v = -v;
                best[k] = best[k].max(v).max(gb);
            }
        }
    }
    Ok(Derived {
        peak_force: best[0],
        max_indentation: best[1],
        energy_lost: energy_lost(&e),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::mpfr::Mpi;
    use crate::engines::taylor::{TaylorOptions, integrate_to_separation};
    use crate::models::classical::{Law, LawModel, LawParams, LawSource};
    use crate::models::hunt_crossley::HuntCrossley;
    use crate::models::{ModelKind, NdParams, Shc};
    use crate::observables::impact;
    use crate::observables::precision::options_for_digits;
    use crate::observables::rigorous::rigorous_impact;
    use rug::ops::Pow;
    use rug::{Float, Rational};

    const BITS: u32 = 256;

    fn q(x: f64) -> Rational {
        Rational::from_f64(x).unwrap()
    }

    /// The reference `r` (a 256-bit value, good to ~1e-70) inside `x`, compared as rationals
    /// with a margin of 1e-60 either side.
    fn encloses(x: &Interval, r: &Float) -> bool {
        let r = r.to_rational().unwrap();
        let margin = Rational::from((1, 10)).pow(60u32);
        q(x.inf()) <= r.clone() - &margin && r + margin <= q(x.sup())
    }

    fn float(x: f64) -> Float {
        Float::with_val(BITS, x)
    }

    #[test]
    fn empty_enclosures_bound_nothing() {
        assert_eq!(upper_of(&Interval::EMPTY), f64::INFINITY);
        assert_eq!(lower_of(&Interval::EMPTY), f64::NEG_INFINITY);
        let x = Interval::try_from((1.0, 2.0)).unwrap();
        assert_eq!((lower_of(&x), upper_of(&x)), (1.0, 2.0));
    }

    #[test]
    fn energy_lost_of_an_enclosure() {
        let e = Interval::try_from((0.5, 0.75)).unwrap();
        let d = energy_lost_interval(e);
        // (1 − [0.25, 0.5625])/2 = [0.21875, 0.375], exact in binary
        assert_eq!((d.inf(), d.sup()), (0.21875, 0.375));
        assert_eq!(energy_lost(&0.5f64), 0.375);
    }

    /// Hertz's law X″ = −|X|^(n−1)X from X = 0, V = −1 conserves V²/2 + |X|^(n+1)/(n+1): at the
    /// maximum indentation V = 0, so δ_max = ((n+1)/2)^(1/(n+1)) and F_max = δ_max^n (n = 1:
    /// Hooke, 1 and 1). Both enclosed to 1e-13, around the 256-bit closed form.
    #[test]
    fn hertz_maxima_are_the_closed_form() {
        for n in [1.0, 1.5, 2.5] {
            let m = if n == 1.0 {
                HuntCrossley::<Interval>::hooke()
            } else {
                HuntCrossley::hertz(Interval::try_from((n, n)).unwrap()).unwrap()
            };
            let enc = rigorous_impact(&m, &TaylorOptions::default()).unwrap();
            let d = derived_rigorous(&m, &enc, &PeakOptions::default()).unwrap();
            let nf = float(n);
            let x = (nf.clone() + 1u32) / 2u32;
            let x = x.pow(float(1.0) / (nf.clone() + 1u32));
            let f = x.clone().pow(&nf);
            assert!(encloses(&d.max_indentation, &x), "n {n}: {d:?} vs {x}");
            assert!(encloses(&d.peak_force, &f), "n {n}: {d:?} vs {f}");
            for w in [d.max_indentation.wid(), d.peak_force.wid()] {
                assert!(w < 1e-13, "n {n}: width {w:e}, {d:?}");
            }
            // no energy is lost: ΔE = (1 − e²)/2 ∋ 0
            assert!(d.energy_lost.contains(0.0) && d.energy_lost.wid() < 1e-12);
        }
    }

    /// With T_s only known to lie in [1, 1.2] (Hooke: X = −sin T), every value of
    /// max_{[0, T_s]} sin T = sin T_s in [sin 1, sin 1.2] is possible: the enclosure must hold
    /// them all (a lower bound taken past inf T_s, or an upper one short of sup T_s, fails).
    #[test]
    fn an_uncertain_separation_time_widens_the_maximum() {
        let m = HuntCrossley::<Interval>::hooke();
        let enc = rigorous_impact(&m, &TaylorOptions::default()).unwrap();
        let ts = Interval::try_from((1.0, 1.2)).unwrap();
        for q in [Peak::Force, Peak::Indentation] {
            let r = peak_enclosure(&m, &enc.flow, &ts, q, &PeakOptions::default()).unwrap();
            assert!(encloses(&r, &float(1.0).sin()), "{q:?} {r:?}");
            assert!(encloses(&r, &float(1.2).sin()), "{q:?} {r:?}");
            // and not much more: sin 1 = 0.84147098…, sin 1.2 = 0.93203908…
            assert!(
                r.inf() > 0.8414709 - 1e-12 && r.sup() < 0.9320391,
                "{q:?} {r:?}"
            );
        }
        // past the flow's end: refused
        let late = Interval::try_from((1.0, enc.flow.t_end() * 2.0)).unwrap();
        assert!(
            peak_enclosure(&m, &enc.flow, &late, Peak::Force, &PeakOptions::default()).is_err()
        );
    }

    /// The SHC DSS set at v0 = 1: the f64 enclosures hold the 256-bit engine's (≥ 100× tighter:
    /// the low-order pieces across V = 0, where δ_max is, set their floor), and
    /// the DOP853 values lie within 1e-9 of them.
    #[test]
    fn shc_maxima_hold_the_mpfr_enclosures() {
        let text = "1.43,-1.42,0.632,0.00715,1.31,1.27";
        let mi = Shc::new(NdParams::<Interval>::parse(ModelKind::Shc, text).unwrap());
        let enc = rigorous_impact(&mi, &TaylorOptions::default()).unwrap();
        let d = derived_rigorous(&mi, &enc, &PeakOptions::default()).unwrap();
        let mp = Shc::new(NdParams::<Mpi<BITS>>::parse(ModelKind::Shc, text).unwrap());
        let (flow, ev) = integrate_to_separation::<Mpi<BITS>, _, 3>(
            &mp,
            &options_for_digits(40, &TaylorOptions::default()),
        )
        .unwrap();
        let fine = PeakOptions {
            rel_gap: 1e-40,
            min_cell: 0.0,
            max_bisections: 4000,
        };
        let mf = Shc::new(NdParams::<f64>::parse(ModelKind::Shc, text).unwrap());
        let opts = FloatOptions::default();
        let r = impact(&mf, &opts).unwrap();
        let df = derived_float(&mf, &opts, r.ts.unwrap(), r.e).unwrap();
        for (which, x, xf) in [
            (Peak::Force, d.peak_force, df.peak_force),
            (Peak::Indentation, d.max_indentation, df.max_indentation),
        ] {
            let p = peak_enclosure(&mp, &flow, &ev.ts, which, &fine).unwrap();
            let (lo, hi) = (
                p.inf().to_rational().unwrap(),
                p.sup().to_rational().unwrap(),
            );
            let w = Rational::from(&hi - &lo);
            eprintln!(
                "{which:?}: f64 {x:?} (width {:e}), 256-bit width {:e}",
                x.wid(),
                w.to_f64()
            );
            assert!(
                q(x.inf()) <= lo && hi <= q(x.sup()),
                "{which:?}: {x:?} vs [{lo}, {hi}]"
            );
            assert!(x.wid() < 1e-12, "{which:?}: {x:?}");
            // the reference is far tighter than what it checks
            assert!(
                w < q(x.wid() * 1e-2),
                "{which:?}: 256-bit width {}",
                w.to_f64()
            );
            assert!(
                (xf - x.mid()).abs() < 1e-9,
                "{which:?}: float {xf} vs {x:?}"
            );
        }
    }

    fn law<R: Real>(law: Law, text: &str) -> LawModel<R> {
        LawParams::<R>::parse(law, LawSource::Nd, text)
            .unwrap()
            .model()
            .unwrap()
    }

    #[test]
    fn hooke_float_maxima_are_one() {
        let LawModel::Force(m) = law::<f64>(Law::Hooke, "") else {
            panic!("Hooke is a force law")
        };
        let opts = FloatOptions::default();
        let r = impact(&m, &opts).unwrap();
        let d = derived_float(&m, &opts, r.ts.unwrap(), r.e).unwrap();
        assert!((d.peak_force - 1.0).abs() < 1e-10, "{d:?}");
        assert!((d.max_indentation - 1.0).abs() < 1e-10, "{d:?}");
        assert!(d.energy_lost.abs() < 1e-9, "{d:?}");
    }
}
