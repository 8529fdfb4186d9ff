//! Across a branch point in one step: the crossing variable as the independent variable.
//!
//! Near a time t_c where one switching component w (Z of eq:BWSHCCM_nd, Y or Z of
//! eq:BWMCM_nd) passes through 0 with ẇ ≠ 0, every other component is analytic in the state and
//! the field's only singular terms are powers of w: |w|^(q−1)w and |w|^q with the model's
//! exponents q (n, p, p − 1, …). With w = σu (σ = ±1 the side, u = |w| ≥ 0) as the independent
//! variable, the remaining components y and the time t solve
//!
//! ```text
//! dy/du = σ f_y(y, σu) / f_w(y, σu),      dt/du = σ / f_w(y, σu),
//! ```
//!
//! whose right-hand side is analytic in y and a combination of u, u^n, u^p, … in u. The solution
//! is therefore a convergent series in the powers u^α, α = k₀ + k₁q₁ + k₂q₂ + … (Puiseux-type;
//! [`puiseux`]), which the Taylor steps in t cannot represent: they shrink geometrically towards
//! t_c (about 40 steps on each side for the Table 1 sets, the last ~1e-8 long) and cross it
//! with a low-order step whose width grows like h^(1+a).
//!
//! The step, from a box x₀ at t₀ with w(t₀) = σ_A u₀ (u₀ ∈ U₀ > 0) moving towards 0:
//! 1. **Approach side** u ∈ [0, δ_A], δ_A = sup U₀: the fixed point of
//!    T(y)(u) = y₀ + I(y)(u) − I(y)(U₀), I(y)(u) = ∫₀^u G(y(s), s) ds,
//!    over generalized polynomials with remainder. A candidate set S (coefficient intervals and
//!    a remainder) with T(S) ⊆ S contains the solution (Schauder; G is Lipschitz in y where
//!    f_w ≠ 0 and the other switching components keep their signs, which the interval
//!    operations check: otherwise they return unbounded values and the step is refused).
//!    At u = 0 it gives the crossing state and t_c.
//! 2. **Departure side** w = σ_B u, σ_B = −σ_A, u ∈ [0, δ_B]: T(y)(u) = y(t_c) + I(y)(u), the same
//!    way.
//! 3. **Exit at an exact time** t₁ (a double between t_c and t(δ_B)): t(u) is increasing, so
//!    bisection on its enclosure brackets the u* with t(u*) = t₁, and the state there is
//!    y([u_lo, u_hi]).
//!
//! At the start two components are at their branch points at once; [`start`] leaves it in one
//! step with the second one factored as s·u·W.
//!
//! The step is given to the rest of the engine as a low-order piece x₀ + τ·f(Y) over [t₀, t₁]
//! (Y the hull of both sides' ranges, which contains the whole path), so that the event scan
//! and dense output need nothing new; the step is taken only when that piece clears the
//! separation condition.

pub mod puiseux;
pub mod start;

use super::affine::AffineSet;
use super::flow::tau;
use super::step::{StepOut, low_order_to};
use super::tape::Tape;
use crate::arith::jet::dual::Dual;
use crate::arith::{Enclosure, Real};
use puiseux::{Basis, Ctx, Gts, bounded};
use std::sync::Arc;

/// Whether BWCL_TRACE_SING is set: the singular steps then print what they try to stderr (read
/// once per process, not at every step).
fn trace_sing() -> bool {
    static TRACE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *TRACE.get_or_init(|| std::env::var_os("BWCL_TRACE_SING").is_some())
}

/// The exact double x as a point of `I`.
fn point<I: Enclosure>(x: f64) -> I {
    I::from_exact_f64(x)
}

/// Tunables of the singular step.
#[derive(Clone, Debug)]
pub struct SingularOptions {
    /// Exponent cut-off M of the expansions.
    pub max_exp: f64,
    /// Plain Picard iterations of a crossing's sides before the validation, in the full
    /// arithmetic (each fixes the terms of at least one more order), after the truncated ones.
    pub iterations: usize,
    /// Precede them by plain iterations cut off at exponents 1, 2, …, ⌈M⌉ − 1 (see
    /// `validate`).
    pub truncated_iterations: bool,
    /// Plain iterations of the start step ([`start`]), all in the full arithmetic (truncated
    /// ones measured no faster there: its factored components' widths need the full
    /// iterations to settle, 0.33 ms against 0.38–0.44 ms with 1–3 full ones after them).
    pub start_iterations: usize,
    /// Picard images taken after the validation (each sheds most of the candidate's inflation).
    pub tighten: usize,
    /// Exponent cut-off of the start step's expansions ([`start`]).
    pub start_max_exp: f64,
    /// How far the start step goes in its variable u = |x_w| ([`start`]).
    pub start_delta: f64,
    /// A crossing is tried once the branch point is this near (the time for its component to
    /// reach 0 at its fastest): the domain δ of the expansions is about this times |ẇ|, their
    /// remainder ∝ δ^M.
    pub near: f64,
    /// Also cross kinks (components inside |·| or sgn only) by the step: at f64 precision a
    /// low-order step crosses them within the tolerance; beyond it the shortest such step (an
    /// ulp of t) adds ≈ ulp(t)² > tol.
    pub kinks: bool,
    /// The departure side's domain is at least this long in u (a kink is usually approached
    /// to within an ulp of t by a cut Taylor step: δ_A ≈ 1e-16, and t(δ_A) − t_c would hold
    /// no double).
    pub depart_min: f64,
    /// Candidates tried before the validation gives up (each the last image's hull with the
    /// candidate, inflated).
    pub tries: usize,
    /// The fixed-point candidates' coefficients are widened by this of their magnitude (a few
    /// ulps of the coefficients' type).
    pub inflate_rel: f64,
}

