//! The classical collision laws as families over the impact speed (issue #33, item 4): what
//! `fit`, `identify` and `compare` fit to CoR data beside the Bouc–Wen models.
//!
//! Each law's nondimensional form ([`crate::models::hunt_crossley`],
//! [`crate::models::kelvin_voigt`], [`crate::models::linear_maxwell`]) depends on the impact
//! speed v0 through one number at most, so a law's family over the speeds is one *base*
//! parameter θ (at v0 = 1 in the data's unit of speed, as the Bouc–Wen P* is):
//!
//! ```text
//! law              θ                      the model at v0     e(v0)
//! hooke, hertz     —                      σ = 0               1
//! hunt-crossley    σ_b = χ·(1 m/s)/k      σ = σ_b·v0          e(σ_b v0), decreasing in σ_b
//! kelvin-voigt     ζ = c/(2√(mk))         ζ                   constant; decreasing in ζ
//! linear-maxwell   c̃ = c/√(mk) > 1/2      c̃                   constant; increasing in c̃
//! ```
//!
//! e does not depend on the Hertz exponent n (the restitution relation of
//! [`crate::models::hunt_crossley`]); the runs use n = 3/2 ([`HERTZ_N`]). Linear Maxwell
//! separates only for c̃ > 1/2 (β = 1/(2c̃) < 1: for β ≥ 1 the spring's deflection never
//! changes sign, F > 0 for ever), so its family starts there.
//!
//! **Monotonicity**, which lets the rigorous side enclose e over a parameter interval by the
//! proved enclosures at its two ends ([`Law::monotone_from`]):
//! - Hunt–Crossley: e(σ) is strictly decreasing (proved in [`crate::observables::restitution`])
//!   and σ = σ_b v0 with v0 > 0.
//! - Kelvin–Voigt, ζ < 1: with ζ = sin α, α ∈ [0, π/2), ω = cos α and φ = atan2(sin 2α, cos 2α)
//!   = 2α, so ln e = −ζ T_s = −tan α (π − 2α) and d ln e/dα = −((π − 2α) − sin 2α)/cos²α < 0
//!   (sin b < b for b = π − 2α > 0). ζ = 1: X = −T e^(−T), F = (2 − T) e^(−T), so T_s = 2 and
//!   e = e^(−2), the limit of both sides. ζ > 1: the roots −a, −1/a of r² + 2ζr + 1, a = ζ −
//!   √(ζ² − 1) ∈ (0, 1) decreasing in ζ, give F = 0 first at T_s = −4a ln a/(1 − a²) and
//!   e = a^(2(1 + a²)/(1 − a²)); d ln e/da has the sign of h(a) = 1 − a⁴ + 4a² ln a, and h(1) = 0,
//!   h′(a) = 4a(1 − a² + 2 ln a) < 0 on (0, 1) (the bracket is 0 at a = 1 with derivative
//!   2/a − 2a > 0), so h > 0: e increases with a and decreases with ζ. So e is continuous and
//!   strictly decreasing on all of ζ ≥ 0.
//! - Linear Maxwell, c̃ > 1/2: ln e = −πβ/√(1 − β²) is decreasing in β = 1/(2c̃), which is
//!   decreasing in c̃.
//!
//! The f64 fit minimizes the weighted J of [`super::weights`] over θ: a grid in ln(θ − floor)
//! over the bounds, every grid minimum refined by golden-section search, the distinct minima
//! kept with their Δχ², the standard error by central differences and the likelihood-ratio
//! interval {θ : J(θ)² − J_min² ≤ s² χ²_0.95(1)} (the profile: there is nothing else to
//! re-optimize).

use super::chi2::chi2_quantile;
use super::data::CorData;
use super::nelder_mead::FitStats;
use super::weights::Weights;
use crate::arith::float::golden::golden_min;
use crate::engines::taylor::TaylorOptions;
use crate::models::hunt_crossley::HuntCrossley;
use crate::models::kelvin_voigt::KelvinVoigt;
use crate::models::linear_maxwell::LinearMaxwell;
use crate::observables::rigorous::rigorous_impact;
use crate::observables::{FloatOptions, impact};
use inari::Interval;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// The Hertz exponent of the runs (e does not depend on it).
pub const HERTZ_N: f64 = 1.5;

pub use crate::models::classical::Law;

