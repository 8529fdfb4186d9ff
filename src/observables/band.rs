//! A proved CoR curve over a range of impact speeds, and its monotonicity.
//!
//! The range [a, b] of v0 is cut adaptively into pieces [v_lo, v_hi]. On each piece, one run of
//! the variational system ([`super::sets`]) proves enclosures of de/dv0 and dT_s/dv0 over the
//! whole piece, and one point run proves e and T_s at the piece's centre v_c; by the mean-value
//! theorem, for every v0 in the piece
//!
//! ```text
//! e(v0)   ∈ e(v_c)   + [de/dv0]·(v0 − v_c)
//! T_s(v0) ∈ T_s(v_c) + [dT_s/dv0]·(v0 − v_c)
//! ```
//!
//! (an affine form in v0: value at the centre, slope enclosure; the centre value's own width is
//! its remainder), intersected with the hull of the piece's range enclosure. The band's
//! *thickness* at v0 is the width of that enclosure of e(v0); a piece is split until its largest
//! thickness, wid e(v_c) + wid[de/dv0]·max(v_hi − v_c, v_c − v_lo), is below the target (v_c
//! is a point with a short exact decimal in the middle half of the piece, printed exactly).
//!
//! **Sub-centres.** The slope enclosure of a piece holds on every part of it, so a piece too
//! thick by a factor r ≤ [`MAX_SUB_CENTRES`] is cut into m ≈ r equal parts that keep its slope and
//! hull and get each its own centre (one point run each, ≈ 1/6 of a range run): the thickness
//! falls like 1/m. A piece thicker than that is cut into parts that are proved again, aimed at a
//! thickness of about [`AIM`] × the target (finished with sub-centres), since the thickness of a
//! proved piece grows like its width to the power ≈ 2.4 (measured, below).
//!
//! **Monotonicity**: sup [de/dv0] < 0 on a piece proves e strictly decreasing there (e is C¹ in
//! v0: the field is Lipschitz and piecewise C¹ with transversal crossings, so the variational
//! equation holds almost everywhere); pieces where the slope's sign is not decided are split
//! down to a minimum width and then named.

use super::sets::{Inputs, SetEnclosure, prove_over_set_with_slopes, short_centre};
use crate::engines::taylor::{DEADLINE, RigorError, TaylorOptions};
use crate::models::{ModelKind, NdParams};
use inari::Interval;
use rayon::prelude::*;
use std::sync::Mutex;

/// One proved piece of the band.
#[derive(Clone, Debug)]
pub struct BandPiece {
    pub v0_lo: f64,
    pub v0_hi: f64,
    /// The centre v_c (an exact double inside the piece).
    pub v0_c: f64,
    /// e(v_c), T_s(v_c).
    pub e_c: Interval,
    pub ts_c: Interval,
    /// de/dv0 and dT_s/dv0 over the whole piece.
    pub de: Interval,
    pub dts: Interval,
    /// Enclosures of e and T_s over the whole piece (their hulls).
    pub e: Interval,
    pub ts: Interval,
}

impl BandPiece {
    /// The largest vertical width of the enclosure of e(v0) on the piece (rounded up).
    pub fn thickness(&self) -> f64 {
        // the affine form's width grows linearly away from the centre: its largest value is at
        // an end, computed as the enclosure there is (rounding included), rounded up, plus a
        // margin for the rounding of the evaluation at interior points
        let width_up = |x: Interval| {
            let p = |y: f64| Interval::try_from((y, y)).unwrap();
            (p(x.sup()) - p(x.inf())).sup()
        };
        let c = Interval::try_from((self.v0_c, self.v0_c)).unwrap();
        let at = |v: f64| self.e_c + self.de * (Interval::try_from((v, v)).unwrap() - c);
        let w = width_up(at(self.v0_lo))
            .max(width_up(at(self.v0_hi)))
            .max(width_up(self.e_c));
        w + 8.0 * f64::EPSILON * self.e.mag().max(1.0)
    }

