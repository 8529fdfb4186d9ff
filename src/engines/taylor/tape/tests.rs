use super::shortcuts::log_leads;
use super::*;
use crate::arith::Scalar;
use crate::arith::jet::series::Series;
use crate::models::{CollisionModel, Maxwell, ModelKind, NdParams, Shc};
use inari::Interval;

/// Coefficients by the slow route: Picard on truncated series, re-evaluating the model on
/// `Series` K times.
fn series_jet<M: CollisionModel<f64, N>, const N: usize>(
    m: &M,
    x0: [f64; N],
    order: usize,
) -> [Vec<f64>; N] {
    let mut x: [Vec<f64>; N] = std::array::from_fn(|i| {
        let mut v = vec![0.0; order + 1];
        v[0] = x0[i];
        v
    });
    for k in 0..order {
        let s: [Series<f64>; N] = std::array::from_fn(|i| Series::from_coefficients(x[i].clone()));
        let f = m.field(&s);
        for i in 0..N {
            x[i][k + 1] = f[i].c[k] / (k as f64 + 1.0);
        }
    }
    x
}

#[test]
fn entire_powers_expand_at_zero() {
    // s′ = 1, y′ = |s|^(q−1)s (q odd) or |s|^q (q even) from s = 0: y = t^(q+1)/(q+1). The
    // power's operand starts at 0, where the power recurrence does not exist: entire powers
    // must be expanded as products (they panicked for q ≥ 3, issue #12)
    let zero = Interval::try_from((0.0, 0.0)).unwrap();
    let one = Interval::try_from((1.0, 1.0)).unwrap();
    for q in [3_u32, 4, 5, 6, 10, 11, 50] {
        let qi = Interval::try_from((q as f64, q as f64)).unwrap();
        let signed = q % 2 == 1;
        let tape = Tape::<Interval, 2>::record(|v| {
            let p = if signed {
                Scalar::<Interval>::spow(&v[0], &qi)
            } else {
                Scalar::<Interval>::apow(&v[0], &qi)
            };
            vec![v[1].scale(&zero).shift(&one), p]
        });
        assert!(tape.switching().is_empty(), "q = {q}: an entire power");
        let order = 60;
        let mut ws = Workspace::default();
        let j = tape.jet(&[zero, zero], order, &mut ws).unwrap();
        for (k, c) in j[1].iter().enumerate() {
            let exact = if k == q as usize + 1 {
                1.0 / (q as f64 + 1.0)
            } else {
                0.0
            };
            assert!(
                c.inf() <= exact && exact <= c.sup() && c.wid() <= 1e-14,
                "q = {q}, k = {k}: {c:?} vs {exact}"
            );
        }
    }
}

#[test]
fn tape_jet_equals_series_jet() {
    let shc = Shc::<f64>::new(
        NdParams::parse(ModelKind::Shc, "1.43,-1.42,0.632,0.00715,1.31,1.27").unwrap(),
    );
    let tape = Tape::<f64, 3>::record(|v| shc.field(v).to_vec());
    assert_eq!(tape.switching(), &[0, 1, 2]);
    // |V| is a kink; X and Z are branch points of the real powers
    assert_eq!(tape.kinks(), &[2]);
    let x0 = [-0.3, -0.2, 0.4];
    let a = tape.jet(&x0, 12, &mut Workspace::default()).unwrap();
    let b = series_jet(&shc, x0, 12);
    for i in 0..3 {
        for k in 0..=12 {
            assert!(
                (a[i][k] - b[i][k]).abs() <= 1e-12 * (1.0 + b[i][k].abs()),
                "{i} {k}: {} {}",
                a[i][k],
                b[i][k]
            );
        }
    }
    let mx = Maxwell::<f64>::new(
        NdParams::parse(ModelKind::Maxwell, "0.44,-0.418,0.113,0.00785,1.27,3.14").unwrap(),
    );
    let tape = Tape::<f64, 4>::record(|v| mx.field(v).to_vec());
    assert_eq!(tape.switching(), &[1, 2, 3]);
    assert_eq!(tape.kinks(), &[3]);
    let x0 = [0.1, -0.3, -0.2, 0.4];
    let a = tape.jet(&x0, 10, &mut Workspace::default()).unwrap();
    let b = series_jet(&mx, x0, 10);
    for i in 0..4 {
        for k in 0..=10 {
            assert!(
                (a[i][k] - b[i][k]).abs() <= 1e-12 * (1.0 + b[i][k].abs()),
                "{i} {k}"
            );
        }
    }
}

/// The jets the engine runs on [`Ulp`](crate::arith::interval::ulp::Ulp) intervals enclose the same
/// coefficients as those on inari intervals (endpoints within one ulp; equal almost always),
/// and both enclose the f64 jet, at random thin points and small boxes of both models.
#[test]
fn ulp_jets_match_inari_jets() {
    use crate::arith::interval::ulp::Ulp;
    use inari::Interval;
    fn check<M, const N: usize>(m: &M, mf: &impl CollisionModel<f64, N>, seed: u64)
    where
        M: CollisionModel<Interval, N>,
    {
        let tape = Tape::<Interval, N>::record(|v| m.field(v).to_vec());
        let fast = tape.map(|c| Ulp::of(*c));
        let ftape = Tape::<f64, N>::record(|v| mf.field(v).to_vec());
        let mut r = crate::arith::interval::xorshift(seed);
        let mut next = move || (r() >> 11) as f64 / (1u64 << 53) as f64;
        let (mut equal, mut total) = (0, 0);
        for case in 0..200 {
            let x: [f64; N] = std::array::from_fn(|_| {
                let v = 0.05 + next();
                if next() < 0.5 { -v } else { v }
            });
            let r = if case % 2 == 0 { 0.0 } else { 1e-9 * next() };
            let xi: [Interval; N] = x.map(|v| Interval::try_from((v - r, v + r)).unwrap());
            let side = [0i8; N];
            let a = tape
                .jet_on(&xi, 16, &mut Workspace::default(), &side)
                .unwrap();
            let b = fast
                .jet_on(&xi.map(Ulp::of), 16, &mut Workspace::default(), &side)
                .unwrap();
            let f = ftape.jet(&x, 16, &mut Workspace::default()).unwrap();
            for i in 0..N {
                for k in 0..=16 {
                    let (ai, bi) = (a[i][k], b[i][k]);
                    total += 1;
                    if ai.inf() == bi.lo && ai.sup() == bi.hi {
                        equal += 1;
                    }
                    assert!(
                        bi.lo >= ai.inf().next_down() && bi.hi <= ai.sup().next_up(),
                        "x = {x:?} ± {r}, component {i}, order {k}: {ai:?} vs {bi:?}"
                    );
                    let tol = 1e-9 * (1.0 + f[i][k].abs());
                    assert!(
                        ai.inf() - tol <= f[i][k] && f[i][k] <= ai.sup() + tol,
                        "f64 coefficient {} outside {ai:?}",
                        f[i][k]
                    );
                }
            }
        }
        assert!(
            equal * 10 >= total * 9,
            "only {equal} of {total} endpoints equal"
        );
    }
    let shc = "1.43,-1.42,0.632,0.00715,1.31,1.27";
    check(
        &Shc::new(NdParams::<Interval>::parse(ModelKind::Shc, shc).unwrap()),
        &Shc::new(NdParams::<f64>::parse(ModelKind::Shc, shc).unwrap()),
        7,
    );
    let mx = "0.44,-0.418,0.113,0.00785,1.27,3.14";
    check(
        &Maxwell::new(NdParams::<Interval>::parse(ModelKind::Maxwell, mx).unwrap()),
        &Maxwell::new(NdParams::<f64>::parse(ModelKind::Maxwell, mx).unwrap()),
        11,
    );
}

