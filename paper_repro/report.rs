//! The CSVs, the plots and REPORT.md.

use crate::Args;
use crate::cor::{self, Proved, TABLE1, model_title};
use crate::demo::Demo;
use crate::loops::{self, Loop};
use crate::plot::{Chart, Series, save};
use bwcl::fit::{FitOptions, model_curve};
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::FloatOptions;
use bwcl::observables::decimal::{Rounding, outward, sci_up, width_up};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn write(path: &Path, text: &str) -> Result<String, String> {
    std::fs::write(path, text).map_err(|e| format!("writing '{}': {e}", path.display()))?;
    Ok(path.display().to_string())
}

fn label(s: &cor::Table1Set) -> String {
    format!("{}_{}", s.kind.name(), s.data)
}

/// Fig. 3: cor_float.csv, cor_rigorous.csv, fig3_&lt;model&gt;.{svg,png} (+ _rigorous).
pub fn write_cor(
    out: &Path,
    v0: &[f64],
    curves: &[Vec<Result<f64, String>>],
    proved: Option<&Vec<Vec<Proved>>>,
) -> Result<Vec<String>, String> {
    let mut files = Vec::new();
    let mut csv = String::from("v0");
    for s in &TABLE1 {
        write!(csv, ",e_{}", label(s)).unwrap();
    }
    csv.push('\n');
    for (i, v) in v0.iter().enumerate() {
        write!(csv, "{v}").unwrap();
        for c in curves {
            match &c[i] {
                Ok(e) => write!(csv, ",{e}").unwrap(),
                Err(_) => csv.push(','),
            }
        }
        csv.push('\n');
    }
    files.push(write(&out.join("cor_float.csv"), &csv)?);
    if let Some(p) = proved {
        let mut csv = String::from("model,data,v0,e_lo,e_hi,width,seconds,reason\n");
        for (s, rows) in TABLE1.iter().zip(p) {
            for r in rows {
                match &r.e {
                    // bounds rounded outward, the width up (decimal.rs)
                    Ok((lo, hi)) => writeln!(
                        csv,
                        "{},{},{},{},{},{},{:.3},",
                        s.kind.name(),
                        s.data,
                        r.v0,
                        outward(*lo, Rounding::Down),
                        outward(*hi, Rounding::Up),
                        outward(width_up(*lo, *hi), Rounding::Up),
                        r.seconds
                    ),
                    Err(why) => writeln!(
                        csv,
                        "{},{},{},,,,{:.3},\"{}\"",
                        s.kind.name(),
                        s.data,
                        r.v0,
                        r.seconds,
                        why.replace('"', "'")
                    ),
                }
                .unwrap();
            }
        }
        files.push(write(&out.join("cor_rigorous.csv"), &csv)?);
    }
    for kind in [ModelKind::Shc, ModelKind::Maxwell] {
        let mut series = Vec::new();
        let mut bands = Vec::new();
        for (k, s) in TABLE1.iter().enumerate().filter(|(_, s)| s.kind == kind) {
            let grey = if s.data == "DSS" { 150 } else { 0 };
            let pts: Vec<(f64, f64)> = v0
                .iter()
                .zip(&curves[k])
                .filter_map(|(&v, e)| e.as_ref().ok().map(|&e| (v, e)))
                .collect();
            series.push(Series::Line {
                label: format!("{}: {} (Table 1 P*)", s.data, model_title(kind)),
                grey,
                dashed: false,
                points: pts,
            });
            if let Some(p) = proved {
                bands.push(Series::Band {
                    label: format!("{}: {} proved enclosure", s.data, model_title(kind)),
                    grey,
                    points: p[k]
                        .iter()
                        .filter_map(|r| r.e.as_ref().ok().map(|&(lo, hi)| (r.v0, lo, hi)))
                        .collect(),
                });
                let failed: Vec<(f64, f64)> = p[k]
                    .iter()
                    .filter(|r| r.e.is_err())
                    .map(|r| (r.v0, 0.52))
                    .collect();
                if !failed.is_empty() {
                    bands.push(Series::Marks {
                        label: format!("{}: not proved (v0 marked at e = 0.52)", s.data),
                        grey,
                        filled: false,
                        points: failed,
                    });
                }
            }
        }
        let name = model_title(kind);
        let chart = Chart {
            title: format!("CoR: {name}, Table 1 base sets"),
            x_label: "v0 (m/s)".into(),
            y_label: "e".into(),
            x_range: (0.0, 6.2),
            y_range: (0.5, 1.0),
            series,
            legend_left: false,
        };
        files.extend(save(&chart, &out.join(format!("fig3_{name}")))?);
        if proved.is_some() {
            let chart = Chart {
                title: format!("CoR: {name}, proved enclosures (interval Taylor)"),
                series: bands,
                ..chart
            };
            files.extend(save(&chart, &out.join(format!("fig3_{name}_rigorous")))?);
        }
    }
    Ok(files)
}

