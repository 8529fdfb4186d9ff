//! A sign-orthant abstract interpretation of the models' generic code, for the proofs of
//! thm:BWSHCCM_dV_leq_0, thm:BWMCM_dV_leq_0, thm:BWSHCCM_inv_dV_1 and thm:BWMCM_inv_dV_1.
//!
//! The implementation's `lyapunov_rate` is generic over `T: Scalar<R>`. It is evaluated here
//! with
//! - `R = PSym`: an inari interval that also carries, when it is known exactly, the affine form
//!   c₀ + c_p·p + c_n·n of the exponents (p + 1, p + n − 1, … are recognised as such);
//! - `T = Poly`: a value on one open sign orthant of the state space (every state component
//!   has a fixed sign sᵢ ∈ {−1, 0, +1}) written as a sum of terms
//!   `c · Π |xᵢ|^(eᵢ) · Π qₖ²`, with c an interval enclosing the coefficient for every parameter
//!   of the box, eᵢ exact affine forms in (p, n), and qₖ sub-expressions that were multiplied by
//!   themselves (squares).
//!
//! Every operation is exact or encloses (interval coefficients); what the abstraction cannot
//! represent (|·| of a sum of mixed signs, a power of a sum, a quotient) becomes `Unknown`, and a
//! proof that meets `Unknown` fails. On the orthant every |xᵢ|^e > 0 and every qₖ² ≥ 0, so a term
//! whose coefficient is ≤ 0 is ≤ 0 everywhere on the orthant: 𝒱̇ ≤ 0 on the whole orthant (not
//! only on a bounded box) follows when every coefficient is ≤ 0 — which is the lemma's argument
//! (−σ|X|^pV² ≤ 0; B|Z||V| + ΓZV = (B ± Γ)|Z||V| ≥ 0 with the sign of ZV fixed), checked on the
//! implementation's own expression.
#![allow(dead_code)]

use bwcl::arith::{Real, Scalar};
use inari::{Interval, const_interval};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// An exact affine form c₀ + c_p·p + c_n·n (small integer coefficients, exact in f64).
pub type Form = [f64; 3];

fn exact_small(x: f64) -> bool {
    x.is_finite() && x.fract() == 0.0 && x.abs() < 1e6
}

/// A parameter: an interval, and the exponent form when it is known exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct PSym {
    pub iv: Interval,
    pub form: Option<Form>,
}

impl PSym {
    pub fn interval(iv: Interval) -> Self {
        Self { iv, form: None }
    }
    pub fn exponent(iv: Interval, form: Form) -> Self {
        Self {
            iv,
            form: Some(form),
        }
    }
    fn is_const_form(f: &Form) -> bool {
        f[1] == 0.0 && f[2] == 0.0
    }
}

fn form_op(a: &Option<Form>, b: &Option<Form>, op: impl Fn(f64, f64) -> f64) -> Option<Form> {
    let (a, b) = (a.as_ref()?, b.as_ref()?);
    let r: Form = std::array::from_fn(|i| op(a[i], b[i]));
    r.iter().all(|x| exact_small(*x)).then_some(r)
}

/// The product of two forms when one of them is a constant (exact for small integers).
fn form_mul(a: &Option<Form>, b: &Option<Form>) -> Option<Form> {
    let (a, b) = (a.as_ref()?, b.as_ref()?);
    let r: Form = if PSym::is_const_form(a) {
        b.map(|x| a[0] * x)
    } else if PSym::is_const_form(b) {
        a.map(|x| b[0] * x)
    } else {
        return None;
    };
    r.iter().all(|x| exact_small(*x)).then_some(r)
}

impl Add for PSym {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            iv: self.iv + o.iv,
            form: form_op(&self.form, &o.form, |a, b| a + b),
        }
    }
}
impl Sub for PSym {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self {
            iv: self.iv - o.iv,
            form: form_op(&self.form, &o.form, |a, b| a - b),
        }
    }
}
impl Mul for PSym {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self {
            iv: self.iv * o.iv,
            form: form_mul(&self.form, &o.form),
        }
    }
}
impl Div for PSym {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let form = match &o.form {
            Some([c, 0.0, 0.0]) if *c == 1.0 => self.form,
            _ => None,
        };
        Self {
            iv: self.iv / o.iv,
            form,
        }
    }
}
impl Neg for PSym {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            iv: -self.iv,
            form: self.form.map(|f| f.map(|x| -x)),
        }
    }
}

