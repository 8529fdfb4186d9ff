//! Proved feasible sets of a classical law (issue #33, item 4): the set-membership problem of
//! [`super::problem`] for the one-parameter families of [`crate::fit::laws`],
//!
//! ```text
//! F = {θ ∈ [lo, hi] : |e(θ, v0_i) − e_i| ≤ E_i for every row i},
//! ```
//!
//! paved into intervals proved feasible, proved infeasible and undecided, in the output shape of
//! [`super::paving::Paving`]. Over an interval [a, b] where the law is proved monotone
//! ([`Law::monotone_from`]) each row's e lies between the rigorous engine's enclosures at a and b
//! (thin runs, cached per end, so each split costs one run per row); elsewhere the engine runs
//! on [a, b] itself. A row whose e is proved outside its outer target refutes the interval; an
//! interval on which every row is proved inside its inner target is feasible; the rest is split
//! — at the geometric mean of the distances to the admissible set's floor while they differ by
//! more than 4× (the parameters span decades), else at the midpoint — until its width is below
//! 1/N of its distance to the floor (or 1e−12 of the starting width), then undecided — or below
//! 1/16 of it where the engine failed for a row (at large damping the separation becomes
//! undecidable for the engine, and splitting does not cure it).
//!
//! An empty F is a certificate that no law of the family fits the data at those errors; the
//! refuting rows are kept per infeasible interval ([`Refutation`]), so the certificate names
//! them: "row 3 refutes σ_b ∈ [0.21, 100]; row 17 refutes σ_b ∈ [0, 0.21]".
//!
//! Hooke's and Hertz's laws have no parameter (e = 1): F is one point, decided by one
//! rigorous run against every row (a leaf with no coordinates).

use super::paving::{Leaf, Paving, Progress, Status};
use super::problem::{Row, Target, check_error};
use crate::engines::taylor::TaylorOptions;
use crate::fit::data::CorData;
use crate::fit::laws::{Law, Monotone};
use inari::Interval;
use rayon::prelude::*;
use std::collections::HashMap;
use std::time::Instant;

/// A law's set-membership problem: CoR rows only (durations are the Bouc–Wen models').
#[derive(Clone, Debug)]
pub struct LawProblem {
    pub law: Law,
    pub rows: Vec<Row>,
}

impl LawProblem {
    /// Every e of `data` known to ±`error` (a `sigma` column overrides it per row). A tc
    /// column is refused unless `ignore_tc`.
    pub fn new(
        law: Law,
        data: &CorData,
        error: Option<f64>,
        ignore_tc: bool,
    ) -> Result<Self, String> {
        check_error(data, error)?;
        if data.tc.is_some() && !ignore_tc {
            return Err(format!(
                "the data have a column tc: the law {} is identified from CoRs alone \
                 (--no-tc to ignore the column)",
                law.key()
            ));
        }
        let rows = (0..data.len()).map(|i| Row::cor(data, i, error)).collect();
        Ok(Self { law, rows })
    }
}

/// The resolution of intervals on which the engine failed for some row (module doc).
pub const FAILED_RESOLUTION: f64 = 16.0;

/// Settings of a law's paving.
#[derive(Clone, Debug)]
pub struct LawOptions {
    /// N: an interval is not split once narrower than 1/N of its distance to the floor.
    pub resolution: f64,
    pub taylor: TaylorOptions,
    pub max_boxes: usize,
}

/// Row `row` (0-based, file order) refutes θ ∈ [lo, hi]: its e is proved outside the row's
/// target there. hi = ∞ and lo = the admissible floor (excluded where the set excludes it) come
/// from monotonicity: the row's e is proved outside its target at the box's end on the side
/// that the law's monotone e keeps beyond it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Refutation {
    pub row: usize,
    pub lo: f64,
    pub hi: f64,
}

/// A law's paving and the rows that refute its infeasible intervals (adjacent intervals
/// refuted by one row merged).
#[derive(Clone, Debug)]
pub struct LawPaving {
    pub paving: Paving,
    pub refuted: Vec<Refutation>,
}

