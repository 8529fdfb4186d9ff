//! Seeded multi-start Nelder–Mead minimization of J over 𝓟 (argmin's `NelderMead` on the
//! coordinates of [`Reparam`](super::reparam::Reparam)).
//!
//! Every start is a point drawn from a ChaCha8 stream seeded by [`FitOptions::seed`] (all
//! points are drawn before any run, so the result does not depend on the thread schedule),
//! or one of the user's initial sets. From it, Nelder–Mead runs for at most
//! [`FitOptions::max_iter`] iterations on an initial simplex with edge
//! [`FitOptions::simplex_step`] in every coordinate, and is then restarted
//! [`FitOptions::restarts`] times from its best vertex with a fresh simplex of half that edge
//! (at most `max_iter` iterations each), the usual cure for a simplex that collapsed early.
//! The starts run in parallel, and inside each J the speeds run in parallel (rayon).
//!
//! The search space is a [`Space`] (`--fix`, `--bounds`) mapped by [`SpaceMap`], J the weighted
//! cost of [`Weights`] (the paper's J with unit weights). After the runs, the end points are
//! clustered into distinct minima ([`super::minima`]).

use super::chi2::chi2_quantile;
use super::cost::weighted_cost;
use super::data::CorData;
use super::minima::{Minimum, cluster};
use super::reparam::SpaceMap;
use super::space::{Slot, Space};
use super::weights::Weights;
use crate::models::{ModelKind, NdParams};
use crate::observables::FloatOptions;
use argmin::core::observers::{Observe, ObserverMode};
use argmin::core::{CostFunction, Error, Executor, IterState, KV, State};
use argmin::solver::neldermead::NelderMead;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Settings of a fit.
#[derive(Clone, Debug)]
pub struct FitOptions {
    /// Random starts (≥ 0; with `initial` empty, ≥ 1).
    pub starts: usize,
    /// Seed of the start points.
    pub seed: u64,
    /// Nelder–Mead iterations per run (≥ 1).
    pub max_iter: u64,
    /// Restarts from the best vertex after the first run.
    pub restarts: usize,
    /// Stop a run when the sample standard deviation of J over the simplex is below this.
    pub sd_tolerance: f64,
    /// Edge of the initial simplex, in the reparametrized coordinates.
    pub simplex_step: f64,
    /// Search the p = 1 slice (the Maxwell model's isolated p = 1) instead of p's interval.
    pub p1: bool,
    /// Start points given by the user, run before the random ones.
    pub initial: Vec<NdParams<f64>>,
    /// The f64 engine's settings for every CoR (the paper's by default).
    pub float: FloatOptions,
    /// Fixed and bounded parameters (`None`: all free over 𝓟, p = 1 with `p1`).
    pub space: Option<Space>,
    /// The residuals' errors (`None`: [`Weights::unit`], the paper's J).
    pub weights: Option<Weights>,
    /// Cluster the end points into distinct minima (hill–valley; a few J evaluations per pair).
    pub cluster: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            starts: 8,
            seed: 1,
            max_iter: 300,
            restarts: 1,
            sd_tolerance: 1e-9,
            simplex_step: 0.5,
            p1: false,
            initial: Vec::new(),
            float: FloatOptions::default(),
            space: None,
            weights: None,
            cluster: true,
        }
    }
}

impl FitOptions {
    /// The map of the search space: `space` (with `p1`: p must be free without bounds there,
    /// and is fixed to 1), or all of 𝓟.
    pub fn space_map(&self, kind: ModelKind) -> Result<SpaceMap, String> {
        let Some(space) = &self.space else {
            return Ok(SpaceMap::unbounded(kind, self.p1));
        };
        if space.kind != kind {
            return Err(format!(
                "the space is of model {}, the fit of {}",
                space.kind.name(),
                kind.name()
            ));
        }
        let mut space = space.clone();
        if self.p1 {
            match space.slots[5] {
                Slot::Free { lo, hi } if lo.is_infinite() && hi.is_infinite() => {
                    space.slots[5] = Slot::Fixed(1.0)
                }
                Slot::Fixed(1.0) => {}
                _ => return Err("--p1 fixes p = 1: p cannot also be fixed or bounded".into()),
            }
        }
        if space.free().is_empty() {
            return Err("every parameter is fixed: nothing to fit".into());
        }
        Ok(SpaceMap::new(space))
    }
}

