//! Fig. 4 (fig:RCross) and Table 2 (tab:RCross): the BWSHCCM hysteresis loops of a baseball on
//! a flat surface, in physical units (F in N against |x| in mm), with each loop's numbers.

use bwcl::models::scaling::PhysicalParams;
use bwcl::models::{ModelKind, Shc};
use bwcl::observables::trajectory::{Units, trajectory};
use bwcl::observables::{FloatOptions, impact};

/// Table 2 as `PhysicalParams::parse` reads it.
pub const BASEBALL: &str =
    "m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925";

/// The impact speeds of Fig. 4 [m/s].
pub const SPEEDS: [f64; 4] = [2.15, 3.03, 4.18, 5.02];

/// One simulated loop and its numbers.
pub struct Loop {
    pub v0: f64,
    /// (|x| \[mm\], F \[N\]) samples from contact to separation.
    pub points: Vec<(f64, f64)>,
    /// T_s·T_c \[s\].
    pub duration: f64,
    pub peak_force: f64,
    /// max |x| \[mm\].
    pub max_compression: f64,
    /// |x| at separation \[mm\].
    pub residual: f64,
    pub e: f64,
    /// T_c \[s\], X_c \[m\].
    pub t_c: f64,
    pub x_c: f64,
}

pub fn simulate(v0: f64, samples: usize) -> Result<Loop, String> {
    let phys = PhysicalParams::<f64>::parse(ModelKind::Shc, BASEBALL).map_err(|e| e.to_string())?;
    let nd = phys
        .nondimensionalize(ModelKind::Shc, &v0)
        .map_err(|e| e.to_string())?;
    let scales = phys.scales(&v0);
    let model = Shc::new(nd);
    // the paper's settings; its max step ≈ T_c/100 s is 0.01 nondimensional, the default
    let opts = FloatOptions::default();
    let imp = impact(&model, &opts).map_err(|e| e.to_string())?;
    let ts = imp
        .ts
        .ok_or_else(|| format!("v0 = {v0}: no separation before the horizon"))?;
    let tr = trajectory(
        &model,
        &opts,
        Some(ts),
        samples,
        &Units::Physical(scales.clone()),
    )
    .map_err(|e| e.to_string())?;
    let points: Vec<(f64, f64)> = tr.iter().map(|s| (s.x.abs() * 1e3, s.force)).collect();
    let peak_force = points.iter().map(|p| p.1).fold(f64::MIN, f64::max);
    let max_compression = points.iter().map(|p| p.0).fold(0.0, f64::max);
    // the state at T_s from the event location (the last sample is the same time)
    use bwcl::models::CollisionModel;
    let residual = model.position(&imp.state).abs() * scales.x_c * 1e3;
    Ok(Loop {
        v0,
        points,
        duration: ts * scales.t_c,
        peak_force,
        max_compression,
        residual,
        e: imp.e,
        t_c: scales.t_c,
        x_c: scales.x_c,
    })
}
