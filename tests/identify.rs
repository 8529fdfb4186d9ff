//! Set-membership identification (`bwcl identify`, issue #31): the paving against a closed form
//! (the Hunt–Crossley limit, compared as exact rationals), against the generating set under
//! bounded noise (20 seeds), against sampled f64 residuals, and the command's bad input.

use crate::common;

use bwcl::fit::cost::model_cor;
use bwcl::fit::data::CorData;
use bwcl::identify::paving::{Leaf, Options, Paving, Status, pave};
use bwcl::identify::sample::{feasible, sample};
use bwcl::identify::setup::{Spec, problem};
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::FloatOptions;
use inari::Interval;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rug::Rational;

fn run(
    kind: ModelKind,
    data: &CorData,
    spec: &Spec,
    div: f64,
    max_boxes: usize,
) -> (Paving, Vec<Interval>) {
    let (p, start) = problem(kind, data, spec).expect("a valid problem");
    let mut o = Options::new(&start, div);
    o.max_boxes = max_boxes;
    // the slopes' wall-clock budget (0.25 s per run) is a work bound, not part of what is
    // tested: on a loaded machine (the test command runs the Python tests beside these) a run
    // that takes 0.1 s quiet can pass it, and a box then stays undecided (seen once:
    // data_off_the_model_are_proved_inconsistent with 2 undecided boxes)
    o.slope_seconds = 30.0;
    (pave(&p, &start, &o, None), start)
}

fn q(x: f64) -> Rational {
    Rational::from_f64(x).expect("finite")
}

/// The Hunt–Crossley limit (B_b = 10⁻³⁰⁰, Γ_b = 0): e depends on σ = σ_b v0 alone and
/// decreases in it, so F = {σ_b : |e_HC(σ_b v0_i) − e_i| ≤ E} is an interval known exactly.
/// Every box proved feasible has both ends in F, every box proved infeasible has one row
/// violated on one side at both ends (e monotone: on the whole box), as exact rationals.
#[test]
fn the_hunt_crossley_feasible_set_is_paved_exactly() {
    let (e_err, v0) = (0.02, [1.0, 2.0]);
    // data: e_HC at σ_b = 0.3 (the bracket's lower end, rounded to a double)
    let e: Vec<f64> = v0
        .iter()
        .map(|&v| common::hunt_crossley_bracket(&(q(0.3) * q(v))).0.to_f64())
        .collect();
    let data = CorData::new(v0.to_vec(), e.clone()).unwrap();
    let spec = Spec {
        base: Some("1e-300,0,0.5,0.3,1.5,1.5"),
        bounds: Some("sigma_b=0.1..0.6"),
        error: Some(e_err),
        ..Spec::default()
    };
    let (pav, _) = run(ModelKind::Shc, &data, &spec, 128.0, 400);
    let [nf, ni, _] = pav.counts();
    assert!(nf > 0 && ni > 0, "counts {:?}", pav.counts());
    // F contains σ_b = 0.3: a box holding it is never infeasible
    let eh = |sigma_b: f64, i: usize| common::hunt_crossley_bracket(&(q(sigma_b) * q(v0[i])));
    let (lo_t, hi_t): (Vec<Rational>, Vec<Rational>) = e
        .iter()
        .map(|&x| (q(x) - q(e_err), q(x) + q(e_err)))
        .unzip();
    for b in &pav.boxes {
        let (a, c) = (b.lo[0], b.hi[0]);
        match b.status {
            Status::Feasible => {
                for s in [a, c] {
                    for i in 0..2 {
                        let (l, h) = eh(s, i);
                        assert!(l >= lo_t[i] && h <= hi_t[i], "feasible [{a}, {c}] row {i}");
                    }
                }
            }
            Status::Infeasible => {
                assert!(!(a <= 0.3 && 0.3 <= c), "the data's σ_b in [{a}, {c}]");
                let violated = (0..2).any(|i| {
                    let (ea, ec) = (eh(a, i), eh(c, i));
                    // e decreases in σ_b: e(c) ≤ e ≤ e(a) on the box
                    ea.1 < lo_t[i] || ec.0 > hi_t[i]
                });
                assert!(violated, "infeasible [{a}, {c}] holds feasible points");
            }
            Status::Undecided => {}
        }
    }
}

/// The f64 residuals at a point: max_i |e(𝓟(P*, v0_i)) − e_i| (∞ when not evaluated).
fn worst_residual(kind: ModelKind, base: [f64; 6], data: &CorData) -> f64 {
    let p = NdParams::from_array(base);
    model_cor(kind, &p, &data.v0, &FloatOptions::default())
        .iter()
        .zip(&data.e)
        .map(|(r, e)| r.as_ref().map_or(f64::INFINITY, |m| (m - e).abs()))
        .fold(0.0, f64::max)
}

