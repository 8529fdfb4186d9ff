//! The rigorous engine at a chosen precision: T_s and e proved to D digits on intervals over
//! MPFR floats ([`Mpi`]), the same algorithm as the f64-interval engine
//! ([`crate::engines::taylor`], generic over [`crate::arith::Enclosure`]).
//!
//! **Precision.** D digits need about D·log₂10 ≈ 3.33·D bits for the result plus what the
//! integration loses (the widths grow by ~10²–10³ over a CoR, rounding errors add up over
//! ~10³ steps): the engine runs at the smallest tier of [`TIERS`] with
//! BITS ≥ ⌈3.33·D⌉ + [`MARGIN_BITS`] (D = 30: 128 bits, D = 60: 256 bits, D ≤ 100: 384).
//!
//! **Tunables follow the precision** ([`options_for_digits`]), with the f64 engine's (D ≈ 15)
//! as the anchor:
//! - tol = 10^−(D+3) per step (f64: 10⁻¹⁵ gives e ≈ 10⁻¹³ wide: the width ends ~100× tol);
//! - cross_tol = 10^−(D+4), a decade below tol (f64: 10⁻¹⁶);
//! - the Taylor order K = max(16, D): the cost of a step grows like K², the number of steps
//!   like tol^(−1/K); K ≈ −ln(tol)/2 balances the two (16 at D ≈ 15, as measured there);
//! - low-order steps (across the branch points X = Z = 0) add width ≈ h² (the first-order
//!   form: τ·f(Y) with f varying ≈ L·h|f| over the a-priori box) and ≈ h^(1+a) (a branch
//!   exponent): min_taylor_step = √cross_tol (f64: 10⁻⁸), the first trial low_order_step
//!   10× that, and the shortest tried 10⁻¹⁸ (the step ends are doubles: near T ≈ 3 a step
//!   cannot be shorter than ≈ 4.4·10⁻¹⁶, which bounds what a crossing adds, see below);
//! - event_slack, horizon, max_width as given; max_steps ×10.
//!
//! **Limit of the f64 step times.** The times of step boundaries are doubles, so a low-order
//! step across a branch point or a kink away from T = 0 is at least an ulp of T long
//! (≈ 2–4·10⁻¹⁶ at T ≈ 1–3) and adds at least ≈ that squared to the width: about 10⁻³¹.
//! Beyond f64 the engine therefore crosses the branch points, the kinks and the start by the
//! singular step on MPFR intervals ([`crate::engines::taylor::singular`], tunables
//! `SingularOptions::at_precision`: M = max(7, ⌈(D + 3)/7⌉), trigger distance tol^(1/M)):
//! measured on the four Table 1 sets at v0 = 1, one thread, 30 digits in 0.96–1.63 s, 40 in
//! 1.9–3.5 s, 60 in 5.2–8.8 s (SHC DSS: 80 digits in 22 s, 100 in 65 s).
//!
//! **Beyond f64's range.** Near a branch point the Taylor coefficients of order K grow like
//! dist^−K: at 60 digits (K = 60) ≈ 10³⁰⁰ a few 10⁻⁶ from the start, so the step-size
//! estimates and remainder widths are taken through log₂ where an f64 ratio would overflow
//! or underflow (an underflowed tol/|x_K| had made every step "too short" there).

use crate::arith::mpfr::Mpi;
use crate::engines::taylor::{RigorError, TaylorOptions, integrate_to_separation};
use crate::models::scaling::nd_from_base;
use crate::models::{CollisionModel, Maxwell, ModelKind, NdParams, Shc};
use crate::observables::decimal::{Rounding, directed_rational};
use crate::observables::rigorous::rigorous_impact;
use rug::{Float, Rational};

/// The precisions the engine is compiled at (bits of the MPFR ends).
pub const TIERS: [u32; 4] = [128, 192, 256, 384];
/// Bits beyond ⌈D·log₂10⌉ for what the integration loses (measured: see the module doc).
pub const MARGIN_BITS: u32 = 24;
/// The most digits asked for (the largest tier holds ≈ 115).
pub const MAX_DIGITS: u32 = 100;