fn speed_tag(v: f64) -> String {
    format!("{v:.2}").replace('.', "_")
}

/// Fig. 4: fig4_loop_&lt;v0&gt;.csv, table2_loops.csv, fig4_RCross.{svg,png}.
pub fn write_loops(out: &Path, loops: &[Loop]) -> Result<Vec<String>, String> {
    let mut files = Vec::new();
    let mut summary = String::from(
        "v0_m_s,contact_duration_s,peak_force_N,max_compression_mm,residual_indentation_mm,e,T_c_s,X_c_m\n",
    );
    let greys = [200, 150, 100, 0];
    let mut series = Vec::new();
    let (mut xmax, mut fmax) = (0.0f64, 0.0f64);
    for (l, g) in loops.iter().zip(greys) {
        let mut csv = String::from("x_mm,F_N\n");
        for (x, f) in &l.points {
            writeln!(csv, "{x},{f}").unwrap();
        }
        files.push(write(
            &out.join(format!("fig4_loop_{}.csv", speed_tag(l.v0))),
            &csv,
        )?);
        writeln!(
            summary,
            "{},{},{},{},{},{},{},{}",
            l.v0, l.duration, l.peak_force, l.max_compression, l.residual, l.e, l.t_c, l.x_c
        )
        .unwrap();
        xmax = xmax.max(l.max_compression);
        fmax = fmax.max(l.peak_force);
        series.push(Series::Line {
            label: format!("v0 = {:.2} m/s (BWSHCCM)", l.v0),
            grey: g,
            dashed: false,
            points: l.points.clone(),
        });
    }
    files.push(write(&out.join("table2_loops.csv"), &summary)?);
    let chart = Chart {
        title: "Baseball on a flat surface: BWSHCCM loops (Table 2)".into(),
        x_label: "|x| (mm)".into(),
        y_label: "F (N)".into(),
        x_range: (0.0, xmax * 1.05),
        y_range: (0.0, fmax * 1.1),
        series,
        legend_left: true,
    };
    files.extend(save(&chart, &out.join("fig4_RCross"))?);
    Ok(files)
}