/// Points of a box: its corners' mix and inner points (deterministic).
fn samples(b: &Leaf, k: usize) -> Vec<Vec<f64>> {
    (0..k)
        .map(|s| {
            b.lo.iter()
                .zip(&b.hi)
                .enumerate()
                .map(|(j, (&l, &h))| {
                    let t = ((s * (2 * j + 3) + 1) % (k + 1)) as f64 / k as f64;
                    l + t.clamp(0.0, 1.0) * (h - l)
                })
                .collect()
        })
        .collect()
}

/// 20 data sets from the DSS set with bounded noise |δ| ≤ E/2: the generating σ_b and κ are in F,
/// so never in a box proved infeasible; sampled points of feasible boxes have f64 residuals
/// within E (the f64 engine's error, ≪ 1e-6, as margin), those of infeasible boxes violate a
/// row.
#[test]
fn the_generating_set_is_never_proved_infeasible_under_bounded_noise() {
    let kind = ModelKind::Shc;
    let truth = [1.43, -1.42, 0.632, 0.00715, 1.31, 1.27];
    let p = NdParams::from_array(truth);
    let v0 = vec![0.5, 2.5];
    let clean: Vec<f64> = model_cor(kind, &p, &v0, &FloatOptions::default())
        .into_iter()
        .map(|r| r.unwrap())
        .collect();
    let e_err = 0.01;
    let margin = 1e-6;
    let (mut nf, mut ni) = (0, 0);
    for seed in 0..20u64 {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let e: Vec<f64> = clean
            .iter()
            .map(|c| c + rng.random_range(-e_err / 2.0..e_err / 2.0))
            .collect();
        let data = CorData::new(v0.clone(), e).unwrap();
        let spec = Spec {
            base: Some("1.43,-1.42,0.632,0.00715,1.31,1.27"),
            bounds: Some(if seed % 2 == 0 {
                "sigma_b=0.003..0.02"
            } else {
                "kappa=0.5..0.75"
            }),
            error: Some(e_err),
            ..Spec::default()
        };
        let j = if seed % 2 == 0 { 3 } else { 2 };
        let (pav, _) = run(kind, &data, &spec, 16.0, 80);
        for b in &pav.boxes {
            let at = |x: f64| {
                let mut q = truth;
                q[j] = x;
                q
            };
            match b.status {
                Status::Infeasible => {
                    ni += 1;
                    assert!(
                        !(b.lo[0] <= truth[j] && truth[j] <= b.hi[0]),
                        "seed {seed}: the generating value in infeasible {b:?}"
                    );
                    for s in samples(b, 5) {
                        let r = worst_residual(kind, at(s[0]), &data);
                        assert!(r > e_err - margin, "seed {seed}: {s:?} fits ({r}) in {b:?}");
                    }
                }
                Status::Feasible => {
                    nf += 1;
                    for s in samples(b, 5) {
                        let r = worst_residual(kind, at(s[0]), &data);
                        assert!(
                            r <= e_err + margin,
                            "seed {seed}: {s:?} misses ({r}) in {b:?}"
                        );
                    }
                }
                Status::Undecided => {}
            }
        }
    }
    // the test decides something
    assert!(nf > 0 && ni > 0, "feasible {nf}, infeasible {ni}");
}

