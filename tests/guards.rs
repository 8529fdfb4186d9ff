//! Toy fields with closed-form solutions, each driving one soundness guard of the rigorous
//! engine through the engine's own code (issue #12): removing the guard makes a test here fail
//! (the commands and results are in `proofs/MUTANTS.md`).
//!
//! | guard | test |
//! |---|---|
//! | a-priori inclusion test of the Taylor step | `a_taylor_step_whose_first_guess_fails` |
//! | Picard inclusion test of the low-order step | `low_order_steps_toward_a_blow_up` |
//! | the set carried between steps (affine symbols, the image's error term) | `a_rotating_box_is_carried_as_an_affine_set` |
//! | interval Newton's existence proof N(T) ⊆ int T | `newton_claims_no_root_it_has_not_proved` |
//! | the T_s enclosure | `harmonic_separation_encloses_pi_exactly` |
//! | grazing: undecidable, never guessed | `a_grazing_event_is_undecided` |
//! | which zero is a separation (F's while V > 0, V's while F < 0) | `separation_needs_both_conditions_at_once` |
//! | the condition proved on a box (after an undecided stretch) | `the_condition_holds_only_when_both_parts_are_proved` |
//! | dense output of the whole flow, at and between piece boundaries | `the_proved_flow_holds_the_harmonic_solution_everywhere` |
//!
//! References are exact: rationals (the doubles' values) against MPFR at 256 bits.

use bwcl::arith::Scalar;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::engines::taylor::event::{Verdict, scan_piece};
use bwcl::engines::taylor::flow::point;
use bwcl::engines::taylor::newton::{Newton, interval_newton};
use bwcl::engines::taylor::step::{
    StepOut, Tapes, Workspaces, jacobian_orders, low_order_step, taylor_eval, taylor_step,
};
use bwcl::engines::taylor::tape::{Tape, Workspace};
use bwcl::engines::taylor::window::Window;
use bwcl::models::{Admissibility, ModelKind, NdParams, Shc};
use bwcl::observables::rigorous::rigorous_impact;
use inari::Interval;
use rug::{Float, Rational};

const PREC: u32 = 256;

fn iv(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).unwrap()
}

/// lo ≤ x ≤ hi, exactly.
fn encloses(i: Interval, x: &Float) -> bool {
    !i.is_empty() && Float::with_val(PREC, i.inf()) <= *x && *x <= Float::with_val(PREC, i.sup())
}

/// x′ = x² from x(0) = 1: x(t) = 1/(1 − t), blowing up at t = 1.
fn blow_up_tape() -> Tape<Interval, 1> {
    Tape::<Interval, 1>::record(|v| vec![v[0].clone() * v[0].clone()])
}

fn blow_up_exact(t: f64) -> Float {
    Float::with_val(PREC, 1) / (Float::with_val(PREC, 1) - Float::with_val(PREC, t))
}

/// The piece encloses x(t) = 1/(1 − t) at 41 times of its span.
fn piece_holds_blow_up(out: &StepOut<1>) {
    let (t0, t1) = (out.piece.t0(), out.piece.t1());
    for i in 0..=40 {
        let t = t0 + (t1 - t0) * i as f64 / 40.0;
        let t = t.min(t1);
        let enc = out.piece.enclose(&point(t))[0];
        assert!(
            encloses(enc, &blow_up_exact(t)),
            "x({t}) = {} ∉ {enc:?} (piece [{t0}, {t1}])",
            blow_up_exact(t).to_f64()
        );
        assert!(
            encloses(out.apriori[0], &blow_up_exact(t)),
            "a-priori box at {t}"
        );
    }
    assert!(encloses(out.x1[0], &blow_up_exact(t1)), "x1 at {t1}");
}