/// Measured on SHC DSS, v0 = 1 (30 runs, one thread, 2026-11-23): M = 6 with 3
/// iterations and one tightening image took 17.5 ms per CoR (M = 5: 19.9 ms, M = 8: 27.7 ms),
/// e 1.83e-13 wide.
///
/// The start step (measured on the 28 Table 1 cases, `cargo run --release --features bench --example
/// singular`, 3 interleaved repetitions, 2026-11-25): δ = 5e-3 with M = 6 took a median 0.942
/// of the time without it (pieces −17 … −24 per case, SHC DSS v0 = 1: 134 → 112); δ = 1e-2,
/// M = 8: 1.001; δ = 2e-2, M = 8: 0.993 (−27 pieces, refused on SHC DSA v0 = 5); δ = 3e-2,
/// M = 10: 1.143. At M = 6 the state's width after the step is 3.3e-16 at δ = 2e-3, 1.0e-15
/// at 5e-3, 4.4e-14 at 1e-2 (the remainder ∝ δ^M); the start step costs ≈ 1 ms at M = 6
/// (7 evaluations of the field on generalized polynomials), ≈ 12 Taylor pieces.
///
/// Measured again once the steps got cheaper (2026-11-26: the binomial series' partial sums
/// cut at M − k·α_min, negative powers without MPFR, the exit parameter placed directly): on
/// SHC DSS v0 = 1 the start step takes 0.32–0.41 ms and the crossing 0.82–0.88 ms (were 0.60
/// and 1.26 ms). With them, δ = 2e-2, M = 8 for the start still gains nothing (per-case time
/// ratio 1.001 over 3 alternating runs, 4–5 pieces fewer, e 3–10 % narrower on most cases
/// but refused on SHC DSA v0 = 5 and 1.34× wider on Maxwell DSS v0 = 0.1), nor do larger
/// trigger distances for the crossings (near 4e-3, 8e-3 with M = 6 or 7: 5–20 % slower; at
/// M = 6 the remainder reaches 8e-15 and the step is refused once).
impl Default for SingularOptions {
    fn default() -> Self {
        Self {
            max_exp: 6.0,
            iterations: 1,
            truncated_iterations: true,
            start_iterations: 3,
            tighten: 1,
            start_max_exp: 6.0,
            start_delta: 5e-3,
            near: 2e-3,
            inflate_rel: 1e-15,
            tries: 8,
            kinks: false,
            depart_min: 0.0,
        }
    }
}

impl SingularOptions {
    /// The tunables for intervals whose ends have machine epsilon `eps`, the engine's
    /// tolerance per step `tol`: the defaults at f64 precision (eps ≥ 2⁻⁵²); at higher
    /// precision the remainder ∝ δ^M must fall below `tol` (see `high_precision`).
    pub fn at_precision(eps: f64, tol: f64) -> Self {
        if eps >= f64::EPSILON {
            Self::default()
        } else {
            high_precision(eps, tol)
        }
    }
}

/// The smallest cut-off M beyond f64 precision.
const HIGH_PRECISION_M: f64 = 7.0;
/// The trigger distance is at least 10^−`NEAR_DECADES`: beyond ≈ 50 digits M grows instead
/// (see [`high_precision`]).
const NEAR_DECADES: f64 = 7.0;

