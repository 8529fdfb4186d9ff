//! Golden-section search for a minimum of an `f64` function on an interval.

/// The golden ratio's conjugate, (√5 − 1)/2.
const R: f64 = 0.618_033_988_749_894_8;

/// Golden-section search of `f` (unimodal on [a, b]) for its minimum, from a point already
/// known, `best` = (x, f(x)): the bracket shrinks until `narrow(a, b)` or `max_evals`
/// evaluations (the first two included). Returns the best point seen — `best` or one of the
/// last two inner points (the lower value; a tie keeps the earlier) — and the evaluations.
pub fn golden_min(
    f: impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    best: (f64, f64),
    narrow: impl Fn(f64, f64) -> bool,
    max_evals: usize,
) -> (f64, f64, usize) {
    let (mut a, mut b) = (a, b);
    let mut c = b - R * (b - a);
    let mut d = a + R * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    let mut n = 2;
    while !narrow(a, b) && n < max_evals {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - R * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + R * (b - a);
            fd = f(d);
        }
        n += 1;
    }
    let mut best = best;
    for (x, fx) in [(c, fc), (d, fd)] {
        if fx < best.1 {
            best = (x, fx);
        }
    }
    (best.0, best.1, n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_vertex_of_a_parabola() {
        let (x, fx, n) = golden_min(
            |x| (x - 0.3) * (x - 0.3) + 2.0,
            -1.0,
            2.0,
            (2.0, 5.29),
            |a, b| b - a < 1e-12,
            200,
        );
        assert!(
            (x - 0.3).abs() < 1e-7 && (fx - 2.0).abs() < 1e-14 && n < 200,
            "{x} {fx} {n}"
        );
        // a known point better than the bracket's inside is kept
        let (x, fx, _) = golden_min(|x| x, 0.0, 1.0, (-1.0, -1.0), |_, _| false, 10);
        assert_eq!((x, fx), (-1.0, -1.0));
    }
}
