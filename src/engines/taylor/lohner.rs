//! Wrapping-effect control: Lohner's QR method.
//!
//! The enclosure at a step's start is kept as a parallelepiped X ⊆ c + A·r (c a point, A a
//! nonsingular f64 matrix, r a box around 0) instead of a box. A Taylor step maps it, by the
//! mean-value form, to
//!
//! ```text
//! x(t1) ∈ z + B·r,    z = T(c) + R  (the point's Taylor polynomial and the remainder),
//!                     B = J·A,  J = Σ h^k D_k(X) (the Jacobian of the Taylor map over X)
//! ```
//!
//! and the new representation is c′ = mid(z) (a point of the engine's number type: at high
//! precision an f64 centre would add its rounding to every step), A′ = Q from a QR factorization of mid(B) with its
//! columns sorted by ‖mid(B)e_j‖·rad(r_j) (the longest edge of the parallelepiped first),
//! r′ = (Q⁻¹B)·r + Q⁻¹(z − c′), with Q⁻¹ enclosed rigorously (below). The box of a rotating
//! set is then not re-wrapped at every step (Lohner 1987; Nedialkov & Jackson 2001).
//!
//! Q⁻¹ is enclosed from R = Qᵀ (an approximate inverse): with E = I − R·Q computed in interval
//! arithmetic and e = ‖E‖_∞ < 1, Q⁻¹ = (I − E)⁻¹R and every entry of Q⁻¹ − R is bounded by
//! ‖(I − E)⁻¹ − I‖_∞‖R‖_∞ ≤ e/(1 − e)·‖R‖_∞ (Neumann series).

use crate::arith::Enclosure;
use inari::Interval;

fn pt<I: Enclosure>(x: f64) -> I {
    I::from_exact_f64(x)
}

/// A set c + A·r (c a point of the number type `I`, A an f64 matrix, r a box).
#[derive(Clone, Debug)]
pub struct Parallelepiped<const N: usize, I = Interval> {
    pub c: [I; N],
    pub a: [[f64; N]; N],
    pub r: [I; N],
}

impl<const N: usize, I: Enclosure> Parallelepiped<N, I> {
    /// The box X as c = mid X, A = I, r = X − c.
    pub fn from_box(x: &[I; N]) -> Self {
        let c: [I; N] = std::array::from_fn(|i| x[i].mid_point());
        let a = std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }));
        Self {
            r: std::array::from_fn(|i| x[i].clone() - c[i].clone()),
            c,
            a,
        }
    }

    /// The interval hull of c + A·r.
    pub fn hull(&self) -> [I; N] {
        std::array::from_fn(|i| {
            I::dot(
                std::iter::once((self.c[i].clone(), I::one()))
                    .chain((0..N).map(|j| (pt(self.a[i][j]), self.r[j].clone()))),
            )
        })
    }

    /// A·r, the set's offsets from c.
    pub fn offsets(&self) -> [I; N] {
        std::array::from_fn(|i| I::dot((0..N).map(|j| (pt(self.a[i][j]), self.r[j].clone()))))
    }

    /// The set z + B·r of the next step, re-represented with A′ = Q (see the module doc).
    /// `None` when Q⁻¹ cannot be enclosed (then the caller keeps a box).
    pub fn advance(z: &[I; N], b: &[[I; N]; N], r: &[I; N]) -> Option<Self> {
        let c: [I; N] = std::array::from_fn(|i| z[i].mid_point());
        let bm: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| b[i][j].mid()));
        let q = orthonormal_basis(&bm, r)?;
        let qinv = inverse_enclosure_in::<I, N>(&q)?;
        // Q⁻¹B, then r′ = (Q⁻¹B)·r + Q⁻¹(z − c′)
        let qb: [[I; N]; N] = std::array::from_fn(|i| {
            std::array::from_fn(|j| I::dot((0..N).map(|l| (qinv[i][l].clone(), b[l][j].clone()))))
        });
        let r1 = std::array::from_fn(|i| {
            I::dot(
                (0..N)
                    .map(|j| (qinv[i][j].clone(), z[j].clone() - c[j].clone()))
                    .chain((0..N).map(|j| (qb[i][j].clone(), r[j].clone()))),
            )
        });
        Some(Self { c, a: q, r: r1 })
    }

    /// The set {p + d : p ∈ c + A·r, d ∈ D}, re-represented (z + A·r with z = c + D): a
    /// low-order step across a switching surface moves every point by τ·f(Y) for some f in the
    /// box f(Y), so the parallelepiped survives it with the small box τ·f(Y) added, instead of
    /// being re-wrapped as a box (which loses the correlations of a wide set, e.g. with a
    /// parameter range as components).
    pub fn shifted(&self, d: &[I; N]) -> Option<Self> {
        let z: [I; N] = std::array::from_fn(|i| self.c[i].clone() + d[i].clone());
        let b: [[I; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| pt(self.a[i][j])));
        Self::advance(&z, &b, &self.r)
    }
}

