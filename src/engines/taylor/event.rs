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

use super::flow::{Flow, Piece, tau};
use super::newton::{Newton, interval_newton};
use super::tape::{Tape, Workspace};
use crate::arith::Enclosure;
use inari::Interval;

/// Bisection depth inside one piece.
const MAX_DEPTH: u32 = 14;
/// The tighter forms of (F, V) on an interval the box does not clear, tried in this order.
#[derive(Clone, Copy)]
enum Form {
    Poly,
    Centred,
}

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
    /// F and V along a Taylor piece as polynomials in τ ([`output_poly`]), computed the first
    /// time the box evaluation does not clear an interval (`Some(None)`: not available).
    poly: Option<Option<[Vec<I>; 2]>>,
    /// Whether the tighter forms are tried at all ([`super::TaylorOptions::event_forms`]).
    forms: bool,
}

/// F and V along a Taylor piece as polynomials in τ = t − t0 with a remainder:
///
/// ```text
/// F(Φ(t0 + τ)) ∈ Σ_{k<K} F_k τ^k + F_K(B)·τ^K,     0 ≤ τ ≤ t1 − t0,
/// ```
///
/// F_k the k-th Taylor coefficients of F along the solutions through the box at t0 (the
/// piece's x_0; the tape's jet, whose outputs are F and V), F_K(B) the K-th over the box B of
/// the flow on the whole piece (Lagrange's remainder of g(τ) = F(Φ(t0 + τ)) on each
/// trajectory, g^(K)(ξ)/K! with Φ(t0 + ξ) ∈ B). Valid where the jet exists on B: every branch and
/// kink component then has a decided sign on B, and F, V are analytic there. Returns
/// [F coefficients, V coefficients], each K + 1 long (the last one the remainder's).
///
/// The terms of the force cancel coefficient by coefficient here, where the box evaluation
/// adds their ranges (see [`Ctx::fv_poly`]).
fn output_poly<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    ws: &mut Workspace<I>,
    piece: &Piece<N, I>,
) -> Option<[Vec<I>; 2]> {
    let Piece::Taylor { t0, t1, coefs, .. } = piece else {
        return None;
    };
    let k = coefs.len();
    if k == 0 {
        return None;
    }
    let whole = piece.enclose(&I::from_bounds(*t0, *t1)?);
    tape.jet(&whole, k, ws).ok()?;
    let (rf, rv) = (
        tape.output_coef(ws, k, N, k),
        tape.output_coef(ws, k, N + 1, k),
    );
    tape.jet(&coefs[0], k - 1, ws).ok()?;
    let mut f: Vec<I> = (0..k).map(|j| tape.output_coef(ws, k - 1, N, j)).collect();
    let mut v: Vec<I> = (0..k)
        .map(|j| tape.output_coef(ws, k - 1, N + 1, j))
        .collect();
    f.push(rf);
    v.push(rv);
    Some([f, v])
}

/// Σ_{k<K} c_k τ^k + c_K·τ^K for τ in `s` ⊆ [0, ∞) (c = `c`, K + 1 long): the polynomial part in
/// the centred form P(m) + P′(s)·(s − m), m the midpoint of s, plus the remainder term.
fn poly_eval<I: Enclosure>(c: &[I], s: &I) -> I {
    let k = c.len() - 1;
    let m = s.mid_point();
    let mut p = c[k - 1].clone();
    for ck in c[..k - 1].iter().rev() {
        p = p * m.clone() + ck.clone();
    }
    let mut dp = c[k - 1].mul_int(k as i64 - 1);
    for j in (1..k - 1).rev() {
        dp = dp * s.clone() + c[j].mul_int(j as i64);
    }
    let centred = p + dp * (s.clone() - m);
    centred + c[k].clone() * s.powi_nonneg(k as u32)
}

impl<'a, const N: usize, I: Enclosure> Ctx<'a, N, I> {
    fn new(
        tape: &'a Tape<I, N>,
        ws: &'a mut Workspace<I>,
        piece: &'a Piece<N, I>,
        forms: bool,
    ) -> Self {
        Self {
            tape,
            ws,
            piece,
            poly: None,
            forms,
        }
    }

