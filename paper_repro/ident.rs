//! Issue #31, item 5: the Table 1 DSS synthetic case worked through — which parameters the
//! data determine. The distinct minima of the multi-start fit, the likelihood-ratio profiles
//! of J, and the proved feasible sets (`bwcl identify`) in the (σ_b, κ) and (Γ_b, B_b) planes,
//! each from the CoRs alone and with the contact durations (`synthetic_dss_tc.csv`).

use crate::plot::{Chart, Series, save_grid};
use bwcl::fit::chi2::chi2_quantile;
use bwcl::fit::cost::model_point;
use bwcl::fit::profile::{Profile, profile};
use bwcl::fit::space::NAMES;
use bwcl::fit::{CorData, FitOptions, FitResult, Weights, fit};
use bwcl::identify::setup::{Spec, problem};
use bwcl::identify::{Options, Paving, Status, pave};
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::FloatOptions;
use bwcl::observables::decimal::{Rounding, directed};
use inari::Interval;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The generating set of both data files.
const DSS: [f64; 6] = [1.43, -1.42, 0.632, 0.00715, 1.31, 1.27];
/// Bounded errors for the pavings: 4 σ_noise (e: 0.005, tc: 0.01).
pub const E_ERROR: f64 = 0.02;
pub const TC_ERROR: f64 = 0.04;
/// The profiles' grids (the 6-D box, widened to hold the CoR-only minima).
const PROFILE_RANGES: [(f64, f64); 6] = [
    (0.5, 3.0),
    (-2.0, 1.5),
    (0.5, 0.8),
    (0.001, 0.08),
    (1.05, 3.0),
    (1.0, 1.6),
];

/// One data set: the CoRs alone, or with the durations.
pub struct Case {
    pub label: &'static str,
    pub file: &'static str,
    pub fit: FitResult,
    pub fit_seconds: f64,
    pub profiles: Vec<Profile>,
    pub profile_seconds: f64,
    pub planes: Vec<Plane>,
}

/// The paving of one plane, the others fixed at the generating values.
pub struct Plane {
    /// (x, y) parameter indices.
    pub axes: (usize, usize),
    pub bounds: &'static str,
    pub start: Vec<Interval>,
    pub paving: Paving,
    /// The free parameters' order in the paving (indices).
    pub free: Vec<usize>,
    /// Cell centres of a `grid`² grid where the f64 residuals are all within the errors, as
    /// (x, y) in the order of `axes`.
    pub sampled: Vec<(f64, f64)>,
    pub grid: usize,
}

pub struct Ident {
    pub cases: Vec<Case>,
    pub resolution: f64,
    pub seconds_per_paving: f64,
    pub starts: usize,
    pub profile_points: usize,
}

fn data_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("paper_repro/data")
        .join(name)
}

const PLANES: [((usize, usize), &str); 2] = [
    ((3, 2), "sigma_b=0.001..0.1,kappa=0.4..0.8"),
    ((1, 0), "Gamma_b=-1.6..1,B_b=0.8..1.6"),
];

