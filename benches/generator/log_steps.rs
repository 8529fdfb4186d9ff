//! Probe (f64, not a proof): how many Taylor steps a CoR run needs near the branch points when
//! the independent variable is s = ln|x_w| (x_w the component at its branch point, or t itself
//! at the start) instead of t.
//!
//! Near a branch point t_b the solution is x = g(τ, |τ|^q, …), τ = t − t_b, so a Taylor series
//! in t has radius |τ| and the steps shrink (approaching) or grow (leaving) geometrically: ≈ 75
//! of SHC DSS v0 = 1's 97 pieces. In s = ln|τ| the powers |τ|^q = e^{qs} are entire and the
//! radius in s grows without bound as |τ| → 0, so a few steps in s reach |τ| = 1e-8, where a
//! low-order step crosses. The systems in s:
//!
//! ```text
//! start (s = ln t):            dx/ds = e^s f(x)
//! crossing of x_w (s = ln|x_w|, x_w = σe^s; the state keeps t in slot w):
//!                              dx_j/ds = x_w f_j(x)/f_w(x),   dt/ds = x_w/f_w(x)
//! ```
//!
//! Both engines of this probe use the same step rule (order K, tol 8e-16, Jorba–Zou from the
//! last two coefficients, then shortened while h^K·|x_K| at the step's far end exceeds the
//! tolerance: the a-priori box's remainder that limits the rigorous engine's steps), on one
//! f64 trajectory, and count steps region by region.
//!
//! `cargo run --release --features bench --example log_steps -- [shc|maxwell] B,Γ,κ,σ,n,p`

use bwcl::arith::Scalar;
use bwcl::arith::jet::series::Series;
use bwcl::models::CollisionModel;
use bwcl::models::maxwell::Maxwell;
use bwcl::models::params::{ModelKind, NdParams};
use bwcl::models::shc::Shc;

const K: usize = 16;
const TOL: f64 = 8e-16;

/// The independent variable of a step.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Var {
    /// t.
    Time,
    /// s = ln t (the start's branch point at t = 0).
    LogTime,
    /// s = ln|x_w| for component w, with the sign σ of x_w.
    LogComp(usize, f64),
}

/// The Taylor coefficients (orders 0..=K) of the solution of y' = G(y, s) through y0 at s0, by
/// K + 1 Picard passes on series.
/// G(y, s) on series.
type System<'a, const N: usize> = dyn Fn(&[Series<f64>; N], &Series<f64>) -> [Series<f64>; N] + 'a;

fn coefficients<const N: usize>(g: &System<'_, N>, y0: &[f64; N], s0: f64) -> [Vec<f64>; N] {
    let s = Series::variable(s0, K);
    let mut y: [Series<f64>; N] = std::array::from_fn(|i| Series::constant(y0[i], K));
    for _ in 0..=K {
        let d = g(&y, &s);
        y = std::array::from_fn(|i| {
            let mut c = vec![0.0; K + 1];
            c[0] = y0[i];
            for k in 0..K {
                c[k + 1] = d[i].c[k] / (k + 1) as f64;
            }
            Series::from_coefficients(c)
        });
    }
    y.map(|s| s.c)
}

fn exp_series(s: &Series<f64>) -> Series<f64> {
    // s = s0 + σ: e^s = e^{s0} Σ σ^k/k!
    let mut c = vec![0.0; s.c.len()];
    let mut f = s.c[0].exp();
    for (k, ck) in c.iter_mut().enumerate() {
        *ck = f;
        f /= (k + 1) as f64;
    }
    Series::from_coefficients(c)
}

fn eval(c: &[f64], h: f64) -> f64 {
    c.iter().rev().fold(0.0, |a, &ck| a * h + ck)
}

struct Probe<'a, const N: usize, M: CollisionModel<f64, N>> {
    m: &'a M,
}

