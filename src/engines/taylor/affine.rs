//! Wrapping-effect control: the enclosure carried between steps as an affine set.
//!
//! The set of states at a step's start is kept as
//!
//! ```text
//! X ⊆ c + Σ_j g_j·u_j      (c a point, g_j points of ℝᴺ — the columns —, u_j intervals)
//! ```
//!
//! one column per *symbol* u_j: the start box's components, then one symbol per component for
//! every step's local error. A Taylor step maps it by the mean-value form
//! Φ(x0) ∈ z + J·(x0 − c) (z the centre's Taylor polynomial plus the remainder, J an interval
//! matrix over X: [`super::step::taylor_step`]), so that with B_j = J·g_j
//!
//! ```text
//! Φ(x0) ∈ c′ + Σ_j g′_j·u_j + E,   c′ = mid z,  g′_j = mid B_j,
//!                                 E = (z − c′) + Σ_j (B_j − g′_j)·u_j
//! ```
//!
//! for the *same* values u_j that x0 had: the old symbols keep their ranges and E becomes N new
//! symbols (axis columns, u = E_i). This is affine arithmetic at the level of steps (kv's
//! `odelong_maffine` carries every rounding as a symbol the same way): a local error is never
//! re-wrapped afterwards, and a small start box is carried by the product of the steps'
//! Jacobians, which reaches the linearized flow's optimum. Lohner's QR method, which this
//! replaces, re-expressed every step's error box in a rotated frame (Q⁻¹E, then the hull
//! through Q): measured on the kv windows (benches/RESULTS.md, "The set carried as an affine
//! set"), 1.6–2× wider than this set alone from a thin start (3.2–5.5× wider than this set with
//! the end state summed as x̂ + s, [`super::step::taylor_step`]) and 1.08–1.35× the linearized
//! optimum from a box of radius 1e-8, where this set reaches it.
//!
//! At most [`SYMBOLS`]·N symbols are kept: beyond, the smallest (by Σ_i |g_j,i|·mag u_j) are
//! merged into N fresh axis symbols, u_i = Σ_j g_j,i·u_j over the merged j — the only place
//! where a part of the set is wrapped into a box, and the smallest part.
//!
//! Nothing is inverted, so no conditioning enters. The columns are points of the number type
//! `I` (at high precision an f64 column would add its rounding to every step).

use crate::arith::Enclosure;
use inari::Interval;

/// The most symbols an affine set keeps, per component of the state. Measured on the kv
/// windows and the 28 Table 1 cases (benches/RESULTS.md, issue #32).
pub const SYMBOLS: usize = 4;

/// A set c + Σ_j g_j·u_j (module doc).
#[derive(Clone, Debug)]
pub struct AffineSet<const N: usize, I = Interval> {
    /// The centre, a point.
    pub c: [I; N],
    /// The columns, points.
    pub g: Vec<[I; N]>,
    /// The symbols' ranges, one per column.
    pub u: Vec<I>,
}

fn axis<const N: usize, I: Enclosure>(i: usize) -> [I; N] {
    std::array::from_fn(|l| if l == i { I::one() } else { I::zero() })
}

fn exact_zero<I: Enclosure>(x: &I) -> bool {
    x.same(&I::zero())
}

impl<const N: usize, I: Enclosure> AffineSet<N, I> {
    /// The box X as c = mid X and one axis symbol u_i = X_i − c_i per component of nonzero
    /// width.
    pub fn from_box(x: &[I; N]) -> Self {
        let c: [I; N] = std::array::from_fn(|i| x[i].mid_point());
        let mut s = Self {
            g: Vec::with_capacity(SYMBOLS * N),
            u: Vec::with_capacity(SYMBOLS * N),
            c,
        };
        let e: [I; N] = std::array::from_fn(|i| x[i].clone() - s.c[i].clone());
        s.push_box(&e);
        s
    }

    /// Σ_j g_j·u_j, the set's offsets from c.
    pub fn offsets(&self) -> [I; N] {
        std::array::from_fn(|i| {
            I::dot(
                self.g
                    .iter()
                    .zip(&self.u)
                    .map(|(g, u)| (g[i].clone(), u.clone())),
            )
        })
    }

    /// The interval hull of the set.
    pub fn hull(&self) -> [I; N] {
        let o = self.offsets();
        std::array::from_fn(|i| self.c[i].clone() + o[i].clone())
    }

