//! Core of `proof-lyapunov`: branch and bound over boxes of parameters (B, g = Γ/B, κ, σ, n, p)
//! × every sign orthant of the state space, on the implementation's `lyapunov_rate` evaluated
//! with the sign-orthant abstraction of `sym.rs` (interval coefficients).
//!
//! The reparametrisation Γ = g·B makes the constraint Γ ∈ (−B, B) the box g ∈ (−1, 1). A box is
//! proved when on every orthant every term's coefficient is ≤ 0 (𝒱̇ ≤ 0 on the whole orthant,
//! states unbounded); a box whose verdict is undecided (B ± Γ of unknown sign: the intervals of
//! B and Γ = g·B are not correlated) is split (B geometrically, else g). A box with a provably
//! positive coefficient is a counterexample region.
#![allow(dead_code)]

use crate::sym::{PSym, Poly, Verdict, orthants, verdict};
use bwcl::models::{BoucWenModel, Maxwell, NdParams, Shc};
use inari::Interval;

/// A parameter box: [lo, hi] of B, g, κ, σ, n, p.
#[derive(Clone, Debug)]
pub struct PBox {
    pub lo: [f64; 6],
    pub hi: [f64; 6],
}

pub const NAMES: [&str; 6] = ["B", "g=Γ/B", "κ", "σ", "n", "p"];

fn iv(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).expect("a valid interval")
}

impl PBox {
    pub fn new(r: [(f64, f64); 6]) -> Self {
        Self {
            lo: r.map(|x| x.0),
            hi: r.map(|x| x.1),
        }
    }
    /// The model's parameters: intervals, with the exponents' forms (n = [0, 0, 1],
    /// p = [0, 1, 0]) so that p + 1, p + n − 1, … are recognised exactly.
    pub fn params(&self) -> NdParams<PSym> {
        let i = |k: usize| iv(self.lo[k], self.hi[k]);
        let b = i(0);
        NdParams {
            b: PSym::interval(b),
            gamma: PSym::interval(i(1) * b),
            kappa: PSym::interval(i(2)),
            sigma: PSym::interval(i(3)),
            n: PSym::exponent(i(4), [0.0, 0.0, 1.0]),
            p: PSym::exponent(i(5), [0.0, 1.0, 0.0]),
        }
    }
    /// Bisects B geometrically while B_hi/B_lo > 1.001, else g.
    fn split(&self) -> (PBox, PBox) {
        let (mut a, mut b) = (self.clone(), self.clone());
        if self.hi[0] / self.lo[0] > 1.001 && self.lo[0] > 0.0 {
            let m = (self.lo[0] * self.hi[0]).sqrt();
            a.hi[0] = m;
            b.lo[0] = m;
        } else {
            let m = 0.5 * (self.lo[1] + self.hi[1]);
            a.hi[1] = m;
            b.lo[1] = m;
        }
        (a, b)
    }
}

/// Which model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Which {
    Shc,
    Maxwell,
}

/// The verdicts of the implementation's 𝒱̇ on every orthant for one parameter box.
pub fn orthant_verdicts(which: Which, b: &PBox) -> Vec<(Vec<i8>, Verdict)> {
    let p = b.params();
    match which {
        Which::Shc => {
            let m = Shc::new(p);
            orthants(3)
                .into_iter()
                .map(|s| {
                    let x: [Poly; 3] = std::array::from_fn(|i| Poly::atom(3, i, s[i]));
                    let v = verdict(&m.lyapunov_rate(&x));
                    (s, v)
                })
                .collect()
        }
        Which::Maxwell => {
            let m = Maxwell::new(p);
            orthants(4)
                .into_iter()
                .map(|s| {
                    let x: [Poly; 4] = std::array::from_fn(|i| Poly::atom(4, i, s[i]));
                    let v = verdict(&m.lyapunov_rate(&x));
                    (s, v)
                })
                .collect()
        }
    }
}

/// Outcome of the branch and bound.
#[derive(Debug, Default)]
pub struct Outcome {
    /// Boxes proved (𝒱̇ ≤ 0 on every orthant).
    pub proved: usize,
    /// Boxes where a positive term was proved: (box, orthant, message).
    pub counterexamples: Vec<(PBox, Vec<i8>, String)>,
    /// Boxes left undecided at the depth limit.
    pub undecided: Vec<PBox>,
    /// Deepest split.
    pub depth: usize,
    /// Orthants (sign patterns) with each verdict class, over all proved boxes:
    /// identically 0 / < 0 / ≤ 0 only.
    pub zero: std::collections::BTreeSet<Vec<i8>>,
    pub negative: std::collections::BTreeSet<Vec<i8>>,
    pub nonpositive: std::collections::BTreeSet<Vec<i8>>,
}

