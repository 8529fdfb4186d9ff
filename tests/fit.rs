//! Identification (sec:ID, eq:J): the cost, the reparametrization onto 𝓟, the data reader, and
//! `bwcl fit` / `bwcl cost` end to end.

use bwcl::fit::cost::model_cor;
use bwcl::fit::reparam::LIMITS;
use bwcl::fit::{CorData, Reparam, cost};
use bwcl::models::{Admissibility, ModelKind, NdParams};
use bwcl::observables::FloatOptions;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::Value;
use std::path::PathBuf;

use crate::common;
use common::bwcl;

const DSS: &str = "1.43,-1.42,0.632,0.00715,1.31,1.27";
const MAXWELL_DSA: &str = "0.44,-0.418,0.113,0.00785,1.27,3.14";

fn synthetic() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("paper_repro/data/synthetic_dss.csv")
}

fn text(b: &[u8]) -> String {
    String::from_utf8(b.to_vec()).unwrap()
}

fn scratch(name: &str, content: &str) -> PathBuf {
    let p = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("bwcl-fit-{}-{name}", std::process::id()));
    std::fs::write(&p, content).unwrap();
    p
}

/// Bad input: exit 2, one stderr line `bwcl: error: …`, nothing on stdout.
fn bad_input(args: &[&str]) -> String {
    let o = bwcl(args);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(o.stdout.is_empty());
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("bwcl: error: "), "{err}");
    err
}

#[test]
fn j_is_zero_on_noiseless_data_from_the_same_set() {
    for (kind, base) in [(ModelKind::Shc, DSS), (ModelKind::Maxwell, MAXWELL_DSA)] {
        let p = NdParams::<f64>::parse(kind, base).unwrap();
        let v0: Vec<f64> = (0..12).map(|i| 0.1 + 0.4 * i as f64).collect();
        let opts = FloatOptions::default();
        let e: Vec<f64> = model_cor(kind, &p, &v0, &opts)
            .into_iter()
            .map(Result::unwrap)
            .collect();
        let data = CorData::new(v0, e).unwrap();
        assert_eq!(cost(kind, &p, &data, &opts), 0.0, "{kind:?}");
        // and J is the root of the sum of squares: shift every e by 0.01
        let shifted =
            CorData::new(data.v0.clone(), data.e.iter().map(|e| e - 0.01).collect()).unwrap();
        let j = cost(kind, &p, &shifted, &opts);
        assert!((j - 0.01 * 12f64.sqrt()).abs() < 1e-12, "{j}");
    }
}

#[test]
fn reparametrization_is_a_bijection_onto_the_admissible_set() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for kind in [ModelKind::Shc, ModelKind::Maxwell] {
        for p1 in [false, true] {
            let r = Reparam::new(kind, p1);
            for _ in 0..2000 {
                // u ↦ P ↦ u inside a moderate box
                let u: Vec<f64> = (0..r.dim())
                    .map(|_| -8.0 + 12.0 * rng.random::<f64>())
                    .collect();
                let p = r.to_params(&u).unwrap();
                p.validate(kind, Admissibility::Open).unwrap();
                if p1 {
                    assert_eq!(p.p, 1.0);
                } else if kind == ModelKind::Maxwell {
                    assert!(p.p > 2.0);
                }
                let back = r.from_params(&p).unwrap();
                for (a, b) in u.iter().zip(&back) {
                    assert!((a - b).abs() < 1e-6 * (1.0 + a.abs()), "{u:?} -> {back:?}");
                }
                // any finite u (even far out, or ±∞) maps into 𝓟
                let wild: Vec<f64> = (0..r.dim())
                    .map(|_| match rng.random_range(0..4) {
                        0 => f64::INFINITY,
                        1 => f64::NEG_INFINITY,
                        _ => (rng.random::<f64>() - 0.5) * 10f64.powi(rng.random_range(0..300)),
                    })
                    .collect();
                let q = r.to_params(&wild).unwrap();
                q.validate(kind, Admissibility::Open)
                    .unwrap_or_else(|e| panic!("{wild:?} -> {q:?}: {e}"));
            }
            // P ↦ u ↦ P for sets of 𝓟
            for _ in 0..2000 {
                let b = 10f64.powf(-3.0 + 5.0 * rng.random::<f64>());
                let p_val = if p1 {
                    1.0
                } else if kind == ModelKind::Maxwell {
                    2.0 + 3.0 * rng.random::<f64>() + 1e-3
                } else {
                    1.0 + 3.0 * rng.random::<f64>() + 1e-3
                };
                let p = NdParams::new(
                    kind,
                    b,
                    b * (1.98 * rng.random::<f64>() - 0.99),
                    0.01 + 0.98 * rng.random::<f64>(),
                    10f64.powf(-4.0 + 4.0 * rng.random::<f64>()),
                    1.001 + 4.0 * rng.random::<f64>(),
                    p_val,
                )
                .unwrap();
                let q = r.to_params(&r.from_params(&p).unwrap()).unwrap();
                for (a, b) in p.as_array().iter().zip(q.as_array()) {
                    assert!((a - b).abs() <= 1e-11 * a.abs(), "{p:?} -> {q:?}");
                }
            }
            assert!(r.to_params(&vec![f64::NAN; r.dim()]).is_err());
            assert!(r.to_params(&[0.0; 3]).is_err());
        }
    }
    // the Maxwell p = 1 is outside the connected search, inside the --p1 one
    let p = NdParams::<f64>::new(ModelKind::Maxwell, 1.0, 0.0, 0.5, 0.1, 1.5, 1.0).unwrap();
    assert!(
        Reparam::new(ModelKind::Maxwell, false)
            .from_params(&p)
            .is_err()
    );
    assert!(
        Reparam::new(ModelKind::Maxwell, true)
            .from_params(&p)
            .is_ok()
    );
    // the boundary n = 1 (SHC DSA) maps to the saturation limit, within 1e-13
    let dsa = NdParams::<f64>::parse(ModelKind::Shc, "0.63,-0.611,0.188,0.00594,1,2.02").unwrap();
    let r = Reparam::new(ModelKind::Shc, false);
    let u = r.from_params(&dsa).unwrap();
    assert_eq!(u[4], LIMITS[4].0);
    assert!((r.to_params(&u).unwrap().n - 1.0).abs() < 1e-12);
}

