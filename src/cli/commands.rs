//! The subcommands: `cor`, `trajectory` and `loop`, each on the float or the rigorous engine.
//!
//! Everything is validated and computed before anything is written; `cor` reports a case that
//! could not be proved (or integrated) in its row and exits with 1, the other cases still
//! printed.

use super::args::{Cli, Command, CorArgs, TrajectoryArgs};
use super::input::{self, Case};
use super::output::{
    self, DerivedOut, FloatRow, JsonPair, ParamsOut, RigorousRow, RowParams, bounds, num, width,
};
use super::{CliError, EXIT_FAILED, EXIT_OK, note};
use bwcl::engines::taylor::RigorError;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::scaling::Scales;
use bwcl::models::{CollisionModel, Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::derived;
use bwcl::observables::precision::{self, FallbackBudget, outward_f64};
use bwcl::observables::rigorous::{Enclosure, rigorous_impact};
use bwcl::observables::trajectory::{Units, trajectory};
use bwcl::observables::{FloatOptions, impact};
use bwcl::observables::{sets, split};
use inari::Interval;
use rayon::prelude::*;

/// Runs `$body` with `$m` bound to the model of `$kind` built from `$params` (the two models
/// have different state counts, so each arm is its own monomorphization).
macro_rules! with_model {
    ($kind:expr, $params:expr, |$m:ident| $body:expr) => {
        match $kind {
            ModelKind::Shc => {
                let $m = Shc::new($params);
                $body
            }
            ModelKind::Maxwell => {
                let $m = Maxwell::new($params);
                $body
            }
        }
    };
}

/// Runs the parsed command; `Ok` carries the exit code (0, or 1 when a case failed).
pub fn run(cli: Cli) -> Result<i32, CliError> {
    match cli.command {
        Command::Cor(a) => cor(&a),
        Command::Trajectory(a) => curve(&a, Curve::Trajectory),
        Command::Loop(a) => curve(&a, Curve::Loop),
        Command::Fit(a) => super::fit::fit(&a),
        Command::Cost(a) => super::fit::cost(&a),
        Command::Identify(a) => super::identify::identify(&a),
        Command::Profile(a) => super::profile::profile(&a),
        Command::Laws(a) => super::laws::laws(&a),
        Command::Classical(a) => super::classical::classical(&a),
        Command::Compare(a) => super::compare::compare(&a),
        Command::Prove(p) => match p.what {
            super::args::ProveCommand::Monotone(m) => super::band::monotone(&m),
        },
    }
}

fn cor(a: &CorArgs) -> Result<i32, CliError> {
    if a.derived && (a.digits.is_some() || a.band.is_some()) {
        let with = if a.band.is_some() {
            "--band"
        } else {
            "--digits"
        };
        return Err(CliError::Input(format!(
            "--derived is not offered with {with} (the derived outputs come from the f64 engines' runs of point cases)"
        )));
    }
    if let Some(d) = a.digits {
        input::bouc_wen_only(a.params.model, "--digits")?;
        if !a.engine.rigorous {
            return Err(CliError::Input(format!(
                "--digits {d} is an option of the rigorous engine: add --rigorous"
            )));
        }
        if a.band.is_some() {
            return Err(CliError::Input(
                "--digits is not supported with --band".into(),
            ));
        }
        return super::precise::cor(a, d);
    }
    if let Some(path) = &a.band {
        return super::band::band(a, path);
    }
    input::out_path(a.out.as_deref())?;
    let mut notes: Vec<String> = Vec::new();
    let (bytes, failed, total, elapsed) = if let Some(law) = a.params.model.law() {
        let (bytes, failed, total, elapsed, law_notes) = super::law_runs::cor(a, law)?;
        notes = law_notes;
        (bytes, failed, total, elapsed)
    } else if a.engine.rigorous {
        let kind = input::bouc_wen_only(a.params.model, "cor")?;
        let opts = input::taylor_options(&a.engine)?;
        let fallback = input::fallback(a.fallback_bits, a.fallback_seconds);
        let cases = input::cases::<Interval>(&a.params)?;
        let (rows, elapsed) = prove_rows(&cases, a.engine.time_limit, |c| {
            rigorous_row(
                kind,
                c,
                &opts,
                input::pieces(&a.engine),
                a.sensitivities,
                a.derived,
                &fallback,
                a.engine.time_limit,
            )
        });
        let failed = rows.iter().filter(|r| !r.proved).count();
        // how each range was split and how tight its hull is (in the JSON output as "range")
        if a.format == super::args::Format::Table {
            notes = rows
                .iter()
                .filter_map(|r| {
                    let g = r.range.as_ref()?;
                    let v0 = r.v0.map_or(String::new(), |[l, h]| {
                        let [a, b] = output::inner_pair(l, h);
                        format!(" for v0 in [{a}, {b}]")
                    });
                    Some(format!("bwcl: note{v0}: {}", g.note))
                })
                .collect();
        }
        (
            output::rigorous_cor(&rows, a.format)?,
            failed,
            rows.len(),
            elapsed,
        )
    } else {
        let kind = input::bouc_wen_only(a.params.model, "cor")?;
        let opts = input::float_options(&a.engine)?;
        let cases = input::cases::<f64>(&a.params)?;
        let start = std::time::Instant::now();
        let rows: Vec<FloatRow> = cases
            .par_iter()
            .map(|c| float_row(kind, c, &opts, a.derived))
            .collect();
        let elapsed = start.elapsed();
        let failed = rows.iter().filter(|r| r.error.is_some()).count();
        notes = resolution_notes(&rows, opts.ode.atol);
        (
            output::float_cor(&rows, a.format)?,
            failed,
            rows.len(),
            elapsed,
        )
    };
    // notes only after the output is written: an error must stay the one stderr line
    let timing = || {
        for n in &notes {
            note(n);
        }
        if a.timing {
            let s = elapsed.as_secs_f64();
            note(&format!(
                "bwcl: timing: {total} case(s) in {s:.6} s, {:.3} µs per case ({} thread(s))",
                s / total.max(1) as f64 * 1e6,
                rayon::current_num_threads()
            ));
        }
    };
    if failed == 0 {
        output::emit(a.out.as_deref(), &bytes)?;
        timing();
        return Ok(EXIT_OK);
    }
    // --out is replaced only when everything succeeded: the rows (with the reasons) go to
    // stdout instead
    output::emit(None, &bytes)?;
    timing();
    let what = if a.engine.rigorous {
        "not proved"
    } else {
        "not integrated"
    };
    let kept = output::out_kept(a.out.as_deref());
    note(&format!(
        "bwcl: {failed} of {total} case(s) {what} (the reason is in the output){kept}"
    ));
    Ok(EXIT_FAILED)
}

/// The rigorous rows of `cor`'s cases, in parallel, with a progress bar on a terminal (the
/// budget `time_limit` shown): the rows and the time they took.
pub fn prove_rows<C: Sync>(
    cases: &[C],
    time_limit: Option<f64>,
    row: impl Fn(&C) -> RigorousRow + Sync + Send,
) -> (Vec<RigorousRow>, std::time::Duration) {
    let start = std::time::Instant::now();
    let bar = super::progress::Progress::cases(
        "cor --rigorous",
        cases.len(),
        input::time_limit(time_limit),
    );
    let rows = cases
        .par_iter()
        .map(|c| {
            let r = row(c);
            bar.inc();
            r
        })
        .collect();
    bar.finish();
    (rows, start.elapsed())
}

/// The six parameters of a set for the JSON output (also used by `fit`).
pub fn params_f64(p: &NdParams<f64>) -> ParamsOut<f64> {
    ParamsOut {
        b: p.b,
        gamma: p.gamma,
        kappa: p.kappa,
        sigma: p.sigma,
        n: p.n,
        p: p.p,
    }
}

fn params_interval(p: &NdParams<Interval>) -> ParamsOut<[f64; 2]> {
    ParamsOut {
        b: bounds(p.b),
        gamma: bounds(p.gamma),
        kappa: bounds(p.kappa),
        sigma: bounds(p.sigma),
        n: bounds(p.n),
        p: bounds(p.p),
    }
}

/// T_s and e of one case on the float engine (and with `derived`, F_max, δ_max, ΔE).
pub fn float_row(kind: ModelKind, c: &Case<f64>, opts: &FloatOptions, derived: bool) -> FloatRow {
    let mut out = None;
    let res = with_model!(kind, c.params.clone(), |m| impact(&m, opts).map(|r| {
        if derived {
            out = Some(float_derived(&m, opts, r.ts, r.e, c.scales.as_ref()));
        }
        (r.ts, r.e, r.stats)
    }));
    let t_c = c.scales.as_ref().map(|s| s.t_c);
    let mut row = FloatRow::new(
        kind.name(),
        c.v0,
        t_c,
        opts.horizon,
        RowParams::BoucWen(params_f64(&c.params)),
    );
    settle_float(&mut row, res);
    row.derived = out;
    row
}

/// The derived outputs of a float run (T_s = `ts`, e = `e`), in SI too with `scales`.
pub fn float_derived<M: CollisionModel<f64, N>, const N: usize>(
    m: &M,
    opts: &FloatOptions,
    ts: Option<f64>,
    e: f64,
    scales: Option<&Scales<f64>>,
) -> DerivedOut<f64> {
    let Some(ts) = ts else {
        return DerivedOut::not("no separation before the horizon");
    };
    match derived::derived_float(m, opts, ts, e) {
        Ok(d) => DerivedOut::of(&d, scales.map(|s| d.in_si(s)).as_ref(), |x| *x),
        Err(err) => DerivedOut::not(err.to_string()),
    }
}

/// The derived outputs of a proved run, enclosed on its flow, in SI too with `scales`.
pub fn proved_derived<M: CollisionModel<Interval, N>, const N: usize>(
    m: &M,
    enc: &Enclosure<N>,
    scales: Option<&Scales<Interval>>,
) -> DerivedOut<JsonPair> {
    match derived::derived_rigorous(m, enc, &derived::PeakOptions::default()) {
        Ok(d) => DerivedOut::of(&d, scales.map(|s| d.in_si(s)).as_ref(), |x| {
            JsonPair(bounds(*x))
        }),
        Err(why) => DerivedOut::not(why),
    }
}

/// Why a proved row has no derived outputs: a range, the precision fallback, no separation.
pub fn derived_missing(row: &mut RigorousRow, ranged: bool) {
    if row.derived.is_some() || !row.proved {
        return;
    }
    row.derived = Some(DerivedOut::not(if !row.separated {
        "no separation before the horizon"
    } else if ranged {
        "computed for point cases only, not over a range of inputs"
    } else {
        "computed on the f64-interval engine only, not by the precision fallback"
    }));
}

/// Notes for the float rows whose separation lies at the integrator's resolution: e = V(T_s)
/// below the absolute tolerance, so that V and F are 0 to what the run resolves and rounding
/// may have met the condition F ≤ 0 ∧ V ≥ 0 (the linear Maxwell law with c̃ = 1/2 + 2⁻⁵³
/// "separated" at T ≈ 39 with e ≈ 1e-14; its T_s is π/ω ≈ 1.5e8).
/// At most five such lines, then one that counts the rest.
pub fn resolution_notes(rows: &[FloatRow], atol: f64) -> Vec<String> {
    let low: Vec<&FloatRow> = rows
        .iter()
        .filter(|r| r.separated && r.e.is_some_and(|e| e.abs() < atol))
        .collect();
    let mut out: Vec<String> = low
        .iter()
        .take(MAX_NOTES)
        .map(|r| resolution_note(r.v0, r.e.unwrap_or(0.0), r.ts, atol))
        .collect();
    if low.len() > MAX_NOTES {
        out.push(format!(
            "bwcl: note: {} more case(s) with e below the absolute tolerance",
            low.len() - MAX_NOTES
        ));
    }
    out
}

/// The note of [`resolution_notes`] for one case (`v0` when the case has one).
pub fn resolution_note(v0: Option<f64>, e: f64, ts: Option<f64>, atol: f64) -> String {
    let v0 = v0.map_or(String::new(), |v| format!(" (v0 = {})", num(v)));
    format!(
        "bwcl: note{v0}: e = {} is below the absolute tolerance {} of the float run: the separation at T = {} lies at its rounding level and may not be real (--rigorous proves or refutes it)",
        num(e),
        num(atol),
        ts.map_or("-".into(), num)
    )
}

/// The most notes of one kind written for a run's cases.
const MAX_NOTES: usize = 5;

/// A float row's result: T_s (in seconds too when the row has the time scale) and e, or why
/// the integration failed.
pub fn settle_float(
    row: &mut FloatRow,
    res: Result<(Option<f64>, f64, bwcl::engines::dop853::Stats), bwcl::observables::ImpactError>,
) {
    match res {
        Ok((ts, e, stats)) => {
            row.separated = ts.is_some();
            row.ts = ts;
            row.e = Some(e);
            row.ts_seconds = row.t_c.map(|tc| ts.map(|t| t * tc));
            row.nfev = stats.nfev;
            row.steps = stats.naccepted;
        }
        Err(err) => row.error = Some(err.to_string()),
    }
}

/// What a case without separation before the horizon proved: the condition fails on [0, H] for
/// the double H, so its decimal is rounded down (2.9 is the double 2.89999999999999991…:
/// "T_s > 2.9" would claim (H, 2.9] too).
/// With `never` (the model's closed form, [`bwcl::engines::taylor::RigorError::never_separates`])
/// the case never separates at all: T_s = +∞.
pub fn no_separation_text(horizon: f64, never: Option<&str>) -> String {
    if let Some(why) = never {
        return format!(
            "proved: the law never separates ({why}; closed form): T_s = +∞, e = 0 by the paper's convention"
        );
    }
    format!(
        "proved: no separation before the horizon T = {h} (T_s > {h}; e = 0 if it never separates, the paper's convention for T_s = +∞)",
        h = output::outward(horizon, bwcl::observables::decimal::Rounding::Down)
    )
}

/// Enclosures of T_s and e of one case on the rigorous engine (`time_limit`: the
/// --time-limit given, named when the run stops at `opts.deadline`).
#[allow(clippy::too_many_arguments)]
pub fn rigorous_row(
    kind: ModelKind,
    c: &Case<Interval>,
    opts: &TaylorOptions,
    pieces: usize,
    sensitivities: bool,
    derived: bool,
    fallback: &FallbackBudget,
    time_limit: Option<f64>,
) -> RigorousRow {
    let mut out = None;
    // inputs given as ranges (wider than the enclosure of a decimal): proved over the whole
    // set, with the solution's dependence on them carried by the engine
    let ranged = c.inputs.values().iter().any(sets::is_range);
    let mut range = None;
    let res = if ranged {
        let split = split::SplitOptions {
            max_pieces: pieces,
            ..Default::default()
        };
        split::prove_over_set_adaptive(kind, &c.inputs, opts, &split).map(|r| {
            range = Some(output::RangeOut {
                pieces: r.pieces,
                stop: match r.stop {
                    split::Stop::Tight => "tight",
                    split::Stop::Pieces => "pieces",
                    split::Stop::Time => "time",
                    split::Stop::Unsplittable => "unsplittable",
                },
                e_inner: r.e_inner,
                ts_inner: r.ts_inner,
                e_ratio: r.e_ratio(),
                ts_ratio: r.ts_ratio(),
                note: r.summary(),
            });
            (r.ts, r.e)
        })
    } else {
        with_model!(kind, c.params.clone(), |m| rigorous_impact(&m, opts).map(
            |enc| {
                if derived {
                    out = Some(proved_derived(&m, &enc, c.scales.as_ref()));
                }
                (enc.ts, enc.e)
            }
        ))
    };
    let mut row = RigorousRow {
        range,
        ..RigorousRow::new(
            kind.name(),
            c.v0.map(bounds),
            c.scales.is_some(),
            opts.horizon,
            opts.order,
            RowParams::BoucWen(params_interval(&c.params)),
        )
    };
    // not decided at f64: the precision fallback (point cases given as text)
    let res = match (res, &c.text) {
        (Err(err), Some(text)) if !ranged && err.precision_may_help() && fallback.max_bits > 0 => {
            let d = precision::decide(kind, text, &err, opts, fallback);
            row.fallback = Some(
                d.attempts
                    .iter()
                    .map(|a| output::FallbackRun {
                        bits: a.bits,
                        seconds: a.seconds,
                        proved: a.error.is_none(),
                        reason: a.error.as_ref().map(|e| e.to_string()),
                    })
                    .collect(),
            );
            if let Some(a) = d.attempts.last() {
                row.bits = a.bits;
            }
            match d
                .enclosure
                .as_ref()
                .map(|p| (outward_f64(&p.ts), outward_f64(&p.e)))
            {
                Some((Some(ts), Some(e))) => Ok((ts, e)),
                _ => Err(RigorError {
                    reason: format!(
                        "{} at f64; {}",
                        err.reason,
                        d.why_not()
                            .unwrap_or_else(|| "the enclosure is not finite".into())
                    ),
                    ..err
                }),
            }
        }
        (res, _) => res,
    };
    let fell_back = row.fallback.is_some();
    settle_rigorous(&mut row, res, c.scales.as_ref().map(|s| s.t_c), time_limit);
    if derived {
        if !fell_back {
            row.derived = out;
        }
        derived_missing(&mut row, ranged);
    }
    if sensitivities {
        let names = c.inputs.names();
        row.sensitivities = Some(
            (0..names.len())
                .into_par_iter()
                .map(|j| match sets::sensitivity(kind, &c.inputs, j, opts) {
                    Ok(s) => output::Sensitivity {
                        input: names[j],
                        dts: Some(bounds(s.ts)),
                        de: Some(bounds(s.e)),
                        reason: None,
                    },
                    Err(e) => output::Sensitivity {
                        input: names[j],
                        dts: None,
                        de: None,
                        reason: Some(e.to_string()),
                    },
                })
                .collect(),
        );
    }
    row
}

/// A rigorous row's result: the enclosures of T_s (in seconds too, with the time scale `t_c`)
/// and e; no separation before the horizon (proved: a result); or the reason it was not
/// proved (`time_limit`: the --time-limit given, named when the run stopped at its deadline).
pub fn settle_rigorous(
    row: &mut RigorousRow,
    res: Result<(Interval, Interval), RigorError>,
    t_c: Option<Interval>,
    time_limit: Option<f64>,
) {
    match res {
        Ok((ts, e)) => {
            row.proved = true;
            row.separated = true;
            row.ts = Some(bounds(ts));
            row.width_ts = Some(width(ts));
            row.e = Some(bounds(e));
            row.width_e = Some(width(e));
            row.ts_seconds = t_c.map(|t_c| Some(bounds(ts * t_c)));
        }
        // the condition proved to fail on [0, horizon]: T_s > horizon, a result
        Err(err) if err.no_separation() => {
            row.proved = true;
            let never = err.never_separates();
            row.reason = Some(no_separation_text(row.horizon, never));
            if never.is_some() {
                // T_s = +∞ for every T by the closed form: e = 0 by the paper's convention, as
                // the float run and `classical` report it
                let zero = Interval::try_from((0.0, 0.0)).unwrap();
                row.e = Some(bounds(zero));
                row.width_e = Some(width(zero));
            }
        }
        Err(err) => row.reason = Some(input::limit_text(&err, time_limit)),
    }
}

/// Which CSV `curve` writes.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Curve {
    /// t, the states, x, v, F.
    Trajectory,
    /// x, F (or x_mm, F_N).
    Loop,
}