#[test]
fn a_taylor_step_whose_first_guess_fails() {
    // Low orders and a loose tolerance make the step long against the blow-up at t = 1: the
    // first a-priori guess (the polynomial over [0, h] with the remainder at X, inflated)
    // misses the solution, and the inclusion test must reject it. Whatever step is taken, the
    // piece, its end and its a-priori box hold the exact solution, and the a-priori box is a
    // fixed point of the enclosure test (Σ x_k(X)[0,h]^k + [0,h]^K x_K(Y) ⊆ Y).
    let tape = blow_up_tape();
    let tapes = Tapes::of(&tape);
    let mut taken = 0;
    for order in [2, 3, 4, 6, 8, 16] {
        for h_max in [0.3, 0.5, 0.7, 0.9, 0.95] {
            for tol in [1e-15, 1e-6, 1e-2, 1.0, 1e3] {
                let mut ws = Workspaces::default();
                let Ok(out) = taylor_step(
                    &tapes,
                    &mut ws,
                    0.0,
                    &[point(1.0)],
                    order,
                    jacobian_orders(order),
                    tol,
                    h_max,
                    1e-9,
                    &[0],
                    None,
                ) else {
                    continue;
                };
                taken += 1;
                piece_holds_blow_up(&out);
                // the a-priori box validates itself
                let y = out.apriori;
                let mut jws = Workspace::default();
                let jy = tape.jet(&y, order, &mut jws).unwrap();
                let jx = tape.jet(&[point(1.0)], order, &mut jws).unwrap();
                let coefs: Vec<[Interval; 1]> = (0..order).map(|k| [jx[0][k]]).collect();
                let s = iv(0.0, out.piece.t1());
                let again = taylor_eval(&coefs, &[jy[0][order]], &s);
                assert!(
                    again[0].subset(y[0]),
                    "order {order}, h_max {h_max}, tol {tol}: Y = {y:?} fails its own test: {again:?}"
                );
            }
        }
    }
    assert!(taken > 50, "only {taken} steps validated");
}

#[test]
fn low_order_steps_toward_a_blow_up() {
    // Picard: Y ⊇ X + [0,h]·f(Y). For h ≥ 1/4 no box validates x′ = x² from 1 (1 + h b² ≤ b
    // has no solution), so the step must fail; below, the piece holds the exact solution.
    let tape = blow_up_tape();
    let mut validated = 0;
    for h in [0.01, 0.05, 0.1, 0.2, 0.24, 0.3, 0.5, 0.7, 0.9, 0.99] {
        match low_order_step(&tape, 0.0, &[point(1.0)], h) {
            Some(out) => {
                validated += 1;
                assert!(h < 0.25, "h = {h}: no box can validate, yet one did");
                piece_holds_blow_up(&out);
            }
            None => assert!(h > 0.05, "h = {h}: a small step should validate"),
        }
    }
    assert!(validated >= 3);
}

/// x′ = y, y′ = −x: the flow is the rotation by −t.
fn rotation_tape() -> Tape<Interval, 2> {
    Tape::<Interval, 2>::record(|v| vec![v[1].clone(), -v[0].clone()])
}

#[test]
fn a_rotating_box_is_carried_as_an_affine_set() {
    // a box of radius r around (1, 0) turned by t = 10: every corner's exact image (MPFR cos/sin
    // at 256 bits) must be in the enclosure, and the enclosure must be the rotated box's hull
    // within 1 % (the linearized optimum: the set is carried by the steps' Jacobians, not
    // re-wrapped as a box)
    let w = Window::of_tape(rotation_tape());
    let (t1, r) = (10.0, 1e-6);
    let x0 = [iv(1.0 - r, 1.0 + r), iv(-r, r)];
    let out = w.enclose(x0, 0.0, t1, &TaylorOptions::default()).unwrap();
    let t = Float::with_val(PREC, t1);
    let (c, s) = (t.clone().cos(), t.sin());
    for (a, b) in [
        (1.0 - r, -r),
        (1.0 - r, r),
        (1.0 + r, -r),
        (1.0 + r, r),
        (1.0, 0.0),
    ] {
        let (a, b) = (Float::with_val(PREC, a), Float::with_val(PREC, b));
        let x = Float::with_val(PREC, &a * &c) + Float::with_val(PREC, &b * &s);
        let y = Float::with_val(PREC, &b * &c) - Float::with_val(PREC, &a * &s);
        assert!(encloses(out.x1[0], &x), "{x} ∉ {:?}", out.x1[0]);
        assert!(encloses(out.x1[1], &y), "{y} ∉ {:?}", out.x1[1]);
    }
    // the rotated box's hull: 2r(|cos t| + |sin t|) in each component
    let hull = 2.0 * r * (t1.cos().abs() + t1.sin().abs());
    for x in out.x1 {
        assert!(x.wid() < 1.01 * hull, "{} vs the optimum {hull}", x.wid());
    }
}

