//! Turning --base / --nd / --physical (+ --v0) and the engine options into validated cases.
//!
//! Everything is generic over the arithmetic: `f64` for the float engine, `Interval` for the
//! rigorous one (decimals enclosed as written, ranges a..b allowed).

use super::CliError;
use super::args::{EngineArgs, ParamArgs};
use super::output::num;
use bwcl::arith::Real;
use bwcl::engines::dop853::Options;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::params::show;
use bwcl::models::scaling::{PhysicalParams, Scales, nd_from_base, parse_speeds};
use bwcl::models::{ModelKind, NdParams, ParamError};
use bwcl::observables::FloatOptions;
use std::path::Path;

/// One collision to compute: its impact speed (none for --nd), its nondimensional parameters,
/// and for --physical the scales at that speed.
#[derive(Clone, Debug)]
pub struct Case<R> {
    pub v0: Option<R>,
    pub params: NdParams<R>,
    pub scales: Option<Scales<R>>,
    /// The base set P* (with --base, or of the --physical set): a range of v0 is proved by
    /// sub-ranges through it.
    pub base: Option<NdParams<R>>,
}

/// The validated cases of the parameter options, in the order of --v0.
pub fn cases<R: Real>(p: &ParamArgs) -> Result<Vec<Case<R>>, CliError> {
    let kind = ModelKind::from(p.model);
    if let Some(text) = &p.nd {
        let params = NdParams::<R>::parse(kind, text).map_err(|e| bad("--nd", e))?;
        return Ok(vec![Case {
            v0: None,
            params,
            scales: None,
            base: None,
        }]);
    }
    // clap guarantees one of --base / --physical, and --v0 with them.
    let Some(v0_text) = &p.v0 else {
        return Err(CliError::Input(
            "--v0 is required with --base and --physical".into(),
        ));
    };
    if let Some(text) = &p.base {
        let base = NdParams::<R>::parse(kind, text).map_err(|e| bad("--base", e))?;
        let speeds = speeds::<R>(v0_text)?;
        speeds
            .into_iter()
            .map(|v0| {
                let params = nd_from_base(kind, &base, &v0).map_err(|e| {
                    CliError::Input(format!("--base mapped to v0 = {}: {e}", show(&v0)))
                })?;
                Ok(Case {
                    v0: Some(v0),
                    params,
                    scales: None,
                    base: Some(base.clone()),
                })
            })
            .collect()
    } else if let Some(text) = &p.physical {
        let phys = PhysicalParams::<R>::parse(kind, text).map_err(|e| bad("--physical", e))?;
        let speeds = speeds::<R>(v0_text)?;
        speeds
            .into_iter()
            .map(|v0| {
                let params = nondimensionalize(kind, &phys, &v0).map_err(|e| {
                    CliError::Input(format!(
                        "--physical at v0 = {}: the nondimensional set is outside 𝓟: {e}",
                        show(&v0)
                    ))
                })?;
                let scales = phys.scales(&v0);
                Ok(Case {
                    v0: Some(v0),
                    params,
                    scales: Some(scales),
                    base: phys.base(kind).ok(),
                })
            })
            .collect()
    } else {
        Err(CliError::Input(
            "give exactly one of --base, --nd, --physical".into(),
        ))
    }
}

/// The nondimensional set of physical parameters at v0; for a range of speeds through the
/// base set: P = 𝓟(P*, v0) holds for every v0, and the map keeps 𝓟 (the direct formulas would
/// compare the enclosures of Γ and B as if independent).
fn nondimensionalize<R: Real>(
    kind: ModelKind,
    phys: &PhysicalParams<R>,
    v0: &R,
) -> Result<NdParams<R>, ParamError> {
    if v0.lo() < v0.hi() {
        nd_from_base(kind, &phys.base(kind)?, v0)
    } else {
        phys.nondimensionalize(kind, v0)
    }
}

