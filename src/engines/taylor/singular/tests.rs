//! The singular step against a closed form: the Hertz oscillator ẋ = v, v̇ = −|x|^(p−1)x keeps
//! its energy E = v²/2 + |x|^(p+1)/(p+1) along every solution, and x passes through its branch
//! point 0. A step across x = 0 from a small box must end in a box whose energy enclosure holds
//! the energy of every corner of the start box (computed with MPFR at 200 bits): the image of
//! the box, not only of its centre.
//!
//! Each check runs on f64 intervals and on MPFR intervals (`Mpi<128>`, the expansions'
//! tunables of [`SingularOptions::at_precision`] for a tolerance 1e-33), where the enclosures
//! must be as narrow as that precision allows (≤ 1e-30 where the start box is a point).

use super::*;
use crate::arith::Scalar;
use crate::arith::mpfr::Mpi;
use crate::engines::taylor::rec::Rec;
use inari::Interval;
use rug::Float;
use rug::ops::Pow;

type M = Mpi<128>;

/// The options of the checks: at f64 precision as given, at MPFR precision the tunables for a
/// tolerance 1e-33 (30 digits).
fn opts_for<I: Enclosure>(f64_opts: SingularOptions) -> SingularOptions {
    if I::epsilon() >= f64::EPSILON {
        f64_opts
    } else {
        SingularOptions::at_precision(I::epsilon(), 1e-33)
    }
}

/// The width an enclosure of a point's flow may have: a few ulps at f64, 1e-30 at MPFR.
fn tight<I: Enclosure>(f64_tight: f64) -> f64 {
    if I::epsilon() >= f64::EPSILON {
        f64_tight
    } else {
        1e-30
    }
}

fn iv<I: Enclosure>(a: f64, b: f64) -> I {
    I::from_bounds(a, b).unwrap()
}

fn hertz<I: Enclosure>(p: &str) -> (Tape<I, 2>, I) {
    let q = I::parse_decimal(p).unwrap();
    let tape = Tape::<I, 2>::record(|v: &[Rec<I>; 2]| vec![v[1].clone(), -Scalar::spow(&v[0], &q)]);
    (tape, q)
}

/// E at the exact double point (x, v), p given as a decimal, at 200 bits.
fn energy_mpfr(x: f64, v: f64, p: &str) -> Float {
    let prec = 200;
    let p = Float::with_val(prec, Float::parse(p).unwrap());
    let p1 = Float::with_val(prec, &p + 1u32);
    let xa = Float::with_val(prec, x.abs());
    let xp = Float::with_val(prec, (&xa).pow(&p1));
    let v2 = Float::with_val(prec, v * v) / 2u32;
    Float::with_val(prec, xp / &p1) + v2
}

fn energy_iv<I: Enclosure>(x: &[I; 2], q: &I) -> I {
    let p1 = q.clone() + I::one();
    Real::apow(&x[0], &p1) / p1 + x[1].clone() * x[1].clone() / I::from_int(2)
}

/// `e` (an exact value) in the enclosure `x`: against x's outward f64 ends, and — since those
/// are loose at MPFR precision — `inner` (an enclosure of e in the type) inside x.
fn holds<I: Enclosure>(x: &I, e: &Float, inner: &I) -> bool {
    Float::with_val(200, x.lo()) <= *e && *e <= Float::with_val(200, x.hi()) && inner.subset(x)
}

fn check_crossing<I: Enclosure>(p: &str, x0: f64, v0: f64, half: f64) -> f64 {
    let (tape, q) = hertz::<I>(p);
    let opts = opts_for::<I>(SingularOptions {
        max_exp: 6.0,
        iterations: 4,
        tighten: 2,
        ..SingularOptions::default()
    });
    let st = SingularTape::of(&tape, &opts).expect("constant exponents");
    let dual = tape.map(|c| Dual::constant(c.clone()));
    let bx: [I; 2] = [iv(x0 - half, x0 + half), iv(v0 - half, v0 + half)];
    let out = crossing_step(&st, &tape, &dual, 0.0, &bx, None, 0, &opts)
        .unwrap_or_else(|| panic!("p = {p}: the crossing is refused"));
    // it crossed: x changed sign
    assert!(out.x1[0].hi() < 0.0, "p = {p}: {:?}", out.x1);
    let e1 = energy_iv(&out.x1, &q);
    for (cx, cv) in [
        (bx[0].inf_point(), bx[1].inf_point()),
        (bx[0].inf_point(), bx[1].sup_point()),
        (bx[0].sup_point(), bx[1].inf_point()),
        (bx[0].sup_point(), bx[1].sup_point()),
    ] {
        let e = energy_mpfr(cx.mid(), cv.mid(), p);
        let inner = energy_iv(&[cx, cv], &q);
        assert!(
            holds(&e1, &e, &inner),
            "p = {p}: E(corner) = {e} outside {e1:?}"
        );
    }
    // and it is an enclosure of the image, not of everything: a few times the box's width
    assert!(
        e1.wid_f64() < 20.0 * half + tight::<I>(0.0),
        "p = {p}: {e1:?}"
    );
    e1.wid_f64()
}

