//! `cor`, `trajectory` and `loop` for a classical law (`--model hooke|hertz|hunt-crossley|
//! kelvin-voigt|linear-maxwell`): the law's cases ([`input::law_cases`]: nondimensional, base
//! or physical parameters, [`bwcl::models::classical`]) on the same engines, rows and writers
//! as the Bouc–Wen models ([`super::commands`]).
//!
//! What only the Bouc–Wen models have is refused by name: --band, --digits, --sensitivities,
//! the precision fallback and the adaptive split of ranges (a law's range is proved whole).

use super::CliError;
use super::args::{CorArgs, TrajectoryArgs};
use super::commands::{
    Csv, Curve, derived_missing, float_curve, float_derived, prove_rows, proved_derived,
    rigorous_curve, settle_float, settle_rigorous,
};
use super::input::{self, LawCase};
use super::output::{FloatRow, RigorousRow, RowParams, bounds};
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::classical::{Law, LawParams};
use bwcl::observables::rigorous::rigorous_impact;
use bwcl::observables::trajectory::Units;
use bwcl::observables::{FloatOptions, impact};
use inari::Interval;
use rayon::prelude::*;

/// Runs `$body` with `$m` bound to the collision model inside a [`LawModel`](bwcl::models::classical::LawModel) (each law its own
/// monomorphization). Exported for the Python bindings' trajectory, which dispatches with it
/// too.
#[macro_export]
#[doc(hidden)]
macro_rules! with_law {
    ($model:expr, |$m:ident| $body:expr) => {
        match $model {
            $crate::models::classical::LawModel::Force($m) => $body,
            $crate::models::classical::LawModel::KelvinVoigt($m) => $body,
            $crate::models::classical::LawModel::LinearMaxwell($m) => $body,
        }
    };
}
pub use crate::with_law;

/// The options of `cor` a classical law does not take, refused naming the option.
pub fn check_cor_options(a: &CorArgs) -> Result<(), CliError> {
    let refused = [
        ("--sensitivities", a.sensitivities),
        ("--fallback-bits", a.fallback_bits.is_some()),
        ("--fallback-seconds", a.fallback_seconds.is_some()),
        ("--pieces", a.engine.pieces.is_some()),
    ];
    match refused.iter().find(|(_, given)| *given) {
        Some((opt, _)) => input::bouc_wen_only(a.params.model, opt).map(|_| ()),
        None => Ok(()),
    }
}

/// The nondimensional values of a case, by name, for the row.
fn named<R: bwcl::arith::Real, T>(p: &LawParams<R>, f: impl Fn(R) -> T) -> RowParams<T> {
    RowParams::Law(p.named().into_iter().map(|(k, v)| (k, f(v))).collect())
}

/// T_s and e of one case on the float engine.
pub fn float_row(law: Law, c: &LawCase<f64>, opts: &FloatOptions, derived: bool) -> FloatRow {
    let t_c = c.scales.as_ref().map(|s| s.t_c);
    let mut row = FloatRow::new(law.key(), c.v0, t_c, opts.horizon, named(&c.nd, |x| x));
    let mut out = None;
    match c.nd.model() {
        Ok(model) => settle_float(
            &mut row,
            with_law!(&model, |m| impact(m, opts).map(|r| {
                if derived {
                    out = Some(float_derived(m, opts, r.ts, r.e, c.scales.as_ref()));
                }
                (r.ts, r.e, r.stats)
            })),
        ),
        Err(why) => row.error = Some(why),
    }
    row.derived = out;
    row
}

/// Enclosures of T_s and e of one case on the rigorous engine (inputs given as ranges are
/// proved whole).
pub fn rigorous_row(
    law: Law,
    c: &LawCase<Interval>,
    opts: &TaylorOptions,
    derived: bool,
    time_limit: Option<f64>,
) -> RigorousRow {
    let mut out = None;
    let mut row = RigorousRow::new(
        law.key(),
        c.v0.map(bounds),
        c.scales.is_some(),
        opts.horizon,
        opts.order,
        named(&c.nd, bounds),
    );
    match c.nd.model() {
        Ok(model) => settle_rigorous(
            &mut row,
            with_law!(&model, |m| rigorous_impact(m, opts).map(|r| {
                if derived {
                    out = Some(proved_derived(m, &r, c.scales.as_ref()));
                }
                (r.ts, r.e)
            })),
            c.scales.as_ref().map(|s| s.t_c),
            time_limit,
        ),
        Err(why) => row.reason = Some(why),
    }
    if derived {
        row.derived = out;
        // (a law's range is proved whole: its derived outputs hold over the range)
        derived_missing(&mut row, false);
    }
    row
}

/// `cor`'s rows rendered: (output, cases failed, cases, compute time, notes for stderr).
pub type Rendered = (Vec<u8>, usize, usize, std::time::Duration, Vec<String>);

/// The rows of `cor` for a law, rendered.
pub fn cor(a: &CorArgs, law: Law) -> Result<Rendered, CliError> {
    check_cor_options(a)?;
    if a.engine.rigorous {
        let opts = input::taylor_options(&a.engine)?;
        let cases = input::law_cases::<Interval>(&a.params, law)?;
        let (rows, elapsed) = prove_rows(&cases, a.engine.time_limit, |c| {
            rigorous_row(law, c, &opts, a.derived, a.engine.time_limit)
        });
        let failed = rows.iter().filter(|r| !r.proved).count();
        Ok((
            super::output::rigorous_cor(&rows, a.format)?,
            failed,
            rows.len(),
            elapsed,
            Vec::new(),
        ))
    } else {
        let opts = input::float_options(&a.engine)?;
        let cases = input::law_cases::<f64>(&a.params, law)?;
        let start = std::time::Instant::now();
        let rows: Vec<FloatRow> = cases
            .par_iter()
            .map(|c| float_row(law, c, &opts, a.derived))
            .collect();
        let elapsed = start.elapsed();
        let failed = rows.iter().filter(|r| r.error.is_some()).count();
        Ok((
            super::output::float_cor(&rows, a.format)?,
            failed,
            rows.len(),
            elapsed,
            super::commands::resolution_notes(&rows, opts.ode.atol),
        ))
    }
}

/// The CSV of `trajectory` or `loop` for a law.
pub fn curve(a: &TrajectoryArgs, law: Law, what: Curve) -> Result<Csv, CliError> {
    let failed = |why: String| CliError::Failed(why);
    if a.engine.rigorous {
        if let Some(k) = a.engine.pieces {
            return Err(CliError::Input(format!(
                "--pieces {k}: a trajectory is proved whole (no split)"
            )));
        }
        let opts = input::taylor_options(&a.engine)?;
        let case = input::single_law_case::<Interval>(&a.params, law)?;
        let bar = super::progress::Progress::cases(
            "proving the flow",
            1,
            input::time_limit(a.engine.time_limit),
        );
        let model = case.nd.model().map_err(failed)?;
        let r = with_law!(&model, |m| rigorous_curve(
            m,
            &opts,
            a.t_end,
            a.points,
            what,
            a.engine.time_limit
        ));
        bar.finish();
        r
    } else {
        let opts = input::float_options(&a.engine)?;
        let case = input::single_law_case::<f64>(&a.params, law)?;
        let units = match (&case.scales, a.physical_units) {
            (Some(s), true) => Units::Physical(s.clone()),
            _ => Units::Nondimensional,
        };
        let model = case.nd.model().map_err(failed)?;
        with_law!(&model, |m| float_curve(
            m, &opts, a.t_end, a.points, &units, what
        ))
    }
}