/// How e varies with θ on an interval.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Monotone {
    Increasing,
    Decreasing,
}

impl Law {
    /// The name of θ (`None`: the law has no parameter that enters e).
    pub fn parameter(self) -> Option<&'static str> {
        match self {
            Law::Hooke | Law::Hertz => None,
            Law::HuntCrossley => Some("sigma_b"),
            Law::KelvinVoigt => Some("zeta"),
            Law::LinearMaxwell => Some("c"),
        }
    }

    /// The lower end of θ's admissible set and whether it is excluded: σ_b, ζ ≥ 0; c̃ > 1/2.
    pub fn floor(self) -> (f64, bool) {
        match self {
            Law::LinearMaxwell => (0.5, true),
            _ => (0.0, false),
        }
    }

    /// Whether θ is admissible (module doc).
    pub fn admits(self, theta: f64) -> bool {
        let (f, open) = self.floor();
        theta.is_finite() && if open { theta > f } else { theta >= f }
    }

    /// The bounds searched when none are given: e spans (about) [1e−5, 1] over them for the
    /// data's speeds in [0.1, 10].
    pub fn default_bounds(self) -> (f64, f64) {
        match self {
            Law::HuntCrossley => (0.0, 100.0),
            Law::KelvinVoigt => (0.0, 10.0),
            _ => (0.52, 1e4),
        }
    }

    /// The largest θ accepted in bounds: σ_b ≤ 10⁴ (e ≈ 1/(σ_b v0) ≤ 1e−3 for speeds ≥ 0.1),
    /// ζ ≤ 10⁴ (e ≈ 1/(4ζ²)), c̃ ≤ 10¹² (1 − e ≈ π/(2c̃)).
    pub fn max_parameter(self) -> f64 {
        match self {
            Law::LinearMaxwell => 1e12,
            _ => 1e4,
        }
    }

    /// Checks bounds [lo, hi] of θ: ordered, finite, admissible; the refusal names them.
    pub fn check_bounds(self, lo: f64, hi: f64) -> Result<(), String> {
        let name = self.parameter().unwrap_or("the parameter");
        let (f, open) = self.floor();
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(format!("{name}: {lo}..{hi} is not a finite range lo ≤ hi"));
        }
        let cap = self.max_parameter();
        if hi > cap {
            return Err(format!(
                "{name} = {hi} is beyond {cap:e}, the largest the engines are asked to take (e is \
                 within 1e-3 of its limit there)"
            ));
        }
        if !self.admits(lo) {
            let why = match self {
                Law::LinearMaxwell => " (for c ≤ 1/2 the law never separates)",
                _ => "",
            };
            return Err(format!(
                "{name} = {lo} is outside the law's admissible set ({name} {} {f}){why}",
                if open { ">" } else { "≥" }
            ));
        }
        Ok(())
    }

    /// How e varies with θ on all of [lo, ∞) (module doc); `None` where it is not proved.
    pub fn monotone_from(self, lo: f64) -> Option<Monotone> {
        match self {
            Law::HuntCrossley if lo >= 0.0 => Some(Monotone::Decreasing),
            Law::KelvinVoigt if lo >= 0.0 => Some(Monotone::Decreasing),
            Law::LinearMaxwell if lo > 0.5 => Some(Monotone::Increasing),
            _ => None,
        }
    }

    /// e of the law with parameter θ at speed v0 on the f64 engine.
    pub fn cor(self, theta: f64, v0: f64, opts: &FloatOptions) -> Result<f64, String> {
        let e = |r: Result<f64, crate::observables::ImpactError>| r.map_err(|e| e.to_string());
        match self {
            Law::Hooke => e(impact(&HuntCrossley::<f64>::hooke(), opts).map(|r| r.e)),
            Law::Hertz => e(impact(&HuntCrossley::hertz(HERTZ_N)?, opts).map(|r| r.e)),
            Law::HuntCrossley => {
                e(impact(&HuntCrossley::new(theta * v0, HERTZ_N)?, opts).map(|r| r.e))
            }
            Law::KelvinVoigt => e(impact(&KelvinVoigt::new(theta)?, opts).map(|r| r.e)),
            Law::LinearMaxwell => {
                self.check_bounds(theta, theta)?;
                e(impact(&LinearMaxwell::new(theta)?, opts).map(|r| r.e))
            }
        }
    }

    /// A proved enclosure of e over θ ∈ `theta` at the speeds `v0` (the rigorous engine on the
    /// law with interval parameters).
    pub fn cor_enclosure(
        self,
        theta: Interval,
        v0: Interval,
        opts: &TaylorOptions,
    ) -> Result<Interval, String> {
        let three_halves = Interval::try_from((HERTZ_N, HERTZ_N)).expect("exact");
        let r = match self {
            Law::Hooke => rigorous_impact(&HuntCrossley::<Interval>::hooke(), opts).map(|r| r.e),
            Law::Hertz => rigorous_impact(&HuntCrossley::hertz(three_halves)?, opts).map(|r| r.e),
            Law::HuntCrossley => {
                rigorous_impact(&HuntCrossley::new(theta * v0, three_halves)?, opts).map(|r| r.e)
            }
            Law::KelvinVoigt => rigorous_impact(&KelvinVoigt::new(theta)?, opts).map(|r| r.e),
            Law::LinearMaxwell => {
                if theta.inf() <= 0.5 || theta.inf().is_nan() {
                    return Err(format!(
                        "c = [{}, {}] reaches c ≤ 1/2, where the law never separates",
                        theta.inf(),
                        theta.sup()
                    ));
                }
                rigorous_impact(&LinearMaxwell::new(theta)?, opts).map(|r| r.e)
            }
        };
        r.map_err(|e| e.reason)
    }
}

