//! Issue #31, the fit side: weighted residuals, --fix/--bounds, the clustered minima, the
//! uncertainty (Jacobian, covariance) and the profile, checked against finite differences and
//! brute force on a two-parameter case (κ and σ_b free, the others at the generating values).

use bwcl::fit::cost::{model_cor, model_point, weighted_cost};
use bwcl::fit::nelder_mead::{FitOptions, fit};
use bwcl::fit::profile::profile;
use bwcl::fit::reparam::SpaceMap;
use bwcl::fit::space::{Slot, Space};
use bwcl::fit::uncertainty::{JacobianMethod, central_column, uncertainty};
use bwcl::fit::{CorData, Weights};
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::FloatOptions;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::Value;
use std::path::PathBuf;

use crate::common;
use common::bwcl;

const K: ModelKind = ModelKind::Shc;
const DSS: [f64; 6] = [1.43, -1.42, 0.632, 0.00715, 1.31, 1.27];

fn dss() -> NdParams<f64> {
    NdParams::new(K, DSS[0], DSS[1], DSS[2], DSS[3], DSS[4], DSS[5]).unwrap()
}

fn synthetic() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("paper_repro/data/synthetic_dss.csv")
}

fn scratch(name: &str, content: &str) -> PathBuf {
    let p = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("bwcl-fitu-{}-{name}", std::process::id()));
    std::fs::write(&p, content).unwrap();
    p
}

fn text(b: &[u8]) -> String {
    String::from_utf8(b.to_vec()).unwrap()
}

/// Data from the model itself at 10 speeds, with Gaussian noise of size `noise` (seeded).
fn model_data(noise: f64, seed: u64) -> CorData {
    let v0: Vec<f64> = (0..10).map(|i| 0.1 + 0.5 * i as f64).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let e: Vec<f64> = model_cor(K, &dss(), &v0, &FloatOptions::default())
        .into_iter()
        .map(|e| {
            let (a, b): (f64, f64) = (rng.random(), rng.random());
            let g = (-2.0 * (1.0 - a).ln()).sqrt() * (std::f64::consts::TAU * b).cos();
            (e.unwrap() + noise * g).clamp(0.0, 1.0)
        })
        .collect();
    CorData::new(v0, e).unwrap()
}

/// κ and σ_b free (σ_b within bounds when asked), the others fixed at the generating values.
fn two_free(bounds: Option<(f64, f64)>) -> Space {
    let mut s = Space::unbounded(K);
    for i in [0, 1, 4, 5] {
        s.slots[i] = Slot::Fixed(DSS[i]);
    }
    if let Some((lo, hi)) = bounds {
        s.slots[3] = Slot::Free { lo, hi };
    }
    s
}

fn with(kappa: f64, sigma: f64) -> NdParams<f64> {
    NdParams::new(K, DSS[0], DSS[1], kappa, sigma, DSS[4], DSS[5]).unwrap()
}

fn fit2(data: &CorData) -> bwcl::fit::FitResult {
    let opts = FitOptions {
        starts: 2,
        space: Some(two_free(None)),
        ..FitOptions::default()
    };
    fit(K, data, &opts, None).unwrap()
}