/// The tier for D digits: the smallest with BITS ≥ ⌈3.33·D⌉ + margin; `None` for D = 0 or
/// D > [`MAX_DIGITS`].
pub fn bits_for_digits(digits: u32) -> Option<u32> {
    if digits == 0 || digits > MAX_DIGITS {
        return None;
    }
    let need = (digits as f64 * std::f64::consts::LOG2_10).ceil() as u32 + MARGIN_BITS;
    TIERS.iter().copied().find(|&b| b >= need)
}

/// The engine's tunables for D digits (the rule of the module doc), from `base` (its horizon,
/// max_width, event_slack, qr and mean-value orders are kept).
pub fn options_for_digits(digits: u32, base: &TaylorOptions) -> TaylorOptions {
    let d = digits as i32;
    let tol = 10f64.powi(-(d + 3));
    let cross_tol = 10f64.powi(-(d + 4));
    let min_taylor_step = cross_tol.sqrt();
    TaylorOptions {
        order: (digits as usize).max(16),
        tol,
        cross_tol,
        min_taylor_step,
        low_order_step: 10.0 * min_taylor_step,
        min_low_order_step: 1e-18,
        max_steps: base.max_steps * 10,
        ..base.clone()
    }
}

/// A proved T_s and e at a precision: the exact ends of the enclosures.
#[derive(Clone, Debug)]
pub struct PreciseEnclosure {
    /// The precision the proof ran at (bits of the MPFR ends).
    pub bits: u32,
    pub ts: [Rational; 2],
    pub e: [Rational; 2],
    /// Pieces of the proved flow.
    pub pieces: usize,
}

impl PreciseEnclosure {
    /// hi − lo of T_s, exactly.
    pub fn width_ts(&self) -> Rational {
        Rational::from(&self.ts[1] - &self.ts[0])
    }
    /// hi − lo of e, exactly.
    pub fn width_e(&self) -> Rational {
        Rational::from(&self.e[1] - &self.e[0])
    }
}

fn ends<const B: u32>(x: &Mpi<B>) -> Option<[Rational; 2]> {
    Some([x.inf().to_rational()?, x.sup().to_rational()?])
}

/// [`integrate_to_separation`] on `Mpi<B>` for a model built at that precision.
pub fn rigorous_impact_mp<const B: u32, M: CollisionModel<Mpi<B>, N> + Sync, const N: usize>(
    model: &M,
    opts: &TaylorOptions,
) -> Result<PreciseEnclosure, RigorError> {
    let (flow, ev) = integrate_to_separation::<Mpi<B>, M, N>(model, opts)?;
    match (ends(&ev.ts), ends(&ev.e)) {
        (Some(ts), Some(e)) => Ok(PreciseEnclosure {
            bits: B,
            ts,
            e,
            pieces: flow.len(),
        }),
        _ => Err(RigorError {
            reason: "the enclosure of T_s or e is unbounded".into(),
            t: flow.t_end(),
            width: f64::INFINITY,
        }),
    }
}

/// The parameters of a case as written: what is enclosed anew at each precision.
#[derive(Clone, Debug)]
pub enum ParamText {
    /// A nondimensional set P = (B, Γ, κ, σ, n, p), e.g. `"1e-300,0,0.5,12,1.5,1.5"`.
    Nd(String),
    /// A base set P* and an impact speed v0 [m/s], mapped by 𝓟(P*, v0).
    Base { base: String, v0: String },
}

impl ParamText {
    /// The parameters enclosed in the number type `R`.
    pub fn params<R: crate::arith::Real>(&self, kind: ModelKind) -> Result<NdParams<R>, String> {
        match self {
            ParamText::Nd(t) => NdParams::<R>::parse(kind, t).map_err(|e| e.0),
            ParamText::Base { base, v0 } => {
                let b = NdParams::<R>::parse(kind, base).map_err(|e| e.0)?;
                let v = R::parse_decimal(v0.trim())?;
                nd_from_base(kind, &b, &v).map_err(|e| e.0)
            }
        }
    }
}

