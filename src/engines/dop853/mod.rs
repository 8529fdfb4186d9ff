//! DOP853: Hairer's explicit Dormand–Prince 8(5,3) Runge–Kutta method in `f64`, with the
//! 7th-order dense output.
//!
//! The method and its error estimator are those of Hairer's Fortran `DOP853` (Hairer, Nørsett &
//! Wanner, *Solving ODEs I*, 2nd ed., §II.10); the step-size controller and the initial step are
//! those of SciPy's `solve_ivp(method="DOP853")` (the paper's integrator, sec:ID), so that both
//! take (nearly) the same steps. Layout, after SciPy's `rk.py`:
//!
//! - [`tableau`]: the Butcher tableau as data (`C`, `A`, `B`, `E3`, `E5`, `D`);
//! - [`dense`]: the continuous extension of one step, [`DenseStep`];
//! - this file: the step (`rk_step`), the error norm, the controller and the driver, each
//!   written once.
//!
//! The state is a fixed-size array `[f64; N]`; the step loop never allocates. On the reference
//! problems (Van der Pol, Lorenz at `rtol = 1e-10`) it takes SciPy's step sequence, step for
//! step, with the same `nfev` (`tests/dop853.rs`).
//!
//! ```
//! use bwcl::engines::dop853::{integrate, Options};
//! // y' = −y, y(0) = 1 ⇒ y(1) = e⁻¹
//! let (y, stats) = integrate(|_t, y: &[f64; 1]| [-y[0]], 0.0, [1.0], 1.0, Options::default())?;
//! assert!((y[0] - (-1.0f64).exp()).abs() < 1e-11);
//! assert!(stats.naccepted > 0);
//! # Ok::<(), bwcl::engines::dop853::Dop853Error>(())
//! ```

pub mod dense;
pub mod tableau;

pub use dense::DenseStep;

use crate::arith::float::fastpow::Power;
use std::sync::LazyLock;
use tableau::{A, B, C, D, E3, E5, N_STAGES, N_STAGES_EXTENDED};

/// Safety factor of the step-size controller (SciPy `SAFETY`).
const SAFETY: f64 = 0.9;
/// Smallest allowed step-size ratio `h_new/h` (SciPy `MIN_FACTOR`).
const MIN_FACTOR: f64 = 0.2;
/// Largest allowed step-size ratio `h_new/h` (SciPy `MAX_FACTOR`).
const MAX_FACTOR: f64 = 10.0;
/// Controller exponent `−1/(q + 1)` with `q = 7`, the order of the error estimator
/// (`err^(−1/8)` by [`crate::arith::float::fastpow`], a few ulps: the libm `powf` was 7% of a CoR's
/// instructions; the step sequences of the SciPy reference tests are unchanged).
const ERROR_EXPONENT: f64 = -1.0 / 8.0;
/// Below this error norm the step-size factor is at least [`CAPPED_FACTOR`]:
/// min(10, 0.9·0.4^(−1/8)) = 1.0092…, which the few ulps of the table power cannot bring
/// under 1.0001.
const CAPPED_ERR: f64 = 0.4;
const CAPPED_FACTOR: f64 = 1.0001;
/// x ↦ x^(−1/8), built on first use.
static CONTROLLER_POWER: LazyLock<Power> = LazyLock::new(|| Power::new(ERROR_EXPONENT));
/// Order `q` of the error estimator, used by [`select_initial_step`].
const ERROR_ESTIMATOR_ORDER: f64 = 7.0;

/// Tolerances and limits of one integration.
///
/// The per-component error scale is `sc_i = atol + rtol · max(|y_i|, |y_new,i|)`.
#[derive(Clone, Debug)]
pub struct Options {
    /// Relative tolerance, finite and `≥ 100 ε` (≈ 2.2e-14).
    pub rtol: f64,
    /// Absolute tolerance, finite and `≥ 0`.
    pub atol: f64,
    /// Largest allowed `|h|`, `> 0` (may be `+∞`).
    pub max_step: f64,
    /// `|h|` of the first trial step; `None` selects it with [`select_initial_step`].
    pub first_step: Option<f64>,
    /// Largest number of attempted steps, accepted plus rejected (Hairer's `NMAX`).
    pub max_steps: usize,
}

