//! Proved T_s and e over ranges of the inputs, split adaptively until the hull is tight.
//!
//! One run of the variational system over a wide range wraps (its enclosure can be far wider
//! than the spread of e over the range) or fails ("grew too wide"). The range is therefore cut
//! into pieces, each proved by [`prove_over_set`], and the result is the hull of the pieces —
//! valid for every input value in the ranges. Which pieces are cut:
//!
//! 1. a piece that could not be proved (bisected along its relatively widest range);
//! 2. otherwise a piece that makes the hull wider than it must be. The point runs at the
//!    pieces' centres (and at the set's two extreme corners) prove values that e takes on the
//!    set, so
//!
//!    ```text
//!    min e ≤ a := min_c sup e(c),    max e ≥ b := max_c inf e(c)      (c: the proved points)
//!    ```
//!
//!    and [a, b] is an *inner* bound of the range of e (when a ≤ b: the spread max e − min e
//!    is at least b − a). A piece whose e enclosure reaches below a (above b) by more than the
//!    tolerance is an *overshoot* of the hull's end; the largest overshoots (of e or T_s) are
//!    cut first, so the hull's ends converge first and no work is spent inside.
//!
//! It stops when every overshoot is within the tolerance — a fraction [`SplitOptions::rel`] of
//! the inner spread b − a, or a few widths of the point enclosures, below which no cut can go —
//! or when the ceiling of pieces or the time is spent (the hull is proved then too, only wider;
//! the outcome says so). The proved ratio wid(hull)/(b − a) bounds how far the hull can be from
//! the true range: it is printed with the result.
//!
//! Measured (SHC DSS, v0 ∈ [0.1, 5], default ceiling): see `cor --rigorous` in README.md.

use inari::Interval;
use rayon::prelude::*;

use super::sets::{Inputs, SetEnclosure, is_range, prove_at_point, prove_over_set};
use crate::engines::taylor::{RigorError, TaylorOptions};
use crate::models::ModelKind;

/// Budget and aim of [`prove_over_set_adaptive`].
#[derive(Clone, Debug)]
pub struct SplitOptions {
    /// Ceiling of the number of pieces of the final partition.
    pub max_pieces: usize,
    /// An overshoot of the hull's end is tolerated up to `rel` × the inner spread (so that
    /// the hull is at most ≈ (1 + 2·rel) × the spread).
    pub rel: f64,
}

impl Default for SplitOptions {
    fn default() -> Self {
        Self {
            max_pieces: 256,
            rel: 0.05,
        }
    }
}

/// Why the split stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// Every overshoot of the hull's ends is within the tolerance.
    Tight,
    /// The ceiling of pieces was reached first.
    Pieces,
    /// The time limit (`TaylorOptions::deadline`) was reached first.
    Time,
    /// A piece to cut could not be proved in halves (its hull is kept).
    Unsplittable,
}

/// Proved T_s and e over the set, with what the split knows about their true ranges.
#[derive(Clone, Debug)]
pub struct SplitEnclosure {
    /// The hull over the pieces: T_s and e for every input value in the ranges.
    pub ts: Interval,
    pub e: Interval,
    /// Inner bounds [a, b] (module doc): min ≤ a and max ≥ b over the set, proved by point
    /// runs; `None` with fewer than two distinct points (or a > b).
    pub ts_inner: Option<[f64; 2]>,
    pub e_inner: Option<[f64; 2]>,
    /// The widest enclosure of a single point run: the floor of any cut's tightness.
    pub point_width_ts: f64,
    pub point_width_e: f64,
    pub pieces: usize,
    pub stop: Stop,
    /// Pieces of the proved flows, over all runs kept.
    pub steps: usize,
}

impl SplitEnclosure {
    /// wid(hull)/(b − a) for e: at least wid(hull)/(max e − min e), the factor by which the hull
    /// can exceed the true range (∞ when no inner spread is known).
    pub fn e_ratio(&self) -> f64 {
        ratio(&self.e, self.e_inner)
    }
    pub fn ts_ratio(&self) -> f64 {
        ratio(&self.ts, self.ts_inner)
    }