    /// The enclosure of e(v0) for v0 in this piece (the affine form ∩ the hull); `None` if v0
    /// is outside the piece.
    pub fn e_at(&self, v0: Interval) -> Option<Interval> {
        if v0.inf() < self.v0_lo || v0.sup() > self.v0_hi {
            return None;
        }
        let c = Interval::try_from((self.v0_c, self.v0_c)).unwrap();
        Some((self.e_c + self.de * (v0 - c)).intersection(self.e))
    }

    /// The enclosure of T_s(v0) for v0 in this piece.
    pub fn ts_at(&self, v0: Interval) -> Option<Interval> {
        if v0.inf() < self.v0_lo || v0.sup() > self.v0_hi {
            return None;
        }
        let c = Interval::try_from((self.v0_c, self.v0_c)).unwrap();
        Some((self.ts_c + self.dts * (v0 - c)).intersection(self.ts))
    }
}

/// A proved band over [a, b] (pieces in order, covering it without gaps).
#[derive(Clone, Debug)]
pub struct Band {
    pub pieces: Vec<BandPiece>,
}

impl Band {
    pub fn thickness(&self) -> f64 {
        self.pieces
            .iter()
            .map(BandPiece::thickness)
            .fold(0.0, f64::max)
    }
    /// The piece holding v0 (the first one, at a shared end).
    pub fn piece_at(&self, v0: f64) -> Option<&BandPiece> {
        self.pieces.iter().find(|p| p.v0_lo <= v0 && v0 <= p.v0_hi)
    }
}

/// Most sub-centres given to one proved piece (see the module's documentation): measured on
/// the four Table 1 sets, a range run costs about 6 point runs, so m point runs beat a second
/// round of range runs up to m ≈ 16.
pub const MAX_SUB_CENTRES: usize = 16;

/// The thickness (× the target) a piece cut for a new round of range runs is aimed at; its
/// sub-centres then take it below the target. The cost per length of the final pieces,
/// (range + m·point)/w with w ∝ m^(1/2.4), is least near m = 4 for a range run of 6 point
/// runs; measured on [0.1, 5] at 1e-6 (SHC DSS, Maxwell DSA): aim 2.5 took 57.7 s and 56.8 s,
/// aim 4 61.7 s and 59.9 s, aim 6 64.5 s and 62.4 s (the cut tends to over-cut, see
/// `THICKNESS_POWER`).
pub const AIM: f64 = 2.5;

/// The thickness of a proved piece grows like its width to this power (measured on the four
/// Table 1 sets at v0 = 0.1, 1, 4.5: widths 0.01 and 0.0025 give thickness ratios 20–30, i.e.
/// 2.2–2.5), used to predict the cut.
const THICKNESS_POWER: f64 = 2.4;

/// Options of the adaptive cut.
#[derive(Clone, Debug)]
pub struct BandOptions {
    /// Largest thickness of the band (vertical width of the enclosure of e).
    pub thickness: f64,
    /// Pieces are not split below this width of v0.
    pub min_width: f64,
    /// The first cut: this many equal pieces at least, and none wider than `first_width`.
    pub initial: usize,
    /// The widest piece of the first cut (m/s): wider ones fail (measured at 1e-6 on the four
    /// Table 1 sets: pieces of 0.077 all failed, of 0.038 half of them, of 0.019 one in 20).
    pub first_width: f64,
    /// Most pieces in all.
    pub max_pieces: usize,
    /// The Taylor order of the band's runs (replacing the options' order): measured on SHC DSS
    /// pieces at v0 = 0.2, 1 and 4.5, order 12 proves the same slope widths (0.94–1.02×) in
    /// 0.75–0.85× the time of order 16 (order 10: 0.8–0.95×, order 8: slower again).
    pub order: usize,
    /// Called after each round of the adaptive cut with the share of [a, b] settled so far
    /// (proved and kept, or final) and the pieces settled: a progress display.
    pub progress: Option<Progress>,
}

/// A progress callback of [`BandOptions`]: (share of the range settled, pieces settled).
#[derive(Clone)]
pub struct Progress(pub std::sync::Arc<dyn Fn(f64, usize) + Send + Sync>);

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Progress")
    }
}