/// A box thin in x and wide in v: over the step, x picks up ∫v, so the image of the box is
/// sheared (the Jacobian's off-diagonal τ). Each corner's own flow (a point step, which uses no
/// Jacobian) must end inside the box's image.
fn check_shear<I: Enclosure>(p: &str) {
    let (tape, _) = hertz::<I>(p);
    let opts = opts_for::<I>(SingularOptions::default());
    let st = SingularTape::of(&tape, &opts).unwrap();
    let dual = tape.map(|c| Dual::constant(c.clone()));
    let bx: [I; 2] = [iv(2e-3, 2e-3), iv(-1.0 - 1e-8, -1.0 + 1e-8)];
    let out = crossing_step(&st, &tape, &dual, 0.0, &bx, None, 0, &opts).expect("crossed");
    let t1 = out.piece.t1();
    for v in [bx[1].inf_point(), bx[1].sup_point()] {
        let c = [bx[0].clone(), v.clone()];
        let (_, z) = cross_point(&st, &tape, 0.0, &c, 0, &opts, Some(t1)).expect("point");
        for (i, (zi, xi)) in z.iter().zip(&out.x1).enumerate() {
            assert!(
                zi.subset(xi),
                "p = {p}, v0 = {v:?}: component {i}: {zi:?} not in {xi:?}"
            );
        }
    }
}

#[test]
fn the_image_of_a_sheared_box_holds_each_corners_flow() {
    for p in ["1.5", "2.28"] {
        check_shear::<Interval>(p);
        check_shear::<M>(p);
    }
}

#[test]
fn hertz_crossings_keep_the_energy_of_every_corner() {
    for p in ["1.5", "1.27", "2.28", "3.14"] {
        check_crossing::<Interval>(p, 2e-3, -1.0, 1e-12);
        check_crossing::<Interval>(p, 5e-4, -0.7, 1e-9);
        // at the distance the MPFR tunables trigger the step (their δ^M ≈ tol)
        let near = opts_for::<M>(SingularOptions::default()).near;
        check_crossing::<M>(p, near, -1.0, 1e-12);
        check_crossing::<M>(p, 0.5 * near, -0.7, 1e-9);
    }
}

/// At MPFR precision from a point (a box of width 0): the energy is proved to 1e-30 across the
/// branch point, which f64 intervals cannot do (their ulp is 2e-16).
#[test]
fn hertz_crossings_of_a_point_are_proved_to_30_digits_at_128_bits() {
    for p in ["1.5", "1.27", "2.28", "3.14"] {
        let near = opts_for::<M>(SingularOptions::default()).near;
        for (x0, v0) in [(near, -1.0), (0.5 * near, -0.7)] {
            let w = check_crossing::<M>(p, x0, v0, 0.0);
            assert!(w <= 1e-30, "p = {p}, x0 = {x0}: width {w:e}");
        }
    }
}

#[test]
fn a_crossing_with_the_velocity_reaching_zero_is_refused() {
    fn check<I: Enclosure>() {
        // x near 0 but v = 0 there too (x does not cross: the expansion in x does not exist)
        let (tape, _) = hertz::<I>("1.5");
        let opts = opts_for::<I>(SingularOptions::default());
        let st = SingularTape::of(&tape, &opts).unwrap();
        let dual = tape.map(|c| Dual::constant(c.clone()));
        let bx: [I; 2] = [iv(1e-3, 1e-3), iv(-1e-6, 1e-6)];
        assert!(crossing_step(&st, &tape, &dual, 0.0, &bx, None, 0, &opts).is_none());
    }
    check::<Interval>();
    check::<M>();
}