    /// A sentence on how tight the hull is and why it stopped, for the output's notes.
    pub fn summary(&self) -> String {
        let r = |x: f64| {
            if x.is_finite() {
                let d = super::decimal::directed(x, 3, super::decimal::Rounding::Up);
                format!("≤ {}×", d.map_or(format!("{x}"), |d| d.plain()))
            } else {
                "unknown×".into()
            }
        };
        let why = match self.stop {
            Stop::Tight => "tight".to_string(),
            Stop::Pieces => "the ceiling of --pieces was reached".to_string(),
            Stop::Time => "the time limit was reached".to_string(),
            Stop::Unsplittable => "a piece could not be proved in halves".to_string(),
        };
        let mut s = format!(
            "{} piece{} ({why}); width of e {} its spread over the range, of T_s {}",
            self.pieces,
            if self.pieces == 1 { "" } else { "s" },
            r(self.e_ratio()),
            r(self.ts_ratio())
        );
        for (name, inner, pw) in [
            ("e", self.e_inner, self.point_width_e),
            ("T_s", self.ts_inner, self.point_width_ts),
        ] {
            let spread = inner.map_or(0.0, |[a, b]| b - a);
            if spread <= 8.0 * pw {
                s.push_str(&format!(
                    "; the spread of {name} proved so far ({spread:.1e}) is within a few widths of \
                     a single point's enclosure ({pw:.1e}), so its ratio says little"
                ));
            }
        }
        s
    }
}

/// An upper bound of wid(h)/(b − a) (directed rounding: the width up, the spread down).
fn ratio(h: &Interval, inner: Option<[f64; 2]>) -> f64 {
    let pt = |x: f64| Interval::try_from((x, x)).ok();
    match inner {
        Some([a, b]) if b > a => match (pt(h.inf()), pt(h.sup()), pt(a), pt(b)) {
            (Some(l), Some(u), Some(a), Some(b)) => {
                let r = (u - l) / (b - a);
                if r.is_empty() { f64::INFINITY } else { r.sup() }
            }
            _ => f64::INFINITY,
        },
        _ => f64::INFINITY,
    }
}

/// A point of the set with its proved (T_s, e).
type Point = (Interval, Interval);

/// One piece of the partition: its inputs, its proof (or why not), its centre point's proof.
struct Piece {
    inputs: Inputs<Interval>,
    proof: Result<SetEnclosure, RigorError>,
    centre: Option<Point>,
    /// Cutting it failed once (a half not proved): it is kept whole.
    whole: bool,
    /// Proved or refused under a cap of steps below the options' own.
    capped: bool,
    /// Refused at that cap; and its parent was too.
    hit_cap: bool,
    parent_hit_cap: bool,
}

/// The cap of steps of a piece: this many times the most a proved piece took …
const CAP_FACTOR: usize = 10;
/// … and at least this many.
const MIN_CAP: usize = 2_000;
/// Pieces cut per pass when tightening (in parallel): a constant, so that the result does not
/// depend on the number of threads.
const BATCH: usize = 4;

/// The ranged inputs replaced by their midpoints (or by an end: `corner` −1 / +1, one double
/// inside).
fn at(inputs: &Inputs<Interval>, corner: i8) -> Inputs<Interval> {
    let v: Vec<Interval> = inputs
        .values()
        .into_iter()
        .map(|x| {
            if !is_range(&x) {
                return x;
            }
            // the corners one double inside the interval: a range written with decimal ends
            // is enclosed by doubles just outside them (0.1 by 0.09999999999999999), and the
            // inner bounds are claims about the range as written
            let p = match corner {
                -1 => x.inf().next_up(),
                1 => x.sup().next_down(),
                _ => x.mid(),
            };
            Interval::try_from((p, p)).unwrap_or(x)
        })
        .collect();
    inputs.with_values(v)
}

/// The two halves of a piece along its relatively widest range (`None`: no range to cut).
fn halves(inputs: &Inputs<Interval>) -> Option<[Inputs<Interval>; 2]> {
    let vals = inputs.values();
    let j = (0..vals.len())
        .filter(|&i| is_range(&vals[i]))
        .max_by(|&a, &b| {
            let rel = |x: &Interval| x.wid() / x.mag();
            rel(&vals[a]).total_cmp(&rel(&vals[b]))
        })?;
    let (lo, hi, m) = (vals[j].inf(), vals[j].sup(), vals[j].mid());
    if !(lo < m && m < hi) {
        return None;
    }
    Some([(lo, m), (m, hi)].map(|(a, b)| {
        let mut v = vals.clone();
        v[j] = Interval::try_from((a, b)).expect("lo < m < hi");
        inputs.with_values(v)
    }))
}