impl Default for BandOptions {
    fn default() -> Self {
        Self {
            thickness: 1e-6,
            min_width: 1e-6,
            initial: 16,
            first_width: 0.02,
            max_pieces: 20_000,
            order: 12,
            progress: None,
        }
    }
}

/// Proves one piece [lo, hi] of base set `base`.
pub fn prove_piece(
    kind: ModelKind,
    base: &NdParams<Interval>,
    lo: f64,
    hi: f64,
    opts: &TaylorOptions,
) -> Result<BandPiece, RigorError> {
    let v0 = Interval::try_from((lo, hi)).map_err(|_| RigorError {
        reason: format!("bad range of v0: [{lo}, {hi}]"),
        t: 0.0,
        width: 0.0,
    })?;
    let inputs = Inputs::Base {
        base: base.clone(),
        v0,
    };
    piece_of(lo, hi, prove_over_set_with_slopes(kind, &inputs, opts)?)
}

/// The band's piece of [lo, hi] from a proved set enclosure: its affine forms need the slope
/// enclosures and the centre's values, which a range's enclosure carries; one without them
/// is refused ("no slope over the piece") — taking de = dT_s = 0 would claim e constant on the
/// piece. A point piece (lo = hi) needs none.
fn piece_of(lo: f64, hi: f64, r: SetEnclosure) -> Result<BandPiece, RigorError> {
    let (Some(slope), Some((c, ts_c, e_c))) = (r.slope, r.centre) else {
        if lo < hi {
            // (prove_over_set_with_slopes gives a range its slope; a piece's affine form and
            // its sub-centres need it)
            return Err(RigorError {
                reason: "no slope over the piece".into(),
                t: 0.0,
                width: 0.0,
            });
        }
        // a point range (lo = hi): no slope needed
        return Ok(BandPiece {
            v0_lo: lo,
            v0_hi: hi,
            v0_c: lo,
            e_c: r.e,
            ts_c: r.ts,
            de: Interval::try_from((0.0, 0.0)).unwrap(),
            dts: Interval::try_from((0.0, 0.0)).unwrap(),
            e: r.e,
            ts: r.ts,
        });
    };
    Ok(BandPiece {
        v0_lo: lo,
        v0_hi: hi,
        v0_c: c,
        e_c,
        ts_c,
        de: slope.e,
        dts: slope.ts,
        e: r.e,
        ts: r.ts,
    })
}

/// The parts of a proved piece cut into `m` equal parts, each with its own centre (a point
/// run) and the piece's slope enclosures and hulls: for v0 in a part [l, h] ⊆ [v_lo, v_hi],
/// e(v0) ∈ e(c) + [de/dv0](v0 − c) by the mean-value theorem, as [de/dv0] holds on the whole
/// piece (likewise T_s).
pub fn sub_centres(
    kind: ModelKind,
    base: &NdParams<Interval>,
    piece: &BandPiece,
    m: usize,
    opts: &TaylorOptions,
) -> Result<Vec<BandPiece>, RigorError> {
    short_cuts(piece.v0_lo, piece.v0_hi, m)
        .par_windows(2)
        .map(|w| {
            let (l, h) = (w[0], w[1]);
            let c = short_centre(l, h);
            let at_c = prove_piece(kind, base, c, c, opts)?;
            let part = Interval::try_from((l, h)).expect("ordered ends");
            let d = part - Interval::try_from((c, c)).expect("a double");
            Ok(BandPiece {
                v0_lo: l,
                v0_hi: h,
                v0_c: c,
                e_c: at_c.e,
                ts_c: at_c.ts,
                de: piece.de,
                dts: piece.dts,
                e: (at_c.e + piece.de * d).intersection(piece.e),
                ts: (at_c.ts + piece.dts * d).intersection(piece.ts),
            })
        })
        .collect()
}

/// What becomes of a proved piece: kept as these pieces, or cut into this many parts to be
/// proved again.
pub enum Refine {
    Keep(Vec<BandPiece>),
    Cut(usize),
}

