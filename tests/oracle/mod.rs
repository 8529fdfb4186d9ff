//! An independent high-precision reference integrator for T_s and e (issue #12): plain Taylor
//! recurrences in MPFR floats (rug), written from the paper, sharing no code with the crate's
//! models, tapes or series, so that it can disagree with the crate.
//!
//! Fields (the paper's labels):
//! - NDBWSHCCM (eq:BWSHCCM_nd), state (X, Z, V):
//!   Ẋ = V, Ż = V − B|Z|^(n−1)Z|V| − Γ|Z|^n V,
//!   V̇ = F = −κ|X|^(p−1)X − κ_c|Z|^(p−1)Z − σ|X|^p V; X = Z = 0, V = −1 at T = 0.
//! - NDBWMCM (eq:BWMCM_nd), state (R, Y, Z, W):
//!   Ṙ = κσ|Y|^(p−1)Y + κ_cσ|Z|^(p−1)Z, Ẏ = W, Ż = W − B|Z|^(n−1)Z|W| − Γ|Z|^n W,
//!   Ẇ = −Ṙ/σ − κpσ|Y|^(p−1)Ẏ − κ_c pσ|Z|^(p−1)Ż; R = Y = Z = 0, W = −1 at T = 0;
//!   outputs (eq:BWMCM_nd_output) X = R + Y, V = Ṙ + Ẏ, and F = −κ|Y|^(p−1)Y − κ_c|Z|^(p−1)Z
//!   = −Ṙ/σ.
//!
//! T_s = inf{T ≥ 0 : F ≤ 0 ∧ V ≥ 0}, e = V(T_s).
//!
//! Method. Where no component under |·|^a or |·| is zero, the field is analytic: a Taylor step
//! of order K, its length from the last two coefficients (|c_k| h^k ≤ tol, k = K−1, K), which
//! also keeps it a fraction tol^(1/K) of the distance to the nearest singularity (the zero of
//! a switching component, where the solution has a branch point). The steps therefore approach
//! such a zero geometrically; once its predicted distance is below `cross` the zero is crossed
//! by one Euler step of length ≤ 2·cross (local error O(cross²): the field is Lipschitz), and
//! the steps leave it geometrically again. The start (X = Z = 0) is left the same way. T_s is
//! the root of F's Taylor polynomial (bisection, then Newton) in the first step where F goes
//! from > 0 to ≤ 0 with V ≥ 0 at the root. Cases where T_s falls in a crossing step, or where
//! V turns ≥ 0 while F ≤ 0, are refused (panic) rather than guessed, except for the explicit
//! `event_at_crossing` option (used for the closed-form check where F vanishes with X).

use rug::Float;
use rug::float::Round;
use rug::ops::Pow;

/// Which model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Shc,
    Maxwell,
}

/// Numerical settings of one run.
#[derive(Clone, Copy, Debug)]
pub struct Setting {
    /// MPFR precision (bits).
    pub prec: u32,
    /// Taylor order K.
    pub order: usize,
    /// Local error target 10^(−tol_digits) per step.
    pub tol_digits: i32,
    /// Crossing half-width 10^(−cross_digits).
    pub cross_digits: i32,
}

/// The two settings of the self-check.
pub const SETTING_A: Setting = Setting {
    prec: 200,
    order: 60,
    tol_digits: 42,
    cross_digits: 25,
};
pub const SETTING_B: Setting = Setting {
    prec: 300,
    order: 80,
    tol_digits: 55,
    cross_digits: 30,
};

/// Nondimensional parameters (B, Γ, κ, σ, n, p) at the run's precision.
#[derive(Clone, Debug)]
pub struct Params {
    pub b: Float,
    pub g: Float,
    pub kappa: Float,
    pub sigma: Float,
    pub n: Float,
    pub p: Float,
}

/// Parses a decimal, correctly rounded to `prec` bits.
pub fn dec(prec: u32, s: &str) -> Float {
    Float::with_val(
        prec,
        Float::parse(s.trim()).unwrap_or_else(|e| panic!("{s}: {e}")),
    )
}

