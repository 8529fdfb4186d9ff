//! Information criteria for comparing fitted models on the same data (issue #33, item 4):
//! Akaike's (AIC, and AICc with the small-sample correction) and Schwarz's (BIC), for
//! least-squares fits with Gaussian errors.
//!
//! With M residuals, k fitted parameters and J² the weighted sum of squares:
//!
//! ```text
//! errors given (χ² = J² absolute):   AIC = J² + 2k,              BIC = J² + k ln M
//! errors unknown (one σ for all):    AIC = M ln(J²/M) + 2K,      BIC = M ln(J²/M) + K ln M,
//!                                    K = k + 1 (σ² is fitted too)
//! AICc = AIC + 2K(K + 1)/(M − K − 1)  (K = k with errors given; ∞ when M ≤ K + 1)
//! ```
//!
//! (both up to a constant common to every model on the data, so only differences mean
//! anything: ΔAIC ≥ 10 is commonly read as "essentially no support" for the worse model,
//! Burnham & Anderson 2002, sec. 2.6). k counts the parameters that enter the CoR: the six of
//! P* for the Bouc–Wen models, one (σ_b, ζ or c̃) for Hunt–Crossley, Kelvin–Voigt and linear
//! Maxwell, none for Hooke and Hertz.

/// The criteria of one fit.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Criteria {
    /// M, the number of residuals.
    pub m: usize,
    /// k, the fitted parameters that enter the CoR.
    pub k: usize,
    #[serde(rename = "J")]
    pub j: f64,
    pub aic: f64,
    pub aicc: f64,
    pub bic: f64,
}

impl Criteria {
    /// The criteria of a fit with best cost `j` (module doc).
    pub fn new(j: f64, m: usize, k: usize, errors_given: bool) -> Self {
        let mf = m as f64;
        let (base, kk) = if errors_given {
            (j * j, k)
        } else {
            (mf * (j * j / mf).ln(), k + 1)
        };
        let kf = kk as f64;
        let aic = base + 2.0 * kf;
        let aicc = if m > kk + 1 {
            aic + 2.0 * kf * (kf + 1.0) / (mf - kf - 1.0)
        } else {
            f64::INFINITY
        };
        Self {
            m,
            k,
            j,
            aic,
            aicc,
            bic: base + kf * mf.ln(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn textbook_values() {
        // M = 20, RSS = 0.0005, k = 1, σ unknown: AIC = 20 ln(2.5e−5) + 4
        let c = Criteria::new(0.0005f64.sqrt(), 20, 1, false);
        let want = 20.0 * (2.5e-5f64).ln() + 4.0;
        assert!((c.aic - want).abs() < 1e-12, "{} {want}", c.aic);
        assert!((c.aicc - (want + 12.0 / 17.0)).abs() < 1e-12);
        assert!((c.bic - (20.0 * (2.5e-5f64).ln() + 2.0 * 20f64.ln())).abs() < 1e-12);
        // χ² given: χ² + 2k
        let c = Criteria::new(3.0, 10, 2, true);
        assert_eq!(c.aic, 13.0);
        assert!((c.bic - (9.0 + 2.0 * 10f64.ln())).abs() < 1e-12);
        // a parameter more must buy a smaller J to win
        let a = Criteria::new(0.1, 20, 1, false);
        let b = Criteria::new(0.1, 20, 6, false);
        assert!(a.aic < b.aic && a.bic < b.bic);
        assert!(Criteria::new(0.1, 3, 6, false).aicc.is_infinite());
    }
}