/// Points of every sign pattern of the state (components ±[0.05, 1.05]) by a xorshift.
fn sign_pattern_points<const N: usize>(seed: u64, n: usize) -> Vec<[f64; N]> {
    let mut r = crate::arith::interval::xorshift(seed);
    let mut next = move || (r() >> 11) as f64 / (1u64 << 53) as f64;
    (0..n)
        .map(|case| {
            std::array::from_fn(|i| {
                let v = 0.05 + next();
                if (case >> i) & 1 == 1 { -v } else { v }
            })
        })
        .collect()
}

/// The shortcuts change how a jet is computed, not what it encloses. On both models'
/// tapes (recorded and fused, as the engine runs them) at points of every sign pattern,
/// to order 16: the jets with the shortcuts contain the 256-bit jets of the same tape
/// without them (intervals ~1e-70 wide, compared exactly), and the sign copies alone give
/// the jets of the sums bit for bit (a change of sign is exact) where the fused forms sum
/// the copy's term on its own ([`Tape::without_merges`]). Maxwell's tape has two integral
/// powers (|Y|^(p−1)Y, |Z|^(p−1)Z) and one sign copy, SHC's one sign copy; the fused
/// forms merge one pair of terms in each.
#[test]
fn shortcut_jets_enclose_the_jets_of_the_sums() {
    use crate::arith::mpfr::Mpi;
    type M = Mpi<256>;
    fn check<const N: usize>(
        tape: &Tape<Interval, N>,
        reference: &Tape<M, N>,
        shortcuts: (usize, usize),
        seed: u64,
    ) {
        assert_eq!(tape.shortcuts(), shortcuts);
        // (tape, merged pairs: the recorded tape has no fused forms)
        for (t, merges) in [
            (tape.clone(), 0),
            (tape.fused(Rounding::Each), 1),
            (tape.fused(Rounding::Once), 1),
        ] {
            assert_eq!(t.shortcuts(), shortcuts, "fused");
            assert_eq!(t.merges(), merges, "merged pairs");
            let sums = t.without_shortcuts(false, true);
            let copies = t.without_merges();
            let side = [0i8; N];
            for x in sign_pattern_points::<N>(seed, 2 << N) {
                let xi = x.map(|v| Interval::try_from((v, v)).unwrap());
                let a = t.jet_on(&xi, 16, &mut Workspace::default(), &side).unwrap();
                let c = copies
                    .jet_on(&xi, 16, &mut Workspace::default(), &side)
                    .unwrap();
                let b = sums
                    .jet_on(&xi, 16, &mut Workspace::default(), &side)
                    .unwrap();
                let r = reference
                    .jet_on(
                        &x.map(M::from_exact_f64),
                        16,
                        &mut Workspace::default(),
                        &side,
                    )
                    .unwrap();
                for i in 0..N {
                    for k in 0..=16 {
                        assert!(
                            c[i][k].inf() == b[i][k].inf() && c[i][k].sup() == b[i][k].sup(),
                            "sign copy at {x:?}, {i}, order {k}: {:?} vs {:?}",
                            c[i][k],
                            b[i][k]
                        );
                        for (what, j) in [("merged", &a), ("copies", &c)] {
                            assert!(
                                r[i][k].subset(&M::from_interval(j[i][k])),
                                "{what}: x = {x:?}, component {i}, order {k}: {:?} not in \
                                 {:?}",
                                r[i][k].to_interval(),
                                j[i][k]
                            );
                        }
                    }
                }
            }
        }
    }
    let (shc, mx) = (
        "1.43,-1.42,0.632,0.00715,1.31,1.27",
        "0.44,-0.418,0.113,0.00785,1.27,3.14",
    );
    let m = Shc::new(NdParams::<Interval>::parse(ModelKind::Shc, shc).unwrap());
    let mm = Shc::new(NdParams::<M>::parse(ModelKind::Shc, shc).unwrap());
    let tape = Tape::<Interval, 3>::record(|v| m.field(v).to_vec());
    let reference = Tape::<M, 3>::record(|v| mm.field(v).to_vec()).without_shortcuts(true, true);
    check(&tape, &reference, (0, 1), 5);
    let m = Maxwell::new(NdParams::<Interval>::parse(ModelKind::Maxwell, mx).unwrap());
    let mm = Maxwell::new(NdParams::<M>::parse(ModelKind::Maxwell, mx).unwrap());
    let tape = Tape::<Interval, 4>::record(|v| m.field(v).to_vec());
    let reference = Tape::<M, 4>::record(|v| mm.field(v).to_vec()).without_shortcuts(true, true);
    check(&tape, &reference, (2, 1), 9);
}