#[test]
fn newton_claims_no_root_it_has_not_proved() {
    // g(t) = a (t − r) on T = [0, 1] with a derivative enclosure [a/w, a·w] (valid, loose):
    // Root only if r ∈ T (and then it holds r), never for r outside T
    let mut state = 0x2545_F491_4F6C_DD1D_u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut roots, mut undecided_outside) = (0, 0);
    for _ in 0..20_000 {
        let a = -(0.1 + 10.0 * next());
        let w = 1.0 + 20.0 * next();
        // roots inside and just outside T, some at a few ulps beyond the ends
        let r = match (next() * 4.0) as u32 {
            0 => 1.0 + next() * 1e-12,
            1 => -next() * 1e-12,
            2 => 1.0 + f64::EPSILON * (1.0 + (next() * 8.0).floor()),
            _ => next() * 1.2 - 0.1,
        };
        let ri = Rational::from_f64(r).unwrap();
        let g = |m: &Interval| point(a) * (*m - point(r));
        let d = iv(a * w, a / w);
        let inside = (0..=1).contains(&ri);
        match interval_newton(iv(0.0, 1.0), g, |_| Some(d)) {
            Newton::Root(t) => {
                roots += 1;
                assert!(inside, "r = {r} ∉ T, yet Root({t:?})");
                let (lo, hi) = (
                    Rational::from_f64(t.inf()).unwrap(),
                    Rational::from_f64(t.sup()).unwrap(),
                );
                assert!(lo <= ri && ri <= hi, "r = {r} ∉ {t:?}");
            }
            Newton::NoRoot => assert!(!inside, "r = {r} ∈ T, yet NoRoot"),
            Newton::Undecided => {
                if !inside {
                    undecided_outside += 1;
                }
            }
        }
    }
    assert!(roots > 3000, "{roots}");
    // the loose derivative makes Newton stall outside T: without the existence proof these
    // cases would be claimed as roots
    assert!(undecided_outside > 100, "{undecided_outside}");
}

/// B = Γ = σ = 0, p = n = 1 (the closed admissible set): Z = X, X″ = −X.
fn harmonic() -> Shc<Interval> {
    Shc::new(
        NdParams::<Interval>::with_admissibility(
            ModelKind::Shc,
            Admissibility::Closed,
            point(0.0),
            point(0.0),
            point(0.5),
            point(0.0),
            point(1.0),
            point(1.0),
        )
        .unwrap(),
    )
}

#[test]
fn harmonic_separation_encloses_pi_exactly() {
    // B = Γ = σ = 0, p = n = 1: Z = X, X″ = −X from X = 0, V = −1: F = sin T, V = −cos T,
    // T_s = π and e = 1 — compared with π itself, not a double near it
    let r = rigorous_impact(&harmonic(), &TaylorOptions::default()).unwrap();
    let pi = Float::with_val(PREC, rug::float::Constant::Pi);
    assert!(encloses(r.ts, &pi), "π ∉ {:?}", r.ts);
    assert!(encloses(r.e, &Float::with_val(PREC, 1)), "1 ∉ {:?}", r.e);
    assert!(
        r.ts.wid() < 1e-11 && r.e.wid() < 1e-12,
        "{:?} {:?}",
        r.ts,
        r.e
    );
}

/// s′ = 1 from s = 0, with the outputs F(s) and V(s) recorded by `outputs`: one Taylor piece
/// over [0, 2], scanned for the event.
fn scan_outputs(
    outputs: impl FnOnce(
        &bwcl::engines::taylor::tape::Rec<Interval>,
    ) -> [bwcl::engines::taylor::tape::Rec<Interval>; 2],
) -> Verdict<1> {
    let one = point(1.0);
    let tape = Tape::<Interval, 1>::record(|v| {
        let [f, vv] = outputs(&v[0]);
        vec![v[0].scale(&point(0.0)).shift(&one), f, vv]
    });
    let tapes = Tapes::of(&tape);
    let mut ws = Workspaces::default();
    let out = taylor_step(
        &tapes,
        &mut ws,
        0.0,
        &[point(0.0)],
        8,
        2,
        1e-15,
        2.0,
        1e-9,
        &[0],
        None,
    )
    .ok()
    .expect("s′ = 1 steps exactly");
    assert_eq!(out.piece.t1(), 2.0);
    scan_piece(&tape, &mut Workspace::default(), &out.piece, true)
}

/// F = (s − 1)² + c, V = 1.
fn grazing(c: f64) -> Verdict<1> {
    scan_outputs(|s| {
        let d = s.shift(&point(-1.0));
        [
            (d.clone() * d).shift(&point(c)),
            s.scale(&point(0.0)).shift(&point(1.0)),
        ]
    })
}

