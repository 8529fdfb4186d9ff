//! The paving of a box of free parameters into boxes proved feasible, proved infeasible and
//! undecided (set inversion via interval analysis, SIVIA, with contractors).
//!
//! Each box U carries the rows whose constraints are not yet settled on it, and per row the
//! slopes proved over an ancestor box ([`RowSlopes`]). Processing U:
//!
//! 1. 𝓟 contracts it: Γ_b ∈ [−sup B_b, sup B_b], B_b ≥ min |Γ_b|; the cut slabs hold no point
//!    of 𝓟 (they are reported infeasible: F ⊂ 𝓟 by definition). A box that still crosses
//!    |Γ_b| = B_b cannot be given to the engines: it is split (undecided at the resolution).
//! 2. For every open row, its observables are enclosed over U — by their hulls over U where the
//!    row has no slopes (one run with the parameters as components,
//!    [`crate::observables::sets::hull_over_set`]), then by the mean-value form about U's
//!    centre ([`super::form`]) where it has or gets them: proved outside the outer target → U
//!    is infeasible; inside the inner target → the constraint holds on all of U and the row is
//!    dropped for U's sub-boxes; else the form contracts U. Contraction repeats (at a new
//!    centre) while it removes at least a fifth of some side.
//! 3. No open row left: U is feasible. Else U is bisected along its side that is widest
//!    relative to the starting box, until the sides reach the resolution (then undecided).
//!
//! Before step 2 the f64 engine guesses each open row's outcome on U ([`super::guide`]), and
//! only what the guess says can succeed is tried: the surest violated row that can be tried
//! alone (one with slopes first, then the slowest impact: the variational runs reach wider
//! boxes at low speeds), else — no row guessed violated — every row guessed inside (closed on
//! U, its sub-boxes do not run it again), else nothing (U is bisected at once). A row's slopes
//! (its hulls) are tried on a box no wider than the widest on which they were proved, or
//! narrower than the narrowest on which they failed; hulls that decided nothing are tried again
//! on boxes half as large. Guesses only choose the work: each verdict is still the interval
//! engines'. Measured on the 2-D floor of issue #31 (σ_b × κ, 1/128, 2 cores): with the
//! slopes alone 6.3 % undecided (complete) in 293 s, no box proved feasible (the slopes of the
//! rows at v0 ≥ 4 wrap even at the resolution); with the hulls first 1.46 % undecided and
//! 1.73 % feasible (complete) in 50–57 s.
//!
//! Work order: half of the boxes by volume (largest first: the boundary of F is resolved
//! uniformly), the other half round-robin by the lowest lower end and the highest upper end of
//! each coordinate (the hull of F converges first). Boxes are processed in parallel batches
//! (rayon), the rows of a box too. A time limit or a box budget stops the work: what is left
//! is reported undecided, and everything reported is still proved.

use super::form::{RowSlopes, centre_of, contract, enclose, tc_factor};
use super::guide::{Guess, SAFETY, guess};
use super::problem::{Problem, Target};
use crate::engines::taylor::TaylorOptions;
use crate::models::NdParams;
use crate::observables::sets::{Inputs, hull_over_set, prove_at_point, slopes_over_set};
use inari::Interval;
use rayon::prelude::*;
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::Arc;
use std::time::Instant;

/// The local tolerance of the hulls' runs: their widths come from the boxes (≈ 10⁻³ at the
/// resolution of the 2-D floor), and 10⁻⁶ took 10 % less time than the slopes' 10⁻¹⁰ there
/// (10⁻⁴ grew too wide).
const HULL_TOL: f64 = 1e-6;

/// What is proved about a box.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Every constraint holds at every point of the box (and the box is inside 𝓟).
    Feasible,
    /// No point of the box satisfies every constraint (or the box is outside 𝓟).
    Infeasible,
    /// Neither was proved at the resolution (or within the budget).
    Undecided,
}

/// A box of the paving (free coordinates, in the order of `Space::free`).
#[derive(Clone, Debug, PartialEq)]
pub struct Leaf {
    pub lo: Vec<f64>,
    pub hi: Vec<f64>,
    pub status: Status,
}

