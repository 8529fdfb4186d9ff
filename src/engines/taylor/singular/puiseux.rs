//! Generalized polynomials in u ≥ 0 with real exponents, interval coefficients and a remainder:
//! the number type of the singular step ([`super`]).
//!
//! A value is the set of functions on the domain u ∈ [0, δ]
//!
//! ```text
//! y(u) ∈ Σ_α c_α u^α + R,     α = k₀g₀ + k₁g₁ + … (kⱼ ≥ 0 integers, g₀ = 1),
//! ```
//!
//! the generators gⱼ being the exponents of the model's powers (n, p, p − 1, …, each an
//! enclosure of the decimal the user wrote), the coefficients c_α and the remainder R intervals:
//! y(u) − Σ c_α u^α ∈ R for every u in the domain. The exponent of a term is kept as the integer
//! vector k, so that terms are merged only when their exponents are the same function of the
//! generators (u^p and u·u^(p−1) stay two terms, which is harmless).
//!
//! Every operation returns a value containing the pointwise result for every pair of functions
//! of its operands' sets:
//! - sums add coefficients and remainders;
//! - products multiply the polynomial parts exactly (exponent vectors add), move terms with an
//!   exponent above the cut-off M into the remainder by their range c·[0, δ^α] on the domain, and
//!   add P₁R₂ + P₂R₁ + R₁R₂ with Pᵢ bounded by its range;
//! - analytic functions of a value bounded away from their singularity — x^q for x of one sign,
//!   1/x — are composed by the binomial series in ε = (x − c₀)/c₀ (c₀ the constant
//!   coefficient) to the order where εᴷ falls beyond the cut-off, with Lagrange's remainder
//!   binom(q, K)(1 + θε)^(q−K) εᴷ (θ ∈ [0, 1]) bounded over ε's range;
//! - a power of the independent variable itself, |±u|^q = u^q (and |±u|^(q−1)(±u) = ±u^q), is the
//!   monomial of generator q — exactly, which is what carries the solution through the branch
//!   point;
//! - ∫₀^u y(s) ds adds g₀ = 1 to each exponent and divides by α + 1; the remainder becomes
//!   [0, δ]·R.

use crate::arith::{Dot, Enclosure, PlainDot, Real};
use inari::Interval;
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::sync::Arc;

/// a + b in the jet arithmetic of `I` ([`Enclosure::Jet`]): for f64 intervals the ulp
/// intervals, inari's sum bit for bit without the rounding-mode switches of an inari
/// operation (measured: about half of a product's time went to those switches in the sums
/// of its remainder and ranges); for other types their own sum.
#[inline]
fn add<I: Enclosure>(a: &I, b: &I) -> I {
    I::from_jet(a.to_jet() + b.to_jet())
}

/// a·b in the jet arithmetic of `I` (as [`add`]).
#[inline]
fn mul<I: Enclosure>(a: &I, b: &I) -> I {
    I::from_jet(a.to_jet() * b.to_jet())
}

/// a/b in the jet arithmetic of `I` (as [`add`]; a divisor reaching 0 gives every real).
#[inline]
fn div<I: Enclosure>(a: &I, b: &I) -> I {
    I::from_jet(a.to_jet() / b.to_jet())
}

/// [|c|, |c|] (an upper bound of |c| as a point).
fn point_mag<I: Enclosure>(c: &I) -> I {
    let m = c.mag_f64();
    I::from_bounds(m, m).unwrap_or_else(I::entire)
}

/// A non-empty interval with finite ends.
pub(crate) fn bounded<I: Enclosure>(x: &I) -> bool {
    !x.is_empty() && x.lo().is_finite() && x.hi().is_finite()
}

/// Most generators (g₀ = 1 included).
pub const MAX_GENS: usize = 6;
/// A term's exponent as counts of the generators.
pub type Key = [u8; MAX_GENS];
/// "Beyond the cut-off" in the index tables.
const BEYOND: u16 = u16::MAX;

/// The generators, every exponent vector up to the cut-off M (the basis of the expansions) and
/// their sums, made once per run. The exponents are enclosures in the coefficients' type `I`
/// (at MPFR precision they are not rounded to f64).
#[derive(Debug)]
pub struct Basis<I = Interval> {
    gens: Vec<I>,
    max_exp: f64,
    keys: Vec<Key>,
    /// α of each key.
    exps: Vec<I>,
    /// α + 1 of each key (the divisors of [`Gts::integral`] and [`Gts::average`]).
    exps_plus_one: Vec<I>,
    /// index of keys[i] + keys[j] (BEYOND above the cut-off), n × n
    sum: Vec<u16>,
    /// index of keys[i] + (1, 0, …): the exponent of the integral
    plus_one: Vec<u16>,
    /// (index of the key with one count of generator j fewer, j) per key: u^α of key i is
    /// u^α of its parent times u^(g_j) ([`Ctx::powers`]); (0, 0) for the constant.
    parent: Vec<(u16, u8)>,
    /// The products' table in the exponents' order, when every row is a prefix there (see
    /// [`Prefix`]); `None` when some row is not (exponents equal within their enclosures'
    /// widths): products then look each pair up in `sum`.
    prefix: Option<Prefix>,
}

/// The keys' positions in the order of their exponents (by lower bound), and for each key i
/// the first position `cut[i]` from which on every sum with i lies beyond the cut-off — and
/// before which every sum lies within it (checked for every row when the basis is made; where
/// two keys' exponents are equal within their enclosures' widths it may fail, and products
/// then test each pair).
#[derive(Debug)]
struct Prefix {
    pos: Vec<u16>,
    cut: Vec<u16>,
}

impl Prefix {
    fn new<I: Enclosure>(exps: &[I], sum: &[u16]) -> Option<Self> {
        let n = exps.len();
        let mut order: Vec<u16> = (0..n as u16).collect();
        order.sort_by(|&a, &b| exps[a as usize].lo().total_cmp(&exps[b as usize].lo()));
        let mut pos = vec![0u16; n];
        for (p, &k) in order.iter().enumerate() {
            pos[k as usize] = p as u16;
        }
        let mut cut = Vec::with_capacity(n);
        for i in 0..n {
            let row: Vec<u16> = order.iter().map(|&j| sum[i * n + j as usize]).collect();
            let c = row.iter().position(|&k| k == BEYOND).unwrap_or(n);
            if row[c..].iter().any(|&k| k != BEYOND) {
                return None;
            }
            cut.push(c as u16);
        }
        Some(Self { pos, cut })
    }
}

/// Bases already made in this process, for f64 intervals, keyed by the generators' ends and
/// the cut-off (which determine the basis: an inari interval is its two doubles). A sweep or
/// a fit makes the same basis for every speed; the table of sums of 40–60 exponents took 1.7 %
/// of a proved CoR's time. At most [`CACHED_BASES`] kept (the oldest dropped first).
type BasisCache = Vec<(Vec<(u64, u64)>, u64, Arc<Basis<Interval>>)>;
const CACHED_BASES: usize = 32;

fn basis_cache() -> &'static std::sync::Mutex<BasisCache> {
    static CACHE: std::sync::OnceLock<std::sync::Mutex<BasisCache>> = std::sync::OnceLock::new();
    CACHE.get_or_init(Default::default)
}

impl<I: Enclosure> Basis<I> {
    /// [`Basis::new`], the same basis taken from the process's cache where `I` is inari's
    /// interval (for other types the ends do not determine the value: made anew).
    pub fn cached(gens: &[I], max_exp: f64) -> Option<Arc<Self>> {
        use std::any::Any;
        // (by the type itself: an empty list of generators says nothing about it)
        if std::any::TypeId::of::<I>() != std::any::TypeId::of::<Interval>() {
            return Self::new(gens, max_exp);
        }
        // I is Interval: every generator downcasts
        let gens: Vec<Interval> = gens
            .iter()
            .filter_map(|g| (g as &dyn Any).downcast_ref::<Interval>().copied())
            .collect();
        let key: Vec<(u64, u64)> = gens
            .iter()
            .map(|x| (x.inf().to_bits(), x.sup().to_bits()))
            .collect();
        let m = max_exp.to_bits();
        let found = basis_cache().lock().ok().and_then(|c| {
            c.iter()
                .find(|e| e.0 == key && e.1 == m)
                .map(|e| e.2.clone())
        });
        let b: Arc<Basis<Interval>> = match found {
            Some(b) => b,
            None => {
                let b = Basis::<Interval>::new(&gens, max_exp)?;
                if let Ok(mut c) = basis_cache().lock() {
                    if c.len() >= CACHED_BASES {
                        c.remove(0);
                    }
                    c.push((key, m, b.clone()));
                }
                b
            }
        };
        (Box::new(b) as Box<dyn Any>)
            .downcast::<Arc<Self>>()
            .ok()
            .map(|b| *b)
    }

    /// `gens` are the exponents other than 1 (duplicates, 1 and non-positive ones are dropped).
    pub fn new(gens: &[I], max_exp: f64) -> Option<Arc<Self>> {
        let mut g = vec![I::one()];
        for q in gens {
            if !g.iter().any(|x| x.same(q)) && q.lo() > 0.0 {
                if !q.hi().is_finite() {
                    return None;
                }
                g.push(q.clone());
            }
        }
        if g.len() > MAX_GENS {
            return None;
        }
        let exponent = |k: &Key| -> I {
            let mut a = I::zero();
            for (j, &kj) in k.iter().enumerate() {
                if kj > 0 {
                    a = a + g[j].mul_int(kj as i64);
                }
            }
            a
        };
        // every key with α ≤ M (by its lower bound), depth-first over the generators
        let mut keys = Vec::new();
        let mut stack = vec![([0u8; MAX_GENS], 0usize)];
        while let Some((k, j)) = stack.pop() {
            if j == g.len() {
                keys.push(k);
                continue;
            }
            let mut k1 = k;
            loop {
                if exponent(&k1).lo() > max_exp {
                    break;
                }
                stack.push((k1, j + 1));
                k1[j] += 1;
                if k1[j] == u8::MAX {
                    return None;
                }
            }
            if keys.len() > 4000 {
                return None;
            }
        }
        keys.sort();
        keys.dedup();
        let n = keys.len();
        let index = |k: &Key| keys.binary_search(k).map_or(BEYOND, |i| i as u16);
        let mut sum = vec![BEYOND; n * n];
        for i in 0..n {
            for j in 0..n {
                let mut k = [0u8; MAX_GENS];
                for l in 0..MAX_GENS {
                    k[l] = keys[i][l].saturating_add(keys[j][l]);
                }
                sum[i * n + j] = index(&k);
            }
        }
        let plus_one = keys
            .iter()
            .map(|k| {
                let mut k1 = *k;
                k1[0] += 1;
                index(&k1)
            })
            .collect();
        let exps: Vec<I> = keys.iter().map(exponent).collect();
        // the parent of a key (its last nonzero count lowered by one) is a key too (its
        // exponent is smaller: every generator is > 0) and sorts before it
        let parent = keys
            .iter()
            .map(|k| match k.iter().rposition(|&c| c > 0) {
                Some(j) => {
                    let mut k1 = *k;
                    k1[j] -= 1;
                    (index(&k1), j as u8)
                }
                None => (0, 0),
            })
            .collect();
        let prefix = Prefix::new(&exps, &sum);
        let exps_plus_one = exps.iter().map(|a| a.clone() + I::one()).collect();
        Some(Arc::new(Self {
            gens: g,
            max_exp,
            keys,
            exps,
            exps_plus_one,
            sum,
            plus_one,
            parent,
            prefix,
        }))
    }