/// F = a_f s + b_f, V = a_v s + b_v (affine in time).
fn affine_event(f: (f64, f64), v: (f64, f64)) -> Verdict<1> {
    scan_outputs(|s| {
        [
            s.scale(&point(f.0)).shift(&point(f.1)),
            s.scale(&point(v.0)).shift(&point(v.1)),
        ]
    })
}

#[test]
fn separation_needs_both_conditions_at_once() {
    // T_s = inf{T : F ≤ 0 ∧ V ≥ 0}, exact for affine outputs: a zero of F while V < 0, or of V
    // while F > 0, is not a separation
    let exact = |x: f64| Rational::from_f64(x).unwrap();
    // (F as (slope, value at 0), V likewise, T_s)
    type Case = ((f64, f64), (f64, f64), Option<Rational>);
    let cases: [Case; 10] = [
        // the condition holds from the start: T_s = 0 (F increasing through 0 later, V > 0: its
        // zero is where the condition ends, not where it starts)
        ((1.0, -0.6), (0.0, 1.0), Some(exact(0.0))),
        // F ≡ 0 with V > 0, and V ≡ 0 with F < 0: both hold at once from the start (F ≤ 0 and
        // V ≥ 0 are not strict)
        ((0.0, 0.0), (0.0, 1.0), Some(exact(0.0))),
        ((0.0, -1.0), (0.0, 0.0), Some(exact(0.0))),
        // F ≡ −1 and V increasing through 0 at 1.3: T_s = 1.3, not the start
        ((0.0, -1.0), (1.0, -1.3), Some(exact(1.3))),
        // F crosses at 1 while V = −1: never
        ((-1.0, 1.0), (0.0, -1.0), None),
        // F ≤ 0 from 1, V ≥ 0 from 1.3: T_s = 1.3 (V's zero, F < 0 there)
        ((-1.0, 1.0), (1.0, -1.3), Some(exact(1.3))),
        // V ≥ 0 from 0.7, F ≤ 0 from 1.3: T_s = 1.3 (F's zero, V > 0 there)
        ((-1.0, 1.3), (1.0, -0.7), Some(exact(1.3))),
        // F ≤ 0 from 0.6, V ≥ 0 until 1.7: T_s = 0.6
        ((-1.0, 0.6), (-1.0, 1.7), Some(exact(0.6))),
        // F ≤ 0 until 0.6, V ≥ 0 from 0.3: T_s = 0.3 (V's zero)
        ((1.0, -0.6), (1.0, -0.3), Some(exact(0.3))),
        // F ≤ 0 until 0.3, V ≥ 0 from 0.6: never
        ((1.0, -0.3), (1.0, -0.6), None),
    ];
    for (f, v, ts) in cases {
        // the zero of a s + b is −b/a (exact: a = ±1)
        match (affine_event(f, v), ts) {
            (Verdict::Found(ev), Some(ts)) => {
                let (lo, hi) = (exact(ev.ts.inf()), exact(ev.ts.sup()));
                assert!(
                    lo <= ts && ts <= hi,
                    "F {f:?}, V {v:?}: {:?} misses {}",
                    ev.ts,
                    ts.to_f64()
                );
                assert!(ev.ts.wid() < 1e-12, "F {f:?}, V {v:?}: {:?}", ev.ts);
            }
            (Verdict::Found(ev), None) => {
                panic!("F {f:?}, V {v:?}: no separation, found {:?}", ev.ts)
            }
            (Verdict::Undecided(t), _) => panic!("F {f:?}, V {v:?}: undecided on {t:?}"),
            (Verdict::Cleared, Some(ts)) => {
                panic!("F {f:?}, V {v:?}: T_s = {} cleared", ts.to_f64())
            }
            (Verdict::Cleared, None) => {}
        }
    }
}

#[test]
fn a_grazing_event_is_undecided() {
    // F touches 0 at T = 1 only (c = 0): T_s = 1 by the definition, but no enclosure can
    // prove F ≤ 0 there — the scan must say so, not guess; F stays above 0 (c > 0): no event;
    // F crosses (c < 0): T_s = 1 − √(−c), enclosed
    assert!(
        matches!(grazing(0.0), Verdict::Undecided(_)),
        "a tangency was decided"
    );
    for c in [1e-300, 1e-30, 1e-12] {
        assert!(
            !matches!(grazing(c), Verdict::Found(_)),
            "c = {c}: no separation exists"
        );
    }
    for c in [-1e-6, -1e-2, -0.2] {
        match grazing(c) {
            Verdict::Found(ev) => {
                let exact = Float::with_val(PREC, 1) - Float::with_val(PREC, -c).sqrt();
                assert!(encloses(ev.ts, &exact), "c = {c}: {exact} ∉ {:?}", ev.ts);
            }
            Verdict::Undecided(t) => {
                // allowed only for a near-tangency, and then T must hold the crossing
                let exact = Float::with_val(PREC, 1) - Float::with_val(PREC, -c).sqrt();
                assert!(
                    c > -1e-3 && encloses(t, &exact),
                    "c = {c}: undecided on {t:?}"
                );
            }
            Verdict::Cleared => panic!("c = {c}: the crossing was cleared"),
        }
    }
}