fn prove_at<const B: u32>(
    kind: ModelKind,
    p: &ParamText,
    opts: &TaylorOptions,
) -> Result<PreciseEnclosure, RigorError> {
    let params = p.params::<Mpi<B>>(kind).map_err(|reason| RigorError {
        reason,
        t: 0.0,
        width: 0.0,
    })?;
    match kind {
        ModelKind::Shc => rigorous_impact_mp::<B, _, 3>(&Shc::new(params), opts),
        ModelKind::Maxwell => rigorous_impact_mp::<B, _, 4>(&Maxwell::new(params), opts),
    }
}

/// Proves T_s and e of a case at precision `bits` (one of [`TIERS`]) with the tunables `opts`.
pub fn rigorous_impact_bits(
    kind: ModelKind,
    p: &ParamText,
    bits: u32,
    opts: &TaylorOptions,
) -> Result<PreciseEnclosure, RigorError> {
    match bits {
        128 => prove_at::<128>(kind, p, opts),
        192 => prove_at::<192>(kind, p, opts),
        256 => prove_at::<256>(kind, p, opts),
        384 => prove_at::<384>(kind, p, opts),
        _ => Err(RigorError {
            reason: format!("no engine at {bits} bits (tiers: {TIERS:?})"),
            t: 0.0,
            width: 0.0,
        }),
    }
}

/// Proves T_s and e of a case to D digits: at the tier [`bits_for_digits`]`(D)` with the
/// tunables [`options_for_digits`]`(D, base)`.
pub fn rigorous_impact_digits(
    kind: ModelKind,
    p: &ParamText,
    digits: u32,
    base: &TaylorOptions,
) -> Result<PreciseEnclosure, RigorError> {
    let bits = bits_for_digits(digits).ok_or_else(|| RigorError {
        reason: format!("{digits} digits: 1 ≤ D ≤ {MAX_DIGITS}"),
        t: 0.0,
        width: 0.0,
    })?;
    rigorous_impact_bits(kind, p, bits, &options_for_digits(digits, base))
}

/// [`rigorous_impact_digits`], never proving less than the f64-interval engine: where the
/// precise run fails (but not for lack of time), the case is proved at f64 precision and that
/// enclosure returned (`bits` 53) with the precise run's error beside it — a proof with fewer
/// digits, never "not proved" where the double-precision engine proves.
pub fn rigorous_impact_digits_or_f64(
    kind: ModelKind,
    p: &ParamText,
    digits: u32,
    base: &TaylorOptions,
) -> Result<(PreciseEnclosure, Option<RigorError>), RigorError> {
    let precise = match rigorous_impact_digits(kind, p, digits, base) {
        Ok(enc) => return Ok((enc, None)),
        // no separation before the horizon is proved (a result, not a failure to retry)
        Err(e) if e.out_of_time() || base.out_of_time() || e.no_separation() => return Err(e),
        Err(e) => e,
    };
    let params = p
        .params::<inari::Interval>(kind)
        .map_err(|reason| RigorError {
            reason,
            t: 0.0,
            width: 0.0,
        })?;
    let f64_run = match kind {
        ModelKind::Shc => {
            rigorous_impact(&Shc::new(params), base).map(|r| (r.ts, r.e, r.flow.len()))
        }
        ModelKind::Maxwell => {
            rigorous_impact(&Maxwell::new(params), base).map(|r| (r.ts, r.e, r.flow.len()))
        }
    };
    let (ts, e, pieces) = match f64_run {
        Ok(r) => r,
        // no separation before the horizon, proved by the f64-interval engine: a result
        Err(e) if e.no_separation() => return Err(e),
        Err(_) => return Err(precise),
    };
    let ends = |x: inari::Interval| -> Option<[Rational; 2]> {
        Some([Rational::from_f64(x.inf())?, Rational::from_f64(x.sup())?])
    };
    match (ends(ts), ends(e)) {
        (Some(ts), Some(e)) => Ok((
            PreciseEnclosure {
                bits: 53,
                ts,
                e,
                pieces,
            },
            Some(precise),
        )),
        _ => Err(precise),
    }
}