/// The ranged inputs named with their ranges, for a reason.
fn ranges_text(inputs: &Inputs<Interval>) -> String {
    let vals = inputs.values();
    (0..vals.len())
        .filter(|&i| is_range(&vals[i]))
        .map(|i| {
            format!(
                "{} in [{}, {}]",
                inputs.names()[i],
                vals[i].inf(),
                vals[i].sup()
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// `full`: the options' own ceiling of steps (`opts` may carry a lower cap).
fn prove_piece(
    kind: ModelKind,
    inputs: Inputs<Interval>,
    opts: &TaylorOptions,
    full: usize,
) -> Piece {
    let start = std::time::Instant::now();
    let proof = prove_over_set(kind, &inputs, opts);
    if std::env::var_os("BWCL_TRACE_SPLIT").is_some() {
        eprintln!(
            "split: {} {:.3} s: {}",
            ranges_text(&inputs),
            start.elapsed().as_secs_f64(),
            match &proof {
                Ok(r) => format!(
                    "e {:.3e} wide, ts {:.3e}, {} steps",
                    r.e.wid(),
                    r.ts.wid(),
                    r.steps
                ),
                Err(e) => e.reason.clone(),
            }
        );
    }
    let cap = format!("more than {} steps", opts.max_steps);
    let hit_cap =
        opts.max_steps < full && proof.as_ref().is_err_and(|e| e.reason.starts_with(&cap));
    // the centre: from the run when it proved one (one range), else a point run
    let centre = match &proof {
        Ok(SetEnclosure {
            centre: Some((_, ts, e)),
            ..
        }) => Some((*ts, *e)),
        Ok(_) => prove_at_point(kind, &at(&inputs, 0), opts).ok(),
        Err(_) => None,
    };
    Piece {
        inputs,
        proof,
        centre,
        whole: false,
        capped: opts.max_steps < full,
        hit_cap,
        parent_hit_cap: false,
    }
}

/// What the proved points say about the true ranges of (T_s, e): the inner bounds.
fn inner(points: &[Point], pick: impl Fn(&Point) -> Interval) -> Option<[f64; 2]> {
    let a = points
        .iter()
        .map(|p| pick(p).sup())
        .fold(f64::INFINITY, f64::min);
    let b = points
        .iter()
        .map(|p| pick(p).inf())
        .fold(f64::NEG_INFINITY, f64::max);
    (points.len() >= 2 && a <= b).then_some([a, b])
}

/// Encloses T_s and e of model `kind` for every value of `inputs` (module doc): the hull of
/// proved pieces, cut where a piece is not proved or overshoots the hull's ends. Fails with the
/// reason (naming the sub-range) when a piece cannot be proved within the ceiling of pieces or
/// the time, or when no separation happens before the horizon on the whole set.
pub fn prove_over_set_adaptive(
    kind: ModelKind,
    inputs: &Inputs<Interval>,
    opts: &TaylorOptions,
    split: &SplitOptions,
) -> Result<SplitEnclosure, RigorError> {
    let max_pieces = split.max_pieces.max(1);
    // the set's extreme corners: where a monotone e takes its extremes
    // (their steps: the scale of a piece's cap of steps below)
    let corners: Vec<SetEnclosure> = [-1, 1]
        .par_iter()
        .filter_map(|&c| prove_over_set(kind, &at(inputs, c), opts).ok())
        .collect();
    let mut points: Vec<Point> = corners.iter().map(|r| (r.ts, r.e)).collect();
    // a piece that will fail usually fails slowly: its set crosses the switching surfaces in
    // thousands of short steps before it grows too wide (measured, SHC DSS, v0 ∈ [3.85, 3.93]:
    // 11 294 steps and 5.2 s, where its halves take 197 and 173 steps, 0.12 s each). The pieces
    // run with a cap of CAP_FACTOR × the most steps a proved piece took (at least MIN_CAP);
    // one that hits it is cut like any other; a piece that hits it as its parent did needs
    // the steps, not a smaller set (Maxwell, B = 1000, Γ ∈ −999.9999999..−999.999999: every
    // piece hit a cap of 2000), and runs again without the cap, as does a piece that cannot
    // be cut. The scale before any piece is proved: the corners' point runs.
    let capped = |most: usize| TaylorOptions {
        max_steps: opts.max_steps.min((CAP_FACTOR * most).max(MIN_CAP)),
        ..opts.clone()
    };
    let mut most = corners.iter().map(|r| r.steps).max().unwrap_or(0);
    let mut pieces = vec![prove_piece(
        kind,
        inputs.clone(),
        &capped(most),
        opts.max_steps,
    )];
    let mut timed_out = false;
    loop {
        // 1. unproved pieces: cut (all of them at once, in parallel)
        if let Some(i) = pieces.iter().position(|p| p.proof.is_err()) {
            let e = pieces[i].proof.as_ref().expect_err("an error").clone();
            if e.out_of_time() {
                return Err(RigorError {
                    reason: format!(
                        "{} ({} pieces of the range proved, {} not)",
                        e.reason,
                        pieces.iter().filter(|p| p.proof.is_ok()).count(),
                        pieces.iter().filter(|p| p.proof.is_err()).count()
                    ),
                    ..e
                });
            }
            if e.no_separation() && pieces.len() == 1 {
                return Err(e);
            }
            // twice at the cap in a row: the same piece again, without it
            let again: Vec<usize> = (0..pieces.len())
                .filter(|&i| pieces[i].hit_cap && pieces[i].parent_hit_cap)
                .collect();
            if !again.is_empty() {
                let redone: Vec<(usize, Piece)> = again
                    .par_iter()
                    .map(|&i| {
                        let p = prove_piece(kind, pieces[i].inputs.clone(), opts, opts.max_steps);
                        (i, p)
                    })
                    .collect();
                for (i, p) in redone {
                    pieces[i] = p;
                }
                continue;
            }
            let failed: Vec<usize> = (0..pieces.len())
                .filter(|&i| pieces[i].proof.is_err())
                .collect();
            let cut: Vec<[Inputs<Interval>; 2]> = failed
                .iter()
                .map_while(|&i| halves(&pieces[i].inputs))
                .collect();
            if cut.len() < failed.len() || pieces.len() + failed.len() > max_pieces {
                // the last resort: the failed pieces without the cap of steps
                if failed.iter().any(|&i| pieces[i].capped) {
                    let again: Vec<(usize, Piece)> = failed
                        .par_iter()
                        .map(|&i| {
                            (
                                i,
                                prove_piece(kind, pieces[i].inputs.clone(), opts, opts.max_steps),
                            )
                        })
                        .collect();
                    for (i, p) in again {
                        pieces[i] = p;
                    }
                    continue;
                }
                let p = &pieces[failed[cut.len().min(failed.len() - 1)]];
                let ranges = ranges_text(&p.inputs);
                let e = p.proof.as_ref().expect_err("an error");
                return Err(RigorError {
                    reason: if ranges.is_empty() {
                        e.reason.clone()
                    } else {
                        format!("for {ranges} (of {} pieces): {}", pieces.len(), e.reason)
                    },
                    ..e.clone()
                });
            }
            let hits: Vec<bool> = failed.iter().map(|&i| pieces[i].hit_cap).collect();
            let new: Vec<Piece> = cut
                .into_par_iter()
                .zip(hits)
                .flat_map_iter(|(h, hit)| h.into_iter().map(move |inp| (inp, hit)))
                .map(|(inp, hit)| Piece {
                    parent_hit_cap: hit,
                    ..prove_piece(kind, inp, &capped(most), opts.max_steps)
                })
                .collect();
            pieces.retain(|p| p.proof.is_ok());
            pieces.extend(new);
            continue;
        }
        // 2. every piece proved: the hull, the inner bounds, the overshoots
        most = pieces
            .iter()
            .filter_map(|p| p.proof.as_ref().ok().map(|r| r.steps))
            .fold(most, usize::max);
        points.extend(pieces.iter().filter_map(|p| p.centre));
        points.sort_by(|a, b| a.1.inf().total_cmp(&b.1.inf()));
        points.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1);
        let proofs: Vec<&SetEnclosure> = pieces.iter().map(|p| p.proof.as_ref().unwrap()).collect();
        let hull = |f: &dyn Fn(&SetEnclosure) -> Interval| {
            proofs
                .iter()
                .map(|r| f(r))
                .reduce(|a, b| a.convex_hull(b))
                .expect("a piece")
        };
        let (ts, e) = (hull(&|r| r.ts), hull(&|r| r.e));
        let (ts_in, e_in) = (inner(&points, |p| p.0), inner(&points, |p| p.1));
        let pw =
            |f: &dyn Fn(&Point) -> Interval| points.iter().map(|p| f(p).wid()).fold(0.0, f64::max);
        let (pw_ts, pw_e) = (pw(&|p| p.0), pw(&|p| p.1));
        // tolerance of an overshoot: rel × the inner spread, not below a few point widths
        let tol = |inn: Option<[f64; 2]>, pwid: f64| {
            (split.rel * inn.map_or(0.0, |[a, b]| b - a)).max(4.0 * pwid)
        };
        let (tol_ts, tol_e) = (tol(ts_in, pw_ts), tol(e_in, pw_e));
        // how far a piece's enclosure reaches beyond the inner bounds, in tolerances
        let over = |x: &Interval, inn: Option<[f64; 2]>, t: f64| match inn {
            Some([a, b]) => ((a - x.inf()).max(x.sup() - b).max(0.0)) / t,
            // no inner spread yet: the widest pieces first
            None => x.wid() / t,
        };
        let mut cands: Vec<(f64, usize)> = pieces
            .iter()
            .enumerate()
            .filter(|(_, p)| !p.whole)
            .map(|(i, p)| {
                let r = p.proof.as_ref().unwrap();
                (over(&r.e, e_in, tol_e).max(over(&r.ts, ts_in, tol_ts)), i)
            })
            .filter(|&(o, _)| o > 1.0)
            .collect();
        cands.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let done = |stop: Stop, pieces: &[Piece]| SplitEnclosure {
            ts,
            e,
            ts_inner: ts_in,
            e_inner: e_in,
            point_width_ts: pw_ts,
            point_width_e: pw_e,
            pieces: pieces.len(),
            stop,
            steps: pieces
                .iter()
                .map(|p| p.proof.as_ref().map_or(0, |r| r.steps))
                .sum(),
        };
        if cands.is_empty() {
            let stop = if timed_out {
                Stop::Time
            } else if pieces.iter().any(|p| p.whole) {
                Stop::Unsplittable
            } else {
                Stop::Tight
            };
            return Ok(done(stop, &pieces));
        }
        let room = max_pieces.saturating_sub(pieces.len());
        if room == 0 {
            return Ok(done(Stop::Pieces, &pieces));
        }
        if opts.out_of_time() {
            return Ok(done(Stop::Time, &pieces));
        }
        // 3. cut the largest overshoots (a batch, in parallel); a parent stays until both its
        // halves are proved, so the hull is proved at every stage
        let chosen: Vec<usize> = cands
            .iter()
            .take(BATCH.min(room))
            .map(|&(_, i)| i)
            .collect();
        let tried: Vec<(usize, Option<[Piece; 2]>)> = chosen
            .par_iter()
            .map(|&i| {
                let h = halves(&pieces[i].inputs).map(|[a, b]| {
                    let o = capped(most);
                    let (pa, pb) = rayon::join(
                        || prove_piece(kind, a, &o, opts.max_steps),
                        || prove_piece(kind, b, &o, opts.max_steps),
                    );
                    [pa, pb]
                });
                (i, h.filter(|[a, b]| a.proof.is_ok() && b.proof.is_ok()))
            })
            .collect();
        let mut replace: Vec<(usize, [Piece; 2])> = Vec::new();
        for (i, h) in tried {
            match h {
                Some(two) => replace.push((i, two)),
                None => {
                    timed_out |= opts.out_of_time();
                    pieces[i].whole = true;
                }
            }
        }
        replace.sort_by_key(|r| std::cmp::Reverse(r.0));
        for (i, [a, b]) in replace {
            pieces.swap_remove(i);
            pieces.push(a);
            pieces.push(b);
        }
        if timed_out {
            // the pieces proved so far stand; the next pass returns their hull
            for p in &mut pieces {
                p.whole = true;
            }
        }
    }
}
