//! The proved CoR curve over a range of v0 at thicknesses far below the first-order band's
//! (issue #32 item 4): pieces in an interpolation form.
//!
//! On a piece [a, b], one run of the second variational system ([`super::curvature`]) proves
//! [e″] and [T_s″] over the whole piece; point runs prove e and T_s at nodes
//! a = v_0 < v_1 < … < v_m = b (exact doubles). Between two nodes, by the interpolation error
//! formula (Peano's kernel (v − v_k)(v − v_{k+1})/2 ≤ 0 keeps its sign, so the mean value
//! theorem applies to e″ over [v_k, v_{k+1}]):
//!
//! ```text
//! e(v) ∈ e(v_k)·(v_{k+1} − v)/h + e(v_{k+1})·(v − v_k)/h + [e″]·(v − v_k)(v − v_{k+1})/2
//! ```
//!
//! (h = v_{k+1} − v_k; likewise T_s). The width at v is at most
//! max(wid e(v_k), wid e(v_{k+1})) + wid[e″]·h²/8: the known part of e″ (its midpoint) is carried
//! by the form, only its width costs thickness, and wid[e″] ∝ the piece's width — so a piece
//! is wide and its nodes cheap (a point run is ≈ 1/30 of a second-order range run). The first
//! order's thickness wid[e′]·w/2 ∝ w^2.4 needed ≈ 13 times more range runs at 1e-9
//! (benches/RESULTS.md).
//!
//! The nodes per piece come from the target: wid[e″]·h²/8 ≤ 0.95·target (the rest for the
//! nodes' own widths, ≈ 1e-12: their runs' tolerance per step is 10⁻⁴ of the target). The
//! range is cut into segments walked in parallel ([`prove_band_second`]); along a segment each
//! piece's width comes from the nodes the last one needed (aimed at [`AIM_NODES`]), and a
//! piece needing more than [`MAX_NODES`] intervals, or whose run fails, is tried narrower.

use super::band::Progress;
use super::curvature::curvature_over_range;
use super::sets::{Inputs, prove_at_point};
use crate::engines::taylor::{RigorError, TaylorOptions};
use crate::models::{ModelKind, NdParams};
use inari::Interval;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Most node intervals on one piece (beyond, the piece is tried narrower: its [e″] narrows at
/// least ∝ width).
pub const MAX_NODES: usize = 128;

/// A piece in the interpolation form (module doc).
#[derive(Clone, Debug)]
pub struct InterpPiece {
    /// The nodes v_k (exact doubles, the first and last the piece's ends) with e(v_k), T_s(v_k).
    pub nodes: Vec<Node>,
    /// e″ and T_s″ over the whole piece.
    pub e2: Interval,
    pub ts2: Interval,
    /// e′ over the whole piece (from the same run).
    pub e1: Interval,
}

fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).expect("a finite double")
}

/// Rounded-up width of an interval.
fn width_up(x: Interval) -> f64 {
    (point(x.sup()) - point(x.inf())).sup()
}

impl InterpPiece {
    pub fn v0_lo(&self) -> f64 {
        self.nodes[0].0
    }
    pub fn v0_hi(&self) -> f64 {
        self.nodes[self.nodes.len() - 1].0
    }

    /// The interpolation form of `q` (e or T_s: the node values `val`, second derivative `d2`)
    /// at v0 in the node interval k.
    fn form(
        &self,
        k: usize,
        v0: Interval,
        val: impl Fn(usize) -> Interval,
        d2: Interval,
    ) -> Interval {
        let (a, b) = (point(self.nodes[k].0), point(self.nodes[k + 1].0));
        let h = b - a;
        let (p, q) = (v0 - a, b - v0);
        (val(k) * q + val(k + 1) * p) / h - d2 * p * q / point(2.0)
    }

    /// The node interval holding v0 (the first one at a shared node).
    fn interval_of(&self, v0: Interval) -> Option<usize> {
        let k = self
            .nodes
            .windows(2)
            .position(|w| w[0].0 <= v0.inf() && v0.sup() <= w[1].0)?;
        Some(k)
    }

    /// The enclosure of e(v0) for v0 (an interval inside one node interval of the piece).
    pub fn e_at(&self, v0: Interval) -> Option<Interval> {
        let k = self.interval_of(v0)?;
        Some(self.form(k, v0, |i| self.nodes[i].1, self.e2))
    }

    /// The enclosure of T_s(v0).
    pub fn ts_at(&self, v0: Interval) -> Option<Interval> {
        let k = self.interval_of(v0)?;
        Some(self.form(k, v0, |i| self.nodes[i].2, self.ts2))
    }