impl Default for Options {
    /// `rtol = 1e-10`, `atol = 1e-12`, no step limit, automatic first step, 10⁶ steps.
    fn default() -> Self {
        Options {
            rtol: 1e-10,
            atol: 1e-12,
            max_step: f64::INFINITY,
            first_step: None,
            max_steps: 1_000_000,
        }
    }
}

impl Options {
    /// The paper's SciPy settings (sec:ID): `rtol ≈ 1e-10`, `atol ≈ 1e-12`, `max_step ≈ 1e-2`.
    pub fn paper() -> Self {
        Options {
            max_step: 1e-2,
            ..Options::default()
        }
    }
}

/// Why an integration could not proceed. Each carries the offending value.
#[derive(Clone, Debug, PartialEq)]
pub enum Dop853Error {
    /// An invalid option or initial condition (the message names the value).
    BadOption(String),
    /// The step size fell below `10 ulp(t)` at `t` (e.g. approaching a blow-up).
    StepTooSmall {
        /// Time at which the integration stopped.
        t: f64,
        /// The last (signed) step size that was tried.
        h: f64,
    },
    /// More than `max_steps` attempted steps.
    TooManySteps {
        /// Time reached.
        t: f64,
        /// The limit that was hit.
        steps: usize,
    },
    /// A stop was requested ([`crate::engines::cancel`]) before the step from `t`.
    Cancelled {
        /// Time reached.
        t: f64,
    },
    /// The right-hand side returned a non-finite value at `t`, and shrinking the step did not help.
    NonFinite {
        /// Time of the last accepted state.
        t: f64,
    },
}

impl std::fmt::Display for Dop853Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Dop853Error::BadOption(msg) => write!(f, "DOP853: bad option: {msg}"),
            Dop853Error::StepTooSmall { t, h } => {
                write!(f, "DOP853: step size h = {h:e} too small at t = {t}")
            }
            Dop853Error::TooManySteps { t, steps } => {
                write!(
                    f,
                    "DOP853: more than {steps} steps needed, stopped at t = {t}"
                )
            }
            Dop853Error::Cancelled { t } => write!(f, "DOP853: cancelled at t = {t}"),
            Dop853Error::NonFinite { t } => {
                write!(f, "DOP853: right-hand side not finite near t = {t}")
            }
        }
    }
}

impl std::error::Error for Dop853Error {}

/// Counters of one integration (SciPy's `nfev` and `len(t) − 1`, plus rejections).
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    /// Right-hand-side evaluations: `f(t0, y0)`, one more for the automatic initial step,
    /// `12` per attempted step (FSAL), `3` per dense output (as SciPy counts them).
    pub nfev: usize,
    /// Accepted steps.
    pub naccepted: usize,
    /// Rejected steps.
    pub nrejected: usize,
}