/// The Hertz oscillator with a twin: ẋ = v, ż = v, v̇ = −½|x|^(p−1)x − ½|z|^(p−1)z from
/// x = z = 0, v = −1 (z ≡ x: two components at the branch point at once, as at the models'
/// start; the force is half z's). E = v²/2 + |x|^(p+1)/(p+1) = 1/2 along the solution.
fn hertz_twin<I: Enclosure>(p: &str) -> (Tape<I, 3>, I) {
    let q = I::parse_decimal(p).unwrap();
    let half = I::from_exact_f64(0.5);
    let tape = Tape::<I, 3>::record(|v: &[Rec<I>; 3]| {
        vec![
            v[2].clone(),
            v[2].clone(),
            -(Scalar::spow(&v[0], &q) + Scalar::spow(&v[1], &q)).scale(&half),
        ]
    });
    (tape, q)
}

/// The start step of the twin Hertz oscillator: the energy enclosure at t₁ holds 1/2 (compared
/// exactly), z − x holds 0, and x moved (the step went somewhere).
fn check_start<I: Enclosure>(p: &str, delta: f64) -> [I; 3] {
    let (tape, q) = hertz_twin::<I>(p);
    let opts = opts_for::<I>(SingularOptions::default());
    let st = SingularTape::of(&tape, &opts).expect("constant exponents");
    let basis = Basis::new(st.basis.gens(), opts.start_max_exp).unwrap();
    let x0: [I; 3] = [I::zero(), I::zero(), -I::one()];
    let out = start::start_step(&st.tape, &basis, &tape, 0.0, &x0, delta, &opts)
        .unwrap_or_else(|| panic!("p = {p}: the start step is refused"));
    let x1 = out.x1;
    assert!(x1[0].hi() < 0.0 && x1[1].hi() < 0.0, "p = {p}: {x1:?}");
    let e1 = energy_iv(&[x1[0].clone(), x1[2].clone()], &q);
    let half = I::from_exact_f64(0.5);
    assert!(
        half.subset(&e1),
        "p = {p}, δ = {delta}: E = {e1:?} misses 1/2"
    );
    let d = x1[1].clone() - x1[0].clone();
    assert!(I::zero().subset(&d), "p = {p}: z − x = {d:?}");
    // an enclosure, not everything: a few ulps of 1/2 at the default δ (the remainder grows
    // like δ^M beyond it)
    let tight = if delta <= opts.start_delta {
        tight::<I>(1e-14)
    } else {
        tight::<I>(1e-10)
    };
    assert!(e1.wid_f64() < tight, "p = {p}, δ = {delta}: {e1:?}");
    x1
}

#[test]
fn the_start_step_keeps_the_energy_of_the_hertz_oscillator() {
    for p in ["1.5", "1.27", "2.28", "3.14"] {
        for delta in [1e-3, 5e-3, 2e-2] {
            check_start::<Interval>(p, delta);
        }
        let d = opts_for::<M>(SingularOptions::default()).start_delta;
        check_start::<M>(p, d);
        check_start::<M>(p, 0.5 * d);
    }
}

/// A pair whose second component is not a copy: ẋ = v, ż = v(1 + z)², v̇ = −½|x|^(p−1)x −
/// ½|z|^(p−1)z(1 + z)² from x = z = 0, v = −1. Then z = x/(1 − x) (dz/dx = (1 + z)²), so z's
/// W = 1/(1 + u) is not constant (x = −u), and E = v²/2 + (|x|^(p+1) + |z|^(p+1))/(2(p+1)) =
/// 1/2 (Ė = 0 term by term). The start step's box at t₁ must hold E = 1/2 and z(1 − x) − x = 0.
fn check_start_pair<I: Enclosure>(p: &str, delta: f64) {
    let q = I::parse_decimal(p).unwrap();
    let half = I::from_exact_f64(0.5);
    let tape = Tape::<I, 3>::record(|v: &[Rec<I>; 3]| {
        let one_z = v[1].shift(&I::one());
        let sq = one_z.clone() * one_z;
        vec![
            v[2].clone(),
            v[2].clone() * sq.clone(),
            -(Scalar::spow(&v[0], &q) + Scalar::spow(&v[1], &q) * sq).scale(&half),
        ]
    });
    let opts = opts_for::<I>(SingularOptions::default());
    let st = SingularTape::of(&tape, &opts).expect("constant exponents");
    let basis = Basis::new(st.basis.gens(), opts.start_max_exp).unwrap();
    let x0: [I; 3] = [I::zero(), I::zero(), -I::one()];
    let out = start::start_step(&st.tape, &basis, &tape, 0.0, &x0, delta, &opts)
        .unwrap_or_else(|| panic!("p = {p}: the start step is refused"));
    let [x, z, v] = out.x1;
    assert!(x.hi() < 0.0 && z.hi() < 0.0, "p = {p}: {x:?} {z:?}");
    let p1 = q.clone() + I::one();
    let e1 = (Real::apow(&x, &p1) + Real::apow(&z, &p1)) / (p1 * I::from_int(2))
        + v.clone() * v / I::from_int(2);
    assert!(
        half.subset(&e1),
        "p = {p}, δ = {delta}: E = {e1:?} misses 1/2"
    );
    let inv = z * (I::one() - x.clone()) - x;
    assert!(
        I::zero().subset(&inv),
        "p = {p}, δ = {delta}: z(1 − x) − x = {inv:?}"
    );
    let tight = if delta <= opts.start_delta {
        tight::<I>(1e-13)
    } else {
        tight::<I>(1e-9)
    };
    assert!(
        e1.wid_f64() < tight && inv.wid_f64() < tight,
        "p = {p}, δ = {delta}: {e1:?} {inv:?}"
    );
}