#[test]
fn csv_errors_name_the_line_and_its_content() {
    let cases = [
        ("v0,e\n1,0.5\n2,abc\n", "line 3", "2,abc"),
        ("v0,e\n1,0.5\n\n-1,0.5\n", "line 4", "-1,0.5"),
        ("v0,e\n0,0.5\n", "line 2", "must be a finite number > 0"),
        ("v0,e\nNaN,0.5\n", "line 2", "NaN,0.5"),
        ("v0,e\n1,NaN\n", "line 2", "[0, 1]"),
        ("v0,e\n1,1.2\n", "line 2", "[0, 1]"),
        ("v0,e\n1,0.5,3\n", "line 2", "field"),
        ("speed,cor_x\n1,0.5\n", "line 1", "header"),
        ("1,0.5\n2,0.4\n", "line 1", "header"),
        ("# comment\nv0,e\n1,0.5\n2\n", "line 4", "'2'"),
    ];
    for (csv, line, what) in cases {
        let err = CorData::parse(csv).unwrap_err().to_string();
        assert!(err.contains(line) && err.contains(what), "{csv:?}: {err}");
    }
    assert!(CorData::parse("").is_err());
    assert!(CorData::parse("v0,e\n").is_err());
    let ok = CorData::parse("# x\ne,v0,extra\n0.9,0.5,a\n0.8,1,b\n").unwrap();
    assert_eq!(ok.v0, vec![0.5, 1.0]);
    assert_eq!(ok.e, vec![0.9, 0.8]);
    // through the CLI: exit 2, the line in the message
    let bad = scratch("bad.csv", "v0,e\n0.5,0.9\n1.0,x\n");
    let err = bad_input(&[
        "cost",
        "--model",
        "shc",
        "--base",
        DSS,
        "--data",
        bad.to_str().unwrap(),
    ]);
    assert!(err.contains("line 3") && err.contains("1.0,x"), "{err}");
    let err = bad_input(&["fit", "--model", "shc", "--data", "/nonexistent/data.csv"]);
    assert!(err.contains("/nonexistent/data.csv"), "{err}");
}