/// A merged pair of terms ([`lin_merges`]) over a box: the hysteretic rate's
/// β|V||Z|^(n−1)Z + γV|Z|^n of SHC DSS (β + γ = 0.01) on two a-priori boxes of its flow
/// (v0 = 1, 2; 2–15 % wide): in loading (V, Z < 0: the terms cancel) and in unloading
/// (V > 0, Z < 0: they add). The order-16 jet with the pair merged contains the 256-bit jets at 40
/// points of the box (the end corners included), and in loading its coefficient of Ż is
/// at least 10⁴ times narrower than with the terms summed one by one (measured: 6.7e6
/// times, 1.9e3 → 2.8e-4); in unloading, where nothing cancels, as wide (to 1 %).
#[test]
fn merged_pairs_spare_the_cancellation_over_a_box() {
    use crate::arith::mpfr::Mpi;
    type M = Mpi<256>;
    let shc = "1.43,-1.42,0.632,0.00715,1.31,1.27";
    let m = Shc::new(NdParams::<Interval>::parse(ModelKind::Shc, shc).unwrap());
    let mm = Shc::new(NdParams::<M>::parse(ModelKind::Shc, shc).unwrap());
    let reference = Tape::<M, 3>::record(|v| mm.field(v).to_vec())
        .without_shortcuts(true, true)
        .fused(Rounding::Each)
        .without_merges();
    let tape = Tape::<Interval, 3>::record(|v| m.field(v).to_vec()).fused(Rounding::Each);
    assert_eq!(tape.merges(), 1);
    let sums = tape.without_merges();
    let mut next = crate::arith::interval::xorshift(0x7a3c_91e5_0d42_b861);
    let loading = [(-0.9338, -0.8820), (-0.9301, -0.8787), (-0.5788, -0.4976)];
    let unloading = [(-0.949, -0.929), (-0.490, -0.423), (0.431, 0.463)];
    for (bx, min_gain) in [(loading, 1e4), (unloading, 1.0 / 1.01)] {
        let y = bx.map(|(a, b)| Interval::try_from((a, b)).unwrap());
        let side = [0i8; 3];
        let a = tape
            .jet_on(&y, 16, &mut Workspace::default(), &side)
            .unwrap();
        let b = sums
            .jet_on(&y, 16, &mut Workspace::default(), &side)
            .unwrap();
        let gain = b[1][16].wid() / a[1][16].wid();
        assert!(
            gain >= min_gain,
            "{bx:?}: {:e} vs {:e}",
            a[1][16].wid(),
            b[1][16].wid()
        );
        for case in 0..40 {
            let x: [f64; 3] = std::array::from_fn(|i| {
                let (lo, hi) = bx[i];
                match case {
                    0 => lo,
                    1 => hi,
                    _ => lo + (hi - lo) * ((next() >> 11) as f64 / (1u64 << 53) as f64),
                }
            });
            let r = reference
                .jet_on(
                    &x.map(M::from_exact_f64),
                    16,
                    &mut Workspace::default(),
                    &side,
                )
                .unwrap();
            for i in 0..3 {
                for k in 0..=16 {
                    assert!(
                        r[i][k].subset(&M::from_interval(a[i][k])),
                        "x = {x:?}, component {i}, order {k}: {:?} not in {:?}",
                        r[i][k].to_interval(),
                        a[i][k]
                    );
                }
            }
        }
    }
}

/// A pair is merged only where its two products are one function up to sign — not where
/// the common subexpressions made one node of operations that only have equal enclosures
/// (found by an adversarial review): (A) exponents n, p ∈ [1.1, 1.3] recorded apart (the
/// true n = 1.1, p = 1.3), (B) x = κ₁v and κ₂v with κ₁, κ₂ ∈ [0.9, 1.1] (true 0.9 and
/// 1.1). There the merged form would be 10–20 times too narrow (order 1: [0.0041, 0.0047]
/// against the true 0.0904); now nothing merges and every jet contains the 256-bit jet of
/// the truth. One range recorded by `spow_apow` (one constant: one exponent) merges, and
/// contains the truth for q at either end of the range. (C) At 256 bits, exponents 1.31 and
/// 1.31 + 2⁻⁶⁰ (equal f64 bounds) are two nodes, not one power and its Twin as before,
/// whose order-1 coefficient missed the exact value.
#[test]
fn merged_pairs_need_one_origin() {
    use crate::arith::mpfr::Mpi;
    type M = Mpi<256>;
    let iv = |a: f64, b: f64| Interval::try_from((a, b)).unwrap();
    let (b, g) = (
        Interval::parse_decimal("1.43").unwrap(),
        Interval::parse_decimal("-1.42").unwrap(),
    );
    let (bm, gm) = (
        M::parse_decimal("1.43").unwrap(),
        M::parse_decimal("-1.42").unwrap(),
    );
    // β·|z|^(n−1)z·|x₁| + γ·|z|^p·x₂ with x₁ = κ₁v, x₂ = κ₂v (κ = None: v itself), the
    // powers recorded apart or (`pair`) by one spow_apow of n
    fn field<R: Real>(
        v: &[Rec<R>; 2],
        (n, p): (&R, &R),
        k: Option<(&R, &R)>,
        (b, g): (&R, &R),
        pair: bool,
    ) -> Vec<Rec<R>> {
        let (x1, x2) = match k {
            Some((k1, k2)) => (v[1].scale(k1), v[1].scale(k2)),
            None => (v[1].clone(), v[1].clone()),
        };
        let (s, a) = if pair {
            Scalar::<R>::spow_apow(&v[0], n)
        } else {
            (Scalar::<R>::spow(&v[0], n), Scalar::<R>::apow(&v[0], p))
        };
        let rate = (s * Real::abs(&x1)).scale(b) + (a * x2).scale(g);
        vec![rate, -v[0].clone()]
    }
    let check = |tape: &Tape<Interval, 2>, truth: &Tape<M, 2>, merges: usize, what: &str| {
        let truth = truth.without_shortcuts(true, true);
        for rounding in [Rounding::Each, Rounding::Once] {
            let t = tape.fused(rounding);
            assert_eq!(t.merges(), merges, "{what}");
            for x in sign_pattern_points::<2>(31, 8) {
                let a = t
                    .jet(&x.map(|c| iv(c, c)), 6, &mut Workspace::default())
                    .unwrap();
                let r = truth
                    .jet(&x.map(M::from_exact_f64), 6, &mut Workspace::default())
                    .unwrap();
                for i in 0..2 {
                    for k in 0..=6 {
                        assert!(
                            r[i][k].subset(&M::from_interval(a[i][k])),
                            "{what}, {rounding:?}: x = {x:?}, {i}, order {k}"
                        );
                    }
                }
            }
        }
    };
    let (r1, r2) = (iv(1.1, 1.3), iv(1.1, 1.3));
    let (lo, hi) = (
        M::parse_decimal("1.1").unwrap(),
        M::parse_decimal("1.3").unwrap(),
    );
    // (A)
    let tape = Tape::<Interval, 2>::record(|v| field(v, (&r1, &r2), None, (&b, &g), false));
    let truth = Tape::<M, 2>::record(|v| field(v, (&lo, &hi), None, (&bm, &gm), false));
    check(&tape, &truth, 0, "exponents apart");
    // one constant: merged, and the truth for either end of the range inside
    let tape = Tape::<Interval, 2>::record(|v| field(v, (&r1, &r1), None, (&b, &g), true));
    for q in [&lo, &hi] {
        let truth = Tape::<M, 2>::record(|v| field(v, (q, q), None, (&bm, &gm), true));
        check(&tape, &truth, 1, "one exponent");
    }
    // (B)
    let q = Interval::parse_decimal("1.31").unwrap();
    let qm = M::parse_decimal("1.31").unwrap();
    let (k1, k2) = (iv(0.9, 1.1), iv(0.9, 1.1));
    let (k1m, k2m) = (
        M::parse_decimal("0.9").unwrap(),
        M::parse_decimal("1.1").unwrap(),
    );
    let tape =
        Tape::<Interval, 2>::record(|v| field(v, (&q, &q), Some((&k1, &k2)), (&b, &g), true));
    let truth =
        Tape::<M, 2>::record(|v| field(v, (&qm, &qm), Some((&k1m, &k2m)), (&bm, &gm), true));
    check(&tape, &truth, 0, "κ₁, κ₂ apart");
    // (C) at 256 bits
    let q2 = qm.clone() + M::from_exact_f64(2f64.powi(-60));
    assert_eq!((q2.lo(), q2.hi()), (qm.lo(), qm.hi()));
    let tape = Tape::<M, 2>::record(|v| field(v, (&qm, &q2), None, (&bm, &gm), false));
    assert_eq!(tape.shortcuts(), (0, 0), "1.31 and 1.31 + 2⁻⁶⁰ at 256 bits");
    assert!(!tape.ops().iter().any(|op| matches!(op, Op::Twin(..))));
    let z = [M::from_exact_f64(0.5), M::from_exact_f64(1.0)];
    let exact = Real::spow(&z[0], &qm) * bm.clone() + Real::apow(&z[0], &q2) * gm.clone();
    for t in [tape.clone(), tape.fused(Rounding::Each)] {
        let a = t.jet(&z, 2, &mut Workspace::default()).unwrap();
        assert!(exact.subset(&a[0][1]), "order 1 at 256 bits");
    }
}

