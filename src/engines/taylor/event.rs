//! The separation event, proved: T_s = inf{T ≥ 0 : F ≤ 0 ∧ V ≥ 0} (eq:main_t_s).
//!
//! Every piece of the flow is scanned in time order. A time interval T is *cleared* when the
//! enclosures prove F > 0 or V < 0 on all of it. The first interval that is not cleared holds
//! T_s if it exists there:
//! - V > 0 on T and dF/dt < 0 on T (transversality, dF/dt = ∇F·f from the tape's jet over
//!   the box): F has at most one zero in T; interval Newton N(T) = m − F(Φ(m)) / F′(T) on the
//!   flow's Taylor polynomial encloses it (existence: N(T) ⊆ int T), and F > 0 before it, so
//!   T_s is that zero — and symmetrically F < 0 on T with dV/dt > 0 for a crossing of V = 0;
//! - otherwise T is bisected; at the finest level an interval whose right end provably satisfies
//!   the condition encloses T_s (all of it before was cleared), and one that can neither be
//!   cleared nor proved is reported as a grazing or undecidable separation — never guessed.
//!
//! e = V(Φ(T_s)) is enclosed by the flow at the enclosure of T_s (the piece's polynomial in
//! time, not the hull of a step), intersected with [0, ∞) since V(T_s) ≥ 0 holds at T_s.

use super::flow::{Flow, Piece};
use super::newton::{Newton, interval_newton};
use super::tape::{Tape, Workspace};
use crate::arith::Enclosure;
use inari::Interval;

/// Bisection depth inside one piece.
const MAX_DEPTH: u32 = 14;

/// A proved separation.
#[derive(Clone, Debug)]
pub struct SeparationEvent<const N: usize, I = Interval> {
    pub ts: I,
    pub e: I,
    pub state: [I; N],
}

pub enum Verdict<const N: usize, I = Interval> {
    Cleared,
    Found(SeparationEvent<N, I>),
    Undecided(I),
}

struct Ctx<'a, const N: usize, I: Enclosure> {
    tape: &'a Tape<I, N>,
    ws: &'a mut Workspace<I>,
    piece: &'a Piece<N, I>,
}

impl<const N: usize, I: Enclosure> Ctx<'_, N, I> {
    /// (F, V) over the flow's enclosure at the times `t`.
    fn fv(&self, t: &I) -> ([I; N], I, I) {
        let s = self.piece.enclose(t);
        let mut o = self.tape.eval(&s);
        let v = o.swap_remove(N + 1);
        let f = o.swap_remove(N);
        (s, f, v)
    }
    fn found(&self, t: I) -> Verdict<N, I> {
        let (s, _, v) = self.fv(&t);
        let e = v.nonneg();
        Verdict::Found(SeparationEvent { ts: t, e, state: s })
    }

    /// The condition F ≤ 0 ∧ V ≥ 0 provably holds at the time point t.
    fn holds_at(&self, t: &I) -> bool {
        let (_, f, v) = self.fv(t);
        f.hi() <= 0.0 && v.lo() >= 0.0
    }

    /// Interval Newton for the zero of g = sgn·output_j on T, g′ of sign `-1` on T.
    /// Returns the proved enclosure, `Some(None)` if g has no zero in T, or `None` if undecided.
    fn newton(&mut self, t: I, j: usize, sgn: f64) -> Option<Option<I>> {
        let s = I::from_exact_f64(sgn);
        // the closures share `self`: g needs only the flow, g′ the jet workspace
        let (tape, piece) = (self.tape, self.piece);
        let ws = &mut *self.ws;
        let g = |m: &I| tape.eval(&piece.enclose(m)).swap_remove(j) * s.clone();
        let dg = |t: &I| {
            tape.jet(&piece.enclose(t), 1, ws).ok()?;
            let d = tape.output_coef(ws, 1, j, 1) * s.clone();
            (d.hi() < 0.0).then_some(d)
        };
        match interval_newton(t, g, dg) {
            Newton::Root(ts) => Some(Some(ts)),
            Newton::NoRoot => Some(None),
            Newton::Undecided => None,
        }
    }

    fn scan(&mut self, t: I, depth: u32) -> Verdict<N, I> {
        let (_, f, v) = self.fv(&t);
        if f.lo() > 0.0 || v.hi() < 0.0 {
            return Verdict::Cleared;
        }
        // a transversal crossing: of F = 0 while V > 0, or of V = 0 while F < 0
        let attempt = if v.lo() > 0.0 {
            Some((N, 1.0))
        } else if f.hi() < 0.0 {
            Some((N + 1, -1.0))
        } else {
            None
        };
        if let Some((j, sgn)) = attempt {
            if f.hi() <= 0.0 && v.lo() >= 0.0 {
                // the condition holds on all of T and failed just before it: T_s = T.lo
                return self.found(t.inf_point());
            }
            match self.newton(t.clone(), j, sgn) {
                Some(Some(ts)) => return self.found(ts),
                // monotone g without a zero in T: g keeps the sign it has at T's end
                Some(None) if !self.holds_at(&t.sup_point()) => {
                    let (_, fe, ve) = self.fv(&t.sup_point());
                    if fe.lo() > 0.0 || ve.hi() < 0.0 {
                        return Verdict::Cleared;
                    }
                }
                Some(None) => {}
                None => {}
            }
        }
        if depth >= MAX_DEPTH {
            return if self.holds_at(&t.sup_point()) {
                self.found(t)
            } else {
                Verdict::Undecided(t)
            };
        }
        let m = t.mid_point();
        let (a, b) = (t.inf_point().hull(&m), m.hull(&t.sup_point()));
        match self.scan(a, depth + 1) {
            Verdict::Cleared => self.scan(b, depth + 1),
            other => other,
        }
    }
}

/// Scans one piece of the flow for the separation event.
pub fn scan_piece<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    ws: &mut Workspace<I>,
    piece: &Piece<N, I>,
) -> Verdict<N, I> {
    let t = I::from_bounds(piece.t0(), piece.t1()).expect("a piece's times");
    let mut ctx = Ctx { tape, ws, piece };
    ctx.scan(t, 0)
}

/// The condition F ≤ 0 ∧ V ≥ 0 provably holds at every point of the box `x`.
pub fn holds<const N: usize, I: Enclosure>(tape: &Tape<I, N>, x: &[I; N]) -> bool {
    let o = tape.eval(x);
    o[N].hi() <= 0.0 && o[N + 1].lo() >= 0.0
}

/// The event when T_s is only known to lie in [a, b] (all of [0, a) cleared, the condition
/// proved at b): T_s = [a, b], Φ(T_s) in the hull of the flow over [a, b], e = V(Φ(T_s)) ∩ [0, ∞).
pub fn between<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    flow: &Flow<N, I>,
    a: f64,
    b: f64,
) -> SeparationEvent<N, I> {
    let mut state: Option<[I; N]> = None;
    for piece in &flow.pieces {
        let (lo, hi) = (piece.t0().max(a), piece.t1().min(b));
        if lo > hi {
            continue;
        }
        let s = piece.enclose(&I::from_bounds(lo, hi).expect("lo ≤ hi"));
        state = Some(match state {
            None => s,
            Some(h) => std::array::from_fn(|i| h[i].hull(&s[i])),
        });
    }
    let state = state.expect("the flow covers [a, b]");
    let e = tape.eval(&state)[N + 1].nonneg();
    SeparationEvent {
        ts: I::from_bounds(a, b).expect("a ≤ b"),
        e,
        state,
    }
}