/// Runs everything: `quick` shrinks the grids and budgets (for the test of `paper-repro`).
pub fn run(quick: bool, seconds: f64) -> Result<Ident, String> {
    let resolution = if quick { 8.0 } else { 128.0 };
    let mut cases = Vec::new();
    for (label, file, with_tc) in [
        ("CoRs alone", "synthetic_dss.csv", false),
        ("CoRs and contact durations", "synthetic_dss_tc.csv", true),
    ] {
        let path = data_path(file);
        let mut data = CorData::read(&path).map_err(|e| e.to_string())?;
        // fit: the CoRs with unit weights (the paper's J); with durations, each residual
        // divided by its error (e: σ_noise = 0.005, tc: the tc_sigma column)
        let weights = if with_tc {
            Weights::new(&data, Some(0.005), None, true)?
        } else {
            Weights::unit(&data)
        };
        let mut opts = FitOptions {
            starts: if quick { 2 } else { 8 },
            seed: 1,
            max_iter: if quick { 30 } else { 300 },
            weights: Some(weights.clone()),
            ..FitOptions::default()
        };
        // as `bwcl fit` and `bwcl profile`: a set whose integration needs more steps (far out
        // on a profile's grid) counts as not evaluable instead of costing seconds
        opts.float.ode.max_steps = opts.float.ode.max_steps.min(50_000);
        eprintln!("identifiability ({label}): fit, {} starts…", opts.starts);
        let t = Instant::now();
        let res = fit(ModelKind::Shc, &data, &opts, None)?;
        let fit_seconds = t.elapsed().as_secs_f64();
        eprintln!("identifiability ({label}): profiles of the six parameters…");
        let t = Instant::now();
        let points = if quick { 3 } else { 9 };
        let popts = FitOptions {
            max_iter: if quick { 20 } else { 200 },
            ..opts.clone()
        };
        let mut profiles = Vec::new();
        for (i, &range) in PROFILE_RANGES.iter().enumerate() {
            profiles.push(profile(
                ModelKind::Shc,
                &data,
                &weights,
                &res.map,
                &res.best.base,
                res.best.j,
                i,
                range,
                points,
                &popts,
                res.stats.s2,
                None,
            )?);
        }
        let profile_seconds = t.elapsed().as_secs_f64();
        // the pavings: bounded errors of 4 σ
        if with_tc {
            data.tc_sigma = Some(vec![TC_ERROR; data.len()]);
        }
        let mut planes = Vec::new();
        for (axes, bounds) in PLANES {
            eprintln!(
                "identifiability ({label}): paving {bounds} to 1/{resolution} (≤ {seconds} s)…"
            );
            let spec = Spec {
                base: Some(crate::DSS),
                bounds: Some(bounds),
                error: Some(E_ERROR),
                tc_error: None,
                no_tc: !with_tc,
                ..Spec::default()
            };
            let (prob, start) = problem(ModelKind::Shc, &data, &spec)?;
            let mut po = Options::new(&start, resolution);
            po.taylor.deadline = Some(Instant::now() + Duration::from_secs_f64(seconds));
            let paving = pave(&prob, &start, &po, None);
            let free = prob.space.free();
            let grid = if quick { 8 } else { 96 };
            let sampled = sample(&data, with_tc, &start, &free, axes, grid);
            planes.push(Plane {
                axes,
                bounds,
                start,
                paving,
                free,
                sampled,
                grid,
            });
        }
        cases.push(Case {
            label,
            file,
            fit: res,
            fit_seconds,
            profiles,
            profile_seconds,
            planes,
        });
    }
    Ok(Ident {
        cases,
        resolution,
        seconds_per_paving: seconds,
        starts: if quick { 2 } else { 8 },
        profile_points: if quick { 3 } else { 9 },
    })
}

/// The centres of a grid² grid over `start` where every f64 residual is within its error.
fn sample(
    data: &CorData,
    with_tc: bool,
    start: &[Interval],
    free: &[usize],
    axes: (usize, usize),
    grid: usize,
) -> Vec<(f64, f64)> {
    let opts = FloatOptions::default();
    let mut out = Vec::new();
    for a in 0..grid {
        for b in 0..grid {
            let x = |k: usize, i: usize| {
                let s = start[k];
                s.inf() + (i as f64 + 0.5) / grid as f64 * s.wid()
            };
            let mut p = DSS;
            p[free[0]] = x(0, a);
            p[free[1]] = x(1, b);
            if p[1].abs() >= p[0] {
                continue;
            }
            let base = NdParams {
                b: p[0],
                gamma: p[1],
                kappa: p[2],
                sigma: p[3],
                n: p[4],
                p: p[5],
            };
            let ok = (0..data.len()).all(|i| {
                let Ok((e, tc)) = model_point(ModelKind::Shc, &base, data.v0[i], &opts) else {
                    return false;
                };
                (e - data.e[i]).abs() <= E_ERROR
                    && (!with_tc
                        || (tc - data.tc.as_ref().expect("a tc column")[i]).abs() <= TC_ERROR)
            });
            if ok {
                out.push((p[axes.0], p[axes.1]));
            }
        }
    }
    out
}

fn plane_hull(p: &Plane) -> Option<Vec<(f64, f64)>> {
    p.paving.hull()
}

/// (x, y) of a paving's box in the plane's axes order.
fn xy(p: &Plane, lo: &[f64], hi: &[f64]) -> (f64, f64, f64, f64) {
    let k = |i: usize| p.free.iter().position(|&f| f == i).expect("a free axis");
    let (kx, ky) = (k(p.axes.0), k(p.axes.1));
    (lo[kx], lo[ky], hi[kx], hi[ky])
}

