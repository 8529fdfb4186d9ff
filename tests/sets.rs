//! Proved results over sets of parameters (issue #13): ranges of any input, the band of e over
//! a range of v0, and the monotonicity prover — each against point enclosures compared exactly,
//! and with negative controls that must fail.

use bwcl::arith::Real;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::params::TABLE1;
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::band::{
    BandOptions, prove_band, prove_decreasing, prove_piece, sub_centres,
};
use bwcl::observables::sets::{Inputs, hull_over_set, prove_at_point, prove_over_set};
use inari::Interval;

use crate::common;

const DSS_SHC: &str = "1.43,-1.42,0.632,0.00715,1.31,1.27";
const DSA_SHC: &str = "0.63,-0.611,0.188,0.00594,1,2.02";
const DSA_MX: &str = "0.44,-0.418,0.113,0.00785,1.27,3.14";

fn iv(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).unwrap()
}

fn base(kind: ModelKind, text: &str, v0: Interval) -> Inputs<Interval> {
    Inputs::Base {
        base: NdParams::parse(kind, text).unwrap(),
        v0,
    }
}

/// Point enclosures at `n` points of input `j`'s range (ends included): (T_s, e) each.
fn samples(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    j: usize,
    n: usize,
) -> Vec<(Interval, Interval)> {
    let vals = inputs.values();
    let (lo, hi) = (vals[j].inf(), vals[j].sup());
    (0..n)
        .map(|i| {
            let x = if i + 1 == n {
                hi
            } else {
                lo + (hi - lo) * i as f64 / (n - 1) as f64
            };
            let mut v = vals.clone();
            v[j] = iv(x, x);
            let r =
                prove_over_set(kind, &inputs.with_values(v), &TaylorOptions::default()).unwrap();
            (r.ts, r.e)
        })
        .collect()
}

/// (lo, hi) of the midpoints: a lower bound of the true spread.
fn spread(xs: impl Iterator<Item = Interval>) -> f64 {
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x.mid()), b.max(x.mid()))
    });
    hi - lo
}

/// One range of each kind of input: the enclosure contains every sampled point enclosure
/// (doubles compared exactly), and its width is within the factors of the sampled
/// spread — v0 of the SHC DSS set (×1.2 for e, ×1.5 for T_s), κ and a variable exponent n of
/// the Maxwell DSA set (×1.5), and n of the SHC DSA set over [1, 1.001] (n = 1 is the edge of
/// 𝓟; ∂(|Z|^(n−1)Z)/∂n = |Z|^(n−1)Z·ln|Z| has no bounded enclosure at Z = 0, so this range is
/// proved by the hull of the parameters as components, ×1.5).
#[test]
fn ranges_contain_their_points_and_are_tight() {
    let cases = [
        (ModelKind::Shc, DSS_SHC, 6, iv(0.999, 1.001), 1.2, 1.5),
        (ModelKind::Shc, DSA_SHC, 4, iv(1.0, 1.001), 1.5, 1.5),
        (
            ModelKind::Maxwell,
            DSA_MX,
            2,
            iv(0.113 - 5.65e-5, 0.113 + 5.65e-5),
            1.5,
            1.5,
        ),
        (
            ModelKind::Maxwell,
            DSA_MX,
            4,
            iv(1.27 - 6.35e-4, 1.27 + 6.35e-4),
            1.5,
            1.5,
        ),
    ];
    for (kind, text, j, range, fe, ft) in cases {
        let inputs = base(kind, text, Interval::one());
        let mut vals = inputs.values();
        vals[j] = range;
        let inputs = inputs.with_values(vals);
        let r = prove_over_set(kind, &inputs, &TaylorOptions::default()).unwrap();
        let pts = samples(kind, &inputs, j, 9);
        for (ts, e) in &pts {
            assert!(
                ts.subset(r.ts) && e.subset(r.e),
                "{text} input {j}: {ts:?} {e:?} not in {r:?}"
            );
        }
        let (se, st) = (
            spread(pts.iter().map(|p| p.1)),
            spread(pts.iter().map(|p| p.0)),
        );
        assert!(
            r.e.wid() <= fe * se + 1e-12,
            "{text} input {j}: e {:e} vs spread {se:e}",
            r.e.wid()
        );
        assert!(
            r.ts.wid() <= ft * st + 1e-12,
            "{text} input {j}: T_s {:e} vs spread {st:e}",
            r.ts.wid()
        );
    }
}