/// The tunables at a precision beyond f64 (machine epsilon `eps`, tolerance `tol` per step):
/// M = max(7, ⌈−log₁₀(tol)/7⌉) and the trigger distance near = tol^(1/M) (so that δ^M ≈ tol:
/// the expansions' remainder is ∝ δ^M with δ ≈ |ẇ|·near), the start step on the same δ and M.
/// Up to ≈ 46 digits (tol ≥ 10⁻⁴⁹) this is M = 7 with near ≥ 10⁻⁷; beyond, M grows so that
/// near stays ≈ 10⁻⁷ (60 digits: M = 9).
///
/// Measured at 60 digits (tol 1e-63, 256 bits; the four Table 1 sets at v0 = 1, one thread,
/// 2026-11-25, load < 1): M = 7 put near at 10⁻⁹ (clamped to 10⁻⁸), where the start step ends
/// 2.8e-58 wide, far above its limit (cross_tol 10⁻⁶⁴), and the low-order steps cannot cross;
/// M = 9, near 1e-7: 5.3–8.7 s (376–441 pieces, e ≤ 6.3e-63 wide); M = 10, 3e-7: 4.8–9.7 s;
/// M = 12, 1e-6: 4.7–13.4 s; M = 14, 3e-6: 5.3–28.9 s (the basis grows like M²).
///
/// Measured on SHC DSS, v0 = 1, 30 digits (128 bits, tol 1e-33; one thread, load ≈ 3 on 2
/// CPUs, 2026-11-25): near 1e-3 with M = 12 crossed Z = 0 in 3.7 s (262 exponents, 3 + 7
/// iterations); near 3e-5, M = 9: 0.79 s; near 1e-5, M = 8: 0.39 s; near 1e-5, M = 7: 0.18 s,
/// whole CoR 1.19 s, e 1.59e-32 wide (M = 9: 1.43e-32). A nearer trigger costs Taylor steps
/// (287 pieces at 1e-5, 271 at 3e-5) but each of them much less than the larger basis.
/// Iterations ⌈M/2⌉ + 1 before the validation: the coefficients of exponent up to ~M must have
/// settled, or the candidates grow (measured on the Hertz pair, M = 12: 3 iterations left
/// coefficients 1.5 wide, 6 settled them). Up to 24 candidates (8 were too few at 128 bits:
/// the start validated at candidate 9–12); the inflation a few ulps of the precision.
fn high_precision(eps: f64, tol: f64) -> SingularOptions {
    let m = HIGH_PRECISION_M.max((-tol.log10() / NEAR_DECADES).ceil());
    let near = tol.powf(1.0 / m).clamp(1e-8, 1e-3);
    SingularOptions {
        max_exp: m,
        iterations: (m / 2.0).ceil() as usize + 1,
        truncated_iterations: true,
        start_iterations: (m / 2.0).ceil() as usize + 1,
        tighten: 2,
        start_max_exp: m,
        start_delta: near,
        near,
        tries: 24,
        kinks: true,
        depart_min: 1e-12,
        inflate_rel: 1e-15 * (eps / f64::EPSILON),
    }
}

/// The tape over generalized polynomials and the exponents of its powers, made once per run.
pub struct SingularTape<const N: usize, I: Enclosure> {
    tape: Tape<Gts<I>, N>,
    basis: Arc<Basis<I>>,
}

impl<const N: usize, I: Enclosure> SingularTape<N, I> {
    /// `None` when the model has powers with a variable exponent (not expanded).
    pub fn of(tape: &Tape<I, N>, opts: &SingularOptions) -> Option<Self> {
        if tape.has_variable_exponents() {
            return None;
        }
        let gens: Vec<I> = tape
            .power_exponents()
            .into_iter()
            .filter(|q| q.lo() > 0.0)
            .collect();
        let basis = Basis::cached(&gens, opts.max_exp)?;
        if trace_sing() {
            eprintln!(
                "singular basis: generators {gens:?}, {} exponents up to M",
                basis.len()
            );
        }
        Some(Self {
            tape: tape.map(|c| Gts::constant(c.clone())),
            basis,
        })
    }
}