/// A CSV: the header and the rows, already formatted, and a note for stderr (written after
/// the CSV).
pub type Csv = (Vec<String>, Vec<Vec<String>>, Option<String>);

fn curve(a: &TrajectoryArgs, what: Curve) -> Result<i32, CliError> {
    input::out_path(a.out.as_deref())?;
    let (points, t_end) = (a.points, a.t_end);
    check_units(a)?;
    let (head, rows, remark) = if let Some(law) = a.params.model.law() {
        super::law_runs::curve(a, law, what)?
    } else if a.engine.rigorous {
        let kind = input::bouc_wen_only(a.params.model, "this command")?;
        let opts = input::taylor_options(&a.engine)?;
        let case = input::single_case::<Interval>(&a.params)?;
        let bar = super::progress::Progress::cases(
            "proving the flow",
            1,
            input::time_limit(a.engine.time_limit),
        );
        let r = with_model!(kind, case.params, |m| rigorous_curve(
            &m,
            &opts,
            t_end,
            points,
            what,
            a.engine.time_limit
        ));
        bar.finish();
        r?
    } else {
        let kind = input::bouc_wen_only(a.params.model, "this command")?;
        let opts = input::float_options(&a.engine)?;
        let case = input::single_case::<f64>(&a.params)?;
        let units = match (&case.scales, a.physical_units) {
            (Some(s), true) => Units::Physical(s.clone()),
            _ => Units::Nondimensional,
        };
        with_model!(kind, case.params, |m| float_curve(
            &m, &opts, t_end, points, &units, what
        ))?
    };
    let head: Vec<&str> = head.iter().map(String::as_str).collect();
    let bytes = output::csv(&head, rows)?;
    output::emit(a.out.as_deref(), &bytes)?;
    if let Some(r) = remark {
        note(&r);
    }
    Ok(EXIT_OK)
}