/// `a·b + c`, fused when the target has FMA (it does under `target-cpu=haswell`).
#[inline(always)]
fn madd(a: f64, b: f64, c: f64) -> f64 {
    if cfg!(target_feature = "fma") {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// `y + h Σ_{j<s} w[j] K[j]`, componentwise (one stage argument, or the new state).
///
/// Summed in stage order as `y + h·(Σ_{j<s−1} w[j] K[j]) + (h·w[s−1])·K[s−1]`: the newest
/// stage comes last with h folded into its weight, so the next evaluation waits for one FMA
/// after `K[s−1]`, not two (the stages are a dependent chain: this is its latency).
#[inline(always)]
fn combine<const N: usize>(
    y: &[f64; N],
    h: f64,
    k: &[[f64; N]; N_STAGES_EXTENDED],
    w: &[f64],
    s: usize,
) -> [f64; N] {
    // Plain loops, no closures: with the tableau row a constant after inlining, the zero
    // tests fold away (a closure in `array::from_fn` is not always inlined, and then they
    // do not: measured 2× slower on the Maxwell model with one codegen unit).
    let last = s - 1;
    let h_last = h * w[last];
    let mut out = [0.0; N];
    for i in 0..N {
        let mut acc = 0.0;
        for j in 0..last {
            // The tableau is sparse: skipping its zeros saves a third of the work.
            if w[j] != 0.0 {
                acc = madd(w[j], k[j][i], acc);
            }
        }
        let early = madd(h, acc, y[i]);
        out[i] = if w[last] != 0.0 {
            madd(h_last, k[last][i], early)
        } else {
            early
        };
    }
    out
}

/// RMS norm `‖v‖ = sqrt(Σ v_i² / N)`.
#[inline]
fn rms<const N: usize>(v: impl Fn(usize) -> f64) -> f64 {
    let mut s = 0.0;
    for i in 0..N {
        let x = v(i);
        s = madd(x, x, s);
    }
    (s / N as f64).sqrt()
}

/// Stages 1 … 11 of a step of size `h` from `(t, y)`, given `K[0] = f(t, y)`:
/// `K[s] = f(t + c_s h, y + h Σ_{j<s} a_{sj} K[j])`.
#[inline(always)]
fn rk_stages<F, const N: usize>(
    f: &mut F,
    k: &mut [[f64; N]; N_STAGES_EXTENDED],
    t: f64,
    y: &[f64; N],
    h: f64,
) where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    // Unrolled with literal stage numbers so that each combination sees its row of `A` as
    // constants and the zero entries cost nothing (≈ 35% faster than a loop for N = 3).
    macro_rules! stages {
        ($($s:literal)*) => {$(
            let ys = combine(y, h, k, &A[$s], $s);
            k[$s] = f(madd(C[$s], h, t), &ys);
        )*};
    }
    stages!(1 2 3 4 5 6 7 8 9 10 11);
}

/// Hairer's initial step (*Solving ODEs I*, §II.4, p. 169), as in SciPy:
///
/// with `sc_i = atol + rtol |y0_i|`, `d0 = ‖y0/sc‖`, `d1 = ‖f0/sc‖` (RMS norms),
/// `h0 = 0.01 d0/d1` (or `1e-6` if `d0` or `d1 < 1e-5`), clipped to the interval length;
/// one explicit Euler step gives `f1 = f(t0 + h0, y0 + h0 f0)` and `d2 = ‖(f1 − f0)/sc‖ / h0`;
/// `h1 = (0.01 / max(d1, d2))^{1/(q+1)}` with `q = 7` (or `max(1e-6, 1e-3 h0)` if both
/// `d1, d2 ≤ 1e-15`); the result is `min(100 h0, h1, |t_bound − t0|, max_step)`.
/// Costs one evaluation of `f`.
pub fn select_initial_step<F, const N: usize>(
    f: &mut F,
    t0: f64,
    y0: &[f64; N],
    f0: &[f64; N],
    t_bound: f64,
    opts: &Options,
) -> f64
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    let interval = (t_bound - t0).abs();
    if N == 0 {
        return interval.min(opts.max_step);
    }
    let direction = (t_bound - t0).signum();
    let scale: [f64; N] = core::array::from_fn(|i| madd(opts.rtol, y0[i].abs(), opts.atol));
    let d0 = rms::<N>(|i| y0[i] / scale[i]);
    let d1 = rms::<N>(|i| f0[i] / scale[i]);
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let h0 = h0.min(interval);
    let y1: [f64; N] = core::array::from_fn(|i| madd(h0 * direction, f0[i], y0[i]));
    let f1 = f(t0 + h0 * direction, &y1);
    let d2 = rms::<N>(|i| (f1[i] - f0[i]) / scale[i]) / h0;
    let h1 = if d1 <= 1e-15 && d2 <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d1.max(d2)).powf(1.0 / (ERROR_ESTIMATOR_ORDER + 1.0))
    };
    // NaN-safe: a NaN h1 (non-finite f1) falls back to 100 h0.
    let mut h = 100.0 * h0;
    for c in [h1, interval, opts.max_step] {
        if c < h {
            h = c;
        }
    }
    h
}

