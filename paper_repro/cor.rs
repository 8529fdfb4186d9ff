//! Fig. 3 (fig:CoR): the CoR against v0 of the four Table 1 (tab:param) base sets, by the f64
//! DOP853 engine (the paper's settings), and with --rigorous as proved enclosures.

use bwcl::engines::taylor::TaylorOptions;
use bwcl::fit::cost::model_cor;
use bwcl::models::scaling::nd_from_base;
use bwcl::models::{Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::FloatOptions;
use bwcl::observables::rigorous::rigorous_impact;
use inari::Interval;
use rayon::prelude::*;

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

/// The proved enclosures of one set at every speed (the base set enclosed as written, each v0
/// the exact double of the grid).
pub fn rigorous_curve(set: &Table1Set, v0: &[f64]) -> Vec<Proved> {
    let base = NdParams::<Interval>::parse(set.kind, set.base).expect("Table 1 sets are in 𝓟");
    let opts = TaylorOptions::default();
    v0.par_iter()
        .map(|&v| {
            let t0 = std::time::Instant::now();
            let iv = Interval::try_from((v, v)).expect("a finite speed");
            let e = nd_from_base(set.kind, &base, &iv)
                .map_err(|e| e.to_string())
                .and_then(|p| match set.kind {
                    ModelKind::Shc => rigorous_impact(&Shc::new(p), &opts)
                        .map(|r| r.e)
                        .map_err(|e| e.to_string()),
                    ModelKind::Maxwell => rigorous_impact(&Maxwell::new(p), &opts)
                        .map(|r| r.e)
                        .map_err(|e| e.to_string()),
                })
                .map(|e| (e.inf(), e.sup()));
            Proved {
                v0: v,
                e,
                seconds: t0.elapsed().as_secs_f64(),
            }
        })
        .collect()
}
