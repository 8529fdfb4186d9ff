//! Interval Newton for the zero of a function of time on a time interval, shared by the
//! separation event and the kink crossings.
//!
//! N(T) = m − g(m)/g′(T), m the midpoint of T; T ← T ∩ N(T) until it stops shrinking. If some
//! N(T) ⊆ int T, g has exactly one zero in the first T (Moore), and every later T contains it.

use crate::arith::Enclosure;

/// What interval Newton proved about the zeros of g on T.
pub enum Newton<I> {
    /// Exactly one zero, inside this interval.
    Root(I),
    /// No zero in T (T ∩ N(T) = ∅).
    NoRoot,
    /// Neither could be proved (or `dg` declined).
    Undecided,
}

/// Interval Newton on T with `g(m)` an enclosure of g at the point m and `dg(T)` an enclosure
/// of g′ over T (`None`: not usable there, e.g. its sign is not the one required). The
/// midpoint m is a point of the type (at high precision T becomes far narrower than a double's
/// spacing).
pub fn interval_newton<I: Enclosure>(
    mut t: I,
    mut g: impl FnMut(&I) -> I,
    mut dg: impl FnMut(&I) -> Option<I>,
) -> Newton<I> {
    let mut proved = false;
    for _ in 0..40 {
        let Some(d) = dg(&t) else {
            return Newton::Undecided;
        };
        let m = t.mid_point();
        let n = m.clone() - g(&m) / d;
        let tn = t.intersection(&n);
        if tn.is_empty() {
            return Newton::NoRoot;
        }
        if n.interior(&t) {
            proved = true;
        }
        if tn.same(&t) {
            break;
        }
        t = tn;
    }
    if proved {
        Newton::Root(t)
    } else {
        Newton::Undecided
    }
}
