//! The `profile` subcommand: J profiled along each free parameter, with its likelihood-ratio
//! interval (see `bwcl::fit::profile`).

use super::args::{ProfileArgs, ProfileFormat};
use super::fit::{
    FIT_MAX_STEPS, base_text, progress_bar, read_data, search_space, search_weights, table,
};
use super::output::{self, ParamsOut, json, num};
use super::{CliError, EXIT_OK};
use bwcl::fit::data::echo;
use bwcl::fit::profile::{End, Profile, grid_range, profile as run_profile};
use bwcl::fit::space::{NAMES, Slot, param_index};
use bwcl::fit::uncertainty::{JacobianMethod, uncertainty};
use bwcl::fit::{CorData, FitOptions, fit as run_fit};
use bwcl::models::ModelKind;
use bwcl::observables::FloatOptions;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::sync::Arc;

#[derive(Serialize)]
pub struct ProfileOut {
    model: &'static str,
    /// The best fit the profiles start from.
    #[serde(rename = "P_star")]
    p_star: ParamsOut<f64>,
    base: String,
    #[serde(skip)]
    p_best: bwcl::models::NdParams<f64>,
    #[serde(rename = "J")]
    j: f64,
    s2: f64,
    /// χ²_0.95(1): the likelihood-ratio threshold of Δχ².
    threshold: f64,
    seconds: f64,
    profiles: Vec<Profile>,
}

