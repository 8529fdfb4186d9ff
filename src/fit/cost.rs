//! The cost J of eq:J and the model's CoR curve 𝓟(P*, ṽ0_i) ↦ e, the speeds in parallel.

use super::data::CorData;
use crate::models::scaling::nd_from_base;
use crate::models::{Maxwell, ModelKind, NdParams, Shc};
use crate::observables::{FloatOptions, impact};
use rayon::prelude::*;

/// Settings of a CoR evaluation: the f64 engine's (the paper's by default).
pub type CostOptions = FloatOptions;

/// The CoR of the model with nondimensional set `p` (`Err` with the reason when the set could
/// not be integrated).
pub fn cor(kind: ModelKind, p: NdParams<f64>, opts: &FloatOptions) -> Result<f64, String> {
    match kind {
        ModelKind::Shc => impact(&Shc::new(p), opts).map(|r| r.e),
        ModelKind::Maxwell => impact(&Maxwell::new(p), opts).map(|r| r.e),
    }
    .map_err(|e| e.to_string())
}

/// e(𝓟(P*, v0)) at each speed, evaluated in parallel; a speed where the base set cannot be
/// mapped (overflow) or integrated gives `Err` with the reason.
pub fn model_cor(
    kind: ModelKind,
    base: &NdParams<f64>,
    v0: &[f64],
    opts: &FloatOptions,
) -> Vec<Result<f64, String>> {
    v0.par_iter()
        .map(|v| {
            let p = nd_from_base(kind, base, v).map_err(|e| e.to_string())?;
            cor(kind, p, opts)
        })
        .collect()
}

/// The data beside the model: the fitted curve and J.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FitCurve {
    pub v0: Vec<f64>,
    pub e_data: Vec<f64>,
    /// `None` where the model could not be evaluated (see `errors`).
    pub e_model: Vec<Option<f64>>,
    /// J of eq:J; a speed without a model value counts with the residual 1 (the largest
    /// possible for CoRs in [0, 1]), so J is then an upper bound, not the paper's J.
    #[serde(rename = "J")]
    pub j: f64,
    /// (v0, reason) of every speed without a model value.
    pub errors: Vec<(f64, String)>,
}

/// J(ṽ0, ẽ, P*) (eq:J) with the model's curve.
pub fn model_curve(
    kind: ModelKind,
    base: &NdParams<f64>,
    data: &CorData,
    opts: &FloatOptions,
) -> FitCurve {
    let res = model_cor(kind, base, &data.v0, opts);
    let mut ss = 0.0;
    let mut errors = Vec::new();
    let mut e_model = Vec::with_capacity(res.len());
    for ((r, &v), &ed) in res.into_iter().zip(&data.v0).zip(&data.e) {
        match r {
            Ok(e) => {
                ss += (ed - e) * (ed - e);
                e_model.push(Some(e));
            }
            Err(why) => {
                ss += 1.0;
                errors.push((v, why));
                e_model.push(None);
            }
        }
    }
    FitCurve {
        v0: data.v0.clone(),
        e_data: data.e.clone(),
        e_model,
        j: ss.sqrt(),
        errors,
    }
}

/// J(ṽ0, ẽ, P*) (eq:J): always a finite number ≥ 0 (a speed the model cannot evaluate counts
/// with residual 1, see [`FitCurve::j`]).
pub fn cost(kind: ModelKind, base: &NdParams<f64>, data: &CorData, opts: &FloatOptions) -> f64 {
    model_cor(kind, base, &data.v0, opts)
        .into_iter()
        .zip(&data.e)
        .map(|(r, &ed)| match r {
            Ok(e) => (ed - e) * (ed - e),
            Err(_) => 1.0,
        })
        .sum::<f64>()
        .sqrt()
}
