//! The second derivatives of e and T_s over a range of v0 (the second variational system,
//! `observables::curvature`) against an independent rigorous reference: the second difference
//! (e(v − h) − 2e(v) + e(v + h))/h² = e″(ξ), ξ ∈ (v − h, v + h), of three point values proved
//! to 30 digits by the MPFR engine, compared as rationals — the enclosure of e″ over
//! [v − h, v + h] must meet it (and likewise T_s″).

use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::ModelKind;
use bwcl::models::NdParams;
use bwcl::models::params::TABLE1;
use bwcl::observables::curvature::{Curvature, curvature_over_range};
use bwcl::observables::precision::{ParamText, PreciseEnclosure, rigorous_impact_digits};
use bwcl::observables::sets::Inputs;
use inari::Interval;
use rug::Rational;

fn range_run(case: usize, lo: f64, hi: f64) -> Curvature {
    let (_, kind, base) = TABLE1[case];
    let b = NdParams::<Interval>::parse(kind, base).unwrap();
    let inputs = Inputs::Base {
        base: b,
        v0: Interval::try_from((lo, hi)).unwrap(),
    };
    curvature_over_range(kind, &inputs, &TaylorOptions::default())
        .unwrap_or_else(|e| panic!("{}: not proved: {}", TABLE1[case].0, e.reason))
}

fn precise(kind: ModelKind, base: &str, v0: f64) -> PreciseEnclosure {
    let p = ParamText::Base {
        base: base.into(),
        v0: format!("{v0:e}"),
    };
    rigorous_impact_digits(kind, &p, 30, &TaylorOptions::default()).unwrap()
}

/// The second difference's enclosure [lo, hi] from the exact ends of three enclosures.
fn second_difference(
    m: &[Rational; 2],
    c: &[Rational; 2],
    p: &[Rational; 2],
    h: f64,
) -> [Rational; 2] {
    let h2 = Rational::from_f64(h).unwrap().square();
    let lo = Rational::from(&m[0] + &p[0]) - Rational::from(&c[1] * 2u32);
    let hi = Rational::from(&m[1] + &p[1]) - Rational::from(&c[0] * 2u32);
    [lo / &h2, hi / h2]
}

fn meets(x: Interval, r: &[Rational; 2]) -> bool {
    Rational::from_f64(x.inf()).unwrap() <= r[1] && r[0] <= Rational::from_f64(x.sup()).unwrap()
}

fn check(case: usize, v: f64, h: f64) -> Curvature {
    let (name, kind, base) = TABLE1[case];
    let c = range_run(case, v - h, v + h);
    let (em, e0, ep) = (
        precise(kind, base, v - h),
        precise(kind, base, v),
        precise(kind, base, v + h),
    );
    let de = second_difference(&em.e, &e0.e, &ep.e, h);
    let dt = second_difference(&em.ts, &e0.ts, &ep.ts, h);
    eprintln!(
        "{name} v0 = {v} ± {h}: e'' {:?} (width {:.2e}), second difference {:.8e}; T'' {:?}, {:.8e}; {} steps",
        c.e2,
        c.e2.wid(),
        de[0].to_f64(),
        c.ts2,
        dt[0].to_f64(),
        c.steps
    );
    assert!(
        meets(c.e2, &de),
        "{name} v0 = {v}: e'' {:?} misses the second difference [{}, {}]",
        c.e2,
        de[0].to_f64(),
        de[1].to_f64()
    );
    assert!(
        meets(c.ts2, &dt),
        "{name} v0 = {v}: T'' {:?} misses the second difference [{}, {}]",
        c.ts2,
        dt[0].to_f64(),
        dt[1].to_f64()
    );
    c
}

#[test]
fn maxwell_dsa_second_derivatives_meet_the_second_differences() {
    check(3, 1.0, 1.0 / 16384.0);
}

#[test]
fn shc_dss_second_derivatives_meet_the_second_differences() {
    check(0, 1.0, 1.0 / 16384.0);
}

#[test]
fn maxwell_dss_second_derivatives_meet_the_second_differences() {
    check(2, 1.0, 1.0 / 16384.0);
}

