//! The uncertainty of a fit at a point θ̂ of the free parameters (issue #31, item 1): what
//! `scipy.optimize.curve_fit`'s `pcov` gives, and the directions the data do not fix.
//!
//! ```text
//! J_ik = ∂r_i/∂θ_k                       r the weighted residuals of super::weights
//!      = −(∂e/∂θ_k)(𝓟(θ̂, v0_i)) / s_i                          (CoR rows)
//!      = −(∂T_s/∂θ_k · v0^(−(p−1)/(p+1))
//!          − [θ_k = p] T_s v0^(−(p−1)/(p+1)) ln v0 · 2/(p+1)²) / t_i   (tc rows)
//! C    = s² (JᵀJ)⁻¹ = s² V Σ⁻² Vᵀ     (J = U Σ Vᵀ, the thin SVD)
//! SE_k = sqrt(C_kk),   ρ_kl = C_kl / (SE_k SE_l)
//! ```
//!
//! s² = J_best²/(M_res − k) without given errors (curve_fit's default), s² = 1 with them
//! (`absolute_sigma=True`). The derivatives ∂e/∂u, ∂T_s/∂u are the midpoints of the proved
//! sensitivities ([`crate::observables::sets::sensitivity`], enclosures of width ~1e−8 at a
//! point); a column where one of them fails (near the branch point n = 1, say) is computed by
//! central differences of the f64 engine instead, and the result says so. A singular value
//! below [`POOR`] times the largest marks a combination of parameters the data do not determine
//! (its right singular vector, in the units of P*).

use super::cost::{residuals, tc_scale};
use super::data::CorData;
use super::space::NAMES;
use super::weights::Weights;
use crate::engines::taylor::TaylorOptions;
use crate::models::{ModelKind, NdParams};
use crate::observables::FloatOptions;
use crate::observables::sets::{Inputs, sensitivity};
use inari::Interval;
use nalgebra::DMatrix;
use rayon::prelude::*;

/// Ratio σ_i/σ_max below which a direction counts as poorly determined.
pub const POOR: f64 = 1e-3;

/// Local error target of the proved sensitivities' Taylor steps: 1e−12 instead of the
/// engine's 8e−16 — only the midpoints are used, the enclosures stay ~1e−7 wide at most, and
/// the runs take about 25 % less time (measured on the DSS set at v0 = 0.1, 1, 5 m/s).
pub const SENSITIVITY_TOL: f64 = 1e-12;

/// How the Jacobian is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JacobianMethod {
    /// The proved sensitivities' midpoints, a column by central differences where they fail.
    Proved,
    /// Central differences of the f64 engine (tolerances 1e−13/1e−15) for every column.
    Central,
}

/// The uncertainty of a fit (module doc).
#[derive(Clone, Debug, serde::Serialize)]
pub struct Uncertainty {
    /// The free parameters, in the order of every vector and matrix below.
    pub names: Vec<&'static str>,
    pub theta: Vec<f64>,
    /// M_res × k.
    pub jacobian: Vec<Vec<f64>>,
    /// Per column: "proved" or "central differences (why)".
    pub jacobian_source: Vec<String>,
    pub s2: f64,
    pub covariance: Vec<Vec<f64>>,
    pub std_errors: Vec<f64>,
    pub correlation: Vec<Vec<f64>>,
    /// Singular values of J, largest first.
    pub singular_values: Vec<f64>,
    /// The right singular vectors, one per singular value (components in `names` order).
    pub directions: Vec<Vec<f64>>,
    /// σ_max / σ_min (∞ for a rank-deficient J).
    pub condition_number: f64,
    /// The poorly determined combinations, as text ("0.71 kappa − 0.70 sigma_b (σ/σ_max = 3e-5)").
    pub poorly_determined: Vec<String>,
}

fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE)
}

fn with(base: &NdParams<f64>, i: usize, x: f64) -> [f64; 6] {
    let mut a = base.as_array();
    a[i] = x;
    a
}

/// The f64 engine at tight tolerances, for central differences.
pub fn tight(float: &FloatOptions) -> FloatOptions {
    let mut f = float.clone();
    f.ode.rtol = 1e-13;
    f.ode.atol = 1e-15;
    f
}

