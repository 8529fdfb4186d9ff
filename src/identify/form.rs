//! Enclosures of a row's observables over a box of the free parameters, as mean-value forms
//! re-centred on each box, and the contractor they give.
//!
//! For an observable y (e, or tc) and a box U inside a box A over which the slopes
//! g_j ⊇ {∂y/∂u_j (u) : u ∈ A} are proved ([`crate::observables::sets::slopes_over_set`]), and
//! a point ŝ ∈ U where y(ŝ) is proved (the point engine), the mean-value theorem along the
//! segment [ŝ, u] ⊂ U ⊂ A gives for every u ∈ U
//!
//! ```text
//! y(u) ∈ y(ŝ) + Σ_j g_j (u_j − ŝ_j)                                          (MV)
//! ```
//!
//! so y(U) ⊂ [y(ŝ)] + Σ_j g_j (U_j − ŝ_j), intersected with the hull of y over A. The slopes
//! are computed once on a box and re-used on its sub-boxes (only the point run is new); their
//! width multiplies U − ŝ, which shrinks with U.
//!
//! **Contractor.** If u ∈ U satisfies y(u) ∈ T (the outer target), (MV) gives for each j
//!
//! ```text
//! g_j (u_j − ŝ_j) ∋ y(u) − y(ŝ) − Σ_{k≠j} g_k (u_k − ŝ_k) ∈ T − [y(ŝ)] − Σ_{k≠j} g_k (U_k − ŝ_k) =: R_j
//! ```
//!
//! (with the same g' ∈ g in both places), so where 0 ∉ g_j, u_j ∈ ŝ_j + R_j / g_j: the part of
//! U_j outside it holds no feasible point. This is the linear (Hansen–Sengupta-like) hull
//! consistency step of interval constraint propagation on the mean-value form.
//!
//! tc = T_s · c(p) with c(p) = v0^(−(p−1)/(p+1)): ∂tc/∂u_j = c ∂T_s/∂u_j, and for p also
//! T_s c ln(v0) (−2/(p+1)²).

use crate::observables::sets::SetSlopes;
use inari::{Interval, const_interval};

const ZERO: Interval = const_interval!(0.0, 0.0);

/// c(p) = v0^(−(p−1)/(p+1)) and dc/dp = c · ln(v0) · (−2/(p+1)²), over intervals.
pub fn tc_factor(v0: Interval, p: Interval) -> (Interval, Interval) {
    let one = const_interval!(1.0, 1.0);
    let two = const_interval!(2.0, 2.0);
    let p1 = p + one;
    let a = -(p - one) / p1;
    let c = (a * v0.ln()).exp();
    let dc = c * v0.ln() * (-two / p1.sqr());
    (c, dc)
}

/// The slopes of one row's observables over a box A (the free coordinates' order), and
/// their hulls over A.
#[derive(Clone, Debug)]
pub struct RowSlopes {
    /// The widths of A (to decide when sub-boxes deserve their own).
    pub widths: Vec<f64>,
    pub e_hull: Interval,
    /// ∂e/∂u_j over A; `None` where the crossing is not transversal over A.
    pub e: Option<Vec<Interval>>,
    pub tc_hull: Interval,
    pub tc: Option<Vec<Interval>>,
}

impl RowSlopes {
    /// From the variational runs `s` over the box `a` of the free parameters `free` (their
    /// indices in P*, the inputs' order of [`crate::observables::sets::Inputs::Base`]), with p
    /// over A `p` and the speed `v0`. A free coordinate that is not a range (a box a few ulps
    /// wide) gets slope 0: the centre's point run takes its whole interval instead
    /// ([`centre_of`]), which keeps (MV) true.
    pub fn new(s: &SetSlopes, a: &[Interval], free: &[usize], p: Interval, v0: Interval) -> Self {
        let dim = a.len();
        let mut e = Some(vec![ZERO; dim]);
        let mut ts = Some(vec![ZERO; dim]);
        for (input, slope) in &s.slopes {
            let k = free.iter().position(|f| f == input);
            match (slope, k) {
                (Some(sl), Some(k)) => {
                    if let Some(v) = e.as_mut() {
                        v[k] = sl.e;
                    }
                    if let Some(v) = ts.as_mut() {
                        v[k] = sl.ts;
                    }
                }
                // a range that is not free (cannot happen: fixed parameters are decimals'
                // enclosures, v0 too) or no derivative: no form
                _ => {
                    e = None;
                    ts = None;
                }
            }
        }
        let p_free = free.iter().position(|&f| f == 5);
        let (c, dc) = tc_factor(v0, p);
        let tc = ts.map(|g| {
            g.iter()
                .enumerate()
                .map(|(j, &d)| {
                    let mut x = c * d;
                    if Some(j) == p_free {
                        x += s.ts * dc;
                    }
                    x
                })
                .collect()
        });
        Self {
            widths: a.iter().map(|x| x.wid()).collect(),
            e_hull: s.e,
            e,
            tc_hull: s.ts * c,
            tc,
        }
    }
}

