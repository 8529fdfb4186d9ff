//! The profile of J along one free parameter θ_i, the others re-optimized (issue #31, item 1),
//! and its likelihood-ratio interval:
//!
//! ```text
//! J_p(x) = min { J(θ) : θ_i = x }           on a grid of K values x_0 < … < x_{K−1}
//! I_95   = { x : (J_p(x)² − J_min²) / s² ≤ χ²_0.95(1) = 3.841 }
//! ```
//!
//! with s² as in [`super::minima`] and J_min the smallest J seen (the fit's best, or a lower
//! profile point). Each grid point's minimization is a Nelder–Mead run ([`Problem::run`]) over the
//! other free parameters, warm-started from the neighbouring grid point's optimum, walking
//! outward from the grid point nearest the best fit in both directions. The interval's ends are
//! found by linear interpolation of (J_p² − J_min²)/s² between the first grid point above the
//! threshold and its inner neighbour; an end whose side never rises above it is "open" (the
//! interval reaches the grid's end there).

use super::chi2::chi2_quantile;
use super::data::CorData;
use super::nelder_mead::{FitOptions, Problem, ProgressFn};
use super::reparam::SpaceMap;
use super::space::{NAMES, Slot, admissible_range};
use super::weights::Weights;
use crate::models::{ModelKind, NdParams};
use std::sync::Arc;
use std::sync::atomic::AtomicUsize;

/// Fewest and most grid points.
pub const POINTS: (usize, usize) = (3, 1001);

/// One grid point of a profile.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ProfilePoint {
    pub value: f64,
    #[serde(rename = "J")]
    pub j: f64,
    /// (J² − J_min²)/s².
    pub delta_chi2: f64,
    /// The re-optimized P* (B, Γ, κ, σ_b, n, p).
    pub p_star: [f64; 6],
    pub converged: bool,
}

/// One end of the likelihood-ratio interval.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct End {
    pub value: f64,
    /// The interval reaches the grid's end on this side (the value is the grid's end).
    pub open: bool,
}

/// The profile of one parameter.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Profile {
    pub name: &'static str,
    /// The best fit's value of the parameter and J.
    pub best_value: f64,
    #[serde(rename = "J_best")]
    pub j_best: f64,
    #[serde(rename = "J_min")]
    pub j_min: f64,
    pub s2: f64,
    /// χ²_0.95(1).
    pub threshold: f64,
    pub points: Vec<ProfilePoint>,
    pub lo: End,
    pub hi: End,
}

/// The default range of a profile of parameter `i` at the best fit `best`: its bounds, else
/// best ± 4 `se` clipped to 𝓟 (the open ends pulled in by 1e−9), else (no finite SE) ± 50 %.
pub fn grid_range(map: &SpaceMap, best: &NdParams<f64>, i: usize, se: Option<f64>) -> (f64, f64) {
    if let Some(b) = map.bounds(i) {
        return b;
    }
    let x = best.as_array();
    let v = x[i];
    let half = match se {
        Some(s) if s.is_finite() && s > 0.0 => 4.0 * s,
        _ if v != 0.0 => 0.5 * v.abs(),
        _ => 0.5,
    };
    let (mut lo, mut hi, _) = admissible_range(map.kind(), i);
    match i {
        1 if matches!(map.space.slots[0], Slot::Fixed(_)) => (lo, hi) = (-x[0], x[0]),
        0 => {
            if let Slot::Fixed(g) = map.space.slots[1] {
                lo = g.abs();
            }
        }
        _ => {}
    }
    let pull = |e: f64| 1e-9 * e.abs().max(1.0);
    let a = (v - half).max(lo + pull(lo));
    let b = (v + half).min(hi - pull(hi));
    (a, b)
}

/// Moves a warm start onto θ_i = x: fixes Γ or B so that |Γ| < B holds.
fn place(best: &NdParams<f64>, i: usize, x: f64) -> [f64; 6] {
    let mut a = best.as_array();
    a[i] = x;
    if i == 1 && a[0] <= x.abs() {
        a[0] = x.abs() * 1.01;
    }
    if i == 0 && a[1].abs() >= x {
        a[1] = a[1].signum() * 0.99 * x;
    }
    a
}

