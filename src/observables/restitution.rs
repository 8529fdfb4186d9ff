//! The CoR a Hunt–Crossley law really produces, proved, and the errors of the published damping
//! formulas (issue #33, item 3).
//!
//! The law's e solves H(σ, e) = 0 ([`crate::models::hunt_crossley`]): for each σ > 0 a unique
//! root in (0, min(1, 1/σ)), where H(σ, ·) increases. So a point a with H(σ, a) < 0 and a point
//! b with H(σ, b) > 0, both proved over every σ of an interval \[σ\], bracket e(σ) for all of
//! them. [`cor_of_sigma`] bisects such a bracket with H evaluated in 128-bit MPFR interval
//! arithmetic (directed rounding; no cancellation trouble in G(u) ≈ u²/2 for small u) until
//! the sign of H at the midpoint is no longer decided, then tightens each end on its own.
//!
//! A formula's error at a target e* is e(σ(e*)) − e*, with e* enclosed as written (a decimal)
//! and σ(e*) evaluated over that enclosure. [`pave_within`] proves where |error| ≤ tol over a
//! whole range of e*: a piece [l, r] of targets gives σ([l, r]), its bracket of e and so an
//! enclosure of every error on the piece; pieces are split until decided or narrower than a
//! floor. Everything is an enclosure; nothing is sampled.

use super::decimal::{Rounding, parse_rational};
use crate::arith::Real;
use crate::arith::mpfr::Mpi;
use crate::models::hunt_crossley::{DampingFormula, restitution_residual};
use rayon::prelude::*;
use rug::float::Round;
use rug::{Float, Rational};

/// The working arithmetic: 128-bit MPFR intervals.
pub type Big = Mpi<128>;

/// Bisection steps of a bracket (each halves it; 128-bit ends stop it well before).
const MAX_BISECTIONS: usize = 200;

fn mid(a: &Float, b: &Float) -> Float {
    Float::with_val_round(128, a + b, Round::Nearest).0 / 2u32
}

fn point(x: &Float) -> Big {
    Big::point(x)
}

/// The proved sign of `h` over an interval: −1, +1, or 0 when it contains 0 (or is empty).
fn sign(h: &Big) -> i8 {
    if h.is_empty() {
        0
    } else if h.hi() < 0.0 {
        -1
    } else if h.lo() > 0.0 {
        1
    } else {
        0
    }
}

/// b − a < `tight` (a ≤ b).
fn narrow(a: &Float, b: &Float, tight: f64) -> bool {
    Float::with_val(128, b - a) < tight
}

/// Shrinks a bracket [a, b] of the root of an increasing function (sign(f(a)) = −1,
/// sign(f(b)) = +1, proved): bisection while the midpoint's sign is decided, then each end
/// tightened on its own towards the undecided midpoint; it stops early once b − a < `tight`.
fn shrink(f: impl Fn(&Float) -> i8, mut a: Float, mut b: Float, tight: f64) -> (Float, Float) {
    let mut undecided = None;
    for _ in 0..MAX_BISECTIONS {
        if narrow(&a, &b, tight) {
            return (a, b);
        }
        let m = mid(&a, &b);
        if m <= a || m >= b {
            break;
        }
        match f(&m) {
            -1 => a = m,
            1 => b = m,
            _ => {
                undecided = Some(m);
                break;
            }
        }
    }
    if let Some(m) = undecided {
        tighten(&f, &mut a, m.clone(), -1, tight);
        tighten(&f, &mut b, m, 1, tight);
    }
    (a, b)
}

/// Moves `end`, where f has the proved sign `s`, towards `u` by bisection: a midpoint with the
/// sign `s` proved becomes the end, any other becomes `u`; until the two are `tight` apart or
/// adjacent at 128 bits.
fn tighten(f: &impl Fn(&Float) -> i8, end: &mut Float, mut u: Float, s: i8, tight: f64) {
    for _ in 0..MAX_BISECTIONS {
        let (lo, hi) = if *end <= u { (&*end, &u) } else { (&u, &*end) };
        if narrow(lo, hi, tight) {
            break;
        }
        let c = mid(lo, hi);
        if c <= *lo || c >= *hi {
            break;
        }
        if f(&c) == s {
            *end = c;
        } else {
            u = c;
        }
    }
}