impl<const N: usize, M: CollisionModel<f64, N>> Probe<'_, N, M> {
    /// G(y, s) in the variable `v`.
    fn system(&self, v: Var) -> impl Fn(&[Series<f64>; N], &Series<f64>) -> [Series<f64>; N] + '_ {
        move |y, s| match v {
            Var::Time => self.m.field(y),
            Var::LogTime => {
                let e = exp_series(s);
                self.m.field(y).map(|f| f * e.clone())
            }
            Var::LogComp(w, sg) => {
                let xw = exp_series(s).scale(&sg);
                let x: [Series<f64>; N] =
                    std::array::from_fn(|j| if j == w { xw.clone() } else { y[j].clone() });
                let f = self.m.field(&x);
                let r = xw / f[w].clone();
                std::array::from_fn(|j| {
                    if j == w {
                        r.clone()
                    } else {
                        f[j].clone() * r.clone()
                    }
                })
            }
        }
    }

    /// The state (t, x) in the variable's coordinates (y, s0).
    fn to_var(v: Var, t: f64, x: &[f64; N]) -> ([f64; N], f64) {
        match v {
            Var::Time => (*x, t),
            Var::LogTime => (*x, t.ln()),
            Var::LogComp(w, _) => {
                let mut y = *x;
                y[w] = t;
                (y, x[w].abs().ln())
            }
        }
    }

    fn from_var(v: Var, y: &[f64; N], s: f64) -> (f64, [f64; N]) {
        match v {
            Var::Time => (s, *y),
            Var::LogTime => (s.exp(), *y),
            Var::LogComp(w, sg) => {
                let mut x = *y;
                x[w] = sg * s.exp();
                (y[w], x)
            }
        }
    }

    /// One step in `v` from (t, x) in the direction `dir` of s: its length in s and the state at
    /// its end, or `None`.
    fn step(
        &self,
        v: Var,
        t: f64,
        x: &[f64; N],
        dir: f64,
        h_cap: f64,
    ) -> Option<(f64, f64, [f64; N])> {
        let (y0, s0) = Self::to_var(v, t, x);
        let g = self.system(v);
        let c = coefficients::<N>(&g, &y0, s0);
        let mut h = h_cap;
        for ci in &c {
            for kk in [K - 1, K] {
                let m = ci[kk].abs();
                if m > 0.0 {
                    h = h.min((TOL / m).powf(1.0 / kk as f64));
                }
            }
        }
        if !h.is_finite() || h <= 0.0 {
            return None;
        }
        // the remainder over the step: h^K·|x_K| at the far end (and the middle) below tol
        for _ in 0..60 {
            let mut worst = 0.0_f64;
            for frac in [0.5, 1.0] {
                let y1: [f64; N] = std::array::from_fn(|i| eval(&c[i], dir * h * frac));
                let s1 = s0 + dir * h * frac;
                let (t1, x1) = Self::from_var(v, &y1, s1);
                let (yb, sb) = Self::to_var(v, t1, &x1);
                let cb = coefficients::<N>(&g, &yb, sb);
                for cbi in &cb {
                    worst = worst.max(cbi[K].abs());
                }
            }
            if worst.is_finite() && h.powi(K as i32) * worst <= TOL {
                let y1: [f64; N] = std::array::from_fn(|i| eval(&c[i], dir * h));
                let (t1, x1) = Self::from_var(v, &y1, s0 + dir * h);
                return Some((h, t1, x1));
            }
            h *= 0.8;
        }
        None
    }
}