/// The weighted residuals r_i = (ẽ_i − e(θ, v0_i))/s_i (a speed the engine cannot evaluate:
/// residual 1/s_i, as in [`super::cost::residuals`]).
pub fn residuals(
    law: Law,
    theta: f64,
    data: &CorData,
    w: &Weights,
    opts: &FloatOptions,
) -> Vec<f64> {
    data.v0
        .iter()
        .zip(&data.e)
        .zip(&w.e)
        .map(|((&v, &ed), &s)| match law.cor(theta, v, opts) {
            Ok(e) => (ed - e) / s,
            Err(_) => 1.0 / s,
        })
        .collect()
}

/// J = sqrt(Σ r²) of [`residuals`].
pub fn cost(law: Law, theta: f64, data: &CorData, w: &Weights, opts: &FloatOptions) -> f64 {
    residuals(law, theta, data, w, opts)
        .iter()
        .map(|r| r * r)
        .sum::<f64>()
        .sqrt()
}

/// One distinct local minimum of J(θ).
#[derive(Clone, Debug, serde::Serialize)]
pub struct LawMinimum {
    pub theta: f64,
    #[serde(rename = "J")]
    pub j: f64,
    /// (J² − J_best²)/s².
    pub delta_chi2: f64,
    /// Δχ² ≤ χ²_0.95(1).
    pub indistinguishable: bool,
    /// θ is at (within 1e−9 relative of) a bound of the search.
    pub at_bound: bool,
}

/// The fit of one law (module doc).
#[derive(Clone, Debug)]
pub struct LawFit {
    pub law: Law,
    /// The searched bounds of θ (`None` for a law without parameter).
    pub bounds: Option<(f64, f64)>,
    /// The best θ.
    pub theta: Option<f64>,
    pub j: f64,
    /// e of the law at each speed at the best θ (`None` where the engine failed).
    pub e_model: Vec<Option<f64>>,
    /// Distinct minima, best first.
    pub minima: Vec<LawMinimum>,
    pub stats: FitStats,
    /// The standard error of θ: sqrt(s² / Σ (∂r_i/∂θ)²), central differences.
    pub se: Option<f64>,
    /// The likelihood-ratio 95 % interval of θ, each end with whether it is a bound of the
    /// search (the interval then reaches past it).
    pub interval: Option<[(f64, bool); 2]>,
    pub evaluations: usize,
    pub elapsed: Duration,
}

/// Points of the search grid.
pub const GRID: usize = 64;

/// θ at grid coordinate u = ln(θ − floor).
fn from_u(law: Law, u: f64) -> f64 {
    law.floor().0 + u.exp()
}

