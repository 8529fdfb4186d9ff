//! Fig. 3 (fig:CoR): the CoR against v0 of the four Table 1 (tab:param) base sets, by the f64
//! DOP853 engine (the paper's settings), and with --rigorous as the continuous proved band.

use bwcl::engines::taylor::TaylorOptions;
use bwcl::fit::cost::model_cor;
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::FloatOptions;
use inari::Interval;

/// One column of Table 1.
pub struct Table1Set {
    pub kind: ModelKind,
    /// DSS or DSA.
    pub data: &'static str,
    pub base: &'static str,
    /// The paper's J.
    pub j: f64,
}

pub const TABLE1: [Table1Set; 4] = [
    Table1Set {
        kind: ModelKind::Shc,
        data: "DSS",
        base: "1.43,-1.42,0.632,0.00715,1.31,1.27",
        j: 0.0357,
    },
    Table1Set {
        kind: ModelKind::Shc,
        data: "DSA",
        base: "0.63,-0.611,0.188,0.00594,1,2.02",
        j: 0.011,
    },
    Table1Set {
        kind: ModelKind::Maxwell,
        data: "DSS",
        base: "0.655,-0.64,0.519,0.0118,1.94,2.28",
        j: 0.0406,
    },
    Table1Set {
        kind: ModelKind::Maxwell,
        data: "DSA",
        base: "0.44,-0.418,0.113,0.00785,1.27,3.14",
        j: 0.0114,
    },
];

pub fn model_title(kind: ModelKind) -> &'static str {
    match kind {
        ModelKind::Shc => "NDBWSHCCM",
        ModelKind::Maxwell => "NDBWMCM",
    }
}

/// `points` speeds from 0.05 to 6 m/s, evenly spaced.
pub fn grid(points: usize) -> Vec<f64> {
    let (a, b) = (0.05, 6.0);
    (0..points)
        .map(|i| a + (b - a) * i as f64 / (points - 1) as f64)
        .collect()
}

/// The f64 curve of one set: e at every speed (`Err` with the reason where it failed).
pub fn float_curve(set: &Table1Set, v0: &[f64]) -> Vec<Result<f64, String>> {
    let base = NdParams::<f64>::parse(set.kind, set.base).expect("Table 1 sets are in 𝓟");
    model_cor(set.kind, &base, v0, &FloatOptions::default())
}

/// A proved enclosure of e at one speed, or why it was not proved.
pub struct Proved {
    pub v0: f64,
    pub e: Result<(f64, f64), String>,
    pub seconds: f64,
}

/// The continuous proved band of e over v0 ∈ [a, b] for one set ([`bwcl::observables::band`]):
/// the enclosure of e at the ends and the centre of every piece (its bounds are linear in v0
/// between them), the piece count and the band's thickness; or why it was not proved.
pub fn band_curve(
    set: &Table1Set,
    a: f64,
    b: f64,
    thickness: f64,
) -> Result<(Vec<Proved>, usize, f64, f64), String> {
    use bwcl::observables::band::{BandOptions, prove_band};
    let base = NdParams::<Interval>::parse(set.kind, set.base).expect("Table 1 sets are in 𝓟");
    let t0 = std::time::Instant::now();
    let bo = BandOptions {
        thickness,
        ..BandOptions::default()
    };
    let band = prove_band(set.kind, &base, a, b, &bo, &TaylorOptions::default())
        .map_err(|e| e.to_string())?;
    let secs = t0.elapsed().as_secs_f64() / band.pieces.len().max(1) as f64;
    let mut pts = Vec::with_capacity(3 * band.pieces.len());
    for p in &band.pieces {
        for v in [p.v0_lo, p.v0_c, p.v0_hi] {
            let e = p
                .e_at(Interval::try_from((v, v)).expect("finite"))
                .expect("inside its piece");
            pts.push(Proved {
                v0: v,
                e: Ok((e.inf(), e.sup())),
                seconds: secs / 3.0,
            });
        }
    }
    // sup de/dv0 over all pieces: < 0 proves e strictly decreasing on [a, b] (the argument of
    // `bwcl prove monotone`, here on the band's own pieces)
    let max_slope = band
        .pieces
        .iter()
        .map(|p| p.de.sup())
        .fold(f64::NEG_INFINITY, f64::max);
    Ok((pts, band.pieces.len(), band.thickness(), max_slope))
}