#[test]
fn cost_json_matches_the_library() {
    let data = synthetic();
    let o = bwcl(&[
        "cost",
        "--model",
        "shc",
        "--base",
        DSS,
        "--data",
        data.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let d = CorData::read(&data).unwrap();
    let p = NdParams::<f64>::parse(ModelKind::Shc, DSS).unwrap();
    let j = cost(ModelKind::Shc, &p, &d, &FloatOptions::default());
    assert_eq!(v["J"].as_f64().unwrap(), j);
    assert_eq!(v["P_star"]["B"].as_f64(), Some(1.43));
    assert_eq!(v["P_star"]["Gamma"].as_f64(), Some(-1.42));
    assert_eq!(v["curve"].as_array().unwrap().len(), d.len());
    assert_eq!(v["m"].as_u64(), Some(20));
    // bad input
    bad_input(&[
        "cost",
        "--model",
        "maxwell",
        "--base",
        "1,0,0.5,0.1,1.5,1.5",
        "--data",
        data.to_str().unwrap(),
    ]);
    // table
    let o = bwcl(&[
        "cost",
        "--model",
        "shc",
        "--base",
        DSS,
        "--data",
        data.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    assert!(text(&o.stdout).contains("J = "));
}

#[test]
fn fit_recovers_j_to_the_noise_level_on_the_synthetic_data() {
    let data = synthetic();
    let t0 = std::time::Instant::now();
    let o = bwcl(&[
        "fit",
        "--model",
        "shc",
        "--data",
        data.to_str().unwrap(),
        "--starts",
        "2",
        "--max-iter",
        "100",
        "--seed",
        "1",
        "--format",
        "json",
    ]);
    let secs = t0.elapsed().as_secs_f64();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    // stderr is not a terminal here: no progress bar (at most the warning of several minima
    // within the noise)
    let err = text(&o.stderr);
    assert!(
        err.is_empty() || (err.lines().count() == 1 && err.contains("do not determine P*")),
        "{err}"
    );
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let j = v["J"].as_f64().unwrap();
    let noise = 20f64.sqrt() * 0.005;
    assert!(j <= 1.5 * noise, "J = {j}, noise level {noise}");
    let names = ["B", "Gamma", "kappa", "sigma", "n", "p"];
    let p: Vec<f64> = names
        .iter()
        .map(|k| v["P_star"][k].as_f64().unwrap())
        .collect();
    let set = NdParams::<f64>::new(ModelKind::Shc, p[0], p[1], p[2], p[3], p[4], p[5]).unwrap();
    // J as reported is J of the reported P*, as `bwcl cost` computes it
    let d = CorData::read(&data).unwrap();
    assert_eq!(cost(ModelKind::Shc, &set, &d, &FloatOptions::default()), j);
    let base = v["base"].as_str().unwrap();
    let o = bwcl(&[
        "cost",
        "--model",
        "shc",
        "--base",
        base,
        "--data",
        data.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let c: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(c["J"].as_f64(), Some(j));
    assert_eq!(v["starts"].as_array().unwrap().len(), 2);
    assert!(secs < 60.0, "{secs} s");
}

#[test]
fn fit_refuses_bad_options() {
    let data = synthetic();
    let d = data.to_str().unwrap();
    bad_input(&["fit", "--model", "shc", "--data", d, "--starts", "0"]);
    bad_input(&["fit", "--model", "shc", "--data", d, "--max-iter", "0"]);
    bad_input(&[
        "fit",
        "--model",
        "shc",
        "--data",
        d,
        "--init",
        "1,2,0.5,0.1,1.5,1.5",
    ]);
    let err = bad_input(&[
        "fit",
        "--model",
        "maxwell",
        "--data",
        d,
        "--init",
        "1,0,0.5,0.1,1.5,1",
    ]);
    assert!(err.contains("--p1"), "{err}");
    bad_input(&["fit", "--model", "shc", "--data", d, "--format", "csv"]);
}

#[test]
fn fit_from_an_initial_set_alone_is_deterministic() {
    let data = synthetic();
    let d = data.to_str().unwrap();
    let run = || {
        let o = bwcl(&[
            "fit",
            "--model",
            "shc",
            "--data",
            d,
            "--starts",
            "0",
            "--init",
            DSS,
            "--max-iter",
            "30",
            "--format",
            "json",
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
        let v: Value = serde_json::from_slice(&o.stdout).unwrap();
        (
            v["J"].as_f64().unwrap(),
            v["base"].as_str().unwrap().to_string(),
        )
    };
    let (j1, b1) = run();
    let (j2, b2) = run();
    assert_eq!((j1, &b1), (j2, &b2));
    // never worse than the start
    let p = NdParams::<f64>::parse(ModelKind::Shc, DSS).unwrap();
    let j0 = cost(
        ModelKind::Shc,
        &p,
        &CorData::read(&data).unwrap(),
        &FloatOptions::default(),
    );
    assert!(j1 <= j0, "{j1} > {j0}");
}