/// Q of a QR factorization of m with its columns sorted by ‖m e_j‖·rad(r_j), by modified
/// Gram–Schmidt (None if the columns are numerically dependent).
fn orthonormal_basis<const N: usize, I: Enclosure>(
    m: &[[f64; N]; N],
    r: &[I; N],
) -> Option<[[f64; N]; N]> {
    let col = |j: usize| -> [f64; N] { std::array::from_fn(|i| m[i][j]) };
    let norm = |v: &[f64; N]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut order: Vec<usize> = (0..N).collect();
    order.sort_by(|&a, &b| {
        (norm(&col(b)) * r[b].rad_f64()).total_cmp(&(norm(&col(a)) * r[a].rad_f64()))
    });
    let mut qs: Vec<[f64; N]> = Vec::with_capacity(N);
    for &j in &order {
        let mut v = col(j);
        for q in &qs {
            let d: f64 = (0..N).map(|i| q[i] * v[i]).sum();
            for i in 0..N {
                v[i] -= d * q[i];
            }
        }
        let n = norm(&v);
        if n.is_nan() || n <= 1e-12 * norm(&col(j)).max(f64::MIN_POSITIVE) {
            return None;
        }
        qs.push(v.map(|x| x / n));
    }
    Some(std::array::from_fn(|i| std::array::from_fn(|j| qs[j][i])))
}

/// A rigorous enclosure of Q⁻¹ for a point matrix Q close to orthogonal (module doc), as
/// inari intervals.
pub fn inverse_enclosure<const N: usize>(q: &[[f64; N]; N]) -> Option<[[Interval; N]; N]> {
    inverse_enclosure_in::<Interval, N>(q)
}

