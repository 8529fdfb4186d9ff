//! An f64 *inner* estimate of the hull of F: points of the box found feasible by the f64 engine
//! (every constraint met at the targets' midpoints, and |Γ_b| < B_b), and the hull of those
//! points. It brackets F's hull with the paving's proved outer hull: every proved bound lies
//! outside the sampled one (up to the f64 engine's error, ≈ 1e-9 on e), and the gap between the
//! two is what the paving has not resolved. Nothing here is proved: it is reported as an
//! estimate, and it is the reference of the 6-D floor of issue #31 ("the proved hull within 2×
//! of the hull of f64-sampled feasible points").
//!
//! 1. `n` points uniform in the box (ChaCha8, seeded: the same points on every run); each is
//!    tested row by row, stopping at the first row it violates.
//! 2. From each feasible point found (at most [`PUSH_SEEDS`] of them), a push per coordinate
//!    and side: the point is moved along e_j towards the face of the box, the whole way if the
//!    face's point is feasible, else to the furthest feasible point a bisection of
//!    [`PUSH_STEPS`] steps finds between the two (F need not be convex: this is a search, and
//!    only points tested feasible are kept).
//! 3. Rounds from the current extremes: from the point holding the lowest (highest) value of
//!    coordinate j, pushes along e_j tilted by a random direction in the other coordinates
//!    (the extreme of F in j is usually not reached along e_j from an interior point).

use super::problem::Problem;
use crate::fit::cost::{CostOptions, model_point};
use crate::models::NdParams;
use inari::Interval;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Most feasible points of step 1 pushed in step 2.
pub const PUSH_SEEDS: usize = 64;
/// Bisection steps of a push.
pub const PUSH_STEPS: usize = 12;
/// Tilted pushes per extreme and round in step 3.
const TILTS: usize = 8;
/// Rounds of step 3.
const ROUNDS: usize = 4;

/// The sampled points of F.
#[derive(Clone, Debug, Default)]
pub struct Sampled {
    /// The uniform points of step 1.
    pub uniform: usize,
    /// Points tested, pushes included (each at most one f64 run per row).
    pub tested: usize,
    /// The uniform points of step 1 found feasible.
    pub uniform_feasible: usize,
    /// Every point found feasible (free coordinates, in the order of `Space::free`).
    pub points: Vec<Vec<f64>>,
}

impl Sampled {
    /// The hull of the feasible points per free coordinate (`None`: none found).
    pub fn hull(&self) -> Option<Vec<(f64, f64)>> {
        let first = self.points.first()?;
        let mut h: Vec<(f64, f64)> = first.iter().map(|&x| (x, x)).collect();
        for p in &self.points {
            for (hj, &x) in h.iter_mut().zip(p) {
                hj.0 = hj.0.min(x);
                hj.1 = hj.1.max(x);
            }
        }
        Some(h)
    }
}

/// Whether the point `x` (free coordinates) is in 𝓟 and meets every row's targets by the f64
/// engine (e, and tc where the row has one), rows tried in order until one fails.
pub fn feasible(problem: &Problem, x: &[f64]) -> bool {
    let free: Vec<Interval> = x
        .iter()
        .map(|&v| Interval::try_from((v, v)).expect("a finite point"))
        .collect();
    let b = problem.base(&free).map(|i| i.mid());
    if b[1].abs() >= b[0] || b[1].is_nan() {
        return false;
    }
    let base = NdParams::from_array(b);
    let opts = CostOptions::default();
    problem.rows.iter().all(|r| {
        let Ok((e, tc)) = model_point(problem.kind, &base, r.v0.mid(), &opts) else {
            return false;
        };
        let meets = |y: f64, t: &super::problem::Target| t.lo.mid() <= y && y <= t.hi.mid();
        meets(e, &r.e) && r.tc.as_ref().is_none_or(|t| meets(tc, t))
    })
}