/// A piece of v0 with its result.
type Outcome = (f64, f64, Result<BandPiece, RigorError>);

/// Cuts [a, b] adaptively until every piece is proved and kept by `refine`, or is at the
/// minimum width; a proved piece `refine` cuts is cut into that many equal parts (at least 2),
/// one not proved is halved; pieces are proved in parallel (rayon). Returns the pieces in order,
/// each with its result (a piece at the minimum width that `refine` would still cut, as
/// proved).
///
/// Bounded: at most `bo.max_pieces` pieces, and no round starts after `opts.deadline` (a piece
/// whose run stops there keeps that error, as does every piece not yet tried); after each
/// round `stop()` may end the cut early (the pieces still to do then carry [`NOT_EXAMINED`]).
#[allow(clippy::too_many_arguments)]
fn adapt(
    kind: ModelKind,
    base: &NdParams<Interval>,
    a: f64,
    b: f64,
    bo: &BandOptions,
    opts: &TaylorOptions,
    refine: impl Fn(BandPiece) -> Refine + Sync,
    stop: impl Fn() -> bool,
) -> Vec<Outcome> {
    let by_width = ((b - a) / bo.first_width).ceil();
    let n = if by_width.is_finite() && by_width < bo.max_pieces as f64 {
        bo.initial.max(by_width as usize).max(1)
    } else {
        bo.initial.max(1)
    };
    let cut = short_cuts(a, b, n);
    let mut todo: Vec<(f64, f64)> = cut.windows(2).map(|w| (w[0], w[1])).collect();
    let mut done: Vec<Outcome> = Vec::new();
    let kept: Mutex<Vec<Outcome>> = Mutex::new(Vec::new());
    let telling = Mutex::new(());
    let settled = |done: &[Outcome], kept: &Mutex<Vec<Outcome>>| {
        let kept = kept.lock().expect("no panic");
        let len: f64 = done.iter().chain(kept.iter()).map(|o| o.1 - o.0).sum();
        ((len / (b - a)).clamp(0.0, 1.0), done.len() + kept.len())
    };
    while !todo.is_empty() {
        if opts.out_of_time() || stop() {
            let why = if opts.out_of_time() {
                RigorError {
                    reason: DEADLINE.into(),
                    t: 0.0,
                    width: 0.0,
                }
            } else {
                RigorError {
                    reason: NOT_EXAMINED.into(),
                    t: 0.0,
                    width: 0.0,
                }
            };
            done.extend(todo.drain(..).map(|(lo, hi)| (lo, hi, Err(why.clone()))));
            break;
        }
        let results: Vec<(f64, f64, Result<BandPiece, RigorError>, usize)> = todo
            .par_iter()
            .map(|&(lo, hi)| match prove_piece(kind, base, lo, hi, opts) {
                // out of time: kept as it is (a split would not be tried either)
                Err(e) if e.out_of_time() => (lo, hi, Err(e), 1),
                // a piece not proved is halved
                Err(e) => (lo, hi, Err(e), 2),
                Ok(p) => match refine(p.clone()) {
                    Refine::Keep(parts) => {
                        for q in parts {
                            let (l, h) = (q.v0_lo, q.v0_hi);
                            kept.lock().expect("no panic").push((l, h, Ok(q)));
                        }
                        // told as each piece settles, not only after the round: a round of a
                        // long band runs for seconds
                        // (one thread at a time, so that the shares told never go back)
                        if let Some(Progress(f)) = &bo.progress {
                            let _one = telling.lock().expect("no panic");
                            let (share, pieces) = settled(&done, &kept);
                            f(share, pieces);
                        }
                        (lo, hi, Ok(p), 0)
                    }
                    Refine::Cut(k) => (lo, hi, Ok(p), k),
                },
            })
            .collect();
        todo.clear();
        for (lo, hi, r, k) in results {
            if k == 0 {
                continue;
            }
            // no part narrower than min_width
            let k = k.clamp(2, 64).min(((hi - lo) / bo.min_width) as usize);
            let cut = short_cuts(lo, hi, k);
            let can_split = k >= 2
                && cut.windows(2).all(|w| w[0] < w[1])
                && !r.as_ref().is_err_and(|e| e.out_of_time());
            let count = done.len() + kept.lock().expect("no panic").len() + todo.len();
            if !can_split || count + k > bo.max_pieces {
                done.push((lo, hi, r));
            } else {
                todo.extend(cut.windows(2).map(|w| (w[0], w[1])));
            }
        }
        if let Some(Progress(f)) = &bo.progress {
            let (share, pieces) = settled(&done, &kept);
            f(share, pieces);
        }
    }
    done.extend(kept.into_inner().expect("no panic"));
    done.sort_by(|x, y| x.0.total_cmp(&y.0));
    done
}

