//! The first step, from the start: two or more components at their branch point at once.
//!
//! Both nondimensional models start on their branch points: eq:BWSHCCM_nd at (X, Z, V) =
//! (0, 0, −1), eq:BWMCM_nd at (R, Y, Z, W) = (0, 0, 0, −1). Two switching components are 0 at
//! t = 0, so the crossing step ([`super::crossing_step`]), which takes one of them as the
//! independent variable and needs the others away from 0, does not apply; without this step
//! the engine leaves the start in ~25 Taylor steps that grow geometrically from 1e-7.
//!
//! **Variables.** Let w be a component with x_w(0) = 0 and σ = sign ẋ_w(0) ≠ 0 (X in SHC, Y in
//! Maxwell: ẋ_w = V or W = −1). With u = |x_w| ≥ 0 the independent variable, x_w = σu and
//!
//! ```text
//! t(u) = t₀ + ∫₀^u G_t,      G_t = σ/f_w(x),       (t₀ = 0 at the start, exactly)
//! ```
//!
//! Every other component j with x_j(0) = 0 and s_j = sign f_j(x(0)) ≠ 0 (Z in both models)
//! starts at 0 with u, and is written
//!
//! ```text
//! x_j = s_j·u·W_j,     W_j = s_j·A(G_j),     A(y)(u) = (1/u)∫₀^u y(s) ds,     G_j = σ f_j/f_w,
//! ```
//!
//! since x_j(u) = ∫₀^u G_j = u·A(G_j)(u); W_j(0) = |f_j/f_w|(x(0)) > 0, and W_j stays > 0 on the
//! step (checked). The powers of x_j are then exact products of a monomial and an analytic
//! function ([`Gts::factored`]): |x_j|^q = u^q W_j^q, |x_j|^(q−1)x_j = s_j u^q W_j^q. The
//! remaining components (V, W; Maxwell's R, which starts at 0 with Ṙ(0) = 0 and is the operand
//! of no power) are regular: y_j = x_j(0) + ∫₀^u G_j. A component that is at 0 inside a power
//! and fits neither form makes that power unbounded, and the step is refused.
//!
//! **The operator.** T(y, W, t) = (x(0) + ∫G, s·A(G), t₀ + ∫G_t), G evaluated on generalized
//! polynomials in u ([`super::puiseux`]). The mean A maps c·u^α to c·u^α/(α + 1) and keeps
//! the remainder interval ([`Gts::average`]).
//!
//! **Why T(S) ⊆ S encloses the solution.** Written for x_j = s_j·u·W_j instead of W_j, the
//! operator is the Picard operator x ↦ x(0) + ∫₀^u G(x) of the system in u: continuous and
//! compact on bounded sets (its images are Lipschitz with constant sup|G|), and the set
//! S′ = {(y, s·u·W): (y, W) ∈ S} (W continuous on (0, δ]) is closed, convex and bounded. So
//! T(S) ⊆ S (checked coefficientwise) gives a fixed point in S′ (Schauder), i.e. a solution
//! of the system with t(u) strictly increasing (f_w keeps its sign), i.e. a solution x(t) of
//! the model from x(0). It is the model's solution: any solution from x(0) has ẋ_w(0) ≠ 0, so
//! it is such a fixed point too, and two of them have |x_j| ≥ c·u (W_j > 0), where the
//! field's dependence on x_j is Lipschitz with constant ≤ C·u^(q−1) for the exponents q < 1
//! (Maxwell's p − 1), integrable on [0, δ]: Grönwall with that kernel makes them equal.
//!
//! **Exit.** At an exact double t₁ just below t(δ): bisection on t(u) brackets u* with
//! t(u*) = t₁ (`exit_parameter`, as for the crossings), and the state at t₁ is x_w = σu*,
//! x_j = s_j·u*·W_j(u*) (intersected with the expanded s_j·u·W_j at u*), y_j(u*).