    /// The image {z′ + J′(x0 − c) : x0 in the set, z′ ∈ z, J′ ∈ J} with z = z0 + s, as an
    /// affine set (module doc; `None` when it is not finite), and its direct enclosure
    /// z0 + (s + Σ_j (J·g_j)·u_j). z0 is the large part (a Taylor step's point x̂) and s the
    /// small one (the step's displacement and remainder): the new symbols E = (z0 − c′) + s + …
    /// are summed at the scale of s, not rounded at the scale of the state.
    pub fn image(&self, jac: &[[I; N]; N], z0: &[I; N], s: &[I; N]) -> (Option<Self>, [I; N]) {
        let b: Vec<[I; N]> = self
            .g
            .iter()
            .map(|g| {
                std::array::from_fn(|i| I::dot((0..N).map(|l| (jac[i][l].clone(), g[l].clone()))))
            })
            .collect();
        let direct: [I; N] = std::array::from_fn(|i| {
            z0[i].clone()
                + (s[i].clone()
                    + I::dot(
                        b.iter()
                            .zip(&self.u)
                            .map(|(bj, u)| (bj[i].clone(), u.clone())),
                    ))
        });
        let c: [I; N] = std::array::from_fn(|i| (z0[i].clone() + s[i].mid_point()).mid_point());
        let g: Vec<[I; N]> = b
            .iter()
            .map(|bj| std::array::from_fn(|i| bj[i].mid_point()))
            .collect();
        let e: [I; N] = std::array::from_fn(|i| {
            (z0[i].clone() - c[i].clone())
                + (s[i].clone()
                    + I::dot(
                        b.iter()
                            .zip(&g)
                            .zip(&self.u)
                            .map(|((bj, gj), u)| (bj[i].clone() - gj[i].clone(), u.clone())),
                    ))
        });
        let mut set = Self {
            c,
            g,
            u: self.u.clone(),
        };
        set.push_box(&e);
        set.reduce();
        (set.finite().then_some(set), direct)
    }

    /// The set {p + d : p in the set, d ∈ D}: a low-order step across a switching surface
    /// moves every point by τ·f(Y) for some f in the box f(Y), so the set survives it with the
    /// small box τ·f(Y) added as N symbols (a box would lose the correlations of a wide set,
    /// e.g. with a parameter range as components). `None` when not finite.
    pub fn shifted(&self, d: &[I; N]) -> Option<Self> {
        let z: [I; N] = std::array::from_fn(|i| self.c[i].clone() + d[i].clone());
        let c: [I; N] = std::array::from_fn(|i| z[i].mid_point());
        let e: [I; N] = std::array::from_fn(|i| z[i].clone() - c[i].clone());
        let mut s = Self {
            c,
            g: self.g.clone(),
            u: self.u.clone(),
        };
        s.push_box(&e);
        s.reduce();
        s.finite().then_some(s)
    }

    /// Appends the box e as axis symbols (components exactly 0 add none).
    fn push_box(&mut self, e: &[I; N]) {
        for (i, ei) in e.iter().enumerate() {
            if !exact_zero(ei) {
                self.g.push(axis(i));
                self.u.push(ei.clone());
            }
        }
    }

    /// Merges the smallest symbols into N axis symbols while more than [`SYMBOLS`]·N are kept.
    fn reduce(&mut self) {
        let cap = SYMBOLS * N;
        let m = self.g.len();
        if m <= cap {
            return;
        }
        // keep the cap − N largest (an order only: the merge below is rigorous whichever)
        let size = |j: usize| -> f64 {
            self.u[j].mag_f64() * self.g[j].iter().map(|x| x.mag_f64()).sum::<f64>()
        };
        let mut order: Vec<(f64, usize)> = (0..m).map(|j| (size(j), j)).collect();
        order.sort_by(|a, b| b.0.total_cmp(&a.0));
        let mut merged = vec![false; m];
        for &(_, j) in &order[cap - N..] {
            merged[j] = true;
        }
        let e: [I; N] = std::array::from_fn(|i| {
            I::dot(
                (0..m)
                    .filter(|&j| merged[j])
                    .map(|j| (self.g[j][i].clone(), self.u[j].clone())),
            )
        });
        (self.g, self.u) = std::mem::take(&mut self.g)
            .into_iter()
            .zip(std::mem::take(&mut self.u))
            .zip(merged)
            .filter_map(|(gu, m)| (!m).then_some(gu))
            .unzip();
        self.push_box(&e);
    }

    fn finite(&self) -> bool {
        let ok = |x: &I| x.is_finite();
        self.c.iter().all(ok) && self.u.iter().all(ok) && self.g.iter().flatten().all(ok)
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)] // matrix products read clearer indexed
mod tests {
    use super::*;
    use rug::Rational;