/// The DOP853 integrator for `y' = f(t, y)`, `y(t0) = y0`, on the span from `t0` to `t_bound`
/// (either direction).
///
/// Drive it with [`Dop853::step`]; after each accepted step [`Dop853::dense_output`] gives the
/// 7th-order interpolant on `[t_old, t]`.
pub struct Dop853<F, const N: usize>
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    f: F,
    t: f64,
    y: [f64; N],
    /// `f(t, y)`, carried over from the last stage of the previous step (FSAL).
    fy: [f64; N],
    t_old: f64,
    y_old: [f64; N],
    t_bound: f64,
    /// `sign(t_bound − t0)`.
    direction: f64,
    /// Proposed `|h|` of the next step.
    h_abs: f64,
    rtol: f64,
    atol: f64,
    max_step: f64,
    max_steps: usize,
    /// Stages `K[0] … K[15]` of the last step (13 … 15 only after a dense output).
    k: [[f64; N]; N_STAGES_EXTENDED],
    /// Whether `K[0] … K[12]` are those of the last accepted step (a failed `step` leaves the
    /// stages of a rejected trial there).
    stages_valid: bool,
    /// Dense output of the last accepted step, once computed.
    dense: Option<DenseStep<N>>,
    nfev: usize,
    naccepted: usize,
    nrejected: usize,
}