impl Params {
    /// "B,Γ,κ,σ,n,p" as decimals.
    pub fn parse(prec: u32, text: &str) -> Params {
        let v: Vec<Float> = text.split(',').map(|s| dec(prec, s)).collect();
        assert_eq!(v.len(), 6, "{text}");
        let [b, g, kappa, sigma, n, p]: [Float; 6] = v.try_into().unwrap();
        Params {
            b,
            g,
            kappa,
            sigma,
            n,
            p,
        }
    }

    /// The base-parameter map 𝓟(P*, v0) of sec:KVCL / sec:MCL:
    /// (B_b s, Γ_b s, κ, σ_b v0^m, n, p), s = v0^(2n/(p+1)), m = 1 (NDBWSHCCM) or
    /// (p−1)/(p+1) (NDBWMCM).
    pub fn from_base(kind: Kind, prec: u32, base: &str, v0: &str) -> Params {
        let b = Params::parse(prec, base);
        let v0 = dec(prec, v0);
        let p1 = Float::with_val(prec, &b.p + 1u32);
        let s = Float::with_val(prec, (&v0).pow(Float::with_val(prec, 2u32 * &b.n) / &p1));
        let m = match kind {
            Kind::Shc => Float::with_val(prec, 1u32),
            Kind::Maxwell => Float::with_val(prec, &b.p - 1u32) / &p1,
        };
        Params {
            b: Float::with_val(prec, &b.b * &s),
            g: Float::with_val(prec, &b.g * &s),
            sigma: Float::with_val(prec, &b.sigma * Float::with_val(prec, (&v0).pow(&m))),
            kappa: b.kappa,
            n: b.n,
            p: b.p,
        }
    }
}

/// The reference values of one run.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub ts: Float,
    pub e: Float,
    pub steps: usize,
    pub crossings: usize,
}

/// Options beyond the setting.
#[derive(Clone, Copy, Debug, Default)]
pub struct Extra {
    /// Accept T_s inside a crossing step as the crossing time (exact only when F vanishes
    /// together with the crossing component; for closed-form checks only).
    pub event_at_crossing: bool,
}

struct Run<'a> {
    kind: Kind,
    prm: &'a Params,
    prec: u32,
    order: usize,
    kc: Float,
    /// Components whose zero is a singularity of the field.
    singular: Vec<usize>,
}

fn zero(prec: u32) -> Float {
    Float::with_val(prec, 0)
}

/// |x|^a for x ≥ 0 given as y (0^0 = 1).
fn powp(y: &Float, a: &Float) -> Float {
    Float::with_val(y.prec(), y.pow(a))
}

/// Sign as ±1 (0 for 0).
fn sgn(x: &Float) -> i32 {
    if x.is_zero() {
        0
    } else if x.is_sign_negative() {
        -1
    } else {
        1
    }
}

/// Coefficient k of u = y^a from y_0..y_k and u_0..u_{k−1} (y_0 > 0):
/// k y_0 u_k = Σ_{j<k} (a(k−j) − j) y_{k−j} u_j (from y u′ = a u y′). Exponents 0 and 1 exactly.
fn power_coef(prec: u32, y: &[Float], u: &[Float], a: &Float, k: usize) -> Float {
    if *a == 0 {
        return if k == 0 {
            Float::with_val(prec, 1)
        } else {
            zero(prec)
        };
    }
    if *a == 1 {
        return y[k].clone();
    }
    if k == 0 {
        assert!(y[0] > 0, "power of a non-positive base in a Taylor step");
        return powp(&y[0], a);
    }
    let mut acc = zero(prec);
    for j in 0..k {
        let w = Float::with_val(prec, a * ((k - j) as u32)) - (j as u32);
        acc += w * &y[k - j] * &u[j];
    }
    acc / (Float::with_val(prec, &y[0] * (k as u32)))
}

/// Cauchy product coefficient k.
fn prod(prec: u32, a: &[Float], b: &[Float], k: usize) -> Float {
    let mut acc = zero(prec);
    for j in 0..=k {
        acc += Float::with_val(prec, &a[j] * &b[k - j]);
    }
    acc
}