    /// The largest width of the enclosure of e(v0) on the piece (rounded up): per node
    /// interval max(wid e(v_k), wid e(v_{k+1})) + wid[e″]·h²/8, with a margin for the rounding
    /// of the evaluation at interior points.
    pub fn thickness(&self) -> f64 {
        (0..self.nodes.len() - 1)
            .map(|k| self.interval_thickness(k))
            .fold(0.0, f64::max)
    }

    /// The hull of e over the node interval k: e(v) − L(v) = −e″(ξ)·pq/2 with pq ∈ [0, h²/4],
    /// so e ∈ hull(e(v_k), e(v_{k+1})) − [e″]·[0, h²/8].
    pub fn hull_on(&self, k: usize) -> Interval {
        let (a, b) = (&self.nodes[k], &self.nodes[k + 1]);
        let h = point(b.0) - point(a.0);
        let quad = Interval::try_from((0.0, (h * h / point(8.0)).sup())).expect("h ≥ 0");
        a.1.convex_hull(b.1) - self.e2 * quad
    }

    /// The largest width of the enclosure of e(v0) on the node interval k (rounded up).
    pub fn interval_thickness(&self, k: usize) -> f64 {
        let (a, b) = (&self.nodes[k], &self.nodes[k + 1]);
        let h = (point(b.0) - point(a.0)).sup();
        let mag = a.1.mag().max(b.1.mag()).max(1.0);
        let quad = (point(width_up(self.e2)) * point(h) * point(h) / point(8.0)).sup();
        width_up(a.1).max(width_up(b.1)) + quad + 16.0 * f64::EPSILON * mag
    }
}

/// A band of interpolation pieces over [a, b] (in order, sharing their end nodes).
#[derive(Clone, Debug)]
pub struct InterpBand {
    pub pieces: Vec<InterpPiece>,
    /// Second-order range runs and point runs made.
    pub range_runs: usize,
    pub point_runs: usize,
}

impl InterpBand {
    pub fn thickness(&self) -> f64 {
        self.pieces
            .iter()
            .map(InterpPiece::thickness)
            .fold(0.0, f64::max)
    }
    /// The piece holding v0 (the first one at a shared end).
    pub fn piece_at(&self, v0: f64) -> Option<&InterpPiece> {
        self.pieces
            .iter()
            .find(|p| p.v0_lo() <= v0 && v0 <= p.v0_hi())
    }
}

/// The band's options: the target thickness, the first pieces' width (at v0 ≥ 1; ∝ v0 below,
/// `first_guess`), the narrowest piece, a progress display.
#[derive(Clone, Debug)]
pub struct InterpOptions {
    pub thickness: f64,
    pub first_width: f64,
    pub min_width: f64,
    /// Told (share of the range settled, pieces settled) as each piece settles.
    pub progress: Option<Progress>,
}

/// Measured on [0.1, 5] at 1e-9 (benches/RESULTS.md): pieces of 0.05·clamp(v0, 0.1, 1) first.
impl Default for InterpOptions {
    fn default() -> Self {
        Self {
            thickness: 1e-9,
            first_width: 0.05,
            min_width: 1e-6,
            progress: None,
        }
    }
}

fn point_run(
    kind: ModelKind,
    base: &NdParams<Interval>,
    v: f64,
    opts: &TaylorOptions,
) -> Result<(Interval, Interval), RigorError> {
    let inputs = Inputs::Base {
        base: base.clone(),
        v0: point(v),
    };
    let (ts, e) = prove_at_point(kind, &inputs, opts)?;
    Ok((e, ts))
}

/// What one piece's attempt gave.
enum Tried {
    /// The piece, with its number of node intervals.
    Proved(InterpPiece, usize),
    /// Its [e″] needs this many node intervals, more than [`MAX_NODES`].
    TooWide(f64),
    /// Its run failed (or the nodes' own widths exceed the target).
    Failed,
}

/// A node: v0 (an exact double) with e(v0) and T_s(v0).
type Node = (f64, Interval, Interval);