use super::puiseux::{Basis, Ctx, Gts, bounded};
use super::{SingularOptions, exit_parameter, point, trace_sing, validate};
use crate::arith::{Enclosure, Real};
use crate::engines::taylor::step::{StepOut, low_order_to};
use crate::engines::taylor::tape::Tape;
use std::sync::Arc;

/// What each component is in the start step's variables.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Role {
    /// The independent variable: x_w = σu.
    Var,
    /// x_j = s·u·W_j, the unknown is W_j.
    Factored(i8),
    /// x_j = x_j(0) + ∫G_j.
    Regular,
}

/// The roles at the point `x0` (a box of exact points), or `None` when no switching component
/// is at 0 with a certain nonzero rate: (the variable's index w, σ, the roles).
fn roles<const N: usize, I: Enclosure>(
    tape: &Tape<I, N>,
    x0: &[I; N],
) -> Option<(usize, i8, [Role; N])> {
    if x0.iter().any(|c| !c.same(&c.inf_point())) {
        return None;
    }
    let f0 = tape.eval(x0);
    let rate_sign = |j: usize| x0[j].same(&I::zero()).then(|| Real::sign(&f0[j])).flatten();
    let w = tape
        .switching()
        .iter()
        .copied()
        .find(|&j| rate_sign(j).is_some())?;
    let sigma = rate_sign(w)?;
    let roles: [Role; N] = std::array::from_fn(|j| match (j == w, rate_sign(j)) {
        (true, _) => Role::Var,
        (false, Some(s)) => Role::Factored(s),
        (false, None) => Role::Regular,
    });
    // only at a branch point (a power's operand at 0): at kinks alone (|·|, e.g. p = n = 1)
    // the field continued from one side is analytic, and the Taylor steps' dense output is
    // finer than this step's low-order piece
    let branch = (0..N).any(|j| {
        roles[j] != Role::Regular && tape.switching().contains(&j) && !tape.kinks().contains(&j)
    });
    branch.then_some((w, sigma, roles))
}

/// The start step's operator T (see the module's documentation) on y = (the unknown of each
/// component by its role, then t); the variable's own slot stays 0.
#[allow(clippy::too_many_arguments)]
fn picard<const N: usize, I: Enclosure>(
    tape: &Tape<Gts<I>, N>,
    ctx: &Arc<Ctx<I>>,
    w: usize,
    sigma: i8,
    roles: &[Role; N],
    t0: f64,
    x0: &[I; N],
    y: &[Gts<I>],
) -> Option<Vec<Gts<I>>> {
    let x: [Gts<I>; N] = std::array::from_fn(|j| match roles[j] {
        Role::Var => Gts::variable(ctx, sigma),
        Role::Factored(s) => Gts::factored(ctx, s, y[j].in_ctx(ctx)),
        Role::Regular => y[j].in_ctx(ctx),
    });
    let f = tape.eval(&x);
    let dt = Gts::from_int(sigma as i64) / f[w].clone();
    if !dt.is_bounded() {
        return None;
    }
    let mut out = Vec::with_capacity(N + 1);
    for j in 0..N {
        let g = || f[j].clone() * dt.clone();
        let yj = match roles[j] {
            Role::Var => Gts::constant_in(ctx, I::zero()),
            Role::Factored(s) => g().average() * Gts::from_int(s as i64),
            Role::Regular => Gts::constant_in(ctx, x0[j].clone()) + g().integral(),
        };
        if !yj.is_bounded() {
            return None;
        }
        out.push(yj);
    }
    out.push(Gts::constant_in(ctx, point(t0)) + dt.integral());
    Some(out)
}