/// Distance (relative to the bound range) within which a result is reported "at bound".
pub const AT_BOUND: f64 = 1e-6;

/// What the fit reports while it runs.
#[derive(Clone, Debug)]
pub enum Progress {
    /// One Nelder–Mead iteration of start `start` was done.
    Iteration { start: usize },
    /// Start `start` finished with cost `j` after `iterations` iterations (of a budget of
    /// `budget`).
    StartDone {
        start: usize,
        j: f64,
        iterations: u64,
        budget: u64,
    },
}

/// The progress callback.
pub type ProgressFn = Arc<dyn Fn(Progress) + Send + Sync>;

/// One start's outcome.
#[derive(Clone, Debug)]
pub struct StartResult {
    /// Its index (user starts first).
    pub start: usize,
    /// Where it started.
    pub initial: NdParams<f64>,
    /// The best base set it found.
    pub base: NdParams<f64>,
    /// J at `base`.
    pub j: f64,
    pub iterations: u64,
    pub evaluations: usize,
    /// Whether the last run stopped on the tolerance (not on the iteration budget).
    pub converged: bool,
    /// The bounded parameters within [`AT_BOUND`] of a bound at `base`.
    pub at_bound: Vec<&'static str>,
}

/// The statistics of a fit's residuals.
#[derive(Clone, Debug, PartialEq)]
pub struct FitStats {
    /// M_res, the number of residuals (M, or 2M with durations).
    pub m_res: usize,
    /// k, the number of free parameters.
    pub k: usize,
    /// The scale s² of χ²: J_best²/(M_res − k) without given errors (∞ if M_res ≤ k), else 1.
    pub s2: f64,
    /// χ²_0.95(k).
    pub crit: f64,
}

impl FitStats {
    /// The statistics of a best cost `j` (see [`FitStats::s2`]).
    pub fn new(j: f64, m_res: usize, k: usize, errors_given: bool) -> Self {
        let s2 = if errors_given {
            1.0
        } else if m_res > k {
            j * j / (m_res - k) as f64
        } else {
            f64::INFINITY
        };
        Self {
            m_res,
            k,
            s2,
            crit: chi2_quantile(k.max(1), 0.95),
        }
    }

    /// χ² = J² over its degrees of freedom M_res − k (NaN without any).
    pub fn reduced_chi2(&self, j: f64) -> f64 {
        if self.m_res > self.k {
            j * j / (self.m_res - self.k) as f64
        } else {
            f64::NAN
        }
    }
}

/// The outcome of a fit.
#[derive(Clone, Debug)]
pub struct FitResult {
    pub kind: ModelKind,
    pub p1: bool,
    /// The start with the lowest J.
    pub best: StartResult,
    /// Every start, in start order.
    pub starts: Vec<StartResult>,
    /// The distinct minima, best first (one per start without clustering).
    pub minima: Vec<Minimum>,
    pub stats: FitStats,
    /// The search space's map and the residuals' errors that were used.
    pub map: SpaceMap,
    pub weights: Weights,
    /// Cost evaluations in all (each one M CoRs).
    pub evaluations: usize,
    pub elapsed: Duration,
}

/// J as a function of the reparametrized coordinates.
struct Objective<'a> {
    kind: ModelKind,
    map: &'a SpaceMap,
    data: &'a CorData,
    weights: &'a Weights,
    float: &'a FloatOptions,
    evals: &'a AtomicUsize,
}

impl CostFunction for Objective<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, u: &Vec<f64>) -> Result<f64, Error> {
        self.evals.fetch_add(1, Ordering::Relaxed);
        Ok(match self.map.to_params(u) {
            Ok(base) => weighted_cost(self.kind, &base, self.data, self.weights, self.float),
            // a NaN coordinate, or a B for which a bounded Γ has no admissible value
            Err(_) => 1e3 / min_error(self.weights),
        })
    }
}