/// `--sample`'s f64 inner estimate against the paving's proved outer one, on a one-parameter
/// problem (F an interval): every sampled point has f64 residuals within E (checked by an
/// independent path, `model_cor` on all rows); none lies in a box proved infeasible (those
/// with residuals E − 10⁻⁶ at most: truly feasible, the f64 engine's error being ≪ 10⁻⁶); the
/// sampled hull is inside the proved one, and the pushes bring its ends within a box of the
/// resolution of the proved ends (inner and outer estimates bracket F's hull tightly). A
/// negative control: `feasible` rejects the uniform points whose residuals exceed E.
#[test]
fn sampled_points_are_feasible_and_bracket_the_proved_hull() {
    let kind = ModelKind::Shc;
    let truth = [1.43, -1.42, 0.632, 0.00715, 1.31, 1.27];
    let v0 = vec![0.5, 2.5];
    let p = NdParams::from_array(truth);
    let e: Vec<f64> = model_cor(kind, &p, &v0, &FloatOptions::default())
        .into_iter()
        .map(|r| r.unwrap() + 0.002)
        .collect();
    let data = CorData::new(v0, e).unwrap();
    let e_err = 0.01;
    let spec = Spec {
        base: Some("1.43,-1.42,0.632,0.00715,1.31,1.27"),
        bounds: Some("sigma_b=0.001..0.03"),
        error: Some(e_err),
        ..Spec::default()
    };
    let (prob, start) = problem(kind, &data, &spec).unwrap();
    let sp = sample(&prob, &start, 200, 7);
    assert!(sp.uniform_feasible > 0 && sp.points.len() > sp.uniform_feasible);
    let at = |x: f64| {
        let mut q = truth;
        q[3] = x;
        q
    };
    for x in &sp.points {
        let r = worst_residual(kind, at(x[0]), &data);
        assert!(r <= e_err + 1e-9, "{x:?}: residual {r}");
    }
    // negative control: points off F are rejected
    let mut rejected = 0;
    for k in 0..=60 {
        let x = start[0].inf() + start[0].wid() * k as f64 / 60.0;
        let r = worst_residual(kind, at(x), &data);
        if r > e_err + 1e-9 {
            assert!(!feasible(&prob, &[x]), "{x} accepted with residual {r}");
            rejected += 1;
        }
    }
    assert!(rejected > 0, "the control tests nothing");
    let div = 256.0;
    let (pav, _) = run(kind, &data, &spec, div, 2000);
    assert!(pav.stopped.is_none(), "{:?}", pav.stopped);
    for x in &sp.points {
        if worst_residual(kind, at(x[0]), &data) > e_err - 1e-6 {
            continue;
        }
        for b in pav.boxes.iter().filter(|b| b.status == Status::Infeasible) {
            assert!(
                !(b.lo[0] <= x[0] && x[0] <= b.hi[0]),
                "the feasible {x:?} in the infeasible {b:?}"
            );
        }
    }
    let (inner, outer) = (sp.hull().unwrap()[0], pav.hull().unwrap()[0]);
    let cell = start[0].wid() / div;
    assert!(
        outer.0 <= inner.0 && inner.1 <= outer.1,
        "{inner:?} ⊄ {outer:?}"
    );
    assert!(
        inner.0 - outer.0 <= 2.0 * cell && outer.1 - inner.1 <= 2.0 * cell,
        "sampled {inner:?}, proved {outer:?}, cell {cell}"
    );
}

/// An error far below the noise: F is proved empty (the model falsified at that error) — a
/// certificate, with every box infeasible.
#[test]
fn data_off_the_model_are_proved_inconsistent() {
    // e = 0.3 at v0 = 1 while the DSS set gives ≈ 0.85 for every κ in the box
    let data = CorData::new(vec![1.0], vec![0.3]).unwrap();
    let spec = Spec {
        base: Some("1.43,-1.42,0.632,0.00715,1.31,1.27"),
        bounds: Some("kappa=0.6..0.65"),
        error: Some(0.01),
        ..Spec::default()
    };
    let (pav, _) = run(ModelKind::Shc, &data, &spec, 8.0, 50);
    assert!(pav.hull().is_none(), "{:?}", pav.counts());
    assert!(pav.stopped.is_none());
}

fn one_line_exit_2(args: &[&str], needle: &str) {
    let out = common::bwcl(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err}");
    assert!(out.stdout.is_empty());
}