impl<F, const N: usize> Dop853<F, N>
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    /// Validates the options (`rtol` finite and `≥ 100 ε`, `atol` finite and `≥ 0`,
    /// `max_step > 0`, `first_step` in `(0, |t_bound − t0|]`, `max_steps > 0`, `t0`, `t_bound`
    /// and `y0` finite, `t_bound ≠ t0`), evaluates `f(t0, y0)` and picks the first step with
    /// [`select_initial_step`] unless `first_step` is given.
    pub fn new(
        mut f: F,
        t0: f64,
        y0: [f64; N],
        t_bound: f64,
        opts: Options,
    ) -> Result<Self, Dop853Error> {
        validate(t0, &y0, t_bound, &opts)?;
        let f0 = f(t0, &y0);
        if f0.iter().any(|v| !v.is_finite()) {
            return Err(Dop853Error::NonFinite { t: t0 });
        }
        let mut nfev = 1;
        let h_abs = match opts.first_step {
            Some(h) => h,
            None => {
                nfev += 1;
                select_initial_step(&mut f, t0, &y0, &f0, t_bound, &opts)
            }
        };
        Ok(Dop853 {
            f,
            t: t0,
            y: y0,
            fy: f0,
            t_old: t0,
            y_old: y0,
            t_bound,
            direction: (t_bound - t0).signum(),
            h_abs,
            rtol: opts.rtol,
            atol: opts.atol,
            max_step: opts.max_step,
            max_steps: opts.max_steps,
            k: [[0.0; N]; N_STAGES_EXTENDED],
            stages_valid: false,
            dense: None,
            nfev,
            naccepted: 0,
            nrejected: 0,
        })
    }

    /// One trial step of size `h` from `(t, y)` (SciPy's `rk_step`):
    /// `K[0] = f(t, y)` (reused), `K[s] = f(t + c_s h, y + h Σ_{j<s} a_{sj} K[j])` for
    /// `s = 1 … 11`, `y_new = y + h Σ_{j<12} b_j K[j]`, `K[12] = f(t_new, y_new)`.
    /// Costs 12 evaluations.
    #[inline]
    fn rk_step(&mut self, h: f64, t_new: f64) -> [f64; N] {
        self.k[0] = self.fy;
        self.stages_valid = false;
        rk_stages(&mut self.f, &mut self.k, self.t, &self.y, h);
        let y_new = combine(&self.y, h, &self.k, &B, N_STAGES);
        self.k[N_STAGES] = (self.f)(t_new, &y_new);
        self.nfev += N_STAGES;
        y_new
    }

    /// Hairer's combined error norm of the trial step in `K`:
    ///
    /// with `sc_i = atol + rtol max(|y_i|, |y_new,i|)`,
    /// `err5² = Σ_i (Σ_j E5_j K_ij / sc_i)²`, `err3² = Σ_i (Σ_j E3_j K_ij / sc_i)²`,
    ///
    /// `err = |h| · err5² / sqrt(N (err5² + 0.01 err3²))`
    ///
    /// (0 when both vanish). The step is accepted when `err < 1`.
    #[inline]
    fn error_norm(&self, h: f64, y_new: &[f64; N]) -> f64 {
        let (mut e5, mut e3) = (0.0, 0.0);
        for (i, (y, y_new)) in self.y.iter().zip(y_new).enumerate() {
            let sc = madd(self.rtol, y.abs().max(y_new.abs()), self.atol);
            let (mut s5, mut s3) = (0.0, 0.0);
            for ((e5j, e3j), kj) in E5.iter().zip(&E3).zip(&self.k[..N_STAGES]) {
                if *e5j != 0.0 {
                    s5 = madd(*e5j, kj[i], s5);
                }
                if *e3j != 0.0 {
                    s3 = madd(*e3j, kj[i], s3);
                }
            }
            let (s5, s3) = (s5 / sc, s3 / sc);
            e5 = madd(s5, s5, e5);
            e3 = madd(s3, s3, e3);
        }
        if e5 == 0.0 && e3 == 0.0 {
            return 0.0;
        }
        h.abs() * e5 / ((e5 + 0.01 * e3) * N as f64).sqrt()
    }

    /// Advances by one accepted step; `Ok(false)` if `t` already equals `t_bound`.
    ///
    /// Controller (SciPy's `RungeKutta._step_impl`): `|h|` is clamped to
    /// `[10 ulp(t), max_step]` and clipped so as not to pass `t_bound`; after a trial with
    /// error norm `err`,
    /// - accept if `err < 1`, next `|h| ← |h| · min(10, 0.9 err^{−1/8})` (10 if `err = 0`),
    ///   but never larger than `|h|` if this step had a rejection;
    /// - otherwise reject, `|h| ← |h| · max(0.2, 0.9 err^{−1/8})`, and retry.
    ///
    /// A trial whose `y_new` or `f(t_new, y_new)` is not finite is rejected with factor 0.2.
    /// Fails with [`Dop853Error::StepTooSmall`] when `|h| < 10 ulp(t)` (or
    /// [`Dop853Error::NonFinite`] if the last trial was not finite), and with
    /// [`Dop853Error::TooManySteps`] after `max_steps` attempted steps; with
    /// [`Dop853Error::Cancelled`] when a stop is requested ([`crate::engines::cancel`]).
    pub fn step(&mut self) -> Result<bool, Dop853Error> {
        if self.t == self.t_bound {
            return Ok(false);
        }
        let t = self.t;
        if crate::engines::cancel::requested() {
            return Err(Dop853Error::Cancelled { t });
        }
        let toward = if self.direction > 0.0 {
            t.next_up()
        } else {
            t.next_down()
        };
        let min_step = 10.0 * (toward - t).abs();
        let mut h_abs = self.h_abs.min(self.max_step).max(min_step);
        let mut rejected = false;
        let mut non_finite = false;
        loop {
            if h_abs.is_nan() || h_abs < min_step {
                let h = h_abs * self.direction;
                return Err(if non_finite {
                    Dop853Error::NonFinite { t }
                } else {
                    Dop853Error::StepTooSmall { t, h }
                });
            }
            if self.naccepted + self.nrejected >= self.max_steps {
                return Err(Dop853Error::TooManySteps {
                    t,
                    steps: self.max_steps,
                });
            }
            let mut t_new = madd(h_abs, self.direction, t);
            if self.direction * (t_new - self.t_bound) > 0.0 {
                t_new = self.t_bound;
            }
            let h = t_new - t;
            h_abs = h.abs();

            let y_new = self.rk_step(h, t_new);
            let finite = y_new
                .iter()
                .chain(self.k[N_STAGES].iter())
                .all(|v| v.is_finite());
            let err = self.error_norm(h, &y_new);

            if finite && err < 1.0 {
                if !rejected && err < CAPPED_ERR && h_abs * CAPPED_FACTOR >= self.max_step {
                    // The next |h| is max_step whatever the exact factor (≥ CAPPED_FACTOR here):
                    // a constant, so that the next step need not wait for err^(−1/8) (with
                    // max_step binding, as at the paper's settings, this is most steps).
                    self.h_abs = self.max_step;
                } else {
                    let mut factor = if err == 0.0 {
                        MAX_FACTOR
                    } else {
                        MAX_FACTOR.min(SAFETY * CONTROLLER_POWER.pow(err))
                    };
                    if rejected {
                        factor = factor.min(1.0);
                    }
                    self.h_abs = h_abs * factor;
                }
                self.t_old = t;
                self.y_old = self.y;
                self.t = t_new;
                self.y = y_new;
                self.fy = self.k[N_STAGES];
                self.dense = None;
                self.stages_valid = true;
                self.naccepted += 1;
                return Ok(true);
            }
            non_finite = !finite || err.is_nan();
            let factor = if non_finite {
                MIN_FACTOR
            } else {
                MIN_FACTOR.max(SAFETY * CONTROLLER_POWER.pow(err))
            };
            h_abs *= factor;
            rejected = true;
            self.nrejected += 1;
        }
    }

    /// Current time.
    #[inline]
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current state.
    #[inline]
    pub fn y(&self) -> &[f64; N] {
        &self.y
    }

    /// Start of the last accepted step (`t0` before the first step).
    #[inline]
    pub fn t_old(&self) -> f64 {
        self.t_old
    }

    /// State at [`Self::t_old`].
    #[inline]
    pub fn y_old(&self) -> &[f64; N] {
        &self.y_old
    }

    /// The endpoint `t_bound` of the span.
    #[inline]
    pub fn t_bound(&self) -> f64 {
        self.t_bound
    }

    /// The 7th-order interpolant of the last accepted step on `[t_old, t]` (see [`dense`]).
    ///
    /// The first call after a step evaluates the three extra stages
    /// `K[s] = f(t_old + c_s h, y_old + h Σ_{j<s} a_{sj} K[j])`, `s = 13, 14, 15`
    /// (3 evaluations) and forms `F₀ … F₆`; later calls return the cached value. Before the
    /// first step it is the constant `y0` on `[t0, t0]`. After [`Self::step`] returned an
    /// error it is still the last accepted step's (its stages are recomputed: 12 more
    /// evaluations).
    pub fn dense_output(&mut self) -> DenseStep<N> {
        if let Some(d) = self.dense {
            return d;
        }
        if self.naccepted == 0 {
            let d = DenseStep::constant(self.t, self.y);
            self.dense = Some(d);
            return d;
        }
        let (t_old, h) = (self.t_old, self.t - self.t_old);
        if !self.stages_valid {
            // Only after `step` returned an error: redo the accepted step's stages.
            self.k[0] = (self.f)(t_old, &self.y_old);
            rk_stages(&mut self.f, &mut self.k, t_old, &self.y_old, h);
            self.k[N_STAGES] = self.fy;
            self.stages_valid = true;
            self.nfev += N_STAGES;
        }
        {
            let y_old = &self.y_old;
            let k = &mut self.k;
            let f = &mut self.f;
            // Stages 13, 14, 15, unrolled as in `rk_stages`.
            macro_rules! stages {
                ($($s:literal)*) => {$(
                    let ys = combine(y_old, h, k, &A[$s], $s);
                    k[$s] = f(madd(C[$s], h, t_old), &ys);
                )*};
            }
            stages!(13 14 15);
        }
        self.nfev += N_STAGES_EXTENDED - N_STAGES - 1;
        let k = &self.k;
        let (f_old, f_new) = (&k[0], &k[N_STAGES]);
        let mut coef = [[0.0; N]; 7];
        for i in 0..N {
            let dy = self.y[i] - self.y_old[i];
            coef[0][i] = dy;
            coef[1][i] = h * f_old[i] - dy;
            coef[2][i] = 2.0 * dy - h * (f_old[i] + f_new[i]);
        }
        macro_rules! rows {
            ($($r:literal)*) => {$(
                coef[3 + $r] = combine(&[0.0; N], h, k, &D[$r], N_STAGES_EXTENDED);
            )*};
        }
        rows!(0 1 2 3);
        let d = DenseStep::new(t_old, self.t, self.y_old, self.y, coef);
        self.dense = Some(d);
        d
    }

    /// Right-hand-side evaluations so far (see [`Stats::nfev`]).
    #[inline]
    pub fn nfev(&self) -> usize {
        self.nfev
    }

    /// Accepted steps so far.
    #[inline]
    pub fn naccepted(&self) -> usize {
        self.naccepted
    }

    /// Rejected steps so far.
    #[inline]
    pub fn nrejected(&self) -> usize {
        self.nrejected
    }

    /// The counters as one value.
    #[inline]
    pub fn stats(&self) -> Stats {
        Stats {
            nfev: self.nfev,
            naccepted: self.naccepted,
            nrejected: self.nrejected,
        }
    }
}