/// Settings of a paving.
#[derive(Clone, Debug)]
pub struct Options {
    /// Per free coordinate: a box is not split along it once its side is this narrow.
    pub min_width: Vec<f64>,
    /// The interval engine's settings for the point runs at the boxes' centres; its deadline
    /// is the paving's time limit.
    pub taylor: TaylorOptions,
    /// Its settings for the slopes over boxes (the variational runs): order 8 and a loose local
    /// tolerance (the forms need 1e-6, not 1e-13). Order 8 measured against 16 on boxes of the
    /// DSS (κ, σ_b) slice: half the time (0.07 s against 0.13 s at v0 = 0.62) and no more
    /// failures (at v0 = 2.68 on a 0.004 × 0.001 box 8 succeeded where 16 grew too wide).
    pub slope_taylor: TaylorOptions,
    /// Slopes are first tried on boxes of at most this volume relative to the starting box
    /// (over wider boxes the variational runs wrap and fail, at a cost).
    pub slope_volume: f64,
    /// Most seconds one row's slopes may take on one box (a run that wraps slowly is given up
    /// and tried again on a smaller box).
    pub slope_seconds: f64,
    /// Most boxes processed (each one point run per open row, and slopes now and then).
    pub max_boxes: usize,
    /// Slopes are proved anew on a box once its sides are on average 2^refresh times narrower
    /// than those of the box they were proved on (∞: never; the forms' widths shrink with the
    /// boxes anyway, only the slopes' own width is kept).
    pub refresh: f64,
    /// Most contraction rounds per box.
    pub rounds: usize,
}

impl Options {
    /// Resolution `1/div` of the sides of `start`, the engine's default settings.
    pub fn new(start: &[Interval], div: f64) -> Self {
        let slope_taylor = TaylorOptions {
            tol: 1e-10,
            order: 8,
            ..TaylorOptions::default()
        };
        Self {
            min_width: start.iter().map(|x| x.wid() / div).collect(),
            taylor: TaylorOptions::default(),
            slope_taylor,
            slope_volume: 1.0,
            slope_seconds: 0.25,
            max_boxes: 1_000_000,
            refresh: f64::INFINITY,
            rounds: 3,
        }
    }
}

/// Progress of a paving: boxes processed, boxes waiting, and the undecided share of the
/// starting box's volume (the waiting boxes included).
#[derive(Clone, Copy, Debug)]
pub struct Progress {
    pub processed: usize,
    pub queued: usize,
    pub undecided: f64,
}

/// The outcome of a paving.
#[derive(Clone, Debug)]
pub struct Paving {
    pub boxes: Vec<Leaf>,
    /// Boxes processed.
    pub processed: usize,
    /// The work stopped early (time limit or box budget): the reason.
    pub stopped: Option<String>,
    pub seconds: f64,
}

impl Paving {
    /// The outer hull of F per coordinate: the hull of the feasible and undecided boxes
    /// (`None`: F is proved empty).
    pub fn hull(&self) -> Option<Vec<(f64, f64)>> {
        hull_of(self.boxes.iter().filter(|b| b.status != Status::Infeasible))
    }

    /// The hull of the boxes proved feasible (`None`: none).
    pub fn feasible_hull(&self) -> Option<Vec<(f64, f64)>> {
        hull_of(self.boxes.iter().filter(|b| b.status == Status::Feasible))
    }

    /// Number of boxes of each status (feasible, infeasible, undecided).
    pub fn counts(&self) -> [usize; 3] {
        let c = |s| self.boxes.iter().filter(|b| b.status == s).count();
        [
            c(Status::Feasible),
            c(Status::Infeasible),
            c(Status::Undecided),
        ]
    }

    /// Share of the starting box's volume of each status (relative volumes, each side divided by
    /// the starting box's).
    ///
    /// Summed exactly (as rationals: the boxes' ends and the start's are doubles) and rounded
    /// so that what is proved is not overstated: the feasible and infeasible shares down, the
    /// undecided share up (0.25 exactly, where a sum in doubles gave 0.24999999999999986).
    pub fn shares(&self, start: &[Interval]) -> [f64; 3] {
        use rug::float::Round;
        let mut v: [rug::Rational; 3] = Default::default();
        for b in &self.boxes {
            let k = b.status as usize;
            v[k] += rel_volume(&b.lo, &b.hi, start);
        }
        let round = |r: &rug::Rational, up: bool| {
            rug::Float::with_val_round(53, r, if up { Round::Up } else { Round::Down })
                .0
                .to_f64()
        };
        [round(&v[0], false), round(&v[1], false), round(&v[2], true)]
    }
}