/// The progress bar of `profile` on stderr (hidden when stderr is not a terminal): grid points.
fn profile_bar() -> ProgressBar {
    let bar = progress_bar(0);
    bar.set_style(
        ProgressStyle::with_template(
            "profile {bar:32} {pos}/{len} grid points, {elapsed} elapsed, ~{eta} left  {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}

fn end_text(e: &End) -> String {
    if e.open {
        format!("open (≥ grid end {})", num(e.value))
    } else {
        num(e.value)
    }
}

pub fn profile(a: &ProfileArgs) -> Result<i32, CliError> {
    super::input::out_path(a.out.as_deref())?;
    super::input::out_path_as("--plot", a.plot.as_deref())?;
    let data = read_data(&a.data)?;
    let bar = profile_bar();
    let out = compute(a, &data, &bar)?;
    bar.finish_and_clear();
    let kind = ModelKind::from(a.model);
    let (best, profiles) = (&out.p_best, &out.profiles);
    let bytes = match a.format {
        ProfileFormat::Json => json(&out)?,
        ProfileFormat::Csv => {
            let mut s =
                String::from("param,value,J,delta_chi2,B,Gamma,kappa,sigma,n,p,converged\n");
            for p in profiles {
                for q in &p.points {
                    s.push_str(&format!(
                        "{},{},{},{},{},{}\n",
                        p.name,
                        num(q.value),
                        num(q.j),
                        num(q.delta_chi2),
                        q.p_star.map(num).join(","),
                        q.converged
                    ));
                }
            }
            s.into_bytes()
        }
        ProfileFormat::Table => {
            let mut s = format!(
                "model {}: best P* (B,Γ,κ,σ_b,n,p) = {}, J = {}, s² = {}\n\
                 95 % likelihood-ratio intervals {{θ : (J_p(θ)² − J_min²)/s² ≤ {:.3}}}:\n",
                kind.name(),
                base_text(best),
                num(out.j),
                num(out.s2),
                out.threshold,
            );
            let rows: Vec<Vec<String>> = profiles
                .iter()
                .map(|p| {
                    vec![
                        p.name.to_string(),
                        num(p.best_value),
                        end_text(&p.lo),
                        end_text(&p.hi),
                        num(p.j_min),
                    ]
                })
                .collect();
            s.push_str(&table(&["param", "best", "lo", "hi", "J_min"], &rows));
            for p in profiles {
                s.push_str(&format!("\nprofile of {}:\n", p.name));
                let rows: Vec<Vec<String>> = p
                    .points
                    .iter()
                    .map(|q| {
                        vec![
                            num(q.value),
                            format!("{:.6e}", q.j),
                            format!("{:.3}", q.delta_chi2),
                            if q.converged { "yes" } else { "budget" }.into(),
                        ]
                    })
                    .collect();
                s.push_str(&table(&[p.name, "J", "Δχ²", "converged"], &rows));
            }
            s.into_bytes()
        }
    };
    if let Some(p) = &a.plot {
        output::emit_as("--plot", Some(p), svg(profiles, out.threshold).as_bytes())?;
    }
    output::emit(a.out.as_deref(), &bytes)?;
    Ok(EXIT_OK)
}

/// The profiles as SVG, one panel per parameter: Δχ² = (J_p² − J_min²)/s² at the grid points
/// (a polyline with marks; points whose re-optimization used its whole budget hollow), the
/// threshold χ²_0.95(1) dashed, the 95 % interval shaded, the best fit's value a vertical line.
pub fn svg(profiles: &[Profile], threshold: f64) -> String {
    use std::fmt::Write;
    const W: f64 = 300.0;
    const H: f64 = 220.0;
    const M: f64 = 55.0;
    let cols = profiles.len().clamp(1, 3);
    let rows = profiles.len().div_ceil(cols).max(1);
    let (w, h) = (cols as f64 * (W + M) + M, rows as f64 * (H + M) + M / 2.0);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    for (k, p) in profiles.iter().enumerate() {
        let (ox, oy) = (
            M + (k % cols) as f64 * (W + M),
            M / 2.0 + (k / cols) as f64 * (H + M),
        );
        let pts: Vec<(f64, f64, bool)> = p
            .points
            .iter()
            .filter(|q| q.delta_chi2.is_finite())
            .map(|q| (q.value, q.delta_chi2, q.converged))
            .collect();
        let (x0, x1) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), q| {
                (a.min(q.0), b.max(q.0))
            });
        let (x0, x1) = if x1 > x0 {
            (x0, x1)
        } else {
            (x0 - 1.0, x0 + 1.0)
        };
        let top = pts
            .iter()
            .map(|q| q.1)
            .fold(2.0 * threshold, f64::max)
            .min(20.0 * threshold);
        let x = |v: f64| ox + W * (v - x0) / (x1 - x0);
        let y = |v: f64| oy + H - H * (v.clamp(-0.05 * top, top) + 0.05 * top) / (1.05 * top);
        let _ = writeln!(
            s,
            "<rect x=\"{ox}\" y=\"{oy}\" width=\"{W}\" height=\"{H}\" fill=\"none\" stroke=\"black\"/>"
        );
        // the interval, the threshold, the best value
        let (a, b) = (x(p.lo.value.max(x0)), x(p.hi.value.min(x1)));
        let _ = writeln!(
            s,
            "<rect x=\"{a:.2}\" y=\"{oy}\" width=\"{:.2}\" height=\"{H}\" fill=\"#cfe3f5\"/>\
             <line x1=\"{ox}\" y1=\"{t:.2}\" x2=\"{:.2}\" y2=\"{t:.2}\" stroke=\"#c0392b\" stroke-dasharray=\"5,3\"/>\
             <line x1=\"{bx:.2}\" y1=\"{oy}\" x2=\"{bx:.2}\" y2=\"{:.2}\" stroke=\"#888\"/>",
            (b - a).max(0.5),
            ox + W,
            oy + H,
            t = y(threshold),
            bx = x(p.best_value.clamp(x0, x1)),
        );
        let line: Vec<String> = pts
            .iter()
            .map(|q| format!("{:.2},{:.2}", x(q.0), y(q.1)))
            .collect();
        let _ = writeln!(
            s,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"#1f4e79\" stroke-width=\"1.5\"/>",
            line.join(" ")
        );
        for q in &pts {
            let fill = if q.2 { "#1f4e79" } else { "white" };
            let _ = writeln!(
                s,
                "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"2.5\" fill=\"{fill}\" stroke=\"#1f4e79\"/>",
                x(q.0),
                y(q.1)
            );
        }
        let lab = |v: f64| format!("{v:.4}");
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\
             <text x=\"{ox}\" y=\"{}\">{}</text><text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\
             <text x=\"{}\" y=\"{}\" text-anchor=\"end\">0</text>\
             <text x=\"{}\" y=\"{}\" text-anchor=\"end\">{:.2}</text>\
             <text x=\"{}\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 {} {})\">Δχ²</text>",
            ox + W / 2.0,
            oy + H + 28.0,
            p.name,
            oy + H + 14.0,
            lab(x0),
            ox + W,
            oy + H + 14.0,
            lab(x1),
            ox - 3.0,
            y(0.0) + 4.0,
            ox - 3.0,
            y(threshold) + 4.0,
            threshold,
            ox - 30.0,
            oy + H / 2.0,
            ox - 30.0,
            oy + H / 2.0,
        );
    }
    s.push_str("</svg>\n");
    s
}

