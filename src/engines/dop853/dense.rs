//! Dense output of one DOP853 step: the 7th-order continuous extension.
//!
//! With `θ = (t − t_old)/h ∈ [0, 1]` and `θ' = 1 − θ`, the interpolant of Hairer's `CONTD8`
//! (SciPy's `Dop853DenseOutput`) is the nested product
//!
//! ```text
//! u(θ) = y_old + θ (F₀ + θ' (F₁ + θ (F₂ + θ' (F₃ + θ (F₄ + θ' (F₅ + θ F₆))))))
//! ```
//!
//! with, for `Δ = y_new − y_old`, `f_old = K[0]`, `f_new = K[12]`,
//!
//! ```text
//! F₀ = Δ,   F₁ = h f_old − Δ,   F₂ = 2Δ − h (f_old + f_new),   F₃₊ᵣ = h Σⱼ D[r][j] K[j]  (r = 0…3)
//! ```
//!
//! so `u(0) = y_old`, `u(1) = y_new`, `u'(0) = f_old`, `u'(1) = f_new` and `u` is a 7th-order
//! approximation on the whole step (it needs the three extra stages 13–15 of
//! [`super::tableau::A`]).

/// The interpolating polynomial of one accepted step, `t ∈ [t_old, t_new]`.
///
/// Evaluating outside the step extrapolates the same polynomial (not meaningful far away).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DenseStep<const N: usize> {
    t_old: f64,
    t_new: f64,
    h: f64,
    y_old: [f64; N],
    y_new: [f64; N],
    /// The coefficients `F₀ … F₆` of the nested form (see the module docs).
    f: [[f64; N]; 7],
}

impl<const N: usize> DenseStep<N> {
    /// Assembles the step from its end points and the coefficients `F₀ … F₆` of the module docs;
    /// `h = t_new − t_old` is the step the coefficients were computed with.
    #[inline]
    pub(crate) fn new(
        t_old: f64,
        t_new: f64,
        y_old: [f64; N],
        y_new: [f64; N],
        f: [[f64; N]; 7],
    ) -> Self {
        DenseStep {
            t_old,
            t_new,
            h: t_new - t_old,
            y_old,
            y_new,
            f,
        }
    }

    /// The degenerate step `[t, t]` on which the interpolant is the constant `y` (used before
    /// the solver has taken a step).
    #[inline]
    pub(crate) fn constant(t: f64, y: [f64; N]) -> Self {
        DenseStep {
            t_old: t,
            t_new: t,
            h: 1.0,
            y_old: y,
            y_new: y,
            f: [[0.0; N]; 7],
        }
    }

    /// Start of the step.
    #[inline]
    pub fn t_old(&self) -> f64 {
        self.t_old
    }

    /// End of the step (the solver's accepted `t`, bit for bit).
    #[inline]
    pub fn t_new(&self) -> f64 {
        self.t_new
    }

    /// Signed step size `h = t_new − t_old` (negative when integrating backward).
    #[inline]
    pub fn h(&self) -> f64 {
        self.t_new - self.t_old
    }

    /// `u(θ)` for every component, `θ = (t − t_old)/h`, by the nested product of the module
    /// docs (Horner-like, 7 multiply–adds per component). Exact (bitwise) at `t_old`/`t_new`.
    #[inline]
    pub fn eval(&self, t: f64) -> [f64; N] {
        if t == self.t_old {
            return self.y_old;
        }
        if t == self.t_new {
            return self.y_new;
        }
        let x = (t - self.t_old) / self.h;
        core::array::from_fn(|i| self.poly(x, i))
    }

    /// Component `i` of [`Self::eval`]. Panics if `i >= N`.
    #[inline]
    pub fn eval_component(&self, t: f64, i: usize) -> f64 {
        if t == self.t_old {
            return self.y_old[i];
        }
        if t == self.t_new {
            return self.y_new[i];
        }
        let x = (t - self.t_old) / self.h;
        self.poly(x, i)
    }

    /// `y_old + θ (F₀ + θ' (F₁ + θ (F₂ + θ' (F₃ + θ (F₄ + θ' (F₅ + θ F₆))))))`, `θ' = 1 − θ`.
    #[inline(always)]
    fn poly(&self, x: f64, i: usize) -> f64 {
        let x1 = 1.0 - x;
        let f = &self.f;
        let mut acc = f[6][i] * x;
        acc = (acc + f[5][i]) * x1;
        acc = (acc + f[4][i]) * x;
        acc = (acc + f[3][i]) * x1;
        acc = (acc + f[2][i]) * x;
        acc = (acc + f[1][i]) * x1;
        acc = (acc + f[0][i]) * x;
        self.y_old[i] + acc
    }
}
