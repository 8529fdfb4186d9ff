//! Chains of linear operations fused into one sum of products per result.
//!
//! A model's field is mostly linear combinations of a few non-linear terms, e.g. eq:BWSHCCM_nd
//!
//! ```text
//! Ż = V − B|V||Z|^(n−1)Z − Γ V|Z|^n,      V̇ = −κ|X|^(p−1)X − (1 − κ)|Z|^(p−1)Z − σ|X|^p V,
//! ```
//!
//! which the recorder writes as chains of products by a constant, sums, differences and
//! negations: 11 operations per Taylor order for these two lines, each rounded outward on its
//! own. A linear operation commutes with taking Taylor coefficients (its coefficient k is the
//! same combination of its operands' coefficients k; a constant shift only moves coefficient
//! 0), so a chain is one form
//!
//! ```text
//! y = c₀ + Σⱼ cⱼ·x_{nⱼ}      (y_k = Σⱼ cⱼ·(x_{nⱼ})_k for k ≥ 1, plus c₀ at k = 0)
//! ```
//!
//! over the chain's non-linear operands ("leaves"), evaluated as one sum of products by the
//! type's [`Dot`](crate::arith::Dot) accumulator: one bound of all rounding errors instead of
//! one outward rounding per operation. The coefficients cⱼ are products and sums of the tape's
//! constants, enclosed in the recording type (each tape constant encloses one real number, so
//! e.g. x − c·x = (1 − c)·x holds for that number and (1 − [c])·x encloses it).
//!
//! Which nodes fuse: a linear node (not constant in time) whose every user is itself a linear
//! node and which is no output is *absorbed*: its form is written into each user's and it is
//! no longer computed. Every other linear node whose form absorbed one becomes an
//! [`Op::Lin`](super::tape::Op::Lin).

use super::tape::{Op, operands};
use crate::arith::Real;

/// c₀ + Σⱼ cⱼ·x_{nⱼ}: the constant `shift` (index of c₀ among the tape's constants; it enters
/// coefficient 0 only) and the terms (index of cⱼ among the constants, node nⱼ).
#[derive(Clone, Debug, PartialEq)]
pub struct Lin {
    pub shift: Option<usize>,
    pub terms: Vec<(usize, usize)>,
}

/// A linear form while it is built: the shift and one coefficient per leaf node.
struct Form<R> {
    shift: Option<R>,
    terms: Vec<(usize, R)>,
}

impl<R: Real> Form<R> {
    fn leaf(n: usize) -> Self {
        Self {
            shift: None,
            terms: vec![(n, R::one())],
        }
    }

    /// self + s·other (s = ±1, exact).
    fn add(mut self, other: Self, negate: bool) -> Self {
        let sgn = |c: R| if negate { -c } else { c };
        self.shift = match (self.shift, other.shift) {
            (a, None) => a,
            (None, Some(b)) => Some(sgn(b)),
            (Some(a), Some(b)) => Some(a + sgn(b)),
        };
        for (n, c) in other.terms {
            match self.terms.iter_mut().find(|(m, _)| *m == n) {
                Some((_, d)) => *d = d.clone() + sgn(c),
                None => self.terms.push((n, sgn(c))),
            }
        }
        self
    }

    /// self·c.
    fn scale(self, c: &R) -> Self {
        Self {
            shift: self.shift.map(|s| s * c.clone()),
            terms: self
                .terms
                .into_iter()
                .map(|(n, d)| (n, d * c.clone()))
                .collect(),
        }
    }
}

/// The tape after fusion: its operations, the forms of its [`Op::Lin`] nodes, and where each
/// old node went (`None`: absorbed).
pub(super) struct Fused {
    pub ops: Vec<Op>,
    pub lins: Vec<Lin>,
    pub map: Vec<Option<usize>>,
}