/// The reason of a piece the cut did not examine, having been stopped early (e.g. once a
/// monotonicity claim was refuted).
pub const NOT_EXAMINED: &str = "not examined (the search stopped early)";

/// The ends of [lo, hi] cut into `k` parts of about equal length, lo and hi exactly; each
/// inner end a double with a short exact decimal (the coarsest multiple of a power of two
/// within a fifth of a part of the equal cut), so that a piece's ends are printed exactly and
/// neighbouring pieces share their end in print too. Parts that share an end share the same
/// double.
pub fn short_cuts(lo: f64, hi: f64, k: usize) -> Vec<f64> {
    let part = (hi - lo) / k as f64;
    let mut out = Vec::with_capacity(k + 1);
    out.push(lo);
    for i in 1..k {
        let x = lo + (hi - lo) * (i as f64) / (k as f64);
        let c = short_centre(x - part / 5.0, x + part / 5.0);
        out.push(if c > *out.last().expect("lo") && c < hi {
            c
        } else {
            x
        });
    }
    if k > 0 {
        out.push(hi);
    }
    out
}

/// The options of the band's runs: `bo.order`, and a largest width. A wide piece's run fails
/// slowly (its set creeps through thousands of low-order steps up to `max_width`: 2.7 s for
/// SHC DSS v0 ∈ [4, 4.0766], 1312 steps, against 0.06 s with a limit of 0.03); a state that
/// wide cannot give a thin band, so the runs stop at 20·√target (0.02 at the default 1e-6) and
/// the piece is halved.
///
/// The truncation tolerance is at least 10⁻⁶ × the target: the centres' point runs then prove
/// e to ≈ 3e-11 instead of 3e-13 at the default 1e-6 (still 3·10⁻⁵ of the thickness), in
/// 0.75–0.85× the time (SHC DSS and Maxwell DSA, v0 = 1, order 12; a looser 1e-10 is no
/// faster).
fn run_options(bo: &BandOptions, opts: &TaylorOptions) -> TaylorOptions {
    TaylorOptions {
        max_width: opts.max_width.min(20.0 * bo.thickness.sqrt()),
        order: bo.order,
        tol: opts.tol.max(1e-6 * bo.thickness),
        ..opts.clone()
    }
}