/// Checks the inputs of [`Dop853::new`]; the message names the offending value.
fn validate<const N: usize>(
    t0: f64,
    y0: &[f64; N],
    t_bound: f64,
    opts: &Options,
) -> Result<(), Dop853Error> {
    let bad = |m: String| Err(Dop853Error::BadOption(m));
    let min_rtol = 100.0 * f64::EPSILON;
    if !(opts.rtol.is_finite() && opts.rtol >= min_rtol) {
        return bad(format!(
            "rtol = {:e} must be finite and >= 100 eps = {min_rtol:e}",
            opts.rtol
        ));
    }
    if !(opts.atol.is_finite() && opts.atol >= 0.0) {
        return bad(format!("atol = {:e} must be finite and >= 0", opts.atol));
    }
    if opts.max_step.is_nan() || opts.max_step <= 0.0 {
        return bad(format!("max_step = {:e} must be > 0", opts.max_step));
    }
    if opts.max_steps == 0 {
        return bad("max_steps = 0 must be > 0".to_string());
    }
    if !t0.is_finite() {
        return bad(format!("t0 = {t0} must be finite"));
    }
    if !t_bound.is_finite() {
        return bad(format!("t_bound = {t_bound} must be finite"));
    }
    if t_bound == t0 {
        return bad(format!("t_bound = {t_bound} must differ from t0 = {t0}"));
    }
    if let Some((i, v)) = y0.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return bad(format!("y0[{i}] = {v} must be finite"));
    }
    if let Some(h) = opts.first_step {
        let span = (t_bound - t0).abs();
        if !(h > 0.0 && h <= span) {
            return bad(format!(
                "first_step = {h:e} must be in (0, |t_bound - t0|] = (0, {span:e}]"
            ));
        }
    }
    Ok(())
}