/// One rung of the precision fallback: the precision and the digits whose tunables
/// ([`options_for_digits`]) it runs with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rung {
    pub bits: u32,
    pub digits: u32,
}

/// The rungs tried after the f64-interval engine (53-bit ends) could not decide a case, in
/// order: f64 runs at tol 10⁻¹⁵ (results ≈ 10⁻¹³ wide); 128 bits with the tunables of 16
/// digits (tol 10⁻¹⁹), 192 bits with 24 (10⁻²⁷), 256 bits with 26 (10⁻²⁹).
///
/// Why 26 and not more (measured on SHC (1.43, −1.42, 0.632, 0.00715, 1.31, 1.27) at 256
/// bits, `examples/rung.rs`): D = 24 proves in 1.9 s (e 4.8·10⁻²⁶ wide), D = 26 in 4.5 s
/// (7.5·10⁻²⁸); D = 28 fails at T ≈ 1.6 ("cannot cross a switching surface": a low-order
/// step across Z = 0 adds ≈ h^(1+a) with h at least an ulp of T), and D = 30 does not leave the
/// start X = Z = 0 in 30 s — the branch points without singular expansions (issue #15).
pub const LADDER: [Rung; 3] = [
    Rung {
        bits: 128,
        digits: 16,
    },
    Rung {
        bits: 192,
        digits: 24,
    },
    Rung {
        bits: 256,
        digits: 26,
    },
];

/// The longest stretch of time on which the fallback lets the separation condition stay
/// undecided before it is proved (f64: [`TaylorOptions::event_slack`], 10⁻³): the T_s
/// enclosure is then that wide. Near a Hunt–Crossley separation F = |X|^p(1 − σV) vanishes
/// like |X|^p·(1 − σV) as X → 0 and is below any width for a while (σ = 50 at 192 bits:
/// 1.02·10⁻³).
pub const FALLBACK_EVENT_SLACK: f64 = 1e-2;

/// The budget of the precision fallback.
#[derive(Clone, Debug, PartialEq)]
pub struct FallbackBudget {
    /// The highest precision tried (bits; below 128 the fallback is off).
    pub max_bits: u32,
    /// Wall-clock seconds per rung: a run still going then stops ([`TaylorOptions::deadline`])
    /// and the fallback ends there (a higher precision is slower still).
    pub seconds: f64,
}

impl Default for FallbackBudget {
    /// All three rungs, 60 s each (measured: the Hunt–Crossley σ = 30 case decides at 128 bits
    /// in ≈ 7 s, see [`decide`]).
    fn default() -> Self {
        Self {
            max_bits: 256,
            seconds: 60.0,
        }
    }
}

impl FallbackBudget {
    /// No fallback.
    pub fn off() -> Self {
        Self {
            max_bits: 0,
            seconds: 0.0,
        }
    }
}

/// One run of the engine at a precision, and how it ended.
#[derive(Clone, Debug)]
pub struct Attempt {
    pub bits: u32,
    pub seconds: f64,
    /// `None`: proved.
    pub error: Option<RigorError>,
}

/// What the precision fallback found: the enclosure of the first rung that proved the case,
/// and every run it made.
#[derive(Clone, Debug)]
pub struct Decision {
    pub enclosure: Option<PreciseEnclosure>,
    pub attempts: Vec<Attempt>,
}

impl Decision {
    /// Why no rung proved the case (the last run's reason), if none did.
    pub fn why_not(&self) -> Option<String> {
        if self.enclosure.is_some() {
            return None;
        }
        Some(match self.attempts.last() {
            None => "no higher precision was tried".into(),
            Some(a) => format!(
                "at {} bits: {}",
                a.bits,
                a.error.as_ref().map_or("?".into(), |e| e.to_string())
            ),
        })
    }
}