fn range_of(p: &Plane, i: usize) -> (f64, f64) {
    let k = p.free.iter().position(|&f| f == i).expect("a free axis");
    (p.start[k].inf(), p.start[k].sup())
}

/// CSVs and the two figures.
pub fn write(out: &Path, id: &Ident) -> Result<Vec<String>, String> {
    let mut files = Vec::new();
    let mut minima =
        String::from("data,minimum,J,delta_chi2,starts,B_b,Gamma_b,kappa,sigma_b,n,p\n");
    let mut prof = String::from("data,parameter,value,J,delta_chi2\n");
    let mut boxes = String::from("data,plane,x_lo,x_hi,y_lo,y_hi,status\n");
    for c in &id.cases {
        for (k, m) in c.fit.minima.iter().enumerate() {
            let p = m.base.as_array();
            writeln!(
                minima,
                "{},{},{},{},{},{},{},{},{},{},{}",
                c.label,
                k + 1,
                m.j,
                m.delta_chi2,
                m.starts.len(),
                p[0],
                p[1],
                p[2],
                p[3],
                p[4],
                p[5]
            )
            .unwrap();
        }
        for pr in &c.profiles {
            for q in &pr.points {
                writeln!(
                    prof,
                    "{},{},{},{},{}",
                    c.label, pr.name, q.value, q.j, q.delta_chi2
                )
                .unwrap();
            }
        }
        for p in &c.planes {
            let plane = format!("{}-{}", NAMES[p.axes.0], NAMES[p.axes.1]);
            for b in &p.paving.boxes {
                let (x0, y0, x1, y1) = xy(p, &b.lo, &b.hi);
                let st = match b.status {
                    Status::Feasible => "feasible",
                    Status::Infeasible => "infeasible",
                    Status::Undecided => "undecided",
                };
                // the boxes' ends are the doubles the paving used (exact binary values)
                writeln!(
                    boxes,
                    "{},{plane},{x0:e},{x1:e},{y0:e},{y1:e},{st}",
                    c.label
                )
                .unwrap();
            }
        }
    }
    for (name, text) in [
        ("ident_minima.csv", &minima),
        ("ident_profiles.csv", &prof),
        ("ident_pavings.csv", &boxes),
    ] {
        let p = out.join(name);
        std::fs::write(&p, text).map_err(|e| format!("writing '{}': {e}", p.display()))?;
        files.push(p.display().to_string());
    }
    // the profiles: Δχ² along each parameter, both data sets
    let thr = chi2_quantile(1, 0.95);
    let mut charts = Vec::new();
    for i in 0..6 {
        let (lo, hi) = PROFILE_RANGES[i];
        let mut series = Vec::new();
        let mut top: f64 = 2.0 * thr;
        for (c, g) in id.cases.iter().zip([20u8, 140]) {
            let pts: Vec<(f64, f64)> = c.profiles[i]
                .points
                .iter()
                .map(|q| (q.value, q.delta_chi2))
                .collect();
            top = top.max(pts.iter().map(|p| p.1).fold(0.0, f64::max).min(60.0));
            series.push(Series::Line {
                label: c.label.to_string(),
                grey: g,
                dashed: false,
                points: pts.clone(),
            });
            series.push(Series::Marks {
                label: String::new(),
                grey: g,
                filled: true,
                points: pts,
            });
        }
        series.push(Series::Line {
            label: format!("χ²_0.95(1) = {thr:.2}"),
            grey: 100,
            dashed: true,
            points: vec![(lo, thr), (hi, thr)],
        });
        series.push(Series::Marks {
            label: "generating".into(),
            grey: 0,
            filled: false,
            points: vec![(DSS[i], 0.0)],
        });
        charts.push(Chart {
            title: format!("profile of {}", NAMES[i]),
            x_label: NAMES[i].into(),
            y_label: "Δχ² (others re-optimized)".into(),
            x_range: (lo, hi),
            y_range: (-0.5, top * 1.05),
            series,
            legend_left: false,
        });
    }
    files.extend(save_grid(&charts, 3, &out.join("ident_profiles"))?);
    // the pavings
    let mut charts = Vec::new();
    for c in &id.cases {
        for p in &c.planes {
            let rects = |s: Status| -> Vec<(f64, f64, f64, f64)> {
                p.paving
                    .boxes
                    .iter()
                    .filter(|b| b.status == s)
                    .map(|b| xy(p, &b.lo, &b.hi))
                    .collect()
            };
            let series = vec![
                Series::Rects {
                    label: "proved infeasible".into(),
                    grey: 235,
                    rects: rects(Status::Infeasible),
                },
                Series::Rects {
                    label: "undecided".into(),
                    grey: 160,
                    rects: rects(Status::Undecided),
                },
                Series::Rects {
                    label: "proved feasible".into(),
                    grey: 60,
                    rects: rects(Status::Feasible),
                },
                Series::Marks {
                    label: "f64-sampled feasible".into(),
                    grey: 0,
                    filled: true,
                    points: p.sampled.clone(),
                },
                Series::Marks {
                    label: "generating P*".into(),
                    grey: 0,
                    filled: false,
                    points: vec![(DSS[p.axes.0], DSS[p.axes.1])],
                },
            ];
            charts.push(Chart {
                title: format!("{}: {} × {}", c.label, NAMES[p.axes.0], NAMES[p.axes.1]),
                x_label: NAMES[p.axes.0].into(),
                y_label: NAMES[p.axes.1].into(),
                x_range: range_of(p, p.axes.0),
                y_range: range_of(p, p.axes.1),
                series,
                legend_left: false,
            });
        }
    }
    files.extend(save_grid(&charts, 2, &out.join("ident_pavings"))?);
    Ok(files)
}