/// The band in the interpolation form at 1e-9 over a short range: thinner than the target,
/// and at v0 between the nodes it holds e and T_s proved to 30 digits (compared as rationals).
/// `first_width`: None for the default (several pieces, walked in segments).
fn band_holds_precise_values(
    case: usize,
    lo: f64,
    hi: f64,
    first_width: Option<f64>,
    probes: &[f64],
) -> bwcl::observables::band_second::InterpBand {
    use bwcl::observables::band_second::{InterpOptions, prove_band_second};
    let (name, kind, base) = TABLE1[case];
    let b = NdParams::<Interval>::parse(kind, base).unwrap();
    let io = InterpOptions {
        thickness: 1e-9,
        first_width: first_width.unwrap_or(InterpOptions::default().first_width),
        ..InterpOptions::default()
    };
    let band = prove_band_second(kind, &b, lo, hi, &io, &TaylorOptions::default())
        .unwrap_or_else(|e| panic!("{name}: band not proved: {}", e.reason));
    let thick = band.thickness();
    eprintln!(
        "{name} [{lo}, {hi}]: {} pieces, {} point runs, thickness {thick:.2e}",
        band.pieces.len(),
        band.point_runs
    );
    assert!(thick <= 1e-9, "{name}: thickness {thick}");
    // consecutive pieces share their ends and cover [lo, hi]
    assert_eq!(band.pieces[0].v0_lo(), lo);
    assert_eq!(band.pieces.last().unwrap().v0_hi(), hi);
    assert!(band.pieces.windows(2).all(|w| w[0].v0_hi() == w[1].v0_lo()));
    for &v in probes {
        let p = band.piece_at(v).unwrap();
        let x = Interval::try_from((v, v)).unwrap();
        let (e, ts) = (p.e_at(x).unwrap(), p.ts_at(x).unwrap());
        assert!(e.wid() <= thick && ts.is_common_interval());
        let r = precise(kind, base, v);
        // the 30-digit enclosures lie inside the band's
        let inside = |x: Interval, q: &[Rational; 2]| {
            Rational::from_f64(x.inf()).unwrap() <= q[0]
                && q[1] <= Rational::from_f64(x.sup()).unwrap()
        };
        assert!(
            inside(e, &r.e),
            "{name} v0 = {v}: e {e:?} misses [{}, {}]",
            r.e[0].to_f64(),
            r.e[1].to_f64()
        );
        assert!(
            inside(ts, &r.ts),
            "{name} v0 = {v}: T_s {ts:?} misses {}",
            r.ts[0].to_f64()
        );
    }
    band
}

#[test]
fn a_maxwell_dsa_band_at_1e_9_holds_precise_values_between_its_nodes() {
    band_holds_precise_values(
        3,
        0.9375,
        1.0625,
        Some(0.125),
        &[0.94, 0.99, 1.0001, 1.0623],
    );
}

#[test]
fn a_shc_dss_band_at_1e_9_holds_precise_values_between_its_nodes() {
    band_holds_precise_values(
        0,
        0.9375,
        1.0625,
        Some(0.125),
        &[0.94, 0.99, 1.0001, 1.0623],
    );
}

/// At low speeds with the default options: the range cut into segments walked in parallel,
/// each piece's width from its neighbour's nodes; the pieces still share their ends and cover
/// the range, and the band holds 30-digit values (one probe near a segment's end).
#[test]
fn a_band_walked_in_segments_covers_its_range_and_holds_precise_values() {
    let band = band_holds_precise_values(0, 0.1, 0.16, None, &[0.1002, 0.1299, 0.1597]);
    assert!(band.pieces.len() >= 4, "{}", band.pieces.len());
    // (the widths from the neighbours' nodes: few pieces tried in vain — deterministic, the
    // cuts do not depend on the threads)
    assert!(
        band.range_runs <= band.pieces.len() + 2,
        "{} range runs for {} pieces",
        band.range_runs,
        band.pieces.len()
    );
}

/// SHC DSA has n = 1: |Z|^n is |Z|, whose derivative sgn Z jumps where Z = 0 (not a kink of
/// |·|: Z also enters a power), so S₂ jumps there, at each member's own time; the jump is
/// carried in the crossing of Z = 0 (`crossing::across_zero`) and in any time step across it
/// (`integrable::kink_jump`). Checked at a low, the middle and a high speed.
#[test]
fn shc_dsa_second_derivatives_meet_the_second_differences() {
    for v in [0.25, 1.0, 4.0] {
        check(1, v, 1.0 / 16384.0);
    }
}

#[test]
fn a_shc_dsa_band_at_1e_9_holds_precise_values_between_its_nodes() {
    band_holds_precise_values(
        1,
        0.9375,
        1.0625,
        Some(0.125),
        &[0.94, 0.99, 1.0001, 1.0623],
    );
}

/// With n itself the range [1, 1.001], the derivative of |Z|^n holds |Z|^(n−1) with an exponent
/// reaching 0 (a jump at n = 1, none above): not carried, so refused with that reason.
#[test]
fn a_derivative_that_jumps_off_the_kinks_is_refused() {
    let (_, kind, base) = TABLE1[1];
    // (the base set as a nondimensional set: P = P* at v0 = 1)
    let b = NdParams::<Interval>::parse(kind, base).unwrap();
    let inputs = Inputs::Nd(NdParams {
        n: Interval::try_from((1.0, 1.001)).unwrap(),
        ..b
    });
    let e = curvature_over_range(kind, &inputs, &TaylorOptions::default()).unwrap_err();
    assert!(e.reason.contains("derivative jumps"), "{}", e.reason);
}

/// A base set with n itself the range: the hyper-dual of v0^(2n/(p+1)) has an unbounded second
/// derivative in n at record time — a reason, not a panic.
#[test]
fn a_set_whose_second_derivatives_are_unbounded_is_refused_not_a_panic() {
    let (_, kind, base) = TABLE1[1];
    let b = NdParams::<Interval>::parse(kind, base).unwrap();
    let inputs = Inputs::Base {
        base: NdParams {
            n: Interval::try_from((1.0, 1.001)).unwrap(),
            ..b
        },
        v0: Interval::try_from((1.0, 1.0)).unwrap(),
    };
    let e = curvature_over_range(kind, &inputs, &TaylorOptions::default()).unwrap_err();
    assert!(e.reason.contains("not bounded"), "{}", e.reason);
}