#[test]
fn jacobian_matches_central_differences_and_covariance_is_s2_inverse_jtj() {
    for noise in [0.0, 0.005] {
        let data = model_data(noise, 7);
        let w = Weights::unit(&data);
        let res = fit2(&data);
        let best = res.best.base.clone();
        let free = [2, 3];
        let u = uncertainty(
            K,
            &best,
            &free,
            &data,
            &w,
            res.stats.s2,
            JacobianMethod::Proved,
            &FloatOptions::default(),
        )
        .unwrap();
        assert_eq!(u.jacobian_source, vec!["proved", "proved"], "{noise}");
        for (c, &i) in free.iter().enumerate() {
            let (cd, how) =
                central_column(K, &best, i, &data, &w, &FloatOptions::default()).unwrap();
            assert_eq!(how, "central");
            // the central differences are the less accurate side: DOP853's global error at
            // rtol 1e-13 (~1e-12) over h = 1e-5 max(|x|, 1e-2) ≥ 1e-7 is up to ~1e-5 of an
            // entry; the proved midpoints are exact to ~1e-8
            let norm = cd.iter().map(|x| x * x).sum::<f64>().sqrt();
            for (r, row) in u.jacobian.iter().enumerate() {
                let d = (row[c] - cd[r]).abs();
                assert!(
                    d <= 5e-6 * norm,
                    "noise {noise}, column {i}, row {r}: {} vs {} (norm {norm})",
                    row[c],
                    cd[r]
                );
            }
        }
        // C = s² (JᵀJ)⁻¹, the 2×2 inverse by hand
        let (mut a, mut b, mut d) = (0.0, 0.0, 0.0);
        for row in &u.jacobian {
            a += row[0] * row[0];
            b += row[0] * row[1];
            d += row[1] * row[1];
        }
        let det = a * d - b * b;
        let s2 = if noise == 0.0 {
            res.best.j * res.best.j / 8.0
        } else {
            res.stats.s2
        };
        assert_eq!(u.s2, res.stats.s2);
        assert!((res.stats.s2 - res.best.j.powi(2) / 8.0).abs() <= 1e-15 + 1e-12 * s2);
        let want = [[d / det, -b / det], [-b / det, a / det]];
        for (r, row) in want.iter().enumerate() {
            for (c, &x) in row.iter().enumerate() {
                let w = u.s2 * x;
                assert!(
                    (u.covariance[r][c] - w).abs() <= 1e-8 * w.abs().max(1e-300),
                    "{noise}: C[{r}][{c}] = {} vs {w}",
                    u.covariance[r][c]
                );
            }
            assert!((u.std_errors[r] - u.covariance[r][r].sqrt()).abs() <= 1e-15);
        }
        assert!((u.correlation[0][1] - (-b / (a * d).sqrt())).abs() < 1e-8);
    }
}

#[test]
fn profile_agrees_with_a_brute_force_grid_and_the_covariance() {
    let data = model_data(0.005, 11);
    let w = Weights::unit(&data);
    let res = fit2(&data);
    let best = res.best.base.clone();
    let u = uncertainty(
        K,
        &best,
        &[2, 3],
        &data,
        &w,
        res.stats.s2,
        JacobianMethod::Proved,
        &FloatOptions::default(),
    )
    .unwrap();
    let map = SpaceMap::new(two_free(None));
    let (se_k, se_s) = (u.std_errors[0], u.std_errors[1]);
    let rho = u.correlation[0][1];
    // σ_b's conditional mean and SE given κ, from the covariance alone (κ and σ_b are strongly
    // correlated: the valley is narrow across and must be gridded along its own line)
    let centre = |k: f64| best.sigma + rho * se_s / se_k * (k - best.kappa);
    let half = 8.0 * se_s * (1.0 - rho * rho).sqrt().max(1e-3);
    let range = (best.kappa - 3.0 * se_k, best.kappa + 3.0 * se_k);
    let opts = FitOptions::default();
    let pr = profile(
        K,
        &data,
        &w,
        &map,
        &best,
        res.best.j,
        2,
        range,
        7,
        &opts,
        res.stats.s2,
        None,
    )
    .unwrap();
    assert_eq!(pr.points.len(), 7);
    // brute force: at each profile κ, J on a fine σ_b grid across the valley (8 conditional
    // SEs each side of the profile's σ_b) is never below the profile's J: the re-optimization
    // found the valley's bottom; and J at the profile's own point is its J
    let o = FloatOptions::default();
    let mut grid_min = f64::INFINITY;
    for p in &pr.points {
        let own = p.p_star[3];
        assert_eq!(weighted_cost(K, &with(p.value, own), &data, &w, &o), p.j);
        let sigmas: Vec<f64> = (0..=400)
            .map(|g| own + (g as f64 / 200.0 - 1.0) * half)
            .filter(|&s| s > 0.0)
            .collect();
        let jg = sigmas
            .iter()
            .map(|&s| weighted_cost(K, &with(p.value, s), &data, &w, &o))
            .fold(f64::INFINITY, f64::min);
        grid_min = grid_min.min(jg);
        assert!(
            p.j <= jg + 1e-9,
            "κ = {}: profile {} > grid {jg}",
            p.value,
            p.j
        );
    }
    // the grid around the regression line through the best point: its minimum is the profile's
    let line_min = (0..=60)
        .flat_map(|a| (0..=40).map(move |b| (a, b)))
        .map(|(a, b)| {
            let k = best.kappa + (a as f64 / 30.0 - 1.0) * 0.3 * se_k;
            let s = centre(k) + (b as f64 / 20.0 - 1.0) * half;
            if s > 0.0 {
                weighted_cost(K, &with(k, s), &data, &w, &o)
            } else {
                f64::INFINITY
            }
        })
        .fold(f64::INFINITY, f64::min);
    assert!(line_min >= pr.j_min - 1e-12, "{line_min} < {}", pr.j_min);
    assert!(
        line_min - pr.j_min <= 1e-3 * pr.j_min,
        "{line_min} vs {}",
        pr.j_min
    );
    // the profile's minimum is the fit's (and the grid's, to its resolution)
    assert!(
        (pr.j_min - res.best.j).abs() <= 1e-6 * res.best.j,
        "{} {}",
        pr.j_min,
        res.best.j
    );
    assert!(grid_min >= pr.j_min - 1e-12);
    // a near-linear problem: the LR interval is close to best ± 1.96 SE
    assert!(!pr.lo.open && !pr.hi.open, "{:?} {:?}", pr.lo, pr.hi);
    for (end, want) in [
        (pr.lo.value, best.kappa - 1.96 * se_k),
        (pr.hi.value, best.kappa + 1.96 * se_k),
    ] {
        assert!(
            (end - want).abs() <= 0.3 * 1.96 * se_k,
            "end {end} vs {want} (SE {se_k})"
        );
    }
    // a narrow grid: the interval is open on both sides
    let narrow = (best.kappa - 0.2 * se_k, best.kappa + 0.2 * se_k);
    let pr = profile(
        K,
        &data,
        &w,
        &map,
        &best,
        res.best.j,
        2,
        narrow,
        3,
        &opts,
        res.stats.s2,
        None,
    )
    .unwrap();
    assert!(pr.lo.open && pr.hi.open);
    assert_eq!(pr.hi.value, narrow.1);
}