/// Fits, then profiles (the work of `profile`), advancing `bar` per grid point.
pub fn compute(a: &ProfileArgs, data: &CorData, bar: &ProgressBar) -> Result<ProfileOut, CliError> {
    let kind = ModelKind::from(a.model);
    let data = data.clone();
    let space = search_space(kind, &a.search)?;
    let weights = search_weights(&data, &a.search)?;
    let mut opts = FitOptions {
        starts: a.starts,
        seed: a.seed,
        max_iter: a.max_iter,
        space,
        weights: Some(weights.clone()),
        ..FitOptions::default()
    };
    opts.float.ode.max_steps = opts.float.ode.max_steps.min(FIT_MAX_STEPS);
    let map = opts.space_map(kind).map_err(CliError::Input)?;
    let free = map.space.free();
    let params: Vec<usize> = match &a.param {
        None => free.clone(),
        Some(name) => {
            let i = param_index(name).ok_or_else(|| {
                CliError::Input(format!(
                    "--param: '{}' is not a parameter name (one of {})",
                    echo(name),
                    NAMES.join(", ")
                ))
            })?;
            if let Slot::Fixed(v) = map.space.slots[i] {
                return Err(CliError::Input(format!(
                    "--param {}: it is fixed (--fix {}={v}); a fixed parameter has no profile",
                    NAMES[i], NAMES[i]
                )));
            }
            vec![i]
        }
    };
    let t0 = std::time::Instant::now();
    bar.set_message("fitting (the best point)");
    let res = run_fit(kind, &data, &opts, None).map_err(CliError::Failed)?;
    let best = res.best.base.clone();
    // standard errors for the grid ranges of unbounded parameters (central differences: the
    // range needs no proof)
    let se: Vec<Option<f64>> = if params.iter().any(|&i| map.bounds(i).is_none()) {
        let u = uncertainty(
            kind,
            &best,
            &free,
            &data,
            &weights,
            res.stats.s2,
            JacobianMethod::Central,
            &FloatOptions::default(),
        )
        .ok();
        params
            .iter()
            .map(|&i| {
                let k = free.iter().position(|&f| f == i)?;
                u.as_ref().map(|u| u.std_errors[k])
            })
            .collect()
    } else {
        vec![None; params.len()]
    };
    bar.set_length((params.len() * a.points) as u64);
    let tick: Arc<dyn Fn() + Send + Sync> = {
        let bar = bar.clone();
        Arc::new(move || bar.inc(1))
    };
    let mut profiles = Vec::new();
    for (&i, s) in params.iter().zip(&se) {
        bar.set_message(format!("profile of {}", NAMES[i]));
        let range = grid_range(&map, &best, i, *s);
        profiles.push(
            run_profile(
                kind,
                &data,
                &weights,
                &map,
                &best,
                res.best.j,
                i,
                range,
                a.points,
                &opts,
                res.stats.s2,
                Some(tick.clone()),
            )
            .map_err(CliError::Failed)?,
        );
    }
    Ok(ProfileOut {
        model: kind.name(),
        p_star: super::commands::params_f64(&best),
        base: base_text(&best),
        p_best: best.clone(),
        j: res.best.j,
        s2: res.stats.s2,
        threshold: bwcl::fit::chi2::chi2_quantile(1, 0.95),
        seconds: t0.elapsed().as_secs_f64(),
        profiles,
    })
}