    /// The generator index of the exponent q (an exact match of the enclosure).
    fn gen_of(&self, q: &I) -> Option<usize> {
        self.gens.iter().position(|g| g.same(q))
    }

    /// The index of u^(g_j).
    fn gen_index(&self, j: usize) -> u16 {
        let mut k = [0u8; MAX_GENS];
        k[j] = 1;
        self.keys.binary_search(&k).map_or(BEYOND, |i| i as u16)
    }

    /// The exponents as counts of the generators, sorted (index 0: the constant).
    #[cfg(test)]
    pub(crate) fn keys(&self) -> &[Key] {
        &self.keys
    }

    /// The generators other than g₀ = 1.
    pub fn gens(&self) -> &[I] {
        &self.gens[1..]
    }

    /// The exponent cut-off M.
    pub fn max_exp(&self) -> f64 {
        self.max_exp
    }

    /// How many exponents the basis has.
    pub fn len(&self) -> usize {
        self.keys.len()
    }

    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }
}

/// A basis on the domain [0, δ]: the ranges [0, δ^α] of its terms, made once per step.
#[derive(Debug)]
pub struct Ctx<I = Interval> {
    basis: Arc<Basis<I>>,
    /// δ, the domain's right end (an exact double, < 1).
    delta: f64,
    /// [0, δ^α] per key ([1, 1] for the constant).
    ranges: Vec<I>,
    /// [0, δ^M]: the range of every term beyond the cut-off (δ < 1).
    beyond: I,
    /// The cut-off its operations keep terms to: M, or below it for the cheap plain
    /// iterations of a fixed point ([`Ctx::truncated`]).
    cut: f64,
}

impl<I: Enclosure> Ctx<I> {
    pub fn new(basis: &Arc<Basis<I>>, delta: f64) -> Option<Arc<Self>> {
        if !(delta > 0.0 && delta < 1.0) {
            return None;
        }
        let d = I::from_bounds(0.0, delta)?;
        let ranges = basis
            .exps
            .iter()
            .map(|a| {
                if a.hi() == 0.0 {
                    I::one()
                } else {
                    Real::pow(&d, a)
                }
            })
            .collect();
        let m = I::from_bounds(basis.max_exp, basis.max_exp)?;
        Some(Arc::new(Self {
            basis: basis.clone(),
            delta,
            ranges,
            beyond: Real::pow(&d, &m),
            cut: basis.max_exp,
        }))
    }

    pub fn delta(&self) -> f64 {
        self.delta
    }

    /// Whether `other` is a context of the same basis and domain [0, δ] (possibly with another
    /// cut-off, [`Ctx::truncated`]): only then does a key index stand for the same exponent in
    /// both and a remainder bound the same u. The basis is the same when it is one (the usual
    /// case: contexts of one step share it) or made from the same generators with the same
    /// keys (a basis of MPFR intervals made twice).
    pub fn same_domain(&self, other: &Self) -> bool {
        let (a, b) = (&self.basis, &other.basis);
        let same_basis = Arc::ptr_eq(a, b)
            || (a.keys == b.keys
                && a.gens.len() == b.gens.len()
                && a.gens.iter().zip(&b.gens).all(|(x, y)| x.same(y)));
        self.delta == other.delta && same_basis
    }

    /// The same basis and domain with the operations keeping terms only up to exponent `m`
    /// (at least 1, at most M): every term above goes into the remainder by its range
    /// c·[0, δ^α], as those above M do — as sound as the full context, and as cheap as the
    /// smaller basis it uses. For the plain iterations of a fixed point, which fix the terms
    /// one unit of exponent further each (`super::validate`): those above have no value yet.
    pub fn truncated(self: &Arc<Self>, m: f64) -> Arc<Self> {
        let m = m.max(1.0);
        if m >= self.cut {
            return self.clone();
        }
        Arc::new(Self {
            basis: self.basis.clone(),
            delta: self.delta,
            ranges: self.ranges.clone(),
            beyond: self.beyond.clone(),
            cut: m,
        })
    }

    /// Whether key `i` lies above the cut-off of the context (by its exponent's lower end,
    /// as the basis decides what lies above M).
    #[inline]
    fn above_cut(&self, i: usize) -> bool {
        self.cut < self.basis.max_exp && self.basis.exps[i].lo() > self.cut
    }

    /// u^α of the keys 0..=`last` for u ⊆ [0, ∞) (1 for the constant): u^(g_j) once per
    /// generator, then each key's power as its parent's times one generator's
    /// ([`Basis::parent`]). Every factor is ≥ 0 and increasing in u, so each product encloses
    /// u^(α_parent + g_j) = u^α for every u of the interval (no dependency is lost); a key of
    /// total degree d carries d products' roundings and d generator powers' widths instead of
    /// one power's (≤ 70 ulps measured, at α ≈ 6: negligible against the coefficients'
    /// widths), and costs one product instead of a power.
    pub(crate) fn powers(&self, u: &I, last: usize) -> Vec<I> {
        let b = &self.basis;
        let u = u.nonneg();
        let n = (last + 1).min(b.keys.len());
        if u.hi() == 0.0 {
            return (0..n)
                .map(|i| if i == 0 { I::one() } else { I::zero() })
                .collect();
        }
        let g: Vec<I> = b
            .gens
            .iter()
            .enumerate()
            .map(|(j, gj)| if j == 0 { u.clone() } else { Real::pow(&u, gj) })
            .collect();
        let mut p: Vec<I> = Vec::with_capacity(n);
        for i in 0..n {
            let (par, j) = b.parent[i];
            p.push(if i == 0 {
                I::one()
            } else {
                p[par as usize].mul_constant(&g[j as usize])
            });
        }
        p
    }
}

/// A generalized polynomial with remainder on [0, δ] (see the module's documentation), with
/// coefficients and remainder in the interval type `I`.
#[derive(Clone, Debug)]
pub struct Gts<I = Interval> {
    ctx: Option<Arc<Ctx<I>>>,
    /// (key index, coefficient), sorted by index; index 0 is the constant term. Without a
    /// context only the constant term.
    terms: Vec<(u16, I)>,
    rem: I,
    /// ±1 when the value is exactly ±u (the independent variable), else 0.
    var: i8,
    /// (s, W) when the value is exactly s·u·W(u) with s = ±1 and W a value of one sign > 0
    /// (a component that starts at 0 with the independent variable, see [`Gts::factored`]);
    /// the terms and remainder above are the expanded product, used by every operation
    /// except the powers and |·|.
    fac: Option<Arc<(i8, Gts<I>)>>,
}

impl<I: Enclosure> Gts<I> {
    pub fn constant(c: I) -> Self {
        Self {
            ctx: None,
            terms: vec![(0, c)],
            rem: I::zero(),
            var: 0,
            fac: None,
        }
    }

    /// ±u on the context's domain.
    pub fn variable(ctx: &Arc<Ctx<I>>, sign: i8) -> Self {
        Self {
            ctx: Some(ctx.clone()),
            terms: vec![(ctx.basis.gen_index(0), I::from_int(sign as i64))],
            rem: I::zero(),
            var: sign,
            fac: None,
        }
    }

    /// s·u·W on the context's domain, s = ±1, for a component that starts at 0 together with
    /// the independent variable ([`super::start`]). Its powers are taken in the factored form
    ///
    /// ```text
    /// |s·u·W|^q = u^q·W^q,     |s·u·W|^(q−1)·(s·u·W) = s·u^q·W^q       (W > 0),
    /// ```
    ///
    /// the monomial of the generator q times the binomial series of W^q about W's constant
    /// coefficient, and |s·u·W| = u·W: exact on every function of the set as long as every
    /// function of W's set is > 0, which the powers and |·| check (otherwise they are
    /// unbounded). Every other operation uses the expanded product s·u·W.
    pub fn factored(ctx: &Arc<Ctx<I>>, s: i8, w: Gts<I>) -> Self {
        let mut g = Self::variable(ctx, s) * w.clone();
        g.fac = Some(Arc::new((s, w)));
        g
    }

    /// The constant `c` in the context (so that its range is defined).
    pub fn constant_in(ctx: &Arc<Ctx<I>>, c: I) -> Self {
        let mut g = Self::constant(c);
        g.ctx = Some(ctx.clone());
        g
    }

    /// The value Σ c·u^α + R on the context's domain from (exponent vector, coefficient)
    /// pairs (each key in the basis, at most once) and the remainder R: for tests that need a
    /// value of a given form.
    #[cfg(test)]
    pub(crate) fn from_parts(ctx: &Arc<Ctx<I>>, terms: &[(Key, I)], rem: I) -> Self {
        let mut t: Vec<(u16, I)> = terms
            .iter()
            .map(|(k, c)| {
                let i = ctx.basis.keys.binary_search(k).expect("a key of the basis");
                (i as u16, c.clone())
            })
            .collect();
        t.sort_by_key(|e| e.0);
        assert!(t.windows(2).all(|w| w[0].0 < w[1].0), "a key given twice");
        Self {
            ctx: Some(ctx.clone()),
            terms: t,
            rem,
            var: 0,
            fac: None,
        }
    }

    /// (exponent vector, coefficient) of each term.
    pub fn terms(&self) -> Vec<(Key, I)> {
        match &self.ctx {
            Some(ctx) => self
                .terms
                .iter()
                .map(|(i, c)| (ctx.basis.keys[*i as usize], c.clone()))
                .collect(),
            None => self
                .terms
                .iter()
                .map(|(_, c)| ([0; MAX_GENS], c.clone()))
                .collect(),
        }
    }

    pub fn remainder(&self) -> I {
        self.rem.clone()
    }

    /// The constant coefficient.
    pub fn c0(&self) -> I {
        match self.terms.first() {
            Some((0, c)) => c.clone(),
            _ => I::zero(),
        }
    }

    fn is_const(&self) -> bool {
        self.terms.iter().all(|(i, _)| *i == 0)
    }

    fn merge_ctx(a: &Option<Arc<Ctx<I>>>, b: &Option<Arc<Ctx<I>>>) -> Option<Arc<Ctx<I>>> {
        a.clone().or_else(|| b.clone())
    }

    /// The range of the value over the domain (the constant itself without a context).
    pub fn range(&self) -> I {
        add(&self.poly_range(), &self.rem)
    }

    /// The range of the polynomial part over the domain (summed from the highest exponent
    /// down, so that outward rounding at the constant's magnitude happens once).
    fn poly_range(&self) -> I {
        let mut r = I::zero().to_jet();
        for (i, c) in self.terms.iter().rev() {
            r = r + match &self.ctx {
                Some(ctx) => c.mul_constant(&ctx.ranges[*i as usize]),
                None => c.clone(),
            }
            .to_jet();
        }
        I::from_jet(r)
    }

    /// The value at u ∈ `u` (an interval inside the domain), summed as `Gts::poly_range`.
    pub fn eval(&self, u: &I) -> I {
        let p = match (&self.ctx, self.terms.last()) {
            (Some(ctx), Some((last, _))) => ctx.powers(u, *last as usize),
            _ => Vec::new(),
        };
        self.eval_with(&p)
    }

    /// [`Gts::eval`] from the powers u^α of the keys ([`Ctx::powers`] at u, up to this value's
    /// last key at least): for several values at one u (the same enclosure, bit for bit).
    pub(crate) fn eval_with(&self, p: &[I]) -> I {
        let mut r = I::zero().to_jet();
        for (i, c) in self.terms.iter().rev() {
            r = r + match &self.ctx {
                Some(_) => c.mul_constant(&p[*i as usize]),
                None => c.clone(),
            }
            .to_jet();
        }
        I::from_jet(r + self.rem.to_jet())
    }