/// Where the fixed point's constant comes from.
enum Start<'a, I> {
    /// y(u₀) = y₀ for u₀ ∈ U₀ (the approach side).
    At(&'a [I], I),
    /// y(0) = y_c (the departure side).
    Zero(&'a [I]),
}

/// y = (the components other than w, then t) as generalized polynomials on one side.
struct Side<I: Enclosure> {
    y: Vec<Gts<I>>,
}

/// The Picard operator of one side: T(y) = c + I(y) (see the module's documentation).
fn picard<const N: usize, I: Enclosure>(
    st: &SingularTape<N, I>,
    ctx: &Arc<Ctx<I>>,
    sigma: i8,
    w: usize,
    y: &[Gts<I>],
    start: &Start<I>,
) -> Option<Vec<Gts<I>>> {
    let x: [Gts<I>; N] = std::array::from_fn(|j| {
        if j == w {
            Gts::variable(ctx, sigma)
        } else {
            y[j].in_ctx(ctx)
        }
    });
    let f = st.tape.eval(&x);
    let dt = Gts::from_int(sigma as i64) / f[w].clone();
    if !dt.is_bounded() {
        return None;
    }
    // u₀'s powers once for the N constants (Gts::eval would make them for each)
    let pw = match start {
        Start::At(_, u0) => ctx.powers(u0, st.basis.len().saturating_sub(1)),
        Start::Zero(_) => Vec::new(),
    };
    let mut out = Vec::with_capacity(N + 1);
    for j in 0..=N {
        if j == w {
            out.push(Gts::constant_in(ctx, I::zero()));
            continue;
        }
        let g = if j == N {
            dt.clone()
        } else {
            f[j].clone() * dt.clone()
        };
        let i = g.integral();
        let c = match start {
            Start::At(y0, _) => y0[j].clone() - i.eval_with(&pw),
            Start::Zero(yc) => yc[j].clone(),
        };
        let yj = Gts::constant_in(ctx, c) + i;
        if !yj.is_bounded() {
            return None;
        }
        out.push(yj);
    }
    Some(out)
}

/// The validated solution of one side, or `None`.
fn solve_side<const N: usize, I: Enclosure>(
    st: &SingularTape<N, I>,
    ctx: &Arc<Ctx<I>>,
    sigma: i8,
    w: usize,
    start: Start<I>,
    opts: &SingularOptions,
) -> Option<Side<I>> {
    let c: Vec<I> = match &start {
        Start::At(y0, _) | Start::Zero(y0) => y0.to_vec(),
    };
    let y: Vec<Gts<I>> = c
        .iter()
        .map(|ci| Gts::constant_in(ctx, ci.clone()))
        .collect();
    // the constants: y_c on the departure side, T gives them again (keeping them thin in the
    // candidate spares two candidates there; on the approach side they change and are widened)
    let schedule = (opts.truncated_iterations, opts.iterations);
    let y = validate(y, w, opts, opts.max_exp, schedule, true, |y, cut| {
        picard(st, &ctx.truncated(cut), sigma, w, y, &start)
    })?;
    Some(Side { y })
}

/// A validated fixed point of the Picard-type operator `op`: plain images of `y`, then
/// candidates S (the last image inflated) until T(S) ⊆ S coefficientwise in every component
/// but `skip` (every term of either, a missing one 0, the remainder, on one basis and domain:
/// [`Gts::subset_of`]), then `tighten` more images. The solution is in T(S) and in each further image
/// (the fixed-point argument of the caller's operator); `None` when no candidate validates in
/// `tries` tries.
///
/// `op(y, cut)` is the operator in the arithmetic cut off at exponent `cut` ([`Ctx::truncated`];
/// ∞: the basis's M). The plain images fix the terms one unit of exponent further each (the
/// integral raises every exponent by 1, and the field's term of exponent α depends on the
/// terms up to α only), so with `truncated` (the schedule's first entry) they are first taken
/// cut off at 1, 2, …, ⌈M⌉ − 1 — each on the terms it can fix, cheap where few exponents lie
/// below the cut — then as many as the schedule's second entry in the full arithmetic, as are
/// the candidates and the tightening images: the validation itself never uses a truncated
/// context (a truncated image would be as sound, only wider). Measured on the 28 Table 1
/// cases (2026-11-26): the crossings' two sides validate at the first candidate in 120 of 168
/// sides (at the third before: 3 full iterations, 3 candidates), a crossing 1.14 → 0.85 ms.
///
/// With `keep_constants`, a constant coefficient that the last iteration left unchanged is not
/// widened in the candidate (the start's x_j(0), and W_j(0) computed from them: T gives them
/// again, while widening them widens their images by the dependency of interval arithmetic,
/// e.g. V/V — measured at the start, SHC DSS: 6 failed candidates before, 2 after).
#[allow(clippy::too_many_arguments)]
fn validate<I: Enclosure>(
    mut y: Vec<Gts<I>>,
    skip: usize,
    opts: &SingularOptions,
    max_exp: f64,
    (truncated, iterations): (bool, usize),
    keep_constants: bool,
    op_cut: impl Fn(&[Gts<I>], f64) -> Option<Vec<Gts<I>>>,
) -> Option<Vec<Gts<I>>> {
    let op = |y: &[Gts<I>]| op_cut(y, f64::INFINITY);
    let mut same_c0 = vec![false; y.len()];
    let cuts: Vec<f64> = if truncated {
        (1..)
            .map(|k| k as f64)
            .take_while(|&m| m < max_exp)
            .collect()
    } else {
        Vec::new()
    };
    for (_it, cut) in cuts
        .into_iter()
        .chain(std::iter::repeat_n(f64::INFINITY, iterations))
        .enumerate()
    {
        let y1 = op_cut(&y, cut);
        if y1.is_none() && trace_sing() {
            eprintln!("validate: the image of iteration {_it} is unbounded");
        }
        // a truncated image only prepares the guess: without it the full ones go on
        let y1 = y1.or_else(|| cut.is_finite().then(|| y.clone()))?;
        for (j, (a, b)) in y1.iter().zip(&y).enumerate() {
            same_c0[j] = keep_constants && a.c0().same(&b.c0());
        }
        y = y1;
    }
    // T(S) ⊆ S for an inflated candidate S
    let mut s: Vec<Gts<I>> = y
        .iter()
        .zip(&same_c0)
        .map(|(g, &same)| {
            let s = g.inflate(0.5, opts.inflate_rel, 1e-300);
            if same { s.with_constant(g.c0()) } else { s }
        })
        .collect();
    for _try in 0..opts.tries {
        let ts = op(&s);
        if ts.is_none() && trace_sing() {
            eprintln!("validate: the image of candidate {_try} is unbounded");
        }
        let ts = ts?;
        if ts
            .iter()
            .zip(&s)
            .enumerate()
            .all(|(j, (a, b))| j == skip || a.subset_of(b))
        {
            // T(S) ⊆ S: the solution is in T(S), and in every further image (T contracts by
            // about δ·Lip: each image sheds most of the candidate's inflation)
            let mut y = ts;
            for _ in 0..opts.tighten {
                y = op(&y)?;
            }
            if trace_sing() {
                eprintln!("validate: T(S) ⊆ S at candidate {_try}");
            }
            return Some(y);
        }
        s = ts
            .iter()
            .zip(&s)
            .map(|(a, b)| {
                // the next candidate covers both (terms new in the image included)
                let h = hull(a, b);
                h.inflate(0.5, opts.inflate_rel, 1e-300)
            })
            .collect();
    }
    None
}

/// A value whose every coefficient and remainder contains both operands'.
fn hull<I: Enclosure>(a: &Gts<I>, b: &Gts<I>) -> Gts<I> {
    // a + (b − a)·0 keeps a's keys and b's; take coefficientwise hulls by adding the difference
    // of the two as an interval [0, 1] multiple: a + [0, 1](b − a) ⊇ a ∪ b coefficientwise
    let d = b.clone() - a.clone();
    a.clone() + d * Gts::constant(I::from_bounds(0.0, 1.0).expect("[0, 1]"))
}

/// The flow of the point `x0` (a box of tiny width) across the zero of component `w`: the
/// exit time t₁ (`at`, or one chosen just before t(δ_B)) and the state there, or `None` (see
/// [`crossing_step`]).
fn cross_point<const N: usize, I: Enclosure>(
    st: &SingularTape<N, I>,
    tape: &Tape<I, N>,
    t0: f64,
    x0: &[I; N],
    w: usize,
    opts: &SingularOptions,
    at: Option<f64>,
) -> Option<(f64, [I; N])> {
    let sa = Real::sign(&x0[w])?;
    let f0 = tape.eval(x0);
    if Real::sign(&f0[w]) != Some(-sa) {
        return None;
    }
    let u0 = if sa > 0 {
        x0[w].clone()
    } else {
        -x0[w].clone()
    };
    let delta_a = u0.hi();
    let ctx_a = Ctx::new(&st.basis, delta_a)?;
    let y0: Vec<I> = (0..=N)
        .map(|j| if j == N { point(t0) } else { x0[j].clone() })
        .collect();
    let a = solve_side(st, &ctx_a, sa, w, Start::At(&y0, u0), opts)?;
    let yc: Vec<I> = a.y.iter().map(|g| g.eval(&I::zero())).collect();
    let sb = -sa;
    // a given exit time may lie a little beyond this point's own t(δ_A)
    let delta_b = if at.is_some() {
        1.5 * delta_a
    } else {
        delta_a.max(opts.depart_min)
    };
    let ctx_b = Ctx::new(&st.basis, delta_b)?;
    let b = solve_side(st, &ctx_b, sb, w, Start::Zero(&yc), opts)?;
    // the exit time: t(δ_B) > t1 > t_c
    let tb = &b.y[N];
    let t_end = tb.eval(&point(delta_b)).lo();
    let t1 = at.unwrap_or(t_end.next_down());
    if !(t1 > yc[N].hi() && t1 > t0 && t1 < t_end) {
        return None;
    }
    let clock = std::time::Instant::now();
    let ustar = exit_parameter(tb, t1, delta_b)?;
    let exit_time = clock.elapsed();
    let x1: [I; N] = std::array::from_fn(|j| {
        if j == w {
            if sb > 0 {
                ustar.clone()
            } else {
                -ustar.clone()
            }
        } else {
            b.y[j].eval(&ustar)
        }
    });
    if trace_sing() {
        let rems = |s: &Side<I>| {
            s.y.iter()
                .map(|g| format!("{:.1e}/{}", g.remainder().wid_f64(), g.terms().len()))
                .collect::<Vec<_>>()
                .join(" ")
        };
        eprintln!(
            "singular: t0 {t0} t1 {t1} δ {delta_a:.3e} u* width {:.1e} (bisection {exit_time:?}); remainders/terms A {} B {}",
            ustar.wid_f64(),
            rems(&a),
            rems(&b)
        );
    }
    Some((t1, x1))
}

/// The parameters u ∈ [0, δ] where the increasing time t(u) (enclosed by `t`) can equal the
/// exact double `t1`: bisection from below to the last u with t(u) < t1 surely, and from above
/// to the first u with t(u) > t1 surely. The midpoints are points of `I` (at MPFR precision the
/// bracket shrinks to the precision of `I`, not to an f64 ulp), each comparison exact:
/// t(u) − t1 < 0 (> 0) surely.
///
/// The bisections start from a bracket [u_g − r, u_g + r] around an estimate u_g (Newton's
/// method on the midpoint expansion in f64, [`Gts::mid_value_slope`]) once its ends are
/// checked like every midpoint (t < t1 surely at the lower end, t > t1 at the upper), else
/// from [0, δ]: the estimate only chooses where to look (measured, SHC DSS v0 = 1: ≈ 30
/// evaluations of t instead of ≈ 120).
///
/// For f64 intervals the bracket is first tried directly ([`exit_direct`]: 2–4 evaluations,
/// the same checks); the bisections run only where that fails.
pub(crate) fn exit_parameter<I: Enclosure>(t: &Gts<I>, t1f: f64, delta: f64) -> Option<I> {
    let estimate = exit_estimate(t, t1f, delta);
    if I::epsilon() >= f64::EPSILON
        && let Some(b) = estimate.and_then(|u| exit_direct(t, t1f, delta, u))
    {
        return Some(b);
    }
    exit_parameter_from(
        t,
        t1f,
        delta,
        estimate.and_then(|u| exit_guess(t, delta, u)),
    )
}

/// t(u) − t1 < 0 for every u in `u` (the exact comparison of the brackets' checks).
fn surely_below<I: Enclosure>(t: &Gts<I>, u: &I, t1: &I) -> bool {
    (t.eval(u) - t1.clone()).hi() < 0.0
}

/// t(u) − t1 > 0 for every u in `u`.
fn surely_above<I: Enclosure>(t: &Gts<I>, u: &I, t1: &I) -> bool {
    (t.eval(u) - t1.clone()).lo() > 0.0
}

/// The bracket [u_lo, u_hi] of exact doubles with t(u_lo) < t1 < t(u_hi) surely, placed from
/// the estimate u_g where the enclosure t(u_g) = [a, b] and the slope d say t crosses t1:
/// u_lo = u_g − (b − t1)/d − μ, u_hi = u_g + (t1 − a)/d + μ with the margin μ = ε(b − a)/d + m
/// (ε = 10⁻³, m = 4 ulps of u_g and 2 ulps of t1 over d), each end checked like a
/// bisection's midpoint; ε and m grow eightfold where a check fails, three times at most;
/// then each end is moved inward by eight halvings to the estimate's other side, each
/// checked the same way. Taken only where t(u_g) is thin (its width under 10⁻⁹ of |t1|: t's
/// width then hardly changes across the bracket, so the bracket is as narrow as the
/// bisections' to within ε of it and a few ulps). t is increasing: the true u* with
/// t(u*) = t1 lies between the ends; nothing but the checks is relied on. `None` when no try
/// passes.
fn exit_direct<I: Enclosure>(t: &Gts<I>, t1f: f64, delta: f64, u: f64) -> Option<I> {
    let t1 = point::<I>(t1f);
    let tu = t.eval(&point::<I>(u));
    let (_, d) = t.mid_value_slope(u);
    let (a, b) = (tu.lo(), tu.hi());
    if !(d > 0.0 && d.is_finite() && a.is_finite() && b.is_finite() && b - a <= 1e-9 * t1f.abs()) {
        return None;
    }
    // m: 4 ulps of u, and the u-distance of 2 ulps of t (its evaluations round at t's scale)
    let (mut eps, mut m) = (
        1e-3,
        4.0 * u * f64::EPSILON + 2.0 * t1f.abs() * f64::EPSILON / d,
    );
    for _ in 0..3 {
        let margin = eps * (b - a) / d + m;
        // where t's upper and lower ends are estimated to pass t1 (the exit time is usually
        // placed just below t(δ): the upper end is then δ itself)
        let (est_lo, est_hi) = (u - (b - t1f) / d, (u + (t1f - a) / d).min(delta));
        let lo = est_lo - margin;
        let hi = (est_hi + margin).min(delta);
        if !(lo > 0.0 && lo < hi) {
            return None;
        }
        let below = |u: f64| surely_below(t, &point::<I>(u), &t1);
        let above = |u: f64| surely_above(t, &point::<I>(u), &t1);
        if below(lo) && above(hi) {
            // each end moved inward by bisection to the estimate's other side (eight
            // halvings: the ends then lie within 2μ/256 of where the checks stop passing)
            let (mut l, mut l_out) = (lo, (est_lo + margin).min(hi));
            let (mut h, mut h_out) = (hi, (est_hi - margin).max(lo));
            for _ in 0..8 {
                let m = 0.5 * (l + l_out);
                if below(m) {
                    l = m
                } else {
                    l_out = m
                }
                let m = 0.5 * (h + h_out);
                if above(m) { h = m } else { h_out = m }
            }
            return Some(point::<I>(l).hull(&point::<I>(h)));
        }
        eps *= 8.0;
        m *= 8.0;
    }
    None
}

/// [`exit_parameter`] from the bracket `hint` (exact doubles in (0, δ)) where its ends pass
/// the checks, else from [0, δ].
fn exit_parameter_from<I: Enclosure>(
    t: &Gts<I>,
    t1f: f64,
    delta: f64,
    hint: Option<(f64, f64)>,
) -> Option<I> {
    // enough halvings to reach the ends' precision from δ (200 for f64 ends)
    let iters = 200.max((-I::epsilon().log2()) as usize + 80);
    let t1 = point::<I>(t1f);
    let below = |u: &I| surely_below(t, u, &t1);
    let above = |u: &I| surely_above(t, u, &t1);
    let mid = |a: &I, b: &I| -> Option<I> {
        let m = a.hull(b).mid_point();
        (!m.same(a) && !m.same(b)).then_some(m)
    };
    // u_lo: t(u) < t1 surely for u ≤ u_lo; u_hi: t(u) > t1 surely for u ≥ u_hi (δ: the caller
    // has t(δ) > t1; 0: t(0) < t1)
    let (mut lo, mut upper) = (I::zero(), point::<I>(delta));
    if let Some((a, b)) = hint {
        let (pa, pb) = (point::<I>(a), point::<I>(b));
        if below(&pa) && above(&pb) {
            (lo, upper) = (pa, pb);
        }
    }
    // (the first bisection moves its upper end to where t < t1 is merely not sure: the
    // second starts again from `upper`)
    let mut hi = upper.clone();
    for _ in 0..iters {
        let Some(m) = mid(&lo, &hi) else { break };
        if below(&m) {
            lo = m;
        } else {
            hi = m;
        }
    }
    let (mut lo2, mut hi2) = (lo.clone(), upper);
    for _ in 0..iters {
        let Some(m) = mid(&lo2, &hi2) else { break };
        if above(&m) {
            hi2 = m;
        } else {
            lo2 = m;
        }
    }
    ((hi2.clone() - lo.clone()).lo() >= 0.0).then(|| lo.hull(&hi2))
}

/// A bracket (a, b) ⊂ (0, δ) of exact doubles around the estimate u ([`exit_estimate`]) of
/// the u with t(u) = t1 (see [`exit_parameter`]; nothing here is proved): a margin of the
/// larger of 64 ulps and 4× t's width over its slope.
fn exit_guess<I: Enclosure>(t: &Gts<I>, delta: f64, u: f64) -> Option<(f64, f64)> {
    let (_, d) = t.mid_value_slope(u);
    let w = t.eval(&I::from_exact_f64(u)).wid_f64();
    let r = (64.0 * u * f64::EPSILON).max(4.0 * w / d);
    let (a, b) = (u - r, u + r);
    (a > 0.0 && b < delta && r.is_finite()).then_some((a, b))
}

/// The u ∈ (0, δ) with t(u) = t1 estimated by Newton's method on the midpoint expansion from
/// the secant over [0, δ] (nothing here is proved). `None` when the estimate fails (a flat or
/// non-finite slope, or it leaves the domain).
fn exit_estimate<I: Enclosure>(t: &Gts<I>, t1: f64, delta: f64) -> Option<f64> {
    let t0 = t.c0().mid();
    let (td, _) = t.mid_value_slope(delta);
    let mut u = delta * (t1 - t0) / (td - t0);
    for _ in 0..8 {
        if !(u > 0.0 && u < delta) {
            return None;
        }
        let (v, d) = t.mid_value_slope(u);
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        u -= (v - t1) / d;
    }
    (u > 0.0 && u < delta).then_some(u)
}

/// A step across the zero of component `w` from the set at t0 (the affine set `rep`, or
/// the box `x0`), or `None` when it cannot be proved (a component other than w reaches a
/// switching surface, ẇ reaches 0, the expansions do not validate, the exit time is not after
/// t_c, or the field's Jacobian is unbounded on the way).
///
/// The set is carried by the mean-value form, as a Taylor step carries it: with c the
/// set's centre, φ(x) ∈ φ(c) + J·(x − c), where φ(c) is the point's flow by the expansions
/// (`cross_point`) and J encloses the flow's Jacobian over the set from the variational
/// equation Φ′ = Df(x(t))Φ, Φ(t₀) = I, on the a-priori box Y ⊇ x(t) of a low-order step:
/// ‖Φ(t) − I‖_∞ ≤ e^(‖Df(Y)‖_∞ τ) − 1 (Grönwall), then Φ(t₁) ∈ I + τ₁·Df(Y)·(I + [−ε, ε]).
/// Df(Y) is evaluated on duals; at a kink of |·| its derivative is [−1, 1] (Clarke's), so the
/// inclusion holds for the Lipschitz fields of n = 1 too. The low-order step also gives the
/// piece x₀ + τ·f(Y) that the event scan and the dense output use.
#[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
pub fn crossing_step<const N: usize, I: Enclosure>(
    st: &SingularTape<N, I>,
    tape: &Tape<I, N>,
    dual: &Tape<Dual<I, N>, N>,
    t0: f64,
    x0: &[I; N],
    rep: Option<&AffineSet<N, I>>,
    w: usize,
    opts: &SingularOptions,
) -> Option<StepOut<N, I>> {
    let clock = std::time::Instant::now();
    let trace = trace_sing();
    let p = rep.cloned().unwrap_or_else(|| AffineSet::from_box(x0));
    let c: [I; N] = p.c.clone();
    let cp = cross_point(st, tape, t0, &c, w, opts, None);
    if trace {
        eprintln!(
            "singular attempt at t0 {t0}: {} in {:?}",
            if cp.is_some() { "crossed" } else { "refused" },
            clock.elapsed()
        );
    }
    let (t1, z) = cp?;
    // the piece must end at t₁ itself: z encloses the state there, and x1 is stored as the
    // state at the piece's end (fl(t₀ + (t₁ − t₀)) may be t₁'s neighbour)
    let lo = low_order_to(tape, t0, x0, t1)?;
    let y = lo.apriori;
    let fd = dual.eval(&Dual::seed(&y));
    let d: [[I; N]; N] = std::array::from_fn(|i| fd[i].d.clone());
    if !d.iter().flatten().all(bounded) {
        return None;
    }
    let tau1 = tau(&point::<I>(t1), t0);
    let norm = d
        .iter()
        .map(|row| row.iter().fold(I::zero(), |s, x| s + point(x.mag_f64())))
        .fold(I::zero(), |m, s| point(m.hi().max(s.hi())));
    let eps = ((norm * tau1.clone()).exp() - I::one()).hi();
    if eps.is_nan() || eps >= 1.0 {
        return None;
    }
    let ball = I::from_bounds(-eps, eps)?;
    let jy: [[I; N]; N] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            if i == j {
                I::one() + ball.clone()
            } else {
                ball.clone()
            }
        })
    });
    let jac: [[I; N]; N] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let s = I::dot((0..N).map(|l| (d[i][l].clone(), jy[l][j].clone())));
            let e = if i == j { I::one() } else { I::zero() };
            e + tau1.clone() * s
        })
    });
    // the image of the set x̂ + Σ g_j u_j: z + J·(x0 − x̂)
    let zero: [I; N] = std::array::from_fn(|_| I::zero());
    let (rep1, direct) = p.image(&jac, &zero, &z);
    let x1: [I; N] = match &rep1 {
        Some(r) => {
            let h = r.hull();
            std::array::from_fn(|i| h[i].intersection(&direct[i]).intersection(&lo.x1[i]))
        }
        None => std::array::from_fn(|i| direct[i].intersection(&lo.x1[i])),
    };
    if x1.iter().any(|c| c.is_empty()) {
        return None;
    }
    Some(StepOut {
        piece: lo.piece,
        x1,
        apriori: y,
        rep: rep1,
    })
}