/// Profiles J along free parameter `i` over `range` with `points` grid points (module doc);
/// `best` with cost `j_best` is the fit's best point, `s2` the χ² scale. `progress` is told of
/// every grid point done.
#[allow(clippy::too_many_arguments)]
pub fn profile(
    kind: ModelKind,
    data: &CorData,
    weights: &Weights,
    map: &SpaceMap,
    best: &NdParams<f64>,
    j_best: f64,
    i: usize,
    range: (f64, f64),
    points: usize,
    opts: &FitOptions,
    s2: f64,
    progress: Option<Arc<dyn Fn() + Send + Sync>>,
) -> Result<Profile, String> {
    if !matches!(map.space.slots[i], Slot::Free { .. }) {
        return Err(format!("{} is fixed: it has no profile", NAMES[i]));
    }
    if !(POINTS.0..=POINTS.1).contains(&points) {
        return Err(format!(
            "{points} grid points: {} to {} needed",
            POINTS.0, POINTS.1
        ));
    }
    let (lo, hi) = range;
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return Err(format!("the profile range [{lo}, {hi}] is empty"));
    }
    let grid: Vec<f64> = (0..points)
        .map(|g| {
            if g + 1 == points {
                hi
            } else {
                lo + (hi - lo) * g as f64 / (points - 1) as f64
            }
        })
        .collect();
    let xb = best.as_array()[i];
    let g0 = (0..points)
        .min_by(|&a, &b| (grid[a] - xb).abs().total_cmp(&(grid[b] - xb).abs()))
        .expect("a grid point");
    let tick = progress.unwrap_or_else(|| Arc::new(|| {}));
    let quiet: ProgressFn = Arc::new(|_| {});
    let evals = AtomicUsize::new(0);
    // one grid point, warm-started from `warm`
    let solve = |g: usize, warm: &NdParams<f64>| -> Result<ProfilePoint, String> {
        let mut space = map.space.clone();
        space.slots[i] = Slot::Fixed(grid[g]);
        let sub = SpaceMap::new(space);
        let a = place(warm, i, grid[g]);
        let start = NdParams::new(kind, a[0], a[1], a[2], a[3], a[4], a[5])
            .map_err(|e| format!("{} = {}: {e}", NAMES[i], grid[g]))?;
        let (base, j, converged) = if sub.dim() == 0 {
            let j = super::cost::weighted_cost(kind, &start, data, weights, &opts.float);
            (start, j, true)
        } else {
            let u0 = sub
                .from_params(&start)
                .map_err(|e| format!("{} = {}: {e}", NAMES[i], grid[g]))?;
            let pb = Problem {
                kind,
                map: &sub,
                data,
                weights,
                opts,
            };
            let r = pb.run(g, &u0, opts.simplex_step.min(0.2), &evals, &quiet)?;
            (r.base, r.j, r.converged)
        };
        tick();
        Ok(ProfilePoint {
            value: grid[g],
            j,
            delta_chi2: f64::NAN,
            p_star: base.as_array(),
            converged,
        })
    };
    let walk = |range: Vec<usize>| -> Result<Vec<ProfilePoint>, String> {
        let mut warm = best.clone();
        let mut out = Vec::new();
        for g in range {
            let pt = solve(g, &warm)?;
            let a = pt.p_star;
            warm = NdParams::new(kind, a[0], a[1], a[2], a[3], a[4], a[5]).unwrap_or(warm);
            out.push(pt);
        }
        Ok(out)
    };
    let (up, down) = rayon::join(
        || walk((g0..points).collect()),
        || walk((0..g0).rev().collect()),
    );
    let (up, mut down) = (up?, down?);
    down.reverse();
    let mut pts: Vec<ProfilePoint> = down.into_iter().chain(up).collect();
    let j_min = pts.iter().map(|p| p.j).fold(j_best, f64::min);
    let dchi = |j: f64| {
        if s2.is_finite() && s2 > 0.0 {
            (j * j - j_min * j_min) / s2
        } else {
            0.0
        }
    };
    for p in &mut pts {
        p.delta_chi2 = dchi(p.j);
    }
    let threshold = chi2_quantile(1, 0.95);
    // the curve with the best point as its anchor, walked outward from it
    let end = |side: &mut dyn Iterator<Item = &ProfilePoint>| -> End {
        let (mut x0, mut f0) = (xb, dchi(j_best));
        let mut last = xb;
        for p in side {
            if p.delta_chi2 > threshold {
                let t = ((threshold - f0) / (p.delta_chi2 - f0)).clamp(0.0, 1.0);
                return End {
                    value: x0 + t * (p.value - x0),
                    open: false,
                };
            }
            (x0, f0, last) = (p.value, p.delta_chi2, p.value);
        }
        End {
            value: last,
            open: true,
        }
    };
    let hi_end = end(&mut pts.iter().filter(|p| p.value > xb));
    let lo_end = end(&mut pts.iter().rev().filter(|p| p.value < xb));
    Ok(Profile {
        name: NAMES[i],
        best_value: xb,
        j_best,
        j_min,
        s2,
        threshold,
        points: pts,
        lo: lo_end,
        hi: hi_end,
    })
}