    /// The value and the derivative in u of the midpoint expansion (midpoint coefficients
    /// and exponents, the remainder's midpoint) at a double u > 0, in f64: an estimate, for
    /// choosing where the rigorous evaluations look (`super::exit_parameter`).
    pub fn mid_value_slope(&self, u: f64) -> (f64, f64) {
        let (mut v, mut d) = (self.rem.mid(), 0.0);
        for (i, c) in &self.terms {
            let c = c.mid();
            match &self.ctx {
                Some(ctx) if *i != 0 => {
                    let a = ctx.basis.exps[*i as usize].mid();
                    let ua = u.powf(a);
                    v += c * ua;
                    d += c * a * ua / u;
                }
                _ => v += c,
            }
        }
        (v, d)
    }

    /// ∫₀^u of the value (see the module's documentation).
    pub fn integral(&self) -> Self {
        let ctx = self.ctx.as_ref().expect("an integral needs a domain");
        let d = I::from_bounds(0.0, ctx.delta).expect("0 < δ < 1");
        let mut rem = mul(&self.rem, &d);
        let mut terms = Vec::with_capacity(self.terms.len());
        for (i, c) in &self.terms {
            let c1 = div(c, &ctx.basis.exps_plus_one[*i as usize]);
            match ctx.basis.plus_one[*i as usize] {
                BEYOND => rem = add(&rem, &mul(&c1, &ctx.beyond)),
                j if ctx.above_cut(j as usize) => {
                    rem = add(&rem, &mul(&c1, &ctx.ranges[j as usize]))
                }
                j => terms.push((j, c1)),
            }
        }
        terms.sort_by_key(|(j, _)| *j);
        Self {
            ctx: self.ctx.clone(),
            terms,
            rem,
            var: 0,
            fac: None,
        }
    }

    /// The mean A(y)(u) = (1/u)∫₀^u y(s) ds (A(y)(0) = y(0)): c·u^α ↦ c·u^α/(α + 1), and the
    /// remainder R stays R — the mean over [0, u] of a function with values in the interval R
    /// lies in R. Exponents do not change, so nothing moves beyond the cut-off.
    pub fn average(&self) -> Self {
        let ctx = self.ctx.as_ref().expect("a mean needs a domain");
        let terms = self
            .terms
            .iter()
            .map(|(i, c)| (*i, div(c, &ctx.basis.exps_plus_one[*i as usize])))
            .collect();
        Self {
            ctx: self.ctx.clone(),
            terms,
            rem: self.rem.clone(),
            var: 0,
            fac: None,
        }
    }

    /// Whether `self`'s set lies in `other`'s, decided coefficientwise (the fixed-point test
    /// T(S) ⊆ S of `super::validate`): true only when
    /// - both are values on one basis and domain ([`Ctx::same_domain`]; a value without a
    ///   context has the constant term only, the same function on every domain), and
    /// - for every key of either value, `self`'s coefficient lies in `other`'s, a key that one
    ///   of them lacks having the coefficient 0 there: a term only in `self` needs its
    ///   coefficient ⊆ [0, 0], a term only in `other` needs 0 in its coefficient, and
    /// - `self`'s remainder lies in `other`'s.
    ///
    /// Sufficient: a function y of `self`'s set has at each u ∈ [0, δ] a value
    /// y(u) = Σ c_α u^α + r with c_α ∈ C_α, r ∈ R (u^α a real ≥ 0 on the domain, the same
    /// function of u for one key in both values); with C_α ⊆ C′_α (0 ∈ C′_α for a key `self`
    /// lacks, C_α = [0, 0] for one `other` lacks) and R ⊆ R′ the same c_α and r give y(u) as a
    /// value of `other`'s set at u, for every u. Not necessary (a remainder may hold what a
    /// coefficient lacks): false only makes the validation try a wider candidate.
    pub fn subset_of(&self, other: &Self) -> bool {
        let same_domain = match (&self.ctx, &other.ctx) {
            (Some(a), Some(b)) => a.same_domain(b),
            (None, _) => self.is_const(),
            (_, None) => other.is_const(),
        };
        if !same_domain {
            return false;
        }
        if !self.rem.subset(&other.rem) {
            return false;
        }
        // the keys of both in increasing order (each list is sorted), u32::MAX past the end
        let zero = I::zero();
        let key = |t: &[(u16, I)], i: usize| t.get(i).map_or(u32::MAX, |e| e.0 as u32);
        let (mut i, mut j) = (0, 0);
        while i < self.terms.len() || j < other.terms.len() {
            let (ka, kb) = (key(&self.terms, i), key(&other.terms, j));
            let inside = if ka == kb {
                self.terms[i].1.subset(&other.terms[j].1)
            } else if ka < kb {
                self.terms[i].1.subset(&zero) // a term only in self: 0 in other
            } else {
                zero.subset(&other.terms[j].1) // a term only in other: 0 in self
            };
            if !inside {
                return false;
            }
            i += usize::from(ka <= kb);
            j += usize::from(kb <= ka);
        }
        true
    }

    /// Each coefficient widened by `rel` of its width plus `abs_c` of its magnitude, the
    /// remainder by `rel` of its width plus `abs_r` (the next candidate of a fixed-point
    /// iteration; any widening is sound, the inclusion test decides).
    pub fn inflate(&self, rel: f64, abs_c: f64, abs_r: f64) -> Self {
        Self {
            ctx: self.ctx.clone(),
            terms: self
                .terms
                .iter()
                .map(|(k, c)| (*k, c.widen(rel, abs_c * c.mag_f64().max(1e-300))))
                .collect(),
            rem: self.rem.widen(rel, abs_r),
            var: 0,
            fac: None,
        }
    }

    /// The same value with the constant coefficient c.
    pub fn with_constant(mut self, c: I) -> Self {
        match self.terms.first_mut() {
            Some((0, x)) => *x = c,
            _ => self.terms.insert(0, (0, c)),
        }
        self.var = 0;
        self.fac = None;
        self
    }

    /// The same set in the context `ctx` of the same basis and domain (e.g. a truncated one
    /// or the full one again, [`Ctx::truncated`]): terms above its cut-off go into the
    /// remainder by their range. A value of another basis or domain, or without a context,
    /// is returned as it is (its own context stays: sound either way).
    pub fn in_ctx(&self, ctx: &Arc<Ctx<I>>) -> Self {
        let Some(own) = &self.ctx else {
            return self.clone();
        };
        if Arc::ptr_eq(own, ctx) || !Arc::ptr_eq(&own.basis, &ctx.basis) || own.delta != ctx.delta {
            return self.clone();
        }
        let mut rem = self.rem.clone();
        let mut terms = Vec::with_capacity(self.terms.len());
        for (i, c) in &self.terms {
            if ctx.above_cut(*i as usize) {
                rem = add(&rem, &mul(c, &ctx.ranges[*i as usize]));
            } else {
                terms.push((*i, c.clone()));
            }
        }
        let moved = terms.len() < self.terms.len();
        Self {
            ctx: Some(ctx.clone()),
            terms,
            rem,
            // ±u is kept exactly (its one term has exponent 1 ≤ every cut-off)
            var: if moved { 0 } else { self.var },
            fac: self
                .fac
                .as_ref()
                .filter(|_| !moved)
                .map(|f| Arc::new((f.0, f.1.in_ctx(ctx)))),
        }
    }

    /// Every coefficient and the remainder are bounded.
    pub fn is_bounded(&self) -> bool {
        bounded(&self.rem) && self.terms.iter().all(|(_, c)| bounded(c))
    }

    /// Whether both operands of a product or power are bounded. One that is not — above all
    /// an expansion that does not exist ([`Real::unbounded`]: no terms, every real as the
    /// remainder), the sign of a hypothesis failing — must make the result unbounded too:
    /// the shortcuts for a value without a context read it as its constant coefficient, which
    /// is 0 there, and would drop the remainder (x·unbounded = 0, |unbounded|^q = 0).
    fn both_bounded(a: &Self, b: &Self) -> bool {
        a.is_bounded() && b.is_bounded()
    }

    /// [`Real::unbounded`] in the context `ctx` (kept, so that a later integral or mean of it
    /// has a domain: unbounded as well).
    fn unbounded_in(ctx: Option<Arc<Ctx<I>>>) -> Self {
        Self {
            ctx,
            ..<Self as Real>::unbounded()
        }
    }

    /// self^q for a value of one sign s (the constant coefficient sc₀ > 0 and every function
    /// of the set > 0): c₀^q Σ binom(q, k) εᵏ + Lagrange's remainder, ε = (x − c₀)/c₀.
    fn analytic_pow(&self, q: I) -> Self {
        let c0 = self.c0();
        let Some(ctx) = self.ctx.clone() else {
            return Self::constant(Real::pow(&c0, &q));
        };
        if c0.lo() <= 0.0 || self.range().lo() <= 0.0 {
            return Self::unbounded();
        }
        // ε = x/c₀ − 1
        let inv_c0 = I::one() / c0.clone();
        let mut eps = self.scale_by(&inv_c0);
        if let Some(first) = eps.terms.first_mut()
            && first.0 == 0
        {
            first.1 = first.1.clone() - I::one();
        }
        let e_range = eps.range();
        if e_range.mag_f64() >= 0.5 {
            return Self::unbounded();
        }
        // the smallest exponent in ε: εᵏ is beyond the cut-off once k·α_min > M
        let a_min = eps
            .terms
            .iter()
            .filter(|(i, _)| *i != 0)
            .map(|(i, _)| ctx.basis.exps[*i as usize].lo())
            .fold(f64::INFINITY, f64::min);
        let kmax = if a_min.is_finite() && a_min > 0.0 {
            ((ctx.cut / a_min).floor() as usize + 1).clamp(1, 40)
        } else {
            1
        };
        // Σ_{k<K} binom(q, k) εᵏ by Horner's scheme in ε, then Lagrange's term for k ≥ K
        let mut binoms = vec![I::one()];
        for k in 1..=kmax {
            let b = binoms[k - 1].clone() * (q.clone() - I::from_int(k as i64 - 1))
                / I::from_int(k as i64);
            binoms.push(b);
        }
        // S_k = S_{k+1}·ε + binom(q, k) is multiplied by ε k more times, and each raises a
        // term's exponent by at least α_min (ε's constant, a few ulps of 0, aside): terms of
        // S_k above M − k·α_min end beyond M, so they go to the remainder already here
        // (the same bound, |c|δ^α times ε's magnitudes, without the pairs' products)
        let mut sum = Self::constant_in(&ctx, binoms[kmax - 1].clone());
        let eps_bounds = eps.bounds(&ctx);
        for k in (0..kmax - 1).rev() {
            let cut = if a_min.is_finite() {
                ctx.cut - k as f64 * a_min
            } else {
                f64::INFINITY
            };
            // (`sum` always has the context: constant_in gives it one)
            let sb = sum.bounds(&ctx);
            sum = sum
                .product_bounded(&eps, &ctx, &sb, &eps_bounds, cut)
                .shift_by(binoms[k].clone());
        }
        // Lagrange: binom(q, K)·(1 + θε)^(q−K)·ε^K, θ ∈ [0, 1]
        let k = kmax as i64;
        let base = I::one() + e_range.hull(&I::zero());
        let lag = binoms[kmax].clone()
            * Real::pow(&base, &(q.clone() - I::from_int(k)))
            * e_range.powi_signed(k as u32);
        sum.rem = sum.rem.clone() + lag;
        sum.scale_by(&Real::pow(&c0, &q))
    }