#[test]
fn the_start_step_keeps_the_invariants_of_a_coupled_pair() {
    for p in ["1.5", "1.27", "2.28", "3.14"] {
        for delta in [1e-3, 5e-3, 2e-2] {
            check_start_pair::<Interval>(p, delta);
        }
        let d = opts_for::<M>(SingularOptions::default()).start_delta;
        check_start_pair::<M>(p, d);
        check_start_pair::<M>(p, 0.5 * d);
    }
}

/// t(u) = t₀ + c·u + d·u^1.5 on [0, δ] with interval coefficients (a band of functions): the
/// exit bracket must hold every u where a function of the band meets t1 — from the estimate,
/// from a hint that misses u* (its ends fail the checks: the bisection starts from [0, δ]),
/// from none, placed directly from the estimate ([`exit_direct`]) and from a poor estimate
/// (half the true u: its checks fail, or its bracket still holds the band) — and the
/// estimate's brackets are as tight as the plain bisection's.
#[test]
fn the_exit_bracket_holds_every_crossing_of_the_band() {
    let basis = Basis::<Interval>::new(&[iv::<Interval>(1.5, 1.5)], 4.0).unwrap();
    let delta = 1e-3;
    let ctx = Ctx::new(&basis, delta).unwrap();
    let u = Gts::variable(&ctx, 1);
    let u15 = Real::apow(&u, &Gts::constant(iv(1.5, 1.5)));
    let (c, d) = (iv::<Interval>(0.9, 1.1), iv::<Interval>(2.0, 3.0));
    let t = Gts::constant_in(&ctx, iv(2.0, 2.0))
        + u.clone() * Gts::constant(c)
        + u15 * Gts::constant(d);
    let t1 = 2.0 + 5e-4;
    // the band's crossings: the smallest u from the largest coefficients and vice versa
    let solve = |c: f64, d: f64| {
        let (mut a, mut b) = (0.0_f64, delta);
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if c * m + d * m.powf(1.5) < 5e-4 {
                a = m
            } else {
                b = m
            }
        }
        (a, b)
    };
    let (first, _) = solve(1.1, 3.0);
    let (_, last) = solve(0.9, 2.0);
    let plain = exit_parameter_from(&t, t1, delta, None).unwrap();
    let estimate = exit_estimate(&t, t1, delta).expect("an estimate");
    let guess = exit_guess(&t, delta, estimate);
    // the band's width varies along u: the direct bracket may fail its checks (then the
    // bisections run), never hold a wrong bracket
    let direct = exit_direct(&t, t1, delta, estimate);
    // a poor estimate likewise
    let off = exit_direct(&t, t1, delta, 0.5 * estimate);
    for (what, b) in [
        ("estimate", exit_parameter_from(&t, t1, delta, guess)),
        (
            "missing hint",
            exit_parameter_from(&t, t1, delta, Some((0.8 * delta, 0.9 * delta))),
        ),
        ("none", exit_parameter_from(&t, t1, delta, None)),
        ("exit_parameter", exit_parameter(&t, t1, delta)),
    ]
    .into_iter()
    .chain(direct.map(|b| ("direct", Some(b))))
    .chain(off.map(|b| ("direct from a poor estimate", Some(b))))
    {
        let b = b.unwrap();
        assert!(
            b.inf() <= first && last <= b.sup(),
            "{what}: {b:?} ⊉ [{first}, {last}]"
        );
        assert!(
            off.is_some_and(|o| o.same(&b)) || b.wid() <= 1.01 * plain.wid(),
            "{what}: {b:?} wider than {plain:?}"
        );
    }
    assert!(guess.is_some(), "the estimate is used here");
}