/// --physical-units needs the scales of --physical.
pub fn check_units(a: &TrajectoryArgs) -> Result<(), CliError> {
    if a.physical_units && a.params.physical.is_none() {
        return Err(CliError::Input(
            "--physical-units needs --physical (the scales come from the physical parameters)"
                .into(),
        ));
    }
    Ok(())
}

/// Samples on the float engine's dense output.
pub fn float_curve<M: CollisionModel<f64, N>, const N: usize>(
    model: &M,
    opts: &FloatOptions,
    t_end: Option<f64>,
    points: usize,
    units: &Units,
    what: Curve,
) -> Result<Csv, CliError> {
    let failed = |e: bwcl::observables::ImpactError| CliError::Failed(e.to_string());
    let mut remark = None;
    let end = match t_end {
        Some(t) => t,
        None => match impact(model, opts).map_err(failed)?.ts {
            Some(ts) => ts,
            None => {
                remark = Some(format!(
                    "bwcl: note: no separation before the horizon T = {}; the samples end there",
                    num(opts.horizon)
                ));
                opts.horizon
            }
        },
    };
    let samples = trajectory(model, opts, Some(end), points, units).map_err(failed)?;
    let physical = matches!(units, Units::Physical(_));
    let (head, rows): (Vec<String>, Vec<Vec<String>>) = match what {
        Curve::Trajectory => {
            let mut head = vec!["t".to_string()];
            head.extend(M::STATE_NAMES.iter().map(|s| s.to_string()));
            head.extend(["x", "v", "F"].map(String::from));
            let rows = samples
                .iter()
                .map(|s| {
                    let mut r = vec![num(s.t)];
                    r.extend(s.state.iter().map(|&y| num(y)));
                    r.extend([num(s.x), num(s.v), num(s.force)]);
                    r
                })
                .collect();
            (head, rows)
        }
        Curve::Loop if physical => (
            vec!["x_mm".into(), "F_N".into()],
            samples
                .iter()
                .map(|s| vec![num(s.x.abs() * 1e3), num(s.force)])
                .collect(),
        ),
        Curve::Loop => (
            vec!["x".into(), "F".into()],
            samples
                .iter()
                .map(|s| vec![num(s.x), num(s.force)])
                .collect(),
        ),
    };
    Ok((head, rows, remark))
}

