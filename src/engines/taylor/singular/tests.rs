//! The singular step against a closed form: the Hertz oscillator ẋ = v, v̇ = −|x|^(p−1)x keeps
//! its energy E = v²/2 + |x|^(p+1)/(p+1) along every solution, and x passes through its branch
//! point 0. A step across x = 0 from a small box must end in a box whose energy enclosure holds
//! the energy of every corner of the start box (computed with MPFR at 200 bits): the image of
//! the box, not only of its centre.

use super::*;
use crate::arith::Scalar;
use crate::engines::taylor::rec::Rec;
use rug::Float;
use rug::ops::Pow;

fn hertz(p: &str) -> (Tape<Interval, 2>, Interval) {
    let q = Interval::parse_decimal(p).unwrap();
    let tape = Tape::<Interval, 2>::record(|v: &[Rec<Interval>; 2]| {
        vec![v[1].clone(), -Scalar::spow(&v[0], &q)]
    });
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

fn energy_iv(x: &[Interval; 2], q: Interval) -> Interval {
    let p1 = q + Interval::one();
    Real::apow(&x[0], &p1) / p1 + x[1] * x[1] / Interval::from_int(2)
}

fn check_crossing(p: &str, x0: f64, v0: f64, half: f64) {
    let (tape, q) = hertz(p);
    let opts = SingularOptions {
        max_exp: 6.0,
        iterations: 4,
        tighten: 2,
        ..SingularOptions::default()
    };
    let st = SingularTape::of(&tape, &opts).expect("constant exponents");
    let dual = tape.map(|c| Dual::constant(*c));
    let bx = [
        Interval::try_from((x0 - half, x0 + half)).unwrap(),
        Interval::try_from((v0 - half, v0 + half)).unwrap(),
    ];
    let out = crossing_step(&st, &tape, &dual, 0.0, &bx, None, 0, &opts)
        .unwrap_or_else(|| panic!("p = {p}: the crossing is refused"));
    // it crossed: x changed sign
    assert!(out.x1[0].sup() < 0.0, "p = {p}: {:?}", out.x1);
    let e1 = energy_iv(&out.x1, q);
    for (cx, cv) in [
        (bx[0].inf(), bx[1].inf()),
        (bx[0].inf(), bx[1].sup()),
        (bx[0].sup(), bx[1].inf()),
        (bx[0].sup(), bx[1].sup()),
    ] {
        let e = energy_mpfr(cx, cv, p);
        assert!(
            Float::with_val(200, e1.inf()) <= e && e <= Float::with_val(200, e1.sup()),
            "p = {p}: E(corner) = {e} outside {e1:?}"
        );
    }
    // and it is an enclosure of the image, not of everything: a few times the box's width
    assert!(e1.wid() < 20.0 * half, "p = {p}: {e1:?}");
}

/// A box thin in x and wide in v: over the step, x picks up ∫v, so the image of the box is
/// sheared (the Jacobian's off-diagonal τ). Each corner's own flow (a point step, which uses no
/// Jacobian) must end inside the box's image.
fn check_shear(p: &str) {
    let (tape, _) = hertz(p);
    let opts = SingularOptions::default();
    let st = SingularTape::of(&tape, &opts).unwrap();
    let dual = tape.map(|c| Dual::constant(*c));
    let bx = [
        Interval::try_from((2e-3, 2e-3)).unwrap(),
        Interval::try_from((-1.0 - 1e-8, -1.0 + 1e-8)).unwrap(),
    ];
    let out = crossing_step(&st, &tape, &dual, 0.0, &bx, None, 0, &opts).expect("crossed");
    let t1 = out.piece.t1();
    for v in [bx[1].inf(), bx[1].sup()] {
        let c = [bx[0], point(v)];
        let (_, z) = cross_point(&st, &tape, 0.0, &c, 0, &opts, Some(t1)).expect("point");
        for (i, (zi, xi)) in z.iter().zip(&out.x1).enumerate() {
            assert!(
                Interval::subset(*zi, *xi),
                "p = {p}, v0 = {v}: component {i}: {zi:?} not in {xi:?}"
            );
        }
    }
}

#[test]
fn the_image_of_a_sheared_box_holds_each_corners_flow() {
    for p in ["1.5", "2.28"] {
        check_shear(p);
    }
}

#[test]
fn hertz_crossings_keep_the_energy_of_every_corner() {
    for p in ["1.5", "1.27", "2.28", "3.14"] {
        check_crossing(p, 2e-3, -1.0, 1e-12);
        check_crossing(p, 5e-4, -0.7, 1e-9);
    }
}

#[test]
fn a_crossing_with_the_velocity_reaching_zero_is_refused() {
    // x near 0 but v = 0 there too (x does not cross: the expansion in x does not exist)
    let (tape, _) = hertz("1.5");
    let opts = SingularOptions::default();
    let st = SingularTape::of(&tape, &opts).unwrap();
    let dual = tape.map(|c| Dual::constant(*c));
    let bx = [
        Interval::try_from((1e-3, 1e-3)).unwrap(),
        Interval::try_from((-1e-6, 1e-6)).unwrap(),
    ];
    assert!(crossing_step(&st, &tape, &dual, 0.0, &bx, None, 0, &opts).is_none());
}

/// The Hertz oscillator with a twin: ẋ = v, ż = v, v̇ = −½|x|^(p−1)x − ½|z|^(p−1)z from
/// x = z = 0, v = −1 (z ≡ x: two components at the branch point at once, as at the models'
/// start; the force is half z's). E = v²/2 + |x|^(p+1)/(p+1) = 1/2 along the solution.
fn hertz_twin(p: &str) -> (Tape<Interval, 3>, Interval) {
    let q = Interval::parse_decimal(p).unwrap();
    let half = Interval::try_from((0.5, 0.5)).unwrap();
    let tape = Tape::<Interval, 3>::record(|v: &[Rec<Interval>; 3]| {
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
fn check_start(p: &str, delta: f64) -> [Interval; 3] {
    let (tape, q) = hertz_twin(p);
    let opts = SingularOptions::default();
    let st = SingularTape::of(&tape, &opts).expect("constant exponents");
    let basis = Basis::new(st.basis.gens(), opts.start_max_exp).unwrap();
    let x0 = [ZERO, ZERO, -ONE];
    let out = start::start_step(&st.tape, &basis, &tape, 0.0, &x0, delta, &opts)
        .unwrap_or_else(|| panic!("p = {p}: the start step is refused"));
    let x1 = out.x1;
    assert!(x1[0].sup() < 0.0 && x1[1].sup() < 0.0, "p = {p}: {x1:?}");
    let e1 = energy_iv(&[x1[0], x1[2]], q);
    let half = Interval::try_from((0.5, 0.5)).unwrap();
    assert!(
        half.subset(e1),
        "p = {p}, δ = {delta}: E = {e1:?} misses 1/2"
    );
    assert!(
        ZERO.subset(x1[1] - x1[0]),
        "p = {p}: z − x = {:?}",
        x1[1] - x1[0]
    );
    // an enclosure, not everything: a few ulps of 1/2 at the default δ (the remainder grows
    // like δ^M beyond it)
    let tight = if delta <= opts.start_delta {
        1e-14
    } else {
        1e-10
    };
    assert!(e1.wid() < tight, "p = {p}, δ = {delta}: {e1:?}");
    x1
}

#[test]
fn the_start_step_keeps_the_energy_of_the_hertz_oscillator() {
    for p in ["1.5", "1.27", "2.28", "3.14"] {
        for delta in [1e-3, 5e-3, 2e-2] {
            check_start(p, delta);
        }
    }
}

/// A pair whose second component is not a copy: ẋ = v, ż = v(1 + z)², v̇ = −½|x|^(p−1)x −
/// ½|z|^(p−1)z(1 + z)² from x = z = 0, v = −1. Then z = x/(1 − x) (dz/dx = (1 + z)²), so z's
/// W = 1/(1 + u) is not constant (x = −u), and E = v²/2 + (|x|^(p+1) + |z|^(p+1))/(2(p+1)) =
/// 1/2 (Ė = 0 term by term). The start step's box at t₁ must hold E = 1/2 and z(1 − x) − x = 0.
fn check_start_pair(p: &str, delta: f64) {
    let q = Interval::parse_decimal(p).unwrap();
    let half = Interval::try_from((0.5, 0.5)).unwrap();
    let tape = Tape::<Interval, 3>::record(|v: &[Rec<Interval>; 3]| {
        let one_z = v[1].shift(&Interval::one());
        let sq = one_z.clone() * one_z;
        vec![
            v[2].clone(),
            v[2].clone() * sq.clone(),
            -(Scalar::spow(&v[0], &q) + Scalar::spow(&v[1], &q) * sq).scale(&half),
        ]
    });
    let opts = SingularOptions::default();
    let st = SingularTape::of(&tape, &opts).expect("constant exponents");
    let basis = Basis::new(st.basis.gens(), opts.start_max_exp).unwrap();
    let x0 = [ZERO, ZERO, -ONE];
    let out = start::start_step(&st.tape, &basis, &tape, 0.0, &x0, delta, &opts)
        .unwrap_or_else(|| panic!("p = {p}: the start step is refused"));
    let [x, z, v] = out.x1;
    assert!(x.sup() < 0.0 && z.sup() < 0.0, "p = {p}: {:?}", out.x1);
    let p1 = q + ONE;
    let e1 = (Real::apow(&x, &p1) + Real::apow(&z, &p1)) / (p1 * Interval::from_int(2))
        + v * v / Interval::from_int(2);
    assert!(
        half.subset(e1),
        "p = {p}, δ = {delta}: E = {e1:?} misses 1/2"
    );
    let inv = z * (ONE - x) - x;
    assert!(
        ZERO.subset(inv),
        "p = {p}, δ = {delta}: z(1 − x) − x = {inv:?}"
    );
    let tight = if delta <= opts.start_delta {
        1e-13
    } else {
        1e-9
    };
    assert!(
        e1.wid() < tight && inv.wid() < tight,
        "p = {p}, δ = {delta}: {e1:?} {inv:?}"
    );
}

#[test]
fn the_start_step_keeps_the_invariants_of_a_coupled_pair() {
    for p in ["1.5", "1.27", "2.28", "3.14"] {
        for delta in [1e-3, 5e-3, 2e-2] {
            check_start_pair(p, delta);
        }
    }
}