/// σ as a number: finite and > 0.
fn check_sigma(sigma: &Big) -> Result<(), String> {
    if sigma.is_empty() || sigma.lo() <= 0.0 || !sigma.hi().is_finite() {
        return Err(format!(
            "the damping σ must be a finite positive number (got {})",
            crate::models::params::show(sigma)
        ));
    }
    Ok(())
}

/// The bracket [a, b] ∋ e(σ) at one σ > 0 (an exact 128-bit float).
fn cor_at(sigma: &Float, tight: f64) -> Result<(Float, Float), String> {
    let s = point(sigma);
    let h = |e: &Float| sign(&restitution_residual(&s, &point(e)));
    // a = 0: H(σ, 0) = −G(−σ) < 0; b = min(1, 1/σ) nudged inside (0, 1/σ)
    let a = Float::with_val(128, 0);
    let b = if *sigma < 1u32 {
        Float::with_val(128, 1)
    } else {
        let inv = Float::with_val_round(128, 1u32 / sigma, Round::Down).0;
        inv * (1u32 - Float::with_val(128, Float::i_exp(1, -100)))
    };
    if h(&a) != -1 {
        return Err("H(σ, 0) < 0 not proved".into());
    }
    if h(&b) != 1 {
        return Err(format!("H(σ, {}) > 0 not proved", b.to_f64()));
    }
    Ok(shrink(h, a, b, tight))
}

/// The CoR e of the Hunt–Crossley law for every damping σ in `sigma` (σ > 0): an enclosure of
/// all the roots of H(σ, ·) = 0. Errors say why a bracket could not be proved.
///
/// e(σ) is strictly decreasing (module doc of [`crate::models::hunt_crossley`]: at a root,
/// σ > (1 − e)/e, where ∂H/∂σ > 0, and ∂H/∂e > 0), so the roots over [σ₁, σ₂] fill
/// [e(σ₂), e(σ₁)]: the brackets at the two ends give the enclosure, with none of the
/// dependency an interval evaluation of H over [σ₁, σ₂] would add.
pub fn cor_of_sigma(sigma: &Big) -> Result<Big, String> {
    cor_of_sigma_to(sigma, 0.0)
}

/// [`cor_of_sigma`], each end's bracket shrunk only until it is narrower than `tight`.
fn cor_of_sigma_to(sigma: &Big, tight: f64) -> Result<Big, String> {
    check_sigma(sigma)?;
    let (lo, _) = cor_at(sigma.sup(), tight)?;
    let (_, hi) = if sigma.inf() == sigma.sup() {
        cor_at(sigma.sup(), tight)?
    } else {
        cor_at(sigma.inf(), tight)?
    };
    Ok(Big::new(lo, hi))
}

/// The bracket of the exact damping σ*(e) at one e ∈ (0, 1) (an exact 128-bit float): the root
/// of H(·, e) beyond (1 − e)/e, where H(·, e) increases
/// (∂H/∂σ = (1 + e)σ(σe − (1 − e))/((1 − σe)(1 + σ))) from below 0 (H(0, e) = 0 and H
/// decreases before) to +∞ at σ → 1/e.
fn exact_sigma_at(e: &Float, tight: f64) -> Result<(Float, Float), String> {
    let ep = point(e);
    let h = |s: &Float| sign(&restitution_residual(&point(s), &ep));
    let start = (Big::one() - ep.clone()) / ep.clone();
    let a = start.sup().clone();
    let inv = Float::with_val_round(128, 1u32 / e, Round::Down).0;
    let b = inv * (1u32 - Float::with_val(128, Float::i_exp(1, -100)));
    if h(&a) != -1 || h(&b) != 1 {
        return Err("the exact damping's bracket was not proved".into());
    }
    Ok(shrink(h, a, b, tight))
}

