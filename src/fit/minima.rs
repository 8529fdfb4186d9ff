//! The distinct minima among a multi-start fit's end points (issue #31, item 2): the starts are
//! clustered into basins by the hill–valley test, and each minimum is compared with the best by
//! Δχ².
//!
//! Hill–valley (Ursem 2000): end points a, b belong to one basin if J on the interior points
//! P(t) = (1 − t) a + t b, t ∈ {1/4, 1/2, 3/4}, of the segment between them in P* space never
//! rises above max(J_a, J_b)(1 + 10⁻³) + 10⁻¹² (𝓟 and every bounds box are convex, so the
//! segment stays admissible). Starts are taken best J first; each is compared only with the
//! representatives (the best point) of the clusters found so far, best first, and joins the first
//! it shares a valley with, or opens a new cluster.
//!
//! ```text
//! Δχ²_m = (J_m² − J_best²) / s²,   s² = J_best² / (M_res − k)   (no errors given)
//!                                  s² = 1                        (errors given: absolute χ²)
//! ```
//!
//! A minimum with Δχ² ≤ χ²_0.95(k) is statistically indistinguishable from the best.

use super::nelder_mead::StartResult;
use crate::models::NdParams;

/// Relative rise of J allowed on the segment between two end points of one basin.
pub const RISE: f64 = 1e-3;
/// Absolute rise allowed on top of [`RISE`].
pub const RISE_ABS: f64 = 1e-12;
/// The interior points of the hill–valley test.
pub const INTERIOR: [f64; 3] = [0.25, 0.5, 0.75];

/// One distinct minimum.
#[derive(Clone, Debug)]
pub struct Minimum {
    /// Its best point (the cluster's representative).
    pub base: NdParams<f64>,
    pub j: f64,
    /// The starts (0-based indices) that ended in this basin.
    pub starts: Vec<usize>,
    /// Whether the representative's run stopped on the tolerance.
    pub converged: bool,
    /// The bounded parameters at a bound.
    pub at_bound: Vec<&'static str>,
    /// (J² − J_best²)/s².
    pub delta_chi2: f64,
    /// Δχ² ≤ χ²_0.95(k).
    pub indistinguishable: bool,
}

/// Whether a and b (with costs ja, jb) share a basin of `cost` by the hill–valley test.
pub fn same_basin(
    a: &NdParams<f64>,
    ja: f64,
    b: &NdParams<f64>,
    jb: f64,
    cost: &(dyn Fn(&NdParams<f64>) -> f64 + Sync),
) -> bool {
    let (xa, xb) = (a.as_array(), b.as_array());
    if xa == xb {
        return true;
    }
    let top = ja.max(jb) * (1.0 + RISE) + RISE_ABS;
    INTERIOR.iter().all(|&t| {
        let x: [f64; 6] = std::array::from_fn(|i| (1.0 - t) * xa[i] + t * xb[i]);
        let p = NdParams {
            b: x[0],
            gamma: x[1],
            kappa: x[2],
            sigma: x[3],
            n: x[4],
            p: x[5],
        };
        cost(&p) <= top
    })
}

/// Clusters the starts (see the module doc) and scores each minimum against the best: `s2` as
/// in the module doc, `crit` = χ²_0.95(k).
pub fn cluster(
    starts: &[StartResult],
    cost: &(dyn Fn(&NdParams<f64>) -> f64 + Sync),
    s2: f64,
    crit: f64,
) -> Vec<Minimum> {
    let mut order: Vec<&StartResult> = starts.iter().collect();
    order.sort_by(|x, y| x.j.total_cmp(&y.j));
    let mut out: Vec<Minimum> = Vec::new();
    for st in order {
        let home = out
            .iter()
            .position(|m| same_basin(&m.base, m.j, &st.base, st.j, cost));
        match home {
            Some(c) => out[c].starts.push(st.start),
            None => out.push(Minimum {
                base: st.base.clone(),
                j: st.j,
                starts: vec![st.start],
                converged: st.converged,
                at_bound: st.at_bound.clone(),
                delta_chi2: 0.0,
                indistinguishable: true,
            }),
        }
    }
    let jb = out.first().map_or(0.0, |m| m.j);
    for m in &mut out {
        m.delta_chi2 = if s2 > 0.0 {
            (m.j * m.j - jb * jb) / s2
        } else if m.j == jb {
            0.0
        } else {
            f64::INFINITY
        };
        m.indistinguishable = m.delta_chi2 <= crit;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::ModelKind;

    fn set(kappa: f64) -> NdParams<f64> {
        NdParams::new(ModelKind::Shc, 1.0, 0.0, kappa, 0.01, 1.3, 1.3).unwrap()
    }

    fn start(i: usize, kappa: f64, j: f64) -> StartResult {
        StartResult {
            start: i,
            initial: set(0.5),
            base: set(kappa),
            j,
            iterations: 1,
            evaluations: 1,
            converged: true,
            at_bound: vec![],
        }
    }

    /// Two wells in κ, at 0.3 and 0.7, with a ridge at 0.5.
    fn wells(p: &NdParams<f64>) -> f64 {
        let k = p.kappa;
        ((k - 0.3) * (k - 0.7)).powi(2) + 0.01 * (k - 0.3).abs().min((k - 0.7).abs()) + 1.0
    }

    #[test]
    fn wells_apart_two_clusters_the_same_well_one() {
        let starts = vec![
            start(0, 0.3, wells(&set(0.3))),
            start(1, 0.7, wells(&set(0.7))),
            start(2, 0.30001, wells(&set(0.30001))),
            start(3, 0.3, wells(&set(0.3))),
        ];
        let m = cluster(&starts, &wells, 1.0, 3.84);
        assert_eq!(m.len(), 2, "{m:?}");
        let mut sizes: Vec<usize> = m.iter().map(|m| m.starts.len()).collect();
        sizes.sort();
        assert_eq!(sizes, vec![1, 3]);
        // Δχ² relative to the best
        assert_eq!(m[0].delta_chi2, 0.0);
        assert!(m.iter().all(|m| m.indistinguishable));
        let m = cluster(&starts, &wells, 1e-9, 3.84);
        assert!(m.iter().all(|m| m.delta_chi2 >= 0.0));
        // a flat valley: one cluster
        let flat = |_: &NdParams<f64>| 1.0;
        assert_eq!(cluster(&starts, &flat, 1.0, 3.84).len(), 1);
    }
}