/// The direct exit bracket ([`exit_direct`]) on a thin t(u) = 2 + c·u + d·u^1.5 + [−r, r]
/// (point coefficients, a remainder r): it passes its checks from the estimate, holds the
/// exact u* of 2 + c·u* + d·u*^1.5 = t1 (200-bit MPFR bisection) with room for the remainder,
/// and is no wider than the bisections' bracket by more than 3 % and a few ulps; from a poor
/// estimate it fails or still holds u*.
#[test]
fn the_direct_exit_bracket_holds_the_exact_parameter() {
    let basis = Basis::<Interval>::new(&[iv::<Interval>(1.5, 1.5)], 4.0).unwrap();
    let delta = 1e-3;
    let ctx = Ctx::new(&basis, delta).unwrap();
    let u = Gts::variable(&ctx, 1);
    let u15 = Real::apow(&u, &Gts::constant(iv(1.5, 1.5)));
    for (c, d, r) in [(1.0, 2.5, 0.0), (0.7, -3.0, 1e-15), (1.3, 40.0, 1e-13)] {
        let t = Gts::constant_in(&ctx, iv(2.0, 2.0))
            + u.clone() * Gts::from_exact_f64(c)
            + u15.clone() * Gts::from_exact_f64(d)
            + Gts::constant_in(&ctx, iv(-r, r));
        let t1 = 2.0 + 4e-4;
        // u* for the remainder at either end: t(u) = t1 ∓ r, exactly in rationals
        let root = |shift: f64| {
            let (mut a, mut b) = (Float::with_val(200, 0), Float::with_val(200, delta));
            let target = Float::with_val(200, t1) - Float::with_val(200, 2.0) - shift;
            for _ in 0..190 {
                let m: Float = Float::with_val(200, &a + &b) / 2u32;
                let v = Float::with_val(200, c) * &m
                    + Float::with_val(200, d) * m.clone().pow(Float::with_val(200, 1.5));
                if v < target { a = m } else { b = m }
            }
            a
        };
        let (first, last) = (root(r), root(-r));
        let plain = exit_parameter_from(&t, t1, delta, None).unwrap();
        let estimate = exit_estimate(&t, t1, delta).expect("an estimate");
        let b = exit_direct(&t, t1, delta, estimate).expect("the direct bracket passes");
        assert!(
            Float::with_val(200, b.inf()) <= first && last <= Float::with_val(200, b.sup()),
            "c {c} d {d} r {r}: {b:?} ⊉ [{first}, {last}]"
        );
        assert!(
            b.wid() <= 1.03 * plain.wid() + 16.0 * f64::EPSILON * b.sup(),
            "c {c} d {d} r {r}: {b:?} wider than {plain:?}"
        );
        if let Some(o) = exit_direct(&t, t1, delta, 0.5 * estimate) {
            assert!(
                Float::with_val(200, o.inf()) <= first && last <= Float::with_val(200, o.sup()),
                "c {c} d {d}: poor estimate {o:?}"
            );
        }
    }
}

/// u^α by the basis' table of powers ([`Ctx::powers`]) holds u^α computed with MPFR at 200 bits,
/// for points and intervals of u, and is ≤ 128 ulps wide at a point (measured ≤ 70, at α ≈ 6).
#[test]
fn the_table_of_powers_holds_every_power() {
    let basis = Basis::<Interval>::new(&[iv::<Interval>(1.5, 1.5), iv(1.25, 1.25)], 6.0).unwrap();
    let ctx = Ctx::new(&basis, 1e-2).unwrap();
    let keys = basis.keys().to_vec();
    let alpha = |k: &super::puiseux::Key| k[0] as f64 + 1.5 * k[1] as f64 + 1.25 * k[2] as f64;
    for (a, b) in [(3e-3, 3e-3), (1e-3, 4e-3), (0.0, 1e-2), (7.5e-3, 7.5e-3)] {
        let u = iv::<Interval>(a, b);
        let p = ctx.powers(&u, keys.len() - 1);
        assert_eq!(p.len(), keys.len());
        for (i, k) in keys.iter().enumerate() {
            let al = alpha(k);
            for x in [a, b] {
                let exact = Float::with_val(200, x).pow(Float::with_val(200, al));
                assert!(
                    exact >= p[i].inf() && exact <= p[i].sup(),
                    "u = [{a}, {b}], α = {al}: {:?} ∌ {x}^{al}",
                    p[i]
                );
            }
            if a == b {
                // (a key of degree d: d products of powers a few ulps wide each)
                assert!(
                    p[i].wid() <= 128.0 * f64::EPSILON * p[i].sup(),
                    "{:?}",
                    p[i]
                );
            }
        }
    }
}