/// Samples of the proved flow: the enclosure of every column at each grid time.
pub fn rigorous_curve<M: CollisionModel<Interval, N>, const N: usize>(
    model: &M,
    opts: &TaylorOptions,
    t_end: Option<f64>,
    points: usize,
    what: Curve,
    time_limit: Option<f64>,
) -> Result<Csv, CliError> {
    // up to T_s (its upper bound), as the float curves; the flow reaches a little past it (to
    // the horizon, or --t-end, for a law that never separates)
    use bwcl::observables::rigorous::{CurveError, curve_flow};
    let (flow, end, never) = curve_flow(model, opts, t_end).map_err(|e| {
        CliError::Failed(match e {
            CurveError::Engine(e) => input::limit_text(&e, time_limit),
            CurveError::Other(m) => m,
        })
    })?;
    let names: Vec<&str> = match what {
        Curve::Trajectory => M::STATE_NAMES
            .iter()
            .copied()
            .chain(["x", "v", "F"])
            .collect(),
        Curve::Loop => vec!["x", "F"],
    };
    let mut head: Vec<String> = match what {
        Curve::Trajectory => vec!["t".into()],
        Curve::Loop => vec![],
    };
    for n in &names {
        head.push(format!("{n}_lo"));
        head.push(format!("{n}_hi"));
    }
    let mut rows = Vec::with_capacity(points);
    for t in bwcl::observables::trajectory::sample_times(end, points) {
        let s = flow.enclose(t).ok_or_else(|| {
            CliError::Failed(format!("the proved flow has no enclosure at T = {t}"))
        })?;
        let (x, v, f) = (model.position(&s), model.velocity(&s), model.force(&s));
        let cols: Vec<Interval> = match what {
            Curve::Trajectory => s.iter().copied().chain([x, v, f]).collect(),
            Curve::Loop => vec![x, f],
        };
        let mut r = match what {
            Curve::Trajectory => vec![num(t)],
            Curve::Loop => vec![],
        };
        for c in cols {
            r.extend(output::outward_pair(c));
        }
        rows.push(r);
    }
    let remark = never.then(|| {
        format!(
            "bwcl: note: the law never separates (its closed form); the samples end at T = {}",
            num(end)
        )
    });
    Ok((head, rows, remark))
}