    /// The coefficients of self·o within the cut-off (each Σ c_a·c_b over the pairs whose
    /// exponents sum to its own, in one accumulator of the type: for f64 intervals a single
    /// rounding bound) and an upper bound of Σ |c_a|δ^α_a·|c_b|δ^α_b over the pairs beyond it
    /// (which bounds those terms: |c_a c_b u^(α_a+α_b)| ≤ |c_a|δ^α_a·|c_b|δ^α_b on [0, δ]);
    /// `ma`, `mb` are the magnitudes |c|δ^α of `self`'s and `o`'s terms.
    ///
    /// By the exponents' order ([`Prefix`]): with `o`'s terms sorted by it, the partners of a
    /// term of `self` within the cut-off are a prefix of them, so the loop over a row stops at
    /// the first one beyond, and the rest are bounded at once by |c_a|δ^α_a times the suffix
    /// sum of `o`'s magnitudes (an enclosure of the exact sum) — instead of a test per pair,
    /// whose outcome the keys' own order made unpredictable (measured on the 28 Table 1
    /// cases: the crossing steps' Picard operations 15 % faster).
    fn products_by_prefix(
        &self,
        o: &Gts<I>,
        ctx: &Ctx<I>,
        pf: &Prefix,
        ma: &[I],
        mb: &[I],
        cut_exp: f64,
    ) -> (Vec<(u16, I)>, f64) {
        let n = pf.pos.len();
        let sum = &ctx.basis.sum;
        let exps = &ctx.basis.exps;
        // o's terms by position: (position, key, coefficient, magnitude)
        let mut ob: Vec<(u16, u16, &I, &I)> = o
            .terms
            .iter()
            .zip(mb)
            .map(|((k, c), m)| (pf.pos[*k as usize], *k, c, m))
            .collect();
        ob.sort_unstable_by_key(|e| e.0);
        // suffix[t] ⊇ Σ_{s ≥ t} magnitude of ob[s]
        let mut suffix = vec![I::zero(); ob.len() + 1];
        for t in (0..ob.len()).rev() {
            suffix[t] = add(&suffix[t + 1], ob[t].3);
        }
        let mut acc: Vec<Option<I::Dot>> = (0..n).map(|_| None).collect();
        let mut beyond = <I::Dot as Dot<I>>::new();
        for ((ia, ca), m) in self.terms.iter().zip(ma) {
            let ia = *ia as usize;
            let (cut, row) = (pf.cut[ia], &sum[ia * n..(ia + 1) * n]);
            // partners within `cut_exp` (by the exponents' lower ends, the order of `ob`):
            // also a prefix; any partner left out is bounded with the suffix below
            let room = cut_exp - exps[ia].lo();
            let mut t = 0;
            while t < ob.len() && ob[t].0 < cut && exps[ob[t].1 as usize].lo() <= room {
                let k = row[ob[t].1 as usize];
                acc[k as usize]
                    .get_or_insert_with(<I::Dot as Dot<I>>::new)
                    .add_prod(ca, ob[t].2);
                t += 1;
            }
            beyond.add_prod(m, &suffix[t]);
        }
        (Self::sums(acc), beyond.sum().hi())
    }

    /// [`Gts::products_by_prefix`] by a lookup of each pair in the table of sums (for a basis
    /// without the prefix order).
    fn products_by_table(
        &self,
        o: &Gts<I>,
        ctx: &Ctx<I>,
        ma: &[I],
        mb: &[I],
        cut_exp: f64,
    ) -> (Vec<(u16, I)>, f64) {
        let n = ctx.basis.keys.len();
        let exps = &ctx.basis.exps;
        let mut acc: Vec<Option<I::Dot>> = (0..n).map(|_| None).collect();
        let mut beyond = <I::Dot as Dot<I>>::new();
        for ((ia, ca), ma) in self.terms.iter().zip(ma) {
            let row = &ctx.basis.sum[*ia as usize * n..(*ia as usize + 1) * n];
            let room = cut_exp - exps[*ia as usize].lo();
            for ((ib, cb), mb) in o.terms.iter().zip(mb) {
                match row[*ib as usize] {
                    _ if exps[*ib as usize].lo() > room => beyond.add_prod(ma, mb),
                    BEYOND => beyond.add_prod(ma, mb),
                    k => acc[k as usize]
                        .get_or_insert_with(<I::Dot as Dot<I>>::new)
                        .add_prod(ca, cb),
                }
            }
        }
        (Self::sums(acc), beyond.sum().hi())
    }

    /// The terms of the accumulators that received a product.
    fn sums(acc: Vec<Option<I::Dot>>) -> Vec<(u16, I)> {
        acc.into_iter()
            .enumerate()
            .filter_map(|(k, c)| c.map(|c| (k as u16, c.sum())))
            .collect()
    }

    /// self·c for an interval constant c.
    fn scale_by(&self, c: &I) -> Self {
        Self {
            ctx: self.ctx.clone(),
            terms: self
                .terms
                .iter()
                .map(|(i, x)| (*i, x.mul_constant(c)))
                .collect(),
            rem: self.rem.mul_constant(c),
            var: 0,
            fac: None,
        }
    }

    /// self + c for an interval constant c.
    fn shift_by(mut self, c: I) -> Self {
        match self.terms.first_mut() {
            Some((0, x)) => *x = add(x, &c),
            _ => self.terms.insert(0, (0, c)),
        }
        self.var = 0;
        self.fac = None;
        self
    }

    /// 1/self for a value of one sign.
    fn recip(&self) -> Self {
        let s = match Real::sign(&self.range()) {
            Some(s) => s,
            None => return Self::unbounded(),
        };
        let x = if s > 0 { self.clone() } else { -self.clone() };
        let r = x.analytic_pow(I::from_int(-1));
        if s > 0 { r } else { -r }
    }

    /// The sign of every function of the set (the independent variable's own sign for ±u).
    fn certain_sign(&self) -> Option<i8> {
        if self.var != 0 {
            return Some(self.var);
        }
        if let Some((s, _)) = self.positive_factor() {
            return Some(s);
        }
        Real::sign(&self.range())
    }

    /// (s, W) of a value s·u·W ([`Gts::factored`]) whose W is > 0 on the whole domain.
    fn positive_factor(&self) -> Option<(i8, &Gts<I>)> {
        let f = self.fac.as_deref()?;
        (f.1.range().lo() > 0.0).then_some((f.0, &f.1))
    }

    /// s·u^q·W^q (`signed`) or u^q·W^q for the value s·u·W ([`Gts::factored`]).
    fn factored_pow(&self, s: i8, w: &Gts<I>, q: &Self, signed: bool) -> Self {
        if !q.is_const() {
            return Self::unbounded();
        }
        let c = if signed {
            I::from_int(s as i64)
        } else {
            I::one()
        };
        self.monomial_of(q, c) * w.analytic_pow(q.c0())
    }

    /// u^(g_j)·c for the generator of the constant exponent `q`.
    fn monomial_of(&self, q: &Self, c: I) -> Self {
        let Some(ctx) = self.ctx.clone() else {
            return Self::unbounded();
        };
        if !q.is_const() {
            return Self::unbounded();
        }
        let Some(g) = ctx.basis.gen_of(&q.c0()) else {
            return Self::unbounded();
        };
        match ctx.basis.gen_index(g) {
            BEYOND => Self {
                rem: c * ctx.beyond.clone(),
                ctx: Some(ctx),
                terms: Vec::new(),
                var: 0,
                fac: None,
            },
            i if ctx.above_cut(i as usize) => Self {
                rem: c * ctx.ranges[i as usize].clone(),
                ctx: Some(ctx),
                terms: Vec::new(),
                var: 0,
                fac: None,
            },
            i => Self {
                ctx: Some(ctx),
                terms: vec![(i, c)],
                rem: I::zero(),
                var: 0,
                fac: None,
            },
        }
    }
}

impl<I: Enclosure> Add for Gts<I> {
    type Output = Gts<I>;
    fn add(self, o: Gts<I>) -> Gts<I> {
        let ctx = Gts::merge_ctx(&self.ctx, &o.ctx);
        let mut terms = Vec::with_capacity(self.terms.len() + o.terms.len());
        let (mut i, mut j) = (0, 0);
        while i < self.terms.len() || j < o.terms.len() {
            match (self.terms.get(i), o.terms.get(j)) {
                (Some(a), Some(b)) if a.0 == b.0 => {
                    terms.push((a.0, add(&a.1, &b.1)));
                    i += 1;
                    j += 1;
                }
                (Some(a), Some(b)) if a.0 < b.0 => {
                    terms.push(a.clone());
                    i += 1;
                }
                (Some(a), None) => {
                    terms.push(a.clone());
                    i += 1;
                }
                (_, Some(b)) => {
                    terms.push(b.clone());
                    j += 1;
                }
                (None, None) => unreachable!(),
            }
        }
        Gts {
            ctx,
            terms,
            rem: add(&self.rem, &o.rem),
            var: 0,
            fac: None,
        }
    }
}

impl<I: Enclosure> Neg for Gts<I> {
    type Output = Gts<I>;
    fn neg(self) -> Gts<I> {
        Gts {
            ctx: self.ctx,
            terms: self.terms.into_iter().map(|(k, c)| (k, -c)).collect(),
            rem: -self.rem,
            var: -self.var,
            fac: self.fac.map(|f| Arc::new((-f.0, f.1.clone()))),
        }
    }
}

impl<I: Enclosure> Sub for Gts<I> {
    type Output = Gts<I>;
    fn sub(self, o: Gts<I>) -> Gts<I> {
        self + (-o)
    }
}

impl<I: Enclosure> Mul for Gts<I> {
    type Output = Gts<I>;
    fn mul(self, o: Gts<I>) -> Gts<I> {
        self.product(&o, f64::INFINITY)
    }
}

impl<I: Enclosure> Gts<I> {
    /// self·o with the terms of exponent above `cut` (as well as those above the basis's
    /// cut-off M) moved into the remainder by their range (any term may be: the remainder
    /// then holds it for every u of the domain). A `cut` below M is for a factor that is
    /// multiplied again later by values without a constant term, which lifts those terms
    /// beyond M anyway (see [`Gts::analytic_pow`]).
    fn product(&self, o: &Gts<I>, cut: f64) -> Gts<I> {
        if !Self::both_bounded(self, o) {
            return Self::unbounded_in(Gts::merge_ctx(&self.ctx, &o.ctx));
        }
        if self.ctx.is_none() && self.is_const() {
            return o.scale_by(&self.c0());
        }
        if o.ctx.is_none() && o.is_const() {
            return self.scale_by(&o.c0());
        }
        let ctx = Gts::merge_ctx(&self.ctx, &o.ctx).expect("a product of non-constants");
        let (a, b) = (self.bounds(&ctx), o.bounds(&ctx));
        self.product_bounded(o, &ctx, &a, &b, cut)
    }

    /// The magnitudes |c|δ^α of the terms (upper bounds, as points) and the polynomial part's
    /// range [`Gts::poly_range`], from one product c·[0, δ^α] per term.
    fn bounds(&self, ctx: &Ctx<I>) -> Bounds<I> {
        let mut mags = vec![I::zero(); self.terms.len()];
        let mut r = I::zero().to_jet();
        for (t, (i, c)) in self.terms.iter().enumerate().rev() {
            let p = c.mul_constant(&ctx.ranges[*i as usize]);
            mags[t] = point_mag(&p);
            r = r + p.to_jet();
        }
        Bounds {
            mags,
            range: I::from_jet(r),
        }
    }