impl LawPaving {
    /// F is proved empty over the law's whole admissible set (not only the box): the
    /// refutations reach from its floor to ∞.
    pub fn refutes_all(&self, law: Law) -> bool {
        self.paving.hull().is_none()
            && match (law.parameter(), self.refuted.first(), self.refuted.last()) {
                (None, Some(_), _) => true,
                (Some(_), Some(a), Some(b)) => a.lo == law.floor().0 && b.hi == f64::INFINITY,
                _ => false,
            }
    }
}

/// A decided interval [a, b]: its status and the refuting row (with whether its e is below
/// the target).
type Interval1 = (f64, f64, Status, Option<(usize, bool)>);

/// What one row says about an interval.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum RowVerdict {
    Inside,
    /// Proved below the outer target (`true`) or above it.
    Outside(bool),
    Open,
}

fn judge(e: Option<Interval>, t: &Target) -> RowVerdict {
    match e {
        // an empty enclosure proves nothing (never returned by the engine; kept out anyway)
        Some(e) if e.is_empty() => RowVerdict::Open,
        Some(e) if e.disjoint(t.outer()) => RowVerdict::Outside(e.sup() < t.outer().inf()),
        Some(e) if t.inner().is_some_and(|i| e.subset(i)) => RowVerdict::Inside,
        _ => RowVerdict::Open,
    }
}

/// The thin-run enclosures of every row at θ, cached by θ.
struct Ends<'a> {
    p: &'a LawProblem,
    taylor: &'a TaylorOptions,
    cache: HashMap<u64, Vec<Option<Interval>>>,
}

impl Ends<'_> {
    fn at(&mut self, theta: f64) -> &Vec<Option<Interval>> {
        let (p, o) = (self.p, self.taylor);
        self.cache.entry(theta.to_bits()).or_insert_with(|| {
            let t = Interval::try_from((theta, theta)).expect("a finite θ");
            p.rows
                .par_iter()
                .map(|r| p.law.cor_enclosure(t, r.v0, o).ok())
                .collect()
        })
    }

    /// Each row's e over [a, b]: between the ends' enclosures where the law is monotone, else
    /// the engine on the interval.
    fn over(&mut self, a: f64, b: f64) -> Vec<Option<Interval>> {
        if self.p.law.monotone_from(a).is_some() {
            let ea = self.at(a).clone();
            let eb = self.at(b);
            ea.iter()
                .zip(eb)
                .map(|(x, y)| Some(x.as_ref()?.convex_hull(*y.as_ref()?)))
                .collect()
        } else {
            let t = Interval::try_from((a, b)).expect("an ordered interval");
            let (p, o) = (self.p, self.taylor);
            p.rows
                .par_iter()
                .map(|r| p.law.cor_enclosure(t, r.v0, o).ok())
                .collect()
        }
    }
}