#[test]
fn bad_input_gets_one_line_and_exit_2() {
    let dir = std::env::temp_dir().join(format!("bwcl-identify-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = dir.join("d.csv");
    std::fs::write(&data, "v0,e\n1,0.85\n").unwrap();
    let empty = dir.join("empty.csv");
    std::fs::write(&empty, "").unwrap();
    let d = data.to_str().unwrap();
    let base = "--base=1.43,-1.42,0.632,0.00715,1.31,1.27";
    fn with<'a>(d: &'a str, base: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
        let mut v = vec!["identify", "--model", "shc", "--data", d, base];
        v.extend_from_slice(extra);
        v
    }
    let cmd = |extra: &[&'static str]| with(d, base, extra);
    one_line_exit_2(
        &cmd(&["--error", "0", "--bounds", "kappa=0.5..0.7"]),
        "'0' for '--error <E>': must be a finite number > 0",
    );
    one_line_exit_2(
        &cmd(&["--error", "-0.1", "--bounds", "kappa=0.5..0.7"]),
        "> 0",
    );
    one_line_exit_2(
        &cmd(&["--error", "0.02", "--bounds", "kappa=1.2..1.5"]),
        "outside 𝓟",
    );
    one_line_exit_2(
        &cmd(&[
            "--error",
            "0.02",
            "--fix",
            "B_b=1",
            "--bounds",
            "Gamma_b=2..3",
        ]),
        "outside 𝓟",
    );
    one_line_exit_2(
        &cmd(&["--error", "0.02", "--bounds", "zeta=0.5..0.7"]),
        "'zeta'",
    );
    one_line_exit_2(
        &cmd(&[
            "--error",
            "0.02",
            "--bounds",
            "kappa=0.5..0.7",
            "--free",
            "kappa,nu",
        ]),
        "'nu'",
    );
    one_line_exit_2(&cmd(&["--error", "0.02"]), "--bounds");
    one_line_exit_2(
        &[
            "identify",
            "--model",
            "shc",
            "--data",
            empty.to_str().unwrap(),
            base,
            "--error",
            "0.02",
            "--bounds",
            "kappa=0.5..0.7",
        ],
        "empty",
    );
    // no error at all, and no sigma column
    one_line_exit_2(&cmd(&["--bounds", "kappa=0.5..0.7"]), "sigma");
    std::fs::remove_dir_all(&dir).ok();
}

/// The JSON of the issue: free names, boxes with outward ends in the order of `free`, the hull,
/// counts and seconds; every box end is a bound of a double the paving used.
#[test]
fn the_json_output_has_the_documented_shape() {
    let dir = std::env::temp_dir().join(format!("bwcl-identify-json-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = dir.join("d.csv");
    std::fs::write(&data, "v0,e\n1,0.85\n2,0.79\n").unwrap();
    let out = common::bwcl(&[
        "identify",
        "--model",
        "shc",
        "--data",
        data.to_str().unwrap(),
        "--base=1.43,-1.42,0.632,0.00715,1.31,1.27",
        "--error",
        "0.02",
        "--bounds",
        "sigma_b=0.004..0.012",
        "--resolution",
        "4",
        "--format",
        "json",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["free"], serde_json::json!(["sigma_b"]));
    let boxes = v["boxes"].as_array().unwrap();
    assert!(!boxes.is_empty());
    let mut total = 0;
    for b in boxes {
        let (lo, hi) = (b["lo"][0].as_f64().unwrap(), b["hi"][0].as_f64().unwrap());
        assert!(lo < hi && lo >= 0.0039 && hi <= 0.0121, "{b}");
        assert!(["feasible", "infeasible", "undecided"].contains(&b["status"].as_str().unwrap()));
        total += 1;
    }
    let c = &v["counts"];
    let n = c["feasible"].as_u64().unwrap()
        + c["infeasible"].as_u64().unwrap()
        + c["undecided"].as_u64().unwrap();
    assert_eq!(n, total);
    assert!(v["seconds"].as_f64().unwrap() >= 0.0);
    assert!(v["hull"].is_object() || v["hull"].is_null());
    std::fs::remove_dir_all(&dir).ok();
}

/// A printed box claims no point the paving did not prove: the ends of feasible and infeasible
/// boxes, of the start box and of the feasible hull are rounded inward (the decimal lies inside
/// the double it reads back to), the outer hull and undecided boxes outward — in JSON, CSV and
/// the table, compared as exact rationals.
#[test]
fn printed_boxes_claim_only_what_was_proved() {
    use bwcl::observables::decimal::parse_rational;
    use serde_json::value::RawValue;
    use std::collections::BTreeMap;
    let data = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/paper_repro/data/synthetic_dss.csv"
    );
    let args = |format: &'static str| {
        [
            "identify",
            "--model",
            "shc",
            "--data",
            data,
            "--error",
            "0.02",
            "--base=1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--bounds",
            "sigma_b=0.001..0.02",
            "--resolution",
            "16",
            "--format",
            format,
        ]
    };
    // the decimal `text` against the double it reads to: inside (≥ for a lower end, ≤ for an
    // upper one) when `inner`, else outside; returns whether it differs from the double
    let side = |text: &str, lower: bool, inner: bool, what: &str| -> bool {
        let x: f64 = text.parse().unwrap_or_else(|_| panic!("{what}: {text}"));
        let (d, r) = (parse_rational(text).unwrap(), q(x));
        let ok = if lower == inner { d >= r } else { d <= r };
        assert!(
            ok,
            "{what}: {text} is on the wrong side of {x:e} (inner {inner})"
        );
        d != r
    };
    type Pair = [Box<RawValue>; 2];
    #[derive(serde::Deserialize)]
    struct BoxRaw {
        lo: Vec<Box<RawValue>>,
        hi: Vec<Box<RawValue>>,
        status: String,
    }
    #[derive(serde::Deserialize)]
    struct Out {
        #[serde(rename = "box")]
        start: BTreeMap<String, Pair>,
        hull: BTreeMap<String, Pair>,
        feasible_hull: BTreeMap<String, Pair>,
        boxes: Vec<BoxRaw>,
        shares: BTreeMap<String, f64>,
    }
    let o = common::bwcl(&args("json"));
    assert_eq!(o.status.code(), Some(0));
    let out: Out = serde_json::from_slice(&o.stdout).unwrap();
    let pair = |p: &Pair, inner: bool, what: &str| {
        side(p[0].get(), true, inner, what);
        side(p[1].get(), false, inner, what);
    };
    pair(&out.start["sigma_b"], true, "box");
    pair(&out.hull["sigma_b"], false, "hull");
    pair(&out.feasible_hull["sigma_b"], true, "feasible_hull");
    let mut differs = [0, 0];
    for b in &out.boxes {
        let inner = b.status != "undecided";
        let d = side(b.lo[0].get(), true, inner, &b.status)
            | side(b.hi[0].get(), false, inner, &b.status);
        differs[usize::from(inner)] += usize::from(d);
    }
    // the test has teeth: proved boxes whose ends are not short decimals (so that outward
    // rounding would put them on the wrong side), and undecided ones
    assert!(differs[1] >= 3 && differs[0] >= 1, "{differs:?}");
    // the shares, summed exactly from the boxes' doubles: the proved ones not overstated, the
    // undecided one not understated
    let f = |t: &RawValue| q(t.get().parse::<f64>().unwrap());
    let width = f(&out.start["sigma_b"][1]) - f(&out.start["sigma_b"][0]);
    let mut exact: BTreeMap<&str, Rational> = BTreeMap::new();
    for b in &out.boxes {
        *exact.entry(b.status.as_str()).or_default() += (f(&b.hi[0]) - f(&b.lo[0])) / width.clone();
    }
    for (status, share) in &out.shares {
        let x = exact.remove(status.as_str()).unwrap_or_default();
        if status == "undecided" {
            assert!(q(*share) >= x, "{status}: {share} < {}", x.to_f64());
        } else {
            assert!(q(*share) <= x, "{status}: {share} > {}", x.to_f64());
        }
    }
    // CSV: status, sigma_b_lo, sigma_b_hi
    let o = common::bwcl(&args("csv"));
    let text = String::from_utf8(o.stdout).unwrap();
    let mut rows = 0;
    for line in text.lines().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let inner = c[0] != "undecided";
        side(c[1], true, inner, line);
        side(c[2], false, inner, line);
        rows += 1;
    }
    assert_eq!(rows, out.boxes.len());
    // table: the row of sigma_b has the start box, the hull and the feasible hull as lo..hi
    let o = common::bwcl(&args("table"));
    let text = String::from_utf8(o.stdout).unwrap();
    let row: Vec<&str> = text
        .lines()
        .find(|l| l.starts_with("sigma_b "))
        .unwrap_or_else(|| panic!("{text}"))
        .split_whitespace()
        .collect();
    for (cell, inner) in [(row[1], true), (row[2], false), (row[3], true)] {
        let (a, b) = cell.split_once("..").unwrap();
        side(a, true, inner, cell);
        side(b, false, inner, cell);
    }
}

/// A classical law refuted by its data: each row's refuted range of the parameter is printed
/// with its ends exact (they are claims over every point of the range: neither wider than
/// proved, nor with a gap where the next range begins at the same double).
#[test]
fn a_refutation_certificate_prints_its_ends_exactly() {
    use bwcl::observables::decimal::parse_rational;
    let data = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/paper_repro/data/synthetic_dss_uniform.csv"
    );
    let o = common::bwcl(&[
        "identify",
        "--model",
        "linear-maxwell",
        "--data",
        data,
        "--error",
        "0.02",
    ]);
    let text = String::from_utf8(o.stdout).unwrap();
    let ranges: Vec<&str> = text
        .lines()
        .filter_map(|l| l.split_once(" refutes c ∈ ").map(|(_, r)| r))
        .collect();
    assert!(ranges.len() >= 2, "{text}");
    let mut ends = Vec::new();
    for r in &ranges {
        let (a, b) = r.split_once(", ").unwrap();
        for t in [&a[1..], &b[..b.len() - 1]] {
            if t == "∞" {
                continue;
            }
            let x: f64 = t.parse().unwrap();
            assert_eq!(
                parse_rational(t).unwrap(),
                q(x),
                "{t} is not exactly a double"
            );
            ends.push(x);
        }
    }
    // the ranges meet: an end of one is the start of the next
    assert!(
        ends.windows(2).any(|w| w[0] == w[1]),
        "{ranges:?}: no two ranges meet"
    );
}