/// Fuses the linear chains of `ops` (see the module doc); the forms' coefficients are
/// appended to `consts`. `tconst` marks the nodes constant in time (never fused: they are
/// expanded at order 0 only), `outputs` the nodes the tape returns (never absorbed).
pub(super) fn fuse<R: Real>(
    ops: &[Op],
    consts: &mut Vec<R>,
    tconst: &[bool],
    outputs: &[usize],
) -> Fused {
    let n = ops.len();
    let linear = |i: usize| {
        !tconst[i]
            && matches!(
                ops[i],
                Op::Add(..) | Op::Sub(..) | Op::Neg(_) | Op::Scale(..) | Op::Shift(..)
            )
    };
    let mut users: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (j, op) in ops.iter().enumerate() {
        for a in operands(op) {
            users[a].push(j);
        }
    }
    let absorbed: Vec<bool> = (0..n)
        .map(|i| {
            linear(i)
                && !outputs.contains(&i)
                && !users[i].is_empty()
                && users[i].iter().all(|&u| linear(u))
        })
        .collect();
    // the form of node i's operation, expanding absorbed operands
    fn form<R: Real>(i: usize, ops: &[Op], consts: &[R], absorbed: &[bool]) -> Form<R> {
        let operand = |a: usize| {
            if absorbed[a] {
                form(a, ops, consts, absorbed)
            } else {
                Form::leaf(a)
            }
        };
        match ops[i] {
            Op::Add(a, b) => operand(a).add(operand(b), false),
            Op::Sub(a, b) => operand(a).add(operand(b), true),
            Op::Neg(a) => Form {
                shift: None,
                terms: Vec::new(),
            }
            .add(operand(a), true),
            Op::Scale(a, c) => operand(a).scale(&consts[c]),
            Op::Shift(a, c) => operand(a).add(
                Form {
                    shift: Some(consts[c].clone()),
                    terms: Vec::new(),
                },
                false,
            ),
            _ => unreachable!("a linear operation"),
        }
    }
    let mut out: Vec<Op> = Vec::with_capacity(n);
    let mut lins = Vec::new();
    let mut map = vec![None; n];
    for i in 0..n {
        if absorbed[i] {
            continue;
        }
        let op = if linear(i) && operands(&ops[i]).any(|a| absorbed[a]) {
            let f: Form<R> = form(i, ops, consts, &absorbed);
            let mut push = |c: R| {
                consts.push(c);
                consts.len() - 1
            };
            let shift = f.shift.map(&mut push);
            let terms = f.terms.into_iter().map(|(m, c)| (push(c), m)).collect();
            lins.push(Lin { shift, terms });
            Op::Lin(lins.len() - 1)
        } else {
            ops[i]
        };
        map[i] = Some(out.len());
        out.push(op);
    }
    // operands to the new indices (absorbed nodes are used only by fused forms, whose leaves
    // are never absorbed)
    let m = |a: usize| map[a].expect("an operand that is computed");
    for op in &mut out {
        *op = super::tape::remap(*op, m);
    }
    for lin in &mut lins {
        for t in &mut lin.terms {
            t.1 = m(t.1);
        }
    }
    Fused {
        ops: out,
        lins,
        map,
    }
}

#[cfg(test)]
mod tests {
    use super::super::tape::{Op, Rounding, Tape, Workspace};
    use crate::arith::Scalar;
    use inari::Interval;
    use rug::Rational;

    fn c(x: f64) -> Interval {
        Interval::try_from((x, x)).unwrap()
    }

    fn q(x: f64) -> Rational {
        Rational::from_f64(x).unwrap()
    }

    /// A field of linear chains around the products p = x₀x₁ and s = x₁² (every constant a
    /// double, so that the exact coefficients are rationals):
    ///
    /// a = 2x₀ − 3(x₁ + x₀) (also an output), f₀ = (a + 5)/2 − p,
    /// b = p/4 − p (used by a product), m = b·x₀, f₁ = −(b + s) + m/8.
    fn chains(rounding: Rounding) -> Tape<Interval, 2> {
        Tape::<Interval, 2>::record(|v| {
            let (x0, x1) = (v[0].clone(), v[1].clone());
            let p = x0.clone() * x1.clone();
            let s = x1.clone() * x1.clone();
            let a = x0.scale(&c(2.0)) - (x1 + x0.clone()).scale(&c(3.0));
            let f0 = a.shift(&c(5.0)).scale(&c(0.5)) - p.clone();
            let b = p.scale(&c(0.25)) - p;
            let m = b.clone() * x0;
            let f1 = -(b + s) + m.scale(&c(0.125));
            vec![f0, f1, a]
        })
        .fused(rounding)
    }

    /// The exact Taylor coefficients of [`chains`] from (x₀, x₁), orders 0..=K, and a's.
    fn exact(x: [f64; 2], order: usize) -> ([Vec<Rational>; 2], Vec<Rational>) {
        let conv = |u: &[Rational], w: &[Rational], k: usize| -> Rational {
            (0..=k).map(|j| u[j].clone() * &w[k - j]).sum()
        };
        let mut x0 = vec![q(x[0])];
        let mut x1 = vec![q(x[1])];
        let (mut b, mut a): (Vec<Rational>, Vec<Rational>) = (Vec::new(), Vec::new());
        for k in 0..=order {
            let p = conv(&x0, &x1, k);
            let s = conv(&x1, &x1, k);
            b.push(-(p.clone() * q(0.75)));
            let m = conv(&b, &x0, k);
            a.push(-x0[k].clone() - x1[k].clone() * 3);
            let shift = if k == 0 { q(2.5) } else { q(0.0) };
            let f0 = a[k].clone() * q(0.5) + shift - p;
            let f1 = -b[k].clone() - s + m * q(0.125);
            x0.push(f0 / (k as u32 + 1));
            x1.push(f1 / (k as u32 + 1));
        }
        x0.truncate(order + 1);
        x1.truncate(order + 1);
        ([x0, x1], a)
    }

    fn encloses(i: &Interval, r: &Rational) -> bool {
        q(i.inf()) <= *r && *r <= q(i.sup())
    }