/// Paves [lo, hi] (module doc). Work order: the intervals at the ends of what is not yet
/// infeasible first, so the hull converges first; a time limit (the engine's deadline) or the
/// box budget stops it, the rest undecided.
pub fn pave_law(
    p: &LawProblem,
    lo: f64,
    hi: f64,
    o: &LawOptions,
    progress: Option<&(dyn Fn(Progress) + Sync)>,
) -> LawPaving {
    let start = Instant::now();
    let mut ends = Ends {
        p,
        taylor: &o.taylor,
        cache: HashMap::new(),
    };
    let verdicts = |es: &[Option<Interval>]| -> Vec<RowVerdict> {
        es.iter()
            .zip(&p.rows)
            .map(|(e, r)| judge(*e, &r.e))
            .collect()
    };
    let mut leaves: Vec<Interval1> = Vec::new();
    if p.law.parameter().is_none() {
        let v = verdicts(ends.at(0.0));
        let (status, by) = decide(&v, &p.rows);
        let leaf = Leaf {
            lo: vec![],
            hi: vec![],
            status,
        };
        return LawPaving {
            refuted: by
                .map(|(row, _)| Refutation {
                    row,
                    lo: f64::NAN,
                    hi: f64::NAN,
                })
                .into_iter()
                .collect(),
            paving: Paving {
                boxes: vec![leaf],
                processed: 1,
                stopped: None,
                seconds: start.elapsed().as_secs_f64(),
            },
        };
    }
    let floor = p.law.floor().0;
    let min_abs = (hi - lo) * 1e-12;
    // the queue: intervals in θ order; the outermost open ones are taken first
    let mut queue: std::collections::VecDeque<(f64, f64)> = [(lo, hi)].into();
    let mut processed = 0;
    let mut stopped = None;
    let mut left = true;
    while let Some((a, b)) = if left {
        queue.pop_front()
    } else {
        queue.pop_back()
    } {
        left = !left;
        if processed >= o.max_boxes {
            stopped = Some(format!("the box budget of {} was reached", o.max_boxes));
        } else if o.taylor.deadline.is_some_and(|d| Instant::now() >= d) {
            stopped = Some("the time limit was reached".into());
        }
        if stopped.is_some() {
            leaves.push((a, b, Status::Undecided, None));
            continue;
        }
        processed += 1;
        let es = ends.over(a, b);
        let v = verdicts(&es);
        let (status, by) = decide(&v, &p.rows);
        // where the engine fails (very large damping: the separation becomes undecidable) the
        // failure persists under splitting: such intervals stop at 1/16 of their distance to
        // the floor, so the work stays bounded
        let res = if es.iter().any(Option::is_none) {
            FAILED_RESOLUTION.min(o.resolution)
        } else {
            o.resolution
        };
        let fine = b - a <= (b - floor) / res || b - a <= min_abs;
        if status != Status::Undecided || fine {
            leaves.push((a, b, status, by));
        } else {
            let m = split(a, b, floor);
            // keep θ order: the halves go back where the interval was taken from
            if left {
                // taken from the back (left was flipped): push back in order
                queue.push_back((a, m));
                queue.push_back((m, b));
            } else {
                queue.push_front((m, b));
                queue.push_front((a, m));
            }
        }
        if let Some(cb) = progress {
            let undecided = queue.iter().map(|(a, b)| b - a).sum::<f64>()
                + leaves
                    .iter()
                    .filter(|l| l.2 == Status::Undecided)
                    .map(|l| l.1 - l.0)
                    .sum::<f64>();
            cb(Progress {
                processed,
                queued: queue.len(),
                undecided: if hi > lo { undecided / (hi - lo) } else { 0.0 },
            });
        }
    }
    leaves.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut refuted: Vec<Refutation> = Vec::new();
    for &(a, b, s, by) in &leaves {
        if let (Status::Infeasible, Some((row, _))) = (s, by) {
            match refuted.last_mut() {
                Some(r) if r.row == row && r.hi == a => r.hi = b,
                _ => refuted.push(Refutation { row, lo: a, hi: b }),
            }
        }
    }
    // monotonicity carries the end refutations past the box: a row whose e is proved below
    // its target at hi (e decreasing) or above it (e increasing) is so for every larger θ,
    // and the mirror at lo, down to the admissible set's floor
    if let Some(dir) = p.law.monotone_from(lo) {
        let down = dir == Monotone::Decreasing;
        if let (Some(&(_, b, Status::Infeasible, Some((_, below)))), Some(r)) =
            (leaves.last(), refuted.last_mut())
            && b == hi
            && below == down
        {
            r.hi = f64::INFINITY;
        }
        if let (Some(&(a, _, Status::Infeasible, Some((_, below)))), Some(r)) =
            (leaves.first(), refuted.first_mut())
            && a == lo
            && below != down
        {
            r.lo = floor;
        }
    }
    LawPaving {
        paving: Paving {
            boxes: leaves
                .into_iter()
                .map(|(a, b, status, _)| Leaf {
                    lo: vec![a],
                    hi: vec![b],
                    status,
                })
                .collect(),
            processed,
            stopped,
            seconds: start.elapsed().as_secs_f64(),
        },
        refuted,
    }
}