    /// [`Gts::product`] with the operands' [`Gts::bounds`] given (a factor used in several
    /// products has them computed once).
    fn product_bounded(
        &self,
        o: &Gts<I>,
        ctx: &Arc<Ctx<I>>,
        a: &Bounds<I>,
        b: &Bounds<I>,
        cut: f64,
    ) -> Gts<I> {
        let cut = cut.min(ctx.cut);
        let (terms, beyond) = match &ctx.basis.prefix {
            Some(pf) => self.products_by_prefix(o, ctx, pf, &a.mags, &b.mags, cut),
            None => self.products_by_table(o, ctx, &a.mags, &b.mags, cut),
        };
        let mut rem = I::from_bounds(-beyond, beyond).unwrap_or_else(I::entire);
        let zero = I::zero();
        if !(self.rem.same(&zero) && o.rem.same(&zero)) {
            let (pa, pb) = (&a.range, &b.range);
            rem = I::from_jet(
                rem.to_jet()
                    + pa.mul_constant(&o.rem).to_jet()
                    + pb.mul_constant(&self.rem).to_jet()
                    + self.rem.mul_constant(&o.rem).to_jet(),
            );
        }
        Gts {
            ctx: Some(ctx.clone()),
            terms,
            rem,
            var: 0,
            fac: None,
        }
    }
}

/// A value's term magnitudes |c|δ^α and polynomial range (see [`Gts::bounds`]).
struct Bounds<I> {
    mags: Vec<I>,
    range: I,
}

impl<I: Enclosure> Div for Gts<I> {
    type Output = Gts<I>;
    fn div(self, o: Gts<I>) -> Gts<I> {
        if o.is_const() && o.ctx.is_none() {
            let c = o.c0();
            return self * Gts::constant(I::one() / c);
        }
        self * o.recip()
    }
}