/// Σ c_k τ^k (Horner).
pub fn horner(c: &[Float], tau: &Float) -> Float {
    let prec = tau.prec();
    let mut acc = zero(prec);
    for ck in c.iter().rev() {
        acc *= tau;
        acc += ck;
    }
    acc
}

fn deriv(c: &[Float]) -> Vec<Float> {
    c.iter()
        .enumerate()
        .skip(1)
        .map(|(k, ck)| Float::with_val(ck.prec(), ck * (k as u32)))
        .collect()
}

/// The root of polynomial `c` in [lo, hi] (sign change assumed): bisection, then Newton.
fn poly_root(c: &[Float], lo: &Float, hi: &Float) -> Float {
    let prec = lo.prec();
    let (mut a, mut b) = (lo.clone(), hi.clone());
    let sa = sgn(&horner(c, &a));
    for _ in 0..40 {
        let m = Float::with_val(prec, &a + &b) / 2u32;
        if sgn(&horner(c, &m)) == sa {
            a = m;
        } else {
            b = m;
        }
    }
    let d = deriv(c);
    let mut x = Float::with_val(prec, &a + &b) / 2u32;
    for _ in 0..30 {
        let dx = horner(c, &x) / horner(&d, &x);
        x -= &dx;
        let eps = Float::with_val(prec, 1) >> (prec as i32 - 8);
        let small = dx.is_zero() || Float::with_val(prec, dx.abs_ref()) <= eps * x.clone().abs();
        if small {
            break;
        }
    }
    assert!(
        x >= *lo && x <= *hi,
        "Newton left the bracket [{lo}, {hi}]: {x}"
    );
    x
}

/// Jets of one step: state coefficients (K+1 each), F's and V's polynomials.
struct Jets {
    x: Vec<Vec<Float>>,
    f: Vec<Float>,
    v: Vec<Float>,
}

impl<'a> Run<'a> {
    fn new(kind: Kind, prm: &'a Params, prec: u32, order: usize) -> Self {
        let kc = Float::with_val(prec, 1u32 - &prm.kappa);
        let p_one = prm.p == 1;
        let hyst = !prm.b.is_zero() || !prm.g.is_zero();
        let mut singular = Vec::new();
        match kind {
            Kind::Shc => {
                // X: |X|^p (σ term) and |X|^(p−1)X; Z: |Z|^(p−1)Z, |Z|^n; V: |V|
                if !p_one || !prm.sigma.is_zero() {
                    singular.push(0);
                }
                if !p_one || hyst {
                    singular.push(1);
                }
                if !prm.b.is_zero() {
                    singular.push(2);
                }
            }
            Kind::Maxwell => {
                if !p_one {
                    singular.push(1);
                }
                if !p_one || hyst {
                    singular.push(2);
                }
                if !prm.b.is_zero() {
                    singular.push(3);
                }
            }
        }
        Run {
            kind,
            prm,
            prec,
            order,
            kc,
            singular,
        }
    }

    fn dim(&self) -> usize {
        match self.kind {
            Kind::Shc => 3,
            Kind::Maxwell => 4,
        }
    }

    fn initial(&self) -> Vec<Float> {
        let mut s = vec![zero(self.prec); self.dim()];
        *s.last_mut().unwrap() = Float::with_val(self.prec, -1);
        s
    }