    fn iv(lo: f64, hi: f64) -> Interval {
        Interval::try_from((lo, hi)).unwrap()
    }
    fn pt(x: f64) -> Interval {
        iv(x, x)
    }
    fn q(x: f64) -> Rational {
        Rational::from_f64(x).unwrap()
    }
    /// The point of the interval at fraction a ∈ [0, 1] (an exact rational).
    fn at(x: &Interval, a: f64) -> Rational {
        q(x.inf()) + (q(x.sup()) - q(x.inf())) * q(a)
    }
    fn contains(x: &Interval, r: &Rational) -> bool {
        q(x.inf()) <= *r && *r <= q(x.sup())
    }

    /// A deterministic stream of fractions in [0, 1] (xorshift).
    struct Gen(u64);
    impl Gen {
        fn unit(&mut self) -> f64 {
            (crate::arith::interval::xorshift_step(&mut self.0) >> 11) as f64 / (1u64 << 53) as f64
        }
        /// An end (0 or 1) half the time, else inside.
        fn frac(&mut self) -> f64 {
            let a = self.unit();
            if a < 0.25 {
                0.0
            } else if a > 0.75 {
                1.0
            } else {
                self.unit()
            }
        }
        fn signed(&mut self, scale: f64) -> f64 {
            (2.0 * self.unit() - 1.0) * scale
        }
    }

    /// Whether the point y (exact) is in the set when its first `kept.len()` symbols take the
    /// values `kept` (symbol j of the set is `kept[j]` for j < kept.len()): the rest of y must
    /// lie in the remaining columns, which are axis columns (fresh symbols).
    fn holds(set: &AffineSet<3, Interval>, kept: &[Rational], y: &[Rational; 3]) -> bool {
        (0..3).all(|i| {
            let mut r = y[i].clone() - q(set.c[i].inf());
            for (j, v) in kept.iter().enumerate() {
                r -= q(set.g[j][i].inf()) * v;
            }
            // the fresh symbols: axis columns after the kept ones; those along e_i add up
            let (mut lo, mut hi) = (Rational::new(), Rational::new());
            for j in kept.len()..set.g.len() {
                let unit = |k: usize| (0..3).all(|l| set.g[j][l].inf() == (l == k) as u8 as f64);
                assert!((0..3).any(unit), "column {j} is not an axis column");
                if unit(i) {
                    lo += q(set.u[j].inf());
                    hi += q(set.u[j].sup());
                }
            }
            lo <= r && r <= hi
        })
    }

    fn random_set(g: &mut Gen, columns: usize) -> AffineSet<3, Interval> {
        AffineSet {
            c: std::array::from_fn(|_| pt(g.signed(1.0))),
            g: (0..columns)
                .map(|_| std::array::from_fn(|_| pt(g.signed(1.0))))
                .collect(),
            u: (0..columns)
                .map(|_| {
                    let m = g.signed(1e-3);
                    let r = g.unit() * 1e-3;
                    iv(m - r, m + r)
                })
                .collect(),
        }
    }

    #[test]
    fn the_image_holds_every_mapped_point() {
        let mut g = Gen(0x9e3779b97f4a7c15);
        for _ in 0..200 {
            let set = random_set(&mut g, 5);
            // J an interval matrix, z = z0 + s with z0 a point and s a small box
            let jac: [[Interval; 3]; 3] = std::array::from_fn(|_| {
                std::array::from_fn(|_| {
                    let m = g.signed(2.0);
                    let r = g.unit() * 1e-2;
                    iv(m - r, m + r)
                })
            });
            let z0: [Interval; 3] = std::array::from_fn(|_| pt(g.signed(1.0)));
            let s: [Interval; 3] = std::array::from_fn(|_| {
                let m = g.signed(1e-2);
                iv(m, m + g.unit() * 1e-4)
            });
            let (img, direct) = set.image(&jac, &z0, &s);
            let img = img.expect("finite");
            assert_eq!(img.g.len(), 5 + 3, "five symbols kept, three fresh");
            for _ in 0..20 {
                let u: Vec<Rational> = set.u.iter().map(|x| at(x, g.frac())).collect();
                let jp: [[Rational; 3]; 3] =
                    std::array::from_fn(|i| std::array::from_fn(|l| at(&jac[i][l], g.frac())));
                let y: [Rational; 3] = std::array::from_fn(|i| {
                    let mut y = q(z0[i].inf()) + at(&s[i], g.frac());
                    for l in 0..3 {
                        let mut off = Rational::new();
                        for (j, v) in u.iter().enumerate() {
                            off += q(set.g[j][l].inf()) * v;
                        }
                        y += jp[i][l].clone() * off;
                    }
                    y
                });
                assert!(holds(&img, &u, &y), "a mapped point left the image");
                assert!((0..3).all(|i| contains(&direct[i], &y[i])));
                assert!((0..3).all(|i| contains(&img.hull()[i], &y[i])));
            }
        }
    }

