//! The proved flow: rigorous dense output.
//!
//! Each piece covers [t0, t1] and gives, for every τ = t − t0 in it, a box containing Φ(t):
//! - a Taylor piece: Σ_{k<K} x_k τ^k + τ^K C_K, with x_k the coefficients through the box at
//!   t0 and C_K ⊇ the K-th coefficient over the piece's a-priori enclosure (the Lagrange
//!   remainder);
//! - a low-order piece (across a switching surface): X(t0) + τ·f(Y), Y the a-priori enclosure
//!   (the mean-value form of x(t) = x(t0) + ∫ f).

use crate::arith::Enclosure;
use inari::Interval;

/// One proved piece of the flow (over the engine's number type `I`, inari's `Interval` unless
/// said otherwise). The times of its ends are exact doubles.
#[derive(Clone, Debug)]
pub enum Piece<const N: usize, I = Interval> {
    Taylor {
        t0: f64,
        t1: f64,
        coefs: Vec<[I; N]>,
        remainder: [I; N],
    },
    LowOrder {
        t0: f64,
        t1: f64,
        x0: [I; N],
        slope: [I; N],
    },
}

/// τ = t − t0 as an enclosure (t0 an exact double; the difference may not be).
#[inline]
pub fn tau<I: Enclosure>(t: &I, t0: f64) -> I {
    (t.clone() - I::from_exact_f64(t0)).nonneg()
}

/// The time point x (an exact double) as an inari interval.
pub fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).expect("finite time")
}

/// Σ_{k<K} c_k s^k + s^K r (Horner), for an interval s: in the jet arithmetic of `I` (for
/// inari intervals [`crate::arith::interval::ulp::Ulp`], the same enclosures without
/// rounding-mode switches).
pub fn taylor_eval<const N: usize, I: Enclosure>(coefs: &[[I; N]], rem: &[I; N], s: &I) -> [I; N] {
    let k = coefs.len();
    if s.is_empty() || coefs.iter().any(|c| c.iter().any(|x| x.is_empty())) {
        return std::array::from_fn(|_| I::empty());
    }
    let sk = s.powi_nonneg(k as u32).to_jet();
    let su = s.to_jet();
    std::array::from_fn(|i| {
        let mut p = coefs[k - 1][i].to_jet();
        for c in coefs.iter().rev().skip(1) {
            p = p * su.clone() + c[i].to_jet();
        }
        if rem[i].is_empty() {
            return I::empty();
        }
        I::from_jet(p + rem[i].to_jet() * sk.clone())
    })
}

impl<const N: usize, I: Enclosure> Piece<N, I> {
    /// Ends the piece earlier, at t (t0 ≤ t ≤ t1): its enclosure stays valid on [t0, t].
    pub fn truncate(&mut self, t: f64) {
        match self {
            Piece::Taylor { t0, t1, .. } | Piece::LowOrder { t0, t1, .. } => {
                assert!(*t0 <= t && t <= *t1);
                *t1 = t;
            }
        }
    }

    pub fn t0(&self) -> f64 {
        match self {
            Piece::Taylor { t0, .. } | Piece::LowOrder { t0, .. } => *t0,
        }
    }
    pub fn t1(&self) -> f64 {
        match self {
            Piece::Taylor { t1, .. } | Piece::LowOrder { t1, .. } => *t1,
        }
    }
    /// The enclosure of Φ(t) for every t in `t` (an interval inside [t0, t1]).
    pub fn enclose(&self, t: &I) -> [I; N] {
        match self {
            Piece::Taylor {
                t0,
                coefs,
                remainder,
                ..
            } => taylor_eval(coefs, remainder, &tau(t, *t0)),
            Piece::LowOrder { t0, x0, slope, .. } => {
                let s = tau(t, *t0);
                std::array::from_fn(|i| x0[i].clone() + s.clone() * slope[i].clone())
            }
        }
    }
}

/// The proved flow from its first piece's start (T = 0 for a run of the engine; t0 for a
/// window, [`super::window`]): consecutive pieces.
#[derive(Clone, Debug)]
pub struct Flow<const N: usize, I = Interval> {
    pub pieces: Vec<Piece<N, I>>,
    /// Taylor steps tried that were not taken (refused: too short, at a switching surface, or
    /// their kink crossing unresolved): the work the step choice spent in vain.
    pub refused_taylor: usize,
}

impl<const N: usize, I> Default for Flow<N, I> {
    fn default() -> Self {
        Self {
            pieces: Vec::new(),
            refused_taylor: 0,
        }
    }
}

impl<const N: usize, I: Enclosure> Flow<N, I> {
    /// An enclosure of Φ(t) for [`Flow::t_start`] ≤ t ≤ [`Flow::t_end`] (`None` outside). At
    /// a piece boundary both pieces are valid; the intersection of the two is returned.
    pub fn enclose(&self, t: f64) -> Option<[I; N]> {
        if !(t >= self.t_start() && t <= self.t_end()) {
            return None;
        }
        let i = self.pieces.partition_point(|p| p.t1() < t);
        let tt = I::from_exact_f64(t);
        let mut b = self.pieces.get(i)?.enclose(&tt);
        if let Some(next) = self.pieces.get(i + 1)
            && next.t0() == t
        {
            let c = next.enclose(&tt);
            for j in 0..N {
                let x = b[j].intersection(&c[j]);
                if !x.is_empty() {
                    b[j] = x;
                }
            }
        }
        Some(b)
    }
    /// The start of the proved time range (0 when there is no piece).
    pub fn t_start(&self) -> f64 {
        self.pieces.first().map_or(0.0, |p| p.t0())
    }
    /// The end of the proved time range.
    pub fn t_end(&self) -> f64 {
        self.pieces.last().map_or(0.0, |p| p.t1())
    }
    pub fn len(&self) -> usize {
        self.pieces.len()
    }
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }
}