    /// The field at a point, straight from the formulas (used for the Euler steps).
    fn field(&self, s: &[Float]) -> Vec<Float> {
        let prec = self.prec;
        let q = self.prm;
        let spow = |x: &Float, a: &Float| -> Float {
            // |x|^(a−1) x
            let m = powp(&Float::with_val(prec, x.abs_ref()), a);
            if x.is_sign_negative() { -m } else { m }
        };
        let apow = |x: &Float, a: &Float| powp(&Float::with_val(prec, x.abs_ref()), a);
        let hyst = |z: &Float, w: &Float| -> Float {
            // w − B|Z|^(n−1)Z|w| − Γ|Z|^n w
            let aw = Float::with_val(prec, w.abs_ref());
            let t1 = Float::with_val(prec, &q.b * &spow(z, &q.n)) * aw;
            let t2 = Float::with_val(prec, &q.g * &apow(z, &q.n)) * w;
            Float::with_val(prec, w - &t1) - t2
        };
        match self.kind {
            Kind::Shc => {
                let (x, z, v) = (&s[0], &s[1], &s[2]);
                let f = -Float::with_val(prec, &q.kappa * spow(x, &q.p))
                    - Float::with_val(prec, &self.kc * spow(z, &q.p))
                    - Float::with_val(prec, &q.sigma * apow(x, &q.p)) * v;
                vec![v.clone(), hyst(z, v), f]
            }
            Kind::Maxwell => {
                let (y, z, w) = (&s[1], &s[2], &s[3]);
                let dr = Float::with_val(prec, &q.kappa * spow(y, &q.p))
                    + Float::with_val(prec, &self.kc * spow(z, &q.p));
                let dr = dr * &q.sigma;
                let dz = hyst(z, w);
                let pm1 = Float::with_val(prec, &q.p - 1u32);
                let ps = Float::with_val(prec, &q.p * &q.sigma);
                let dw = -Float::with_val(prec, &dr / &q.sigma)
                    - Float::with_val(prec, &q.kappa * &ps) * apow(y, &pm1) * w
                    - Float::with_val(prec, &self.kc * &ps) * apow(z, &pm1) * &dz;
                vec![dr, w.clone(), dz, dw]
            }
        }
    }

    /// (F, V) at a point.
    fn force_velocity(&self, s: &[Float]) -> (Float, Float) {
        let f = self.field(s);
        match self.kind {
            Kind::Shc => (f[2].clone(), s[2].clone()),
            Kind::Maxwell => (
                -Float::with_val(self.prec, &f[0] / &self.prm.sigma),
                Float::with_val(self.prec, &f[0] + &s[3]),
            ),
        }
    }