/// The exact damping of Carvalho & Martins (2019): σ*(e*) with e(σ*) = e*, for every e* of `e`
/// (0 < e* < 1). σ* is the inverse of the decreasing e(σ), so decreasing too: the brackets at
/// the ends of `e` give the enclosure.
pub fn exact_sigma(e: &Big) -> Result<Big, String> {
    exact_sigma_to(e, 0.0)
}

/// [`exact_sigma`], each end's bracket shrunk only until it is narrower than `tight`.
fn exact_sigma_to(e: &Big, tight: f64) -> Result<Big, String> {
    if e.is_empty() || e.lo() <= 0.0 || e.hi() >= 1.0 {
        return Err("the exact damping needs a target CoR in (0, 1)".into());
    }
    let (lo, _) = exact_sigma_at(e.sup(), tight)?;
    let (_, hi) = exact_sigma_at(e.inf(), tight)?;
    Ok(Big::new(lo, hi))
}

/// σ(e*) of a formula over an enclosure of targets.
pub fn formula_sigma(formula: DampingFormula, e_star: &Big) -> Result<Big, String> {
    formula_sigma_to(formula, e_star, 0.0)
}

fn formula_sigma_to(formula: DampingFormula, e_star: &Big, tight: f64) -> Result<Big, String> {
    match formula.sigma(e_star) {
        Some(s) => Ok(s),
        None => exact_sigma_to(e_star, tight),
    }
}

/// A formula at one target (or over a piece of targets): σ(e*), the CoR e the law produces and
/// the error e − e*, all enclosures.
#[derive(Clone, Debug)]
pub struct FormulaPoint {
    pub formula: DampingFormula,
    pub e_star: Big,
    pub sigma: Big,
    pub e: Big,
    pub error: Big,
}

/// The formula's proved CoR and error at the targets `e_star` (0 < e* < 1).
pub fn evaluate(formula: DampingFormula, e_star: &Big) -> Result<FormulaPoint, String> {
    evaluate_to(formula, e_star, 0.0)
}

/// [`evaluate`] with brackets shrunk only below `tight` (a piece of targets needs no more
/// than a small part of its own width).
fn evaluate_to(formula: DampingFormula, e_star: &Big, tight: f64) -> Result<FormulaPoint, String> {
    let sigma = formula_sigma_to(formula, e_star, tight)?;
    let e = cor_of_sigma_to(&sigma, tight)?;
    let error = e.clone() - e_star.clone();
    Ok(FormulaPoint {
        formula,
        e_star: e_star.clone(),
        sigma,
        e,
        error,
    })
}

/// What a piece of targets was proved to be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// |e − e*| ≤ tol for every target of the piece.
    Within,
    /// |e − e*| > tol for every target of the piece.
    Outside,
    /// Neither, at the narrowest piece allowed.
    Undecided,
}

/// A maximal run of targets [lo, hi] with one verdict.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    pub lo: f64,
    pub hi: f64,
    pub verdict: Verdict,
}

/// The verdict on one piece [lo, hi] of targets.
fn judge(formula: DampingFormula, lo: f64, hi: f64, tol: &Big) -> Verdict {
    let piece = Big::new(Float::with_val(128, lo), Float::with_val(128, hi));
    let Ok(p) = evaluate_to(formula, &piece, 1e-3 * (hi - lo)) else {
        return Verdict::Undecided;
    };
    let (x, t) = (&p.error, tol);
    if x.is_empty() {
        Verdict::Undecided
    } else if x.hi() <= t.lo() && x.lo() >= -t.lo() {
        Verdict::Within
    } else if x.lo() > t.hi() || x.hi() < -t.hi() {
        Verdict::Outside
    } else {
        Verdict::Undecided
    }
}