/// The fit demo: fit_curve.csv, fit_starts.csv, fit_demo.{svg,png}.
pub fn write_fit(out: &Path, kind: ModelKind, d: &Demo) -> Result<Vec<String>, String> {
    let mut files = Vec::new();
    let opts = FloatOptions::default();
    let best = model_curve(kind, &d.result.best.base, &d.data, &opts);
    let truth = d
        .truth
        .as_ref()
        .map(|t| model_curve(kind, t, &d.data, &opts));
    let mut csv = String::from("v0,e_data,e_model,e_truth\n");
    for i in 0..d.data.len() {
        let f = |x: Option<f64>| x.map(|v| v.to_string()).unwrap_or_default();
        writeln!(
            csv,
            "{},{},{},{}",
            d.data.v0[i],
            d.data.e[i],
            f(best.e_model[i]),
            f(truth.as_ref().and_then(|t| t.e_model[i]))
        )
        .unwrap();
    }
    files.push(write(&out.join("fit_curve.csv"), &csv)?);
    let mut csv =
        String::from("start,J,B,Gamma,kappa,sigma,n,p,iterations,evaluations,converged\n");
    for s in &d.result.starts {
        let p = s.base.as_array();
        writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{}",
            s.start + 1,
            s.j,
            p[0],
            p[1],
            p[2],
            p[3],
            p[4],
            p[5],
            s.iterations,
            s.evaluations,
            s.converged
        )
        .unwrap();
    }
    files.push(write(&out.join("fit_starts.csv"), &csv)?);
    // the curves on a fine grid
    let lo = d.data.v0.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = d.data.v0.iter().copied().fold(0.0, f64::max);
    let fine: Vec<f64> = (0..60).map(|i| lo + (hi - lo) * i as f64 / 59.0).collect();
    let line = |p: &NdParams<f64>| -> Vec<(f64, f64)> {
        fine.iter()
            .zip(bwcl::fit::cost::model_cor(kind, p, &fine, &opts))
            .filter_map(|(&v, e)| e.ok().map(|e| (v, e)))
            .collect()
    };
    let mut series = vec![Series::Marks {
        label: "data".into(),
        grey: 0,
        filled: false,
        points: d
            .data
            .v0
            .iter()
            .copied()
            .zip(d.data.e.iter().copied())
            .collect(),
    }];
    series.push(Series::Line {
        label: format!("fit, J = {:.4}", d.result.best.j),
        grey: 0,
        dashed: false,
        points: line(&d.result.best.base),
    });
    if let (Some(t), Some(j)) = (&d.truth, d.j_truth) {
        series.push(Series::Line {
            label: format!("generating P*, J = {j:.4}"),
            grey: 150,
            dashed: true,
            points: line(t),
        });
    }
    let ymin = d.data.e.iter().copied().fold(1.0, f64::min);
    let chart = Chart {
        title: format!("bwcl fit: {} on the data", model_title(kind)),
        x_label: "v0 (m/s)".into(),
        y_label: "e".into(),
        x_range: (0.0, hi * 1.05),
        y_range: ((ymin - 0.05).clamp(0.0, 0.5), 1.0),
        series,
        legend_left: false,
    };
    files.extend(save(&chart, &out.join("fit_demo"))?);
    Ok(files)
}

pub struct Context<'a> {
    pub args: &'a Args,
    pub font: String,
    pub float_seconds: f64,
    pub float_points: usize,
    pub rig: Option<&'a (Vec<Vec<Proved>>, f64)>,
    /// Per Table 1 set: pieces, thickness and seconds of the proved band.
    /// Per set: pieces, thickness, seconds, sup de/dv0 over the pieces.
    pub band: &'a [(usize, f64, f64, f64)],
    /// The 30-digit reference table (with --rigorous).
    pub reference: Option<&'a [crate::digits::Row]>,
    pub loops: &'a [Loop],
    pub curves: &'a [Vec<Result<f64, String>>],
    pub v0: &'a [f64],
    pub demo: &'a Demo,
    pub ident: Option<&'a crate::ident::Ident>,
    pub laws: &'a crate::laws::Laws,
    pub data_path: &'a Path,
    pub fit_opts: &'a FitOptions,
    pub files: &'a [String],
    pub out: &'a PathBuf,
    pub total_seconds: f64,
}

fn rel(p: &str) -> String {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/");
    p.strip_prefix(root).unwrap_or(p).to_string()
}

fn p6(p: &NdParams<f64>) -> String {
    p.as_array().map(|x| format!("{x:.4}")).join(", ")
}