/// Reports every iteration to the progress callback.
struct Observer {
    start: usize,
    progress: ProgressFn,
}

impl Observe<IterState<Vec<f64>, (), (), (), (), f64>> for Observer {
    fn observe_iter(
        &mut self,
        _state: &IterState<Vec<f64>, (), (), (), (), f64>,
        _kv: &KV,
    ) -> Result<(), Error> {
        (self.progress)(Progress::Iteration { start: self.start });
        Ok(())
    }
}

/// The smallest error of any residual (the scale of the penalty of a point without image).
fn min_error(w: &Weights) -> f64 {
    w.e.iter()
        .chain(w.tc.iter().flatten().map(|(_, s)| s))
        .fold(f64::INFINITY, |a, &b| a.min(b))
        .min(1.0)
}

/// A random start, a coordinate per free parameter: log-uniform B_b ∈ [0.05, 5], σ_b ∈
/// [1e−3, 0.1], Γ/B = tanh(U[−3, 3]), κ = logistic(U[−3, 3]), n = 1 + exp(U[−3, 1]),
/// p = floor + exp(U[−2, 1]); a bounded parameter lo + (hi − lo) logistic(U[−3, 3]).
fn random_start(rng: &mut ChaCha8Rng, map: &SpaceMap) -> Vec<f64> {
    let ranges = [
        (0.05f64.ln(), 5f64.ln()),
        (-3.0, 3.0),
        (-3.0, 3.0),
        (1e-3f64.ln(), 0.1f64.ln()),
        (-3.0, 1.0),
        (-2.0, 1.0),
    ];
    map.space
        .free()
        .into_iter()
        .map(|i| {
            let (a, b) = if map.bounds(i).is_some() {
                (-3.0, 3.0)
            } else {
                ranges[i]
            };
            a + (b - a) * rng.random::<f64>()
        })
        .collect()
}

/// Minimizes J(ṽ0, ẽ, ·) over 𝓟 of `kind` (or its p = 1 slice).
pub fn fit(
    kind: ModelKind,
    data: &CorData,
    opts: &FitOptions,
    progress: Option<ProgressFn>,
) -> Result<FitResult, String> {
    if opts.starts + opts.initial.len() == 0 {
        return Err("no start: give at least one random start or an initial set".into());
    }
    if opts.max_iter == 0 {
        return Err("the iteration budget must be ≥ 1".into());
    }
    if !(opts.simplex_step.is_finite() && opts.simplex_step > 0.0) {
        return Err(format!("simplex step {} must be > 0", opts.simplex_step));
    }
    let map = opts.space_map(kind)?;
    let weights = opts.weights.clone().unwrap_or_else(|| Weights::unit(data));
    if weights.e.len() != data.len() {
        return Err(format!(
            "{} errors for {} data rows",
            weights.e.len(),
            data.len()
        ));
    }
    let mut points = Vec::new();
    for (i, p) in opts.initial.iter().enumerate() {
        points.push(
            map.from_params(p)
                .map_err(|e| format!("initial set {}: {e}", i + 1))?,
        );
    }
    let mut rng = ChaCha8Rng::seed_from_u64(opts.seed);
    for _ in 0..opts.starts {
        points.push(random_start(&mut rng, &map));
    }
    let progress = progress.unwrap_or_else(|| Arc::new(|_| {}));
    let t0 = Instant::now();
    let evals = AtomicUsize::new(0);
    let problem = Problem {
        kind,
        map: &map,
        data,
        weights: &weights,
        opts,
    };
    let starts: Vec<StartResult> = points
        .par_iter()
        .enumerate()
        .map(|(i, u0)| problem.run(i, u0, opts.simplex_step, &evals, &progress))
        .collect::<Result<_, _>>()?;
    let best = starts
        .iter()
        .min_by(|a, b| a.j.total_cmp(&b.j))
        .cloned()
        .expect("at least one start");
    let stats = FitStats::new(
        best.j,
        weights.residual_count(),
        map.dim(),
        weights.errors_given,
    );
    let minima = if opts.cluster {
        let j = |p: &NdParams<f64>| {
            evals.fetch_add(1, Ordering::Relaxed);
            weighted_cost(kind, p, data, &weights, &opts.float)
        };
        cluster(&starts, &j, stats.s2, stats.crit)
    } else {
        let mut all: Vec<Minimum> = starts
            .iter()
            .map(|s| Minimum {
                base: s.base.clone(),
                j: s.j,
                starts: vec![s.start],
                converged: s.converged,
                at_bound: s.at_bound.clone(),
                delta_chi2: 0.0,
                indistinguishable: true,
            })
            .collect();
        all.sort_by(|x, y| x.j.total_cmp(&y.j));
        for m in &mut all {
            m.delta_chi2 = (m.j * m.j - best.j * best.j) / stats.s2;
            m.indistinguishable = m.delta_chi2 <= stats.crit;
        }
        all
    };
    Ok(FitResult {
        kind,
        p1: opts.p1,
        best,
        starts,
        minima,
        stats,
        map: map.clone(),
        weights: weights.clone(),
        evaluations: evals.load(Ordering::Relaxed),
        elapsed: t0.elapsed(),
    })
}