fn f4(x: f64) -> String {
    format!("{x:.4}")
}

/// The REPORT.md section.
pub fn render(r: &mut String, id: &Ident) {
    writeln!(
        r,
        "## Identifiability (issue #31): what the synthetic DSS data determine\n\n\
         The data of the fit above (`synthetic_dss.csv`) and the same CoRs with contact durations \
         (`synthetic_dss_tc.csv`: tc = T_s(𝓟(P*, v0))·v0^(−(p−1)/(p+1)), in units of T_c(1 m/s), \
         Gaussian noise 0.01). Fits: {} seeded starts, clustered into distinct minima \
         (hill–valley test); with durations every residual is divided by its error (e: 0.005, \
         tc: 0.01). Profiles: J re-optimized over the other five parameters on {} grid points \
         per parameter. Pavings: `bwcl identify` with bounded errors of 4 σ_noise (e ± {E_ERROR}, \
         tc ± {TC_ERROR}), the other four parameters at the generating values, resolution \
         1/{} of each side, at most {:.0} s each; beside them the cells of a grid whose f64 \
         residuals all lie within the errors (a sample of F, not a proof). Figures: \
         `ident_profiles.svg/.png`, `ident_pavings.svg/.png`; data: `ident_minima.csv`, \
         `ident_profiles.csv`, `ident_pavings.csv`.\n",
        id.starts, id.profile_points, id.resolution, id.seconds_per_paving
    )
    .unwrap();
    writeln!(r, "### Distinct minima\n").unwrap();
    writeln!(
        r,
        "| data | minimum | J | Δχ² | starts | B_b | Γ_b | κ | σ_b | n | p |\n|---|---|---|---|---|---|---|---|---|---|---|"
    )
    .unwrap();
    for c in &id.cases {
        for (k, m) in c.fit.minima.iter().enumerate() {
            let p = m.base.as_array();
            writeln!(
                r,
                "| {} | {} | {} | {:.2} | {} | {} | {} | {} | {:.5} | {} | {} |",
                c.label,
                k + 1,
                f4(m.j),
                m.delta_chi2,
                m.starts.len(),
                f4(p[0]),
                f4(p[1]),
                f4(p[2]),
                p[3],
                f4(p[4]),
                f4(p[5])
            )
            .unwrap();
        }
    }
    writeln!(
        r,
        "| generating | | | | | 1.43 | −1.42 | 0.632 | 0.00715 | 1.31 | 1.27 |\n"
    )
    .unwrap();
    for c in &id.cases {
        let within = c.fit.minima.iter().filter(|m| m.indistinguishable).count();
        writeln!(
            r,
            "- {} (`{}`): {} distinct minima, {} of them within χ²_0.95(6) of the best (fit {:.1} s).",
            c.label,
            c.file,
            c.fit.minima.len(),
            within,
            c.fit_seconds
        )
        .unwrap();
    }
    writeln!(r, "\n### Profiles: 95 % likelihood-ratio intervals\n").unwrap();
    writeln!(
        r,
        "| parameter | generating | {} | {} |\n|---|---|---|---|",
        id.cases[0].label, id.cases[1].label
    )
    .unwrap();
    for i in 0..6 {
        let iv = |c: &Case| {
            let p = &c.profiles[i];
            let end = |e: &bwcl::fit::profile::End, open: &str| {
                if e.open {
                    open.to_string()
                } else {
                    format!("{:.4}", e.value)
                }
            };
            format!(
                "[{}, {}]",
                end(&p.lo, &format!("≤ {:.4} (open)", p.lo.value)),
                end(&p.hi, &format!("≥ {:.4} (open)", p.hi.value))
            )
        };
        writeln!(
            r,
            "| {} | {} | {} | {} |",
            NAMES[i],
            DSS[i],
            iv(&id.cases[0]),
            iv(&id.cases[1])
        )
        .unwrap();
    }
    writeln!(
        r,
        "\n\"open\": the profile stays below the threshold up to the grid's end (the grid is the \
         range in the column header of `ident_profiles.csv`). Profiles took {:.0} s and {:.0} s.\n",
        id.cases[0].profile_seconds, id.cases[1].profile_seconds
    )
    .unwrap();
    writeln!(r, "### Proved feasible sets\n").unwrap();
    writeln!(
        r,
        "| data | plane | boxes | infeasible | undecided | feasible | proved hull of F | hull of the f64 sample | seconds | complete |\n|---|---|---|---|---|---|---|---|---|---|"
    )
    .unwrap();
    for c in &id.cases {
        for p in &c.planes {
            let sh = p.paving.shares(&p.start);
            let hull = |h: Option<Vec<(f64, f64)>>| match h {
                None => "∅ (F proved empty)".to_string(),
                Some(h) => p
                    .free
                    .iter()
                    .zip(h)
                    .map(|(&i, (a, b))| format!("{} ∈ [{}, {}]", NAMES[i], down(a), up(b)))
                    .collect::<Vec<_>>()
                    .join(", "),
            };
            let sample = if p.sampled.is_empty() {
                "no sampled point".to_string()
            } else {
                let (mut x, mut y) = ((f64::MAX, f64::MIN), (f64::MAX, f64::MIN));
                for &(a, b) in &p.sampled {
                    x = (x.0.min(a), x.1.max(a));
                    y = (y.0.min(b), y.1.max(b));
                }
                format!(
                    "{} ∈ [{:.4}, {:.4}], {} ∈ [{:.4}, {:.4}] ({}² cell centres)",
                    NAMES[p.axes.0], x.0, x.1, NAMES[p.axes.1], y.0, y.1, p.grid
                )
            };
            writeln!(
                r,
                "| {} | `{}` | {} | {:.1} % | {:.1} % | {:.1} % | {} | {} | {:.0} | {} |",
                c.label,
                p.bounds,
                p.paving.boxes.len(),
                100.0 * sh[1],
                100.0 * sh[2],
                100.0 * sh[0],
                hull(plane_hull(p)),
                sample,
                p.paving.seconds,
                match &p.paving.stopped {
                    None => "yes".to_string(),
                    Some(why) => format!("no: {why}"),
                }
            )
            .unwrap();
        }
    }
    writeln!(
        r,
        "\nThe proved hull is an outer bound: every P* of the plane consistent with the data lies \
         in it; the f64 sample is an inner estimate. The hull's ends are printed rounded \
         outward. In the (Γ_b, B_b) plane the boxes that cross |Γ_b| = B_b, the boundary of 𝓟, \
         cannot be given to the engines and stay undecided at the resolution (the thin diagonal \
         lines of `ident_pavings`): they carry the proved hull to the corners of the box.\n"
    )
    .unwrap();
}

/// x rounded down to 6 significant digits (a decimal ≤ x, compared as rationals).
fn down(x: f64) -> String {
    directed(x, 6, Rounding::Down).map_or(format!("{x}"), |d| d.text())
}

/// x rounded up to 6 significant digits (a decimal ≥ x).
fn up(x: f64) -> String {
    directed(x, 6, Rounding::Up).map_or(format!("{x}"), |d| d.text())
}