/// Integrates `y' = f(t, y)`, `y(t0) = y0` up to `t_end` (forward or backward) and returns
/// `y(t_end)` with the counters.
pub fn integrate<F, const N: usize>(
    f: F,
    t0: f64,
    y0: [f64; N],
    t_end: f64,
    opts: Options,
) -> Result<([f64; N], Stats), Dop853Error>
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    let mut solver = Dop853::new(f, t0, y0, t_end, opts)?;
    while solver.step()? {}
    Ok((solver.y, solver.stats()))
}

#[cfg(test)]
mod tests {
    use super::tableau::*;
    use super::*;

    /// The controller's shortcut is exact: below `CAPPED_ERR` the factor is at least
    /// `CAPPED_FACTOR` > 1, so |h|·factor ≥ max_step and the next step is max_step either way.
    #[test]
    fn capped_steps_keep_max_step_exactly() {
        let mut err = 1e-300;
        while err < CAPPED_ERR {
            let factor = MAX_FACTOR.min(SAFETY * CONTROLLER_POWER.pow(err));
            assert!(factor >= CAPPED_FACTOR, "err = {err:e}: factor {factor}");
            err *= 1.001;
        }
        for k in 0..1000 {
            let err = CAPPED_ERR.next_down() - k as f64 * f64::EPSILON;
            assert!(
                SAFETY * CONTROLLER_POWER.pow(err) >= CAPPED_FACTOR,
                "err = {err:e}"
            );
        }
    }

    /// Row sums `Σ_j a_{sj} = c_s` (every stage is consistent).
    #[test]
    fn tableau_row_sums_equal_nodes() {
        for s in 0..N_STAGES_EXTENDED {
            let sum: f64 = A[s].iter().sum();
            assert!((sum - C[s]).abs() < 1e-14, "row {s}: {sum} vs {}", C[s]);
        }
    }

    /// Quadrature conditions `Σ b_j c_j^m = 1/(m+1)`, m = 0…7 (order 8); the 5th- and
    /// 3rd-order error weights sum to 0 (consistent embedded methods).
    #[test]
    fn tableau_quadrature_conditions() {
        for m in 0..8 {
            let s: f64 = (0..N_STAGES).map(|j| B[j] * C[j].powi(m)).sum();
            assert!((s - 1.0 / (m as f64 + 1.0)).abs() < 1e-13, "m = {m}: {s}");
        }
        let s5: f64 = E5.iter().sum();
        let s3: f64 = E3.iter().sum();
        assert!(s5.abs() < 1e-14 && s3.abs() < 1e-14, "{s5} {s3}");
        // The embedded 3rd-order method B − E3 integrates t² exactly, but not t³.
        let q = |m: i32| -> f64 { (0..N_STAGES).map(|j| (B[j] - E3[j]) * C[j].powi(m)).sum() };
        assert!((q(2) - 1.0 / 3.0).abs() < 1e-14);
        assert!((q(3) - 0.25).abs() > 1e-6);
    }