/// One piece [lo, hi]: the range run, then the nodes, `known` one of them proved already (an
/// error only where the piece may not be cut further, or the time ran out).
fn prove_piece(
    kind: ModelKind,
    base: &NdParams<Interval>,
    (lo, hi): (f64, f64),
    known: Option<Node>,
    io: &InterpOptions,
    opts: &TaylorOptions,
) -> Result<Tried, RigorError> {
    let inputs = Inputs::Base {
        base: base.clone(),
        v0: Interval::try_from((lo, hi)).map_err(|_| RigorError {
            reason: format!("bad range of v0: [{lo}, {hi}]"),
            t: 0.0,
            width: 0.0,
        })?,
    };
    let c = match curvature_over_range(kind, &inputs, opts) {
        Ok(c) => c,
        Err(e) if e.out_of_time() || hi - lo < 2.0 * io.min_width => return Err(e),
        Err(_) => return Ok(Tried::Failed),
    };
    // nodes: wid[e″]·h²/8 ≤ 0.95·target (the rest for the nodes' own widths, ≈ 1e-12)
    let w2 = width_up(c.e2);
    let m = ((hi - lo) * (w2 / (7.6 * io.thickness)).sqrt())
        .ceil()
        .max(1.0);
    if m.is_nan() || m > MAX_NODES as f64 {
        return if hi - lo < 2.0 * io.min_width {
            Err(RigorError {
                reason: format!("e'' too wide on [{lo}, {hi}] for the thickness"),
                t: 0.0,
                width: w2,
            })
        } else {
            Ok(Tried::TooWide(m))
        };
    }
    let m = m as usize;
    let node_opts = TaylorOptions {
        tol: opts.tol.max(1e-4 * io.thickness),
        ..opts.clone()
    };
    let vs: Vec<f64> = (0..=m)
        .map(|k| match k {
            0 => lo,
            k if k == m => hi,
            k => lo + (hi - lo) * k as f64 / m as f64,
        })
        .collect();
    if vs.windows(2).any(|w| w[0] >= w[1]) {
        return if hi - lo < 2.0 * io.min_width {
            Err(RigorError {
                reason: format!("no {m} distinct nodes on [{lo}, {hi}]"),
                t: 0.0,
                width: 0.0,
            })
        } else {
            Ok(Tried::Failed)
        };
    }
    let nodes = vs
        .iter()
        .map(|&v| match known {
            // (the last piece's end node, proved already)
            Some(n) if n.0 == v => Ok(n),
            _ => point_run(kind, base, v, &node_opts).map(|(e, ts)| (v, e, ts)),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let p = InterpPiece {
        nodes,
        e2: c.e2,
        ts2: c.ts2,
        e1: c.e1,
    };
    if p.thickness() > io.thickness {
        return if hi - lo < 2.0 * io.min_width {
            Err(RigorError {
                reason: format!("the nodes' own widths exceed the thickness on [{lo}, {hi}]"),
                t: 0.0,
                width: p.thickness(),
            })
        } else {
            Ok(Tried::Failed)
        };
    }
    Ok(Tried::Proved(p, m))
}

/// The width a piece at v0 is first tried with: `first_width`, ∝ v0 below v0 = 1 (measured on
/// the Table 1 sets: the widths that settle are ≈ 0.05·v0 there, benches/RESULTS.md).
fn first_guess(io: &InterpOptions, v: f64) -> f64 {
    io.first_width * v.clamp(0.1, 1.0)
}

/// The segments [a, b] is cut into, walked in parallel: about equal numbers of pieces by
/// [`first_guess`], at most [`SEGMENTS`], each of ≥ 3 pieces of the guess where [a, b] holds
/// that many (their ends short decimals: printed exactly).
fn segments(io: &InterpOptions, a: f64, b: f64) -> Vec<f64> {
    // the guessed number of pieces up to v: ∫ dv / first_guess(v), by the midpoint rule
    const GRID: usize = 4096;
    let h = (b - a) / GRID as f64;
    let cum: Vec<f64> = std::iter::once(0.0)
        .chain((0..GRID).scan(0.0, |c, i| {
            *c += h / first_guess(io, a + (i as f64 + 0.5) * h);
            Some(*c)
        }))
        .collect();
    let total = cum[GRID];
    let k = ((total / 3.0).floor() as usize).clamp(1, SEGMENTS);
    let mut out = vec![a];
    for i in 1..k {
        let target = total * i as f64 / k as f64;
        let g = cum.partition_point(|&c| c < target).min(GRID);
        let x = a + g as f64 * h;
        let c = super::sets::short_centre(x - h, x + h);
        if c > *out.last().expect("a") && c < b {
            out.push(c);
        }
    }
    out.push(b);
    out
}

/// At most this many segments (the runs' parallelism; fixed, so that the pieces do not
/// depend on the number of threads).
pub const SEGMENTS: usize = 16;

/// The node intervals a piece is aimed at. A range run costs ≈ 33 point runs (SHC DSS,
/// Maxwell DSA: 85–120 ms against 2.5–3 ms); were [e″] ∝ width, the work per unit of v0,
/// (C_range + m·C_point)/w with m ∝ w^(3/2), would be least at m = 2·C_range/C_point ≈ 64, but
/// [e″] grows faster on wide pieces: measured on [0.1, 5] at 1e-9 (benches/RESULTS.md), 24,
/// 32, 40, 64 gave 15.1, 14.8, 15.1, 17.1 s (SHC DSS) and 16.3, 15.5, 15.3, 15.3 s (Maxwell
/// DSA).
pub const AIM_NODES: f64 = 40.0;

/// The next width from a piece of width `w` that needed `m` node intervals: m ∝ w^(3/2),
/// aimed at [`AIM_NODES`], the change clamped to [lo, hi].
fn next_width(w: f64, m: f64, lo: f64, hi: f64) -> f64 {
    w * (AIM_NODES / m.max(1.0)).powf(2.0 / 3.0).clamp(lo, hi)
}

/// The reason of a segment stopped because another one failed.
const ABORTED: &str = "another segment failed";

/// One segment [s0, s1] walked from its left end, each piece's width from the last one's
/// nodes ([`next_width`]); the pieces in order, the range runs and the point runs made. Stops
/// (an error) when another segment has failed (`abort`).
fn walk(
    kind: ModelKind,
    base: &NdParams<Interval>,
    (s0, s1): (f64, f64),
    io: &InterpOptions,
    opts: &TaylorOptions,
    settled: &dyn Fn(f64),
    abort: &AtomicBool,
) -> Result<(Vec<InterpPiece>, usize, usize), RigorError> {
    let (mut pieces, mut range_runs, mut point_runs) = (Vec::new(), 0, 0);
    let (mut lo, mut w) = (s0, first_guess(io, s0));
    let stop = |reason: &str| RigorError {
        reason: reason.into(),
        t: 0.0,
        width: 0.0,
    };
    while lo < s1 {
        if opts.out_of_time() {
            return Err(stop(crate::engines::taylor::DEADLINE));
        }
        if abort.load(Ordering::Relaxed) {
            return Err(stop(ABORTED));
        }
        // (no sliver left at the end: the last piece takes it)
        let hi = if lo + 1.25 * w >= s1 {
            s1
        } else {
            let c = super::sets::short_centre(lo + 0.9 * w, lo + 1.1 * w);
            if c > lo && c < s1 { c } else { lo + w }
        };
        if hi <= lo || hi.is_nan() {
            return Err(stop(&format!("no piece of width {w:e} after v0 = {lo}")));
        }
        range_runs += 1;
        w = hi - lo;
        let known = pieces
            .last()
            .map(|p: &InterpPiece| p.nodes[p.nodes.len() - 1]);
        match prove_piece(kind, base, (lo, hi), known, io, opts)? {
            Tried::Proved(p, m) => {
                point_runs += m + usize::from(known.is_none());
                pieces.push(p);
                settled(hi - lo);
                lo = hi;
                w = next_width(w, m as f64, 0.5, 2.0);
            }
            Tried::TooWide(m) => w = next_width(w, m, 0.125, 0.5),
            Tried::Failed => w /= 2.0,
        }
        w = w.max(io.min_width);
    }
    Ok((pieces, range_runs, point_runs))
}

/// Proves the band of e (and T_s) over v0 ∈ [a, b] for base set `base` in the interpolation
/// form (module doc), thickness at most `io.thickness`: [a, b] cut into `segments`, walked in
/// parallel, each piece's width adapted to the nodes its neighbour needed (`walk`). Fails
/// with a piece that cannot be proved down to `io.min_width` (the other segments then stop).
pub fn prove_band_second(
    kind: ModelKind,
    base: &NdParams<Interval>,
    a: f64,
    b: f64,
    io: &InterpOptions,
    opts: &TaylorOptions,
) -> Result<InterpBand, RigorError> {
    if !(a < b && b.is_finite() && io.min_width > 0.0) {
        return Err(RigorError {
            reason: format!(
                "bad band: [{a}, {b}] with the narrowest piece {:e}",
                io.min_width
            ),
            t: 0.0,
            width: 0.0,
        });
    }
    let cuts = segments(io, a, b);
    let abort = AtomicBool::new(false);
    let state = std::sync::Mutex::new((0.0f64, 0usize));
    let settled = |dw: f64| {
        if let Some(Progress(f)) = &io.progress {
            // (one thread at a time, so that the shares told never go back)
            let mut s = state.lock().expect("no panic");
            s.0 += dw;
            s.1 += 1;
            f((s.0 / (b - a)).clamp(0.0, 1.0), s.1);
        }
    };
    let walked: Vec<_> = cuts
        .par_windows(2)
        .map(|w| {
            let r = walk(kind, base, (w[0], w[1]), io, opts, &settled, &abort);
            if r.is_err() {
                abort.store(true, Ordering::Relaxed);
            }
            r
        })
        .collect();
    // (the failure itself, not a segment it stopped)
    if let Some(Err(e)) = walked
        .iter()
        .find(|r| r.as_ref().is_err_and(|e| e.reason != ABORTED))
    {
        return Err(e.clone());
    }
    let walked = walked.into_iter().collect::<Result<Vec<_>, _>>()?;
    let mut band = InterpBand {
        pieces: Vec::new(),
        range_runs: 0,
        point_runs: 0,
    };
    for (pieces, r, p) in walked {
        band.pieces.extend(pieces);
        band.range_runs += r;
        band.point_runs += p;
    }
    Ok(band)
}