fn hull_of<'a>(mut it: impl Iterator<Item = &'a Leaf>) -> Option<Vec<(f64, f64)>> {
    let first = it.next()?;
    let mut h: Vec<(f64, f64)> = first
        .lo
        .iter()
        .zip(&first.hi)
        .map(|(&a, &b)| (a, b))
        .collect();
    for b in it {
        for (j, hj) in h.iter_mut().enumerate() {
            hj.0 = hj.0.min(b.lo[j]);
            hj.1 = hj.1.max(b.hi[j]);
        }
    }
    Some(h)
}

/// The volume of a box relative to the starting box's.
fn volume(u: &[Interval], start: &[Interval]) -> f64 {
    volume_of(u.iter().map(|x| x.wid()), start)
}

/// The volume of a box of the side lengths `widths` relative to the starting box's (in doubles:
/// for the queue's order and the progress display; the reported shares are exact,
/// [`rel_volume`]).
fn volume_of(widths: impl Iterator<Item = f64>, start: &[Interval]) -> f64 {
    widths
        .zip(start)
        .map(|(w, s)| if s.wid() > 0.0 { w / s.wid() } else { 1.0 })
        .product()
}

/// The box's volume relative to the start box, exactly.
fn rel_volume(lo: &[f64], hi: &[f64], start: &[Interval]) -> rug::Rational {
    let q = |x: f64| rug::Rational::from_f64(x).unwrap_or_default();
    lo.iter()
        .zip(hi)
        .zip(start)
        .map(|((&a, &b), s)| {
            let w = q(s.sup()) - q(s.inf());
            if w > 0 {
                (q(b) - q(a)) / w
            } else {
                rug::Rational::from(1)
            }
        })
        .fold(rug::Rational::from(1), |acc, x| acc * x)
}

/// One open row of a box: which of its observables are still open, and its slopes.
#[derive(Clone, Debug)]
struct Open {
    row: usize,
    e: bool,
    tc: bool,
    slopes: Option<Arc<RowSlopes>>,
    /// The relative volume of the last box on which the slopes could not be proved: they are
    /// tried again on boxes at most a quarter of it.
    failed: f64,
    /// Likewise for the hulls over the box (tried where the row has no slopes).
    hull_failed: f64,
}

#[derive(Clone, Debug)]
struct Node {
    u: Vec<Interval>,
    open: Vec<Open>,
}

/// What processing a box gives: boxes to report and boxes to process.
#[derive(Default)]
struct Outcome {
    leaves: Vec<Leaf>,
    children: Vec<Node>,
}

fn leaf(u: &[Interval], status: Status) -> Leaf {
    Leaf {
        lo: u.iter().map(|x| x.inf()).collect(),
        hi: u.iter().map(|x| x.sup()).collect(),
        status,
    }
}

/// The boxes of `u` outside `inner` (⊂ u): at most two slabs per coordinate.
fn difference(u: &[Interval], inner: &[Interval]) -> Vec<Vec<Interval>> {
    let mut out = Vec::new();
    let mut rest = u.to_vec();
    for j in 0..u.len() {
        let (a, b) = (rest[j].inf(), rest[j].sup());
        let (c, d) = (inner[j].inf(), inner[j].sup());
        if a < c {
            let mut s = rest.clone();
            s[j] = Interval::try_from((a, c)).expect("ordered");
            out.push(s);
        }
        if d < b {
            let mut s = rest.clone();
            s[j] = Interval::try_from((d, b)).expect("ordered");
            out.push(s);
        }
        rest[j] = inner[j];
    }
    out
}

/// One observable of a row: open, its centre value, slopes, hull over the slopes' box, target.
type Check<'a> = (
    bool,
    Interval,
    Option<&'a Vec<Interval>>,
    Interval,
    Option<Target>,
);

/// A row's verdict on a box.
enum Verdict {
    /// Proved violated on the whole box.
    Violated,
    /// The still-open observables, the contracted box (⊂ u), and the slopes used.
    Open {
        e: bool,
        tc: bool,
        u: Vec<Interval>,
        slopes: Option<Arc<RowSlopes>>,
        failed: f64,
        hull_failed: f64,
    },
}

/// Per row, what its slopes (`[0]`) and its hulls (`[1]`) did: the largest relative volume on
/// which they were proved and the smallest on which they failed.
type Reach = [(f64, f64); 2];