/// Column ∂r/∂x_i by central differences (h = 1e−5 max(|x_i|, 1e−2); one-sided where x_i ± h
/// leaves 𝓟), and how.
pub fn central_column(
    kind: ModelKind,
    base: &NdParams<f64>,
    i: usize,
    data: &CorData,
    w: &Weights,
    float: &FloatOptions,
) -> Result<(Vec<f64>, &'static str), String> {
    let x = base.as_array()[i];
    let h = 1e-5 * x.abs().max(1e-2);
    let f = tight(float);
    let at = |y: f64| {
        let a = with(base, i, y);
        NdParams::new(kind, a[0], a[1], a[2], a[3], a[4], a[5])
            .ok()
            .map(|p| residuals(kind, &p, data, w, &f))
    };
    match (at(x + h), at(x - h)) {
        (Some(a), Some(b)) => Ok((
            a.iter().zip(&b).map(|(p, m)| (p - m) / (2.0 * h)).collect(),
            "central",
        )),
        (Some(a), None) => {
            let r0 = residuals(kind, base, data, w, &f);
            Ok((
                a.iter().zip(&r0).map(|(p, c)| (p - c) / h).collect(),
                "forward",
            ))
        }
        (None, Some(b)) => {
            let r0 = residuals(kind, base, data, w, &f);
            Ok((
                r0.iter().zip(&b).map(|(c, m)| (c - m) / h).collect(),
                "backward",
            ))
        }
        (None, None) => Err(format!("{} ± {h} both leave 𝓟", NAMES[i])),
    }
}

/// Column ∂r/∂x_i from the proved sensitivities' midpoints (`Err` with the first failure).
fn proved_column(
    kind: ModelKind,
    base: &NdParams<f64>,
    i: usize,
    data: &CorData,
    w: &Weights,
    taylor: &TaylorOptions,
    float: &FloatOptions,
) -> Result<Vec<f64>, String> {
    let bi = NdParams {
        b: point(base.b),
        gamma: point(base.gamma),
        kappa: point(base.kappa),
        sigma: point(base.sigma),
        n: point(base.n),
        p: point(base.p),
    };
    let rows: Vec<Result<(f64, f64, f64), String>> = data
        .v0
        .par_iter()
        .map(|&v0| {
            let inp = Inputs::Base {
                base: bi.clone(),
                v0: point(v0),
            };
            let s = sensitivity(kind, &inp, i, taylor)
                .map_err(|e| format!("v0 = {v0}: {}", e.reason))?;
            let (de, dts) = (s.e.mid(), s.ts.mid());
            if !(de.is_finite() && dts.is_finite()) {
                return Err(format!("v0 = {v0}: no finite derivative"));
            }
            // T_s itself for the p term of the duration's chain rule
            let ts = if w.tc.is_some() && i == 5 {
                super::cost::model_point(kind, base, v0, float)?.1 / tc_scale(base.p, v0)
            } else {
                0.0
            };
            Ok((de, dts, ts))
        })
        .collect();
    let rows: Vec<(f64, f64, f64)> = rows.into_iter().collect::<Result<_, _>>()?;
    let mut col: Vec<f64> = rows
        .iter()
        .zip(&w.e)
        .map(|(&(de, _, _), &s)| -de / s)
        .collect();
    if let Some(tc) = &w.tc {
        let p = base.p;
        col.extend(
            rows.iter()
                .zip(tc)
                .zip(&data.v0)
                .map(|((&(_, dts, ts), &(_, t)), &v0)| {
                    let sc = tc_scale(p, v0);
                    let mut d = dts * sc;
                    if i == 5 {
                        d -= ts * sc * v0.ln() * 2.0 / ((p + 1.0) * (p + 1.0));
                    }
                    -d / t
                }),
        );
    }
    Ok(col)
}

/// The Jacobian of the weighted residuals over the free parameters `free` (indices of P*) at
/// `base`: M_res rows, a column per free parameter, and each column's source.
pub fn jacobian(
    kind: ModelKind,
    base: &NdParams<f64>,
    free: &[usize],
    data: &CorData,
    w: &Weights,
    method: JacobianMethod,
    float: &FloatOptions,
) -> Result<(Vec<Vec<f64>>, Vec<String>), String> {
    let taylor = TaylorOptions {
        tol: SENSITIVITY_TOL,
        ..TaylorOptions::default()
    };
    let cols: Vec<Result<(Vec<f64>, String), String>> = free
        .par_iter()
        .map(|&i| {
            let proved = match method {
                JacobianMethod::Proved => {
                    proved_column(kind, base, i, data, w, &taylor, float).map_err(Some)
                }
                JacobianMethod::Central => Err(None),
            };
            match proved {
                Ok(c) => Ok((c, "proved".to_string())),
                Err(why) => {
                    let (c, how) = central_column(kind, base, i, data, w, float)
                        .map_err(|e| format!("the Jacobian's column {}: {e}", NAMES[i]))?;
                    let note = match why {
                        Some(w) => {
                            format!("{how} differences (the proved sensitivity failed: {w})")
                        }
                        None => format!("{how} differences"),
                    };
                    Ok((c, note))
                }
            }
        })
        .collect();
    let cols: Vec<(Vec<f64>, String)> = cols.into_iter().collect::<Result<_, _>>()?;
    let m = cols.first().map_or(0, |c| c.0.len());
    let jac = (0..m)
        .map(|r| cols.iter().map(|c| c.0[r]).collect())
        .collect();
    Ok((jac, cols.into_iter().map(|c| c.1).collect()))
}

