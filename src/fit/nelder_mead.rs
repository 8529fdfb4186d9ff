//! Seeded multi-start Nelder–Mead minimization of J over 𝓟 (argmin's `NelderMead` on the
//! coordinates of [`Reparam`]).
//!
//! Every start is a point drawn from a ChaCha8 stream seeded by [`FitOptions::seed`] (all
//! points are drawn before any run, so the result does not depend on the thread schedule),
//! or one of the user's initial sets. From it, Nelder–Mead runs for at most
//! [`FitOptions::max_iter`] iterations on an initial simplex with edge
//! [`FitOptions::simplex_step`] in every coordinate, and is then restarted
//! [`FitOptions::restarts`] times from its best vertex with a fresh simplex of half that edge
//! (at most `max_iter` iterations each), the usual cure for a simplex that collapsed early.
//! The starts run in parallel, and inside each J the speeds run in parallel (rayon).

use super::cost::cost;
use super::data::CorData;
use super::reparam::Reparam;
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
        }
    }
}

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
    /// Cost evaluations in all (each one M CoRs).
    pub evaluations: usize,
    pub elapsed: Duration,
}

/// J as a function of the reparametrized coordinates.
struct Objective<'a> {
    kind: ModelKind,
    reparam: Reparam,
    data: &'a CorData,
    float: &'a FloatOptions,
    evals: &'a AtomicUsize,
}

impl CostFunction for Objective<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, u: &Vec<f64>) -> Result<f64, Error> {
        self.evals.fetch_add(1, Ordering::Relaxed);
        Ok(match self.reparam.to_params(u) {
            Ok(base) => cost(self.kind, &base, self.data, self.float),
            // only a NaN coordinate gets here; the simplex never makes one from finite J
            Err(_) => 1e3,
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

/// A random start: log-uniform B_b ∈ [0.05, 5], σ_b ∈ [1e−3, 0.1], Γ/B = tanh(U[−3, 3]),
/// κ = logistic(U[−3, 3]), n = 1 + exp(U[−3, 1]), p = floor + exp(U[−2, 1]).
fn random_start(rng: &mut ChaCha8Rng, dim: usize) -> Vec<f64> {
    let ranges = [
        (0.05f64.ln(), 5f64.ln()),
        (-3.0, 3.0),
        (-3.0, 3.0),
        (1e-3f64.ln(), 0.1f64.ln()),
        (-3.0, 1.0),
        (-2.0, 1.0),
    ];
    ranges[..dim]
        .iter()
        .map(|&(a, b)| a + (b - a) * rng.random::<f64>())
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
    let reparam = Reparam::new(kind, opts.p1);
    let dim = reparam.dim();
    let mut points = Vec::new();
    for (i, p) in opts.initial.iter().enumerate() {
        points.push(
            reparam
                .from_params(p)
                .map_err(|e| format!("initial set {}: {e}", i + 1))?,
        );
    }
    let mut rng = ChaCha8Rng::seed_from_u64(opts.seed);
    for _ in 0..opts.starts {
        points.push(random_start(&mut rng, dim));
    }
    let progress = progress.unwrap_or_else(|| Arc::new(|_| {}));
    let t0 = Instant::now();
    let evals = AtomicUsize::new(0);
    let starts: Vec<StartResult> = points
        .par_iter()
        .enumerate()
        .map(|(i, u0)| run_start(kind, reparam, data, opts, i, u0, &evals, &progress))
        .collect::<Result<_, _>>()?;
    let best = starts
        .iter()
        .min_by(|a, b| a.j.total_cmp(&b.j))
        .cloned()
        .expect("at least one start");
    Ok(FitResult {
        kind,
        p1: opts.p1,
        best,
        starts,
        evaluations: evals.load(Ordering::Relaxed),
        elapsed: t0.elapsed(),
    })
}

#[allow(clippy::too_many_arguments)]
fn run_start(
    kind: ModelKind,
    reparam: Reparam,
    data: &CorData,
    opts: &FitOptions,
    start: usize,
    u0: &[f64],
    total: &AtomicUsize,
    progress: &ProgressFn,
) -> Result<StartResult, String> {
    let mine = AtomicUsize::new(0);
    let obj = |evals| Objective {
        kind,
        reparam,
        data,
        float: &opts.float,
        evals,
    };
    let mut best_u = u0.to_vec();
    let mut best_j = f64::INFINITY;
    let mut iterations = 0;
    let mut converged = false;
    let mut step = opts.simplex_step;
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
    let as_params = |u: &[f64]| reparam.to_params(u).map_err(|e| e.to_string());
    Ok(StartResult {
        start,
        initial: as_params(u0)?,
        base: as_params(&best_u)?,
        j: best_j,
        iterations,
        evaluations: n,
        converged,
    })
}