/// A power is taken as the integral of a product only where the product is |w|^(q′)·ẇ
/// with q′ ⊇ q − 1 and ẇ the field's own component: y′ = w, w′ = −|y|^(q−1)y − c·B with
/// B = |y|^(q′)·w (q′ = q − 1: the integral; q′ = q − 1/2, B = |y|^(q−1)·y or ·v: not), and
/// the jets enclose the 256-bit jets of the sums either way (a wrongly taken integral
/// would not: with q′ = q − 1/2 the coefficients differ from order 2 on).
#[test]
fn integral_powers_only_where_the_product_is_the_derivative() {
    use crate::arith::mpfr::Mpi;
    type M = Mpi<256>;
    fn toy<R: Real>(shift: &str, partner: usize) -> Tape<R, 3> {
        let q = R::parse_decimal("2.3").unwrap();
        let qb = q.clone() - R::parse_decimal(shift).unwrap();
        let c = R::parse_decimal("0.7").unwrap();
        let one = R::one();
        Tape::<R, 3>::record(|v| {
            let u = Scalar::<R>::spow(&v[0], &q);
            let b = Scalar::<R>::apow(&v[0], &qb) * v[partner].clone();
            vec![v[1].clone(), -u - b.scale(&c), v[2].scale(&one)]
        })
    }
    for (shift, partner, integrals) in [("1", 1, 1), ("0.5", 1, 0), ("1", 2, 0), ("1", 0, 0)] {
        let tape = toy::<Interval>(shift, partner);
        assert_eq!(
            tape.shortcuts().0,
            integrals,
            "q′ = q − {shift}, partner component {partner}"
        );
        let reference = toy::<M>(shift, partner).without_shortcuts(true, true);
        for x in sign_pattern_points::<3>(3, 16) {
            let xi = x.map(|v| Interval::try_from((v, v)).unwrap());
            let a = tape.jet(&xi, 12, &mut Workspace::default()).unwrap();
            let r = reference
                .jet(&x.map(M::from_exact_f64), 12, &mut Workspace::default())
                .unwrap();
            for i in 0..3 {
                for k in 0..=12 {
                    assert!(
                        r[i][k].subset(&M::from_interval(a[i][k])),
                        "q′ = q − {shift}, x = {x:?}, component {i}, order {k}"
                    );
                }
            }
        }
    }
    // the check that guards it: with q′ = q − 1/2 taken as an integral (the containment
    // test skipped), the jets exclude the true coefficients
    let mut wrong = toy::<Interval>("0.5", 1);
    let s = wrong
        .ops
        .iter()
        .position(|op| matches!(op, Op::Spow(..)))
        .unwrap();
    let m = wrong
        .ops
        .iter()
        .position(|op| matches!(op, Op::Mul(..)))
        .unwrap();
    wrong.integral_of[s] = Some(m);
    wrong.log_lead = log_leads(&wrong.ops, &wrong.consts, &wrong.tconst, &wrong.integral_of);
    let reference = toy::<M>("0.5", 1).without_shortcuts(true, true);
    let x = [0.4, -0.3, 0.2];
    let a = wrong
        .jet(
            &x.map(|v| Interval::try_from((v, v)).unwrap()),
            12,
            &mut Workspace::default(),
        )
        .unwrap();
    let r = reference
        .jet(&x.map(M::from_exact_f64), 12, &mut Workspace::default())
        .unwrap();
    assert!(
        (0..3).any(|i| (0..=12).any(|k| !r[i][k].subset(&M::from_interval(a[i][k])))),
        "a wrong integral went unnoticed"
    );
}