/// The twin of a power (|x|^(q−1)x from |x|^q and the reverse) on generalized polynomials of a
/// certain sign equals the power computed anew, for both signs; of an uncertain sign it is
/// computed anew (unbounded here, as the power itself).
#[test]
fn twin_powers_equal_the_powers() {
    let basis = Basis::<Interval>::new(&[iv::<Interval>(1.5, 1.5)], 4.0).unwrap();
    let ctx = Ctx::new(&basis, 1e-2).unwrap();
    let q = Gts::constant(iv::<Interval>(1.27, 1.27));
    for x0 in [-0.5, 0.5] {
        let x = Gts::constant_in(&ctx, iv(x0, x0)) + Gts::variable(&ctx, 1);
        let (s, a) = (Real::spow(&x, &q), Real::apow(&x, &q));
        let (ts, ta) = (
            Real::twin_pow(&x, &q, &a, true),
            Real::twin_pow(&x, &q, &s, false),
        );
        for (twin, direct) in [(&ts, &s), (&ta, &a)] {
            assert_eq!(twin.terms().len(), direct.terms().len());
            for ((_, c1), (_, c2)) in twin.terms().iter().zip(direct.terms()) {
                assert!(
                    c1.inf() == c2.inf() && c1.sup() == c2.sup(),
                    "x0 {x0}: {c1:?} {c2:?}"
                );
            }
            assert_eq!(twin.remainder(), direct.remainder());
        }
    }
    // across 0: no certain sign, computed anew
    let x = Gts::constant_in(&ctx, iv(-1e-3, 1e-3)) + Gts::variable(&ctx, 1);
    let a = Real::apow(&x, &q);
    assert!(!Real::twin_pow(&x, &q, &a, true).is_bounded());
}

/// An f64 interval [a, b].
fn ivf(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).unwrap()
}

/// The toy basis of the validation tests: generators 1 and 1.5, cut-off M = 3, on [0, 1/4].
fn toy_ctx() -> Arc<Ctx<Interval>> {
    Ctx::new(&Basis::new(&[ivf(1.5, 1.5)], 3.0).unwrap(), 0.25).unwrap()
}

/// The key of u^(k₀ + 1.5k₁).
fn key(k0: u8, k1: u8) -> puiseux::Key {
    let mut k = [0; puiseux::MAX_GENS];
    (k[0], k[1]) = (k0, k1);
    k
}

/// [`validate`] of the one-component operator `image` from `y0` with a single candidate
/// S = y0 inflated, no plain iterations before and no tightening images after: the answer is
/// the inclusion T(S) ⊆ S alone.
fn one_candidate(
    y0: Gts<Interval>,
    image: impl Fn(&Gts<Interval>) -> Gts<Interval>,
) -> Option<Vec<Gts<Interval>>> {
    let opts = SingularOptions {
        tries: 1,
        iterations: 0,
        truncated_iterations: false,
        tighten: 0,
        ..SingularOptions::default()
    };
    validate(
        vec![y0],
        usize::MAX,
        &opts,
        3.0,
        (false, 0),
        false,
        |y, _| Some(vec![image(&y[0])]),
    )
}

