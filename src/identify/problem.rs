//! The constraints of set-membership identification: every measured collision i gives
//!
//! ```text
//! |e(𝓟(P*, v0_i)) − e_i| ≤ E_i        and, with a tc column,   |tc(P*, v0_i) − tc_i| ≤ T_i
//! ```
//!
//! with tc(P*, v0) = T_s(𝓟(P*, v0)) · v0^(−(p−1)/(p+1)), the contact duration in units of
//! T_c(v0 = 1 m/s) (eq:BWSHCCM_T_c: T_c ∝ v0^(−(p−1)/(p+1)) at fixed physical parameters).
//! The data are doubles read from decimals: each value is enclosed by its neighbours
//! [pred(x), succ(x)], which hold the decimal it was rounded from, so the targets are
//! intervals: the *outer* target [lo.inf, hi.sup] (a model value outside it violates the
//! constraint for every reading of the decimals) and the *inner* one [lo.sup, hi.inf] (a value
//! inside it satisfies it).

use crate::fit::data::CorData;
use crate::fit::space::{Slot, Space};
use crate::models::ModelKind;
use inari::Interval;

/// The enclosure [pred(x), succ(x)] of the decimal a double x was read from.
pub fn around(x: f64) -> Interval {
    Interval::try_from((x.next_down(), x.next_up())).expect("a finite double")
}

/// A measured value y ± E as the interval targets of the module doc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    /// y − E, enclosed.
    pub lo: Interval,
    /// y + E, enclosed.
    pub hi: Interval,
}

impl Target {
    /// y ± err (both doubles read from decimals, err > 0).
    pub fn new(y: f64, err: f64) -> Self {
        let (y, e) = (around(y), around(err));
        Self {
            lo: y - e,
            hi: y + e,
        }
    }

    /// Every model value that can satisfy the constraint lies in this interval.
    pub fn outer(&self) -> Interval {
        Interval::try_from((self.lo.inf(), self.hi.sup())).expect("an ordered target")
    }

    /// A model value in this interval satisfies the constraint; `None` when it is empty.
    pub fn inner(&self) -> Option<Interval> {
        Interval::try_from((self.lo.sup(), self.hi.inf())).ok()
    }
}

/// One measured collision: its speed and the targets of its CoR and contact duration.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The data row (0-based, in file order).
    pub index: usize,
    /// The enclosure of the impact speed.
    pub v0: Interval,
    pub e: Target,
    pub tc: Option<Target>,
}

impl Row {
    /// Row i of `data` with its CoR target e_i ± E_i (E_i its `sigma`, else `error`; checked by
    /// [`check_error`]) and no duration.
    pub fn cor(data: &CorData, i: usize, error: Option<f64>) -> Self {
        Self {
            index: i,
            v0: around(data.v0[i]),
            e: Target::new(data.e[i], data.e_error(i, error.unwrap_or(f64::NAN))),
            tc: None,
        }
    }
}

/// `--error`: finite and > 0, and needed unless the data have a `sigma` column.
pub fn check_error(data: &CorData, error: Option<f64>) -> Result<(), String> {
    if let Some(e) = error
        && !(e.is_finite() && e > 0.0)
    {
        return Err(format!("--error {e} must be a finite number > 0"));
    }
    if error.is_none() && data.sigma.is_none() {
        return Err("the error of e is needed: --error E, or a column sigma in the data".into());
    }
    Ok(())
}

/// A set-membership problem: the model, which parameters are free (the box) and which fixed
/// (their enclosures), and the constraints.
#[derive(Clone, Debug)]
pub struct Problem {
    pub kind: ModelKind,
    pub space: Space,
    /// The enclosure of each fixed parameter (of the decimal the user wrote); `None` for a free
    /// one.
    pub fixed: [Option<Interval>; 6],
    pub rows: Vec<Row>,
}

impl Problem {
    /// The problem of `data` with every e known to ±`error` (a `sigma` column overrides it per
    /// row), and every tc to ±`tc_error` (a `tc_sigma` column overrides it); `use_tc` false
    /// ignores a tc column. `fixed` encloses the value of each fixed parameter of `space`.
    /// Fails (with the reason) for a non-positive error, a tc column without its error, or a
    /// fixed parameter without an enclosure.
    pub fn new(
        kind: ModelKind,
        space: Space,
        fixed: [Option<Interval>; 6],
        data: &CorData,
        error: Option<f64>,
        tc_error: Option<f64>,
        use_tc: bool,
    ) -> Result<Self, String> {
        check_error(data, error)?;
        if let Some(e) = tc_error
            && !(e.is_finite() && e > 0.0)
        {
            return Err(format!("--tc-error {e} must be a finite number > 0"));
        }
        let use_tc = use_tc && data.tc.is_some();
        if use_tc && tc_error.is_none() && data.tc_sigma.is_none() {
            return Err(
                "the data have a column tc: its error is needed (--tc-error T or a \
                        column tc_sigma), or --no-tc to ignore it"
                    .into(),
            );
        }
        for (i, s) in space.slots.iter().enumerate() {
            if matches!(s, Slot::Fixed(_)) && fixed[i].is_none() {
                return Err(format!("no enclosure of the fixed parameter {i}"));
            }
        }
        let rows = (0..data.len())
            .map(|i| Row {
                tc: use_tc.then(|| {
                    let tc = data.tc.as_ref().expect("a tc column")[i];
                    Target::new(tc, data.tc_error(i, tc_error.unwrap_or(f64::NAN)))
                }),
                ..Row::cor(data, i, error)
            })
            .collect();
        Ok(Self {
            kind,
            space,
            fixed,
            rows,
        })
    }

    /// The number of free parameters (the box's dimension).
    pub fn dim(&self) -> usize {
        self.space.free().len()
    }

    /// P* over a box of the free parameters (in the order of [`Space::free`]), the fixed ones
    /// at their enclosures.
    pub fn base(&self, free: &[Interval]) -> [Interval; 6] {
        let mut it = free.iter();
        std::array::from_fn(|i| match self.space.slots[i] {
            Slot::Fixed(_) => self.fixed[i].expect("checked in new"),
            Slot::Free { .. } => *it.next().expect("a value per free parameter"),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn targets_enclose_the_decimals() {
        let t = Target::new(0.1, 0.02);
        // 0.1 − 0.02 = 0.08 and 0.1 + 0.02 = 0.12 as rationals
        let (o, i) = (t.outer(), t.inner().unwrap());
        assert!(o.inf() < 0.08 && o.sup() > 0.12);
        assert!(i.inf() > 0.08 - 1e-15 && i.sup() < 0.12 + 1e-15);
        assert!(o.subset(Interval::try_from((0.08 - 1e-15, 0.12 + 1e-15)).unwrap()));
        assert!(i.subset(o));
    }
}