/// The shortcuts' preconditions, each on a field where it decides (found by an adversarial
/// review): a power a Twin reads (its series is needed) is no integral; a |·| of a
/// parameter (its sign is never set by a jet) makes no sign copy; P·|x| and P′·|x| copy
/// with the power's sign alone; at 256 bits an exponent q′ = (q − 1) + 10⁻⁶⁰, whose f64
/// bounds are those of q − 1, is no integral. Every jet contains the 256-bit jet of the
/// sums (exactly), and the copies give the sums' jets bit for bit. Exponent 1: x·|y| and
/// |x|·y copy each other and merge in a fused form, while 1 and 1 + 2⁻³⁰ do neither.
#[test]
fn shortcuts_are_not_taken_where_they_do_not_hold() {
    use crate::arith::mpfr::Mpi;
    type M = Mpi<256>;
    fn twin<R: Real>() -> Tape<R, 2> {
        let q = R::parse_decimal("2.3").unwrap();
        let qb = q.clone() - R::one();
        let c = R::parse_decimal("0.7").unwrap();
        Tape::<R, 2>::record(|v| {
            let (u, ua) = Scalar::<R>::spow_apow(&v[0], &q);
            let b = Scalar::<R>::apow(&v[0], &qb) * v[1].clone();
            vec![v[1].clone(), -u - ua - b.scale(&c)]
        })
    }
    fn abs_pair<R: Real>(param: Option<R>) -> Tape<R, 2> {
        let q = R::parse_decimal("1.5").unwrap();
        let two = R::from_int(2);
        Tape::<R, 2>::record_with([None, param], |v| {
            let (p, pa) = Scalar::<R>::spow_apow(&v[0], &q);
            let a = p * Real::abs(&v[1]);
            let b = pa * Real::abs(&v[1]);
            vec![a + b.scale(&two), Rec::constant(R::zero())]
        })
    }
    fn enclosed<const N: usize>(
        tape: &Tape<Interval, N>,
        reference: &Tape<M, N>,
        points: &[[f64; N]],
        what: &str,
    ) {
        enclosed_as(tape, reference, points, what, true)
    }
    // `bitwise`: the copies are the sums' jets bit for bit (not for exponent 1, where the
    // sums take |x| by the power recurrence and the copy ±x·|y| exactly)
    fn enclosed_as<const N: usize>(
        tape: &Tape<Interval, N>,
        reference: &Tape<M, N>,
        points: &[[f64; N]],
        what: &str,
        bitwise: bool,
    ) {
        let sums = tape.without_shortcuts(false, true);
        let reference = reference.without_shortcuts(true, true);
        for x in points {
            let xi = x.map(|v| Interval::try_from((v, v)).unwrap());
            let a = tape.jet(&xi, 10, &mut Workspace::default()).unwrap();
            let b = sums.jet(&xi, 10, &mut Workspace::default()).unwrap();
            let r = reference
                .jet(&x.map(M::from_exact_f64), 10, &mut Workspace::default())
                .unwrap();
            for i in 0..N {
                for k in 0..=10 {
                    assert!(
                        !bitwise
                            || (a[i][k].inf() == b[i][k].inf() && a[i][k].sup() == b[i][k].sup()),
                        "{what}: a copy differs at {x:?}, {i}, {k}"
                    );
                    assert!(
                        r[i][k].subset(&M::from_interval(a[i][k])),
                        "{what}: x = {x:?}, component {i}, order {k}"
                    );
                }
            }
        }
    }
    let points = sign_pattern_points::<2>(13, 8);
    let tape = twin::<Interval>();
    assert_eq!(tape.shortcuts(), (0, 0), "a power its twin reads");
    enclosed(&tape, &twin::<M>(), &points, "twin");
    let tape = abs_pair::<Interval>(None);
    assert_eq!(tape.shortcuts(), (0, 1), "P·|x| and P′·|x|");
    enclosed(&tape, &abs_pair::<M>(None), &points, "P·|x|");
    for p in [-1.0, 0.5] {
        let tape = abs_pair::<Interval>(Some(Interval::try_from((p, p)).unwrap()));
        assert_eq!(tape.shortcuts(), (0, 0), "|·| of a parameter");
        let xs: Vec<[f64; 2]> = points.iter().map(|x| [x[0], p]).collect();
        enclosed(
            &tape,
            &abs_pair::<M>(Some(M::from_exact_f64(p))),
            &xs,
            "|parameter|",
        );
    }
    // at 256 bits: q′ a hair above q − 1
    let q = M::parse_decimal("2.3").unwrap();
    let qb = q.clone() - M::one() + M::parse_decimal("1e-60").unwrap();
    assert_eq!(qb.lo(), (q.clone() - M::one()).lo());
    assert_eq!(qb.hi(), (q.clone() - M::one()).hi());
    let c = M::parse_decimal("0.7").unwrap();
    let rec = || {
        Tape::<M, 2>::record(|v| {
            let u = Scalar::<M>::spow(&v[0], &q);
            let b = Scalar::<M>::apow(&v[0], &qb) * v[1].clone();
            vec![v[1].clone(), -u - b.scale(&c)]
        })
    };
    assert_eq!(rec().shortcuts(), (0, 0), "q′ ⊉ q − 1 at 256 bits");
    let x = [M::from_exact_f64(0.4), M::from_exact_f64(-0.3)];
    let a = rec().jet(&x, 8, &mut Workspace::default()).unwrap();
    let r = rec()
        .without_shortcuts(true, true)
        .jet(&x, 8, &mut Workspace::default())
        .unwrap();
    assert!((0..2).all(|i| (0..=8).all(|k| r[i][k].subset(&a[i][k]))));
    // exponent 1 (SHC DSA's n = 1): x·|y| and |x|·y are copies (|x|⁰x = x holds no sign,
    // |x| does), merged in the fused form; a hair off (q′ = 1 + 2⁻³⁰) they are not
    // (`swap`: |x|·y recorded first, so that the copy's power x holds no sign)
    fn unit_pair<R: Real>(q2: &R, swap: bool) -> Tape<R, 2> {
        let one = R::one();
        let (b, g) = (
            R::parse_decimal("0.63").unwrap(),
            R::parse_decimal("-0.611").unwrap(),
        );
        Tape::<R, 2>::record(|v| {
            let pair = |first: bool| {
                if first {
                    Scalar::<R>::spow(&v[0], &one) * Real::abs(&v[1])
                } else {
                    Scalar::<R>::apow(&v[0], q2) * v[1].clone()
                }
            };
            let (p, pa) = if swap {
                let pa = pair(false);
                (pair(true), pa)
            } else {
                (pair(true), pair(false))
            };
            vec![v[1].clone() - p.scale(&b) - pa.scale(&g), -v[0].clone()]
        })
    }
    for swap in [false, true] {
        let tape = unit_pair::<Interval>(&Interval::one(), swap);
        assert_eq!(tape.shortcuts(), (0, 1), "x·|y| and |x|·y");
        enclosed_as(
            &tape,
            &unit_pair::<M>(&M::one(), swap),
            &points,
            "exponent 1",
            false,
        );
        let fused = tape.fused(Rounding::Each);
        assert_eq!(fused.merges(), 1, "x·|y| and |x|·y in one form");
        let reference = unit_pair::<M>(&M::one(), swap).without_shortcuts(true, true);
        for x in &points {
            let a = fused
                .jet(
                    &x.map(|v| Interval::try_from((v, v)).unwrap()),
                    10,
                    &mut Workspace::default(),
                )
                .unwrap();
            let r = reference
                .jet(&x.map(M::from_exact_f64), 10, &mut Workspace::default())
                .unwrap();
            assert!(
                (0..2).all(|i| (0..=10).all(|k| r[i][k].subset(&M::from_interval(a[i][k])))),
                "merged at {x:?}"
            );
        }
    }
    let off = 1.0 + 2f64.powi(-30);
    let tape = unit_pair::<Interval>(&Interval::try_from((off, off)).unwrap(), false);
    assert_eq!(tape.shortcuts(), (0, 0), "exponents 1 and 1 + 2⁻³⁰");
    assert_eq!(tape.fused(Rounding::Each).merges(), 0);
    enclosed(
        &tape,
        &unit_pair::<M>(&M::from_exact_f64(off), false),
        &points,
        "exponent 1 + 2⁻³⁰",
    );
}