/// The furthest feasible point found from the feasible `x` along `d` (scaled so that `x + d`
/// is on the box's boundary): `x + d` itself when feasible, else a bisection of the segment.
/// Returns the point and the number of points tested.
fn push(problem: &Problem, start: &[Interval], x: &[f64], d: &[f64]) -> (Vec<f64>, usize) {
    // (clamped: x + (face − x) may round past the face)
    let at = |t: f64| -> Vec<f64> {
        x.iter()
            .zip(d)
            .zip(start)
            .map(|((a, b), s)| (a + t * b).clamp(s.inf(), s.sup()))
            .collect()
    };
    let end = at(1.0);
    if feasible(problem, &end) {
        return (end, 1);
    }
    let (mut good, mut bad) = (0.0, 1.0);
    for _ in 0..PUSH_STEPS {
        let t = 0.5 * (good + bad);
        if feasible(problem, &at(t)) {
            good = t;
        } else {
            bad = t;
        }
    }
    (at(good), 1 + PUSH_STEPS)
}

/// The step from `x` along `dir` to the boundary of `start` (`dir` scaled).
fn to_boundary(x: &[f64], dir: &[f64], start: &[Interval]) -> Vec<f64> {
    let mut t = f64::INFINITY;
    for ((&xi, &di), s) in x.iter().zip(dir).zip(start) {
        if di > 0.0 {
            t = t.min((s.sup() - xi) / di);
        } else if di < 0.0 {
            t = t.min((s.inf() - xi) / di);
        }
    }
    let t = if t.is_finite() { t.max(0.0) } else { 0.0 };
    dir.iter().map(|d| d * t).collect()
}

/// Samples F in the box `start` (module doc): `n` uniform points, then pushes.
pub fn sample(problem: &Problem, start: &[Interval], n: usize, seed: u64) -> Sampled {
    let dim = start.len();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let uniform: Vec<Vec<f64>> = (0..n)
        .map(|_| {
            start
                .iter()
                .map(|s| {
                    if s.wid() > 0.0 {
                        rng.random_range(s.inf()..s.sup())
                    } else {
                        s.inf()
                    }
                })
                .collect()
        })
        .collect();
    let found: Vec<Vec<f64>> = uniform
        .into_par_iter()
        .filter(|x| feasible(problem, x))
        .collect();
    let mut out = Sampled {
        uniform: n,
        tested: n,
        uniform_feasible: found.len(),
        points: found,
    };
    if out.points.is_empty() || dim == 0 {
        return out;
    }
    // step 2: axis pushes from the first feasible points
    let seeds: Vec<Vec<f64>> = out.points.iter().take(PUSH_SEEDS).cloned().collect();
    let jobs: Vec<(Vec<f64>, Vec<f64>)> = seeds
        .iter()
        .flat_map(|x| {
            (0..dim).flat_map(move |j| {
                [start[j].inf(), start[j].sup()].map(|face| {
                    let mut d = vec![0.0; dim];
                    d[j] = face - x[j];
                    (x.clone(), d)
                })
            })
        })
        .collect();
    run_pushes(problem, start, jobs, &mut out);
    // step 3: tilted pushes from the extremes
    for _ in 0..ROUNDS {
        let mut jobs = Vec::new();
        for j in 0..dim {
            for side in [-1.0, 1.0] {
                let Some(x) = extreme(&out.points, j, side) else {
                    continue;
                };
                for _ in 0..TILTS {
                    let mut dir: Vec<f64> = (0..dim)
                        .map(|k| 0.3 * start[k].wid() * rng.random_range(-1.0..1.0))
                        .collect();
                    dir[j] = side * start[j].wid();
                    let d = to_boundary(&x, &dir, start);
                    jobs.push((x.clone(), d));
                }
            }
        }
        run_pushes(problem, start, jobs, &mut out);
    }
    out
}

fn run_pushes(
    problem: &Problem,
    start: &[Interval],
    jobs: Vec<(Vec<f64>, Vec<f64>)>,
    out: &mut Sampled,
) {
    let pushed: Vec<(Vec<f64>, usize)> = jobs
        .into_par_iter()
        .map(|(x, d)| push(problem, start, &x, &d))
        .collect();
    for (p, k) in pushed {
        out.tested += k;
        out.points.push(p);
    }
}

/// The point with the lowest (`side` < 0) or highest value of coordinate `j`.
fn extreme(points: &[Vec<f64>], j: usize, side: f64) -> Option<Vec<f64>> {
    points
        .iter()
        .max_by(|a, b| (side * a[j]).total_cmp(&(side * b[j])))
        .cloned()
}