pub fn render(c: &Context) -> String {
    let mut r = String::new();
    let a = c.args;
    let mut cmd = String::from("cargo run --release --bin paper-repro --");
    if a.rigorous {
        cmd.push_str(" --rigorous");
    }
    if a.identifiability {
        cmd.push_str(" --identifiability");
    }
    if a.quick {
        cmd.push_str(" --quick");
    }
    writeln!(
        r,
        "# Reproduction of the paper's sec:ID (Fig. 3, Table 1, Fig. 4, Table 2)\n"
    )
    .unwrap();
    writeln!(
        r,
        "Generated by `{cmd}` (this file is output: do not edit it by hand). CSVs and plots \
         (SVG, PNG; font `{}`) are in `{}` (git-ignored), {} files. Whole run: {:.1} s on this \
         machine.\n",
        c.font,
        rel(&c.out.display().to_string()),
        c.files.len(),
        c.total_seconds
    )
    .unwrap();

    // Table 1 / Fig. 3
    writeln!(
        r,
        "## Fig. 3 (fig:CoR) and Table 1 (tab:param): CoR of the four base sets\n"
    )
    .unwrap();
    writeln!(
        r,
        "The f64 DOP853 engine with the paper's settings (rtol 1e-10, atol 1e-12, max_step 1e-2) \
         at {} speeds from 0.05 to 6 m/s ({:.2} s for all {} cases). Plots: \
         `fig3_NDBWSHCCM.svg/.png`, `fig3_NDBWMCM.svg/.png`, axes as in the paper (v0 in m/s, \
         e on [0.5, 1]); data: `cor_float.csv`.\n",
        c.float_points,
        c.float_seconds,
        4 * c.float_points
    )
    .unwrap();
    writeln!(
        r,
        "| Table 1 | B_b | Γ_b | κ | σ_b | n | p | J (paper) | J here |"
    )
    .unwrap();
    writeln!(r, "|---|---|---|---|---|---|---|---|---|").unwrap();
    for s in &TABLE1 {
        let v: Vec<&str> = s.base.split(',').collect();
        writeln!(
            r,
            "| {} {} | {} | {} | {} | {} | {} | {} | {} | not computable (no data) |",
            model_title(s.kind),
            s.data,
            v[0],
            v[1],
            v[2],
            v[3],
            v[4],
            v[5],
            s.j
        )
        .unwrap();
    }
    let show = [0.05, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    writeln!(r, "\ne at selected speeds (nearest grid speed):\n").unwrap();
    write!(r, "| v0 (m/s) |").unwrap();
    for s in &TABLE1 {
        write!(r, " {} {} |", model_title(s.kind), s.data).unwrap();
    }
    writeln!(r, "\n|---|---|---|---|---|").unwrap();
    for want in show {
        let i = (0..c.v0.len())
            .min_by(|&x, &y| (c.v0[x] - want).abs().total_cmp(&(c.v0[y] - want).abs()))
            .unwrap();
        write!(r, "| {:.3} |", c.v0[i]).unwrap();
        for cv in c.curves {
            match &cv[i] {
                Ok(e) => write!(r, " {e:.5} |").unwrap(),
                Err(w) => write!(r, " failed: {w} |").unwrap(),
            }
        }
        r.push('\n');
    }
    let failures: usize = c
        .curves
        .iter()
        .map(|cv| cv.iter().filter(|e| e.is_err()).count())
        .sum();
    let (mut emin, mut emax) = (f64::INFINITY, 0.0f64);
    for e in c.curves.iter().flatten().flatten() {
        emin = emin.min(*e);
        emax = emax.max(*e);
    }
    writeln!(
        r,
        "\nAll curves: e ∈ [{emin:.4}, {emax:.4}] on the grid, {failures} integration failure(s). \
         The paper shows these curves only as markers at the measured speeds against the \
         digitized data of Kharaz et al. (Fig. 1 of that paper); it states no e values, so the \
         comparison with the paper is the figure's shape and range: every curve decreases with \
         v0 and stays in the plotted window [0.5, 1].\n"
    )
    .unwrap();
    match c.rig {
        None => writeln!(
            r,
            "Proved enclosures: not computed in this run (add `--rigorous`).\n"
        )
        .unwrap(),
        Some((p, secs)) => {
            let n: usize = p.iter().map(Vec::len).sum();
            let ok: Vec<&Proved> = p.iter().flatten().filter(|x| x.e.is_ok()).collect();
            let wmax = ok
                .iter()
                .map(|x| {
                    let (lo, hi) = x.e.as_ref().unwrap();
                    width_up(*lo, *hi)
                })
                .fold(0.0, f64::max);
            writeln!(
                r,
                "The continuous proved band of e over v0 ∈ [0.05, 6] m/s (interval Taylor \
                 engine with the variational system, the base sets enclosed as written; \
                 issue #13): for every v0 of a piece, e(v0) ∈ e(v_c) + [de/dv0](v0 − v_c). \
                 {} enclosures drawn (the ends and centres of the pieces, between which its \
                 bounds are linear), {} of {n} proved, in {secs:.1} s; widest: {}. Plots \
                 `fig3_*_rigorous.svg/.png` draw the band; data `cor_rigorous.csv`.\n",
                n,
                ok.len(),
                sci_up(wmax, 3)
            )
            .unwrap();
            writeln!(
                r,
                "| set | pieces | thickness | time | de/dv0 ≤ (every piece) |\n\
                 |---|---:|---:|---:|---:|"
            )
            .unwrap();
            for (s, (pieces, thick, t, slope)) in TABLE1.iter().zip(c.band) {
                writeln!(
                    r,
                    "| {} {} | {pieces} | {} | {t:.1} s | {} |",
                    model_title(s.kind),
                    s.data,
                    sci_up(*thick, 3),
                    sci_up(*slope, 3)
                )
                .unwrap();
            }
            let decreasing: Vec<String> = TABLE1
                .iter()
                .zip(c.band)
                .filter(|(_, b)| b.3 < 0.0)
                .map(|(s, _)| format!("{} {}", model_title(s.kind), s.data))
                .collect();
            writeln!(
                r,
                "\n**Proved: e(v0) is strictly decreasing on [0.05, 6] m/s for {} of the 4 Table 1 \
                 sets** ({}; Fig. 3 shows it): the slope enclosure [de/dv0] of every piece of the \
                 band lies below 0 (the last column bounds them all), and e is C¹ in v0, so the \
                 mean-value theorem gives strict decrease; the same argument as `bwcl prove \
                 monotone --model … --base … --v0 a..b` (issue #13, `proofs/README.md`).",
                decreasing.len(),
                if decreasing.is_empty() {
                    "none".to_string()
                } else {
                    decreasing.join(", ")
                }
            )
            .unwrap();
            r.push('\n');
            // the float value must lie in (or next to) the band: check and report
            let mut outside = 0;
            let mut rows = String::new();
            for (s, rows_p) in TABLE1.iter().zip(p) {
                let base = NdParams::<f64>::parse(s.kind, s.base).unwrap();
                let grid: Vec<f64> = rows_p.iter().map(|x| x.v0).collect();
                let fl = bwcl::fit::cost::model_cor(s.kind, &base, &grid, &FloatOptions::default());
                for (x, f) in rows_p.iter().zip(fl) {
                    match (&x.e, f) {
                        (Ok((lo, hi)), Ok(f)) if f < lo - 1e-8 || f > hi + 1e-8 => {
                            outside += 1;
                        }
                        (Err(why), _) => writeln!(
                            rows,
                            "| {} {} | {} | not proved: {} |",
                            model_title(s.kind),
                            s.data,
                            x.v0,
                            why
                        )
                        .unwrap(),
                        _ => {}
                    }
                }
            }
            writeln!(
                r,
                "The f64 value lies within 1e-8 of the enclosure at {} of {} proved speeds.\n",
                ok.len() - outside,
                ok.len()
            )
            .unwrap();
            writeln!(
                r,
                "| set | proved | not proved | widest e enclosure | median width |"
            )
            .unwrap();
            writeln!(r, "|---|---|---|---|---|").unwrap();
            for (s, rows_p) in TABLE1.iter().zip(p) {
                let mut w: Vec<f64> = rows_p
                    .iter()
                    .filter_map(|x| x.e.as_ref().ok().map(|(lo, hi)| width_up(*lo, *hi)))
                    .collect();
                w.sort_by(f64::total_cmp);
                let (wmax, wmed) = match w.len() {
                    0 => ("-".to_string(), "-".to_string()),
                    n => (sci_up(w[n - 1], 3), sci_up(w[n / 2], 3)),
                };
                writeln!(
                    r,
                    "| {} {} | {} | {} | {wmax} | {wmed} |",
                    model_title(s.kind),
                    s.data,
                    w.len(),
                    rows_p.len() - w.len()
                )
                .unwrap();
            }
            r.push('\n');
            if rows.is_empty() {
                writeln!(
                    r,
                    "No speed failed. Every enclosure is in the plots' bands and in \
                     `cor_rigorous.csv` (with its width and time).\n"
                )
                .unwrap();
            } else {
                writeln!(
                    r,
                    "Speeds that were not proved (also marked in the rigorous plots and listed in \
                     `cor_rigorous.csv`):\n\n| set | v0 | |\n|---|---|---|\n{rows}"
                )
                .unwrap();
            }
        }
    }

    if let Some(rows) = c.reference {
        let proved = rows.iter().filter(|x| x.res.is_ok()).count();
        let secs: f64 = rows.iter().map(|x| x.seconds).sum();
        writeln!(
            r,
            "## Reference values to {d} digits (issue #15)\n\n\
             T_s and e of the four Table 1 sets at the speeds of the benchmarks, proved by the \
             rigorous engine on MPFR intervals (`bwcl cor --rigorous --digits {d}`): {proved} of {} \
             cases proved, {secs:.1} s of proof in all (one thread per case, two cases at a time). \
             Every digit the width allows is printed, lower bounds rounded down and upper bounds up. \
             The same table, as CSV, is `{}`; `tests/precision.rs` checks that the f64-interval \
             engine's enclosures (≈ 1e-13 wide) contain these values, and that they agree with the \
             36-digit oracle of `tests/data/references.csv` where it has the case.\n",
            rows.len(),
            crate::digits::DATA,
            d = crate::digits::DIGITS
        )
        .unwrap();
        writeln!(r, "{}", crate::digits::markdown(rows)).unwrap();
    }

    // Fig. 4 / Table 2
    writeln!(
        r,
        "## Fig. 4 (fig:RCross) and Table 2 (tab:RCross): baseball hysteresis loops\n"
    )
    .unwrap();
    writeln!(
        r,
        "BWSHCCM with Table 2 (`{}`), nondimensionalized at each v0 (`PhysicalParams::\
         nondimensionalize`, `scales`), f64 engine with the paper's settings (its max step ≈ T_c/100 s \
         is 0.01 in nondimensional time, the default). Plot `fig4_RCross.svg/.png`: F (N) against \
         |x| (mm), F from 0 as in the paper; loops `fig4_loop_*.csv`, numbers `table2_loops.csv`.\n",
        loops::BASEBALL
    )
    .unwrap();
    writeln!(
        r,
        "| v0 (m/s) | contact duration (s) | peak force (N) | max compression (mm) | residual indentation (mm) | e | T_c (s) |"
    )
    .unwrap();
    writeln!(r, "|---|---|---|---|---|---|---|").unwrap();
    for l in c.loops {
        writeln!(
            r,
            "| {:.2} | {:.4e} | {:.1} | {:.3} | {:.3} | {:.4} | {:.4e} |",
            l.v0, l.duration, l.peak_force, l.max_compression, l.residual, l.e, l.t_c
        )
        .unwrap();
    }
    writeln!(
        r,
        "\nThe paper states none of these numbers: Fig. 4 shows the simulated loops beside Cross's \
         measured loops (dashed), and Table 2 gives only the parameters, which are reproduced \
         above verbatim. The measured loops are not distributed with the paper, so the \
         agreement it describes cannot be checked here; only the simulated side is regenerated.\n"
    )
    .unwrap();

    // fit demo
    let d = c.demo;
    let res = &d.result;
    let m = d.data.len();
    writeln!(
        r,
        "## Identification (eq:J): `bwcl fit` on synthetic data\n"
    )
    .unwrap();
    writeln!(
        r,
        "Data: `{}` (M = {m}). The synthetic file was made by \
         `cargo run --release --bin paper-repro -- synth` (SHC DSS P* = {}, 20 speeds evenly in \
         [0.1, 5] m/s, Gaussian noise σ_noise = 0.005, seed 2024; the command is in the file's \
         header). The fit is the library call behind \
         `bwcl fit --model {} --data {} --starts {} --seed {} --max-iter {}` (same code, same \
         result). A user with measured data runs that command on their own CSV (`v0,e`), or \
         this report with `--data FILE.csv [--model maxwell]`.\n",
        rel(&c.data_path.display().to_string()),
        crate::DSS,
        a.model.name(),
        rel(&c.data_path.display().to_string()),
        c.fit_opts.starts,
        c.fit_opts.seed,
        c.fit_opts.max_iter
    )
    .unwrap();
    writeln!(
        r,
        "Speed: {} cost evaluations × {m} speeds = {} CoRs in {:.2} s ({:.2} ms per J, \
         {} start(s) in parallel, speeds in parallel inside each J, 2 cores).\n",
        res.evaluations,
        res.evaluations * m,
        res.elapsed.as_secs_f64(),
        1e3 * res.elapsed.as_secs_f64() / res.evaluations.max(1) as f64,
        res.starts.len()
    )
    .unwrap();
    writeln!(r, "| | B_b | Γ_b | κ | σ_b | n | p | J |").unwrap();
    writeln!(r, "|---|---|---|---|---|---|---|---|").unwrap();
    if let (Some(t), Some(j)) = (&d.truth, d.j_truth) {
        let v = t.as_array();
        writeln!(
            r,
            "| generating P* | {} | {} | {} | {} | {} | {} | {j:.5} |",
            v[0], v[1], v[2], v[3], v[4], v[5]
        )
        .unwrap();
    }
    let v = res.best.base.as_array();
    writeln!(
        r,
        "| fitted P* (best start) | {:.4} | {:.4} | {:.4} | {:.5} | {:.4} | {:.4} | {:.5} |",
        v[0], v[1], v[2], v[3], v[4], v[5], res.best.j
    )
    .unwrap();
    if let Some(sig) = d.sigma {
        let lvl = sig * (m as f64).sqrt();
        writeln!(
            r,
            "\nNoise level √M·σ_noise = {lvl:.5}: J at the generating set is {} (its expectation \
             is ≈ √M·σ), and a least-squares optimum is expected near √(M−6)·σ = {:.5}. The fit \
             reached J = {:.5} = {:.2} × the noise level: {}",
            d.j_truth
                .map(|j| format!("{j:.5}"))
                .unwrap_or("unknown".into()),
            sig * ((m as f64) - 6.0).max(1.0).sqrt(),
            res.best.j,
            res.best.j / lvl,
            if res.best.j <= 1.5 * lvl {
                "J is recovered to the noise level (≤ 1.5 × √M·σ_noise)."
            } else {
                "J is NOT recovered to the noise level in this run (more --starts or --max-iter)."
            }
        )
        .unwrap();
    }
    if let Some(t) = &d.truth {
        let rel_err: Vec<String> = t
            .as_array()
            .iter()
            .zip(res.best.base.as_array())
            .map(|(a, b)| format!("{:+.0}%", 100.0 * (b - a) / a.abs()))
            .collect();
        writeln!(
            r,
            "The parameters themselves are not recovered: relative deviation of the fitted \
             P* from the generating one (B, Γ, κ, σ, n, p): {}. The CoR curve pins only some \
             combinations of them (see below).\n",
            rel_err.join(", ")
        )
        .unwrap();
    }
    // non-uniqueness
    let sig2 = match d.sigma {
        Some(s) => s * s,
        None => res.best.j * res.best.j / ((m as f64) - 6.0).max(1.0),
    };
    writeln!(
        r,
        "### Non-uniqueness: the starts\n\nΔχ² = (J² − J_best²)/σ² with σ = {} ; a set with \
         Δχ² < 7.04 lies in the 68% joint confidence region of the six parameters (χ² with 6 \
         degrees of freedom), i.e. it is statistically indistinguishable from the best fit.\n",
        match d.sigma {
            Some(s) => format!("σ_noise = {s}"),
            None => format!("the estimate J_best/√(M−6) = {:.5}", sig2.sqrt()),
        }
    )
    .unwrap();
    writeln!(
        r,
        "| start | B_b, Γ_b, κ, σ_b, n, p | J | Δχ² | iterations | same as best? |"
    )
    .unwrap();
    writeln!(r, "|---|---|---|---|---|---|").unwrap();
    let mut st = res.starts.clone();
    st.sort_by(|x, y| x.j.total_cmp(&y.j));
    let bestp = res.best.base.as_array();
    let mut distinct_equal = 0;
    for s in &st {
        let dchi = (s.j * s.j - res.best.j * res.best.j) / sig2;
        let p = s.base.as_array();
        let maxdev = p
            .iter()
            .zip(bestp)
            .map(|(a, b)| ((a - b) / b.abs().max(1e-12)).abs())
            .fold(0.0, f64::max);
        let verdict = if maxdev < 0.02 {
            "same P* (≤ 2%)".to_string()
        } else if dchi < 7.04 {
            distinct_equal += 1;
            format!("distinct P* (up to {:.0}% off), equal J", 100.0 * maxdev)
        } else {
            "distinct, worse (local minimum or budget)".to_string()
        };
        writeln!(
            r,
            "| {} | {} | {:.5} | {:.2} | {} | {} |",
            s.start + 1,
            p6(&s.base),
            s.j,
            dchi,
            s.iterations,
            verdict
        )
        .unwrap();
    }
    if distinct_equal > 0 {
        writeln!(
            r,
            "\n{distinct_equal} start(s) ended at a P* distinct from the best (some parameter more \
             than 2% off) with a statistically equal J: the CoR data alone do not determine P*, \
             as the paper's sensitivity remark in sec:ID says."
        )
        .unwrap();
    } else {
        writeln!(
            r,
            "\nIn this run no start ended at a distinct P* with a statistically equal J (too few \
             starts to show the non-uniqueness)."
        )
        .unwrap();
    }
    writeln!(
        r,
        "Plot `fit_demo.svg/.png`, data `fit_curve.csv`, `fit_starts.csv`.\n"
    )
    .unwrap();

    match c.ident {
        Some(id) => crate::ident::render(&mut r, id),
        None => writeln!(
            r,
            "## Identifiability (issue #31)\n\nNot run: `--identifiability` adds the distinct \
             minima, the profiles and the proved feasible sets of the synthetic DSS case.\n"
        )
        .unwrap(),
    }
    crate::laws::render(&mut r, c.laws);
    writeln!(r, "## What cannot be reproduced, and why\n").unwrap();
    writeln!(
        r,
        "- **J of Table 1** (0.0357, 0.011, 0.0406, 0.0114): J needs the measured (ṽ0, ẽ) of \
         Kharaz et al., digitized by the authors with WebPlotDigitizer. Those data are not \
         distributed with the paper (nor is the figure's `data/DSS.csv`, `data/DSA.csv`), so \
         J cannot be recomputed and the fits cannot be redone on the real data. The same code \
         does it as soon as someone has the data: `bwcl cost --model shc --base 1.43,-1.42,0.632,\
         0.00715,1.31,1.27 --data DSS.csv` and `bwcl fit --model shc --data DSS.csv`.\n\
         - **The experimental markers of Fig. 3**: same reason; only the model curves are \
         drawn. The paper plots the model at the measured speeds only; here it is a curve on \
         [0.05, 6] m/s.\n\
         - **Cross's measured loops of Fig. 4** (data/RCross_*.csv): provided privately to the \
         authors, not distributed; only the simulated loops are drawn, and the paper gives no \
         numbers for them to compare with.\n\
         - **The identification runs themselves**: the paper says its Nelder–Mead details were \
         \"deemed unimportant\"; with non-unique optima (above) a re-run need not return Table \
         1's values even on the same data.\n"
    )
    .unwrap();
    writeln!(r, "## Files\n").unwrap();
    for f in c.files {
        writeln!(r, "- `{}`", rel(f)).unwrap();
    }
    r
}