    #[test]
    fn chains_fuse_into_one_form_each() {
        let tape = chains(Rounding::Once);
        let lin = |op: &Op| matches!(op, Op::Lin(_));
        let linear = |op: &Op| {
            matches!(
                op,
                Op::Add(..) | Op::Sub(..) | Op::Neg(_) | Op::Scale(..) | Op::Shift(..)
            )
        };
        // a, f₀, b, f₁ are forms; the sum x₁ + x₀, the scalings, the negation are absorbed
        assert_eq!(tape.ops().iter().filter(|o| lin(o)).count(), 4, "{tape:?}");
        assert!(!tape.ops().iter().any(linear), "{tape:?}");
        // x₀, x₁, p, s, m and the four forms
        assert_eq!(tape.len(), 9, "{tape:?}");
    }

    #[test]
    fn fused_forms_enclose_the_exact_coefficients() {
        let order = 12;
        for (tape, x) in [Rounding::Each, Rounding::Once].into_iter().flat_map(|r| {
            [[0.3, -0.7], [-1.25, 0.5], [0.0, 0.0], [2.0, 1e-3]].map(|x| (chains(r), x))
        }) {
            let (want, a) = exact(x, order);
            let mut ws = Workspace::default();
            let got = tape.jet(&[c(x[0]), c(x[1])], order, &mut ws).unwrap();
            for i in 0..2 {
                for k in 0..=order {
                    let (g, w) = (&got[i][k], &want[i][k]);
                    assert!(encloses(g, w), "x {x:?}: x{i}_{k} = {g:?} misses {w}");
                    let tight = 1e-11 * (1.0 + w.to_f64().abs());
                    assert!(g.wid() <= tight, "x {x:?}: x{i}_{k} = {g:?}");
                }
            }
            // the output a (a form that is also a leaf of f₀'s) at every order, and at a point
            for (k, ak) in a.iter().enumerate() {
                let g = tape.output_coef(&ws, order, 2, k);
                assert!(encloses(&g, ak), "x {x:?}: a_{k} = {g:?} misses {ak}");
            }
            let v = tape.eval(&[c(x[0]), c(x[1])]);
            for (j, w) in [&want[0][1], &want[1][1]].into_iter().enumerate() {
                assert!(encloses(&v[j], w), "x {x:?}: f{j} = {:?} misses {w}", v[j]);
            }
            assert!(encloses(&v[2], &a[0]));
        }
    }

    #[test]
    fn an_identically_zero_form_is_exactly_zero() {
        // F = 0·x₀ + 0·x₁ (a force that vanishes identically): [0, 0], not ±2^−1020, so that
        // its sign stays decidable
        for rounding in [Rounding::Each, Rounding::Once] {
            let tape = Tape::<Interval, 2>::record(|v| {
                let z = v[0].scale(&c(0.0)) + v[1].scale(&c(0.0));
                let w = v[0].scale(&c(2.0)) + v[1].scale(&c(0.0));
                vec![v[1].clone(), -v[0].clone(), z, w]
            })
            .fused(rounding);
            let e = tape.eval(&[c(0.5), c(-2.0)]);
            assert_eq!(
                (e[2].inf(), e[2].sup()),
                (0.0, 0.0),
                "{rounding:?}: {:?}",
                e[2]
            );
            // only a factor [0, 0] makes a term exactly 0: 2·[0, 1] + 0·x₁ ⊇ [0, 2]
            let e = tape.eval(&[Interval::try_from((0.0, 1.0)).unwrap(), c(-2.0)]);
            assert!(
                e[3].inf() <= 0.0 && e[3].sup() >= 2.0,
                "{rounding:?}: {:?}",
                e[3]
            );
            let mut ws = Workspace::default();
            let j = tape.jet(&[c(0.5), c(-2.0)], 5, &mut ws).unwrap();
            assert!(j[0][1].is_singleton(), "{:?}", j[0][1]);
            for k in 0..=5 {
                let z = tape.output_coef(&ws, 5, 2, k);
                assert_eq!(
                    (z.inf(), z.sup()),
                    (0.0, 0.0),
                    "{rounding:?}, order {k}: {z:?}"
                );
            }
        }
    }

    /// Rounded in turn, a form is the chain it replaces, bit for bit: the same products and
    /// sums in the same order (here), each rounded outward.
    #[test]
    fn forms_rounded_in_turn_are_the_chains() {
        let chain = Tape::<Interval, 2>::record(|v| {
            let s = v[0].scale(&c(0.1)) + v[1].scale(&c(-3.7));
            vec![s.clone(), v[0].clone() * v[1].clone(), s]
        });
        let each = chain.fused(Rounding::Each);
        assert!(each.ops().iter().any(|o| matches!(o, Op::Lin(_))));
        let (mut w1, mut w2) = (Workspace::default(), Workspace::default());
        for x in [[0.3, -0.7], [1e-3, 2.5], [-4.0, 1.0 / 3.0]] {
            let x = [c(x[0]), Interval::try_from((x[1], x[1] + 1e-14)).unwrap()];
            let a = chain.jet(&x, 8, &mut w1).unwrap();
            let b = each.jet(&x, 8, &mut w2).unwrap();
            assert_eq!(a, b, "{x:?}");
        }
    }
}