#[test]
fn the_condition_holds_only_when_both_parts_are_proved() {
    // `holds` (used once T_s was left undecided) on boxes of (F, V): both F ≤ 0 and V ≥ 0 must
    // be proved on the whole box
    let tape = Tape::<Interval, 2>::record(|v| {
        let zero = point(0.0);
        vec![
            v[0].scale(&zero),
            v[1].scale(&zero),
            v[0].clone(),
            v[1].clone(),
        ]
    });
    let holds = |f: (f64, f64), v: (f64, f64)| {
        bwcl::engines::taylor::event::holds(&tape, &[iv(f.0, f.1), iv(v.0, v.1)])
    };
    assert!(holds((-1.0, 0.0), (0.0, 1.0)));
    assert!(holds((-1.0, -0.5), (0.5, 1.0)));
    assert!(!holds((-1.0, 1e-300), (0.5, 1.0)), "F may be > 0");
    assert!(!holds((-1.0, -0.5), (-1e-300, 1.0)), "V may be < 0");
    assert!(!holds((0.5, 1.0), (0.5, 1.0)), "F > 0");
    assert!(!holds((-1.0, -0.5), (-1.0, -0.5)), "V < 0");
    assert!(!holds((0.5, 1.0), (-1.0, -0.5)), "neither");
}

#[test]
fn the_proved_flow_holds_the_harmonic_solution_everywhere() {
    // dense output of the whole proved flow (`Flow::enclose`): X = Z = −sin T, V = −cos T at
    // every piece boundary (where two pieces meet and their enclosures are intersected), at
    // points inside the pieces, and nothing outside [0, T_end]
    let flow = rigorous_impact(&harmonic(), &TaylorOptions::default())
        .unwrap()
        .flow;
    assert!(flow.len() > 10);
    let check = |t: f64| {
        let b = flow
            .enclose(t)
            .unwrap_or_else(|| panic!("no enclosure at {t}"));
        let tf = Float::with_val(PREC, t);
        let x = -Float::with_val(PREC, tf.sin_ref());
        let v = -Float::with_val(PREC, tf.cos_ref());
        assert!(
            encloses(b[0], &x) && encloses(b[1], &x),
            "X({t}) = {x} ∉ {b:?}"
        );
        assert!(encloses(b[2], &v), "V({t}) = {v} ∉ {:?}", b[2]);
        assert!(b.iter().all(|c| c.wid() < 1e-9), "{t}: {b:?}");
    };
    let mut times = 0;
    for piece in &flow.pieces {
        let (t0, t1) = (piece.t0(), piece.t1());
        for i in 0..=4 {
            check(t0 + (t1 - t0) * i as f64 / 4.0);
            times += 1;
        }
    }
    for i in 0..=1000 {
        check(flow.t_end() * i as f64 / 1000.0);
    }
    assert!(times > 50);
    assert!(flow.enclose(-1e-300).is_none());
    assert!(flow.enclose(flow.t_end().next_up()).is_none());
    assert!(flow.enclose(f64::NAN).is_none());
}