/// What to try for a row on a box: its slopes (it has them, or they are due), its hulls over
/// the box (where it has no slopes).
#[derive(Clone, Copy)]
struct Plan {
    slopes: bool,
    hull: bool,
}

struct Ctx<'a> {
    problem: &'a Problem,
    free: Vec<usize>,
    opts: &'a Options,
    start: &'a [Interval],
    /// Per row, what its slopes did before the current batch: the largest relative volume on
    /// which they were proved and the smallest on which they failed (a row is tried on a box no
    /// wider than the former, or narrower than the latter: the variational runs' reach depends
    /// mostly on the impact speed, little on where the box is). Read-only during a batch, so
    /// that the paving does not depend on the order in which the threads finish.
    reach: std::sync::RwLock<Vec<Reach>>,
    /// What the current batch's runs add to it (max and min commute: merged after the batch).
    reach_new: Vec<std::sync::Mutex<Reach>>,
}

impl Ctx<'_> {
    fn inputs(&self, u: &[Interval], v0: Interval) -> Inputs<Interval> {
        let [b, gamma, kappa, sigma, n, p] = self.problem.base(u);
        Inputs::Base {
            base: NdParams {
                b,
                gamma,
                kappa,
                sigma,
                n,
                p,
            },
            v0,
        }
    }

    /// Whether every point of the box is in 𝓟 (|Γ_b| < B_b strictly; the other conditions
    /// hold on the whole starting box).
    fn inside(&self, u: &[Interval]) -> bool {
        let base = self.problem.base(u);
        let (b, g) = (base[0], base[1]);
        g.sup() < b.inf() && -g.inf() < b.inf()
    }

    /// 𝓟's contraction of step 1 (`None`: no point of the box is in 𝓟).
    fn admissible(&self, u: &[Interval]) -> Option<Vec<Interval>> {
        let (ib, ig) = (
            self.free.iter().position(|&f| f == 0),
            self.free.iter().position(|&f| f == 1),
        );
        let base = self.problem.base(u);
        let (b, g) = (base[0], base[1]);
        let mut out = u.to_vec();
        if let Some(j) = ig {
            let lim = Interval::try_from((-b.sup(), b.sup())).ok()?;
            out[j] = out[j].intersection(lim);
            if out[j].is_empty() {
                return None;
            }
        }
        let g = ig.map_or(g, |j| out[j]);
        if let Some(j) = ib {
            let min_abs = if g.contains(0.0) { 0.0 } else { g.mig() };
            out[j] = out[j].intersection(Interval::try_from((min_abs, f64::INFINITY)).ok()?);
            if out[j].is_empty() {
                return None;
            }
        } else if g.mig() >= b.sup() && !g.contains(0.0) {
            return None;
        }
        Some(out)
    }

    fn stale(&self, s: &RowSlopes, u: &[Interval]) -> bool {
        // hulls alone (no derivative over the box) do not shrink with the sub-boxes
        if s.e.is_none() || (s.tc.is_none() && self.problem.rows.iter().any(|r| r.tc.is_some())) {
            return s.widths.iter().zip(u).any(|(w, x)| x.wid() < *w);
        }
        let k: f64 = s
            .widths
            .iter()
            .zip(u)
            .filter(|(w, _)| **w > 0.0)
            .map(|(w, x)| (w / x.wid().max(f64::MIN_POSITIVE)).log2())
            .sum();
        k >= self.opts.refresh * u.len() as f64
    }

    /// The time budget of one run over a box (slopes or hulls).
    fn budgeted(&self) -> TaylorOptions {
        let mut so = self.opts.slope_taylor.clone();
        let own = Instant::now() + std::time::Duration::from_secs_f64(self.opts.slope_seconds);
        so.deadline = Some(so.deadline.map_or(own, |d| d.min(own)));
        so
    }

    /// The verdict of row `o` on box `u` about centre `c`: for a row without slopes its hulls
    /// over the box first where they are due (one run, ≈ 1/4 of the slopes' cost: they decide
    /// most boxes at the resolution), then the mean-value forms from its slopes.
    fn row(&self, o: &Open, u: &[Interval], c: &[Interval], plan: Plan) -> Verdict {
        let mut o = o.clone();
        if o.slopes.is_none() && plan.hull {
            match self.by_hull(&o, u, o.failed) {
                Verdict::Open {
                    e, tc, hull_failed, ..
                } if e || tc => {
                    o.e = e;
                    o.tc = tc;
                    o.hull_failed = hull_failed;
                }
                settled => return settled,
            }
        }
        let o = &o;
        let row = &self.problem.rows[o.row];
        let mut slopes = o.slopes.clone();
        let mut failed = o.failed;
        let vol = volume(u, self.start);
        let due = match &slopes {
            None => plan.slopes,
            Some(s) => self.stale(s, u),
        };
        if due {
            let base = self.problem.base(u);
            let t = Instant::now();
            let r = slopes_over_set(self.problem.kind, &self.inputs(u, row.v0), &self.budgeted());
            if trace() {
                eprintln!(
                    "slopes row {} box {:?}: {:.3} s {}",
                    o.row,
                    u.iter().map(|x| (x.inf(), x.sup())).collect::<Vec<_>>(),
                    t.elapsed().as_secs_f64(),
                    r.as_ref()
                        .map(|_| "ok".to_string())
                        .unwrap_or_else(|e| e.reason.clone())
                );
            }
            match r {
                Ok(s) => {
                    let mut r = self.reach_new[o.row].lock().expect("not poisoned");
                    r[0].0 = r[0].0.max(vol);
                    slopes = Some(Arc::new(RowSlopes::new(&s, u, &self.free, base[5], row.v0)))
                }
                Err(_) => {
                    let mut r = self.reach_new[o.row].lock().expect("not poisoned");
                    r[0].1 = r[0].1.min(vol);
                    failed = vol
                }
            }
        }
        let keep = |slopes| Verdict::Open {
            e: o.e,
            tc: o.tc,
            u: u.to_vec(),
            slopes,
            failed,
            hull_failed: o.hull_failed,
        };
        let Some(s) = slopes else {
            return keep(None);
        };
        let t = Instant::now();
        let r = prove_at_point(
            self.problem.kind,
            &self.inputs(c, row.v0),
            &self.opts.taylor,
        );
        if trace() {
            eprintln!(
                "point row {} {:.3} s {}",
                o.row,
                t.elapsed().as_secs_f64(),
                r.as_ref()
                    .map(|_| "ok".to_string())
                    .unwrap_or_else(|e| e.reason.clone())
            );
        }
        let Ok((ts_c, e_c)) = r else {
            return keep(Some(s));
        };
        let mut out = u.to_vec();
        let mut open = (o.e, o.tc);
        // e, then tc: each enclosed, tested and used to contract
        let p_c = self.problem.base(c)[5];
        let tc_c = ts_c * tc_factor(row.v0, p_c).0;
        let checks: [Check; 2] = [
            (o.e, e_c, s.e.as_ref(), s.e_hull, Some(row.e)),
            (o.tc, tc_c, s.tc.as_ref(), s.tc_hull, row.tc),
        ];
        for (k, (is_open, yc, g, hull, target)) in checks.into_iter().enumerate() {
            let Some(target) = target.filter(|_| is_open) else {
                continue;
            };
            let y = match g {
                Some(g) => enclose(yc, g, &out, c, hull),
                None => hull,
            };
            let outer = target.outer();
            if trace() {
                eprintln!(
                    "form row {} obs {k}: y [{:.6}, {:.6}] centre [{:.6}, {:.6}] target [{:.6}, {:.6}] slopes {:?}",
                    o.row,
                    y.inf(),
                    y.sup(),
                    yc.inf(),
                    yc.sup(),
                    outer.inf(),
                    outer.sup(),
                    g.map(|g| g.iter().map(|x| (x.inf(), x.sup())).collect::<Vec<_>>())
                );
            }
            if y.is_empty() || y.disjoint(outer) {
                return Verdict::Violated;
            }
            if target.inner().is_some_and(|i| y.subset(i)) {
                if k == 0 {
                    open.0 = false;
                } else {
                    open.1 = false;
                }
                continue;
            }
            if let Some(g) = g {
                match contract(yc, g, &out, c, outer) {
                    Some(k) => out = k,
                    None => return Verdict::Violated,
                }
            }
        }
        Verdict::Open {
            e: open.0,
            tc: open.1,
            u: out,
            slopes: Some(s),
            failed,
            hull_failed: o.hull_failed,
        }
    }

    /// The verdict of row `o` on box `u` by the hulls of T_s and e over it (`hull_over_set`:
    /// the parameters as components, no derivative), for a row without slopes: e(U) (or
    /// tc(U) ⊂ T_s(U)·c(p(U))) outside the outer target refutes the box, inside the inner one
    /// closes the observable on it. No contraction (a hull has no slope).
    fn by_hull(&self, o: &Open, u: &[Interval], failed: f64) -> Verdict {
        let row = &self.problem.rows[o.row];
        let vol = volume(u, self.start);
        let open = |e, tc, hull_failed| Verdict::Open {
            e,
            tc,
            u: u.to_vec(),
            slopes: None,
            failed,
            hull_failed,
        };
        let t = Instant::now();
        let mut ho = self.budgeted();
        ho.tol = HULL_TOL;
        let r = hull_over_set(self.problem.kind, &self.inputs(u, row.v0), &ho);
        if trace() {
            eprintln!(
                "hull row {} box {:?}: {:.3} s {}",
                o.row,
                u.iter().map(|x| (x.inf(), x.sup())).collect::<Vec<_>>(),
                t.elapsed().as_secs_f64(),
                r.as_ref()
                    .map(|(ts, e)| format!("ok ts {:e} e {:e}", ts.wid(), e.wid()))
                    .unwrap_or_else(|e| e.reason.clone())
            );
        }
        let (ts, e) = match r {
            Ok(r) => {
                let mut m = self.reach_new[o.row].lock().expect("not poisoned");
                m[1].0 = m[1].0.max(vol);
                r
            }
            Err(_) => {
                let mut m = self.reach_new[o.row].lock().expect("not poisoned");
                m[1].1 = m[1].1.min(vol);
                return open(o.e, o.tc, vol);
            }
        };
        let tc = ts * tc_factor(row.v0, self.problem.base(u)[5]).0;
        let mut still = [o.e, o.tc];
        for (k, y, target) in [(0, e, Some(row.e)), (1, tc, row.tc)] {
            let Some(target) = target.filter(|_| still[k]) else {
                continue;
            };
            // an empty enclosure (an engine fault) decides nothing
            if y.is_empty() {
                continue;
            }
            if y.disjoint(target.outer()) {
                return Verdict::Violated;
            }
            if target.inner().is_some_and(|i| y.subset(i)) {
                still[k] = false;
            }
        }
        // nothing closed: tried again on boxes at most half this one
        let hull_failed = if still == [o.e, o.tc] {
            2.0 * vol
        } else {
            o.hull_failed
        };
        open(still[0], still[1], hull_failed)
    }

    fn process(&self, node: Node, start: &[Interval]) -> Outcome {
        let mut out = Outcome::default();
        let Some(mut u) = self.admissible(&node.u) else {
            out.leaves.push(leaf(&node.u, Status::Infeasible));
            return out;
        };
        for s in difference(&node.u, &u) {
            out.leaves.push(leaf(&s, Status::Infeasible));
        }
        let mut open = node.open;
        if self.inside(&u) {
            // which rows to try (the f64 guess, module `guide`): the surest violated one alone;
            // every open row when each is guessed inside; none when some row cannot be decided
            // at this size (the box is bisected at once)
            let guesses: Vec<Guess> = open
                .par_iter()
                .map(|o| guess(self.problem, &u, o.row, o.e, o.tc))
                .collect();
            // a row can be tried when it has slopes, or they are due on this box and have not
            // failed on a box less than 4 times its size (in its lineage, and no wider than
            // they were proved on or narrower than they failed on, anywhere), or likewise its
            // hulls; among the violated ones the one with slopes, else the slowest impact (the
            // variational runs succeed on wider boxes at low speeds), else the surest
            let vol = volume(&u, self.start);
            let reach = self.reach.read().expect("not poisoned").clone();
            let plan = |o: &Open| {
                let [(ok, bad), (hull_ok, hull_bad)] = reach[o.row];
                let fits = |failed: f64, ok: f64, bad: f64| {
                    vol <= self.opts.slope_volume && vol <= failed / 4.0 && (vol <= ok || vol < bad)
                };
                Plan {
                    slopes: o.slopes.is_some() || fits(o.failed, ok, bad),
                    hull: o.slopes.is_none() && fits(o.hull_failed, hull_ok, hull_bad),
                }
            };
            let tryable = |o: &Open| {
                let p = plan(o);
                p.slopes || p.hull
            };
            let violated = guesses
                .iter()
                .zip(&open)
                .enumerate()
                .filter_map(|(i, (g, o))| match *g {
                    Guess::Violated { ratio } if ratio > SAFETY && tryable(o) => {
                        Some((i, ratio, o))
                    }
                    _ => None,
                })
                .max_by(|a, b| {
                    let key = |(_, r, o): &(usize, f64, &Open)| {
                        (o.slopes.is_some(), -self.problem.rows[o.row].v0.inf(), *r)
                    };
                    let (ka, kb) = (key(a), key(b));
                    ka.0.cmp(&kb.0)
                        .then(ka.1.total_cmp(&kb.1))
                        .then(ka.2.total_cmp(&kb.2))
                })
                .map(|(i, _, _)| i);
            let tried: Vec<bool> = match violated {
                Some(i) => (0..open.len()).map(|k| k == i).collect(),
                // no row guessed violated: the rows guessed inside, so that the sub-boxes of a
                // box that is bisected anyway (other rows open) do not run them again
                None if !guesses.iter().any(|g| matches!(g, Guess::Violated { .. })) => guesses
                    .iter()
                    .zip(&open)
                    .map(|(g, o)| *g == Guess::Inside && tryable(o))
                    .collect(),
                None => vec![false; open.len()],
            };
            let (mut active, mut waiting): (Vec<Open>, Vec<Open>) = (Vec::new(), Vec::new());
            for (o, t) in open.into_iter().zip(tried) {
                if t { active.push(o) } else { waiting.push(o) }
            }
            for _ in 0..self.opts.rounds.max(1) {
                if active.is_empty() {
                    break;
                }
                let c = centre_of(&u);
                let verdicts: Vec<Verdict> = active
                    .par_iter()
                    .map(|o| self.row(o, &u, &c, plan(o)))
                    .collect();
                let mut next = u.clone();
                let mut still = Vec::new();
                for (o, v) in active.iter().zip(verdicts) {
                    match v {
                        Verdict::Violated => {
                            out.leaves.push(leaf(&u, Status::Infeasible));
                            return out;
                        }
                        Verdict::Open {
                            e,
                            tc,
                            u: k,
                            slopes,
                            failed,
                            hull_failed,
                        } => {
                            for (x, y) in next.iter_mut().zip(&k) {
                                *x = x.intersection(*y);
                            }
                            if e || tc {
                                still.push(Open {
                                    row: o.row,
                                    e,
                                    tc,
                                    slopes,
                                    failed,
                                    hull_failed,
                                });
                            }
                        }
                    }
                }
                active = still;
                if next.iter().any(|x| x.is_empty()) {
                    out.leaves.push(leaf(&u, Status::Infeasible));
                    return out;
                }
                for s in difference(&u, &next) {
                    out.leaves.push(leaf(&s, Status::Infeasible));
                }
                let shrunk = u.iter().zip(&next).any(|(a, b)| b.wid() < 0.8 * a.wid());
                u = next;
                if active.is_empty() || !shrunk {
                    break;
                }
            }
            active.append(&mut waiting);
            active.sort_by_key(|o| o.row);
            open = active;
            if open.is_empty() && self.inside(&u) {
                out.leaves.push(leaf(&u, Status::Feasible));
                return out;
            }
        }
        // bisect the side widest relative to the starting box, above the resolution
        let j = (0..u.len())
            .filter(|&j| u[j].wid() > self.opts.min_width[j])
            .max_by(|&a, &b| {
                let r = |j: usize| u[j].wid() / start[j].wid();
                r(a).total_cmp(&r(b))
            });
        let Some(j) = j else {
            out.leaves.push(leaf(&u, Status::Undecided));
            return out;
        };
        let m = u[j].mid();
        for (a, b) in [(u[j].inf(), m), (m, u[j].sup())] {
            let mut v = u.clone();
            v[j] = Interval::try_from((a, b)).expect("ordered halves");
            out.children.push(Node {
                u: v,
                open: open.clone(),
            });
        }
        out
    }
}