/// Branch and bound from `root`, at most `max_boxes` evaluations and depth `max_depth`.
pub fn prove(which: Which, root: PBox, max_depth: usize, max_boxes: usize) -> Outcome {
    let mut out = Outcome::default();
    let mut stack = vec![(root, 0usize)];
    let mut evaluated = 0;
    while let Some((b, d)) = stack.pop() {
        evaluated += 1;
        out.depth = out.depth.max(d);
        let vs = orthant_verdicts(which, &b);
        if let Some((s, Verdict::Positive(w))) =
            vs.iter().find(|(_, v)| matches!(v, Verdict::Positive(_)))
        {
            out.counterexamples.push((b.clone(), s.clone(), w.clone()));
            continue;
        }
        if vs
            .iter()
            .all(|(_, v)| matches!(v, Verdict::Zero | Verdict::Negative | Verdict::NonPositive))
        {
            out.proved += 1;
            for (s, v) in vs {
                match v {
                    Verdict::Zero => out.zero.insert(s),
                    Verdict::Negative => out.negative.insert(s),
                    _ => out.nonpositive.insert(s),
                };
            }
            continue;
        }
        if d >= max_depth || evaluated >= max_boxes {
            out.undecided.push(b);
            continue;
        }
        let (l, r) = b.split();
        stack.push((l, d + 1));
        stack.push((r, d + 1));
    }
    // a sign pattern counts as "< 0" only if it is < 0 in every box
    let neg: Vec<_> = out.negative.iter().cloned().collect();
    for s in neg {
        if out.nonpositive.contains(&s) || out.zero.contains(&s) {
            out.negative.remove(&s);
        }
    }
    out
}

/// The zero set predicted by thm:*_inv_dV_1 on sign patterns: SHC (X, Z, V): U1 = {X = Z = 0},
/// U2 = {V = 0}; Maxwell (R, Y, Z, W): U1 = {Y = Z = 0}; U2 = 𝓔 lies in the orthants W = 0,
/// sgn Y = −sgn Z ≠ 0 (there 𝒱̇ = −σh², = 0 exactly where h = 0, i.e. on 𝓔: proof-equilibria).
pub fn expected(which: Which, s: &[i8]) -> &'static str {
    match which {
        Which::Shc => {
            if s[2] == 0 || (s[0] == 0 && s[1] == 0) {
                "zero"
            } else {
                "negative"
            }
        }
        Which::Maxwell => {
            if s[1] == 0 && s[2] == 0 {
                "zero"
            } else if s[3] == 0 && s[1] == -s[2] {
                "nonpositive"
            } else {
                "negative"
            }
        }
    }
}

/// Checks the classification of every orthant against [`expected`]; returns the mismatches.
pub fn classification_mismatches(which: Which, o: &Outcome) -> Vec<String> {
    let mut bad = Vec::new();
    for s in orthants(if which == Which::Shc { 3 } else { 4 }) {
        let got = if o.zero.contains(&s) && !o.negative.contains(&s) && !o.nonpositive.contains(&s)
        {
            "zero"
        } else if o.negative.contains(&s) {
            "negative"
        } else if o.nonpositive.contains(&s) {
            "nonpositive"
        } else {
            "missing"
        };
        let want = expected(which, &s);
        if got != want {
            bad.push(format!("orthant {s:?}: {got}, expected {want}"));
        }
    }
    bad
}

/// A concrete counterexample box for |Γ| > B: the implementation's `lyapunov_rate` in plain
/// interval arithmetic at B = 1, Γ = ±1.5 (struct literal, outside 𝓟), X = 0, Z = 1/2,
/// V = ∓1 (ZV of the sign where B ± Γ < 0) has a lower bound > 0.
pub fn gamma_counterexample() -> Vec<(String, Interval)> {
    let i = |x: f64| iv(x, x);
    let mut out = Vec::new();
    for (g, v) in [(1.5, -1.0), (-1.5, 1.0)] {
        let p = NdParams {
            b: i(1.0),
            gamma: i(g),
            kappa: i(0.5),
            sigma: i(0.1),
            n: iv(1.0, 1.0),
            p: iv(1.5, 1.5),
        };
        let r = Shc::new(p.clone()).lyapunov_rate(&[
            i(0.0),
            iv(0.49, 0.51),
            iv((v * 1.01_f64).min(v * 0.99), (v * 1.01_f64).max(v * 0.99)),
        ]);
        out.push((
            format!(
                "SHC B=1, Γ={g}, κ=0.5, σ=0.1, n=1, p=1.5 at X=0, Z∈[0.49,0.51], V∈±[0.99,1.01]"
            ),
            r,
        ));
        let r = Maxwell::new(NdParams {
            p: iv(2.0, 2.0),
            ..p
        })
        .lyapunov_rate(&[
            i(0.0),
            i(0.0),
            iv(0.49, 0.51),
            iv((v * 1.01_f64).min(v * 0.99), (v * 1.01_f64).max(v * 0.99)),
        ]);
        out.push((
            format!(
                "Maxwell B=1, Γ={g}, κ=0.5, σ=0.1, n=1, p=2 at R=Y=0, Z∈[0.49,0.51], W∈±[0.99,1.01]"
            ),
            r,
        ));
    }
    out
}