/// The validation refuses a candidate whose image leaves it by one clause of the inclusion
/// alone — a wider remainder; a term the candidate lacks; a term the image lacks where the
/// candidate's coefficient excludes 0; an image on another domain — and accepts the identity
/// and the same images where the clause holds (the term's coefficient 0, or 0 in the
/// candidate's coefficient).
#[test]
fn the_validation_refuses_an_image_outside_the_candidate_by_any_one_clause() {
    let ctx = toy_ctx();
    let rem = ivf(-1e-3, 1e-3);
    let one = (key(0, 0), ivf(1.0, 1.0));
    let y0 = Gts::from_parts(&ctx, &[one, (key(1, 0), ivf(0.5, 0.5))], rem);
    let with = |s: &Gts<Interval>, extra: (puiseux::Key, Interval)| {
        let mut t = s.terms();
        t.push(extra);
        Gts::from_parts(&ctx, &t, s.remainder())
    };
    let without = |s: &Gts<Interval>, k: puiseux::Key| {
        let t: Vec<_> = s.terms().into_iter().filter(|e| e.0 != k).collect();
        Gts::from_parts(&ctx, &t, s.remainder())
    };
    assert!(one_candidate(y0.clone(), |s| s.clone()).is_some());
    // the remainder
    let wider = |s: &Gts<Interval>| Gts::from_parts(&ctx, &s.terms(), s.remainder() + rem);
    assert!(one_candidate(y0.clone(), wider).is_none());
    // a term S lacks (inside only as 0)
    assert!(one_candidate(y0.clone(), |s| with(s, (key(0, 1), ivf(0.25, 0.25)))).is_none());
    assert!(one_candidate(y0.clone(), |s| with(s, (key(0, 1), ivf(0.0, 0.0)))).is_some());
    // a term T(S) lacks: inside only where S's coefficient holds 0
    let lacks = |c: Interval| {
        let y = Gts::from_parts(&ctx, &[one, (key(0, 1), c)], rem);
        one_candidate(y, |s| without(s, key(0, 1)))
    };
    assert!(lacks(ivf(0.25, 0.25)).is_none());
    assert!(lacks(ivf(-0.25, -0.125)).is_none());
    assert!(lacks(ivf(-0.25, 0.25)).is_some());
    // another domain: the same keys and coefficients are other functions there
    let shorter = Ctx::new(&Basis::new(&[ivf(1.5, 1.5)], 3.0).unwrap(), 0.125).unwrap();
    let moved = |s: &Gts<Interval>| Gts::from_parts(&shorter, &s.terms(), s.remainder());
    assert!(one_candidate(y0.clone(), moved).is_none());
    let other = Ctx::new(&Basis::new(&[ivf(1.25, 1.25)], 3.0).unwrap(), 0.25).unwrap();
    let renamed = |s: &Gts<Interval>| Gts::from_parts(&other, &s.terms(), s.remainder());
    let y = Gts::from_parts(&ctx, &[one, (key(0, 1), ivf(0.5, 0.5))], rem);
    assert!(one_candidate(y, renamed).is_none());
}

/// A genuine contraction: T(y) = 1 + ∫₀^u y/2 on [0, 1/4] (generators 1 and 1.5, M = 8)
/// validates from the constant 1, and the validated set holds its fixed point e^(u/2) at
/// u ∈ {0, 1/16, 1/8, 3/16, 1/4} — e^(u/2) rounded down and up at 200 bits inside the
/// enclosure's ends — and is narrow there (the terms beyond M are ≈ (u/2)⁹/9! ≤ 2e-14).
#[test]
fn a_contraction_validates_and_holds_its_fixed_point() {
    use rug::float::Round;
    let ctx = Ctx::new(&Basis::new(&[ivf(1.5, 1.5)], 8.0).unwrap(), 0.25).unwrap();
    let opts = SingularOptions {
        iterations: 10,
        truncated_iterations: false,
        ..SingularOptions::default()
    };
    let half = Gts::from_exact_f64(0.5);
    let y = validate(
        vec![Gts::constant_in(&ctx, ivf(1.0, 1.0))],
        usize::MAX,
        &opts,
        8.0,
        (false, 10),
        false,
        |y, _| {
            Some(vec![
                Gts::constant_in(&ctx, ivf(1.0, 1.0)) + (y[0].clone() * half.clone()).integral(),
            ])
        },
    )
    .expect("a contraction validates");
    for u in [0.0, 0.0625, 0.125, 0.1875, 0.25] {
        let e = y[0].eval(&ivf(u, u));
        let x = Float::with_val(200, u) / 2u32;
        let (mut lo, mut hi) = (Float::with_val(200, &x), Float::with_val(200, &x));
        lo.exp_round(Round::Down);
        hi.exp_round(Round::Up);
        assert!(
            lo >= e.inf() && hi <= e.sup(),
            "u = {u}: e^(u/2) = {lo} not in {e:?}"
        );
        assert!(e.wid() < 1e-12, "u = {u}: {e:?}");
    }
}

/// The start step from (x, z, v) = (0, 0, −1) on a toy tape, x the independent variable and z
/// the second component at its branch point: its state at t₁, or `None` (refused).
fn start_of(tape: &Tape<Interval, 3>, delta: f64) -> Option<(f64, [Interval; 3])> {
    let opts = SingularOptions::default();
    let st = SingularTape::of(tape, &opts).expect("constant exponents");
    let basis = Basis::new(st.basis.gens(), opts.start_max_exp).unwrap();
    let x0 = [ivf(0.0, 0.0), ivf(0.0, 0.0), ivf(-1.0, -1.0)];
    start::start_point(&st.tape, &basis, tape, 0.0, &x0, delta, &opts)
}

