//! The honest demonstration of `bwcl fit`: synthetic CoR data from a Table 1 set with seeded
//! Gaussian noise, fitted back by the same library call as `bwcl fit`.

use bwcl::fit::cost::model_cor;
use bwcl::fit::{CorData, FitOptions, FitResult, cost, fit};
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::FloatOptions;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Settings of the synthetic data.
#[derive(Clone, Debug)]
pub struct Synth {
    pub kind: ModelKind,
    pub base: String,
    pub points: usize,
    pub vmin: f64,
    pub vmax: f64,
    pub sigma: f64,
    pub seed: u64,
}

/// e(𝓟(P*, v0_i)) + σ N(0, 1) at `points` evenly spaced speeds (ChaCha8 + Box–Muller, clamped
/// to [0, 1]).
pub fn synthesize(s: &Synth) -> Result<CorData, String> {
    let base = NdParams::<f64>::parse(s.kind, &s.base).map_err(|e| e.to_string())?;
    if s.points < 2 || !(s.vmin > 0.0 && s.vmax > s.vmin) || s.sigma.is_nan() || s.sigma < 0.0 {
        return Err("synthetic data: need points ≥ 2, 0 < vmin < vmax, sigma ≥ 0".into());
    }
    let v0: Vec<f64> = (0..s.points)
        .map(|i| s.vmin + (s.vmax - s.vmin) * i as f64 / (s.points - 1) as f64)
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
    let mut e = Vec::with_capacity(v0.len());
    for r in model_cor(s.kind, &base, &v0, &FloatOptions::default()) {
        let clean = r?;
        let (u1, u2): (f64, f64) = (rng.random::<f64>(), rng.random::<f64>());
        let z = (-2.0 * (1.0 - u1).ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
        // rounded to 6 decimals, as measured data would be written
        e.push(((clean + s.sigma * z).clamp(0.0, 1.0) * 1e6).round() / 1e6);
    }
    CorData::new(v0, e).map_err(|e| e.to_string())
}

/// The fit of a data set and what it is compared with.
pub struct Demo {
    pub data: CorData,
    pub result: FitResult,
    /// J at the set that generated the data (synthetic data only).
    pub j_truth: Option<f64>,
    pub truth: Option<NdParams<f64>>,
    /// σ_noise of the synthetic data, if known.
    pub sigma: Option<f64>,
}

pub fn run(
    kind: ModelKind,
    data: CorData,
    opts: &FitOptions,
    truth: Option<NdParams<f64>>,
    sigma: Option<f64>,
) -> Result<Demo, String> {
    let result = fit(kind, &data, opts, None)?;
    let j_truth = truth
        .as_ref()
        .map(|t| cost(kind, t, &data, &FloatOptions::default()));
    Ok(Demo {
        data,
        result,
        j_truth,
        truth,
        sigma,
    })
}