    /// Taylor coefficients 0..=K at state `s` (every singular component nonzero).
    fn jets(&self, s: &[Float]) -> Jets {
        let prec = self.prec;
        let k_max = self.order;
        let q = self.prm;
        let sign = |x: &Float| if x.is_sign_negative() { -1i32 } else { 1 };
        let mut x: Vec<Vec<Float>> = s.iter().map(|c| vec![c.clone()]).collect();
        let pm1 = Float::with_val(prec, &q.p - 1u32);
        match self.kind {
            Kind::Shc => {
                let (sx, sz, sv) = (sign(&s[0]), sign(&s[1]), sign(&s[2]));
                // cZ = B sZ sV + Γ: Ż = V − cZ (|Z|^n V)
                let cz = Float::with_val(prec, &q.b * (sz * sv)) + &q.g;
                let (mut yx, mut yz) = (Vec::new(), Vec::new());
                let (mut px, mut pz, mut nz) = (Vec::new(), Vec::new(), Vec::new());
                let (mut nzv, mut pxv) = (Vec::new(), Vec::new());
                let mut fv = Vec::new();
                for k in 0..k_max {
                    yx.push(Float::with_val(prec, &x[0][k] * sx));
                    yz.push(Float::with_val(prec, &x[1][k] * sz));
                    let c = power_coef(prec, &yx, &px, &q.p, k);
                    px.push(c);
                    let c = power_coef(prec, &yz, &pz, &q.p, k);
                    pz.push(c);
                    let c = power_coef(prec, &yz, &nz, &q.n, k);
                    nz.push(c);
                    nzv.push(prod(prec, &nz, &x[2], k));
                    pxv.push(prod(prec, &px, &x[2], k));
                    let fx = x[2][k].clone();
                    let fz = Float::with_val(prec, &x[2][k] - Float::with_val(prec, &cz * &nzv[k]));
                    let f = -Float::with_val(prec, &q.kappa * &px[k]) * sx
                        - Float::with_val(prec, &self.kc * &pz[k]) * sz
                        - Float::with_val(prec, &q.sigma * &pxv[k]);
                    let k1 = (k + 1) as u32;
                    x[0].push(fx / k1);
                    x[1].push(fz / k1);
                    x[2].push(Float::with_val(prec, &f / k1));
                    fv.push(f);
                }
                let v = x[2].clone();
                Jets { x, f: fv, v }
            }
            Kind::Maxwell => {
                let (sy, sz, sw) = (sign(&s[1]), sign(&s[2]), sign(&s[3]));
                let cz = Float::with_val(prec, &q.b * (sz * sw)) + &q.g;
                let ks = Float::with_val(prec, &q.kappa * &q.sigma);
                let kcs = Float::with_val(prec, &self.kc * &q.sigma);
                let kps = Float::with_val(prec, &ks * &q.p);
                let kcps = Float::with_val(prec, &kcs * &q.p);
                let (mut yy, mut yz) = (Vec::new(), Vec::new());
                let (mut py, mut qy, mut pz, mut qz, mut nz) =
                    (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
                let (mut fz, mut fvec, mut vvec) = (Vec::new(), Vec::new(), Vec::new());
                let mut nzw = Vec::new();
                for k in 0..k_max {
                    yy.push(Float::with_val(prec, &x[1][k] * sy));
                    yz.push(Float::with_val(prec, &x[2][k] * sz));
                    let c = power_coef(prec, &yy, &py, &q.p, k);
                    py.push(c);
                    let c = power_coef(prec, &yy, &qy, &pm1, k);
                    qy.push(c);
                    let c = power_coef(prec, &yz, &pz, &q.p, k);
                    pz.push(c);
                    let c = power_coef(prec, &yz, &qz, &pm1, k);
                    qz.push(c);
                    let c = power_coef(prec, &yz, &nz, &q.n, k);
                    nz.push(c);
                    let r = Float::with_val(prec, &ks * &py[k]) * sy
                        + Float::with_val(prec, &kcs * &pz[k]) * sz;
                    nzw.push(prod(prec, &nz, &x[3], k));
                    let dz = Float::with_val(prec, &x[3][k] - Float::with_val(prec, &cz * &nzw[k]));
                    fz.push(dz);
                    let dw = -Float::with_val(prec, &r / &q.sigma)
                        - Float::with_val(prec, &kps * prod(prec, &qy, &x[3], k))
                        - Float::with_val(prec, &kcps * prod(prec, &qz, &fz, k));
                    let k1 = (k + 1) as u32;
                    fvec.push(-Float::with_val(prec, &r / &q.sigma));
                    vvec.push(Float::with_val(prec, &r + &x[3][k]));
                    x[0].push(Float::with_val(prec, &r / k1));
                    let dy = Float::with_val(prec, &x[3][k] / k1);
                    x[1].push(dy);
                    x[2].push(Float::with_val(prec, &fz[k] / k1));
                    x[3].push(dw / k1);
                }
                Jets {
                    x,
                    f: fvec,
                    v: vvec,
                }
            }
        }
    }
}

/// Step length from the last two coefficients: min_k (tol / max_i |c_ik|)^(1/k).
fn step_length(j: &Jets, order: usize, tol_digits: i32, hmax: f64) -> Float {
    let prec = 64;
    let ln_tol = Float::with_val(prec, 10u32).ln() * (-tol_digits);
    let mut h = Float::with_val(prec, hmax);
    for k in [order - 1, order] {
        let mut m = Float::with_val(prec, 0);
        for c in &j.x {
            let a = Float::with_val(prec, c[k].abs_ref());
            if a > m {
                m = a;
            }
        }
        if m.is_zero() {
            continue;
        }
        let hk = ((ln_tol.clone() - m.ln()) / (k as u32)).exp();
        if hk < h {
            h = hk;
        }
    }
    h
}

/// Integrates one case to T_s with one setting.
pub fn solve(kind: Kind, prm: &Params, set: Setting, extra: Extra) -> Outcome {
    let prec = set.prec;
    let run = Run::new(kind, prm, prec, set.order);
    let delta = Float::with_val(
        prec,
        Float::parse(format!("1e-{}", set.cross_digits)).unwrap(),
    );
    let mut t = zero(prec);
    let mut s = run.initial();
    let euler = |s: &[Float], h: &Float| -> Vec<Float> {
        run.field(s)
            .iter()
            .zip(s)
            .map(|(f, x)| Float::with_val(prec, x + Float::with_val(prec, f * h)))
            .collect()
    };
    // leave the start (a branch point) with one Euler step
    s = euler(&s, &delta);
    t += &delta;
    let (mut steps, mut crossings) = (0usize, 0usize);
    loop {
        assert!(t < 1000, "no separation before T = 1000");
        assert!(steps < 200_000, "too many steps");
        steps += 1;
        for &c in &run.singular {
            assert!(!s[c].is_zero(), "component {c} exactly zero at T = {t}");
        }
        let (f0, v0) = run.force_velocity(&s);
        assert!(
            !(f0 <= 0 && v0 >= 0),
            "separation condition holds at a step start T = {t}: missed event"
        );
        let j = run.jets(&s);
        // zeros of singular components within `delta`: cross them
        let mut cross: Option<Float> = None;
        for &c in &run.singular {
            let (x0, x1) = (&j.x[c][0], &j.x[c][1]);
            if x1.is_zero() {
                continue;
            }
            let tau = -Float::with_val(prec, x0 / x1);
            if tau > 0 && tau <= delta {
                let r = poly_root(&j.x[c], &zero(prec), &Float::with_val(prec, &tau * 2u32));
                if cross.as_ref().is_none_or(|m| r > *m) {
                    cross = Some(r);
                }
            }
        }
        if let Some(tc) = cross {
            crossings += 1;
            let h = Float::with_val(prec, &tc + &delta);
            let s1 = euler(&s, &h);
            let (f1, v1) = run.force_velocity(&s1);
            if f1 <= 0 && (v1 >= 0 || f0 > 0) {
                assert!(
                    extra.event_at_crossing,
                    "the separation event falls in a crossing step at T = {t}: not supported"
                );
                let sc = euler(&s, &tc);
                let (_, vc) = run.force_velocity(&sc);
                return Outcome {
                    ts: Float::with_val(prec, &t + &tc),
                    e: vc,
                    steps,
                    crossings,
                };
            }
            s = s1;
            t += &h;
            continue;
        }
        let mut h = Float::with_val(prec, step_length(&j, set.order, set.tol_digits, 0.5));
        // never step onto a zero of a singular component
        for &c in &run.singular {
            let (x0, x1) = (&j.x[c][0], &j.x[c][1]);
            if !x1.is_zero() {
                let tau = -Float::with_val(prec, x0 / x1);
                if tau > 0 {
                    let half = tau / 2u32;
                    if half < h {
                        h = half;
                    }
                }
            }
            loop {
                let end = horner(&j.x[c], &h);
                if sgn(&end) == sgn(&j.x[c][0]) {
                    break;
                }
                h /= 2u32;
            }
        }
        // the event in [0, h]
        let fh = horner(&j.f, &h);
        if f0 > 0 && fh <= 0 {
            let r = poly_root(&j.f, &zero(prec), &h);
            let vr = horner(&j.v, &r);
            if vr >= 0 {
                return Outcome {
                    ts: Float::with_val(prec, &t + &r),
                    e: vr,
                    steps,
                    crossings,
                };
            }
        }
        let vh = horner(&j.v, &h);
        if v0 < 0 && vh >= 0 {
            let r = poly_root(&j.v, &zero(prec), &h);
            assert!(
                horner(&j.f, &r) > 0,
                "V turns ≥ 0 while F ≤ 0 at T = {t}: T_s at a V zero, not supported"
            );
        }
        s = j.x.iter().map(|c| horner(c, &h)).collect();
        t += &h;
    }
}

/// `x` to `digits` significant decimal digits, as d.ddd…e±N (round to nearest).
pub fn to_sci(x: &Float, digits: usize) -> String {
    // e.g. "1.2345e-1" or "-1.2345"
    x.to_string_radix_round(10, Some(digits), Round::Nearest)
}