/// ẋ = v, ż = v·(1 + k·x), v̇ = a − ½|x|^(q−1)x − ½·force(z, x), q = 1.5 (`k`, `a` exact).
fn toy_start_tape(
    k: f64,
    a: f64,
    force: impl Fn(&Rec<Interval>, &Rec<Interval>) -> Rec<Interval>,
) -> Tape<Interval, 3> {
    let q = ivf(1.5, 1.5);
    let (k, a, half) = (ivf(k, k), ivf(a, a), ivf(0.5, 0.5));
    Tape::<Interval, 3>::record(|v: &[Rec<Interval>; 3]| {
        let zrate = v[0].scale(&k).shift(&ivf(1.0, 1.0));
        vec![
            v[2].clone(),
            v[2].clone() * zrate,
            -(Scalar::spow(&v[0], &q) + force(&v[1], &v[0])).scale(&half) + Rec::constant(a),
        ]
    })
}

/// The start step's hypothesis that f_w keeps its sign (dt/du = σ/f_w bounded): with v̇ = 40
/// the velocity v = ẋ reaches 0 at u = |x| ≈ 1/80, where x turns back. On δ = 0.005 the step
/// is taken; on δ = 0.05, where 1/v has no expansion, it must be refused.
#[test]
fn the_start_step_is_refused_where_the_rate_of_its_variable_reaches_zero() {
    let tape = toy_start_tape(0.0, 40.0, |z, _| Scalar::spow(z, &ivf(1.5, 1.5)));
    assert!(start_of(&tape, 0.005).is_some());
    assert!(start_of(&tape, 0.05).is_none());
}

/// The start step's hypothesis W_z > 0 for the factored z = s·u·W_z: with ż = v·(1 − 50u)
/// (x = −u), W_z = 1 − 25u reaches 0 at u = 0.04. On δ = 0.01 the step is taken; on δ = 0.05
/// it must be refused — with z in a power (|z|^(q−1)z), in |z|, and in a power multiplied by
/// another value (|z|^(q−1)z·(1 + x): the product of the power's unbounded value must stay
/// unbounded).
#[test]
fn the_start_step_is_refused_where_a_factored_component_turns_back() {
    let q = ivf(1.5, 1.5);
    let power = toy_start_tape(50.0, 0.0, |z, _| Scalar::spow(z, &q));
    let abs = toy_start_tape(50.0, 0.0, |z, _| Real::abs(z));
    let product = toy_start_tape(50.0, 0.0, |z, x| {
        Scalar::spow(z, &q) * x.shift(&ivf(1.0, 1.0))
    });
    for (what, tape) in [("power", &power), ("|z|", &abs), ("product", &product)] {
        assert!(
            start_of(tape, 0.01).is_some(),
            "{what}: refused on δ = 0.01"
        );
        assert!(start_of(tape, 0.05).is_none(), "{what}: taken on δ = 0.05");
    }
}

/// The start step's roles: a component at 0 whose rate is 0 there is not factored (it does
/// not start with u), so a power of it has no expansion and the step is refused (ż = x: z
/// starts as −u²/2); and with every rate 0 at the start (v = 0) there is no variable at all.
#[test]
fn the_start_step_is_refused_without_a_certain_rate() {
    let q = ivf(1.5, 1.5);
    let tape = Tape::<Interval, 3>::record(|v: &[Rec<Interval>; 3]| {
        vec![
            v[2].clone(),
            v[0].clone(),
            -(Scalar::spow(&v[0], &q) + Scalar::spow(&v[1], &q)).scale(&ivf(0.5, 0.5)),
        ]
    });
    assert!(start_of(&tape, 0.005).is_none());
    let twin = toy_start_tape(0.0, 0.0, |z, _| Scalar::spow(z, &q));
    assert!(start_of(&twin, 0.005).is_some());
    let opts = SingularOptions::default();
    let st = SingularTape::of(&twin, &opts).unwrap();
    let basis = Basis::new(st.basis.gens(), opts.start_max_exp).unwrap();
    let rest = [ivf(0.0, 0.0), ivf(0.0, 0.0), ivf(0.0, 0.0)];
    assert!(start::start_point(&st.tape, &basis, &twin, 0.0, &rest, 0.005, &opts).is_none());
}