    /// The dense output has `u'(0) = f_old`, `u'(1) = f_new` up to rounding, tested on a
    /// step of y' = y.
    #[test]
    fn dense_output_derivatives_at_ends() {
        let opts = Options {
            first_step: Some(0.1),
            ..Options::default()
        };
        let mut s = Dop853::new(|_t, y: &[f64; 1]| [y[0]], 0.0, [1.0], 1.0, opts).unwrap();
        assert!(s.step().unwrap());
        let d = s.dense_output();
        let (t0, t1) = (d.t_old(), d.t_new());
        let eps = 1e-6;
        let d0 = (d.eval_component(t0 + eps, 0) - d.eval_component(t0 - eps, 0)) / (2.0 * eps);
        let d1 = (d.eval_component(t1 + eps, 0) - d.eval_component(t1 - eps, 0)) / (2.0 * eps);
        assert!((d0 - 1.0).abs() < 1e-8, "{d0}");
        assert!((d1 - s.y()[0]).abs() < 1e-8, "{d1}");
    }

    /// FSAL accounting: 2 evaluations to start, 12 per attempted step, 3 per dense output,
    /// and the dense output is cached per step.
    #[test]
    fn nfev_accounting() {
        let mut s = Dop853::new(
            |t, y: &[f64; 1]| [y[0] * t.cos()],
            0.0,
            [1.0],
            3.0,
            Options::default(),
        )
        .unwrap();
        assert_eq!(s.nfev(), 2);
        s.step().unwrap();
        let n = s.nfev();
        assert_eq!(n, 2 + 12 * (s.naccepted() + s.nrejected()));
        let a = s.dense_output();
        let b = s.dense_output();
        assert_eq!(a, b);
        assert_eq!(s.nfev(), n + 3);
        while s.step().unwrap() {}
        assert_eq!(s.nfev(), 2 + 3 + 12 * (s.naccepted() + s.nrejected()));
        assert!(!s.step().unwrap());
    }

    /// A failed `step` overwrites the stages with rejected trials; the dense output must still
    /// be the last accepted step's. Here y' = 1 (y = t) until t = 1, NaN after.
    #[test]
    fn dense_output_after_failed_step() {
        let f = |t: f64, _y: &[f64; 1]| [if t < 1.0 { 1.0 } else { f64::NAN }];
        let mut s = Dop853::new(f, 0.0, [0.0], 2.0, Options::default()).unwrap();
        let e = loop {
            match s.step() {
                Ok(true) => {}
                Ok(false) => panic!("crossed the NaN region"),
                Err(e) => break e,
            }
        };
        assert!(
            matches!(e, Dop853Error::NonFinite { t } if t < 1.0 && t > 0.999),
            "{e}"
        );
        assert!(s.nrejected() > 0);
        let d = s.dense_output();
        assert_eq!((d.t_old(), d.t_new()), (s.t_old(), s.t()));
        for m in 1..10 {
            let t = s.t_old() + (s.t() - s.t_old()) * m as f64 / 10.0;
            let u = d.eval_component(t, 0);
            assert!((u - t).abs() < 1e-12, "u({t}) = {u}");
        }
    }

    #[test]
    fn error_messages_are_one_line_and_name_the_value() {
        let e = Dop853::new(
            |_t, y: &[f64; 1]| [y[0]],
            0.0,
            [1.0],
            1.0,
            Options {
                atol: -3.5,
                ..Options::default()
            },
        )
        .err()
        .unwrap();
        let m = e.to_string();
        assert!(
            m.contains("atol") && m.contains("-3.5e0") && !m.contains('\n'),
            "{m}"
        );
        let m = Dop853Error::StepTooSmall { t: 0.75, h: 1e-17 }.to_string();
        assert!(m.contains("0.75") && m.contains("1e-17"), "{m}");
    }
}
