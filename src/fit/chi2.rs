//! The chi-square quantile χ²_q(k), by bisection on the regularized lower incomplete gamma
//! function: the CDF of χ²(k) at x is P(k/2, x/2), with
//!
//! ```text
//! P(a, x) = γ(a, x)/Γ(a)
//!         = x^a e^(−x) / Γ(a+1) · Σ_{n≥0} x^n / ((a+1)(a+2)…(a+n))          (x < a + 1)
//!         = 1 − x^a e^(−x)/Γ(a) · 1/(x + 1 − a − 1·(1−a)/(x + 3 − a − …))     (x ≥ a + 1)
//! ```
//!
//! (the series and Legendre's continued fraction, evaluated by the modified Lentz method, as in
//! Numerical Recipes §6.2), ln Γ by the Lanczos approximation (g = 7, 9 terms: |rel. error| <
//! 1e−15 for a > 0).

/// ln Γ(x), x > 0 (Lanczos, g = 7).
pub fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // reflection: Γ(x)Γ(1−x) = π / sin(πx)
        return (std::f64::consts::PI / (std::f64::consts::PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// P(a, x), the regularized lower incomplete gamma function (a > 0, x ≥ 0).
pub fn gamma_p(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let front = (a * x.ln() - x - ln_gamma(a)).exp();
    if x < a + 1.0 {
        let (mut term, mut sum, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..1000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * 1e-17 {
                break;
            }
        }
        (sum * front).min(1.0)
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..1000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-17 {
                break;
            }
        }
        (1.0 - front * h).max(0.0)
    }
}

/// The CDF of χ²(k) at x.
pub fn chi2_cdf(k: usize, x: f64) -> f64 {
    gamma_p(k as f64 / 2.0, x / 2.0)
}

/// χ²_q(k): the x with CDF q (0 < q < 1, k ≥ 1), by bisection to the last bit.
pub fn chi2_quantile(k: usize, q: f64) -> f64 {
    assert!(
        k >= 1 && q > 0.0 && q < 1.0,
        "χ² quantile of k = {k}, q = {q}"
    );
    let mut hi = k as f64 + 10.0;
    while chi2_cdf(k, hi) < q {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if m <= lo || m >= hi {
            break;
        }
        if chi2_cdf(k, m) < q {
            lo = m;
        } else {
            hi = m;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_match_the_tables() {
        // scipy.stats.chi2.ppf(0.95, k) and ppf(0.6827, 1)
        for (k, want) in [
            (1, 3.841_458_820_694_124),
            (2, 5.991_464_547_107_979),
            (3, 7.814_727_903_251_178),
            (6, 12.591_587_243_743_977),
            (20, 31.410_432_844_230_918),
        ] {
            let got = chi2_quantile(k, 0.95);
            assert!((got - want).abs() < 1e-9 * want, "k = {k}: {got} vs {want}");
        }
        // k = 2: CDF 1 − e^(−x/2) exactly
        for x in [0.1, 1.0, 7.0, 40.0] {
            assert!((chi2_cdf(2, x) - (1.0 - (-x / 2.0f64).exp())).abs() < 1e-14);
        }
        assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-13);
        assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-13);
    }
}
