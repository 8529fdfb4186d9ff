//! Steps of a second variational system (x, u, S, S₂) ([`SecondOrder`]) across the places its
//! field is not smooth:
//!
//! **Integrable singular terms.** Where the model has |w|^q with 1 < q < 2 (eq:BWHCL's |Z|^n,
//! eq:BWMCM_nd's |Y|^p), Ṡ₂ = D_x f·S₂ + D²f[S̃, S̃] holds |w|^(q−2): unbounded at w = 0, so
//! neither a Taylor step nor the plain low-order step X + \[0,h\]·f(Y) can cross w = 0. The
//! field is affine in those powers s_i = |w_i|^(r_i) (or sgn(w_i)|w_i|^(r_i)), −1 < r_i < 0:
//! f(x) = g(x) + Σ c_i(x)·s_i(x) (checked on the tape, [`Tape::field_degrees`]). While w_i keeps
//! the sign of its rate over the a-priori box Y, |ẇ_i| ≥ m_i > 0, so
//!
//! ```text
//! ∫₀ʰ |w_i(τ)|^r_i dτ = ∫ |w|^r_i dw/|ẇ_i| ≤ ∫_{Y_wi} |w|^r_i dw / m_i = (|a|^(r+1) + |b|^(r+1)) / ((r+1) m_i)
//! ```
//!
//! (Y_wi = [a, b] ∋ 0), and by the mean value theorem for integrals with the nonnegative
//! weight |w_i|^r_i (for a signed power: its positive and negative parts)
//! ∫₀^τ c_i(x)·s_i dτ ∈ h·c_i(Y)·[0, A_i] (A_i the bound above over h). Hence, with
//! q_i = f(Y; s_i := [0, A_i] or [−A_i, A_i]) − f(Y; s := 0) ⊇ c_i(Y)·s_i's range and
//! g(Y) = f(Y; s := 0):
//!
//! ```text
//! Φ(t0 + τ) ∈ X + Σ_i hull(0, h·q_i) + τ·g(Y)   (τ ∈ [0, h]),   Φ(t0 + h) ∈ X + h·(g(Y) + Σ_i q_i),
//! ```
//!
//! Y validated by that box's lying inside Y (the path cannot leave Y first).
//!
//! **The kink.** Where a kink component x_k (the operand of |·| only: the hysteretic rate's
//! |V|) crosses 0, f is continuous but D_x f jumps, so S is continuous and S₂ jumps: with
//! τ′ = −S_k/f_k (the crossing time's derivative in u), S̃ = (S, 1), f̃ = (f, 0),
//!
//! ```text
//! ΔS₂ = (Df_before − Df_after)·(2·S̃·τ′ + f̃·τ′²)
//! ```
//!
//! (differentiate x(t, u) = φ⁺(t − t_c(u), φ⁻(t_c(u), u)) twice in u). The same holds where
//! the tape takes sgn x_k of a component that is no kink ([`Tape::sign_jumps`]: eq:BWHCL's
//! |Z|^n with n = 1, whose derivative is sgn Z, Z also in |Z|^(p−1)Z): f is continuous there
//! too (checked: [`Tape::sign_in_the_rates`]), and the jump is evaluated on the box with
//! x_k = 0 exactly, where the members cross (the powers of x_k are not continued across 0,
//! sgn x_k is, as ±1). A step that may cross
//! adds hull(0, ΔS₂) over its a-priori box and its interior times, and at its end ΔS₂ itself
//! where every member has crossed, hull(0, ΔS₂) where some may not have (each member crosses
//! at most once per step: f_k keeps its sign over the box, or τ′ is unbounded and the step
//! fails).

use super::boxes::{inflate, keep_params, span, subset};
use super::flow::{Piece, tau};
use super::step::StepOut;
use super::tape::{Degree, SecondOrder, Tape};
use crate::arith::{Enclosure, Real};