/// An undecided stretch is not forgotten (the engine's `pending` arm, issue #12's last
/// survivor `mod.rs:282`): the toy t′ = 1, F = (t − 1)²(5/2 − t), V = 1 grazes F = 0 at t = 1
/// — there the condition F ≤ 0 ∧ V ≥ 0 holds, so T_s = 1 exactly — and crosses cleanly at
/// t = 5/2. The engine cannot decide the graze; it must then report it (or an enclosure
/// containing 1), never the clean crossing alone.
#[test]
fn an_undecided_graze_is_not_skipped_for_a_later_crossing() {
    use bwcl::engines::taylor::integrate_system;
    let c = |x: f64| Interval::try_from((x, x)).unwrap();
    let tape = Tape::<Interval, 1>::record(|v| {
        let t = v[0].clone();
        let d = t.shift(&c(-1.0));
        let f = d.clone() * d * (-t.clone()).shift(&c(2.5));
        // t′ = 1 and V = 1, written through the state so that they are nodes of the tape
        let one = t.scale(&c(0.0)).shift(&c(1.0));
        vec![one.clone(), f, one]
    });
    match integrate_system(&tape, [c(0.0)], 1, &TaylorOptions::default()) {
        Ok((_, ev)) => assert!(
            ev.ts.contains(1.0),
            "T_s = 1 (the graze) is not in the reported {:?}",
            ev.ts
        ),
        Err(e) => assert!(e.reason.contains("grazing"), "{e}"),
    }
}

/// A horizon reached while the separation condition is still undecided is not a proof of "no
/// separation" (which the CLI reports as a proved result, T_s > horizon): the graze of the toy
/// above (F = (t − 1)²(5/2 − t), T_s = 1 exactly) with the horizon just past it. Every run must
/// either enclose T_s = 1 or say the separation is undecided — never "no separation".
#[test]
fn an_undecided_stretch_at_the_horizon_is_not_a_proof_of_no_separation() {
    use bwcl::engines::taylor::integrate_system;
    let c = |x: f64| Interval::try_from((x, x)).unwrap();
    let tape = Tape::<Interval, 1>::record(|v| {
        let t = v[0].clone();
        let d = t.shift(&c(-1.0));
        let f = d.clone() * d * (-t.clone()).shift(&c(2.5));
        let one = t.scale(&c(0.0)).shift(&c(1.0));
        vec![one.clone(), f, one]
    });
    let mut undecided = 0;
    for horizon in [1.0 + 1e-9, 1.0 + 1e-6, 1.0 + 1e-4, 1.0005] {
        let opts = TaylorOptions {
            horizon,
            ..TaylorOptions::default()
        };
        match integrate_system(&tape, [c(0.0)], 1, &opts) {
            Ok((_, ev)) => assert!(ev.ts.contains(1.0), "{horizon}: {:?}", ev.ts),
            Err(e) => {
                assert!(!e.no_separation(), "{horizon}: {e}");
                undecided += e.reason.contains("grazing") as usize;
            }
        }
    }
    // the guard is what decides here: the stretch is pending at the horizon
    assert!(undecided > 0);
}

/// A kink component a few ulps from 0 and moving towards it is crossed by a low-order step at
/// once (`kink_now` in the engine's loop): Taylor steps there are cut before the crossing or
/// leave it unresolved at every length (interval Newton cannot separate a crossing 2·10⁻¹⁴
/// ahead from t0), ≈ 18 of them tried in vain before the low-order step. The toy x′ = 1,
/// y′ = |x| from x = −2·10⁻¹⁴, y = 0, with F = 1 − y and V = 1: y(t) = x₀²/2 + (t + x₀)²/2
/// past the kink, so T_s = −x₀ + √(2 − x₀²). The first piece is the low-order step, the steps
/// refused in the whole run are few, and T_s is enclosed.
#[test]
fn a_kink_just_ahead_is_crossed_at_once_by_a_low_order_step() {
    use bwcl::engines::taylor::flow::Piece;
    use bwcl::engines::taylor::integrate_system;
    let c = |x: f64| Interval::try_from((x, x)).unwrap();
    let tape = Tape::<Interval, 2>::record(|v| {
        let (x, y) = (v[0].clone(), v[1].clone());
        let one = x.scale(&c(0.0)).shift(&c(1.0));
        let f = (-y).shift(&c(1.0));
        vec![one.clone(), bwcl::arith::Real::abs(&x), f, one]
    });
    assert_eq!(tape.kinks(), &[0], "x is a kink component");
    let x0 = -2e-14;
    let (flow, ev) =
        integrate_system(&tape, [c(x0), c(0.0)], 2, &TaylorOptions::default()).expect("proved");
    assert!(
        matches!(flow.pieces[0], Piece::LowOrder { .. }),
        "the first step is not the low-order step across the kink"
    );
    assert!(
        flow.refused_taylor <= 4,
        "{} Taylor steps refused (the kink was approached by Taylor steps)",
        flow.refused_taylor
    );
    let x = c(x0);
    let exact = -x + (c(2.0) - x * x).sqrt();
    assert!(exact.subset(ev.ts), "T_s {:?} misses {exact:?}", ev.ts);
}