/// n classical RK4 steps over dt (the reference path across a branch point).
fn rk4<const N: usize, M: CollisionModel<f64, N>>(
    m: &M,
    x: &[f64; N],
    dt: f64,
    n: usize,
) -> [f64; N] {
    let h = dt / n as f64;
    let mut x = *x;
    let add = |a: &[f64; N], b: &[f64; N], c: f64| -> [f64; N] {
        std::array::from_fn(|i| a[i] + c * b[i])
    };
    for _ in 0..n {
        let k1 = m.field(&x);
        let k2 = m.field(&add(&x, &k1, h / 2.0));
        let k3 = m.field(&add(&x, &k2, h / 2.0));
        let k4 = m.field(&add(&x, &k3, h));
        x = std::array::from_fn(|i| x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    x
}

fn run<const N: usize, M: CollisionModel<f64, N>>(m: &M, switching: &[usize]) {
    let p = Probe { m };
    // the reference path: Taylor steps in t from t = 1e-8 (a low-order step from the start:
    // x ≈ x0 + t f(x0)), crossing each switching surface by one step where it is 1e-8 away
    let x0 = m.initial_state();
    let f0 = m.field(&x0);
    let t_a = 1e-8;
    let xa: [f64; N] = std::array::from_fn(|i| x0[i] + t_a * f0[i]);
    // mode 0: t only (the start from t = 5e-3, crossings where 2e-3 away, as the engine);
    // mode 1: the larger of t and the log variables' steps, the same start and crossings;
    // mode 2: as 1, from t = 1e-8 and crossing where 1e-8 away (by low-order steps)
    for mode in 0..3 {
        let (mut t, mut x) = (t_a, xa);
        let mut counts = std::collections::BTreeMap::<String, usize>::new();
        let mut total = 0;
        let mut log = String::new();
        if mode < 2 {
            // the engine's start step: one (costly) step to t = 5e-3
            let mut tt = t;
            while tt < 5e-3 {
                let (_, t1, x1) = p.step(Var::Time, tt, &x, 1.0, 5e-3 - tt).unwrap();
                tt = t1;
                x = x1;
            }
            t = tt;
            *counts.entry("start step (puiseux)".into()).or_default() += 1;
        }
        let near = if mode < 2 { 2e-3 } else { 1e-8 };
        while t < 8.0 {
            let f = m.field(&x);
            // a branch point near: cross it (time to reach 0 at the present rate)
            if let Some(&w) = switching
                .iter()
                .find(|&&w| x[w].abs() < near * f[w].abs() && x[w] * f[w] < 0.0)
            {
                let dt = 2.0 * x[w].abs() / f[w].abs();
                x = rk4(m, &x, dt, 2000);
                t += dt;
                *counts
                    .entry(format!(
                        "crossing {} ({})",
                        M::STATE_NAMES[w],
                        if mode < 2 { "puiseux" } else { "low order" }
                    ))
                    .or_default() += 1;
                total += 1;
                continue;
            }
            let (ht, _, xt) = p
                .step(Var::Time, t, &x, 1.0, f64::INFINITY)
                .expect("a t step");
            let mut best = (ht, xt, Var::Time);
            if mode >= 1 {
                let mut vars = vec![Var::LogTime];
                for &w in switching {
                    if x[w] != 0.0 {
                        vars.push(Var::LogComp(w, x[w].signum()));
                    }
                }
                for v in vars {
                    let dir = match v {
                        Var::LogComp(w, _) => (x[w] * f[w]).signum(),
                        _ => 1.0,
                    };
                    // approaching: stop at |x_w| = near·|f_w|·0.5 (ln of it)
                    let cap = match v {
                        Var::LogComp(w, _) if dir < 0.0 => {
                            (x[w].abs() / (0.5 * near * f[w].abs())).ln().max(0.0)
                        }
                        _ => f64::INFINITY,
                    };
                    if cap == 0.0 {
                        continue;
                    }
                    if let Some((_, t1, x1)) = p.step(v, t, &x, dir, cap)
                        && t1 - t > best.0
                    {
                        best = (t1 - t, x1, v);
                    }
                }
            }
            let key = match best.2 {
                Var::Time => "t".to_string(),
                Var::LogTime => "ln t".to_string(),
                Var::LogComp(w, _) => format!("ln|{}|", M::STATE_NAMES[w]),
            };
            log.push_str(&format!("{key}@{t:.3e} "));
            *counts.entry(key).or_default() += 1;
            total += 1;
            t += best.0;
            x = best.1;
            // separation: F ≤ 0 and v ≥ 0 (a probe: checked at step ends only)
            if m.force(&x) <= 0.0 && m.velocity(&x) >= 0.0 {
                break;
            }
        }
        println!(
            "{}: {} steps to t = {t:.4} {:?}",
            [
                "t steps, start to 5e-3 and crossings from 2e-3 as the engine",
                "t or ln steps, the same start and crossings",
                "t or ln steps from t = 1e-8, crossing from 1e-8"
            ][mode],
            total,
            counts
        );
        if std::env::var_os("LOG_STEPS_TRACE").is_some() {
            println!("  {log}");
        }
    }
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let kind = a.get(1).map_or("shc", |s| s.as_str());
    let text = a
        .get(2)
        .map_or("1.43,-1.42,0.632,0.00715,1.31,1.27", |s| s.as_str());
    match kind {
        "shc" => {
            let m = Shc::new(NdParams::parse(ModelKind::Shc, text).unwrap());
            run::<3, _>(&m, &[0, 1]);
        }
        _ => {
            let m = Maxwell::new(NdParams::parse(ModelKind::Maxwell, text).unwrap());
            run::<4, _>(&m, &[1, 2]);
        }
    }
}