/// Covariance, standard errors, correlations and SVD of a Jacobian `jac` (M_res × k) with scale
/// `s2` (module doc).
pub fn from_jacobian(
    names: Vec<&'static str>,
    theta: Vec<f64>,
    jac: Vec<Vec<f64>>,
    source: Vec<String>,
    s2: f64,
) -> Uncertainty {
    let k = names.len();
    let m = jac.len();
    let a = DMatrix::from_fn(m, k, |r, c| jac[r][c]);
    let svd = a.svd(false, true);
    let vt = svd.v_t.clone().unwrap_or_else(|| DMatrix::identity(k, k));
    let mut idx: Vec<usize> = (0..svd.singular_values.len()).collect();
    idx.sort_by(|&x, &y| svd.singular_values[y].total_cmp(&svd.singular_values[x]));
    let sv: Vec<f64> = idx.iter().map(|&i| svd.singular_values[i]).collect();
    let directions: Vec<Vec<f64>> = idx
        .iter()
        .map(|&i| {
            let mut d: Vec<f64> = (0..k).map(|c| vt[(i, c)]).collect();
            // sign: the largest component positive
            let big = d
                .iter()
                .fold(0.0f64, |b, &x| if x.abs() > b.abs() { x } else { b });
            if big < 0.0 {
                d.iter_mut().for_each(|x| *x = -*x);
            }
            d
        })
        .collect();
    // C = s² Σ_i v_i v_iᵀ / σ_i²  (σ_i = 0: infinite along v_i)
    let mut cov = vec![vec![0.0; k]; k];
    for (d, &s) in directions.iter().zip(&sv) {
        for r in 0..k {
            for c in 0..k {
                let term = d[r] * d[c];
                if term != 0.0 {
                    cov[r][c] += s2 * term / (s * s);
                }
            }
        }
    }
    let se: Vec<f64> = (0..k).map(|i| cov[i][i].sqrt()).collect();
    let corr = (0..k)
        .map(|r| (0..k).map(|c| cov[r][c] / (se[r] * se[c])).collect())
        .collect();
    let smax = sv.first().copied().unwrap_or(0.0);
    let smin = sv.last().copied().unwrap_or(0.0);
    let poorly = sv
        .iter()
        .zip(&directions)
        .filter(|&(&s, _)| s.is_nan() || s <= POOR * smax)
        .map(|(&s, d)| describe(&names, d, s / smax))
        .collect();
    Uncertainty {
        names,
        theta,
        jacobian: jac,
        jacobian_source: source,
        s2,
        covariance: cov,
        std_errors: se,
        correlation: corr,
        singular_values: sv,
        condition_number: smax / smin,
        directions,
        poorly_determined: poorly,
    }
}

/// A direction as text: its components ≥ 0.1 in size, largest first.
pub fn describe(names: &[&str], d: &[f64], ratio: f64) -> String {
    let mut parts: Vec<(f64, &str)> = d
        .iter()
        .zip(names)
        .filter(|(x, _)| x.abs() >= 0.1)
        .map(|(&x, &n)| (x, n))
        .collect();
    parts.sort_by(|a, b| b.0.abs().total_cmp(&a.0.abs()));
    let mut s = String::new();
    for (i, (x, n)) in parts.iter().enumerate() {
        let sign = if *x < 0.0 {
            "−"
        } else if i > 0 {
            "+"
        } else {
            ""
        };
        if i > 0 {
            s.push(' ');
        }
        s.push_str(&format!("{sign}{:.2} {n}", x.abs()));
    }
    format!("{s} (σ/σ_max = {ratio:.1e})")
}

/// The uncertainty at `base` over the free parameters `free` (see the module doc).
#[allow(clippy::too_many_arguments)]
pub fn uncertainty(
    kind: ModelKind,
    base: &NdParams<f64>,
    free: &[usize],
    data: &CorData,
    w: &Weights,
    s2: f64,
    method: JacobianMethod,
    float: &FloatOptions,
) -> Result<Uncertainty, String> {
    let (jac, source) = jacobian(kind, base, free, data, w, method, float)?;
    let x = base.as_array();
    Ok(from_jacobian(
        free.iter().map(|&i| NAMES[i]).collect(),
        free.iter().map(|&i| x[i]).collect(),
        jac,
        source,
        s2,
    ))
}