    #[test]
    fn shifted_and_reduced_sets_hold_every_point() {
        let mut g = Gen(0x2545f4914f6cdd1d);
        for _ in 0..200 {
            // more symbols than kept: the smallest are merged into fresh axis symbols
            let set = random_set(&mut g, SYMBOLS * 3 + 4);
            let d: [Interval; 3] = std::array::from_fn(|_| {
                let m = g.signed(1e-2);
                iv(m, m + g.unit() * 1e-4)
            });
            let moved = set.shifted(&d).expect("finite");
            assert!(moved.g.len() <= SYMBOLS * 3);
            // the symbols kept, in order (the merge keeps their order), and their old indices
            let kept: Vec<usize> = {
                let mut k = Vec::new();
                let mut j = 0;
                for (gm, um) in moved.g.iter().zip(&moved.u) {
                    while j < set.g.len() && !(set.g[j] == *gm && set.u[j] == *um) {
                        j += 1;
                    }
                    if j == set.g.len() {
                        break;
                    }
                    k.push(j);
                    j += 1;
                }
                k
            };
            assert!(
                kept.len() >= SYMBOLS * 3 - 3,
                "the largest symbols are kept"
            );
            for _ in 0..20 {
                let u: Vec<Rational> = set.u.iter().map(|x| at(x, g.frac())).collect();
                let y: [Rational; 3] = std::array::from_fn(|i| {
                    let mut y = q(set.c[i].inf()) + at(&d[i], g.frac());
                    for (j, v) in u.iter().enumerate() {
                        y += q(set.g[j][i].inf()) * v;
                    }
                    y
                });
                let ku: Vec<Rational> = kept.iter().map(|&j| u[j].clone()).collect();
                assert!(holds(&moved, &ku, &y), "a moved point left the set");
            }
        }
    }

    #[test]
    fn a_rotated_thin_set_is_not_rewrapped() {
        // a thin box rotated by 45° ten times: a box grows by √2 per step, the affine set
        // keeps the rotated box's hull (≤ √2 of the start's width), and its symbols stay the
        // start's two
        let (s, c) = (
            std::f64::consts::FRAC_1_SQRT_2,
            std::f64::consts::FRAC_1_SQRT_2,
        );
        let jac = [
            [pt(c), pt(-s), pt(0.0)],
            [pt(s), pt(c), pt(0.0)],
            [pt(0.0), pt(0.0), pt(1.0)],
        ];
        let x0 = [iv(-1e-10, 1e-10), iv(-1e-3, 1e-3), pt(0.5)];
        let mut p = AffineSet::from_box(&x0);
        assert_eq!(p.g.len(), 2, "a point component has no symbol");
        let mut bx = x0;
        let zero = [pt(0.0); 3];
        for _ in 0..10 {
            let (np, _) = p.image(&jac, &p.c, &zero);
            p = np.unwrap();
            bx = std::array::from_fn(|i| jac[i][0] * bx[0] + jac[i][1] * bx[1] + jac[i][2] * bx[2]);
        }
        let h = p.hull();
        assert!(h[0].wid() < 2.9e-3 && h[1].wid() < 2.9e-3, "{h:?}");
        assert!(bx[0].wid() > 1e-2, "the plain box wraps: {bx:?}");
        // 10 rotations by 45°: a half turn and a quarter, the long edge along x
        assert!(h[0].wid() > 1.9e-3 && h[1].wid() < 2.01e-10, "{h:?}");
    }

    #[test]
    fn sets_that_overflow_are_dropped_for_their_boxes() {
        // a set carried on with an unbounded centre, symbol or generator is no set: `image` and
        // `shifted` give None and the caller keeps the direct box (which stays an enclosure)
        let set = AffineSet::<2, Interval>::from_box(&[iv(0.0, 1e300), iv(1.0, 2.0)]);
        let big = [[pt(1e300), pt(0.0)], [pt(0.0), pt(1.0)]];
        let (next, direct) = set.image(&big, &[pt(1.0), pt(1.5)], &[pt(0.0), pt(0.0)]);
        assert!(next.is_none(), "a generator 1e300·5e299 overflows");
        assert!(direct[0].sup() == f64::INFINITY && direct[1].inf() <= 1.0);
        let one = [[pt(1.0), pt(0.0)], [pt(0.0), pt(1.0)]];
        let (kept, _) = set.image(&one, &[pt(1.0), pt(1.5)], &[pt(0.0), pt(0.0)]);
        assert!(kept.is_some(), "the finite image is kept");
        assert!(set.shifted(&[iv(0.0, f64::INFINITY), pt(0.0)]).is_none());
        assert!(set.shifted(&[pt(1.0), pt(0.0)]).is_some());
    }
}