impl<I: Enclosure> Real for Gts<I> {
    type Dot = PlainDot<Self>;
    type Prepared = ();
    fn prepare_exponent(_: &Self) {}
    fn from_int(k: i64) -> Self {
        Self::constant(I::from_int(k))
    }
    fn from_exact_f64(x: f64) -> Self {
        Self::constant(I::from_exact_f64(x))
    }
    fn parse_decimal(s: &str) -> Result<Self, String> {
        I::parse_decimal(s).map(Self::constant)
    }
    fn unbounded() -> Self {
        Self {
            ctx: None,
            terms: Vec::new(),
            rem: I::entire(),
            var: 0,
            fac: None,
        }
    }
    fn abs(&self) -> Self {
        if let (Some((_, w)), Some(ctx)) = (self.positive_factor(), &self.ctx) {
            return Self::factored(ctx, 1, w.clone());
        }
        match self.certain_sign() {
            Some(s) if self.var != 0 => self.clone() * Self::from_int(s as i64),
            Some(s) if s > 0 => self.clone(),
            Some(_) => -self.clone(),
            None => Self::unbounded(),
        }
    }
    fn sqrt(&self) -> Self {
        if !Self::both_bounded(self, self) {
            return Self::unbounded_in(self.ctx.clone());
        }
        if self.is_const() && self.ctx.is_none() {
            Self::constant(Real::sqrt(&self.c0()))
        } else {
            self.analytic_pow(I::from_exact_f64(0.5))
        }
    }
    fn ln(&self) -> Self {
        if self.is_const() && self.ctx.is_none() {
            Self::constant(Real::ln(&self.c0()))
        } else {
            Self::unbounded()
        }
    }
    fn sgn(&self) -> Self {
        match self.certain_sign() {
            Some(s) => Self::from_int(s as i64),
            None => Self::unbounded(),
        }
    }
    fn pow(&self, y: &Self) -> Self {
        if !Self::both_bounded(self, y) {
            return Self::unbounded_in(self.ctx.clone());
        }
        if !y.is_const() {
            return Self::unbounded();
        }
        if self.is_const() && self.ctx.is_none() {
            return Self::constant(Real::pow(&self.c0(), &y.c0()));
        }
        self.analytic_pow(y.c0())
    }
    /// |x|^(q−1)x: ±u^q for x = ±u; s·(s x)^q for x of one sign s.
    fn spow(&self, q: &Self) -> Self {
        if !Self::both_bounded(self, q) {
            return Self::unbounded_in(self.ctx.clone());
        }
        if self.is_const() && self.ctx.is_none() && q.is_const() {
            return Self::constant(Real::spow(&self.c0(), &q.c0()));
        }
        if self.var != 0 {
            return self.monomial_of(q, I::from_int(self.var as i64));
        }
        if let Some((s, w)) = self.positive_factor() {
            return self.factored_pow(s, w, q, true);
        }
        match self.certain_sign() {
            Some(1) if q.is_const() => self.analytic_pow(q.c0()),
            Some(-1) if q.is_const() => -((-self.clone()).analytic_pow(q.c0())),
            _ => Self::unbounded(),
        }
    }
    /// The pair's other power from `other`: for x of a certain sign s (±u, s·u·W with W > 0,
    /// or a value of one sign) |x|^(q−1)x = s·|x|^q exactly, so one series serves both (at a
    /// crossing of Z, |X|^p and |X|^(p−1)X took two binomial series of 7 products each);
    /// otherwise anew.
    fn twin_pow(&self, q: &Self, other: &Self, signed: bool) -> Self {
        match self.certain_sign() {
            Some(1) if q.is_const() => other.clone(),
            Some(-1) if q.is_const() => -other.clone(),
            _ if signed => self.spow(q),
            _ => self.apow(q),
        }
    }
    /// |x|^q: u^q for x = ±u; (s x)^q for x of one sign s.
    fn apow(&self, q: &Self) -> Self {
        if !Self::both_bounded(self, q) {
            return Self::unbounded_in(self.ctx.clone());
        }
        if self.is_const() && self.ctx.is_none() && q.is_const() {
            return Self::constant(Real::apow(&self.c0(), &q.c0()));
        }
        if q.is_const() && q.c0().same(&I::zero()) {
            return Self::from_int(1);
        }
        if self.var != 0 {
            return self.monomial_of(q, I::one());
        }
        if let Some((s, w)) = self.positive_factor() {
            return self.factored_pow(s, w, q, false);
        }
        match self.certain_sign() {
            Some(1) if q.is_const() => self.analytic_pow(q.c0()),
            Some(-1) if q.is_const() => (-self.clone()).analytic_pow(q.c0()),
            _ => Self::unbounded(),
        }
    }
    fn lo(&self) -> f64 {
        self.range().lo()
    }
    fn hi(&self) -> f64 {
        self.range().hi()
    }
    fn mid(&self) -> f64 {
        self.range().mid()
    }
    /// Not decided for generalized polynomials (no caller needs it): false.
    fn encloses(&self, _: &Self) -> bool {
        false
    }
    fn as_integer(&self) -> Option<i64> {
        if self.is_const() && self.rem.same(&I::zero()) {
            self.c0().as_integer()
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use inari::const_interval;

    const ZERO: Interval = const_interval!(0.0, 0.0);

    fn iv(a: f64, b: f64) -> Interval {
        Interval::try_from((a, b)).unwrap()
    }

    /// The prefix order is refused where a row's sums within the cut-off are not a prefix in
    /// the exponents' order (a table no basis of distinct exponents gives, made by hand here:
    /// key 1 sums with key 2 beyond the cut-off but with key 3, of a larger exponent, within
    /// it), and kept where they are.
    #[test]
    fn the_prefix_order_is_checked_row_by_row() {
        let exps = [iv(0.0, 0.0), iv(1.0, 1.0), iv(1.5, 1.5), iv(2.0, 2.0)];
        let b = BEYOND;
        let prefix = [0, 1, 2, 3, 1, 3, b, b, 2, b, b, b, 3, b, b, b];
        let pf = Prefix::new(&exps, &prefix).expect("every row a prefix");
        assert_eq!(pf.cut, vec![4, 2, 1, 1]);
        let mut gap = prefix;
        gap[4 + 2] = b;
        gap[4 + 3] = 3;
        assert!(Prefix::new(&exps, &gap).is_none());
    }

    /// The products by the exponents' order and by the table of sums ([`prefix_order::compare`]),
    /// on the Table 1 exponents with δ = 0.6 (the terms beyond the cut-off large), for which the
    /// prefix order must hold: each coefficient contains the exact Σ c_a·c_b over its pairs,
    /// both routes give the same keys, and the bound of the terms beyond the cut-off is at
    /// least the exact Σ |c_a|δ^α_a·|c_b|δ^α_b over the pairs beyond it (and not far above). A
    /// prefix cut one position off, a suffix sum from the wrong term or a bound left out fails
    /// here.
    #[test]
    fn prefix_products_equal_the_pair_table_and_the_exact_sums() {
        let gens = [
            Interval::parse_decimal("1.31").unwrap(),
            Interval::parse_decimal("1.27").unwrap(),
            Interval::parse_decimal("2.02").unwrap(),
        ];
        let basis = Basis::new(&gens, 6.0).unwrap();
        let pf = basis
            .prefix
            .as_ref()
            .expect("distinct exponents: the prefix order holds");
        let n = basis.keys.len();
        assert!(pf.cut.iter().any(|&c| (c as usize) < n) && pf.cut[0] as usize == n);
        assert!(super::prefix_order::compare(
            &gens,
            6.0,
            0.6,
            "Table 1 exponents",
            300
        ));
    }

    /// y = 0.7 + 0.3u − 2u^1.31 − 0.1u² on [0, δ] with cut-off M; then y^1.5, 1/y, ∫y and the
    /// powers of −u, checked against the functions at points of the domain. With a small M the
    /// remainders carry most terms (a remainder dropped or too small shows here).
    fn check(m: f64, delta: f64, tight: f64) {
        check_cut(m, delta, tight, f64::INFINITY);
    }

    /// [`check`] in the context cut off at `cut` ([`Ctx::truncated`]): no term above the cut
    /// in any result, and the functions still inside.
    fn check_cut(m: f64, delta: f64, tight: f64, cut: f64) {
        let q = Interval::parse_decimal("1.31").unwrap();
        let ctx = Ctx::new(&Basis::new(&[q], m).unwrap(), delta)
            .unwrap()
            .truncated(cut);
        let u = Gts::variable(&ctx, -1); // Z = −u
        let y = Gts::constant_in(&ctx, iv(0.7, 0.7)) + u.clone() * Gts::from_exact_f64(-0.3)
            - Real::apow(&u, &Gts::constant(q)) * Gts::from_int(2)
            - u.clone() * u.clone() * Gts::from_exact_f64(0.1);
        let f = |s: f64| 0.7 + 0.3 * s - 2.0 * s.powf(1.31) - 0.1 * s * s;
        let p = Real::pow(&y, &Gts::constant(iv(1.5, 1.5)));
        let r = Gts::from_int(1) / y.clone();
        let yy = y.clone() * y.clone() * y.clone();
        let i = y.integral();
        let sp = Real::spow(&u, &Gts::constant(q));
        for g in [&y, &p, &r, &yy, &i, &sp] {
            for (k, _) in g.terms() {
                let alpha = k[0] as f64 + 1.31 * k[1] as f64;
                assert!(
                    alpha <= cut.max(1.0) + 1e-12,
                    "M {m}, cut {cut}: a term u^{alpha}"
                );
            }
        }
        for frac in [0.0, 1e-6, 0.1, 0.3, 0.6, 1.0] {
            let s = frac * delta;
            let us = iv(s, s);
            let fy = f(s);
            // a few ulps of slack for the f64 reference itself
            let near = |x: Interval, v: f64| x.inf() - 4e-16 <= v && v <= x.sup() + 4e-16;
            assert!(near(y.eval(&us), fy), "M {m}: y at {s}");
            assert!(near(yy.eval(&us), fy * fy * fy), "M {m}: y³ at {s}");
            assert!(
                near(p.eval(&us), fy.powf(1.5)),
                "M {m}: y^1.5 at {s}: {:?}",
                p.eval(&us)
            );
            assert!(near(r.eval(&us), 1.0 / fy), "M {m}: 1/y at {s}");
            // ∫₀^s f by a fine midpoint rule (error ≤ s·h²/24·max|f''| < 1e-13 here)
            let n = 20000;
            let h = s / n as f64;
            let quad: f64 = (0..n).map(|j| f((j as f64 + 0.5) * h)).sum::<f64>() * h;
            let iv_s = i.eval(&us);
            assert!(
                iv_s.inf() - 1e-13 <= quad && quad <= iv_s.sup() + 1e-13,
                "M {m}: ∫y at {s}: {iv_s:?} vs {quad}"
            );
            assert!(near(sp.eval(&us), -s.powf(1.31)), "M {m}: spow(−u) at {s}");
            assert!(
                p.eval(&us).wid() < tight && r.eval(&us).wid() < tight,
                "M {m}: {:?} {:?}",
                p.eval(&us),
                r.eval(&us)
            );
        }
    }

    /// The cheap plain iterations of the singular steps run in contexts cut off below M: their
    /// operations move the terms above the cut into the remainder, and a value moved into such
    /// a context ([`Gts::in_ctx`]) and back still holds its function.
    #[test]
    fn truncated_contexts_contain_the_functions_too() {
        for cut in [1.0, 2.0, 3.5] {
            check_cut(8.0, 0.01, f64::INFINITY, cut);
            check_cut(6.0, 0.002, f64::INFINITY, cut);
        }
        let q = Interval::parse_decimal("1.31").unwrap();
        let full = Ctx::new(&Basis::new(&[q], 6.0).unwrap(), 0.05).unwrap();
        let u = Gts::variable(&full, 1);
        let y = Gts::constant_in(&full, iv(0.7, 0.7)) + u.clone() * Gts::from_exact_f64(0.3)
            - Real::apow(&u, &Gts::constant(q)) * Gts::from_int(2)
            - u.clone() * u.clone() * u.clone() * Gts::from_exact_f64(0.1);
        let f = |s: f64| 0.7 + 0.3 * s - 2.0 * s.powf(1.31) - 0.1 * s * s * s;
        for cut in [1.0, 2.0, 2.7] {
            let low = y.in_ctx(&full.truncated(cut));
            assert!(
                low.terms().len() < y.terms().len(),
                "cut {cut}: nothing moved"
            );
            let back = low.in_ctx(&full);
            for frac in [0.0, 0.3, 1.0] {
                let s = frac * 0.05;
                for g in [&low, &back] {
                    let v = g.eval(&iv(s, s));
                    assert!(
                        v.inf() - 4e-16 <= f(s) && f(s) <= v.sup() + 4e-16,
                        "cut {cut} at {s}: {v:?} vs {}",
                        f(s)
                    );
                }
            }
        }
    }

    #[test]
    fn products_powers_and_integrals_contain_the_functions_they_stand_for() {
        check(8.0, 0.01, 1e-12);
        check(6.0, 0.002, 1e-12);
        // remainder-dominated: most terms are beyond the cut-off
        check(2.0, 0.05, 0.05);
        check(1.5, 0.2, 1.0);
    }

    /// Powers and reciprocals (the binomial series by Horner's scheme, each partial sum cut at
    /// M − k·α_min) hold the exact values: y = c₀ + Σ c_α u^α with random double coefficients
    /// on the exponents of 1, 1.31 and 1.27 (as decimals), y^q for q ∈ {1.5, −1, 0.31, 2.27} at
    /// points of the domain against 256-bit MPFR, compared as rationals. The exact value must
    /// lie inside, and the enclosure be narrow where the remainder is small (a partial sum cut
    /// too soon loses width there, a term dropped without its bound loses the value).
    #[test]
    fn powers_hold_the_exact_values_at_points() {
        use rug::{Float, Rational, ops::Pow};
        const PREC: u32 = 256;
        let dec = |x: &str| Interval::parse_decimal(x).unwrap();
        let gens = [dec("1.31"), dec("1.27")];
        let exact_gens = [
            Float::with_val(PREC, 1),
            Float::parse("1.31")
                .map(|p| Float::with_val(PREC, p))
                .unwrap(),
            Float::parse("1.27")
                .map(|p| Float::with_val(PREC, p))
                .unwrap(),
        ];
        let q = |x: f64| Rational::from_f64(x).unwrap();
        let mut next = crate::arith::interval::xorshift(0x51af_d7ed_558c_cd1f_u64);
        let mut unit = move || ((next() >> 11) as f64 / (1u64 << 53) as f64) - 0.5;
        let mut checked = 0;
        for (m, delta) in [(6.0, 1.5e-3), (6.0, 0.05), (4.0, 0.01), (8.0, 0.02)] {
            let basis = Basis::new(&gens, m).unwrap();
            let ctx = Ctx::new(&basis, delta).unwrap();
            for _ in 0..12 {
                // y = c0 + a u + b u^1.31 + c u^1.27 + d u^2.58 (keys by generator counts)
                let c0 = 0.5 + unit().abs();
                let cs = [unit() * 4.0, unit() * 4.0, unit() * 4.0, unit()];
                let u = Gts::variable(&ctx, 1);
                let mono = |g: usize| Real::apow(&u, &Gts::constant(gens[g]));
                let y = Gts::constant_in(&ctx, iv(c0, c0))
                    + u.clone() * Gts::from_exact_f64(cs[0])
                    + mono(0) * Gts::from_exact_f64(cs[1])
                    + mono(1) * Gts::from_exact_f64(cs[2])
                    + mono(0) * mono(0) * Gts::from_exact_f64(cs[3]);
                let exact_y = |s: f64| {
                    let s = Float::with_val(PREC, s);
                    let p = |g: usize| s.clone().pow(&exact_gens[g]);
                    Float::with_val(PREC, c0)
                        + Float::with_val(PREC, cs[0]) * p(0)
                        + Float::with_val(PREC, cs[1]) * p(1)
                        + Float::with_val(PREC, cs[2]) * p(2)
                        + Float::with_val(PREC, cs[3]) * p(1) * p(1)
                };
                for (qs, qf) in [("1.5", 1.5), ("-1", -1.0), ("0.31", 0.31), ("2.27", 2.27)] {
                    let qi = dec(qs);
                    let pw = if qf < 0.0 {
                        Gts::from_int(1) / y.clone()
                    } else {
                        Real::pow(&y, &Gts::constant(qi))
                    };
                    let qx = Float::with_val(PREC, Float::parse(qs).unwrap());
                    for frac in [0.0, 0.25, 0.5, 0.9, 1.0] {
                        let s = frac * delta;
                        let Some(yv) = Some(exact_y(s)).filter(|v| *v > 0) else {
                            continue;
                        };
                        let exact = yv.pow(&qx);
                        let e = pw.eval(&iv(s, s));
                        // from the powers of every key at once: the same enclosure, bit for bit
                        let all = ctx.powers(&iv(s, s), basis.len() - 1);
                        let e2 = pw.eval_with(&all);
                        assert!(
                            e.inf().to_bits() == e2.inf().to_bits()
                                && e.sup().to_bits() == e2.sup().to_bits()
                        );
                        assert!(
                            q(e.inf()) <= exact.to_rational().unwrap()
                                && exact.to_rational().unwrap() <= q(e.sup()),
                            "M {m} δ {delta} q {qs} at {s}: {e:?} against {exact}"
                        );
                        if delta <= 1.5e-3 {
                            assert!(e.wid() < 1e-12, "M {m} δ {delta} q {qs}: {e:?}");
                        }
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 800, "{checked} points checked");
    }

    /// The process's cache of bases gives, for inari intervals, the basis `new` makes (same
    /// generators, keys and exponents), once per generators and cut-off: the same Arc again
    /// for the same ends, another for other ends or another cut-off; for MPFR intervals a basis
    /// made anew each time (their f64 ends do not determine them).
    #[test]
    fn cached_bases_are_the_bases_of_their_generators() {
        let g = [iv(1.31, 1.31), iv(1.27, 1.27)];
        let a = Basis::cached(&g, 6.0).unwrap();
        let b = Basis::new(&g, 6.0).unwrap();
        assert_eq!(a.keys, b.keys);
        assert!(a.exps.iter().zip(&b.exps).all(|(x, y)| x.same(y)));
        assert!(a.gens.iter().zip(&b.gens).all(|(x, y)| x.same(y)));
        assert!(Arc::ptr_eq(&a, &Basis::cached(&g, 6.0).unwrap()));
        let wider = [iv(1.31, 1.31), iv(1.27, 1.27f64.next_up())];
        let c = Basis::cached(&wider, 6.0).unwrap();
        assert!(!Arc::ptr_eq(&a, &c) && c.gens[2].same(&wider[1]));
        assert!(!Arc::ptr_eq(&a, &Basis::cached(&g, 5.0).unwrap()));
        use crate::arith::mpfr::Mpi;
        let gm = [Mpi::<128>::parse_decimal("1.31").unwrap()];
        let (m1, m2) = (
            Basis::cached(&gm, 6.0).unwrap(),
            Basis::cached(&gm, 6.0).unwrap(),
        );
        assert!(!Arc::ptr_eq(&m1, &m2) && m1.keys == m2.keys);
        // no generators (the review's case: it returned None for MPFR intervals)
        let none: [Mpi<128>; 0] = [];
        assert_eq!(
            Basis::cached(&none, 6.0).unwrap().keys,
            Basis::new(&none, 6.0).unwrap().keys
        );
        let none_f: [Interval; 0] = [];
        assert_eq!(
            Basis::cached(&none_f, 6.0).unwrap().keys,
            Basis::new(&none_f, 6.0).unwrap().keys
        );
    }

    #[test]
    fn a_value_that_reaches_zero_has_no_power() {
        let ctx = Ctx::new(&Basis::new(&[iv(1.5, 1.5)], 6.0).unwrap(), 0.1).unwrap();
        let u = Gts::variable(&ctx, 1);
        let y = u.clone() - Gts::constant_in(&ctx, iv(0.05, 0.05));
        assert!(!Real::spow(&y, &Gts::constant(iv(1.5, 1.5))).is_bounded());
        assert!(!Real::abs(&y).is_bounded());
        assert!(!(Gts::from_int(1) / y).is_bounded());
        // but ±u itself does: |u|^1.5 exactly
        let m = Real::apow(&u, &Gts::constant(iv(1.5, 1.5)));
        assert_eq!(m.terms().len(), 1);
        assert_eq!(m.remainder(), ZERO);
    }

    /// A value without an expansion ([`Real::unbounded`]) stays unbounded through products —
    /// with a value of the domain, with a constant, with an exact 0, in either order — and
    /// through powers, roots and quotients; so does the power of a value reaching 0 once it is
    /// multiplied by another value (the start step's check W > 0 and the crossings' signs
    /// rely on it: an unbounded image refuses the step).
    #[test]
    fn a_value_without_an_expansion_stays_unbounded_through_products_and_powers() {
        let ctx = Ctx::new(&Basis::new(&[iv(1.5, 1.5)], 6.0).unwrap(), 0.1).unwrap();
        let u = Gts::variable(&ctx, 1);
        let none = Gts::<Interval>::unbounded();
        let q = Gts::constant(iv(1.5, 1.5));
        let c = Gts::constant(iv(2.0, 2.0));
        let zero = Gts::constant_in(&ctx, ZERO);
        for x in [&u, &c, &zero] {
            assert!(!(x.clone() * none.clone()).is_bounded(), "{x:?}·unbounded");
            assert!(!(none.clone() * x.clone()).is_bounded(), "unbounded·{x:?}");
            assert!(!(x.clone() / none.clone()).is_bounded(), "{x:?}/unbounded");
            assert!(!(none.clone() / x.clone()).is_bounded(), "unbounded/{x:?}");
        }
        assert!(!Real::spow(&none, &q).is_bounded());
        assert!(!Real::apow(&none, &q).is_bounded());
        assert!(!Real::pow(&none, &q).is_bounded());
        assert!(!Real::sqrt(&none).is_bounded());
        assert!(!Real::spow(&u, &none).is_bounded());
        // a product keeps the domain: its integral is unbounded, not refused by a panic
        assert!(!(u.clone() * none.clone()).integral().is_bounded());
        let y = u.clone() - Gts::constant_in(&ctx, iv(0.05, 0.05));
        let one_u = u.clone() + Gts::constant_in(&ctx, iv(1.0, 1.0));
        assert!(!(Real::spow(&y, &q) * one_u.clone()).is_bounded());
        assert!(!(one_u * Real::abs(&y)).is_bounded());
    }

    /// The toy basis of the inclusion tests: generators 1 and 1.5, cut-off M = 3 (the keys
    /// 1, u, u^1.5, u², u^2.5, u³ and u^(2·1.5)), on the domain [0, 1/4].
    fn toy_ctx() -> Arc<Ctx<Interval>> {
        Ctx::new(&Basis::new(&[iv(1.5, 1.5)], 3.0).unwrap(), 0.25).unwrap()
    }

    /// The key of u^(k₀ + 1.5k₁).
    fn key(k0: u8, k1: u8) -> Key {
        let mut k = [0; MAX_GENS];
        (k[0], k[1]) = (k0, k1);
        k
    }

    /// Each clause of the inclusion decides a case alone (the others hold there): the
    /// remainder; a term only in the image (its coefficient must be ⊆ [0, 0]); a term only in
    /// the candidate (0 must lie in its coefficient); a term in both; and the contexts (one
    /// basis and domain, or no context and the constant term only).
    #[test]
    fn each_clause_of_the_inclusion_decides_a_case_alone() {
        let ctx = toy_ctx();
        let g = |terms: &[(Key, Interval)], rem: Interval| Gts::from_parts(&ctx, terms, rem);
        let one = (key(0, 0), iv(1.0, 1.0));
        let u = |c: Interval| (key(1, 0), c);
        let u15 = |c: Interval| (key(0, 1), c);
        // the remainder alone
        let (wide, thin) = (iv(-0.125, 0.125), iv(-0.0625, 0.0625));
        let a = g(&[one, u(iv(1.0, 1.0))], wide);
        let b = g(&[one, u(iv(1.0, 1.0))], thin);
        assert!(!a.subset_of(&b) && b.subset_of(&a));
        // a term only in self: inside only as the coefficient 0
        let b = g(&[one], ZERO);
        assert!(!g(&[one, u15(iv(0.5, 0.5))], ZERO).subset_of(&b));
        assert!(!g(&[one, u15(iv(0.0, 0.5))], ZERO).subset_of(&b));
        assert!(g(&[one, u15(ZERO)], ZERO).subset_of(&b));
        // a term only in other: inside only where its coefficient holds 0
        let a = g(&[one], ZERO);
        assert!(!a.subset_of(&g(&[one, u15(iv(0.5, 1.0))], ZERO)));
        assert!(!a.subset_of(&g(&[one, u15(iv(-1.0, -0.5))], ZERO)));
        assert!(a.subset_of(&g(&[one, u15(iv(-0.5, 1.0))], ZERO)));
        assert!(a.subset_of(&g(&[one, u15(iv(0.0, 1.0))], ZERO)));
        // (also when the other key sorts before or after all of self's)
        assert!(!g(&[u(iv(1.0, 1.0))], ZERO).subset_of(&g(&[one, u(iv(1.0, 1.0))], ZERO)));
        assert!(!a.subset_of(&g(&[one, (key(3, 0), iv(0.5, 1.0))], ZERO)));
        // a term in both
        let a = g(&[one, u(iv(0.5, 1.0))], ZERO);
        assert!(!a.subset_of(&g(&[one, u(iv(0.5, 0.75))], ZERO)));
        assert!(a.subset_of(&g(&[one, u(iv(0.25, 1.0))], ZERO)));
        // the contexts: the same basis and domain with another cut-off is the same set
        let a = g(&[one, u15(iv(0.5, 0.5))], thin);
        let b = Gts::from_parts(&ctx.truncated(2.0), &a.terms(), thin);
        assert!(a.subset_of(&b) && b.subset_of(&a));
        // the same generators in a basis made anew: the same exponents under the same keys
        let again = Ctx::new(&Basis::new(&[iv(1.5, 1.5)], 3.0).unwrap(), 0.25).unwrap();
        assert!(a.subset_of(&Gts::from_parts(&again, &a.terms(), thin)));
        // another generator: key (0, 1) is u^1.25 there, not u^1.5
        let other = Ctx::new(&Basis::new(&[iv(1.25, 1.25)], 3.0).unwrap(), 0.25).unwrap();
        let b = Gts::from_parts(&other, &a.terms(), thin);
        assert!(!a.subset_of(&b) && !b.subset_of(&a));
        // another domain
        let shorter = Ctx::new(&ctx.basis, 0.125).unwrap();
        let b = Gts::from_parts(&shorter, &a.terms(), thin);
        assert!(!a.subset_of(&b) && !b.subset_of(&a));
        // a constant without a context: its one term against the constant term
        let c = Gts::constant(iv(1.0, 1.0));
        assert!(c.subset_of(&g(&[one, u15(iv(-1.0, 1.0))], ZERO)));
        assert!(!c.subset_of(&g(&[one, u15(iv(0.5, 1.0))], ZERO)));
        assert!(g(&[one], ZERO).subset_of(&Gts::constant(iv(0.5, 1.0))));
        assert!(!g(&[one, u15(iv(0.5, 0.5))], ZERO).subset_of(&Gts::constant(iv(0.5, 1.0))));
        assert!(c.subset_of(&Gts::constant(iv(0.5, 1.0))));
        assert!(!Gts::<Interval>::unbounded().subset_of(&c));
    }

    /// The clauses of the inclusion ([`Gts::subset_of`]), for [`rule`] to leave one out.
    #[derive(Clone, Copy, Debug, PartialEq)]
    enum Clause {
        Remainder,
        OnlyInSelf,
        OnlyInOther,
        InBoth,
        Context,
    }

    /// The inclusion as its documentation states it, read from the values' exponent vectors,
    /// with the clause `without` left out (every key considered, 0 where a value lacks it).
    fn rule(a: &Gts<Interval>, b: &Gts<Interval>, without: Option<Clause>) -> bool {
        let on = |c: Clause| without != Some(c);
        let (ca, cb) = (a.ctx.as_ref().unwrap(), b.ctx.as_ref().unwrap());
        let same = ca.delta == cb.delta
            && ca.basis.gens.len() == cb.basis.gens.len()
            && ca
                .basis
                .gens
                .iter()
                .zip(&cb.basis.gens)
                .all(|(x, y)| x.same(y));
        if on(Clause::Context) && !same {
            return false;
        }
        if on(Clause::Remainder) && !a.rem.subset(b.rem) {
            return false;
        }
        let (ta, tb) = (a.terms(), b.terms());
        let mut keys: Vec<Key> = ta.iter().chain(&tb).map(|t| t.0).collect();
        keys.sort();
        keys.dedup();
        keys.iter().all(|k| {
            let find = |t: &[(Key, Interval)]| t.iter().find(|e| e.0 == *k).map(|e| e.1);
            match (find(&ta), find(&tb)) {
                (Some(x), Some(y)) => !on(Clause::InBoth) || x.subset(y),
                (Some(x), None) => !on(Clause::OnlyInSelf) || x.subset(ZERO),
                (None, Some(y)) => !on(Clause::OnlyInOther) || ZERO.subset(y),
                (None, None) => unreachable!(),
            }
        })
    }

    /// The inclusion against the sets themselves, by brute force: random pairs of toy values
    /// (dyadic coefficients, the second often a copy of the first with one part changed —
    /// widened, narrowed, a term dropped or added with or without 0 in it — or the same
    /// terms in another basis). Whenever `a.subset_of(b)`, every sampled function of a's set —
    /// its coefficients at their ends (every corner) and midpoints, its remainder a constant at
    /// either end — at u = s² for s ∈ {0, 1/16, 1/8, 1/4, 3/8, 1/2} (u = 0 and δ = 1/4
    /// included; u^α = s^(2k₀ + 3k₁) exactly) lies in b's enclosure at u, compared as
    /// rationals. The decision also equals [`rule`]; and for each clause, the rule without it
    /// accepts pairs where the brute force finds a function outside (so an inclusion test
    /// lacking that clause fails here).
    #[test]
    fn an_inclusion_holds_for_every_sampled_function_of_the_set() {
        use rug::{Rational, ops::Pow};
        /// Draws from xorshift: k/8 ends, small widths.
        struct Draw<F>(F);
        impl<F: FnMut() -> u64> Draw<F> {
            fn pick(&mut self, n: u64) -> u64 {
                (self.0)() % n
            }
            /// j/d for j in 0..n
            fn frac(&mut self, n: u64, d: f64) -> f64 {
                self.pick(n) as f64 / d
            }
            /// A thin coefficient k/8 (|k| ≤ 16), 0, or [k/8, k/8 + w] (w of 1/8 to 1/2).
            fn coef(&mut self) -> Interval {
                let a = (self.pick(33) as f64 - 16.0) / 8.0;
                match self.pick(4) {
                    0 => iv(a, a),
                    1 => ZERO,
                    _ => iv(a, a + (1.0 + self.frac(4, 1.0)) / 8.0),
                }
            }
        }
        let ctx = toy_ctx();
        let other = Ctx::new(&Basis::new(&[iv(1.25, 1.25)], 3.0).unwrap(), 0.25).unwrap();
        let keys: Vec<Key> = ctx.basis.keys.clone();
        assert_eq!(
            keys, other.basis.keys,
            "both bases have the same key vectors"
        );
        let mut d = Draw(crate::arith::interval::xorshift(0x2545_f491_4f6c_dd1d_u64));
        let q = |x: f64| Rational::from_f64(x).unwrap();
        let widen = |c: Interval, l: f64, h: f64| iv(c.inf() - l, c.sup() + h);
        let (mut accepted, mut caught) = (0, [0usize; 5]);
        let clauses = [
            Clause::Remainder,
            Clause::OnlyInSelf,
            Clause::OnlyInOther,
            Clause::InBoth,
            Clause::Context,
        ];
        for round in 0..3000 {
            // a: the constant and about half the other keys
            let mut ta: Vec<(Key, Interval)> = Vec::new();
            for (i, k) in keys.iter().enumerate() {
                if i == 0 || d.pick(2) == 0 {
                    ta.push((*k, d.coef()));
                }
            }
            let ra = match d.pick(3) {
                0 => ZERO,
                _ => iv(-d.frac(4, 16.0), d.frac(4, 16.0)),
            };
            // b: a's terms, each kept, widened, narrowed, dropped or replaced, and some added
            let mut tb: Vec<(Key, Interval)> = Vec::new();
            for k in &keys {
                let c = ta.iter().find(|e| e.0 == *k).map(|e| e.1);
                let nb = match (c, d.pick(8)) {
                    (Some(c), 0..=3) => Some(c),
                    (Some(c), 4) => Some(widen(c, d.frac(3, 8.0), d.frac(3, 8.0))),
                    (Some(c), 5) if c.wid() > 0.0 => Some(iv(c.inf(), c.mid())),
                    (Some(_), 6) => None,
                    (Some(_), _) => Some(d.coef()),
                    (None, 0..=4) => None,
                    // with 0 in it, or of one sign
                    (None, 5) => Some(iv(-d.frac(3, 8.0), d.frac(3, 8.0))),
                    (None, _) => {
                        let (lo, w) = ((1.0 + d.frac(8, 1.0)) / 8.0, d.frac(3, 8.0));
                        Some(if d.pick(2) == 0 {
                            iv(lo, lo + w)
                        } else {
                            iv(-lo - w, -lo)
                        })
                    }
                };
                if let Some(c) = nb {
                    tb.push((*k, c));
                }
            }
            let rb = match d.pick(4) {
                0 | 1 => ra,
                2 => widen(ra, d.frac(3, 16.0), d.frac(3, 16.0)),
                _ => iv(ra.inf() / 2.0, ra.sup()),
            };
            let bctx = match round % 8 {
                7 => &other,
                _ => &ctx,
            };
            let a = Gts::from_parts(&ctx, &ta, ra);
            let b = Gts::from_parts(bctx, &tb, rb);
            let decided = a.subset_of(&b);
            assert_eq!(decided, rule(&a, &b, None), "round {round}: {a:?} ⊆ {b:?}");
            // the brute force: is some sampled function of a's set outside b's enclosure?
            let mut outside = None;
            'u: for s in [0.0, 1.0 / 16.0, 0.125, 0.25, 0.375, 0.5] {
                let u = s * s;
                let e = b.eval(&iv(u, u));
                let (lo, hi) = (q(e.inf()), q(e.sup()));
                // (c·u^α at the coefficient's ends and midpoint) per term of a
                let parts: Vec<[Rational; 3]> = a
                    .terms()
                    .iter()
                    .map(|(k, c)| {
                        let p = q(s).pow(2 * k[0] as u32 + 3 * k[1] as u32);
                        [q(c.inf()) * &p, q(c.mid()) * &p, q(c.sup()) * &p]
                    })
                    .collect();
                let n = parts.len();
                for corner in 0..(1usize << n) + 1 {
                    let mut v = Rational::new();
                    for (t, p) in parts.iter().enumerate() {
                        v += if corner == 1 << n {
                            &p[1]
                        } else if corner >> t & 1 == 1 {
                            &p[2]
                        } else {
                            &p[0]
                        };
                    }
                    for r in [ra.inf(), ra.sup()] {
                        let y = &v + q(r);
                        if y < lo || y > hi {
                            outside = Some((u, y));
                            break 'u;
                        }
                    }
                }
            }
            if decided {
                accepted += 1;
                assert!(
                    outside.is_none(),
                    "round {round}: a ⊆ b decided, but a function of a is {outside:?} at u, \
                     outside b: {a:?} {b:?}"
                );
            }
            if outside.is_some() {
                for (i, c) in clauses.iter().enumerate() {
                    if rule(&a, &b, Some(*c)) {
                        caught[i] += 1;
                    }
                }
            }
        }
        eprintln!("{accepted} of 3000 pairs included; violations per clause left out {caught:?}");
        assert!(accepted > 150, "{accepted} pairs included");
        assert!(caught.iter().all(|&n| n > 0), "{caught:?}");
    }
}

#[cfg(test)]
/// An adversarial review's probe (2026-11-25): the prefix route on bases whose exponents tie or
/// overlap, for f64 and MPFR intervals.
mod prefix_order {
    use super::*;
    use crate::arith::mpfr::Mpi;
    use rug::Rational;

    /// prefix route vs table route on one basis: same keys, coefficients hold the exact sums,
    /// both beyond-bounds ≥ the exact Σ over the pairs the table calls beyond; the rounds
    /// alternate between the basis's cut-off alone and lower ones ([`Gts::product`]'s `cut`)
    pub(super) fn compare<I: Enclosure>(
        gens: &[I],
        m: f64,
        delta: f64,
        name: &str,
        rounds: usize,
    ) -> bool {
        let q = |x: f64| Rational::from_f64(x).unwrap();
        let basis = Basis::new(gens, m).unwrap();
        let n = basis.keys.len();
        let Some(pf) = basis.prefix.as_ref() else {
            eprintln!("{name}: n {n}: no prefix (table route)");
            return false;
        };
        // the prefix property against the table, independently
        for i in 0..n {
            for j in 0..n {
                let within = basis.sum[i * n + j] != BEYOND;
                assert_eq!(within, pf.pos[j] < pf.cut[i], "{name}: pair {i} {j}");
            }
        }
        let ctx = Ctx::new(&basis, delta).unwrap();
        let mut next = crate::arith::interval::xorshift(0x9d2c_5680_1b87_3e4f_u64);
        let mut random = |terms: usize| -> Gts<I> {
            let mut keys: Vec<u16> = (0..terms)
                .map(|_| (next() % n as u64) as u16)
                .chain([0])
                .collect();
            keys.sort_unstable();
            keys.dedup();
            let terms = keys
                .into_iter()
                .map(|k| {
                    let r = next();
                    let c = match r % 7 {
                        0 => 0.0,
                        1 => 1e300,
                        2 => -1e-300,
                        _ => ((next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 4.0,
                    };
                    (k, I::from_bounds(c, c).unwrap())
                })
                .collect();
            Gts {
                ctx: Some(ctx.clone()),
                terms,
                rem: I::zero(),
                var: 0,
                fac: None,
            }
        };
        let mag = |g: &Gts<I>| -> Vec<I> {
            g.terms
                .iter()
                .map(|(i, c)| point_mag(&c.mul_constant(&ctx.ranges[*i as usize])))
                .collect()
        };
        for round in 0..rounds {
            let (a, b) = (
                random(1 + round % n.min(40)),
                random(1 + (round * 7) % n.min(40)),
            );
            let (ma, mb) = (mag(&a), mag(&b));
            // the basis's cut-off alone, and lower cut-offs (down to none kept at all)
            let cut = [f64::INFINITY, m - 1.0, m / 2.0, 1.0, -1.0][round % 5];
            let (tp, bp) = a.products_by_prefix(&b, &ctx, pf, &ma, &mb, cut);
            let (tt, bt) = a.products_by_table(&b, &ctx, &ma, &mb, cut);
            let keys = |t: &[(u16, I)]| t.iter().map(|e| e.0).collect::<Vec<_>>();
            assert_eq!(keys(&tp), keys(&tt), "{name} round {round}");
            let mut exact = vec![Rational::new(); n];
            let mut beyond = Rational::new();
            let mut beyond_inf = false;
            for ((ia, ca), xa) in a.terms.iter().zip(&ma) {
                for ((ib, cb), xb) in b.terms.iter().zip(&mb) {
                    // a pair above the cut is bounded with those beyond M (the routing as the
                    // products do it: by the exponents' lower ends)
                    let above = basis.exps[*ib as usize].lo() > cut - basis.exps[*ia as usize].lo();
                    match basis.sum[*ia as usize * n + *ib as usize] {
                        _ if above => {
                            if xa.hi().is_finite() && xb.hi().is_finite() {
                                beyond += q(xa.hi()) * q(xb.hi())
                            } else {
                                beyond_inf = true
                            }
                        }
                        BEYOND => {
                            if xa.hi().is_finite() && xb.hi().is_finite() {
                                beyond += q(xa.hi()) * q(xb.hi())
                            } else {
                                beyond_inf = true
                            }
                        }
                        k => exact[k as usize] += q(ca.lo()) * q(cb.lo()),
                    }
                }
            }
            for (k, c) in tp.iter().chain(&tt) {
                let e = &exact[*k as usize];
                assert!(
                    (c.lo() == f64::NEG_INFINITY || q(c.lo()) <= *e)
                        && (c.hi() == f64::INFINITY || *e <= q(c.hi())),
                    "{name} round {round}: key {k}"
                );
            }
            for bound in [bp, bt] {
                assert!(
                    bound == f64::INFINITY || (!beyond_inf && q(bound) >= beyond),
                    "{name} round {round}: beyond {bound:e} < exact"
                );
                // and not far above it (where finite: a sum reaching ±∞ bounds nothing tighter)
                assert!(
                    !bound.is_finite() || q(bound) <= beyond.clone() * q(1.0 + 1e-12) + q(1e-300),
                    "{name} round {round}: beyond {bound:e} far above the exact sum"
                );
            }
        }
        eprintln!("{name}: n {n}: prefix ok, {rounds} rounds");
        true
    }

    fn bases<I: Enclosure>(tag: &str) {
        let d = |s: &str| I::parse_decimal(s).unwrap();
        let e = |x: f64| I::from_bounds(x, x).unwrap();
        let w = |a: f64, b: f64| I::from_bounds(a, b).unwrap();
        let cases: Vec<(String, Vec<I>, f64)> = vec![
            ("1.5,3.0 M6".into(), vec![e(1.5), e(3.0)], 6.0),
            ("1.5,3.0 M4.5".into(), vec![e(1.5), e(3.0)], 4.5),
            ("2.0 M5".into(), vec![e(2.0)], 5.0),
            ("0.5 M4".into(), vec![e(0.5)], 4.0),
            (
                "0.1,0.2,0.3 M1.2".into(),
                vec![d("0.1"), d("0.2"), d("0.3")],
                1.2,
            ),
            (
                "1.3,1.3' overlap M5".into(),
                vec![d("1.3"), w(1.3 - 1e-12, 1.3 + 1e-12)],
                5.0,
            ),
            ("wide [1.2,1.4] M5".into(), vec![w(1.2, 1.4)], 5.0),
            (
                "wide [1.2,1.4],1.3 M5".into(),
                vec![w(1.2, 1.4), d("1.3")],
                5.0,
            ),
            (
                "1.31,1.27,2.02 M6".into(),
                vec![d("1.31"), d("1.27"), d("2.02")],
                6.0,
            ),
            (
                "1/3,2/3 M3".into(),
                vec![d("0.3333333333333333333333"), d("0.6666666666666666666667")],
                3.0,
            ),
            (
                "0.7,1.4,2.1 M4.2".into(),
                vec![d("0.7"), d("1.4"), d("2.1")],
                4.2,
            ),
            ("2.5 M5 tie at M".into(), vec![e(2.5)], 5.0),
            ("1.1 M3.3".into(), vec![d("1.1")], 3.3),
        ];
        let mut with = 0;
        for (name, g, m) in &cases {
            for delta in [0.6, 1e-3] {
                if compare::<I>(g, *m, delta, &format!("{tag} {name} δ{delta}"), 200) {
                    with += 1;
                }
            }
        }
        eprintln!(
            "{tag}: {with} of {} cases took the prefix route",
            2 * cases.len()
        );
    }

    #[test]
    fn prefix_route_on_tied_and_overlapping_exponents() {
        bases::<Interval>("f64");
        bases::<Mpi<128>>("mpfr");
    }
}