/// Proves where the formula's error stays within ±tol over the targets [lo, hi] (exact doubles,
/// 0 < lo < hi < 1): pieces are halved until decided or narrower than `min_width`; returns
/// the maximal runs of each verdict, in order, covering [lo, hi].
pub fn pave_within(
    formula: DampingFormula,
    lo: f64,
    hi: f64,
    tol: &Big,
    min_width: f64,
) -> Vec<Segment> {
    let mut out: Vec<Segment> = Vec::new();
    let mut stack = vec![(lo, hi)];
    while let Some((l, r)) = stack.pop() {
        // a stop requested (Ctrl-C in Python, `engines::cancel`): the rest is undecided
        let stopped = crate::engines::cancel::requested();
        let v = if stopped {
            Verdict::Undecided
        } else {
            judge(formula, l, r, tol)
        };
        let m = 0.5 * (l + r);
        if v == Verdict::Undecided && !stopped && r - l > min_width && l < m && m < r {
            // right half pushed first: pieces come off the stack left to right
            stack.push((m, r));
            stack.push((l, m));
            continue;
        }
        match out.last_mut() {
            Some(s) if s.verdict == v && s.hi == l => s.hi = r,
            _ => out.push(Segment {
                lo: l,
                hi: r,
                verdict: v,
            }),
        }
    }
    out
}

/// Pieces of targets narrower than this are not split further by [`study`].
pub const MIN_WIDTH: f64 = 1e-8;

/// The targets of a study: `points` ≥ 2 decimals from `lo` to `hi` (decimal literals, kept as
/// written), rounded to 4 decimals in between.
pub fn target_grid(lo: &str, hi: &str, points: usize) -> Result<Vec<String>, String> {
    let bad = |s: &str| format!("'{s}' is not a decimal number");
    let a = parse_rational(lo).ok_or_else(|| bad(lo))?;
    let b = parse_rational(hi).ok_or_else(|| bad(hi))?;
    Ok((0..points)
        .map(|i| {
            if i == 0 {
                return lo.to_string();
            }
            if i + 1 == points {
                return hi.to_string();
            }
            let x = Rational::from(&b - &a) * Rational::from(i) / Rational::from(points - 1) + &a;
            // the grid point rounded to 4 decimals, written exactly (k/10⁴ through a double
            // read 0.44999999999999996 for 0.45)
            let k = (x * Rational::from(10_000)).round().numer().clone();
            let (q, r) = k.clone().abs().div_rem(rug::Integer::from(10_000));
            let sign = if k < 0 { "-" } else { "" };
            let frac = format!("{r:04}");
            let frac = frac.trim_end_matches('0');
            if frac.is_empty() {
                format!("{sign}{q}")
            } else {
                format!("{sign}{q}.{frac}")
            }
        })
        .collect())
}

/// The double nearest the decimal `s`, moved outward (`Down` for a lower end) when it lies
/// inside the decimal's value: the paving then covers the whole range as written.
fn outward(s: &str, dir: Rounding) -> Result<f64, String> {
    let r = parse_rational(s).ok_or_else(|| format!("'{s}' is not a decimal number"))?;
    let x = r.to_f64();
    let rx = Rational::from_f64(x).ok_or("not finite")?;
    Ok(match dir {
        Rounding::Up if rx < r => x.next_up(),
        Rounding::Down if rx > r => x.next_down(),
        _ => x,
    })
}

/// One formula over a range of targets: its proved points on the grid and the paving of the
/// range (its ends rounded outward to doubles) by the verdict on |e − e*| ≤ tol.
#[derive(Clone, Debug)]
pub struct FormulaStudy {
    pub formula: DampingFormula,
    /// (e* as written, its proved point).
    pub points: Vec<(String, FormulaPoint)>,
    pub segments: Vec<Segment>,
}