/// One minimization problem: J of `data` over the space of `map`.
pub struct Problem<'a> {
    pub kind: ModelKind,
    pub map: &'a SpaceMap,
    pub data: &'a CorData,
    pub weights: &'a Weights,
    pub opts: &'a FitOptions,
}

impl Problem<'_> {
    /// One Nelder–Mead run from coordinates `u0` with initial simplex edge `step`, restarted
    /// as in the module doc.
    pub fn run(
        &self,
        start: usize,
        u0: &[f64],
        step: f64,
        total: &AtomicUsize,
        progress: &ProgressFn,
    ) -> Result<StartResult, String> {
        run_start(self, start, u0, step, total, progress)
    }
}

fn run_start(
    pb: &Problem,
    start: usize,
    u0: &[f64],
    step: f64,
    total: &AtomicUsize,
    progress: &ProgressFn,
) -> Result<StartResult, String> {
    let opts = pb.opts;
    let mine = AtomicUsize::new(0);
    let obj = |evals| Objective {
        kind: pb.kind,
        map: pb.map,
        data: pb.data,
        weights: pb.weights,
        float: &opts.float,
        evals,
    };
    let mut best_u = u0.to_vec();
    let mut best_j = f64::INFINITY;
    let mut iterations = 0;
    let mut converged = false;
    let mut step = step;
    for run in 0..=opts.restarts {
        let mut simplex = vec![best_u.clone()];
        for k in 0..best_u.len() {
            let mut v = best_u.clone();
            v[k] += step;
            simplex.push(v);
        }
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(opts.sd_tolerance)
            .map_err(|e| e.to_string())?;
        let res = Executor::new(obj(&mine), solver)
            .configure(|s| s.max_iters(opts.max_iter))
            .add_observer(
                Observer {
                    start,
                    progress: progress.clone(),
                },
                ObserverMode::Always,
            )
            .run()
            .map_err(|e| format!("start {}: Nelder–Mead failed: {e}", start + 1))?;
        let state = res.state();
        iterations += state.get_iter();
        converged = state.get_iter() < opts.max_iter;
        let j = state.get_best_cost();
        let improved = j < best_j - 1e-12;
        if j < best_j {
            best_j = j;
            best_u = state.get_best_param().cloned().unwrap_or(best_u);
        }
        if run > 0 && !improved {
            break;
        }
        step *= 0.5;
    }
    let n = mine.load(Ordering::Relaxed);
    total.fetch_add(n, Ordering::Relaxed);
    let budget = opts.max_iter * (1 + opts.restarts as u64);
    progress(Progress::StartDone {
        start,
        j: best_j,
        iterations,
        budget,
    });
    let as_params = |u: &[f64]| pb.map.to_params(u).map_err(|e| e.to_string());
    let base = as_params(&best_u)?;
    Ok(StartResult {
        start,
        // a start without image (a bounded Γ empty for its B) is reported by its end point
        initial: as_params(u0).unwrap_or_else(|_| base.clone()),
        at_bound: pb.map.at_bounds(&base, AT_BOUND),
        base,
        j: best_j,
        iterations,
        evaluations: n,
        converged,
    })
}