impl Real for PSym {
    type Dot = bwcl::arith::PlainDot<PSym>;
    type Prepared = ();
    fn prepare_exponent(_: &Self) {}
    fn from_int(k: i64) -> Self {
        Self {
            iv: <Interval as Real>::from_int(k),
            form: exact_small(k as f64).then_some([k as f64, 0.0, 0.0]),
        }
    }
    fn from_exact_f64(x: f64) -> Self {
        Self {
            iv: <Interval as Real>::from_exact_f64(x),
            form: exact_small(x).then_some([x, 0.0, 0.0]),
        }
    }
    fn parse_decimal(s: &str) -> Result<Self, String> {
        <Interval as Real>::parse_decimal(s).map(Self::interval)
    }
    fn unbounded() -> Self {
        Self::interval(Interval::ENTIRE)
    }
    fn abs(&self) -> Self {
        Self::interval(Real::abs(&self.iv))
    }
    fn sqrt(&self) -> Self {
        Self::interval(Real::sqrt(&self.iv))
    }
    fn ln(&self) -> Self {
        Self::interval(Real::ln(&self.iv))
    }
    fn sgn(&self) -> Self {
        Self::interval(Real::sgn(&self.iv))
    }
    fn pow(&self, y: &Self) -> Self {
        Self::interval(Real::pow(&self.iv, &y.iv))
    }
    fn spow(&self, q: &Self) -> Self {
        Self::interval(Real::spow(&self.iv, &q.iv))
    }
    fn apow(&self, q: &Self) -> Self {
        Self::interval(Real::apow(&self.iv, &q.iv))
    }
    fn lo(&self) -> f64 {
        self.iv.inf()
    }
    fn hi(&self) -> f64 {
        self.iv.sup()
    }
    fn mid(&self) -> f64 {
        self.iv.mid()
    }
}

/// An exponent: its exact form and its enclosure over the parameter box.
#[derive(Clone, Debug)]
pub struct Exp {
    pub form: Form,
    pub iv: Interval,
}
impl PartialEq for Exp {
    fn eq(&self, o: &Self) -> bool {
        self.form == o.form
    }
}

/// One term c · Π|xᵢ|^(eᵢ) · Π qₖ².
#[derive(Clone, Debug, PartialEq)]
pub struct Term {
    pub coef: Interval,
    pub exps: Vec<Option<Exp>>,
    pub squares: Vec<Poly>,
}

impl Term {
    fn same_monomial(&self, o: &Term) -> bool {
        self.exps == o.exps && self.squares == o.squares
    }
    fn is_pure_monomial(&self) -> bool {
        self.squares.is_empty()
    }
}

/// A value on a sign orthant.
#[derive(Clone, Debug, PartialEq)]
pub enum Poly {
    Known(Vec<Term>),
    Unknown(String),
}

const NONNEG: Interval = const_interval!(0.0, f64::INFINITY);
const UNIT: Interval = const_interval!(0.0, 1.0);

thread_local! {
    /// Number of atoms (state components) of the current evaluation (set by [`Poly::atom`]).
    static ATOMS: std::cell::Cell<usize> = const { std::cell::Cell::new(4) };
}

/// Number of atoms (state components) of the current evaluation.
fn atoms(_t: &[Term]) -> usize {
    ATOMS.with(|a| a.get())
}

impl Poly {
    pub fn zero() -> Self {
        Poly::Known(Vec::new())
    }
    /// State component i of n with sign s (0: the component is 0 on this orthant).
    pub fn atom(n: usize, i: usize, s: i8) -> Self {
        ATOMS.with(|a| a.set(n));
        if s == 0 {
            return Self::zero();
        }
        let mut exps = vec![None; n];
        exps[i] = Some(Exp {
            form: [1.0, 0.0, 0.0],
            iv: <Interval as Real>::from_int(1),
        });
        Poly::Known(vec![Term {
            coef: <Interval as Real>::from_int(s as i64),
            exps,
            squares: vec![],
        }])
    }
    fn constant(n: usize, c: Interval) -> Self {
        Poly::Known(vec![Term {
            coef: c,
            exps: vec![None; n],
            squares: vec![],
        }])
    }
    fn unknown(why: &str) -> Self {
        Poly::Unknown(why.to_string())
    }
    /// Adds like terms (same monomial and squares); drops exact zeros.
    fn normalise(mut ts: Vec<Term>) -> Self {
        let mut out: Vec<Term> = Vec::new();
        for t in ts.drain(..) {
            if let Some(o) = out.iter_mut().find(|o| o.same_monomial(&t)) {
                o.coef += t.coef;
            } else {
                out.push(t);
            }
        }
        out.retain(|t| !(t.coef.inf() == 0.0 && t.coef.sup() == 0.0));
        Poly::Known(out)
    }
    /// The sign of every value on the orthant, if it is fixed: Some(+1) every term ≥ 0, Some(−1)
    /// every term ≤ 0, Some(0) the value is identically 0.
    pub fn sign(&self) -> Option<i8> {
        match self {
            Poly::Unknown(_) => None,
            Poly::Known(ts) if ts.is_empty() => Some(0),
            Poly::Known(ts) => {
                if ts.iter().all(|t| t.coef.inf() >= 0.0) {
                    Some(1)
                } else if ts.iter().all(|t| t.coef.sup() <= 0.0) {
                    Some(-1)
                } else {
                    None
                }
            }
        }
    }
    /// True when the value is ≠ 0 everywhere on the orthant: one strict sign for every term and
    /// every square strictly positive.
    pub fn strict(&self) -> bool {
        match self {
            Poly::Known(ts) if !ts.is_empty() => {
                let pos = ts.iter().all(|t| t.coef.inf() > 0.0);
                let neg = ts.iter().all(|t| t.coef.sup() < 0.0);
                (pos || neg) && ts.iter().all(|t| t.squares.iter().all(Poly::strict))
            }
            _ => false,
        }
    }
}

