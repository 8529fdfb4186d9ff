//! `bwcl.trajectory` and `bwcl.loop`: the trajectory up to T_s (or `t_end`) at uniform times,
//! on the float engine's dense output (nondimensional or physical units) or as enclosures of
//! the proved flow.

use super::arrays::{put_f64, put_f64_2d};
use super::cli::args::{Command, TrajectoryArgs};
use super::cli::commands::check_units;
use super::cli::input;
use super::cli::law_runs::with_law;
use super::run::{compute, parse, py_error};
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::classical::Law;
use bwcl::models::hunt_crossley::HuntCrossley;
use bwcl::models::linear_maxwell::LinearMaxwell;
use bwcl::models::scaling::Scales;
use bwcl::models::{CollisionModel, Maxwell, ModelKind, Shc};
use bwcl::observables::trajectory::{Sample, Units, trajectory as samples};
use bwcl::observables::{FloatOptions, impact};
use inari::Interval;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The float samples and, without separation before the horizon, a note saying so.
type FloatCurve = (Vec<Sample>, Option<String>);

/// Samples up to `t_end`, or T_s (the horizon without separation), as the CLI's `trajectory`.
fn float_curve<M: CollisionModel<f64, N>, const N: usize>(
    model: &M,
    opts: &FloatOptions,
    t_end: Option<f64>,
    points: usize,
    units: &Units,
) -> Result<FloatCurve, String> {
    let mut note = None;
    let end = match t_end {
        Some(t) => t,
        None => match impact(model, opts).map_err(|e| e.to_string())?.ts {
            Some(ts) => ts,
            None => {
                note = Some(format!(
                    "no separation before the horizon T = {}; the samples end there",
                    opts.horizon
                ));
                opts.horizon
            }
        },
    };
    let s = samples(model, opts, Some(end), points, units).map_err(|e| e.to_string())?;
    Ok((s, note))
}

/// The proved flow's enclosures at uniform times up to `t_end` or the upper bound of T_s:
/// (t, columns), each column the bounds of the states, x, v, F.
type RigorousCurve = (Vec<f64>, Vec<Vec<[f64; 2]>>);

fn rigorous_curve<M: CollisionModel<Interval, N>, const N: usize>(
    model: &M,
    opts: &TaylorOptions,
    t_end: Option<f64>,
    points: usize,
) -> Result<RigorousCurve, String> {
    let (flow, end, _) =
        bwcl::observables::rigorous::curve_flow(model, opts, t_end).map_err(|e| e.to_string())?;
    let mut ts = Vec::with_capacity(points);
    let mut cols = Vec::with_capacity(points);
    for t in bwcl::observables::trajectory::sample_times(end, points) {
        let s = flow
            .enclose(t)
            .ok_or_else(|| format!("the proved flow has no enclosure at T = {t}"))?;
        let (x, v, f) = (model.position(&s), model.velocity(&s), model.force(&s));
        ts.push(t);
        cols.push(
            s.iter()
                .copied()
                .chain([x, v, f])
                .map(|c| [c.inf(), c.sup()])
                .collect(),
        );
    }
    Ok((ts, cols))
}

/// The `trajectory` (or `loop`) arguments of `argv`.
fn curve_args(argv: &[String]) -> PyResult<TrajectoryArgs> {
    match parse(argv)?.command {
        Command::Trajectory(a) | Command::Loop(a) => Ok(a),
        _ => Err(PyValueError::new_err("not a trajectory command")),
    }
}