/// [`evaluate`] on [`target_grid`]`(lo, hi, points)` and [`pave_within`] over [lo, hi] for each
/// formula, in parallel over the formulas (0 < lo < hi < 1, decimals).
pub fn study(
    formulas: &[DampingFormula],
    lo: &str,
    hi: &str,
    points: usize,
    tol: &Big,
    min_width: f64,
) -> Result<Vec<FormulaStudy>, String> {
    let grid = target_grid(lo, hi, points)?;
    let (plo, phi) = (outward(lo, Rounding::Down)?, outward(hi, Rounding::Up)?);
    formulas
        .par_iter()
        .map(|&f| {
            let points = grid
                .iter()
                .map(|t| {
                    if crate::engines::cancel::requested() {
                        return Err("stopped: a cancellation was requested".to_string());
                    }
                    let e = Big::parse_decimal(t)?;
                    evaluate(f, &e)
                        .map(|p| (t.clone(), p))
                        .map_err(|m| format!("{} at e* = {t}: {m}", f.key()))
                })
                .collect::<Result<Vec<_>, _>>()?;
            Ok(FormulaStudy {
                formula: f,
                points,
                segments: pave_within(f, plo, phi, tol, min_width),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid's inner points are the 4-decimal values themselves (helper-21's audit: through
    /// a double they read 0.44999999999999996 and 0.13329999999999997).
    #[test]
    fn grid_targets_are_written_exactly() {
        let g = target_grid("0.05", "0.95", 7).unwrap();
        assert_eq!(g, ["0.05", "0.2", "0.35", "0.5", "0.65", "0.8", "0.95"]);
        let g = target_grid("0.1", "0.9", 7).unwrap();
        assert_eq!(g[1], "0.2333");
        assert_eq!(target_grid("0", "1", 3).unwrap(), ["0", "0.5", "1"]);
    }

    fn dec(s: &str) -> Big {
        Big::parse_decimal(s).unwrap()
    }

    #[test]
    fn the_bracket_is_tight_and_holds_the_small_damping_limit() {
        let e = cor_of_sigma(&dec("0.001")).unwrap();
        assert!(e.wid_f64() < 1e-30, "width {}", e.wid_f64());
        // e = 1 − 2σ/3 + O(σ²)
        assert!((e.mid() - (1.0 - 2e-3 / 3.0)).abs() < 1e-6);
    }

    #[test]
    fn the_exact_damping_reproduces_its_target() {
        for t in ["0.05", "0.3", "0.5", "0.9", "0.99"] {
            let p = evaluate(DampingFormula::CarvalhoMartins, &dec(t)).unwrap();
            assert!(p.e.encloses(&dec(t)), "{t}: {:?}", p.e);
            assert!(p.error.wid_f64() < 1e-25);
        }
    }

    #[test]
    fn wide_damping_ranges_are_enclosed_not_refused() {
        let s = Big::parse_decimal("0.5..0.6").unwrap();
        let e = cor_of_sigma(&s).unwrap();
        let a = cor_of_sigma(&dec("0.5")).unwrap();
        let b = cor_of_sigma(&dec("0.6")).unwrap();
        assert!(e.encloses(&a) && e.encloses(&b));
    }

    #[test]
    fn the_exact_damping_over_a_range_holds_both_ends() {
        let s = exact_sigma(&Big::parse_decimal("0.5..0.6").unwrap()).unwrap();
        let a = exact_sigma(&dec("0.5")).unwrap();
        let b = exact_sigma(&dec("0.6")).unwrap();
        assert!(s.encloses(&a) && s.encloses(&b), "{s:?}");
    }

    #[test]
    fn bad_damping_is_refused() {
        assert!(cor_of_sigma(&dec("0")).is_err());
        assert!(cor_of_sigma(&dec("-1")).is_err());
        assert!(exact_sigma(&dec("1")).is_err());
    }

    #[test]
    fn the_paving_covers_the_range_in_order() {
        let tol = dec("0.001");
        let segs = pave_within(DampingFormula::LankaraniNikravesh, 0.5, 0.99, &tol, 1e-6);
        assert_eq!(segs.first().unwrap().lo, 0.5);
        assert_eq!(segs.last().unwrap().hi, 0.99);
        for w in segs.windows(2) {
            assert_eq!(w[0].hi, w[1].lo);
            assert_ne!(w[0].verdict, w[1].verdict);
        }
        // LN is accurate for e* → 1 and off by far more than 1e-3 at 0.5
        assert_eq!(segs.last().unwrap().verdict, Verdict::Within);
        assert_eq!(segs.first().unwrap().verdict, Verdict::Outside);
    }
}