impl Add for Poly {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        match (self, o) {
            (Poly::Known(mut a), Poly::Known(b)) => {
                a.extend(b);
                Poly::normalise(a)
            }
            (Poly::Unknown(w), _) | (_, Poly::Unknown(w)) => Poly::Unknown(w),
        }
    }
}
impl Neg for Poly {
    type Output = Self;
    fn neg(self) -> Self {
        match self {
            Poly::Known(a) => Poly::Known(
                a.into_iter()
                    .map(|mut t| {
                        t.coef = -t.coef;
                        t
                    })
                    .collect(),
            ),
            u => u,
        }
    }
}
impl Sub for Poly {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

fn add_exps(a: &[Option<Exp>], b: &[Option<Exp>]) -> Option<Vec<Option<Exp>>> {
    a.iter()
        .zip(b)
        .map(|(x, y)| match (x, y) {
            (None, None) => Some(None),
            (Some(e), None) | (None, Some(e)) => Some(Some(e.clone())),
            (Some(e), Some(f)) => {
                let form = form_op(&Some(e.form), &Some(f.form), |a, b| a + b)?;
                Some(Some(Exp {
                    form,
                    iv: e.iv + f.iv,
                }))
            }
        })
        .collect()
}

impl Mul for Poly {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let (a, b) = match (&self, &o) {
            (Poly::Known(a), Poly::Known(b)) => (a, b),
            (Poly::Unknown(w), _) | (_, Poly::Unknown(w)) => return Poly::Unknown(w.clone()),
        };
        if a.is_empty() || b.is_empty() {
            return Poly::zero();
        }
        if self == o {
            // x·x: a square (the coefficient of a single monomial squared exactly ≥ 0)
            if a.len() == 1 && a[0].is_pure_monomial() {
                let t = &a[0];
                return match add_exps(&t.exps, &t.exps) {
                    Some(exps) => Poly::Known(vec![Term {
                        coef: t.coef.sqr(),
                        exps,
                        squares: vec![],
                    }]),
                    None => Poly::unknown("exponent of a square"),
                };
            }
            return Poly::Known(vec![Term {
                coef: <Interval as Real>::from_int(1),
                exps: vec![None; atoms(a)],
                squares: vec![self.clone()],
            }]);
        }
        let mut out = Vec::new();
        for s in a {
            for t in b {
                let Some(exps) = add_exps(&s.exps, &t.exps) else {
                    return Poly::unknown("exponent of a product");
                };
                let mut squares = s.squares.clone();
                squares.extend(t.squares.iter().cloned());
                out.push(Term {
                    coef: s.coef * t.coef,
                    exps,
                    squares,
                });
            }
        }
        Poly::normalise(out)
    }
}
impl Div for Poly {
    type Output = Self;
    fn div(self, _o: Self) -> Self {
        Poly::unknown("quotient")
    }
}

