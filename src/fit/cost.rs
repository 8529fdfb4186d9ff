//! The cost J of eq:J and the model's CoR curve 𝓟(P*, ṽ0_i) ↦ e, the speeds in parallel; the
//! model's contact duration tc(P*, v0) and the weighted residuals of issue #31.

use super::data::CorData;
use super::weights::Weights;
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

/// The model's contact duration in units of T_c,b = T_c(v0 = 1 m/s) (eq:BWSHCCM_T_c:
/// T_c = T_c,b v0^(−(p−1)/(p+1))):
///
/// ```text
/// tc(P*, v0) = T_s(𝓟(P*, v0)) · v0^(−(p−1)/(p+1))
/// ```
///
/// with T_s the nondimensional separation time of the f64 engine — a number of P* and v0 alone,
/// like e. `Err` when the set cannot be mapped or integrated, or does not separate before the
/// horizon.
pub fn tc_scale(p: f64, v0: f64) -> f64 {
    v0.powf(-(p - 1.0) / (p + 1.0))
}

/// e(𝓟(P*, v0)) and tc(P*, v0) (see [`tc_scale`]) of one speed: one integration gives both.
pub fn model_point(
    kind: ModelKind,
    base: &NdParams<f64>,
    v0: f64,
    opts: &FloatOptions,
) -> Result<(f64, f64), String> {
    let p = nd_from_base(kind, base, &v0).map_err(|e| e.to_string())?;
    let r = match kind {
        ModelKind::Shc => impact(&Shc::new(p), opts).map(|r| (r.e, r.ts)),
        ModelKind::Maxwell => impact(&Maxwell::new(p), opts).map(|r| (r.e, r.ts)),
    }
    .map_err(|e| e.to_string())?;
    match r.1 {
        Some(ts) => Ok((r.0, ts * tc_scale(base.p, v0))),
        None => Err(format!(
            "no separation before the horizon T = {}",
            opts.horizon
        )),
    }
}

/// The weighted residuals of [`Weights`] (module doc of [`super::weights`]):
/// r_i = (ẽ_i − e_i)/s_i, then, with durations, r_{M+i} = (t̃c_i − tc_i)/t_i. A speed the model
/// cannot evaluate counts with the e residual 1/s_i (the largest for CoRs in [0, 1]) and the tc
/// residual t̃c_i/t_i (a model duration 0), so J stays finite.
///
/// With unit errors and no durations the residuals are exactly those of eq:J (a failed speed:
/// residual 1, as in [`cost`]).
pub fn residuals(
    kind: ModelKind,
    base: &NdParams<f64>,
    data: &CorData,
    w: &Weights,
    opts: &FloatOptions,
) -> Vec<f64> {
    let with_tc = w.tc.is_some();
    let pts: Vec<Option<(f64, f64)>> = data
        .v0
        .par_iter()
        .map(|&v| {
            if with_tc {
                model_point(kind, base, v, opts).ok()
            } else {
                let p = nd_from_base(kind, base, &v).ok()?;
                cor(kind, p, opts).ok().map(|e| (e, f64::NAN))
            }
        })
        .collect();
    let mut r: Vec<f64> = pts
        .iter()
        .zip(&data.e)
        .zip(&w.e)
        .map(|((m, &ed), &s)| match m {
            Some((e, _)) => (ed - e) / s,
            None => 1.0 / s,
        })
        .collect();
    if let Some(tc) = &w.tc {
        r.extend(pts.iter().zip(tc).map(|(m, &(t, s))| match m {
            Some((_, tm)) => (t - tm) / s,
            None => t / s,
        }));
    }
    r
}

/// J = sqrt(Σ r²) of the weighted [`residuals`]: the paper's J (eq:J) with [`Weights::unit`].
pub fn weighted_cost(
    kind: ModelKind,
    base: &NdParams<f64>,
    data: &CorData,
    w: &Weights,
    opts: &FloatOptions,
) -> f64 {
    residuals(kind, base, data, w, opts)
        .iter()
        .map(|r| r * r)
        .sum::<f64>()
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> NdParams<f64> {
        NdParams::new(ModelKind::Shc, 1.43, -1.42, 0.632, 0.00715, 1.31, 1.27).unwrap()
    }

    #[test]
    fn unit_weights_give_the_papers_j_and_sigma_divides() {
        let o = FloatOptions::default();
        let d = CorData::new(vec![0.3, 1.0, 3.0], vec![0.7, 0.6, 0.5]).unwrap();
        let j = cost(ModelKind::Shc, &base(), &d, &o);
        let wj = weighted_cost(ModelKind::Shc, &base(), &d, &Weights::unit(&d), &o);
        assert_eq!(j, wj);
        // by hand: each residual divided by its sigma
        let s = [0.01, 0.02, 0.04];
        let ds = d
            .clone()
            .with_columns(Some(s.to_vec()), None, None)
            .unwrap();
        let w = Weights::new(&ds, None, None, true).unwrap();
        let em: Vec<f64> = model_cor(ModelKind::Shc, &base(), &d.v0, &o)
            .into_iter()
            .map(|r| r.unwrap())
            .collect();
        let hand = (0..3)
            .map(|i| ((d.e[i] - em[i]) / s[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        let got = weighted_cost(ModelKind::Shc, &base(), &ds, &w, &o);
        assert!((got - hand).abs() <= 1e-12 * hand, "{got} vs {hand}");
    }

    #[test]
    fn duration_is_ts_times_the_speed_scale() {
        let o = FloatOptions::default();
        let b = base();
        for v0 in [0.2, 1.0, 4.0] {
            let (e, tc) = model_point(ModelKind::Shc, &b, v0, &o).unwrap();
            let p = nd_from_base(ModelKind::Shc, &b, &v0).unwrap();
            let r = impact(&Shc::new(p), &o).unwrap();
            assert_eq!(e, r.e);
            let want = r.ts.unwrap() * v0.powf(-(1.27 - 1.0) / (1.27 + 1.0));
            assert_eq!(tc, want);
            if v0 == 1.0 {
                assert_eq!(tc, r.ts.unwrap());
            }
        }
    }
}