/// The singular step as the engine's loop uses it, on the engine's interval type `I` (f64
/// intervals or MPFR intervals: the expansions carry coefficients of the same precision), with
/// the retry rule after a refusal.
pub struct Singular<const N: usize, I: Enclosure> {
    st: SingularTape<N, I>,
    tape: Tape<I, N>,
    dual: Tape<Dual<I, N>, N>,
    opts: SingularOptions,
    /// After a refused step the next try waits until the surface is this near.
    retry: f64,
    /// The start step's basis (its own cut-off), made when first tried; `None` inside when
    /// it cannot be made.
    start: Option<Option<Arc<Basis<I>>>>,
}

impl<const N: usize, I: Enclosure> Singular<N, I> {
    pub fn new(tape: &Tape<I, N>, opts: SingularOptions) -> Option<Self> {
        Some(Self {
            st: SingularTape::of(tape, &opts)?,
            dual: tape.map(|c| Dual::constant(c.clone())),
            tape: tape.clone(),
            opts,
            retry: f64::INFINITY,
            start: None,
        })
    }

    /// [`start::start_step`] from the point `x0` at `t0`, or `None`.
    pub fn try_start(&mut self, t0: f64, x0: &[I; N]) -> Option<StepOut<N, I>> {
        let (gens, m) = (self.st.basis.gens(), self.opts.start_max_exp);
        // every power of exponent 1 (|x|⁰x = x, |x|¹ a kink): no branch point to expand at
        if gens.is_empty() {
            return None;
        }
        let basis = self
            .start
            .get_or_insert_with(|| Basis::cached(gens, m))
            .clone()?;
        let clock = std::time::Instant::now();
        let out = start::start_step(
            &self.st.tape,
            &basis,
            &self.tape,
            t0,
            x0,
            self.opts.start_delta,
            &self.opts,
        );
        if trace_sing() {
            eprintln!(
                "start attempt at t0 {t0}: {} in {:?} ({} exponents up to {})",
                if out.is_some() { "proved" } else { "refused" },
                clock.elapsed(),
                basis.len(),
                self.opts.start_max_exp
            );
        }
        out
    }

    /// [`crossing_step`] across component `w`, `h` the time it needs to reach 0 at its
    /// fastest; `None` while a refused step waits to be nearer.
    pub fn try_step(
        &mut self,
        t0: f64,
        x0: &[I; N],
        rep: Option<&AffineSet<N, I>>,
        w: usize,
        h: f64,
    ) -> Option<StepOut<N, I>> {
        if h >= self.retry {
            return None;
        }
        let out = crossing_step(&self.st, &self.tape, &self.dual, t0, x0, rep, w, &self.opts);
        if out.is_none() {
            self.retry = h / 4.0;
        }
        out
    }

    /// Records whether the caller took the step (a refusal waits until 4× nearer).
    pub fn taken(&mut self, ok: bool, h: f64) {
        self.retry = if ok { f64::INFINITY } else { h / 4.0 };
    }
}

#[cfg(test)]
mod tests;