/// The precision fallback: after the f64-interval engine failed with `first`, the case is
/// run again on [`LADDER`]'s rungs up to `budget.max_bits`, each within `budget.seconds`,
/// until one proves it, one fails for a reason a higher precision cannot remove
/// ([`RigorError::precision_may_help`], e.g. the time budget), or the rungs run out. Nothing
/// is tried when `first` is not such a failure either. Each rung stops at its own budget or
/// at `base`'s deadline, whichever comes first; none starts after that deadline.
///
/// Why it decides cases: the separation condition F ≤ 0 ∧ V ≥ 0 is decided only where F's
/// enclosure excludes 0. Near a Hunt–Crossley separation F = |X|^p(1 − σV) with 1 − σV
/// decaying like exp(−σ∫|X|^p): at σ = 30 it is ≈ 10⁻¹² near T = 8.8, below what the f64
/// enclosure (≈ 10⁻¹³ wide) resolves, and 128 bits decide it (measured: 7 s).
pub fn decide(
    kind: ModelKind,
    p: &ParamText,
    first: &RigorError,
    base: &TaylorOptions,
    budget: &FallbackBudget,
) -> Decision {
    let mut out = Decision {
        enclosure: None,
        attempts: Vec::new(),
    };
    if !first.precision_may_help() {
        return out;
    }
    for rung in LADDER.iter().filter(|r| r.bits <= budget.max_bits) {
        if base.out_of_time() {
            break;
        }
        let start = std::time::Instant::now();
        // the rung's own budget, within the caller's deadline
        let own = start + std::time::Duration::from_secs_f64(budget.seconds.max(0.0));
        let opts = TaylorOptions {
            deadline: Some(base.deadline.map_or(own, |d| d.min(own))),
            event_slack: base.event_slack.max(FALLBACK_EVENT_SLACK),
            ..options_for_digits(rung.digits, base)
        };
        let r = rigorous_impact_bits(kind, p, rung.bits, &opts);
        out.attempts.push(Attempt {
            bits: rung.bits,
            seconds: start.elapsed().as_secs_f64(),
            error: r.as_ref().err().cloned(),
        });
        match r {
            Ok(enc) => {
                out.enclosure = Some(enc);
                break;
            }
            Err(e) if !e.precision_may_help() => break,
            Err(_) => {}
        }
    }
    out
}

/// The ends of an exact enclosure rounded outward to doubles (lo down, hi up): an inari
/// interval containing it.
pub fn outward_f64(ends: &[Rational; 2]) -> Option<inari::Interval> {
    use rug::float::Round;
    // (rounded twice in the same direction: to 53 bits, then into the double's range)
    let lo = Float::with_val_round(53, &ends[0], Round::Down).0;
    let hi = Float::with_val_round(53, &ends[1], Round::Up).0;
    inari::Interval::try_from((lo.to_f64_round(Round::Down), hi.to_f64_round(Round::Up))).ok()
}

/// How many significant digits of [lo, hi] to print: every digit the width allows, i.e. up to
/// the first decade of the width (two more than where lo and hi part), at most what `bits`
/// hold.
pub fn digits_shown(lo: &Rational, hi: &Rational, bits: u32) -> usize {
    let most = (bits as f64 * std::f64::consts::LOG10_2).floor() as usize;
    let mag = Float::with_val(64, lo.clone().abs()).max(&Float::with_val(64, hi.clone().abs()));
    let w = Float::with_val(64, Rational::from(hi - lo));
    if mag.is_zero() {
        return 1;
    }
    if w.is_zero() {
        return most;
    }
    let d = (mag / w).log10().to_f64().ceil() as i64 + 2;
    d.clamp(1, most as i64) as usize
}

/// [lo, hi] as two scientific decimals with [`digits_shown`] digits, lo rounded down and hi
/// up (printed bounds are bounds).
pub fn outward_text(ends: &[Rational; 2], bits: u32) -> (String, String) {
    let d = digits_shown(&ends[0], &ends[1], bits);
    (
        directed_rational(&ends[0], d, Rounding::Down).scientific(d),
        directed_rational(&ends[1], d, Rounding::Up).scientific(d),
    )
}