/// The interval's status from its rows' verdicts, with the refuting row (the first outside).
fn decide(v: &[RowVerdict], rows: &[Row]) -> (Status, Option<(usize, bool)>) {
    if let Some(k) = v.iter().position(|x| matches!(x, RowVerdict::Outside(_))) {
        let below = matches!(v[k], RowVerdict::Outside(true));
        (Status::Infeasible, Some((rows[k].index, below)))
    } else if v.iter().all(|x| *x == RowVerdict::Inside) {
        (Status::Feasible, None)
    } else {
        (Status::Undecided, None)
    }
}

/// Where [a, b] is split (module doc).
fn split(a: f64, b: f64, floor: f64) -> f64 {
    let (da, db) = (a - floor, b - floor);
    let m = if da > 0.0 && db > 4.0 * da {
        floor + (da * db).sqrt()
    } else if da <= 0.0 && db > 0.0 {
        floor + db / 16.0
    } else {
        0.5 * (a + b)
    };
    if m > a && m < b { m } else { 0.5 * (a + b) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts() -> LawOptions {
        LawOptions {
            resolution: 1e4,
            taylor: TaylorOptions::default(),
            max_boxes: 100_000,
        }
    }

    #[test]
    fn constant_cor_data_beyond_twice_the_error_are_refuted_by_two_rows() {
        // Kelvin–Voigt's e is the same at every speed: 0.9 and 0.5 cannot both be met to ±0.1
        let d = CorData::new(vec![1.0, 2.0, 3.0], vec![0.9, 0.7, 0.5]).unwrap();
        let p = LawProblem::new(Law::KelvinVoigt, &d, Some(0.1), false).unwrap();
        let r = pave_law(&p, 0.0, 0.99, &opts(), None);
        assert!(r.paving.hull().is_none(), "{:?}", r.paving.boxes);
        let rows: std::collections::BTreeSet<usize> = r.refuted.iter().map(|x| x.row).collect();
        assert!(rows.contains(&0) && rows.contains(&2), "{:?}", r.refuted);
        // to ±0.21 they can: the hull is the ζ with e(ζ) ∈ [0.69, 0.71]
        let p = LawProblem::new(Law::KelvinVoigt, &d, Some(0.21), false).unwrap();
        let r = pave_law(&p, 0.0, 0.99, &opts(), None);
        let h = r.paving.hull().unwrap()[0];
        let o = crate::observables::FloatOptions::default();
        let (ea, eb) = (
            Law::KelvinVoigt.cor(h.0, 1.0, &o).unwrap(),
            Law::KelvinVoigt.cor(h.1, 1.0, &o).unwrap(),
        );
        assert!(ea > 0.7 && ea < 0.71 + 1e-3, "{ea}");
        assert!(eb < 0.7 && eb > 0.69 - 1e-3, "{eb}");
        assert!(r.paving.counts()[0] > 0);
    }

    #[test]
    fn hertz_is_refuted_by_a_dissipative_row_and_not_by_elastic_data() {
        let d = CorData::new(vec![1.0, 2.0], vec![0.99, 0.9]).unwrap();
        let p = LawProblem::new(Law::Hertz, &d, Some(0.02), false).unwrap();
        let r = pave_law(&p, 0.0, 0.0, &opts(), None);
        assert_eq!(r.paving.boxes[0].status, Status::Infeasible);
        assert_eq!(r.refuted[0].row, 1);
        let d = CorData::new(vec![1.0, 2.0], vec![0.99, 0.995]).unwrap();
        let p = LawProblem::new(Law::Hertz, &d, Some(0.02), false).unwrap();
        let r = pave_law(&p, 0.0, 0.0, &opts(), None);
        assert_eq!(r.paving.boxes[0].status, Status::Feasible);
    }

    #[test]
    fn splits_stay_inside() {
        for (a, b) in [(0.0, 100.0), (1e-9, 100.0), (0.3, 0.31), (0.5, 1e4)] {
            let m = split(a, b, if a == 0.5 { 0.5 } else { 0.0 });
            assert!(m > a && m < b, "{a} {b} {m}");
        }
    }
}