#[test]
fn identical_starts_make_one_cluster_and_bounds_hold() {
    let data = model_data(0.005, 3);
    let start = with(0.6, 0.01);
    let opts = FitOptions {
        starts: 0,
        initial: vec![start.clone(), start],
        space: Some(two_free(Some((0.001, 0.1)))),
        ..FitOptions::default()
    };
    let res = fit(K, &data, &opts, None).unwrap();
    assert_eq!(res.minima.len(), 1, "{:?}", res.minima);
    assert_eq!(res.minima[0].starts.len(), 2);
    let b = &res.best.base;
    assert!(b.sigma >= 0.001 && b.sigma <= 0.1);
    assert_eq!([b.b, b.gamma, b.n, b.p], [DSS[0], DSS[1], DSS[4], DSS[5]]);
    // bounds that exclude the optimum: the result sits at the bound and says so
    let opts = FitOptions {
        starts: 2,
        space: Some(two_free(Some((0.02, 0.1)))),
        ..FitOptions::default()
    };
    let res = fit(K, &data, &opts, None).unwrap();
    assert!(res.best.base.sigma >= 0.02);
    assert_eq!(res.best.at_bound, vec!["sigma_b"]);
    assert_eq!(res.minima[0].at_bound, vec!["sigma_b"]);
}