/// Proves the band of e (and T_s) over v0 ∈ [a, b] for base set `base`, with thickness at most
/// `bo.thickness`; fails with the first piece that could not be proved (or not thin enough).
pub fn prove_band(
    kind: ModelKind,
    base: &NdParams<Interval>,
    a: f64,
    b: f64,
    bo: &BandOptions,
    opts: &TaylorOptions,
) -> Result<Band, RigorError> {
    let opts = &run_options(bo, opts);
    let done = adapt(
        kind,
        base,
        a,
        b,
        bo,
        opts,
        |p| {
            let t = p.thickness();
            if t <= bo.thickness {
                return Refine::Keep(vec![p]);
            }
            // sub-centres: the slope term wid[de]·w/2 falls like 1/m, the centre's own width stays
            let own = p.e_c.wid() * 2.0 + 8.0 * f64::EPSILON * p.e.mag().max(1.0);
            let room = bo.thickness - own;
            let m = ((t - own) / room).ceil();
            if room > 0.0
                && m.is_finite()
                && m <= MAX_SUB_CENTRES as f64
                && let Ok(parts) = sub_centres(kind, base, &p, m as usize, opts)
                && parts.iter().all(|q| q.thickness() <= bo.thickness)
            {
                return Refine::Keep(parts);
            }
            // cut for new range runs, aimed at AIM × the target
            let parts = (t / (AIM * bo.thickness)).powf(1.0 / THICKNESS_POWER);
            Refine::Cut(parts.ceil().max(2.0) as usize)
        },
        || false,
    );
    // what was proved, for the message of a band that is not
    let proved_len: f64 = done
        .iter()
        .filter(|o| o.2.as_ref().is_ok_and(|p| p.thickness() <= bo.thickness))
        .map(|o| o.1 - o.0)
        .sum();
    let proved_count = done
        .iter()
        .filter(|o| o.2.as_ref().is_ok_and(|p| p.thickness() <= bo.thickness))
        .count();
    let so_far = || {
        format!(
            "; proved so far: {proved_count} pieces covering {:.1} % of the range",
            100.0 * proved_len / (b - a)
        )
    };
    let mut pieces = Vec::with_capacity(done.len());
    for (lo, hi, r) in done {
        let p = r.map_err(|e| RigorError {
            reason: if e.out_of_time() {
                format!("{} for v0 in [{lo}, {hi}] and after{}", e.reason, so_far())
            } else {
                format!("for v0 in [{lo}, {hi}]: {}{}", e.reason, so_far())
            },
            ..e
        })?;
        if p.thickness() > bo.thickness {
            return Err(RigorError {
                reason: format!(
                    "for v0 in [{lo}, {hi}]: the band is {:e} thick (the target is {:e}) at the \
                     smallest piece or the piece budget{}",
                    p.thickness(),
                    bo.thickness,
                    so_far()
                ),
                t: 0.0,
                width: p.thickness(),
            });
        }
        pieces.push(p);
    }
    Ok(Band { pieces })
}

/// The outcome of the monotonicity prover.
#[derive(Clone, Debug)]
pub struct Monotonicity {
    /// Proved strictly decreasing on every piece: the pieces and their slope enclosures.
    pub pieces: Vec<(f64, f64, Interval)>,
    /// Proved strictly increasing (inf de/dv0 > 0): the sub-ranges (neighbouring pieces merged)
    /// and the hulls of their slope enclosures — a refutation of the claim on [a, b].
    pub increasing: Vec<(f64, f64, Interval)>,
    /// The sub-ranges where it could not be decided (merged), with the reason.
    pub undecided: Vec<(f64, f64, String)>,
}