/// All six base parameters as ranges at once (each Table 1 set ± 0.1 %; n = 1 as [1, 1.002],
/// 𝓟 needing n ≥ 1): proved, containing the point enclosures at the 64 corners, e within 2×
/// their spread.
#[test]
fn all_six_base_parameters_at_once() {
    for (name, kind, text) in TABLE1 {
        let inputs = base(kind, text, Interval::one());
        let mut vals = inputs.values();
        for v in vals.iter_mut().take(6) {
            let (m, h) = (v.mid(), 0.001 * v.mid().abs());
            *v = if m == 1.0 {
                iv(1.0, 1.0 + 2.0 * h)
            } else {
                iv(m - h, m + h)
            };
        }
        let set = inputs.with_values(vals.clone());
        let r = prove_over_set(kind, &set, &TaylorOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut es = Vec::new();
        for corner in 0..64u32 {
            let v: Vec<Interval> = (0..7)
                .map(|i| match i {
                    6 => vals[6],
                    _ if corner >> i & 1 == 1 => iv(vals[i].sup(), vals[i].sup()),
                    _ => iv(vals[i].inf(), vals[i].inf()),
                })
                .collect();
            let p =
                prove_over_set(kind, &inputs.with_values(v), &TaylorOptions::default()).unwrap();
            assert!(
                p.e.subset(r.e) && p.ts.subset(r.ts),
                "{name}, corner {corner}: {p:?} not in {r:?}"
            );
            es.push(p.e);
        }
        let se = spread(es.into_iter());
        assert!(
            r.e.wid() <= 2.0 * se,
            "{name}: e {:e} vs corner spread {se:e}",
            r.e.wid()
        );
    }
}

/// The band over a range of v0: every sampled point enclosure lies inside the band's enclosure
/// at that v0; the same band shifted by three thicknesses is caught by the same check.
#[test]
fn band_contains_its_points_and_a_shifted_band_is_rejected() {
    let kind = ModelKind::Shc;
    let p = NdParams::parse(kind, DSS_SHC).unwrap();
    let bo = BandOptions {
        thickness: 2e-5,
        initial: 4,
        ..BandOptions::default()
    };
    let band = prove_band(kind, &p, 0.9, 1.0, &bo, &TaylorOptions::default()).unwrap();
    assert!(band.thickness() <= 2e-5);
    assert_eq!(band.pieces.first().unwrap().v0_lo, 0.9);
    assert_eq!(band.pieces.last().unwrap().v0_hi, 1.0);
    for w in band.pieces.windows(2) {
        assert_eq!(w[0].v0_hi, w[1].v0_lo, "gap in the band");
    }
    // the stated thickness bounds the enclosure at the ends (the centre need not be the middle)
    for p in &band.pieces {
        for v in [p.v0_lo, p.v0_hi] {
            let w = p.e_at(iv(v, v)).unwrap().wid();
            assert!(
                w <= p.thickness(),
                "[{}, {}] at {v}: {w:e} > {:e}",
                p.v0_lo,
                p.v0_hi,
                p.thickness()
            );
        }
    }
    let mut shifted_caught = 0;
    for k in 0..=20 {
        let v = 0.9 + 0.005 * k as f64;
        let inputs = base(kind, DSS_SHC, iv(v, v));
        let pt = prove_over_set(kind, &inputs, &TaylorOptions::default()).unwrap();
        let piece = band.piece_at(v).unwrap();
        let e = piece.e_at(iv(v, v)).unwrap();
        let ts = piece.ts_at(iv(v, v)).unwrap();
        assert!(e.wid() <= 2e-5, "thickness at {v}: {:e}", e.wid());
        assert!(
            pt.e.subset(e) && pt.ts.subset(ts),
            "v0 = {v}: {pt:?} not in {e:?} {ts:?}"
        );
        let mut bad = piece.clone();
        let shift = iv(3.0 * bad.thickness(), 3.0 * bad.thickness());
        bad.e_c += shift;
        bad.e += shift;
        if !pt.e.subset(bad.e_at(iv(v, v)).unwrap()) {
            shifted_caught += 1;
        }
    }
    assert_eq!(shifted_caught, 21, "a shifted band passed the check");
}

/// A piece's slope holds on its parts: the parts with their own centres (sub-centres) keep the
/// piece's slope and hull, are thinner, and each contains the point enclosures at its ends and
/// inside (compared exactly); with the piece's centre value in place of a part's own, the same
/// check fails.
#[test]
fn sub_centres_contain_their_points() {
    let opts = TaylorOptions::default();
    let kind = ModelKind::Shc;
    let p = NdParams::parse(kind, DSS_SHC).unwrap();
    let piece = prove_piece(kind, &p, 1.0, 1.004, &opts).unwrap();
    let parts = sub_centres(kind, &p, &piece, 4, &opts).unwrap();
    assert_eq!(parts.len(), 4);
    assert_eq!((parts[0].v0_lo, parts[3].v0_hi), (1.0, 1.004));
    for w in parts.windows(2) {
        assert_eq!(w[0].v0_hi, w[1].v0_lo, "gap between parts");
    }
    let mut wrong_caught = 0;
    for q in &parts {
        assert!(q.v0_lo < q.v0_c && q.v0_c < q.v0_hi);
        assert_eq!((q.de, q.dts), (piece.de, piece.dts));
        assert!(q.e.subset(piece.e) && q.ts.subset(piece.ts));
        assert!(
            q.thickness() < 0.35 * piece.thickness(),
            "{:e} against {:e}",
            q.thickness(),
            piece.thickness()
        );
        for k in 0..=4 {
            let v = q.v0_lo + (q.v0_hi - q.v0_lo) * k as f64 / 4.0;
            let v = if k == 4 { q.v0_hi } else { v };
            let pt = prove_over_set(kind, &base(kind, DSS_SHC, iv(v, v)), &opts).unwrap();
            let (e, ts) = (q.e_at(iv(v, v)).unwrap(), q.ts_at(iv(v, v)).unwrap());
            assert!(
                pt.e.subset(e) && pt.ts.subset(ts),
                "v0 = {v}: {pt:?} not in {e:?} {ts:?}"
            );
            let mut wrong = q.clone();
            (wrong.e_c, wrong.ts_c) = (piece.e_c, piece.ts_c);
            let e = wrong.e_at(iv(v, v)).unwrap();
            if !pt.e.subset(e) {
                wrong_caught += 1;
            }
        }
    }
    assert!(wrong_caught >= 10, "{wrong_caught} of 20 caught");
}

/// The monotonicity prover: proves the SHC DSS curve decreasing on [0.9, 1.1], and fails —
/// naming the range — on a curve that increases (a stiff-exponent SHC set, p = 3, whose e
/// grows with v0; f64: e(0.1) = 0.877, e(0.3) = 0.880, e(1) = 0.928).
#[test]
fn monotonicity_is_proved_and_refused() {
    let opts = TaylorOptions::default();
    let bo = BandOptions {
        initial: 8,
        min_width: 0.01,
        ..BandOptions::default()
    };
    let dss = NdParams::parse(ModelKind::Shc, DSS_SHC).unwrap();
    let m = prove_decreasing(ModelKind::Shc, &dss, 0.9, 1.1, &bo, &opts);
    assert!(m.proved(), "{:?}", m.undecided);
    assert!(m.max_slope() < 0.0);
    let up = NdParams::parse(ModelKind::Shc, "1,0.9,0.3,0.001,1,3").unwrap();
    let m = prove_decreasing(ModelKind::Shc, &up, 0.3, 1.0, &bo, &opts);
    assert!(!m.proved(), "an increasing curve was proved decreasing");
    // refuted: the sub-ranges where e is proved to rise (inf de/dv0 > 0 on each)
    assert!(m.refuted(), "{:?}", m.undecided);
    for (a, b, de) in &m.increasing {
        assert!(
            0.3 <= *a && a < b && *b <= 1.0 && de.inf() > 0.0,
            "{a} {b} {de:?}"
        );
    }
    // and the slopes it found are positive there (the refusal is for the right reason)
    let s = prove_piece(ModelKind::Shc, &up, 0.5, 0.51, &opts).unwrap();
    assert!(s.de.inf() > 0.0, "{:?}", s.de);
}

/// The slope enclosure of a range contains the difference quotient of its end points' point
/// enclosures (mean-value theorem): (e(b) − e(a))/(b − a) ∈ [de/dv0].
#[test]
fn slopes_contain_difference_quotients() {
    let opts = TaylorOptions::default();
    for (_, kind, text) in TABLE1 {
        let p = NdParams::parse(kind, text).unwrap();
        let (a, b) = (1.5, 1.5078125);
        let piece = prove_piece(kind, &p, a, b, &opts).unwrap();
        let at = |v: f64| prove_over_set(kind, &base(kind, text, iv(v, v)), &opts).unwrap();
        let (ea, eb) = (at(a), at(b));
        let q = (eb.e - ea.e) / (iv(b, b) - iv(a, a));
        let qt = (eb.ts - ea.ts) / (iv(b, b) - iv(a, a));
        assert!(
            !q.intersection(piece.de).is_empty(),
            "{text}: {q:?} vs {:?}",
            piece.de
        );
        assert!(
            !qt.intersection(piece.dts).is_empty(),
            "{text}: {qt:?} vs {:?}",
            piece.dts
        );
        // and the slope is informative: narrower than 10% of its size
        assert!(
            piece.de.wid() < 0.1 * piece.de.mag(),
            "{text}: {:?}",
            piece.de
        );
    }
}

/// Sensitivities at a point (`cor --sensitivities`): ∂e/∂v0 at v0 = 1 is a thin enclosure and
/// lies inside the slope enclosure over [0.999, 1.001].
#[test]
fn point_sensitivities_are_thin_and_inside_the_range_slopes() {
    use bwcl::observables::sets::sensitivity;
    let opts = TaylorOptions::default();
    let at = base(ModelKind::Shc, DSS_SHC, Interval::one());
    let s = sensitivity(ModelKind::Shc, &at, 6, &opts).unwrap();
    assert!(s.e.wid() < 1e-6 && s.ts.wid() < 1e-6, "{s:?}");
    let range = base(ModelKind::Shc, DSS_SHC, iv(0.999, 1.001));
    let r = prove_over_set(ModelKind::Shc, &range, &opts).unwrap();
    let slope = r.slope.unwrap();
    assert!(
        s.e.subset(slope.e) && s.ts.subset(slope.ts),
        "{s:?} vs {slope:?}"
    );
}

/// A range whose true spread is known in closed form: the Hunt–Crossley limit of the NDBWSHCCM
/// (B = 10⁻³⁰⁰, Γ = 0; `tests/common/mod.rs`), where e(σ) solves −u − ln(1 − u) = σ − ln(1 + σ),
/// u = σe, and decreases in σ, so that over σ ∈ [σ₁, σ₂] the CoR fills exactly [e(σ₂), e(σ₁)].
/// Its separation is degenerate (F = |X|^p(1 − σV) vanishes at X = 0 with F_t = 0, so T_s has no
/// derivative in σ): the range is proved by the hull of the parameters as components. The
/// enclosure must contain both ends' 400-bit brackets (exact rationals) and be within 1.5× the
/// true spread; σ as the range, and v0 as the range of a base set (σ = σ_b·v0, B = B_b·v0^1.2
/// carried with it).
#[test]
fn hunt_crossley_ranges_contain_the_closed_form_within_the_factor() {
    use rug::Rational;
    let rat = |x: f64| Rational::from_f64(x).unwrap();
    let nd = |s: Interval| {
        let mut p = NdParams::parse(ModelKind::Shc, "1e-300,0,0.5,12,1.5,1.5").unwrap();
        p.sigma = s;
        Inputs::Nd(p)
    };
    let v0 = iv(1.0, 1.001);
    let cases = [
        // (inputs, σ₁, σ₂) with σ exact rationals
        (nd(iv(0.5, 0.5005)), rat(0.5), rat(0.5005)),
        (nd(iv(2.0, 2.002)), rat(2.0), rat(2.002)),
        (
            base(ModelKind::Shc, "1e-300,0,0.5,0.5,1.5,1.5", v0),
            rat(0.5) * rat(v0.inf()),
            rat(0.5) * rat(v0.sup()),
        ),
    ];
    for (inputs, s1, s2) in cases {
        let r = prove_over_set(ModelKind::Shc, &inputs, &TaylorOptions::default())
            .unwrap_or_else(|e| panic!("σ ∈ [{s1}, {s2}]: {e}"));
        let (lo2, hi2) = common::hunt_crossley_bracket(&s2);
        let (lo1, hi1) = common::hunt_crossley_bracket(&s1);
        assert!(hi2 < lo1, "e decreases in σ");
        assert!(
            rat(r.e.inf()) <= lo2 && rat(r.e.sup()) >= hi1,
            "σ ∈ [{s1}, {s2}]: e {:?} misses [{}, {}]",
            r.e,
            lo2.to_f64(),
            hi1.to_f64()
        );
        // the true spread is at least lo1 − hi2
        let spread = (lo1 - hi2).to_f64();
        assert!(
            r.e.wid() <= 1.5 * spread,
            "σ ∈ [{s1}, {s2}]: e width {:e} vs the closed-form spread {spread:e}",
            r.e.wid()
        );
        eprintln!(
            "Hunt–Crossley σ ∈ [{}, {}]: e width / spread = {:.4}",
            s1.to_f64(),
            s2.to_f64(),
            r.e.wid() / spread
        );
    }
}

/// The adaptive split of a range (`observables::split`, issue #32 item 5) against a closed
/// form: in the Hunt–Crossley limit (B_b = 10⁻³⁰⁰, Γ_b = 0) e depends on σ = σ_b·v0 alone and
/// decreases in it, so over v0 ∈ [a, b] the true range of e is [e_HC(σ_b b), e_HC(σ_b a)],
/// bracketed as exact rationals. The hull must contain it, be within 1.05× its width (printed:
/// ≤ 1.02×, 22 pieces), and its
/// inner bounds must hold (min e ≤ a', max e ≥ b'); the printed ratio must bound the true one.
/// Negative control: the split that cuts only what it cannot prove (12 pieces, ≤ 1.1×) is wider
/// than 1.05× — so the factor is the cuts for tightness'.
#[test]
fn an_adaptive_range_split_is_tight_against_the_hunt_crossley_closed_form() {
    use bwcl::observables::split::{SplitOptions, Stop, prove_over_set_adaptive};
    use rug::Rational;
    let q = |x: f64| Rational::from_f64(x).unwrap();
    let sigma_b = 0.3;
    let (a, b) = (0.5, 4.0);
    let inputs = base(ModelKind::Shc, "1e-300,0,0.5,0.3,1.5,1.5", iv(a, b));
    let opts = TaylorOptions::default();
    let r = prove_over_set_adaptive(ModelKind::Shc, &inputs, &opts, &SplitOptions::default())
        .expect("proved");
    // exact range of e: e_HC decreasing in σ
    let (min_lo, min_hi) = common::hunt_crossley_bracket(&(q(sigma_b) * q(b)));
    let (max_lo, max_hi) = common::hunt_crossley_bracket(&(q(sigma_b) * q(a)));
    assert!(
        q(r.e.inf()) <= min_lo && q(r.e.sup()) >= max_hi,
        "hull {:?}",
        r.e
    );
    let spread = max_lo.clone() - &min_hi;
    assert!(
        q(r.e.wid()) <= Rational::from((21, 20)) * &spread,
        "e {:e} vs exact spread {}",
        r.e.wid(),
        spread.to_f64()
    );
    let [ia, ib] = r.e_inner.expect("inner bounds");
    // min e ≤ min_hi ≤ ia and ib ≤ max_lo ≤ max e
    assert!(min_hi <= q(ia) && q(ib) <= max_lo, "inner [{ia}, {ib}]");
    // the printed ratio is at least wid/(true spread) ≥ wid/(max_hi − min_lo)
    let at_least = q(r.e.wid()) / (max_hi.clone() - &min_lo);
    assert!(
        q(r.e_ratio()) >= at_least,
        "ratio {} below the true one",
        r.e_ratio()
    );
    assert_eq!(r.stop, Stop::Tight, "{}", r.summary());
    // negative control: the split without the cuts for tightness (a tolerance a million times
    // the spread: only pieces that cannot be proved are cut; one run does not prove the range,
    // "grew too wide") is not within 1.05× — so the factor is the cuts for tightness'. Its runs
    // may grow to width 1 before they give up (max_width 1): with the default 0.1 the pieces
    // left by failures alone were already tight once the set was carried as an affine set
    // (2026-11-28)
    let loose = SplitOptions {
        rel: 1e6,
        ..SplitOptions::default()
    };
    let wide = TaylorOptions {
        max_width: 1.0,
        ..TaylorOptions::default()
    };
    let r1 = prove_over_set_adaptive(ModelKind::Shc, &inputs, &wide, &loose).expect("proved");
    assert_eq!(r1.stop, Stop::Tight, "{}", r1.summary());
    assert!(r1.pieces > 1, "{}", r1.summary());
    assert!(
        q(r1.e.wid()) > Rational::from((21, 20)) * &spread,
        "{} pieces are already tight: the test would not see the split",
        r1.pieces
    );
    assert!(r.pieces > r1.pieces);
    eprintln!(
        "tight: {}\nwithout cuts for tightness: {}",
        r.summary(),
        r1.summary()
    );
}

/// A range that one run cannot prove (SHC DSS, v0 ∈ [3.7, 4]: "the enclosure grew too wide",
/// measured 2026-11-28; [3.85, 3.93], used before, is proved whole since the set is carried as
/// an affine set) is proved by the adaptive split,
/// its hull containing the point enclosures at 5 speeds and within 1.2× of their spread.
#[test]
fn a_range_one_run_cannot_prove_is_split_until_proved_and_tight() {
    use bwcl::observables::split::{SplitOptions, prove_over_set_adaptive};
    let inputs = base(ModelKind::Shc, DSS_SHC, iv(3.7, 4.0));
    let opts = TaylorOptions::default();
    assert!(
        prove_over_set(ModelKind::Shc, &inputs, &opts).is_err(),
        "proved whole"
    );
    let r = prove_over_set_adaptive(ModelKind::Shc, &inputs, &opts, &SplitOptions::default())
        .expect("proved");
    let pts = samples(ModelKind::Shc, &inputs, 6, 5);
    for (ts, e) in &pts {
        assert!(
            ts.subset(r.ts) && e.subset(r.e),
            "{ts:?} {e:?} not in {r:?}"
        );
    }
    let se = spread(pts.iter().map(|p| p.1));
    assert!(r.e.wid() <= 1.2 * se, "e {:e} vs spread {se:e}", r.e.wid());
    assert!(r.e_ratio() <= 1.2, "{}", r.summary());
}

/// The hulls over a set with no derivative (`hull_over_set`, what identification closes or
/// refutes a row with where its slopes fail), at each dimension it picks (SHC with 1–2 ranges at
/// D = 5, 3–4 at D = 7; Maxwell at D = 9):
/// - in the Hunt–Crossley limit (e depends on σ = σ_b·v0 alone, decreasing) they contain the
///   closed form's range [e_HC(σ₂), e_HC(σ₁)], 400-bit brackets compared as exact rationals,
///   with κ and n ranged beside σ_b (they do not enter e there);
/// - on the DSS sets they contain the point engine's enclosures at the box's corners and
///   centre, and (negative control) not the one at a point outside the box.
#[test]
fn hulls_over_sets_contain_the_closed_form_and_their_points() {
    use rug::Rational;
    let rat = |x: f64| Rational::from_f64(x).unwrap();
    let opts = TaylorOptions::default();
    let v0 = iv(2.0, 2.0);
    for (k, extra) in [(1, ""), (2, "kappa"), (3, "kappa,n")] {
        let mut p = NdParams::parse(ModelKind::Shc, "1e-300,0,0.5,0.25,1.5,1.5").unwrap();
        p.sigma = iv(0.25, 0.2505);
        if extra.contains("kappa") {
            p.kappa = iv(0.4, 0.6);
        }
        if extra.contains(",n") {
            p.n = iv(1.4, 1.6);
        }
        let inputs = Inputs::Base { base: p, v0 };
        let (_, e) = hull_over_set(ModelKind::Shc, &inputs, &opts)
            .unwrap_or_else(|err| panic!("{k} ranges: {err}"));
        let (lo2, _) = common::hunt_crossley_bracket(&(rat(0.2505) * rat(2.0)));
        let (_, hi1) = common::hunt_crossley_bracket(&(rat(0.25) * rat(2.0)));
        assert!(
            rat(e.inf()) <= lo2 && rat(e.sup()) >= hi1,
            "{k} ranges: e {e:?} misses [{}, {}]",
            lo2.to_f64(),
            hi1.to_f64()
        );
    }
    let boxes = [
        (
            ModelKind::Shc,
            DSS_SHC,
            [(2, 0.62, 0.625), (3, 0.007, 0.0072)],
            2.4,
        ),
        (
            ModelKind::Shc,
            DSS_SHC,
            [(2, 0.62, 0.621), (4, 1.3, 1.301)],
            4.2,
        ),
        (
            ModelKind::Maxwell,
            DSA_MX,
            [(2, 0.11, 0.115), (3, 0.0078, 0.0079)],
            1.0,
        ),
    ];
    for (kind, text, ranges, v) in boxes {
        let at = |point: &[f64]| {
            let mut p = NdParams::parse(kind, text).unwrap();
            for (&(j, _, _), &x) in ranges.iter().zip(point) {
                let x = iv(x, x);
                match j {
                    2 => p.kappa = x,
                    3 => p.sigma = x,
                    _ => p.n = x,
                }
            }
            Inputs::Base {
                base: p,
                v0: iv(v, v),
            }
        };
        let mut set = NdParams::parse(kind, text).unwrap();
        for &(j, lo, hi) in &ranges {
            match j {
                2 => set.kappa = iv(lo, hi),
                3 => set.sigma = iv(lo, hi),
                _ => set.n = iv(lo, hi),
            }
        }
        let inputs = Inputs::Base {
            base: set,
            v0: iv(v, v),
        };
        let (ts, e) = hull_over_set(kind, &inputs, &opts)
            .unwrap_or_else(|err| panic!("{text} at {v}: {err}"));
        let (a, b) = (ranges[0], ranges[1]);
        let points = [
            [a.1, b.1],
            [a.1, b.2],
            [a.2, b.1],
            [a.2, b.2],
            [(a.1 + a.2) / 2.0, (b.1 + b.2) / 2.0],
        ];
        for pt in points {
            let (pts, pe) = prove_at_point(kind, &at(&pt), &opts).unwrap();
            assert!(
                pts.subset(ts) && pe.subset(e),
                "{text} at {v}, {pt:?}: T_s {pts:?} e {pe:?} outside the hulls {ts:?} {e:?}"
            );
        }
        // negative control: a point off the box (κ 0.05 lower) is not inside the hull of e
        let (_, off) = prove_at_point(kind, &at(&[a.1 - 0.05, b.1]), &opts).unwrap();
        assert!(
            !off.subset(e),
            "{text} at {v}: the hull {e:?} is too wide to tell {off:?}"
        );
    }
}
