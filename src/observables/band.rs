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
//! **Monotonicity**: sup [de/dv0] < 0 on a piece proves e strictly decreasing there (e is C¹ in
//! v0: the field is Lipschitz and piecewise C¹ with transversal crossings, so the variational
//! equation holds almost everywhere); pieces where the slope's sign is not decided are split
//! down to a minimum width and then named.

use super::sets::{Inputs, SetEnclosure, prove_over_set};
use crate::engines::taylor::{RigorError, TaylorOptions};
use crate::models::{ModelKind, NdParams};
use inari::Interval;
use rayon::prelude::*;

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

/// Options of the adaptive cut.
#[derive(Clone, Debug)]
pub struct BandOptions {
    /// Largest thickness of the band (vertical width of the enclosure of e).
    pub thickness: f64,
    /// Pieces are not split below this width of v0.
    pub min_width: f64,
    /// The first cut: this many equal pieces.
    pub initial: usize,
    /// Most pieces in all.
    pub max_pieces: usize,
}

impl Default for BandOptions {
    fn default() -> Self {
        Self {
            thickness: 1e-6,
            min_width: 1e-6,
            initial: 16,
            max_pieces: 20_000,
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
    let r: SetEnclosure = prove_over_set(kind, &inputs, opts)?;
    let (Some(slope), Some((c, ts_c, e_c))) = (r.slope, r.centre) else {
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

/// Cuts [a, b] adaptively until every piece is proved and needs no more `parts` (0), or is at
/// the minimum width; a proved piece is cut into `parts` equal parts (at least 2), one not
/// proved is halved; pieces are proved in parallel (rayon). Returns the pieces in order, each with its
/// result.
fn adapt(
    kind: ModelKind,
    base: &NdParams<Interval>,
    a: f64,
    b: f64,
    bo: &BandOptions,
    opts: &TaylorOptions,
    parts: impl Fn(&BandPiece) -> usize + Sync,
) -> Vec<(f64, f64, Result<BandPiece, RigorError>)> {
    let n = bo.initial.max(1);
    let cut: Vec<f64> = (0..=n)
        .map(|i| {
            if i == n {
                b
            } else {
                a + (b - a) * (i as f64) / (n as f64)
            }
        })
        .collect();
    let mut todo: Vec<(f64, f64)> = cut.windows(2).map(|w| (w[0], w[1])).collect();
    let mut done: Vec<(f64, f64, Result<BandPiece, RigorError>)> = Vec::new();
    while !todo.is_empty() {
        let results: Vec<(f64, f64, Result<BandPiece, RigorError>)> = todo
            .par_iter()
            .map(|&(lo, hi)| (lo, hi, prove_piece(kind, base, lo, hi, opts)))
            .collect();
        todo.clear();
        for (lo, hi, r) in results {
            // a piece not proved is halved
            let k = r.as_ref().map_or(2, &parts);
            let k = if k == 0 {
                0
            } else {
                // no part narrower than min_width
                k.clamp(2, 64).min(((hi - lo) / bo.min_width) as usize)
            };
            let cut: Vec<f64> = (0..=k)
                .map(|i| match i {
                    0 => lo,
                    i if i == k => hi,
                    i => lo + (hi - lo) * (i as f64) / (k as f64),
                })
                .collect();
            let can_split = k >= 2 && cut.windows(2).all(|w| w[0] < w[1]);
            if !can_split || done.len() + todo.len() + k > bo.max_pieces {
                done.push((lo, hi, r));
            } else {
                todo.extend(cut.windows(2).map(|w| (w[0], w[1])));
            }
        }
    }
    done.sort_by(|x, y| x.0.total_cmp(&y.0));
    done
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
    // the thickness of a proved piece grows like its width squared or faster (measured: about
    // squared near 1e-6, faster on the first, wide pieces): cut a piece too thick into
    // ⌈1.15·∛(thickness/target)⌉ parts instead of halving it again and again (the square root
    // over-cut: v0 ∈ [2, 2.5] at 1e-5 took 88 pieces against 59 with the cube root)
    let done = adapt(kind, base, a, b, bo, opts, |p| {
        let t = p.thickness();
        if t <= bo.thickness {
            0
        } else {
            ((t / bo.thickness).cbrt() * 1.15).ceil() as usize
        }
    });
    let mut pieces = Vec::with_capacity(done.len());
    for (lo, hi, r) in done {
        let p = r.map_err(|e| RigorError {
            reason: format!("for v0 in [{lo}, {hi}]: {}", e.reason),
            ..e
        })?;
        if p.thickness() > bo.thickness {
            return Err(RigorError {
                reason: format!(
                    "for v0 in [{lo}, {hi}]: the band is {:e} thick (the target is {:e}) at the \
                     smallest piece or the piece budget",
                    p.thickness(),
                    bo.thickness
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
    /// The sub-ranges where it could not be proved (merged), with the reason.
    pub undecided: Vec<(f64, f64, String)>,
}

impl Monotonicity {
    pub fn proved(&self) -> bool {
        self.undecided.is_empty()
    }
    /// The largest proved slope (sup of de/dv0 over all pieces): e decreases at least this fast.
    pub fn max_slope(&self) -> f64 {
        self.pieces
            .iter()
            .map(|p| p.2.sup())
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

/// Proves e(v0) strictly decreasing on [a, b] (sup de/dv0 < 0 on every piece), or names the
/// sub-ranges where it cannot.
pub fn prove_decreasing(
    kind: ModelKind,
    base: &NdParams<Interval>,
    a: f64,
    b: f64,
    bo: &BandOptions,
    opts: &TaylorOptions,
) -> Monotonicity {
    let done = adapt(kind, base, a, b, bo, opts, |p| {
        if p.de.sup() < 0.0 { 0 } else { 2 }
    });
    let mut out = Monotonicity {
        pieces: Vec::new(),
        undecided: Vec::new(),
    };
    for (lo, hi, r) in done {
        let why = match r {
            Ok(p) if p.de.sup() < 0.0 => {
                out.pieces.push((lo, hi, p.de));
                continue;
            }
            Ok(p) => format!("de/dv0 ∈ [{:e}, {:e}] is not < 0", p.de.inf(), p.de.sup()),
            Err(e) => e.reason,
        };
        match out.undecided.last_mut() {
            Some(last) if last.1 == lo => last.1 = hi,
            _ => out.undecided.push((lo, hi, why)),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

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