/// Fits the law to the data (module doc); `bounds` default to [`Law::default_bounds`].
pub fn fit_law(
    law: Law,
    data: &CorData,
    w: &Weights,
    bounds: Option<(f64, f64)>,
    opts: &FloatOptions,
) -> Result<LawFit, String> {
    let start = Instant::now();
    let m = data.len();
    let e_model = |theta: f64| -> Vec<Option<f64>> {
        data.v0
            .par_iter()
            .map(|&v| law.cor(theta, v, opts).ok())
            .collect()
    };
    let Some(_) = law.parameter() else {
        let j = cost(law, 0.0, data, w, opts);
        return Ok(LawFit {
            law,
            bounds: None,
            theta: None,
            j,
            e_model: e_model(0.0),
            minima: vec![],
            stats: FitStats::new(j, m, 0, w.errors_given),
            se: None,
            interval: None,
            evaluations: 1,
            elapsed: start.elapsed(),
        });
    };
    let (lo, hi) = bounds.unwrap_or(law.default_bounds());
    law.check_bounds(lo, hi)?;
    let floor = law.floor().0;
    let j_of = |theta: f64| cost(law, theta.clamp(lo, hi), data, w, opts);
    // the grid in u = ln(θ − floor), its lower end 1e−9 of the range above the floor
    let (ua, ub) = (
        ((lo - floor).max((hi - floor) * 1e-9)).ln(),
        (hi - floor).max(f64::MIN_POSITIVE).ln(),
    );
    let mut grid: Vec<f64> = (0..GRID)
        .map(|i| from_u(law, ua + (ub - ua) * i as f64 / (GRID - 1) as f64))
        .map(|t| t.clamp(lo, hi))
        .collect();
    if lo < grid[0] {
        grid.insert(0, lo);
    }
    grid.dedup();
    let js: Vec<f64> = grid.par_iter().map(|&t| j_of(t)).collect();
    let mut evaluations = grid.len();
    // every grid minimum, refined by golden section between its neighbours
    let mut found: Vec<(f64, f64)> = Vec::new();
    for i in 0..grid.len() {
        let left = i == 0 || js[i] <= js[i - 1];
        let right = i + 1 == grid.len() || js[i] <= js[i + 1];
        if !(left && right) {
            continue;
        }
        let (a, b) = (grid[i.saturating_sub(1)], grid[(i + 1).min(grid.len() - 1)]);
        let narrow = |a: f64, b: f64| (b - a).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300);
        let (t, j, n) = golden_min(j_of, a, b, (grid[i], js[i]), narrow, 200);
        evaluations += n;
        found.push((t, j));
    }
    found.sort_by(|x, y| x.1.total_cmp(&y.1));
    let mut distinct: Vec<(f64, f64)> = Vec::new();
    for (t, j) in found {
        if distinct
            .iter()
            .all(|(u, _)| (t - u).abs() > 1e-6 * t.abs().max(u.abs()).max(1e-12))
        {
            distinct.push((t, j));
        }
    }
    let (theta, j) = distinct[0];
    let stats = FitStats::new(j, m, 1, w.errors_given);
    let crit = chi2_quantile(1, 0.95);
    let near = |t: f64, b: f64| (t - b).abs() <= 1e-9 * b.abs().max(1e-300);
    let minima = distinct
        .iter()
        .map(|&(t, jm)| {
            let d = (jm * jm - j * j) / stats.s2;
            LawMinimum {
                theta: t,
                j: jm,
                delta_chi2: d,
                indistinguishable: d <= crit,
                at_bound: near(t, lo) || near(t, hi),
            }
        })
        .collect();
    // standard error by central differences of the residuals
    let h = 1e-6 * (theta - floor).abs().max(1e-9);
    let (tp, tm) = ((theta + h).min(hi), (theta - h).max(lo));
    let se = if tp > tm && stats.s2.is_finite() {
        let rp = residuals(law, tp, data, w, opts);
        let rm = residuals(law, tm, data, w, opts);
        evaluations += 2;
        let g2: f64 = rp
            .iter()
            .zip(&rm)
            .map(|(a, b)| ((a - b) / (tp - tm)).powi(2))
            .sum();
        (g2 > 0.0).then(|| (stats.s2 / g2).sqrt())
    } else {
        None
    };
    // the likelihood-ratio interval: where J² − J_min² crosses s² χ²_0.95(1)
    let level = j * j + stats.s2 * crit;
    let interval = level.is_finite().then(|| {
        let mut end = |bound: f64| -> (f64, bool) {
            if j_of(bound).powi(2) <= level {
                evaluations += 1;
                return (bound, true);
            }
            // bisection between θ̂ (inside) and the bound (outside), in u where possible
            let (mut a, mut b) = (theta, bound);
            for _ in 0..60 {
                let mid = if a - floor > 0.0 && b - floor > 0.0 {
                    floor + ((a - floor) * (b - floor)).sqrt()
                } else {
                    0.5 * (a + b)
                };
                evaluations += 1;
                if j_of(mid).powi(2) <= level {
                    a = mid;
                } else {
                    b = mid;
                }
                if (b - a).abs() <= 1e-10 * a.abs().max(b.abs()) {
                    break;
                }
            }
            (a, false)
        };
        [end(lo), end(hi)]
    });
    Ok(LawFit {
        law,
        bounds: Some((lo, hi)),
        theta: Some(theta),
        j,
        e_model: e_model(theta),
        minima,
        stats,
        se,
        interval,
        evaluations,
        elapsed: start.elapsed(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts() -> FloatOptions {
        FloatOptions::default()
    }

    #[test]
    fn constant_cor_laws_fit_the_weighted_mean() {
        // e is the same at every speed, so the best e(θ) is the mean of the data's CoRs
        let d = CorData::new(vec![0.5, 1.0, 2.0, 4.0], vec![0.62, 0.58, 0.61, 0.59]).unwrap();
        let w = Weights::unit(&d);
        for law in [Law::KelvinVoigt, Law::LinearMaxwell] {
            let f = fit_law(law, &d, &w, None, &opts()).unwrap();
            let e = f.e_model[0].unwrap();
            assert!((e - 0.6).abs() < 1e-7, "{law:?}: e {e}");
            let t = f.theta.unwrap();
            let [lo, hi] = f.interval.unwrap().map(|x| x.0);
            assert!(lo < t && t < hi, "{lo} {t} {hi}");
            assert!(f.se.unwrap() > 0.0);
        }
    }

    #[test]
    fn hunt_crossley_recovers_its_generating_damping() {
        let sb = 0.37;
        let v: Vec<f64> = (1..=12).map(|i| 0.3 * i as f64).collect();
        let e: Vec<f64> = v
            .iter()
            .map(|&v| Law::HuntCrossley.cor(sb, v, &opts()).unwrap())
            .collect();
        let d = CorData::new(v, e).unwrap();
        let f = fit_law(Law::HuntCrossley, &d, &Weights::unit(&d), None, &opts()).unwrap();
        assert!((f.theta.unwrap() - sb).abs() < 1e-7 * sb, "{:?}", f.theta);
        assert!(f.j < 1e-9, "{}", f.j);
    }

    #[test]
    fn monotonicity_claims_hold_on_samples() {
        // negative control of the claims the rigorous side relies on: the f64 engine's e moves
        // the claimed way between samples of each proved range
        for (law, pts) in [
            (Law::HuntCrossley, [0.0, 0.01, 0.3, 2.0, 30.0]),
            (Law::KelvinVoigt, [0.0, 0.4, 0.999, 1.0, 7.0]),
            (Law::LinearMaxwell, [0.51, 0.6, 2.0, 30.0, 1e3]),
        ] {
            let dir = law.monotone_from(pts[0]).unwrap();
            let es: Vec<f64> = pts
                .iter()
                .map(|&t| law.cor(t, 1.3, &opts()).unwrap())
                .collect();
            for k in 1..es.len() {
                let ok = match dir {
                    Monotone::Decreasing => es[k] < es[k - 1],
                    Monotone::Increasing => es[k] > es[k - 1],
                };
                assert!(ok, "{law:?} {pts:?} {es:?}");
            }
        }
        assert_eq!(Law::HuntCrossley.monotone_from(-1.0), None);
        assert_eq!(Law::LinearMaxwell.monotone_from(0.5), None);
    }

    #[test]
    fn bounds_outside_the_admissible_set_are_refused() {
        assert!(Law::LinearMaxwell.check_bounds(0.4, 2.0).is_err());
        assert!(Law::HuntCrossley.check_bounds(-0.1, 2.0).is_err());
        assert!(Law::KelvinVoigt.check_bounds(2.0, 1.0).is_err());
        assert!(Law::KelvinVoigt.check_bounds(0.0, f64::NAN).is_err());
    }
}