/// `BWCL_TRACE_IDENTIFY` set: the runs' times on stderr (read once).
fn trace() -> bool {
    static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ON.get_or_init(|| std::env::var_os("BWCL_TRACE_IDENTIFY").is_some())
}

/// A total order on f64 keys for the work queues.
#[derive(Clone, Copy, PartialEq)]
struct Key(f64);
impl Eq for Key {}
impl PartialOrd for Key {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Key {
    fn cmp(&self, o: &Self) -> Ordering {
        self.0.total_cmp(&o.0)
    }
}

/// Paves `start` (a box of the free parameters of `problem`, in the order of `Space::free`).
pub fn pave(
    problem: &Problem,
    start: &[Interval],
    opts: &Options,
    progress: Option<&(dyn Fn(Progress) + Sync)>,
) -> Paving {
    let t0 = Instant::now();
    let ctx = Ctx {
        problem,
        free: problem.space.free(),
        opts,
        start,
        reach: std::sync::RwLock::new(vec![[(0.0, f64::INFINITY); 2]; problem.rows.len()]),
        reach_new: (0..problem.rows.len())
            .map(|_| std::sync::Mutex::new([(0.0, f64::INFINITY); 2]))
            .collect(),
    };
    let dim = start.len();
    let open = (0..problem.rows.len())
        .map(|row| Open {
            row,
            e: true,
            tc: problem.rows[row].tc.is_some(),
            slopes: None,
            failed: f64::INFINITY,
            hull_failed: f64::INFINITY,
        })
        .collect();
    let mut nodes: Vec<Option<Node>> = vec![Some(Node {
        u: start.to_vec(),
        open,
    })];
    // heap 0: volume; heaps 1 + 2j, 2 + 2j: lowest lower end, highest upper end of coordinate j
    let mut heaps: Vec<BinaryHeap<(Key, usize)>> =
        (0..1 + 2 * dim).map(|_| BinaryHeap::new()).collect();
    let keys = |u: &[Interval]| -> Vec<f64> {
        let mut k = vec![
            u.iter()
                .zip(start)
                .map(|(x, s)| x.wid() / s.wid())
                .product(),
        ];
        for x in u {
            k.push(-x.inf());
            k.push(x.sup());
        }
        k
    };
    let push = |heaps: &mut Vec<BinaryHeap<(Key, usize)>>, id: usize, u: &[Interval]| {
        for (h, k) in heaps.iter_mut().zip(keys(u)) {
            h.push((Key(k), id));
        }
    };
    push(&mut heaps, 0, start);
    let mut waiting = 1usize;
    let mut leaves = Vec::new();
    let mut processed = 0usize;
    let mut turn = 0usize;
    let mut stopped = None;
    // batches of several boxes per thread: a box's work ranges from one f64 guess (ms) to
    // slopes (0.1–0.25 s), and a batch waits for its slowest box
    let batch = 8 * rayon::current_num_threads().max(1);
    while waiting > 0 {
        if opts.taylor.out_of_time() {
            stopped = Some("the time limit was reached".to_string());
            break;
        }
        if processed >= opts.max_boxes {
            stopped = Some(format!("the budget of {} boxes was spent", opts.max_boxes));
            break;
        }
        let mut take = Vec::new();
        while take.len() < batch && waiting > 0 {
            // half by volume, half round-robin over the coordinates' ends
            let h = if turn.is_multiple_of(2) {
                0
            } else {
                1 + (turn / 2) % (2 * dim)
            };
            turn += 1;
            while let Some((_, id)) = heaps[h].pop() {
                if let Some(n) = nodes[id].take() {
                    take.push(n);
                    waiting -= 1;
                    break;
                }
            }
        }
        processed += take.len();
        let outs: Vec<Outcome> = take
            .into_par_iter()
            .map(|n| ctx.process(n, start))
            .collect();
        {
            let mut reach = ctx.reach.write().expect("not poisoned");
            for (r, n) in reach.iter_mut().zip(&ctx.reach_new) {
                *r = *n.lock().expect("not poisoned");
            }
        }
        for o in outs {
            leaves.extend(o.leaves);
            for c in o.children {
                let id = nodes.len();
                push(&mut heaps, id, &c.u);
                nodes.push(Some(c));
                waiting += 1;
            }
        }
        if let Some(f) = progress {
            let mut undecided: f64 = nodes.iter().flatten().map(|n| volume(&n.u, start)).sum();
            undecided += leaves
                .iter()
                .filter(|l| l.status == Status::Undecided)
                .map(|l| volume_of(l.lo.iter().zip(&l.hi).map(|(a, b)| b - a), start))
                .sum::<f64>();
            f(Progress {
                processed,
                queued: waiting,
                undecided,
            });
        }
    }
    for n in nodes.into_iter().flatten() {
        leaves.push(leaf(&n.u, Status::Undecided));
    }
    Paving {
        boxes: leaves,
        processed,
        stopped,
        seconds: t0.elapsed().as_secs_f64(),
    }
}
