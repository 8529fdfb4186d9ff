//! The errors that weight the residuals of a fit (issue #31): per row, the error s_i of the CoR
//! and, with contact durations, the error t_i of tc.
//!
//! ```text
//! r_i       = (ẽ_i − e(𝓟(P*, ṽ0_i))) / s_i          i = 1 … M
//! r_{M+i}   = (t̃c_i − tc(P*, ṽ0_i)) / t_i            (only with a tc column)
//! J         = sqrt(Σ r²),  χ² = J²,  reduced χ² = J² / (M_res − k)
//! ```
//!
//! s_i is the row's `sigma`, else `--error E`, else 1 (then J is the paper's J of eq:J);
//! t_i is the row's `tc_sigma`, else `--tc-error E` — a tc column without either is refused,
//! since a duration and a CoR cannot share a unit weight.

use super::data::CorData;

/// The resolved per-row errors of one data set.
#[derive(Clone, Debug, PartialEq)]
pub struct Weights {
    /// s_i, the error of e_i (M values).
    pub e: Vec<f64>,
    /// (t̃c_i, t_i) per row, when the durations take part in the fit.
    pub tc: Option<Vec<(f64, f64)>>,
    /// Whether the errors of e were given (a `sigma` column or `--error`): then χ² is absolute
    /// (s² = 1 in the covariance and Δχ²), otherwise scaled by the fit's reduced χ².
    pub errors_given: bool,
}

fn positive(what: &str, x: Option<f64>) -> Result<Option<f64>, String> {
    match x {
        Some(v) if !(v.is_finite() && v > 0.0) => Err(format!("{what} {v} must be finite and > 0")),
        _ => Ok(x),
    }
}

impl Weights {
    /// Unit errors, no durations: J is the paper's J.
    pub fn unit(data: &CorData) -> Self {
        Self {
            e: vec![1.0; data.len()],
            tc: None,
            errors_given: false,
        }
    }

    /// The errors of `data` (see the module doc): `e_error` for rows without `sigma`,
    /// `tc_error` for rows without `tc_sigma`, the durations used when present and `use_tc`.
    pub fn new(
        data: &CorData,
        e_error: Option<f64>,
        tc_error: Option<f64>,
        use_tc: bool,
    ) -> Result<Self, String> {
        let e_error = positive("--error", e_error)?;
        let tc_error = positive("--tc-error", tc_error)?;
        let e = (0..data.len())
            .map(|i| data.e_error(i, e_error.unwrap_or(1.0)))
            .collect();
        let tc = match (&data.tc, use_tc) {
            (Some(tc), true) => {
                if data.tc_sigma.is_none() && tc_error.is_none() {
                    return Err(
                        "the data have a column tc but no tc_sigma: give --tc-error E (the error \
                         of every duration) or --no-tc"
                            .into(),
                    );
                }
                Some(
                    tc.iter()
                        .enumerate()
                        .map(|(i, &t)| (t, data.tc_error(i, tc_error.unwrap_or(f64::NAN))))
                        .collect(),
                )
            }
            (None, _) if tc_error.is_some() => {
                return Err("--tc-error is given but the data have no column tc".into());
            }
            _ => None,
        };
        Ok(Self {
            e,
            tc,
            errors_given: data.sigma.is_some() || e_error.is_some(),
        })
    }

    /// M_res, the number of residuals: M, or 2M with durations.
    pub fn residual_count(&self) -> usize {
        self.e.len() * if self.tc.is_some() { 2 } else { 1 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn data(tc: bool, tc_sigma: bool) -> CorData {
        CorData::new(vec![0.5, 1.0], vec![0.6, 0.5])
            .unwrap()
            .with_columns(
                Some(vec![0.01, 0.02]),
                tc.then(|| vec![1.1, 0.9]),
                tc_sigma.then(|| vec![0.05, 0.05]),
            )
            .unwrap()
    }

    #[test]
    fn columns_options_and_refusals() {
        let d = data(false, false);
        let w = Weights::new(&d, Some(0.5), None, true).unwrap();
        assert_eq!(w.e, vec![0.01, 0.02]);
        assert!(w.errors_given && w.tc.is_none());
        assert_eq!(w.residual_count(), 2);
        let plain = CorData::new(vec![0.5], vec![0.6]).unwrap();
        let w = Weights::new(&plain, None, None, true).unwrap();
        assert_eq!(w, Weights::unit(&plain));
        assert_eq!(
            Weights::new(&plain, Some(0.1), None, true).unwrap().e,
            vec![0.1]
        );
        assert!(Weights::new(&plain, Some(0.0), None, true).is_err());
        assert!(Weights::new(&plain, None, Some(0.1), true).is_err());
        let d = data(true, false);
        let e = Weights::new(&d, None, None, true).unwrap_err();
        assert!(e.contains("--tc-error"), "{e}");
        assert!(Weights::new(&d, None, None, false).unwrap().tc.is_none());
        let w = Weights::new(&d, None, Some(0.1), true).unwrap();
        assert_eq!(w.tc, Some(vec![(1.1, 0.1), (0.9, 0.1)]));
        assert_eq!(w.residual_count(), 4);
        let w = Weights::new(&data(true, true), None, Some(0.1), true).unwrap();
        assert_eq!(w.tc, Some(vec![(1.1, 0.05), (0.9, 0.05)]));
    }
}