    /// (F, V) over the flow's enclosure at the times `t`.
    fn fv(&self, t: &I) -> ([I; N], I, I) {
        let s = self.piece.enclose(t);
        let mut o = self.tape.eval_extra(&s);
        let v = o.swap_remove(1);
        let f = o.swap_remove(0);
        (s, f, v)
    }
    /// (F, V) over the times `t` in the centred form of second order, m the midpoint of T:
    ///
    /// ```text
    /// F(Φ(t)) ∈ F(Φ(m)) + (dF/dt)(Φ(m))·(t − m) + ½(d²F/dt²)(Φ(T))·(t − m)²
    /// ```
    ///
    /// (Taylor with Lagrange's remainder on each trajectory; V alike). The derivatives along the
    /// flow are the Taylor coefficients of the outputs from the tape's jet: of order 1 through
    /// the flow's box at m, of order 2 over the box on T. The jet exists only where every branch
    /// and kink component has a decided sign on the box, and there F and V are analytic in the
    /// state (otherwise `None`: the box evaluation stands alone).
    ///
    /// Why: the box evaluation of F loses the cancellation between the force's terms. Near a
    /// Hunt–Crossley separation F = |X|^p(1 − σV) with 1 − σV ≈ 5·10⁻⁶ (σ = 15) is the
    /// difference of terms ≈ 0.03, and on a time interval of length δ each term moves by
    /// ≈ 0.1·δ, so the box proves F > 0 only for δ ≲ 10⁻⁶; here the width is of order δ³ plus
    /// the flow set's own.
    fn fv_centred(&mut self, t: &I, b: &[I; N]) -> Option<(I, I)> {
        self.tape.jet(b, 2, self.ws).ok()?;
        let (f2, v2) = (
            self.tape.output_coef(self.ws, 2, N, 2),
            self.tape.output_coef(self.ws, 2, N + 1, 2),
        );
        let m = t.mid_point();
        let bm = self.piece.enclose(&m);
        self.tape.jet(&bm, 1, self.ws).ok()?;
        let c = |j: usize, k: usize| self.tape.output_coef(self.ws, 1, j, k);
        let (f0, f1, v0, v1) = (c(N, 0), c(N, 1), c(N + 1, 0), c(N + 1, 1));
        let d = t.clone() - m;
        let d2 = d.abs().powi_nonneg(2);
        Some((f0 + f1 * d.clone() + f2 * d2.clone(), v0 + v1 * d + v2 * d2))
    }

