//! A set-membership problem from the options a user writes (`bwcl identify`, `bwcl.identify`):
//! the model, `--base` (values of the parameters that are not free), `--fix name=value,…`,
//! `--bounds name=lo..hi,…` (the free parameters and their box), optionally `--free names`
//! (a check: the bounded names), the errors and the data. Decimals are enclosed as written:
//! the fixed values by their enclosures, the box by the doubles just outside its decimal ends.

use super::problem::Problem;
use crate::arith::interval::enclose_decimal;
use crate::fit::data::{CorData, echo};
use crate::fit::space::{NAMES, Slot, Space, param_index, parse_bounds, parse_fix};
use crate::models::{ModelKind, NdParams};
use inari::Interval;

/// What the user wrote (the options' texts).
#[derive(Clone, Debug, Default)]
pub struct Spec<'a> {
    pub base: Option<&'a str>,
    pub fix: Option<&'a str>,
    pub bounds: Option<&'a str>,
    pub free: Option<&'a str>,
    pub error: Option<f64>,
    pub tc_error: Option<f64>,
    pub no_tc: bool,
}

/// The value texts of a `name=value` or `name=lo..hi` list, by parameter (checked by
/// `parse_fix` or `parse_bounds` first).
fn values(text: &str) -> Vec<(usize, &str)> {
    text.split(',')
        .filter(|s| !s.trim().is_empty())
        .filter_map(|item| {
            let (n, v) = item.split_once('=')?;
            Some((param_index(n)?, v.trim()))
        })
        .collect()
}

/// The problem and its starting box, or a one-line reason naming the option and the value.
pub fn problem(
    kind: ModelKind,
    data: &CorData,
    spec: &Spec,
) -> Result<(Problem, Vec<Interval>), String> {
    let fix = spec
        .fix
        .map(|t| parse_fix(t).map_err(|e| format!("--fix: {e}")))
        .transpose()?
        .unwrap_or_default();
    let bounds_text = spec
        .bounds
        .ok_or("--bounds is needed: the box of the free parameters (e.g. kappa=0.4..0.8)")?;
    let bounds = parse_bounds(bounds_text).map_err(|e| format!("--bounds: {e}"))?;
    let base = spec
        .base
        .map(|t| {
            NdParams::<Interval>::parse(kind, t)
                .map_err(|e| format!("--base '{}': {}", echo(t), e.0))
        })
        .transpose()?;
    let space = Space::build(kind, &fix, &bounds, |i| match &base {
        Some(b) => Ok(Slot::Fixed(b.as_array()[i].mid())),
        None => Err(format!(
            "{} is neither free (--bounds) nor fixed (--fix, --base)",
            NAMES[i]
        )),
    })
    .map_err(|e| format!("--bounds/--fix: {e}"))?;
    if let Some(f) = spec.free {
        let mut names = Vec::new();
        for n in f.split(',').filter(|s| !s.trim().is_empty()) {
            let i = param_index(n).ok_or_else(|| {
                format!(
                    "--free: '{}' is not a parameter name (one of {})",
                    echo(n),
                    NAMES.join(", ")
                )
            })?;
            names.push(i);
        }
        names.sort_unstable();
        names.dedup();
        if names != space.free() {
            return Err(format!(
                "--free '{}' names other parameters than --bounds bounds ({}): each free \
                 parameter needs its bounds",
                echo(f),
                space.free_names().join(", ")
            ));
        }
    }
    // enclosures of the fixed values as written
    let mut fixed: [Option<Interval>; 6] = [None; 6];
    let fix_texts = spec.fix.map(values).unwrap_or_default();
    for (i, f) in fixed.iter_mut().enumerate() {
        if !matches!(space.slots[i], Slot::Fixed(_)) {
            continue;
        }
        *f = Some(match fix_texts.iter().find(|(j, _)| *j == i) {
            Some((_, t)) => enclose_decimal(t).map_err(|e| format!("--fix {}: {e}", NAMES[i]))?,
            None => base.as_ref().expect("checked by Space::build").as_array()[i],
        });
    }
    // the box: the doubles just outside the decimal ends
    let mut start = Vec::new();
    let bound_texts = values(bounds_text);
    for i in space.free() {
        let (_, r) = bound_texts.iter().find(|(j, _)| *j == i).expect("bounded");
        let (a, b) = r.split_once("..").expect("checked by parse_bounds");
        let (lo, hi) = (
            enclose_decimal(a.trim()).map_err(|e| format!("--bounds {}: {e}", NAMES[i]))?,
            enclose_decimal(b.trim()).map_err(|e| format!("--bounds {}: {e}", NAMES[i]))?,
        );
        // 𝓟's closed ends (n, p ≥ 1) are not crossed by the outward rounding
        let floor = match (i, kind) {
            (4, _) | (5, ModelKind::Shc) => 1.0,
            (5, ModelKind::Maxwell) => 2.0,
            (2 | 3 | 0, _) => f64::MIN_POSITIVE,
            _ => f64::NEG_INFINITY,
        };
        let lo = if lo.inf() < floor && lo.sup() >= floor {
            floor
        } else {
            lo.inf()
        };
        let hi = if i == 2 {
            hi.sup().min(1.0f64.next_down())
        } else {
            hi.sup()
        };
        start.push(
            Interval::try_from((lo, hi))
                .map_err(|_| format!("--bounds {}: '{}' is not a range", NAMES[i], echo(r)))?,
        );
    }
    let p = Problem::new(
        kind,
        space,
        fixed,
        data,
        spec.error,
        spec.tc_error,
        !spec.no_tc,
    )?;
    Ok((p, start))
}
