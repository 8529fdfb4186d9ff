//! Interval Newton for the zero of a function of time on a time interval, shared by the
//! separation event and the kink crossings.
//!
//! N(T) = m − g(m)/g′(T), m the midpoint of T; T ← T ∩ N(T) until it stops shrinking. If some
//! N(T) ⊆ int T, g has exactly one zero in the first T (Moore), and every later T contains it.

use inari::Interval;

/// What interval Newton proved about the zeros of g on T.
pub enum Newton {
    /// Exactly one zero, inside this interval.
    Root(Interval),
    /// No zero in T (T ∩ N(T) = ∅).
    NoRoot,
    /// Neither could be proved (or `dg` declined).
    Undecided,
}

/// Interval Newton on T with `g(m)` an enclosure of g at the point m and `dg(T)` an enclosure
/// of g′ over T (`None`: not usable there, e.g. its sign is not the one required).
pub fn interval_newton(
    mut t: Interval,
    mut g: impl FnMut(f64) -> Interval,
    mut dg: impl FnMut(Interval) -> Option<Interval>,
) -> Newton {
    let mut proved = false;
    for _ in 0..40 {
        let Some(d) = dg(t) else {
            return Newton::Undecided;
        };
        let m = t.mid();
        let n = Interval::try_from((m, m)).unwrap() - g(m) / d;
        let tn = t.intersection(n);
        if tn.is_empty() {
            return Newton::NoRoot;
        }
        if n.interior(t) {
            proved = true;
        }
        if tn == t {
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