#[test]
fn contact_durations_join_the_residuals() {
    let data = model_data(0.0, 1);
    let o = FloatOptions::default();
    let tc: Vec<f64> = data
        .v0
        .iter()
        .map(|&v| model_point(K, &dss(), v, &o).unwrap().1)
        .collect();
    let shifted: Vec<f64> = tc.iter().map(|t| t * 1.01).collect();
    let d = data
        .clone()
        .with_columns(None, Some(shifted), None)
        .unwrap();
    let w = Weights::new(&d, Some(0.01), Some(0.02), true).unwrap();
    assert_eq!(w.residual_count(), 20);
    let j = weighted_cost(K, &dss(), &d, &w, &o);
    let hand = tc
        .iter()
        .map(|t| (0.01 * t / 0.02).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!((j - hand).abs() <= 1e-9 * hand, "{j} vs {hand}");
    // the Jacobian of the durations' rows, p's column with the chain rule through
    // v0^(−(p−1)/(p+1)), against central differences
    let u = uncertainty(K, &dss(), &[5], &d, &w, 1.0, JacobianMethod::Proved, &o).unwrap();
    assert_eq!(u.jacobian_source, vec!["proved"]);
    let (cd, _) = central_column(K, &dss(), 5, &d, &w, &o).unwrap();
    let norm = cd.iter().map(|x| x * x).sum::<f64>().sqrt();
    for (r, row) in u.jacobian.iter().enumerate() {
        assert!(
            (row[0] - cd[r]).abs() <= 1e-6 * norm,
            "row {r}: {} vs {}",
            row[0],
            cd[r]
        );
    }
}

/// Bad input: exit 2, one stderr line, nothing on stdout.
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
fn bad_fit_and_profile_options_get_one_line() {
    let s = synthetic();
    let d = s.to_str().unwrap();
    let fit = |extra: &[&str]| {
        let mut a = vec!["fit", "--model", "shc", "--data", d];
        a.extend_from_slice(extra);
        bad_input(&a)
    };
    assert!(fit(&["--fix", "zeta=1"]).contains("zeta"));
    assert!(fit(&["--bounds", "kappa=0.8..0.4"]).contains("kappa"));
    assert!(fit(&["--bounds", "kappa=0.4..1.2"]).contains("𝓟"));
    assert!(fit(&["--error", "0"]).contains("--error"));
    assert!(fit(&["--error", "-1"]).contains("--error"));
    assert!(fit(&["--tc-error", "0.1"]).contains("tc"));
    let all = "B_b=1.43,Gamma_b=-1.42,kappa=0.6,sigma_b=0.007,n=1.3,p=1.27";
    assert!(fit(&["--fix", all]).contains("nothing to fit"));
    let tc = scratch("tc.csv", "v0,e,tc\n0.5,0.8,1.1\n1,0.7,1.0\n");
    let t = tc.to_str().unwrap();
    let err = bad_input(&["fit", "--model", "shc", "--data", t]);
    assert!(err.contains("--tc-error"), "{err}");
    let prof = |extra: &[&str]| {
        let mut a = vec!["profile", "--model", "shc", "--data", d];
        a.extend_from_slice(extra);
        bad_input(&a)
    };
    assert!(prof(&["--param", "zeta"]).contains("zeta"));
    assert!(prof(&["--param", "kappa", "--fix", "kappa=0.6"]).contains("fixed"));
    prof(&["--points", "2"]);
    prof(&["--points", "5000"]);
    prof(&["--points", "-3"]);
}

#[test]
fn the_default_fit_shows_several_minima_on_the_synthetic_data() {
    let s = synthetic();
    let o = bwcl(&[
        "fit",
        "--model",
        "shc",
        "--data",
        s.to_str().unwrap(),
        "--format",
        "json",
        "--uncertainty",
        "--jacobian",
        "central",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let minima = v["minima"].as_array().unwrap();
    assert!(minima.len() >= 2, "{minima:?}");
    let within: Vec<&Value> = minima
        .iter()
        .filter(|m| m["indistinguishable"].as_bool().unwrap())
        .collect();
    assert!(within.len() >= 2);
    assert_eq!(v["indistinguishable"].as_u64(), Some(within.len() as u64));
    // the non-uniqueness of the table: Γ_b of both signs, n over a wide range
    let g: Vec<f64> = within
        .iter()
        .map(|m| m["P_star"]["Gamma"].as_f64().unwrap())
        .collect();
    let n: Vec<f64> = within
        .iter()
        .map(|m| m["P_star"]["n"].as_f64().unwrap())
        .collect();
    assert!(
        g.iter().any(|&x| x > 0.0) && g.iter().any(|&x| x < 0.0),
        "{g:?}"
    );
    assert!(
        n.iter().cloned().fold(0.0, f64::max)
            > 3.0 * n.iter().cloned().fold(f64::INFINITY, f64::min),
        "{n:?}"
    );
    // basin sizes add up to the starts
    let total: u64 = minima
        .iter()
        .map(|m| m["basin_size"].as_u64().unwrap())
        .sum();
    assert_eq!(total, 8);
    let warn = text(&o.stderr);
    assert!(
        warn.contains(&format!(
            "the data do not determine P*: {} minima within the noise",
            within.len()
        )),
        "{warn}"
    );
    // every minimum carries its uncertainty in JSON
    for m in minima {
        assert_eq!(m["uncertainty"]["std_errors"].as_array().unwrap().len(), 6);
    }
    assert_eq!(v["k"].as_u64(), Some(6));
    assert_eq!(v["m_res"].as_u64(), Some(20));
}

#[test]
fn weighted_j_of_the_cli_is_the_hand_computation_and_fix_is_exact() {
    let d = CorData::read(&synthetic()).unwrap();
    let mut csv = String::from("v0,e,sigma\n");
    let sig: Vec<f64> = (0..d.len()).map(|i| 0.004 + 0.0005 * i as f64).collect();
    for (i, s) in sig.iter().enumerate() {
        csv.push_str(&format!("{},{},{s}\n", d.v0[i], d.e[i]));
    }
    let f = scratch("sigma.csv", &csv);
    let o = bwcl(&[
        "fit",
        "--model",
        "shc",
        "--data",
        f.to_str().unwrap(),
        "--starts",
        "1",
        "--max-iter",
        "60",
        "--fix",
        "kappa=0.632,p=1.27",
        "--bounds",
        "sigma_b=0.001..0.02,n=1.1..1.5",
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let p = &v["P_star"];
    assert_eq!(p["kappa"].as_f64(), Some(0.632));
    assert_eq!(p["p"].as_f64(), Some(1.27));
    let sigma = p["sigma"].as_f64().unwrap();
    let n = p["n"].as_f64().unwrap();
    assert!((0.001..=0.02).contains(&sigma) && (1.1..=1.5).contains(&n));
    assert_eq!(
        v["free"],
        serde_json::json!(["B_b", "Gamma_b", "sigma_b", "n"])
    );
    assert_eq!(v["errors_given"].as_bool(), Some(true));
    assert_eq!(v["s2"].as_f64(), Some(1.0));
    let set = NdParams::new(
        K,
        p["B"].as_f64().unwrap(),
        p["Gamma"].as_f64().unwrap(),
        0.632,
        sigma,
        n,
        1.27,
    )
    .unwrap();
    let em = model_cor(K, &set, &d.v0, &FloatOptions::default());
    let hand = em
        .iter()
        .enumerate()
        .map(|(i, e)| ((d.e[i] - e.as_ref().unwrap()) / sig[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    let j = v["J"].as_f64().unwrap();
    assert!((j - hand).abs() <= 1e-12 * hand, "{j} vs {hand}");
    assert!((v["chi2"].as_f64().unwrap() - j * j).abs() <= 1e-12 * j * j);
    assert!((v["reduced_chi2"].as_f64().unwrap() - j * j / 16.0).abs() <= 1e-12 * j * j);
}

/// `profile --plot`: one panel per profiled parameter, its grid points drawn, the threshold line.
#[test]
fn profile_plot_draws_every_grid_point() {
    let s = synthetic();
    let svg = scratch("profile.svg", "");
    let o = bwcl(&[
        "profile",
        "--model",
        "shc",
        "--data",
        s.to_str().unwrap(),
        "--param",
        "kappa",
        "--points",
        "5",
        "--starts",
        "2",
        "--max-iter",
        "60",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let t = std::fs::read_to_string(&svg).unwrap();
    assert!(t.starts_with("<svg") && t.trim_end().ends_with("</svg>"));
    assert_eq!(t.matches("<polyline").count(), 1, "one panel");
    assert_eq!(t.matches("<circle").count(), 5, "five grid points");
    assert!(t.contains(">kappa<") && t.contains("stroke-dasharray"));
}