/// The jumps of S₂ summed over the kink components that may cross 0 in the box `y` (the step
/// from the box `x0`), zero elsewhere: ΔS₂ itself for a kink every member crosses in the step
/// (x_k of one sign at `x0`, of the other at `end`, the step's end without the jump), else
/// hull(0, ΔS₂) (members that cross and members that do not; the a-priori box and the
/// piece's interior times). `None` when the tape is no second variational system or no kink
/// can cross. Unbounded (the step then fails) where a kink's rate may vanish in `y`.
pub fn kink_jump<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    x0: &[I; N],
    y: &[I; N],
    end: Option<&[I; N]>,
) -> Option<[I; N]> {
    let lay = tape.second_order()?;
    let n = lay.n;
    let signs = tape.sign_jumps().0;
    let crossing: Vec<usize> = tape
        .kinks()
        .iter()
        .chain(&signs)
        .copied()
        .filter(|&k| k < n && y[k].lo() <= 0.0 && y[k].hi() >= 0.0)
        .collect();
    if crossing.is_empty() {
        return None;
    }
    // f over the box, for the kinks' formula only (a sign component's jump is evaluated at 0)
    let mut f = None;
    let mut total: [I; N] = std::array::from_fn(|_| I::zero());
    for k in crossing {
        let d = if signs.contains(&k) {
            sign_jump_at_zero(tape, lay, y, k)
        } else {
            jump_of(tape, lay, y, f.get_or_insert_with(|| tape.eval(y)), k)
        };
        let before = Real::sign(&x0[k]);
        let after = end.and_then(|e| Real::sign(&e[k]));
        let crossed = matches!((before, after), (Some(b), Some(a)) if a == -b);
        for i in 0..n {
            // the side before the step: from x0's sign of x_k (unknown: either order)
            let di = match before {
                Some(-1) => d[i].clone(),
                Some(1) => -d[i].clone(),
                _ => d[i].clone().hull(&-d[i].clone()),
            };
            let di = if crossed { di } else { di.hull(&I::zero()) };
            total[lay.s2(i)] = total[lay.s2(i)].clone() + di;
        }
    }
    Some(total)
}

/// (Df₋ − Df₊)·(2S̃τ′ + f̃τ′²) over `y` for the kink k (− the side x_k < 0): the variational
/// outputs Ṡ = D_x f·S + D_u f of the tape evaluated at S := a and S := 0 give
/// Df·(a, b) = (Ṡ(a) − Ṡ(0)) + b·Ṡ(0).
fn jump_of<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    lay: SecondOrder,
    y: &[I; N],
    f: &[I],
    k: usize,
) -> Vec<I> {
    let n = lay.n;
    let tp = -(y[lay.s(k)].clone()) / f[k].clone();
    let a: Vec<I> = (0..n)
        .map(|i| {
            y[lay.s(i)].clone() * tp.clone() * I::from_int(2)
                + f[i].clone() * tp.clone() * tp.clone()
        })
        .collect();
    let b = tp.clone() * I::from_int(2);
    let s_dot = |side: i8, s: Option<&[I]>| -> Vec<I> {
        let mut z = y.clone();
        for i in 0..n {
            z[lay.s(i)] = s.map_or_else(I::zero, |a| a[i].clone());
        }
        let mut sd = [0i8; N];
        sd[k] = side;
        let o = tape.eval_on(&z, &sd);
        (0..n).map(|i| o[lay.s(i)].clone()).collect()
    };
    let df = |side: i8| -> Vec<I> {
        let (sa, s0) = (s_dot(side, Some(&a)), s_dot(side, None));
        (0..n)
            .map(|i| (sa[i].clone() - s0[i].clone()) + b.clone() * s0[i].clone())
            .collect()
    };
    let (minus, plus) = (df(-1), df(1));
    (0..n).map(|i| minus[i].clone() - plus[i].clone()).collect()
}