/// A width as a short decimal rounded up (3 digits).
pub fn width_text(w: &Rational) -> String {
    directed_rational(w, 3, Rounding::Up).scientific(3)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiers_follow_the_digits() {
        assert_eq!(bits_for_digits(0), None);
        assert_eq!(bits_for_digits(1), Some(128));
        assert_eq!(bits_for_digits(30), Some(128));
        assert_eq!(bits_for_digits(31), Some(128));
        assert_eq!(bits_for_digits(32), Some(192));
        assert_eq!(bits_for_digits(60), Some(256));
        assert_eq!(bits_for_digits(100), Some(384));
        assert_eq!(bits_for_digits(101), None);
    }

    #[test]
    fn doubles_of_an_exact_enclosure_are_rounded_outward() {
        // 1/3 ± 10⁻³⁰: both ends round to the same nearest double, on one side of 1/3
        let third = Rational::from((1, 3));
        let tiny = Rational::from((1, 10u128.pow(30)));
        let ends = [
            Rational::from(&third - &tiny),
            Rational::from(&third + &tiny),
        ];
        let x = outward_f64(&ends).unwrap();
        let (lo, hi) = (
            Rational::from_f64(x.inf()).unwrap(),
            Rational::from_f64(x.sup()).unwrap(),
        );
        assert!(lo <= ends[0] && ends[1] <= hi, "{x:?}");
        // and no wider than the next doubles out
        assert!(
            x.inf() < x.sup() && x.sup() - x.inf() < 2.0 * f64::EPSILON,
            "{x:?}"
        );
        // negative ends too
        let neg = [Rational::from(-&ends[1]), Rational::from(-&ends[0])];
        let y = outward_f64(&neg).unwrap();
        assert!(
            Rational::from_f64(y.inf()).unwrap() <= neg[0]
                && neg[1] <= Rational::from_f64(y.sup()).unwrap(),
            "{y:?}"
        );
    }

    #[test]
    fn printed_ends_are_outward_and_as_long_as_the_width_allows() {
        let lo = Rational::from((1, 3)) - Rational::from((1, 1_000_000_000_000u64));
        let hi = Rational::from((1, 3)) + Rational::from((1, 1_000_000_000_000u64));
        let (l, h) = outward_text(&[lo.clone(), hi.clone()], 128);
        let (lr, hr) = (
            crate::observables::decimal::parse_rational(&l).unwrap(),
            crate::observables::decimal::parse_rational(&h).unwrap(),
        );
        assert!(lr <= lo && hi <= hr, "{l} {h}");
        // width 2e-12 around 1/3: 12 digits part them, two more are shown
        assert_eq!(digits_shown(&lo, &hi, 128), 14);
        assert!(l.starts_with("3.3333333333") && h.starts_with("3.3333333333"));
    }
}

#[cfg(test)]
mod floor_tests {
    use super::*;

    /// `--digits` never proves less than the f64-interval engine: a case the precise run
    /// cannot prove (SHC with n = p = 1 at 60 digits: only kinks, which the MPFR engine does
    /// not cross within 10⁻⁶⁴, "cannot cross a switching surface") still gets the f64
    /// enclosure, with the precise run's error beside it; that enclosure holds the one proved
    /// at 30 digits (where the low-order last resorts do cross).
    #[test]
    fn digits_fall_back_to_the_f64_proof() {
        let p = ParamText::Nd("1,0,0.5,1,1,1".into());
        let opts = TaylorOptions::default();
        assert!(rigorous_impact_digits(ModelKind::Shc, &p, 60, &opts).is_err());
        let (enc, why) =
            rigorous_impact_digits_or_f64(ModelKind::Shc, &p, 60, &opts).expect("f64 proves");
        assert_eq!(enc.bits, 53);
        assert!(why.is_some_and(|e| e.reason.starts_with("cannot cross")));
        let (d30, why) = rigorous_impact_digits_or_f64(ModelKind::Shc, &p, 30, &opts).unwrap();
        assert!(d30.bits == 128 && why.is_none());
        assert!(enc.e[0] <= d30.e[0] && d30.e[1] <= enc.e[1]);
        assert!(enc.ts[0] <= d30.ts[0] && d30.ts[1] <= enc.ts[1]);
    }
}