    /// (F, V) on the times `t` from the piece's polynomials ([`output_poly`]), computed once
    /// per piece; `None` on a low-order piece or where the jet does not exist.
    fn fv_poly(&mut self, t: &I) -> Option<(I, I)> {
        if self.poly.is_none() {
            self.poly = Some(output_poly(self.tape, self.ws, self.piece));
        }
        let [f, v] = self.poly.as_ref()?.as_ref()?;
        let s = tau(t, self.piece.t0());
        Some((poly_eval(f, &s), poly_eval(v, &s)))
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
        let g = |m: &I| tape.eval_extra(&piece.enclose(m)).swap_remove(j - N) * s.clone();
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
        let (b, mut f, mut v) = self.fv(&t);
        if f.lo() > 0.0 || v.hi() < 0.0 {
            return Verdict::Cleared;
        }
        // not cleared by the box: the piece's polynomials, else the centred form; what each
        // proves is kept (all are enclosures of the same values)
        for form in [Form::Poly, Form::Centred] {
            let tighter = match form {
                Form::Poly if self.forms => self.fv_poly(&t),
                Form::Centred if self.forms => self.fv_centred(&t, &b),
                _ => None,
            };
            if let Some((fc, vc)) = tighter {
                let (fi, vi) = (f.intersection(&fc), v.intersection(&vc));
                if !fi.is_empty() && !vi.is_empty() {
                    (f, v) = (fi, vi);
                }
                if f.lo() > 0.0 || v.hi() < 0.0 {
                    return Verdict::Cleared;
                }
            }
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

/// Scans one piece of the flow for the separation event; `forms`: try the polynomial and the
/// centred forms of (F, V) where the box evaluation does not clear an interval.
pub fn scan_piece<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    ws: &mut Workspace<I>,
    piece: &Piece<N, I>,
    forms: bool,
) -> Verdict<N, I> {
    let t = I::from_bounds(piece.t0(), piece.t1()).expect("a piece's times");
    let mut ctx = Ctx::new(tape, ws, piece, forms);
    ctx.scan(t, 0)
}

/// The condition F ≤ 0 ∧ V ≥ 0 provably fails at every point of the box `x` (F > 0 or V < 0
/// on all of it).
pub fn excluded<const N: usize, I: Enclosure>(tape: &Tape<I, N>, x: &[I; N]) -> bool {
    let o = tape.eval_extra(x);
    o[0].lo() > 0.0 || o[1].hi() < 0.0
}

/// The condition F ≤ 0 ∧ V ≥ 0 provably holds at every point of the box `x`.
pub fn holds<const N: usize, I: Enclosure>(tape: &Tape<I, N>, x: &[I; N]) -> bool {
    let o = tape.eval_extra(x);
    o[0].hi() <= 0.0 && o[1].lo() >= 0.0
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engines::taylor::flow::point;

    /// x′ = v, v′ = −x from (1, 0) (x = cos t, v = −sin t), outputs F = x and V = v; a Taylor
    /// piece of order K = 4 on [0, 0.5] (the remainder ≈ τ⁴/24 ≈ 2.6·10⁻³ at the end, so that a
    /// form without it misses the truth), its a-priori box [−1, 1]² (|x|, |v| ≤ 1 for all t).
    fn oscillator() -> (Tape<Interval, 2>, Piece<2>) {
        let tape = Tape::<Interval, 2>::record(|s| {
            vec![s[1].clone(), -s[0].clone(), s[0].clone(), s[1].clone()]
        });
        let mut ws = Workspace::default();
        let k = 4;
        let c = tape.jet(&[point(1.0), point(0.0)], k - 1, &mut ws).unwrap();
        let coefs: Vec<[Interval; 2]> = (0..k).map(|j| [c[0][j], c[1][j]]).collect();
        let b = Interval::try_from((-1.0, 1.0)).unwrap();
        let r = tape.jet(&[b, b], k, &mut ws).unwrap();
        let piece = Piece::Taylor {
            t0: 0.0,
            t1: 0.5,
            coefs,
            remainder: [r[0][k], r[1][k]],
        };
        (tape, piece)
    }

    /// Time intervals of the piece: whole, wide, narrow (1e-6) at the start, middle and end,
    /// and points.
    fn intervals() -> Vec<Interval> {
        [
            (0.0, 0.5),
            (0.1, 0.4),
            (0.25, 0.5),
            (0.0, 1e-6),
            (0.3, 0.3 + 1e-6),
            (0.5 - 1e-6, 0.5),
            (0.5, 0.5),
            (0.2, 0.2),
        ]
        .iter()
        .map(|&(a, b)| Interval::try_from((a, b)).unwrap())
        .collect()
    }

    /// The true F and V at 41 points of `t` (ends included) lie in `(f, v)` (compared with
    /// inari's enclosures of cos and −sin: an empty intersection proves exclusion).
    fn assert_contains(t: Interval, (f, v): (Interval, Interval), what: &str) {
        for i in 0..=40 {
            let s = t.inf() + (t.sup() - t.inf()) * (i as f64) / 40.0;
            let s = point(s.clamp(t.inf(), t.sup()));
            assert!(
                !f.intersection(s.cos()).is_empty() && !v.intersection(-s.sin()).is_empty(),
                "{what} on {t:?}: F {f:?} ∌ cos, or V {v:?} ∌ −sin at {s:?}"
            );
        }
        // and no looser than the truth's range plus 10⁻² (not a vacuous enclosure)
        assert!(
            f.wid() < t.wid() + 1e-2 && v.wid() < t.wid() + 1e-2,
            "{what} on {t:?}: {f:?} {v:?}"
        );
    }

    #[test]
    fn polynomial_form_encloses_the_outputs() {
        let (tape, piece) = oscillator();
        let mut ws = Workspace::default();
        let mut ctx = Ctx::new(&tape, &mut ws, &piece, true);
        for t in intervals() {
            let fv = ctx
                .fv_poly(&t)
                .expect("a Taylor piece of an analytic field");
            assert_contains(t, fv, "polynomial form");
        }
    }

    #[test]
    fn centred_form_encloses_the_outputs() {
        let (tape, piece) = oscillator();
        let mut ws = Workspace::default();
        let mut ctx = Ctx::new(&tape, &mut ws, &piece, true);
        for t in intervals() {
            let b = piece.enclose(&t);
            let fv = ctx.fv_centred(&t, &b).expect("the jet exists on the box");
            assert_contains(t, fv, "centred form");
        }
    }

    #[test]
    fn no_polynomial_on_a_low_order_piece() {
        let (tape, _) = oscillator();
        let piece = Piece::LowOrder {
            t0: 0.0,
            t1: 0.1,
            x0: [point(1.0), point(0.0)],
            slope: [Interval::try_from((-1.0, 1.0)).unwrap(); 2],
        };
        let mut ws = Workspace::default();
        let mut ctx = Ctx::new(&tape, &mut ws, &piece, true);
        assert!(ctx.fv_poly(&point(0.05)).is_none());
    }
}