/// The flow of the point `x0` at `t0` (every component an exact double, two or more of them at
/// their branch point) up to an exact time t₁ < t(δ): (t₁, the state there), or `None` when
/// the expansions do not validate (see the module's documentation).
pub fn start_point<const N: usize, I: Enclosure>(
    gts_tape: &Tape<Gts<I>, N>,
    basis: &Arc<Basis<I>>,
    tape: &Tape<I, N>,
    t0: f64,
    x0: &[I; N],
    delta: f64,
    opts: &SingularOptions,
) -> Option<(f64, [I; N])> {
    let (w, sigma, roles) = roles(tape, x0)?;
    let ctx = Ctx::new(basis, delta)?;
    let f0 = tape.eval(x0);
    // the constants: W_j(0) = |f_j/f_w|, x_j(0), t₀
    let y0: Vec<Gts<I>> = (0..=N)
        .map(|j| {
            let c = if j == N {
                point(t0)
            } else {
                match roles[j] {
                    Role::Var => I::zero(),
                    Role::Factored(s) => {
                        f0[j].clone() / f0[w].clone()
                            * I::from_int(s as i64)
                            * I::from_int(sigma as i64)
                    }
                    Role::Regular => x0[j].clone(),
                }
            };
            Gts::constant_in(&ctx, c)
        })
        .collect();
    let schedule = (false, opts.start_iterations);
    let y = validate(y0, w, opts, opts.start_max_exp, schedule, true, |y, cut| {
        picard(gts_tape, &ctx.truncated(cut), w, sigma, &roles, t0, x0, y)
    });
    let Some(y) = y else {
        if trace_sing() {
            eprintln!("start: the expansions do not validate");
        }
        return None;
    };
    let t = &y[N];
    let t_end = t.eval(&point(delta)).lo();
    let t1 = t_end.next_down();
    if t1.is_nan() || t1 <= t0 {
        return None;
    }
    let ustar = exit_parameter(t, t1, delta)?;
    let mut x1: [I; N] = std::array::from_fn(|_| I::zero());
    for j in 0..N {
        x1[j] = match roles[j] {
            Role::Var => ustar.clone() * I::from_int(sigma as i64),
            Role::Factored(s) => {
                let factored = ustar.clone() * y[j].eval(&ustar) * I::from_int(s as i64);
                let expanded = Gts::factored(&ctx, s, y[j].clone()).eval(&ustar);
                factored.intersection(&expanded)
            }
            Role::Regular => y[j].eval(&ustar),
        };
        if !bounded(&x1[j]) {
            return None;
        }
    }
    if trace_sing() {
        let rems: Vec<String> = y
            .iter()
            .map(|g| format!("{:.1e}/{}", g.remainder().wid_f64(), g.terms().len()))
            .collect();
        let cw = y[N]
            .terms()
            .iter()
            .map(|(_, c)| c.wid_f64())
            .fold(0.0, f64::max);
        eprintln!(
            "start: t1 {t1} δ {delta:.3e} t(δ) width {:.1e}, t's widest coefficient {cw:.1e}, u* width {:.1e}; roles {roles:?}; remainders/terms {}",
            t.eval(&point(delta)).wid_f64(),
            ustar.wid_f64(),
            rems.join(" ")
        );
    }
    Some((t1, x1))
}

/// The start step as the engine's loop takes it: the state at t₁ by [`start_point`], and a
/// low-order piece x₀ + τ·f(Y) over [t₀, t₁] for the event scan and the dense output (as
/// [`super::crossing_step`]; the set is a point, so the mean-value form has no Jacobian term).
/// `None` when either cannot be proved.
pub fn start_step<const N: usize, I: Enclosure>(
    gts_tape: &Tape<Gts<I>, N>,
    basis: &Arc<Basis<I>>,
    tape: &Tape<I, N>,
    t0: f64,
    x0: &[I; N],
    delta: f64,
    opts: &SingularOptions,
) -> Option<StepOut<N, I>> {
    let (t1, z) = start_point(gts_tape, basis, tape, t0, x0, delta, opts)?;
    // (the piece ends at t₁ itself, where z encloses the state)
    let lo = low_order_to(tape, t0, x0, t1)?;
    let x1: [I; N] = std::array::from_fn(|i| z[i].intersection(&lo.x1[i]));
    if x1.iter().any(|c| c.is_empty()) {
        return None;
    }
    Some(StepOut {
        piece: lo.piece,
        x1,
        apriori: lo.apriori,
        rep: None,
    })
}