/// [`inverse_enclosure`] in the number type `I`. The norms e and ‖R‖ are carried as f64
/// upper bounds (the ball's radius δ is rounded up), R's entries are exact: the enclosure is
/// R ± δ whatever the precision of `I`.
#[allow(clippy::needless_range_loop)] // matrix products read clearer indexed
pub fn inverse_enclosure_in<I: Enclosure, const N: usize>(
    q: &[[f64; N]; N],
) -> Option<[[I; N]; N]> {
    let r: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| q[j][i]));
    let mut e_norm = I::zero();
    let mut r_norm = I::zero();
    for i in 0..N {
        let mut row = I::zero();
        let mut rrow = I::zero();
        for j in 0..N {
            let rq = I::dot((0..N).map(|l| (pt::<I>(r[i][l]), pt::<I>(q[l][j]))));
            let e = if i == j { I::one() - rq } else { -rq };
            row = row + pt(e.mag_f64());
            rrow = rrow + pt(r[i][j].abs());
        }
        e_norm = pt(e_norm.hi().max(row.hi()));
        r_norm = pt(r_norm.hi().max(rrow.hi()));
    }
    if e_norm.hi().is_nan() || e_norm.hi() >= 0.5 {
        return None;
    }
    let delta = (e_norm.clone() / (I::one() - e_norm) * r_norm).hi();
    let ball = I::from_bounds(-delta, delta)?;
    Some(std::array::from_fn(|i| {
        std::array::from_fn(|j| pt::<I>(r[i][j]) + ball.clone())
    }))
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use inari::const_interval;

    const ZERO: Interval = const_interval!(0.0, 0.0);

    fn pt(x: f64) -> Interval {
        Interval::try_from((x, x)).unwrap()
    }

    #[test]
    fn inverse_of_a_rotation_encloses_its_transpose_and_the_identity() {
        let (s, c) = (0.3f64.sin(), 0.3f64.cos());
        let q = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
        let qi = inverse_enclosure(&q).unwrap();
        for i in 0..3 {
            for j in 0..3 {
                // (Q⁻¹Q)_ij ∋ δ_ij
                let mut acc = ZERO;
                for l in 0..3 {
                    acc += qi[i][l] * pt(q[l][j]);
                }
                assert!(
                    acc.contains(if i == j { 1.0 } else { 0.0 }),
                    "{i}{j}: {acc:?}"
                );
                assert!(qi[i][j].wid() < 1e-14);
            }
        }
    }

    #[test]
    fn advancing_a_rotated_box_does_not_wrap() {
        // a thin box rotated by 45° ten times: boxes grow by √2 per step, the
        // parallelepiped does not
        let (s, c) = (
            std::f64::consts::FRAC_1_SQRT_2,
            std::f64::consts::FRAC_1_SQRT_2,
        );
        let b: [[Interval; 2]; 2] = [[pt(c), pt(-s)], [pt(s), pt(c)]];
        let x0 = [
            Interval::try_from((-1e-10, 1e-10)).unwrap(),
            Interval::try_from((-1e-3, 1e-3)).unwrap(),
        ];
        let mut p = Parallelepiped::from_box(&x0);
        let mut bx = x0;
        for _ in 0..10 {
            let z = [ZERO; 2];
            let bb: [[Interval; 2]; 2] = std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    let mut acc = ZERO;
                    for l in 0..2 {
                        acc += b[i][l] * pt(p.a[l][j]);
                    }
                    acc
                })
            });
            p = Parallelepiped::advance(&z, &bb, &p.r).unwrap();
            bx = std::array::from_fn(|i| b[i][0] * bx[0] + b[i][1] * bx[1]);
        }
        let hp = p.hull();
        assert!(hp[0].wid() < 2.1e-3 && hp[1].wid() < 2.1e-3, "{hp:?}");
        assert!(bx[0].wid() > 1e-2, "the plain box wraps: {bx:?}");
    }

    #[test]
    fn a_shifted_parallelepiped_holds_every_moved_point() {
        // a long thin set along (1, 1)/√2, moved by the box D = [1, 1.5] × [−0.25, 0]: every
        // corner p + d must be inside, and the result stays thin across (1, 1) (a box would not)
        let (s, c) = (
            std::f64::consts::FRAC_1_SQRT_2,
            std::f64::consts::FRAC_1_SQRT_2,
        );
        let p = Parallelepiped {
            c: [pt(0.5), pt(-0.25)],
            a: [[c, -s], [s, c]],
            r: [
                Interval::try_from((-1.0, 1.0)).unwrap(),
                Interval::try_from((-1e-9, 1e-9)).unwrap(),
            ],
        };
        let d = [
            Interval::try_from((1.0, 1.5)).unwrap(),
            Interval::try_from((-0.25, 0.0)).unwrap(),
        ];
        let q = p.shifted(&d).unwrap();
        let inside = |x: [f64; 2]| {
            // x ∈ c′ + A′·r′ ⟺ A′⁻¹(x − c′) ∈ r′ (A′⁻¹ enclosed)
            let qi = inverse_enclosure(&q.a).unwrap();
            (0..2).all(|i| {
                let mut acc = ZERO;
                for j in 0..2 {
                    acc += qi[i][j] * (pt(x[j]) - q.c[j]);
                }
                !acc.intersection(q.r[i]).is_empty()
            })
        };
        for r0 in [-1.0, 1.0] {
            for r1 in [-1e-9, 1e-9] {
                for d0 in [1.0, 1.5] {
                    for d1 in [-0.25, 0.0] {
                        let x = [
                            p.c[0].inf() + c * r0 - s * r1 + d0,
                            p.c[1].inf() + s * r0 + c * r1 + d1,
                        ];
                        assert!(inside(x), "corner {x:?} outside {q:?}");
                    }
                }
            }
        }
        // thin across the long edge: the width of D's projection, not the hull's
        let across = q.r.iter().map(|r| r.wid()).fold(f64::INFINITY, f64::min);
        assert!(across < 0.6, "{q:?}");
        let h = q.hull();
        // the first coordinate's true range is 0.5 ± 1/√2 + [1, 1.5]
        assert!(
            h[0].contains(0.5 - c + 1.0) && h[0].contains(0.5 + c + 1.5),
            "{h:?}"
        );
    }
}