impl Monotonicity {
    /// e strictly decreasing on all of [a, b].
    pub fn proved(&self) -> bool {
        self.undecided.is_empty() && self.increasing.is_empty()
    }
    /// e strictly increasing on a sub-range: the claim is false.
    pub fn refuted(&self) -> bool {
        !self.increasing.is_empty()
    }
    /// The largest proved slope (sup of de/dv0 over all pieces): e decreases at least this fast.
    pub fn max_slope(&self) -> f64 {
        self.pieces
            .iter()
            .map(|p| p.2.sup())
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

/// Decides whether e(v0) is strictly decreasing on [a, b]: proved (sup de/dv0 < 0 on every
/// piece), refuted (inf de/dv0 > 0 on a piece: e strictly increasing there — the search stops
/// after the round that finds one), or neither on the sub-ranges it names (the slope's sign
/// undecided down to the minimum width or the piece budget, a run not proved, or the time
/// budget of `opts.deadline`).
pub fn prove_decreasing(
    kind: ModelKind,
    base: &NdParams<Interval>,
    a: f64,
    b: f64,
    bo: &BandOptions,
    opts: &TaylorOptions,
) -> Monotonicity {
    let opts = &run_options(bo, opts);
    let refuted = std::sync::atomic::AtomicBool::new(false);
    let done = adapt(
        kind,
        base,
        a,
        b,
        bo,
        opts,
        |p| {
            if p.de.sup() < 0.0 {
                Refine::Keep(vec![p])
            } else if p.de.inf() > 0.0 {
                refuted.store(true, std::sync::atomic::Ordering::Relaxed);
                Refine::Keep(vec![p])
            } else {
                Refine::Cut(2)
            }
        },
        || refuted.load(std::sync::atomic::Ordering::Relaxed),
    );
    let mut out = Monotonicity {
        pieces: Vec::new(),
        increasing: Vec::new(),
        undecided: Vec::new(),
    };
    for (lo, hi, r) in done {
        let why = match r {
            Ok(p) if p.de.sup() < 0.0 => {
                out.pieces.push((lo, hi, p.de));
                continue;
            }
            Ok(p) if p.de.inf() > 0.0 => {
                // neighbours merged: e increases on the union (the slopes' hull holds there)
                match out.increasing.last_mut() {
                    Some(last) if last.1 == lo => {
                        last.1 = hi;
                        last.2 = last.2.convex_hull(p.de);
                    }
                    _ => out.increasing.push((lo, hi, p.de)),
                }
                continue;
            }
            Ok(p) => format!("de/dv0 ∈ [{:e}, {:e}] is not < 0", p.de.inf(), p.de.sup()),
            Err(e) => e.reason,
        };
        // neighbours merged (with the first one's reason) when they are undecided for the
        // same kind of reason: the time budget, not examined, or the rest
        let class = |w: &str| {
            if w.starts_with(DEADLINE) {
                0
            } else if w.starts_with(NOT_EXAMINED) {
                1
            } else {
                2
            }
        };
        match out.undecided.last_mut() {
            Some(last) if last.1 == lo && class(&last.2) == class(&why) => last.1 = hi,
            _ => out.undecided.push((lo, hi, why)),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A range's enclosure without a slope cannot make a piece (its affine form would claim e
    /// constant on it); a point's can (lo = hi), and a range's with a slope gives its affine
    /// form.
    #[test]
    fn a_piece_without_a_slope_is_refused() {
        let iv = |a: f64, b: f64| Interval::try_from((a, b)).unwrap();
        let bare = SetEnclosure {
            ts: iv(3.0, 3.1),
            e: iv(0.8, 0.9),
            slope: None,
            centre: None,
            steps: 1,
        };
        let e = piece_of(1.0, 1.5, bare.clone()).unwrap_err();
        assert_eq!(e.reason, "no slope over the piece");
        let p = piece_of(1.0, 1.0, bare.clone()).unwrap();
        assert_eq!((p.v0_lo, p.v0_hi, p.v0_c), (1.0, 1.0, 1.0));
        assert!(p.de.inf() == 0.0 && p.de.sup() == 0.0 && p.e == bare.e);
        let sloped = SetEnclosure {
            slope: Some(super::super::sets::Slope {
                input: 6,
                ts: iv(0.1, 0.2),
                e: iv(-0.3, -0.2),
            }),
            centre: Some((1.25, iv(3.05, 3.05), iv(0.85, 0.85))),
            ..bare
        };
        let p = piece_of(1.0, 1.5, sloped).unwrap();
        assert_eq!(p.v0_c, 1.25);
        assert!(p.de.inf() == -0.3 && p.dts.sup() == 0.2);
        // e(v0) at the piece's ends from its affine form, inside its hull
        assert!(p.e_at(iv(1.5, 1.5)).unwrap().subset(iv(0.8, 0.9)));
    }

    /// A piece's forms hold on the piece only: e_at and ts_at refuse a v0 that reaches outside
    /// it (the affine form extrapolated, cut by a hull proved for the piece alone, would be
    /// claimed where nothing was proved); the thickness bounds the width of e_at at every v0
    /// of the piece, the ends and 1000 interior doubles.
    #[test]
    fn a_piece_answers_only_inside_it_and_its_thickness_bounds_its_widths() {
        let iv = |a: f64, b: f64| Interval::try_from((a, b)).unwrap();
        let p = BandPiece {
            v0_lo: 1.0,
            v0_hi: 1.5,
            v0_c: 1.25,
            e_c: iv(0.85, 0.85 + 1e-15),
            ts_c: iv(3.05, 3.05),
            de: iv(-0.3, -0.2),
            dts: iv(0.1, 0.2),
            e: iv(0.7, 1.0),
            ts: iv(3.0, 3.1),
        };
        for v in [1.0, 1.25, 1.5] {
            assert!(p.e_at(iv(v, v)).is_some() && p.ts_at(iv(v, v)).is_some());
        }
        for (a, b) in [
            (0.9, 0.9),
            (0.99, 1.1),
            (1.4, 1.5000001),
            (1.6, 1.6),
            (0.5, 2.0),
        ] {
            assert!(p.e_at(iv(a, b)).is_none(), "e_at [{a}, {b}]");
            assert!(p.ts_at(iv(a, b)).is_none(), "ts_at [{a}, {b}]");
        }
        // a thin form too: its widths are roundings alone (an interior v0's product by v0 − c
        // is rounded, the ends' products by ±1/4 and the centre's by 0 are exact)
        let thin = BandPiece {
            e_c: iv(0.85, 0.85),
            de: iv(-0.3, -0.3),
            ..p
        };
        for (q, most) in [(p, 0.0250001), (thin, 1e-14)] {
            let th = q.thickness();
            for i in 0..=1000 {
                let v = 1.0 + 0.5 * i as f64 / 1000.0;
                let w = q.e_at(iv(v, v)).unwrap();
                // the width rounded up, against the thickness
                let up = (iv(w.sup(), w.sup()) - iv(w.inf(), w.inf())).sup();
                assert!(up <= th, "v0 = {v}: width {up:e} > thickness {th:e}");
            }
            // and the thickness is that of the form (0.1 · 0.25 at the ends), not much more
            assert!(th < most, "{th:e}");
        }
    }

    /// The cuts of a range: its ends exactly, inner ends with short exact decimals (each a
    /// multiple of a power of two no finer than needed), increasing, each within a fifth of a
    /// part of the equal cut.
    #[test]
    fn cuts_have_short_ends_and_cover_the_range() {
        for (lo, hi, k) in [
            (0.1, 5.0, 245),
            (0.5, 0.7, 16),
            (1.0, 1.0 + 1e-9, 7),
            (3.0, 4.0, 2),
        ] {
            let c = short_cuts(lo, hi, k);
            assert_eq!(c.len(), k + 1);
            assert_eq!((c[0], c[k]), (lo, hi));
            let part = (hi - lo) / k as f64;
            for (i, w) in c.windows(2).enumerate() {
                assert!(w[0] < w[1], "{lo} {hi} {k}: {w:?}");
                if i > 0 {
                    let x = lo + part * i as f64;
                    assert!((w[0] - x).abs() <= part / 5.0 + 4.0 * f64::EPSILON * x.abs());
                }
            }
            // short: the exact decimal of an inner end has few digits against the part
            for &x in &c[1..k] {
                let digits = format!("{}", rug::Rational::from_f64(x).unwrap().denom()).len();
                let need = ((1.0 / part).log10().ceil() as usize) + 3;
                assert!(
                    digits <= need,
                    "{x:e}: denominator of {digits} digits (part {part:e})"
                );
            }
        }
    }

    /// The band of the four Table 1 sets on [0.1, 5]: `cargo test --release --lib
    /// band::tests::explore_band -- --ignored --nocapture` (THICK overrides the target).
    #[test]
    #[ignore]
    fn explore_band() {
        let thick: f64 = std::env::var("THICK")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(1e-6);
        let bo = BandOptions {
            thickness: thick,
            ..BandOptions::default()
        };
        for (name, kind, b) in crate::models::params::TABLE1 {
            let base = NdParams::parse(kind, b).unwrap();
            let t0 = std::time::Instant::now();
            let r = prove_band(kind, &base, 0.1, 5.0, &bo, &TaylorOptions::default());
            let dt = t0.elapsed();
            match r {
                Ok(band) => eprintln!(
                    "{name}: {} pieces, thickness {:e}, in {dt:?}",
                    band.pieces.len(),
                    band.thickness()
                ),
                Err(e) => eprintln!("{name}: {e} in {dt:?}"),
            }
        }
    }
}