/// `jump_of` (ΔS₂ at a kink) for a component k of [`Tape::sign_jumps`]: the tape also takes
/// non-analytic powers of x_k (eq:BWHCL's |Z|^(p−1)Z), which are not continued across x_k = 0,
/// so the jump is evaluated where the members cross, on the box `y` with x_k = 0 exactly: there
/// each side's D_x f is the one-sided limit (sgn x_k := ±1, the powers of x_k at 0 the same on
/// both sides).
pub fn sign_jump_at_zero<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    lay: SecondOrder,
    y: &[I; N],
    k: usize,
) -> Vec<I> {
    let mut at = y.clone();
    at[k] = I::zero();
    let f = tape.eval(&at);
    jump_of(tape, lay, &at, &f, k)
}

/// The displacement's parts over the a-priori box `y` for the step of length τ1 ≥ h_lo
/// (an enclosure `tau1`) from `x`: (g(Y), Σ q_i, Σ hull(0, q_i)), or `None` when no power may
/// be singular in `y`, the field is not affine in them, a singular power's operand has a rate
/// that may vanish or holds a singular power, or an exponent is ≤ −1.
#[allow(clippy::type_complexity)]
fn split<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    y: &[I; N],
    x: &[I; N],
    tau1: &I,
) -> Option<([I; N], [I; N], [I; N])> {
    let h_lo = tau1.lo();
    let mut powers = tape.negative_powers();
    // only the powers whose operand may reach 0 are singular on the step
    powers.retain(|p| y[p.var].lo() <= 0.0 && y[p.var].hi() >= 0.0);
    if powers.is_empty() {
        return None;
    }
    let ids: Vec<usize> = powers.iter().map(|p| p.node).collect();
    let degs = tape.field_degrees(&ids);
    if degs.contains(&Degree::Other) {
        return None;
    }
    let side = [0i8; N];
    let zeros: Vec<(usize, I)> = ids.iter().map(|&i| (i, I::zero())).collect();
    let g = tape.field_replacing(y, &side, &zeros);
    // (node, the power's average over the step): one item per power, two for a signed
    // power of known rate (its positive and negative parts, each a nonnegative weight)
    let mut items: Vec<(usize, I)> = Vec::new();
    for p in &powers {
        // the operand's rate: free of the singular powers, of one sign
        if degs[p.var] != Degree::Free {
            return None;
        }
        let rate = &g[p.var];
        let m = if rate.lo() > 0.0 {
            rate.lo()
        } else if rate.hi() < 0.0 {
            -rate.hi()
        } else {
            return None;
        };
        let r1 = p.r.clone() + I::one();
        if r1.lo().is_nan() || r1.lo() <= 0.0 {
            return None;
        }
        if rate.lo() == rate.hi() && m == 1.0 {
            // w(τ) = w(0) ± τ exactly (the crossing component as the independent variable,
            // [`super::crossing`]): the integrals themselves, K(w) = w^(r+1)/(r+1) on each
            // side of 0 over the traversed range [l, u]
            let w1 = x[p.var].clone() + rate.clone() * tau1.clone();
            let (l, u) = if rate.lo() > 0.0 {
                (x[p.var].clone(), w1)
            } else {
                (w1, x[p.var].clone())
            };
            let pos = |v: &I| I::from_bounds(v.lo().max(0.0), v.hi().max(0.0));
            let k = |v: I| Real::apow(&v, &r1) / r1.clone();
            let plus = (k(pos(&u)?) - k(pos(&l)?)).nonneg();
            let minus = (k(pos(&-l)?) - k(pos(&-u)?)).nonneg();
            let inv = I::one() / tau1.clone();
            if p.signed {
                items.push((p.node, plus * inv.clone()));
                items.push((p.node, -(minus * inv)));
            } else {
                items.push((p.node, (plus + minus) * inv));
            }
            continue;
        }
        let (a, b) = (
            I::from_exact_f64(y[p.var].lo().abs()),
            I::from_exact_f64(y[p.var].hi().abs()),
        );
        let integral = (Real::apow(&a, &r1) + Real::apow(&b, &r1))
            / (r1 * I::from_exact_f64(m) * I::from_exact_f64(h_lo));
        let avg = integral.hi();
        if !(avg.is_finite() && avg >= 0.0) {
            return None;
        }
        items.push((
            p.node,
            I::from_bounds(if p.signed { -avg } else { 0.0 }, avg)?,
        ));
    }
    let mut d: [I; N] = std::array::from_fn(|_| I::zero());
    let mut dh: [I; N] = std::array::from_fn(|_| I::zero());
    for (node, v) in items {
        let repl: Vec<(usize, I)> = ids
            .iter()
            .map(|&i| (i, if i == node { v.clone() } else { I::zero() }))
            .collect();
        let fs = tape.field_replacing(y, &side, &repl);
        for c in 0..N {
            if degs[c] == Degree::Affine {
                let q = fs[c].clone() - g[c].clone();
                dh[c] = dh[c].clone() + q.hull(&I::zero());
                d[c] = d[c].clone() + q;
            }
        }
    }
    let ok = |x: &[I; N]| x.iter().all(|c| c.is_finite() && !c.is_empty());
    (ok(&g) && ok(&d) && ok(&dh)).then_some((g, d, dh))
}

