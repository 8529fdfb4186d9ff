//! Trajectories and hysteresis loops on the f64 engine, nondimensional or physical.
//!
//! A trajectory is sampled on the dense output at a uniform grid in T (plus the step ends are
//! not needed: the dense output is 7th order) up to T_s (or a given end time). A loop is the
//! curve (X, F_P) of the same samples. [`Units::Physical`] converts with the scales of
//! [`crate::models::scaling`]: t = T·T_c, x = X·X_c, v = V·X_c/T_c, force = F_P·m X_c/T_c².

use super::separation::{FloatOptions, ImpactError, impact};
use crate::engines::dop853::Dop853;
use crate::models::CollisionModel;
use crate::models::scaling::Scales;

/// One sample of a trajectory.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Sample {
    pub t: f64,
    /// The model's states (nondimensional even in physical output: they are internal).
    pub state: Vec<f64>,
    pub x: f64,
    pub v: f64,
    pub force: f64,
}

/// Nondimensional, or physical (SI) by the given scales.
#[derive(Clone, Debug)]
pub enum Units {
    Nondimensional,
    Physical(Scales<f64>),
}

impl Units {
    fn apply(&self, mut s: Sample) -> Sample {
        if let Units::Physical(sc) = self {
            s.t *= sc.t_c;
            s.x *= sc.x_c;
            s.v *= sc.v_c;
            s.force *= sc.f_c;
        }
        s
    }
}

/// `points` (at least 2) uniform times on [0, end], the last exactly `end`: end·i/(points − 1)
/// may round past it (a sample past the integration's end was lost) or short of it; for
/// i < points − 1 it stays below `end` (i/(points − 1) ≤ 1 − 1/(points − 1)).
pub fn sample_times(end: f64, points: usize) -> Vec<f64> {
    let last = points.max(2) - 1;
    (0..=last)
        .map(|i| {
            if i == last {
                end
            } else {
                end * i as f64 / last as f64
            }
        })
        .collect()
}

/// Samples the trajectory at `points` uniform times on [0, T_end], T_end = `t_end` or, when
/// `None`, T_s (the horizon if there is no separation). The last sample is at T_end.
pub fn trajectory<M: CollisionModel<f64, N>, const N: usize>(
    model: &M,
    opts: &FloatOptions,
    t_end: Option<f64>,
    points: usize,
    units: &Units,
) -> Result<Vec<Sample>, ImpactError> {
    let end = match t_end {
        Some(t) if t.is_finite() && t > 0.0 => t,
        Some(t) => return Err(ImpactError::BadHorizon(t)),
        None => impact(model, opts)?.ts.unwrap_or(opts.horizon),
    };
    let grid = sample_times(end, points);
    let mut out = Vec::with_capacity(points);
    let sample = |t: f64, y: &[f64; N]| Sample {
        t,
        state: y.to_vec(),
        x: model.position(y),
        v: model.velocity(y),
        force: model.force(y),
    };
    let y0 = model.initial_state();
    out.push(units.apply(sample(0.0, &y0)));
    let mut solver = Dop853::new(
        |_t, y: &[f64; N]| model.field(y),
        0.0,
        y0,
        end,
        opts.ode.clone(),
    )?;
    let mut next = 1;
    while next < grid.len() && solver.step()? {
        let dense = solver.dense_output();
        while next < grid.len() && grid[next] <= dense.t_new() {
            let t = grid[next];
            let y = if next == grid.len() - 1 {
                *solver.y()
            } else {
                dense.eval(t)
            };
            out.push(units.apply(sample(t, &y)));
            next += 1;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::{Admissibility, ModelKind, NdParams, Shc};

    #[test]
    fn harmonic_case_samples_the_closed_form() {
        let p = NdParams::with_admissibility(
            ModelKind::Shc,
            Admissibility::Closed,
            0.0,
            0.0,
            0.5,
            0.0,
            1.0,
            1.0,
        )
        .unwrap();
        let tr = trajectory(
            &Shc::new(p),
            &FloatOptions::default(),
            None,
            101,
            &Units::Nondimensional,
        )
        .unwrap();
        assert_eq!(tr.len(), 101);
        for s in &tr {
            // X = −sin T, V = −cos T, F = sin T
            assert!(
                (s.x + s.t.sin()).abs() < 1e-9
                    && (s.v + s.t.cos()).abs() < 1e-9
                    && (s.force - s.t.sin()).abs() < 1e-9,
                "{s:?}"
            );
        }
        assert!((tr.last().unwrap().t - std::f64::consts::PI).abs() < 1e-9);
    }

    #[test]
    fn the_last_sample_time_is_the_end() {
        // 2.956075324749551·49/49 rounds past the end (the Kelvin–Voigt T_s at ζ = 0.1)
        let end = 2.956075324749551;
        assert!(end * 49.0 / 49.0 > end);
        let g = sample_times(end, 50);
        assert_eq!((g.len(), g[0], g[49]), (50, 0.0, end));
        assert!(g.windows(2).all(|w| w[0] < w[1]));
        // and one where it rounds below the end
        let end = 1.4302060167127721;
        assert!(end * 49.0 / 49.0 < end);
        assert_eq!(sample_times(end, 50)[49], end);
    }
}