/// The impact speeds of --v0.
fn speeds<R: Real>(text: &str) -> Result<Vec<R>, CliError> {
    parse_speeds::<R>(text).map_err(|e| {
        let hint = if e.0.contains("needs the rigorous engine") {
            " (add --rigorous)"
        } else {
            ""
        };
        CliError::Input(format!("--v0 '{text}': {e}{hint}"))
    })
}

/// A parameter error of option `opt`, with a hint when a range was given without --rigorous.
fn bad(opt: &str, e: ParamError) -> CliError {
    let hint = if e.0.contains("needs the rigorous engine") {
        " (add --rigorous)"
    } else {
        ""
    };
    CliError::Input(format!("{opt}: {e}{hint}"))
}

/// The single case of trajectory/loop: exactly one impact speed.
pub fn single_case<R: Real>(p: &ParamArgs) -> Result<Case<R>, CliError> {
    let mut all = cases::<R>(p)?;
    if all.len() != 1 {
        return Err(CliError::Input(format!(
            "--v0 '{}': this command takes exactly one impact speed, got {}",
            p.v0.as_deref().unwrap_or(""),
            all.len()
        )));
    }
    Ok(all.remove(0))
}

/// The horizon: finite and > 0.
fn horizon(e: &EngineArgs) -> Result<f64, CliError> {
    if e.horizon.is_finite() && e.horizon > 0.0 {
        Ok(e.horizon)
    } else {
        Err(CliError::Input(format!(
            "--horizon {} must be a finite number > 0",
            num(e.horizon)
        )))
    }
}

/// DOP853 settings: the paper's, with the given overrides, validated.
pub fn float_options(e: &EngineArgs) -> Result<FloatOptions, CliError> {
    let mut ode = Options::paper();
    if let Some(r) = e.rtol {
        if !(100.0 * f64::EPSILON..1.0).contains(&r) {
            return Err(CliError::Input(format!(
                "--rtol {} must be a finite number in [100 ε, 1) = [{:e}, 1)",
                num(r),
                100.0 * f64::EPSILON
            )));
        }
        ode.rtol = r;
    }
    if let Some(a) = e.atol {
        if !(a.is_finite() && a >= 0.0) {
            return Err(CliError::Input(format!(
                "--atol {} must be a finite number ≥ 0",
                num(a)
            )));
        }
        ode.atol = a;
    }
    if let Some(h) = e.max_step {
        if h.is_nan() || h <= 0.0 {
            return Err(CliError::Input(format!(
                "--max-step {} must be > 0",
                num(h)
            )));
        }
        ode.max_step = h;
    }
    Ok(FloatOptions {
        ode,
        horizon: horizon(e)?,
    })
}

/// Rigorous-engine settings: the engine's defaults with --order and --horizon.
pub fn taylor_options(e: &EngineArgs) -> Result<TaylorOptions, CliError> {
    if e.order == 0 {
        return Err(CliError::Input("--order 0 must be ≥ 1".into()));
    }
    Ok(TaylorOptions {
        horizon: horizon(e)?,
        order: e.order,
        ..TaylorOptions::default()
    })
}

/// --points: at least 2.
pub fn points(n: usize) -> Result<usize, CliError> {
    if n >= 2 {
        Ok(n)
    } else {
        Err(CliError::Input(format!("--points {n} must be ≥ 2")))
    }
}

/// --t-end: finite and > 0 when given.
pub fn t_end(t: Option<f64>) -> Result<Option<f64>, CliError> {
    match t {
        Some(t) if !(t.is_finite() && t > 0.0) => Err(CliError::Input(format!(
            "--t-end {} must be a finite number > 0",
            num(t)
        ))),
        t => Ok(t),
    }
}

/// --out: its directory must exist (checked before any computation).
pub fn out_path(out: Option<&Path>) -> Result<(), CliError> {
    let Some(path) = out else { return Ok(()) };
    if path.as_os_str().is_empty() || path.is_dir() {
        return Err(CliError::Input(format!(
            "--out '{}' is not a file name",
            path.display()
        )));
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(CliError::Input(format!(
            "--out '{}': the directory '{}' does not exist",
            path.display(),
            dir.display()
        )));
    }
    Ok(())
}