/// The low-order step from (t0, X) to the double t1 across integrable singular terms (module
/// doc), with the kink's jump of S₂ where the tape is a second variational system. `None`
/// when no a-priori box validates (or the terms are not of that kind).
pub fn step<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    t0: f64,
    x: &[I; N],
    t1: f64,
) -> Option<StepOut<N, I>> {
    if !(t1 > t0 && t1.is_finite()) {
        return None;
    }
    let tau1 = tau(&I::from_exact_f64(t1), t0);
    let (s, h_lo): (I, f64) = (span(tau1.hi()), tau1.lo());
    if h_lo.is_nan() || h_lo <= 0.0 {
        return None;
    }
    let params = tape.params();
    let mut y = keep_params(inflate(x, 1.0, 1e-300), x, params);
    for _ in 0..12 {
        let Some((g, d, dh)) = split(tape, &y, x, &tau1) else {
            // grow the guess along the regular part of the field (the singular powers at 0)
            let zeros: Vec<(usize, I)> = tape
                .negative_powers()
                .iter()
                .map(|p| (p.node, I::zero()))
                .collect();
            let f = tape.field_replacing(&y, &[0; N], &zeros);
            if !f.iter().all(|c| c.is_finite() && !c.is_empty()) {
                return None;
            }
            let yn: [I; N] = std::array::from_fn(|i| x[i].clone() + s.clone() * f[i].clone());
            let grown: [I; N] = std::array::from_fn(|i| y[i].hull(&yn[i]));
            y = keep_params(inflate(&grown, 0.5, 1e-300), x, params);
            continue;
        };
        let jump = kink_jump(tape, x, &y, None);
        let ynew: [I; N] = std::array::from_fn(|i| {
            let v = x[i].clone() + s.clone() * g[i].clone() + tau1.clone() * dh[i].clone();
            match &jump {
                Some(j) => v + j[i].clone(),
                None => v,
            }
        });
        if ynew.iter().all(|c| c.is_finite() && !c.is_empty()) && subset(&ynew, &y, params) {
            // (no intersection with an evaluation over ynew: its singular powers may differ)
            let mut x1: [I; N] = std::array::from_fn(|i| {
                x[i].clone() + tau1.clone() * (g[i].clone() + d[i].clone())
            });
            let mut x0: [I; N] =
                std::array::from_fn(|i| x[i].clone() + tau1.clone() * dh[i].clone());
            if let Some(j) = kink_jump(tape, x, &ynew, Some(&x1)) {
                x1 = std::array::from_fn(|i| x1[i].clone() + j[i].clone());
            }
            if let Some(j) = kink_jump(tape, x, &ynew, None) {
                x0 = std::array::from_fn(|i| x0[i].clone() + j[i].clone());
            }
            return Some(StepOut {
                rep: None,
                piece: Piece::LowOrder {
                    t0,
                    t1,
                    x0,
                    slope: g,
                },
                x1,
                apriori: ynew,
            });
        }
        y = keep_params(inflate(&ynew, 0.25, 1e-300), x, params);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::Scalar;
    use crate::engines::taylor::op::Op;
    use crate::engines::taylor::rec::Rec;
    use inari::Interval;

    fn iv(lo: f64, hi: f64) -> Interval {
        Interval::try_from((lo, hi)).unwrap()
    }

    /// ẇ = c, ẏ = |w|^r (or sgn(w)|w|^r): one step from (w0, 0) to t1 crossing w = 0.
    fn toy(c: f64, r: f64, signed: bool, w0: f64, t1: f64) -> Option<StepOut<2>> {
        let rr = iv(r, r);
        let tape = Tape::<Interval, 2>::record(|s| {
            // (Spow(w, q) is |w|^(q−1)·w = sgn(w)|w|^q)
            let p = if signed {
                Scalar::<Interval>::spow(&s[0], &rr)
            } else {
                Scalar::<Interval>::apow(&s[0], &rr)
            };
            vec![Rec::constant(iv(c, c)) + s[0].scale(&iv(0.0, 0.0)), p]
        });
        step(&tape, 0.0, &[iv(w0, w0), iv(0.0, 0.0)], t1)
    }

    /// The exact ∫₀ʰ of |w0 + cτ|^r (sgn·|·|^r) for w0 < 0 < w0 + ch.
    fn exact(c: f64, r: f64, signed: bool, w0: f64, h: f64) -> f64 {
        let (a, b) = (-w0, w0 + c * h);
        let k = |x: f64| x.powf(r + 1.0) / (r + 1.0);
        (if signed { k(b) - k(a) } else { k(b) + k(a) }) / c
    }

    const CASES: [(f64, bool, f64, f64); 4] = [
        (-0.5, false, -0.25, 1.0),
        (-0.69, false, -0.5, 0.625),
        (-0.5, true, -0.75, 1.0),
        (-0.3, true, -0.125, 0.5),
    ];

    #[test]
    fn the_integral_of_a_negative_power_across_zero_is_enclosed_and_tight() {
        // rate 2: the crude bound ∫_{Y_w}|w|^r dw / min|ẇ|
        for (r, signed, w0, h) in CASES {
            let o = toy(2.0, r, signed, w0, h / 2.0)
                .unwrap_or_else(|| panic!("no step: r {r} signed {signed}"));
            let y1 = o.x1[1];
            let ex = exact(2.0, r, signed, w0, h / 2.0);
            assert!(y1.contains(ex), "r {r} signed {signed}: {y1:?} misses {ex}");
            // Y_w a little wider than the path: within 25 % of ∫|w|^r over the path ([0,
            // bound]; signed: [−bound, bound])
            let parts = exact(2.0, r, false, w0, h / 2.0);
            let factor = if signed { 2.5 } else { 1.25 };
            assert!(
                y1.wid() <= factor * parts,
                "r {r}: {y1:?} too wide against {parts}"
            );
            // an interior time: the piece holds the path at its middle too
            let tm = iv(0.25 * h, 0.25 * h);
            let ym = o.piece.enclose(&tm)[1];
            let exm = exact(2.0, r, signed, w0, 0.25 * h);
            if w0 + 0.5 * h > 0.0 {
                assert!(ym.contains(exm), "r {r}: the middle {ym:?} misses {exm}");
            }
        }
    }

    #[test]
    fn at_rate_one_the_integral_is_exact() {
        // rate ±1 exactly (the crossing component as the independent variable): K(w1) − K(w0)
        for (r, signed, w0, h) in CASES {
            let o = toy(1.0, r, signed, w0, h)
                .unwrap_or_else(|| panic!("no step: r {r} signed {signed}"));
            let y1 = o.x1[1];
            let ex = exact(1.0, r, signed, w0, h);
            assert!(y1.contains(ex), "r {r} signed {signed}: {y1:?} misses {ex}");
            assert!(y1.wid() <= 1e-12, "r {r} signed {signed}: {y1:?} not tight");
            let tm = iv(0.5 * h, 0.5 * h);
            let ym = o.piece.enclose(&tm)[1];
            let exm = exact(1.0, r, signed, w0, 0.5 * h);
            if w0 + 0.5 * h > 0.0 {
                assert!(ym.contains(exm), "r {r}: the middle {ym:?} misses {exm}");
            }
        }
        // from the other side, w decreasing
        let tape = Tape::<Interval, 2>::record(|s| {
            vec![
                Rec::constant(iv(-1.0, -1.0)) + s[0].scale(&iv(0.0, 0.0)),
                Scalar::<Interval>::spow(&s[0], &iv(-0.5, -0.5)),
            ]
        });
        let o = step(&tape, 0.0, &[iv(0.25, 0.25), iv(0.0, 0.0)], 1.0).expect("a step");
        // ∫ sgn(w)|w|^−½ from 0.25 down to −0.75: 2(√0.25 − √0.75)
        let ex = 2.0 * (0.5 - 0.75f64.sqrt());
        assert!(
            o.x1[1].contains(ex) && o.x1[1].wid() <= 1e-12,
            "{:?} against {ex}",
            o.x1[1]
        );
    }

    type H = crate::arith::jet::dual::Dual<crate::arith::jet::dual::Dual<Rec<Interval>, 1>, 1>;

    /// The second variational system of ẋ = |v|, v̇ = u (v(0) = −1, x(0) = 0) in u, on
    /// hyper-duals: (x, v, u, S_x, S_v, S₂x, S₂v). Closed form: v crosses 0 at 1/u; before,
    /// x = t − ut²/2 (∂²x/∂u² = 0), after, x = 1/u + ut²/2 − t (∂²x/∂u² = 2/u³). |v| taken by
    /// `abs` (v a kink) or as |v|^1 (a power: v is no kink, the tape takes sgn v,
    /// [`Tape::sign_jumps`]).
    fn kink_tape_of(abs: bool) -> Tape<Interval, 7> {
        toy_tape(|vv, one| {
            if abs {
                Real::abs(vv)
            } else {
                Real::apow(vv, one)
            }
        })
    }

    /// ẋ = g(v), v̇ = u as a second variational system in u (`g` given v and the constant 1).
    fn toy_tape(g: impl Fn(&H, &H) -> H) -> Tape<Interval, 7> {
        use crate::arith::jet::dual::Dual;
        let lay = SecondOrder { n: 2 };
        let mut params = [None; 7];
        params[lay.u()] = Some(iv(0.9, 1.1));
        let hyper = |a: Rec<Interval>, b: Rec<Interval>, d: Rec<Interval>| H {
            v: Dual {
                v: a,
                d: [b.clone()],
            },
            d: [Dual { v: b, d: [d] }],
        };
        let c = |x: f64| Rec::constant(iv(x, x));
        Tape::<Interval, 7>::record_with(params, |v| {
            let x = hyper(v[0].clone(), v[lay.s(0)].clone(), v[lay.s2(0)].clone());
            let vv = hyper(v[1].clone(), v[lay.s(1)].clone(), v[lay.s2(1)].clone());
            let u = hyper(v[lay.u()].clone(), c(1.0), c(0.0));
            let mag = g(&vv, &H::constant(Dual::constant(c(1.0))));
            let f = [mag + x * H::constant(Dual::constant(c(0.0))), u];
            let mut o: Vec<Rec<Interval>> = f.iter().map(|q| q.v.v.clone()).collect();
            o.push(c(0.0));
            o.extend(f.iter().map(|q| q.v.d[0].clone()));
            o.extend(f.iter().map(|q| q.d[0].d[0].clone()));
            o
        })
        .with_second_order(lay)
    }

    #[test]
    fn the_second_derivative_jumps_where_a_kink_is_crossed() {
        check_jump_across(&kink_tape_of(true));
    }

    /// The same flow with |v| as |v|^1 (SHC DSA's |Z|^n, n = 1): v is no kink, the jump comes
    /// from [`Tape::sign_jumps`], evaluated at v = 0.
    #[test]
    fn the_second_derivative_jumps_where_a_sign_taking_power_is_crossed() {
        let tape = kink_tape_of(false);
        assert!(tape.kinks().is_empty());
        assert_eq!(tape.sign_jumps().0, [1]);
        check_jump_across(&tape);
    }

    /// sgn v in a rate itself (the field jumps: no jump formula for S₂) is found; sgn v in
    /// the derivatives only (|v|^1) is not, and is a jump of S₂; sgn v in the second
    /// derivatives only (|v|·v: D_x f = 2|v| is continuous; the tape takes sgn v in D²f) is
    /// neither.
    #[test]
    fn signs_are_told_by_where_they_enter() {
        let abs1 = kink_tape_of(false);
        assert_eq!(abs1.sign_in_the_rates(2), None);
        assert_eq!(abs1.sign_jumps().0, [1]);
        assert_eq!(
            toy_tape(|vv, _| Real::sgn(vv)).sign_in_the_rates(2),
            Some(1)
        );
        let sq = toy_tape(|vv, one| Real::spow(vv, &(one.clone() + one.clone())));
        assert_eq!(sq.sign_in_the_rates(2), None);
        assert!(sq.sign_jumps().0.is_empty(), "{:?}", sq.sign_jumps());
    }

    /// A switch on an expression, |v − 1|, is found (its S₂ jump at v = 1 is carried by
    /// nothing); a switch on a state component, |v| or |v|^1, and an entire power, v², are not.
    #[test]
    fn a_switch_on_an_expression_is_found() {
        let shifted = toy_tape(|vv, one| Real::abs(&(vv.clone() - one.clone())));
        let i = shifted.switch_on_an_expression().expect("|v − 1| found");
        // |g| or its derivative sgn g, on the node g = v − 1
        match shifted.ops()[i] {
            Op::Abs(a) | Op::Sign(a) => assert!(!matches!(shifted.ops()[a], Op::Var(_))),
            ref op => panic!("{op:?}"),
        }
        let signed = toy_tape(|vv, one| Real::sgn(&(vv.clone() + one.clone())));
        assert!(signed.switch_on_an_expression().is_some());
        let powered = toy_tape(|vv, one| {
            Real::apow(
                &(vv.clone() + one.clone()),
                &(one.clone() + one.clone() + one.clone()),
            )
        });
        assert!(powered.switch_on_an_expression().is_some());
        for tape in [
            kink_tape_of(true),
            kink_tape_of(false),
            toy_tape(|vv, one| Real::apow(vv, &(one.clone() + one.clone()))),
            toy_tape(|vv, one| {
                Real::apow(&(vv.clone() + one.clone()), &(one.clone() + one.clone()))
            }),
        ] {
            assert_eq!(tape.switch_on_an_expression(), None, "{:?}", tape.ops());
        }
    }

    /// The engine refuses a second variational system that switches on an expression, with
    /// its reason, before any step (the toy has no separation outputs to run further; the
    /// shipped models' second-order bands, which switch on state components, run in
    /// `tests/suite/curvature.rs`).
    #[test]
    fn a_second_order_run_switching_on_an_expression_is_refused() {
        use crate::engines::taylor::{SWITCH_ON_AN_EXPRESSION, TaylorOptions, integrate_system};
        let x0 = |tape: &Tape<Interval, 7>| {
            let mut x: [Interval; 7] = std::array::from_fn(|_| iv(0.0, 0.0));
            x[1] = iv(-1.0, -1.0);
            x[SecondOrder { n: 2 }.u()] = iv(0.99, 1.01);
            assert_eq!(tape.second_order().map(|l| l.n), Some(2));
            x
        };
        let opts = TaylorOptions {
            horizon: 0.5,
            ..TaylorOptions::default()
        };
        let shifted = toy_tape(|vv, one| Real::abs(&(vv.clone() - one.clone())));
        let err = integrate_system(&shifted, x0(&shifted), 2, &opts).expect_err("refused");
        assert_eq!(err.reason, SWITCH_ON_AN_EXPRESSION);
    }

    fn check_jump_across(tape: &Tape<Interval, 7>) {
        // the set at t0 = 0.95 for u ∈ [0.99, 1.01] (before the crossing at 1/u ∈ [0.990,
        // 1.0101]): x = t0 − ut0²/2, v = −1 + ut0, S = (−t0²/2, t0), S₂ = 0
        let (u, t0) = (iv(0.99, 1.01), iv(0.95, 0.95));
        let half_t0_sq = t0 * t0 / iv(2.0, 2.0);
        let x0 = [
            t0 - u * half_t0_sq,
            iv(-1.0, -1.0) + u * t0,
            u,
            -half_t0_sq,
            t0,
            iv(0.0, 0.0),
            iv(0.0, 0.0),
        ];
        let s2x = |t: f64, u: f64| if u * t > 1.0 { 2.0 / (u * u * u) } else { 0.0 };
        let us = [0.99, 0.995, 0.999, 1.001, 1.005, 1.01];
        // every member crosses by t = 1.05: ΔS₂ itself, S₂x = 2/u³ ∈ [1.94, 2.07]
        let all =
            crate::engines::taylor::step::low_order_to(tape, 0.95, &x0, 1.05).expect("a step");
        for &uu in &us {
            assert!(
                all.x1[5].contains(s2x(1.05, uu)),
                "{:?} misses u = {uu}",
                all.x1[5]
            );
        }
        assert!(
            !all.x1[5].contains(0.0),
            "{:?}: ΔS₂ itself, not hull(0, ΔS₂)",
            all.x1[5]
        );
        assert!(all.x1[5].wid() < 2.0, "{:?}", all.x1[5]);
        // by t = 1 only the members u > 1 have crossed: S₂x is 0 or 2/u³
        let some =
            crate::engines::taylor::step::low_order_to(tape, 0.95, &x0, 1.0).expect("a step");
        for &uu in &us {
            assert!(
                some.x1[5].contains(s2x(1.0, uu)),
                "{:?} misses u = {uu}",
                some.x1[5]
            );
        }
        // and at an interior time of the first step (t = 1), from its piece
        let mid = all.piece.enclose(&iv(1.0, 1.0));
        for &uu in &us {
            assert!(
                mid[5].contains(s2x(1.0, uu)),
                "{:?} misses u = {uu}",
                mid[5]
            );
        }
    }

    #[test]
    fn no_step_where_the_operand_may_stop_or_the_power_is_not_integrable() {
        // ẇ = w − 1/2 + … vanishes near w = 1/2 only; here the rate is 0 at w = 0: refused
        let tape = Tape::<Interval, 2>::record(|s| {
            vec![
                s[0].scale(&iv(1.0, 1.0)),
                Scalar::<Interval>::apow(&s[0], &iv(-0.5, -0.5)),
            ]
        });
        assert!(step(&tape, 0.0, &[iv(-0.25, -0.25), iv(0.0, 0.0)], 0.5).is_none());
        // r = −1: not integrable
        assert!(toy(2.0, -1.0, false, -0.25, 0.5).is_none());
        assert!(toy(1.0, -1.0, false, -0.25, 0.5).is_none());
    }

    #[test]
    fn the_field_must_be_affine_in_the_singular_powers() {
        let q = iv(-0.5, -0.5);
        let tape = Tape::<Interval, 3>::record(|s| {
            let p = Scalar::<Interval>::apow(&s[0], &q);
            vec![
                Rec::constant(iv(1.0, 1.0)) + s[0].scale(&iv(0.0, 0.0)),
                p.clone() * s[2].clone() + s[1].clone(),
                p.clone() * p,
            ]
        });
        let nodes: Vec<usize> = tape.negative_powers().iter().map(|p| p.node).collect();
        assert_eq!(nodes.len(), 1);
        assert_eq!(
            tape.field_degrees(&nodes),
            [Degree::Free, Degree::Affine, Degree::Other]
        );
        // a product of two: no step across w = 0
        let x = [iv(-0.25, -0.25), iv(0.0, 0.0), iv(1.0, 1.0)];
        assert!(step(&tape, 0.0, &x, 0.5).is_none());
    }
}