/// The trajectory (see `bwcl.trajectory`): a dict of NumPy arrays.
#[pyfunction]
#[pyo3(signature = (argv, threads=None))]
pub fn trajectory<'py>(
    py: Python<'py>,
    argv: Vec<String>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let a = curve_args(&argv)?;
    check_units(&a).map_err(py_error)?;
    let law = a.params.model.law();
    let kind = a.params.model.kind();
    let (points, t_end) = (a.points, a.t_end);
    let names: Vec<&str> = match (law, kind) {
        (Some(Law::LinearMaxwell), _) => {
            <LinearMaxwell<f64> as CollisionModel<f64, 3>>::STATE_NAMES.to_vec()
        }
        (Some(_), _) => <HuntCrossley<f64> as CollisionModel<f64, 2>>::STATE_NAMES.to_vec(),
        (_, Some(ModelKind::Maxwell)) => {
            <Maxwell<f64> as CollisionModel<f64, 4>>::STATE_NAMES.to_vec()
        }
        _ => <Shc<f64> as CollisionModel<f64, 3>>::STATE_NAMES.to_vec(),
    };
    let n = names.len();
    let d = PyDict::new(py);
    d.set_item("model", a.params.model.key())?;
    d.set_item("state_names", names)?;
    d.set_item("rigorous", a.engine.rigorous)?;
    let failed = |e: String| PyRuntimeError::new_err(e);
    if a.engine.rigorous {
        let opts = input::taylor_options(&a.engine).map_err(py_error)?;
        let (ts, cols) = match (law, kind) {
            (Some(law), _) => {
                let case = input::single_law_case::<Interval>(&a.params, law).map_err(py_error)?;
                let model = case.nd.model().map_err(failed)?;
                compute(py, threads, || {
                    with_law!(&model, |m| rigorous_curve(m, &opts, t_end, points))
                })?
            }
            (_, kind) => {
                let case = input::single_case::<Interval>(&a.params).map_err(py_error)?;
                compute(py, threads, || match kind {
                    Some(ModelKind::Maxwell) => {
                        rigorous_curve(&Maxwell::new(case.params), &opts, t_end, points)
                    }
                    _ => rigorous_curve(&Shc::new(case.params), &opts, t_end, points),
                })?
            }
        }
        .map_err(failed)?;
        put_f64(&d, "t", ts)?;
        let col = |j: usize| -> Vec<f64> { cols.iter().flat_map(|r| r[j]).collect() };
        let states: Vec<f64> = cols
            .iter()
            .flat_map(|r| r[..n].iter().flatten().copied())
            .collect();
        put_f64_2d(&d, "states", states, 2 * n)?;
        put_f64_2d(&d, "x", col(n), 2)?;
        put_f64_2d(&d, "v", col(n + 1), 2)?;
        put_f64_2d(&d, "F", col(n + 2), 2)?;
        d.set_item("units", "nondimensional")?;
        d.set_item("note", None::<String>)?;
    } else {
        let opts = input::float_options(&a.engine).map_err(py_error)?;
        let unit = |scales: &Option<Scales<f64>>| match (scales, a.physical_units) {
            (Some(s), true) => Units::Physical(s.clone()),
            _ => Units::Nondimensional,
        };
        let (units, curve) = match (law, kind) {
            (Some(law), _) => {
                let case = input::single_law_case::<f64>(&a.params, law).map_err(py_error)?;
                let units = unit(&case.scales);
                let model = case.nd.model().map_err(failed)?;
                let c = compute(py, threads, || {
                    with_law!(&model, |m| float_curve(m, &opts, t_end, points, &units))
                })?;
                (units, c)
            }
            (_, kind) => {
                let case = input::single_case::<f64>(&a.params).map_err(py_error)?;
                let units = unit(&case.scales);
                let c = compute(py, threads, || match kind {
                    Some(ModelKind::Maxwell) => {
                        float_curve(&Maxwell::new(case.params), &opts, t_end, points, &units)
                    }
                    _ => float_curve(&Shc::new(case.params), &opts, t_end, points, &units),
                })?;
                (units, c)
            }
        };
        let (s, note) = curve.map_err(failed)?;
        put_f64(&d, "t", s.iter().map(|x| x.t).collect())?;
        put_f64_2d(
            &d,
            "states",
            s.iter().flat_map(|x| x.state.iter().copied()).collect(),
            n,
        )?;
        put_f64(&d, "x", s.iter().map(|x| x.x).collect())?;
        put_f64(&d, "v", s.iter().map(|x| x.v).collect())?;
        put_f64(&d, "F", s.iter().map(|x| x.force).collect())?;
        let physical = matches!(units, Units::Physical(_));
        d.set_item(
            "units",
            if physical {
                "physical"
            } else {
                "nondimensional"
            },
        )?;
        d.set_item("note", note)?;
    }
    Ok(d)
}