impl Poly {
    /// |self|^q (abs = false: |self|^(q−1)·self) for a single monomial of known sign.
    fn power(&self, q: &PSym, signed: bool) -> Self {
        let ts = match self {
            Poly::Known(ts) => ts,
            u => return u.clone(),
        };
        if ts.is_empty() {
            // 0^q: 0 for q > 0, 1 for q = 0, [0, 1] when q ∈ [0, …] is undecided; the signed
            // power of 0 is 0 for q ≥ 1
            if signed || q.iv.inf() > 0.0 {
                return Poly::zero();
            }
            let n = atoms(ts);
            return if q.iv.sup() == 0.0 && q.iv.inf() == 0.0 {
                Poly::constant(n, <Interval as Real>::from_int(1))
            } else {
                Poly::constant(n, UNIT)
            };
        }
        let Some(qf) = q.form else {
            return Poly::unknown("power with an exponent of unknown form");
        };
        if ts.len() != 1 || !ts[0].is_pure_monomial() {
            return Poly::unknown("power of a sum");
        }
        let t = &ts[0];
        let s = if t.coef.inf() > 0.0 {
            1.0
        } else if t.coef.sup() < 0.0 {
            -1.0
        } else {
            return Poly::unknown("power of a term of unknown sign");
        };
        let mag = Real::pow(&Real::abs(&t.coef).intersection(NONNEG), &q.iv);
        let mut exps = Vec::with_capacity(t.exps.len());
        for e in &t.exps {
            exps.push(match e {
                None => None,
                Some(e) => {
                    let Some(form) = form_mul(&Some(e.form), &Some(qf)) else {
                        return Poly::unknown("exponent of a power");
                    };
                    Some(Exp {
                        form,
                        iv: e.iv * q.iv,
                    })
                }
            });
        }
        let coef = if signed && s < 0.0 { -mag } else { mag };
        Poly::Known(vec![Term {
            coef,
            exps,
            squares: vec![],
        }])
    }
}

impl Scalar<PSym> for Poly {
    fn scale(&self, c: &PSym) -> Self {
        match self {
            Poly::Known(ts) => Poly::normalise(
                ts.iter()
                    .map(|t| Term {
                        coef: t.coef * c.iv,
                        ..t.clone()
                    })
                    .collect(),
            ),
            u => u.clone(),
        }
    }
    fn shift(&self, c: &PSym) -> Self {
        match self {
            Poly::Known(ts) => {
                let n = atoms(ts);
                self.clone() + Poly::constant(n, c.iv)
            }
            u => u.clone(),
        }
    }
    fn abs(&self) -> Self {
        match self.sign() {
            Some(0) | Some(1) => self.clone(),
            Some(_) => -self.clone(),
            None => Poly::unknown("|·| of a value of unknown sign"),
        }
    }
    fn spow(&self, q: &PSym) -> Self {
        self.power(q, true)
    }
    fn apow(&self, q: &PSym) -> Self {
        self.power(q, false)
    }
}

/// The verdict of the abstraction on one orthant.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Identically 0 on the orthant.
    Zero,
    /// < 0 everywhere on the orthant.
    Negative,
    /// ≤ 0 everywhere on the orthant (= 0 possible where a square vanishes).
    NonPositive,
    /// Some coefficient is > 0 (a term that is positive on the orthant exists).
    Positive(String),
    /// The abstraction could not decide (split the parameter box).
    Undecided(String),
}

/// Classifies a value on its orthant.
pub fn verdict(p: &Poly) -> Verdict {
    match p {
        Poly::Unknown(w) => Verdict::Undecided(w.clone()),
        Poly::Known(ts) if ts.is_empty() => Verdict::Zero,
        Poly::Known(ts) => {
            if let Some(t) = ts
                .iter()
                .find(|t| t.coef.inf() > 0.0 && t.squares.iter().all(Poly::strict))
            {
                return Verdict::Positive(format!(
                    "a term with coefficient in [{:e}, {:e}]",
                    t.coef.inf(),
                    t.coef.sup()
                ));
            }
            if ts.iter().all(|t| t.coef.sup() <= 0.0) {
                if ts
                    .iter()
                    .any(|t| t.coef.sup() < 0.0 && t.squares.iter().all(Poly::strict))
                {
                    Verdict::Negative
                } else {
                    Verdict::NonPositive
                }
            } else {
                Verdict::Undecided(format!(
                    "coefficients {:?}",
                    ts.iter()
                        .map(|t| (t.coef.inf(), t.coef.sup()))
                        .collect::<Vec<_>>()
                ))
            }
        }
    }
}

/// The orthants {−1, 0, 1}^n of the listed state components (others are set to +1: the
/// evaluated function must not depend on them, which `verdict` would expose as a term).
pub fn orthants(n: usize) -> Vec<Vec<i8>> {
    let mut out = vec![vec![]];
    for _ in 0..n {
        out = out
            .into_iter()
            .flat_map(|v| {
                [-1i8, 0, 1].into_iter().map(move |s| {
                    let mut w = v.clone();
                    w.push(s);
                    w
                })
            })
            .collect();
    }
    out
}