/// The extra outputs computed alone (only the nodes they need) are the full evaluation's,
/// bit for bit, on the engine's tapes of both models (the field, then F and V) and their
/// fused forms, over points and boxes of each sign pattern; the SHC tape skips nodes.
#[test]
fn extra_outputs_alone_equal_the_full_evaluation() {
    fn check<M: CollisionModel<Interval, N>, const N: usize>(m: &M) -> usize {
        let tape = Tape::<Interval, N>::record(|v| {
            let mut o = m.field(v).to_vec();
            o.push(m.force(v));
            o.push(m.velocity(v));
            o
        });
        let mut next = crate::arith::interval::xorshift(0x2545_f491_4f6c_dd1d_u64);
        let mut unit = move || (next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        let mut checked = 0;
        for t in [
            tape.clone(),
            tape.fused(Rounding::Each),
            tape.fused(Rounding::Once),
        ] {
            for _ in 0..300 {
                let x: [Interval; N] = std::array::from_fn(|_| {
                    let (a, w) = (unit() * 2.0, unit().abs() * [0.0, 1e-9, 0.3][checked % 3]);
                    Interval::try_from((a, a + w)).unwrap()
                });
                let full = t.eval(&x);
                let extra = t.eval_extra(&x);
                assert_eq!(extra.len(), 2);
                for (a, b) in full[N..].iter().zip(&extra) {
                    assert!(
                        a.inf().to_bits() == b.inf().to_bits()
                            && a.sup().to_bits() == b.sup().to_bits()
                            || (a.is_empty() && b.is_empty()),
                        "{x:?}: {a:?} vs {b:?}"
                    );
                }
                checked += 1;
            }
        }
        tape.eval_extra(&std::array::from_fn(|_| {
            Interval::try_from((0.5, 0.5)).unwrap()
        }));
        tape.extra_needed
            .get()
            .unwrap()
            .iter()
            .filter(|&&n| !n)
            .count()
    }
    let shc = "1.43,-1.42,0.632,0.00715,1.31,1.27";
    let skipped = check(&Shc::new(
        NdParams::<Interval>::parse(ModelKind::Shc, shc).unwrap(),
    ));
    assert!(
        skipped > 0,
        "the SHC scan skips the hysteretic rate's nodes"
    );
    let mx = "0.44,-0.418,0.113,0.00785,1.27,3.14";
    check(&Maxwell::new(
        NdParams::<Interval>::parse(ModelKind::Maxwell, mx).unwrap(),
    ));
}

/// Asserts that the jets of `tape` to `order` over each box (a point where lo = hi) contain
/// the 256-bit jets of `reference` (compared exactly) at the box's two end corners and at
/// `samples` points drawn in it.
fn jets_contain_the_reference<const N: usize>(
    tape: &Tape<Interval, N>,
    reference: &Tape<crate::arith::mpfr::Mpi<256>, N>,
    boxes: &[[(f64, f64); N]],
    order: usize,
    samples: usize,
    what: &str,
) {
    use crate::arith::mpfr::Mpi;
    let mut r = crate::arith::interval::xorshift(0x243f_6a88_85a3_08d3);
    let mut next = move || (r() >> 11) as f64 / (1u64 << 53) as f64;
    for bx in boxes {
        let y = bx.map(|(a, b)| Interval::try_from((a, b)).unwrap());
        let a = tape.jet(&y, order, &mut Workspace::default()).unwrap();
        let thin = bx.iter().all(|(lo, hi)| lo == hi);
        for case in 0..if thin { 1 } else { 2 + samples } {
            let x: [f64; N] = std::array::from_fn(|i| {
                let (lo, hi) = bx[i];
                match case {
                    0 => lo,
                    1 => hi,
                    _ => lo + (hi - lo) * next(),
                }
            });
            let e = reference
                .jet(
                    &x.map(Mpi::<256>::from_exact_f64),
                    order,
                    &mut Workspace::default(),
                )
                .unwrap();
            for i in 0..N {
                for k in 0..=order {
                    assert!(
                        e[i][k].subset(&Mpi::<256>::from_interval(a[i][k])),
                        "{what}: box {bx:?}, x = {x:?}, component {i}, order {k}: {:?} not \
                         in {:?}",
                        e[i][k].to_interval(),
                        a[i][k]
                    );
                }
            }
        }
    }
}

/// The points of [`sign_pattern_points`] as thin boxes, and boxes around each of
/// relative width `rel`.
fn points_and_boxes<const N: usize>(seed: u64, rel: f64) -> Vec<[(f64, f64); N]> {
    let points = sign_pattern_points::<N>(seed, 2 << N);
    let thin = points.iter().map(|x| x.map(|v| (v, v)));
    let wide = points.iter().map(|x| {
        x.map(|v| {
            let d = v.abs() * rel;
            (v - d, v + d)
        })
    });
    thin.chain(wide).collect()
}

/// One fused form that sums a product and two sign copies of it merges one pair, and each
/// term at most once ([`lin_merges`]): z′ = c₁·P + c₂·P′ + c₃·P″ with P = |z|^(q−1)z·x,
/// P′ = |z|^q·x = s_z·P and P″ = |z|^q·|x| = s_z·s_x·P (the powers by one spow_apow,
/// recorded in that order), x′ = −z; the three terms summed in each of the six orders, and
/// P twice (P, P′, P, P″: two pairs, each P in one). The tapes fused both ways contain the
/// 256-bit jets of the sums at points of every sign pattern and over boxes around them.
/// Pairing a term of P twice dropped the second copy's term from the jet.
#[test]
fn a_product_and_two_sign_copies_merge_one_pair() {
    use crate::arith::mpfr::Mpi;
    type M = Mpi<256>;
    fn field<R: Real>(v: &[Rec<R>; 2], order: &[usize]) -> Vec<Rec<R>> {
        let q = R::parse_decimal("1.31").unwrap();
        let c = ["1.43", "-1.42", "0.37", "-0.55"].map(|c| R::parse_decimal(c).unwrap());
        let (s, a) = Scalar::<R>::spow_apow(&v[0], &q);
        let p = [
            s * v[1].clone(),
            a.clone() * v[1].clone(),
            a * Real::abs(&v[1]),
        ];
        let rate = order
            .iter()
            .zip(&c)
            .map(|(&j, c)| p[j].scale(c))
            .reduce(|a, b| a + b)
            .unwrap();
        vec![rate, -v[0].clone()]
    }
    let boxes = points_and_boxes::<2>(41, 0.02);
    let orders: [&[usize]; 7] = [
        &[0, 1, 2],
        &[0, 2, 1],
        &[1, 0, 2],
        &[1, 2, 0],
        &[2, 0, 1],
        &[2, 1, 0],
        &[0, 1, 0, 2],
    ];
    for order in orders {
        let tape = Tape::<Interval, 2>::record(|v| field(v, order));
        let reference = Tape::<M, 2>::record(|v| field(v, order)).without_shortcuts(true, true);
        for rounding in [Rounding::Each, Rounding::Once] {
            let t = tape.fused(rounding);
            let what = format!("{order:?}, {rounding:?}");
            jets_contain_the_reference(&t, &reference, &boxes, 8, 6, &what);
            // the shape: one form of all the terms, two copies, one pair per copy of P
            assert_eq!(t.lins.len(), 1, "{what}: one form");
            assert_eq!(t.lins[0].terms.len(), order.len(), "{what}: its terms");
            assert_eq!(t.shortcuts(), (0, 2), "{what}: P′ and P″ copies of P");
            assert_eq!(t.merges(), order.len() - 2, "{what}: merged pairs");
        }
    }
}

/// A product is a sign copy of another only where their other factors are one x (x or
/// |x|; [`sign_copies`]): with z′ = c₁·|z|^(q−1)z·A + c₂·|z|^q·B, x′ = −z, y′ = z − y/2,
/// the pairs (A, B) = (x, x), (x, |x|), (|x|, x), (|x|, |x|) are copies (and merge in the
/// fused form), the same with y for B are not. Every tape, recorded and fused, contains
/// the 256-bit jets of the sums at points of every sign pattern and over boxes around
/// them. Taken as a copy, |z|^q·y had the series of ±|z|^(q−1)z·x.
#[test]
fn sign_copies_need_one_other_factor() {
    use crate::arith::mpfr::Mpi;
    type M = Mpi<256>;
    fn field<R: Real>(v: &[Rec<R>; 3], (abs_a, abs_b): (bool, bool), b: usize) -> Vec<Rec<R>> {
        let q = R::parse_decimal("1.31").unwrap();
        let (c1, c2) = (
            R::parse_decimal("1.43").unwrap(),
            R::parse_decimal("-1.42").unwrap(),
        );
        let factor = |n: usize, abs: bool| {
            if abs { Real::abs(&v[n]) } else { v[n].clone() }
        };
        let (s, a) = Scalar::<R>::spow_apow(&v[0], &q);
        let rate = (s * factor(1, abs_a)).scale(&c1) + (a * factor(b, abs_b)).scale(&c2);
        let half = R::parse_decimal("0.5").unwrap();
        vec![rate, -v[0].clone(), v[0].clone() - v[2].scale(&half)]
    }
    let boxes = points_and_boxes::<3>(43, 0.02);
    for abs in [(false, false), (false, true), (true, false), (true, true)] {
        for (b, copies) in [(1, 1), (2, 0)] {
            let what = format!("|·| {abs:?}, other factor component {b}");
            let tape = Tape::<Interval, 3>::record(|v| field(v, abs, b));
            let reference =
                Tape::<M, 3>::record(|v| field(v, abs, b)).without_shortcuts(true, true);
            jets_contain_the_reference(&tape, &reference, &boxes, 8, 4, &what);
            let fused = tape.fused(Rounding::Each);
            jets_contain_the_reference(&fused, &reference, &boxes, 8, 4, &what);
            assert_eq!(tape.shortcuts(), (0, copies), "{what}: copies");
            assert_eq!(fused.merges(), copies, "{what}: merged");
        }
    }
}

/// A power's factor table q(k − j) − j ([`pow_k`]) is kept in the workspace with the
/// exponent it was made for, compared on the type's own ends ([`Real::identical`]), so a
/// workspace reused for another exponent with the same f64 bounds (1.31 and 1.31 + 2⁻⁶⁰ at
/// 256 bits) makes a table of its own. One workspace runs the jets of y′ = |x|^q and of
/// y′ = |x|^(q−1)x (x′ = 1) to order 8, the exponent switching between the two at each jet:
/// as two tapes of constant exponents, and as one tape whose exponent is a parameter
/// component (the engine's reuse: one workspace for every step of a tape). Every jet is the
/// jet of a fresh workspace bit for bit and contains the 512-bit binomial series
/// y_{k+1} = s^(k+1)·C(q, k)·|x₀|^(q−k)/(k + 1) (s^k for |x|^q; s = sign x₀). The bases
/// x₀ = ±2⁻¹²⁰⁰·(1 + j/8) lie below f64's range: their f64 bounds (0 and ±2⁻¹⁰⁷⁴) are not
/// thin, so the jet of the point takes the power recurrence with the table (over a box the
/// box's width would hide 2⁻⁶⁰), and its coefficients are tight to ~2⁻²⁴⁰ relative. With
/// the table keyed by the f64 bounds the second exponent's jets missed the series.
#[test]
fn a_reused_workspace_makes_the_factor_table_of_each_exponent() {
    use crate::arith::mpfr::Mpi;
    type M = Mpi<256>;
    type W = Mpi<512>;
    let q = [
        M::parse_decimal("1.31").unwrap(),
        M::parse_decimal("1.31").unwrap() + M::from_exact_f64(2f64.powi(-60)),
    ];
    assert_eq!(
        (q[0].lo(), q[0].hi()),
        (q[1].lo(), q[1].hi()),
        "equal f64 bounds"
    );
    assert!(!q[0].identical(&q[1]) && q[0].identical(&q[0].clone()));
    let qw = [
        W::parse_decimal("1.31").unwrap(),
        W::parse_decimal("1.31").unwrap() + W::from_exact_f64(2f64.powi(-60)),
    ];
    // y′ = the power of x with exponent `q` (None: the parameter component 2), x′ = 1
    let range = Mpi::hull(&q[0], &q[1]);
    let toy = |q: Option<&M>, signed: bool| {
        let range = q.is_none().then(|| range.clone());
        Tape::<M, 3>::record_with([None, None, range], |v| {
            let e = q.map_or_else(|| v[2].clone(), |q| Rec::constant(q.clone()));
            let p = if signed {
                Real::spow(&v[0], &e)
            } else {
                Real::apow(&v[0], &e)
            };
            vec![Rec::constant(M::one()), p, Rec::constant(M::zero())]
        })
    };
    // y_0..y_8 at 512 bits
    let series = |x0: &W, q: &W, signed: bool| -> Vec<W> {
        let s = x0.sign().unwrap();
        let a = Real::abs(x0);
        let (mut binomial, mut a_k) = (W::one(), W::one());
        let mut y = vec![W::zero()];
        for k in 0..8_i64 {
            let signs = if (k + i64::from(signed)) % 2 == 1 {
                s
            } else {
                1
            };
            let u = binomial.clone() * Real::apow(&a, q) / a_k.clone();
            y.push(u.mul_int(i64::from(signs)).div_int(k + 1));
            binomial = binomial * (q.clone() - W::from_int(k)) / W::from_int(k + 1);
            a_k = a_k * a.clone();
        }
        y
    };
    let tiny = 2f64.powi(-600);
    for signed in [true, false] {
        let consts = [toy(Some(&q[0]), signed), toy(Some(&q[1]), signed)];
        let param = toy(None, signed);
        assert_eq!(consts[0].ops(), consts[1].ops(), "one shape");
        let (mut ws, mut ws_param) = (Workspace::default(), Workspace::default());
        for (n, (j, s)) in [(0, 1.0), (3, -1.0), (7, 1.0), (1, -1.0)]
            .iter()
            .enumerate()
        {
            let m = tiny * (1.0 + f64::from(*j) / 8.0) * s;
            let x0 = M::from_exact_f64(tiny) * M::from_exact_f64(m);
            let x0w = W::from_exact_f64(tiny) * W::from_exact_f64(m);
            assert_eq!((x0.lo() == 0.0, x0.hi() == 0.0), (*s > 0.0, *s < 0.0));
            // the exponent switches at every jet, in both orders
            for i in [n % 2, 1 - n % 2] {
                let x = [x0.clone(), M::zero(), q[i].clone()];
                let exact = series(&x0w, &qw[i], signed);
                for (t, ws) in [(&consts[i], &mut ws), (&param, &mut ws_param)] {
                    let a = t.jet(&x, 8, ws).unwrap();
                    let b = t.jet(&x, 8, &mut Workspace::default()).unwrap();
                    for k in 0..=8 {
                        let (a, b, e) = (&a[1][k], &b[1][k], &exact[k]);
                        let what = format!("q{i}, x₀ = 2⁻⁶⁰⁰·{m:e}, signed {signed}, order {k}");
                        assert!(
                            a.inf() <= e.inf() && e.sup() <= a.sup(),
                            "{what}: {a} vs {e}"
                        );
                        assert!(a.inf() == b.inf() && a.sup() == b.sup(), "{what}: reused");
                    }
                }
            }
        }
    }
}

#[test]
fn switching_components_and_branch_points_are_found() {
    let lin = Shc::<f64>::new(
        NdParams::with_admissibility(
            ModelKind::Shc,
            crate::models::Admissibility::Closed,
            0.0,
            0.0,
            0.5,
            0.0,
            1.0,
            1.0,
        )
        .unwrap(),
    );
    let tape = Tape::<f64, 3>::record(|v| lin.field(v).to_vec());
    // n = p = 1: |X| (in σ|X|^p V) and |Z| (in Γ|Z|^n V) and |V| are kinks, even with zero factors
    assert_eq!(tape.switching(), &[0, 1, 2]);
    // only |V| is a plain |·|; |X|^p, |Z|^n with p = n = 1 are powers, treated (safely) as
    // branch points
    assert_eq!(tape.kinks(), &[2]);
    let shc = Shc::<f64>::new(
        NdParams::parse(ModelKind::Shc, "1.43,-1.42,0.632,0.00715,1.31,1.27").unwrap(),
    );
    let tape = Tape::<f64, 3>::record(|v| shc.field(v).to_vec());
    // at the start X = Z = 0: the first branch met (Z's power in the Bouc–Wen rate, or X's)
    let e = tape.jet(&[0.0, 0.0, -1.0], 5, &mut Workspace::default());
    assert!(
        matches!(e, Err(JetError::Branch { var: Some(0 | 1) })),
        "{e:?}"
    );
}