/// The centre of (MV) in a box: a short point near the middle of each range (a double, as an
/// interval), the whole interval of a coordinate that is not a range (see [`RowSlopes::new`]).
pub fn centre_of(u: &[Interval]) -> Vec<Interval> {
    u.iter()
        .map(|x| {
            if crate::observables::sets::is_range(x) {
                point(crate::observables::sets::short_centre(x.inf(), x.sup()))
            } else {
                *x
            }
        })
        .collect()
}

/// The term g_j (U_j − ŝ_j) of (MV); 0 for a coordinate that is not a range (its slope is 0
/// and the centre holds all of it).
fn term(gj: Interval, uj: Interval, cj: Interval) -> Interval {
    if gj == ZERO { ZERO } else { gj * (uj - cj) }
}

/// y(U) by (MV) about `centre` (with y(centre) ∈ `yc`), intersected with `hull`.
pub fn enclose(
    yc: Interval,
    g: &[Interval],
    u: &[Interval],
    centre: &[Interval],
    hull: Interval,
) -> Interval {
    let mut y = yc;
    for ((&gj, &uj), &cj) in g.iter().zip(u).zip(centre) {
        y += term(gj, uj, cj);
    }
    y.intersection(hull)
}

/// The exact interval of a double.
pub fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).expect("a finite double")
}

/// The contractor of the module doc: the sub-box of `u` that can hold points with y ∈
/// `target` (`None`: no point can). Coordinates with 0 ∈ g_j are left as they are.
pub fn contract(
    yc: Interval,
    g: &[Interval],
    u: &[Interval],
    centre: &[Interval],
    target: Interval,
) -> Option<Vec<Interval>> {
    let terms: Vec<Interval> = g
        .iter()
        .zip(u)
        .zip(centre)
        .map(|((&gj, &uj), &cj)| term(gj, uj, cj))
        .collect();
    let mut out = u.to_vec();
    for j in 0..u.len() {
        // (a centre that is not a point holds coordinate j whole: (MV) has no term in it)
        if g[j].contains(0.0) || !g[j].is_common_interval() || centre[j].wid() > 0.0 {
            continue;
        }
        let mut r = target - yc;
        for (k, t) in terms.iter().enumerate() {
            if k != j {
                r -= *t;
            }
        }
        let uj = centre[j] + r / g[j];
        out[j] = out[j].intersection(uj);
        if out[j].is_empty() {
            return None;
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval {
        Interval::try_from((a, b)).unwrap()
    }

    /// y = 2u₀ − u₁ + 1 exactly: the forms and the contractor against the closed form.
    #[test]
    fn a_linear_function_is_enclosed_and_contracted_exactly() {
        let g = [iv(2.0, 2.0), iv(-1.0, -1.0)];
        let u = [iv(0.0, 1.0), iv(0.0, 1.0)];
        let c = [iv(0.5, 0.5), iv(0.5, 0.5)];
        let yc = iv(1.5, 1.5);
        let y = enclose(yc, &g, &u, &c, Interval::ENTIRE);
        assert_eq!((y.inf(), y.sup()), (0.0, 3.0));
        // y ∈ [2.5, 3]: needs u₀ ≥ 0.75 (at u₁ = 0) and u₁ ≤ 0.5 (at u₀ = 1)
        let k = contract(yc, &g, &u, &c, iv(2.5, 3.0)).unwrap();
        assert_eq!((k[0].inf(), k[0].sup()), (0.75, 1.0));
        assert_eq!((k[1].inf(), k[1].sup()), (0.0, 0.5));
        // y ∈ [4, 5]: nothing in the box
        assert!(contract(yc, &g, &u, &c, iv(4.0, 5.0)).is_none());
        // a slope with 0 inside leaves its coordinate alone
        let g0 = [iv(2.0, 2.0), iv(-1.0, 1.0)];
        let k = contract(yc, &g0, &u, &c, iv(2.5, 3.0)).unwrap();
        assert_eq!((k[1].inf(), k[1].sup()), (0.0, 1.0));
    }

    #[test]
    fn the_tc_factor_is_the_closed_form() {
        let (c, dc) = tc_factor(iv(4.0, 4.0), iv(3.0, 3.0));
        // 4^(−1/2) = 0.5, dc/dp = 0.5 · ln 4 · (−2/16)
        assert!(c.contains(0.5) && c.wid() < 1e-15);
        let want = 0.5 * 4f64.ln() * (-0.125);
        assert!(dc.contains(want) || (dc.mid() - want).abs() < 1e-15);
    }
}
