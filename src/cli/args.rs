//! The command line: clap definitions and the long help texts.

use bwcl::models::ModelKind;
use clap::builder::RangedU64ValueParser;
use clap::{ArgGroup, Args, Parser, Subcommand, ValueEnum};
use std::ops::RangeInclusive;
use std::path::PathBuf;

/// Taylor orders of the rigorous engine: below 2 it cannot step; each order costs O(K²) per
/// step, and past 40 the steps stop growing (the default 16 measured fastest).
pub const ORDER: RangeInclusive<u64> = 2..=40;
/// Sub-ranges of a v0 range (each a proof: some 40 ms on the DSS set).
pub const PIECES: RangeInclusive<u64> = 1..=1024;
/// Digits of `cor --rigorous --digits`: with the singular step on MPFR intervals, measured on
/// the four Table 1 sets at v0 = 1 (one thread): 30 digits in ≈ 1–1.6 s, 40 in ≈ 2–3.5 s, 60 in
/// ≈ 5–9 s; SHC DSS 80 digits in 22 s, 100 in 65 s. 100 is the largest tier's reach
/// ([`crate::observables::precision::MAX_DIGITS`]).
pub const DIGITS: RangeInclusive<u64> = 1..=100;
/// Sample times of `trajectory` and `loop`.
pub const POINTS: RangeInclusive<u64> = 2..=100_000;
/// Random starts of `fit` (each about 3 s on 20 speeds).
pub const STARTS: RangeInclusive<u64> = 0..=256;
/// Nelder–Mead iterations per run of `fit`.
pub const MAX_ITER: RangeInclusive<u64> = 1..=10_000;
/// Largest --horizon and --t-end (nondimensional time; the engines cap their steps too).
pub const T_MAX: f64 = 1e6;
/// Smallest --max-step of DOP853 (its 10⁶ steps then cover T = 10⁻³).
pub const MIN_MAX_STEP: f64 = 1e-9;

/// A decimal (no NaN) as clap reads an option value.
fn decimal(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|x| !x.is_nan())
        .ok_or_else(|| "not a decimal number".to_string())
}

/// --error: a finite number > 0 as a double (a decimal that underflows to 0 is said to).
fn error_bound(s: &str) -> Result<f64, String> {
    let e = decimal(s)?;
    if e.is_finite() && e > 0.0 {
        Ok(e)
    } else if bwcl::arith::float::read_as_zero(s, e) {
        Err("must be a finite number > 0 (this one is below the smallest positive double)".into())
    } else {
        Err("must be a finite number > 0".into())
    }
}

/// --horizon and --t-end: (0, T_MAX].
fn time(s: &str) -> Result<f64, String> {
    let t = decimal(s)?;
    if t > 0.0 && t <= T_MAX {
        Ok(t)
    } else {
        Err(format!("must be a number in (0, {T_MAX:e}]"))
    }
}

/// --fallback-bits: 0, 128, 192 or 256.
fn fallback_bits(s: &str) -> Result<u32, String> {
    match s.trim() {
        "0" => Ok(0),
        "128" => Ok(128),
        "192" => Ok(192),
        "256" => Ok(256),
        _ => Err("must be one of 0 (off), 128, 192, 256".into()),
    }
}

/// --fallback-seconds: (0, 3600].
fn fallback_seconds(s: &str) -> Result<f64, String> {
    let t = decimal(s)?;
    if t > 0.0 && t <= 3600.0 {
        Ok(t)
    } else {
        Err("must be a number in (0, 3600]".into())
    }
}

/// Default of --time-limit (seconds): the longest documented proofs (the band over [0.1, 5] at
/// 1e-6, --digits 100) take about a minute on a 2-core machine.
pub const TIME_LIMIT: f64 = 300.0;
/// Largest --time-limit (a day).
pub const MAX_TIME_LIMIT: f64 = 86_400.0;

/// --time-limit: (0, MAX_TIME_LIMIT].
fn time_limit(s: &str) -> Result<f64, String> {
    let t = decimal(s)?;
    if t > 0.0 && t <= MAX_TIME_LIMIT {
        Ok(t)
    } else {
        Err(format!(
            "must be a number of seconds in (0, {MAX_TIME_LIMIT}]"
        ))
    }
}

/// --thickness: [1e-14, 1].
fn thickness(s: &str) -> Result<f64, String> {
    let t = decimal(s)?;
    if (1e-14..=1.0).contains(&t) {
        Ok(t)
    } else {
        Err("must be a number in [1e-14, 1]".into())
    }
}

/// --rtol: [100 ε, 1).
fn rtol(s: &str) -> Result<f64, String> {
    let r = decimal(s)?;
    if (100.0 * f64::EPSILON..1.0).contains(&r) {
        Ok(r)
    } else {
        Err(format!(
            "must be a number in [100 ε, 1) = [{:e}, 1)",
            100.0 * f64::EPSILON
        ))
    }
}

/// --atol: (0, 1]. DOP853 scales the error of a component by atol + rtol·|y|, which is 0 for
/// a component at 0 (the states start there) when atol = 0.
fn atol(s: &str) -> Result<f64, String> {
    let a = decimal(s)?;
    if a > 0.0 && a <= 1.0 {
        Ok(a)
    } else {
        Err("must be a number in (0, 1]".into())
    }
}

/// --max-step: [MIN_MAX_STEP, ∞].
fn max_step(s: &str) -> Result<f64, String> {
    let h = decimal(s)?;
    if h >= MIN_MAX_STEP {
        Ok(h)
    } else {
        Err(format!("must be a number ≥ {MIN_MAX_STEP:e} (or inf)"))
    }
}

/// A whole number in `range`, as usize.
fn count(range: RangeInclusive<u64>) -> RangedU64ValueParser<usize> {
    RangedU64ValueParser::<usize>::new().range(range)
}

const ABOUT: &str =
    "Separation time T_s and coefficient of restitution e of the Bouc–Wen collision models";

const LONG_ABOUT: &str = "\
Separation time T_s and coefficient of restitution (CoR) e of the Bouc–Wen collision models of
Milehins & Marghitu: the Bouc–Wen–Simon–Hunt–Crossley model (--model shc, NDBWSHCCM) and the
Bouc–Wen–Maxwell model (--model maxwell, NDBWMCM), computed with a DOP853 integrator (the
paper's SciPy settings) or, with --rigorous, proved enclosures from an interval Taylor engine.

T_s = inf{T ≥ 0 : F ≤ 0 and V ≥ 0} (first time the contact force vanishes while the bodies
move apart) and e = V(T_s), both nondimensional (T = t/T_c, V = v/v0).

Exit codes: 0 success, 1 a case not proved (--rigorous) or an integration failure,
2 bad input (the message names the offending value).";

/// The parameter section shared by the subcommands' long help (a macro so that `concat!` can
/// join it with the examples).
macro_rules! parameters_help {
    () => {
        "\
PARAMETERS (exactly one of --base, --nd, --physical):

  --nd B,Γ,κ,σ,n,p        a nondimensional set P (one case; the impact speed is built in)
  --base B,Γ,κ,σ_b,n,p    base parameters P* (the set at v0 = 1 m/s), with --v0
  --physical m=…,k=…,…    physical (SI) parameters, with --v0

  B   hysteresis shape: the Bouc–Wen β scaled,
      B = (A^(p+1)/D)^(n/(p+1)) (β/A) (m/k)^(n/(p+1)) v0^(2n/(p+1)),  B > 0
  Γ   hysteresis shape: the Bouc–Wen γ scaled as β,                   Γ ∈ (−B, B)
  κ   elastic share κ = α/(α + α_c A^p), α_c = 1 − α,                 κ ∈ (0, 1)
  σ   damping: σ = c v0/(D k) (shc),
      σ = D^(1/(p+1)) (m^p k)^(1/(p+1)) v0^((p−1)/(p+1)) / c (maxwell), σ > 0
  n   Bouc–Wen exponent,                                              n ≥ 1
  p   Hertz exponent,                                      p ≥ 1 (maxwell: p = 1 or p ≥ 2)
      where D = α + α_c A^p.
  v0  impact speed [m/s]: the relative speed just before the collision, v0 > 0

BASE-PARAMETER MAP 𝓟(P*, v0) (sections KVCL and MCL of the paper):
  P = (B_b v0^(2n/(p+1)), Γ_b v0^(2n/(p+1)), κ, σ_b v0^s, n, p),
  s = 1 for shc, s = (p−1)/(p+1) for maxwell.

PHYSICAL PARAMETERS (--physical, keys in any order, SI units):
  m      m > 0: effective mass m1 m2/(m1 + m2) [kg]
  k      k > 0: contact stiffness [kg m^(1−p) s^−2] = [N m^−p]
  c      c > 0: damping [kg m^−p s^−1] (shc) or [kg s^−1] (maxwell)
  n      n ≥ 1: Bouc–Wen exponent [1]
  p      p ≥ 1: Hertz exponent [1] (maxwell: p = 1 or p ≥ 2)
  alpha  α ∈ (0, 1): share of the elastic Hertz term [1]
  beta   β > 0: Bouc–Wen shape parameter [m^−n]
  gamma  γ ∈ (−β, β): Bouc–Wen shape parameter [m^−n]
  A      A > 0: Bouc–Wen rate amplitude [1]
  (The paper's BWHCL also allows c = 0, β = 0 and γ = ±β; those give σ = 0, B = 0 or
  Γ = ±B, outside 𝓟, which the nondimensional models need.)
  The scales are T_c = D^(−1/(p+1)) (m/k)^(1/(p+1)) v0^(−(p−1)/(p+1)) [s],
  X_c = D^(−1/(p+1)) (m/k)^(1/(p+1)) v0^(2/(p+1)) [m].

CLASSICAL LAWS (--model hooke|hertz|hunt-crossley|kelvin-voigt|linear-maxwell), parameters
by name, n = 3/2 when not given:
  law             --physical (SI)     --nd          --base (at v0 = 1 m/s)
  hooke           m, k                ''            ''
  hertz           m, k, n             n             n
  hunt-crossley   m, k, n, chi        sigma, n      sigma_b, n
  kelvin-voigt    m, k, c             zeta          zeta
  linear-maxwell  m, k, c             c             c
  F = kδ (hooke), k|δ|^(n−1)δ (hertz), k|δ|^(n−1)δ + χ|δ|^n δ̇ (hunt-crossley), kδ + cδ̇
  (kelvin-voigt), k δ₁ = c δ̇₂ with δ = δ₁ + δ₂ (linear-maxwell); m, k > 0 [kg], [N m^−n];
  χ ≥ 0 [N s m^−(n+1)]; c ≥ 0 (kelvin-voigt), c > 0 (linear-maxwell) [N s/m]. Nondimensional:
  σ = χ v0/k = σ_b v0, ζ = c/(2√(mk)), c̃ = c/√(mk); scales L = (m v0²/k)^(1/(n+1)) [m]
  (n = 1 for the linear laws), T_c = L/v0 [s]. Separation as for the Bouc–Wen models.

Decimals are read as written: each is checked against 𝓟 exactly as a rational (κ =
0.9999999999999999 lies in (0, 1)), with --rigorous every input is enclosed exactly (0.1 is
not rounded to a double) and any value may be a range a..b (e.g. --v0 0.9..1.1).
"
    };
}

macro_rules! cor_examples {
    () => {
        "
EXAMPLES:
  The paper's DSS set (NDBWSHCCM) at v0 = 1 m/s:
    bwcl cor --model shc --base 1.43,-1.42,0.632,0.00715,1.31,1.27 --v0 1
  Several speeds, as JSON:
    bwcl cor --model shc --base 1.43,-1.42,0.632,0.00715,1.31,1.27 --v0 0.5,1,2,5 --format json
  A baseball (Table 2), physical units:
    bwcl cor --model shc --physical m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925 --v0 2.15
  Proved enclosures over a range of speeds:
    bwcl cor --model shc --base 1.43,-1.42,0.632,0.00715,1.31,1.27 --v0 0.9..1.1 --rigorous
  A classical law, physical units, proved:
    bwcl cor --model hunt-crossley --physical m=0.146,k=1e9,chi=2e8,n=1.5 --v0 1,2 --rigorous"
    };
}

macro_rules! trajectory_examples {
    () => {
        "
EXAMPLES:
    bwcl trajectory --model shc --base 1.43,-1.42,0.632,0.00715,1.31,1.27 --v0 1 --out dss.csv
    bwcl loop --model shc --physical m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925 --v0 2.15 --physical-units
    bwcl loop --model kelvin-voigt --physical m=1,k=1e6,c=200 --v0 1 --physical-units"
    };
}

macro_rules! fit_examples {
    () => {
        "
DATA: a CSV file with a header naming the columns v0 (impact speed, m/s, > 0) and e (CoR in
[0, 1]); other columns are ignored (no column may be named twice), blank lines and lines
starting with # are skipped, a UTF-8 byte-order mark is allowed. At most 4 MiB, lines of at
most 1000 characters, at most 10000 data rows.

EXAMPLES:
    bwcl fit --model shc --data paper_repro/data/synthetic_dss.csv --seed 1
    bwcl fit --model maxwell --data my.csv --p1 --format json
    bwcl cost --model shc --base 1.43,-1.42,0.632,0.00715,1.31,1.27 --data paper_repro/data/synthetic_dss.csv"
    };
}

macro_rules! identify_examples {
    () => {
        "
DATA: a CSV with the columns v0 and e, optionally sigma (the error of each e, overrides
--error), tc (contact duration in units of T_c at v0 = 1 m/s) and tc_sigma.

OUTPUT: the verdict (F proved empty, or its proved hull per parameter), the counts and volume
shares of the feasible, infeasible and undecided boxes. JSON: {\"free\": [names], \"boxes\":
[{\"lo\": [...], \"hi\": [...], \"status\": ...}], \"hull\": {...}, \"counts\": {...},
\"seconds\": ...}, every box end rounded outward. Exit 0 when the paving is complete, 1 when the
time limit or the box budget stopped it (what is reported is proved), 2 for bad input.

EXAMPLES:
    bwcl identify --model shc --data paper_repro/data/synthetic_dss.csv --error 0.02 \\
        --base 1.43,-1.42,0.632,0.00715,1.31,1.27 --bounds sigma_b=0.001..0.1,kappa=0.4..0.8
    bwcl identify --model shc --data d.csv --error 0.02 --format json --plot paving.svg \\
        --bounds B_b=0.8..1.6,Gamma_b=-1.6..1,kappa=0.5..0.7,sigma_b=0.004..0.06,n=1.1..1.4,p=1.1..1.4"
    };
}

#[derive(Parser, Debug)]
#[command(name = "bwcl", version, about = ABOUT, long_about = LONG_ABOUT)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// T_s and the coefficient of restitution e, for one or several impact speeds.
    #[command(
        long_about = "T_s and the coefficient of restitution e = V(T_s), one case per impact speed \
                      (or the one --nd set). A case without separation before the horizon is \
                      reported as such (e = 0), not as a number.",
        after_long_help = concat!(parameters_help!(), cor_examples!())
    )]
    Cor(CorArgs),
    /// The trajectory up to T_s as CSV: t, the model's states, x, v, F.
    #[command(
        long_about = "The trajectory up to T_s (or --t-end) at --points uniform times, as CSV with \
                      columns t, the model's states (X,Z,V for shc; R,Y,Z,W for maxwell), x, v, F. \
                      With --rigorous: t, <state>_lo, <state>_hi, …, x_lo, x_hi, v_lo, v_hi, F_lo, \
                      F_hi from the proved flow.",
        after_long_help = concat!(parameters_help!(), trajectory_examples!())
    )]
    Trajectory(TrajectoryArgs),
    /// The hysteresis loop (F against x) up to T_s as CSV.
    #[command(
        long_about = "The hysteresis loop up to T_s (or --t-end) as CSV: columns x,F \
                      (nondimensional), or with --physical-units x_mm,F_N (the deformation |x| in \
                      millimetres and the force in newtons, as in the paper's Fig. 4). With \
                      --rigorous: x_lo,x_hi,F_lo,F_hi.",
        after_long_help = concat!(parameters_help!(), trajectory_examples!())
    )]
    Loop(TrajectoryArgs),
    /// Identify base parameters P* from measured CoR data: minimize J (eq:J) by multi-start
    /// Nelder–Mead inside 𝓟.
    #[command(
        long_about = "Identify the base parameters P* = (B_b, Γ_b, κ, σ_b, n, p) of a model from \
                      measured CoR data (a CSV with the header v0,e): minimize \
                      J = sqrt(Σ (e_i − e(𝓟(P*, v0_i)))²) (eq:J) by Nelder–Mead from --starts \
                      seeded random points (and --init), each restarted once from its best vertex. \
                      The search runs on a smooth bijection ℝ⁶ → 𝓟 (B = exp u1, Γ = B tanh u2, \
                      κ = logistic u3, σ_b = exp u4, n = 1 + exp u5, p = 1 + exp u6, maxwell: \
                      p = 2 + exp u6), so every trial set is admissible. The Maxwell model's p = 1 \
                      is an isolated point of 𝓟 and is searched only with --p1. Prints P*, J and \
                      the fitted curve (v0, e_data, e_model); a progress bar is shown on a \
                      terminal.",
        after_long_help = fit_examples!()
    )]
    Fit(FitArgs),
    /// Evaluate the cost J (eq:J) of a base set P* on measured CoR data.
    #[command(
        long_about = "Evaluate J(v0, e, P*) = sqrt(Σ (e_i − e(𝓟(P*, v0_i)))²) (eq:J) of the base \
                      set --base on the data of --data (a CSV with the header v0,e), with the \
                      model's CoR at every measured speed.",
        after_long_help = fit_examples!()
    )]
    Cost(CostArgs),
    /// Profile J along each free parameter (the others re-optimized) with its 95 %
    /// likelihood-ratio interval.
    #[command(
        long_about = "Fit (as `fit`), then profile J along each free parameter (or --param): on a \
                      grid of --points values (the bounds, else the best fit ± 4 standard errors \
                      clipped to 𝓟, or ± 50 % where the standard error is not finite), the other \
                      free parameters re-optimized by Nelder–Mead warm-started from the \
                      neighbouring grid point. The 95 % likelihood-ratio interval is \
                      {θ : (J_p(θ)² − J_min²)/s² ≤ 3.841} (s² = J_min²/(M − k), or 1 with given \
                      errors), interpolated linearly between grid points; \"open\" where it reaches \
                      the grid's end.",
        after_long_help = fit_examples!()
    )]
    Profile(ProfileArgs),
    /// Computer-assisted proofs over ranges of parameters (see `prove monotone --help`).
    Prove(ProveArgs),
    /// Proved feasible sets of P* (set-membership identification): which base sets are
    /// consistent with CoR data known to within ±E.
    #[command(
        long_about = "Set-membership identification: pave a box of the free base parameters into \
                      boxes proved feasible (|e(𝓟(P*, v0_i)) − e_i| ≤ E_i for every data row and \
                      every P* of the box), proved infeasible (no P* of the box satisfies every \
                      row) and undecided at the resolution, with the interval Taylor engine: \
                      mean-value forms from proved slopes, used as contractors before bisecting. \
                      Prints the proved hull of the feasible set F per parameter (every P* \
                      consistent with the data lies in it); an F proved empty falsifies the model \
                      at that error. A column tc (contact duration, in units of T_c at v0 = 1 m/s) \
                      adds |tc(P*, v0_i) − tc_i| ≤ T_i. Free parameters are those given --bounds; \
                      the others are fixed by --fix or --base.",
        after_long_help = identify_examples!()
    )]
    Identify(IdentifyArgs),
    /// The classical Hunt–Crossley damping formulas χ(e*) against the CoR the law really
    /// produces, proved.
    #[command(
        long_about = "The Hunt–Crossley law F = k|δ|^(n−1)δ + χ|δ|^n δ̇ is usually tuned for a \
                      target CoR e* by a published formula χ = k·σ(e*)/v0, each derived from an \
                      approximate energy balance. Its real CoR e solves \
                      G(σe) = G(−σ), G(u) = −u − ln(1 − u), whatever n (the exact relation of \
                      Carvalho & Martins 2019): this command proves e(σ(e*)) and the error \
                      e − e* at --points targets over --e-star (128-bit interval arithmetic), \
                      and proves over the whole range where |e − e*| ≤ --tol holds, where it \
                      fails, and what stays undecided at pieces 1e-8 wide. Formulas: \
                      hunt-crossley 3(1−e)/2, herbert-mcwhannell 6(1−e)/((2e−1)²+3), lee-wang \
                      3(1−e)/4, lankarani-nikravesh 3(1−e²)/4, gonthier (1−e²)/e, zhiying-qishao \
                      3(1−e²)exp(2(1−e))/4, flores 8(1−e)/(5e), gharib-hurmuzlu 1/e−1, hu-guo \
                      3(1−e)/(2e), carvalho-martins (the exact σ).",
        after_long_help = "Examples:\n  bwcl laws\n  bwcl laws --formulas \
                           lankarani-nikravesh,flores --e-star 0.5..0.99 --points 50 --format csv"
    )]
    Laws(LawsArgs),
    /// T_s and e of a classical collision law (Hooke, Hertz, Hunt–Crossley, linear
    /// Kelvin–Voigt, linear Maxwell), nondimensional, float or proved.
    #[command(
        long_about = "T_s and e of a classical collision law on the same engines as the Bouc–Wen \
                      models, in the nondimensional form (δ = L·X, t = T·√(m/k)-type scaling, \
                      X(0) = 0, V(0) = −1): hooke X″ = −X; hertz X″ = −|X|^(n−1)X \
                      [--n, default 1.5]; hunt-crossley X″ = −|X|^(n−1)X − σ|X|^n X′ \
                      (σ = χv0/k; --sigma, --n; or σ from a published formula: --formula \
                      NAME --e-star E); kelvin-voigt X″ = −X − 2ζX′ (ζ = c/(2√(mk)); \
                      --zeta); linear-maxwell X″ = −(X − Y), Y′ = (X − Y)/c̃ (c̃ = c/√(mk); \
                      --c). Separation: T_s = inf{T ≥ 0 : F ≤ 0 ∧ V ≥ 0}, e = V(T_s) (for \
                      Hunt–Crossley the return to X = 0, for Kelvin–Voigt where the force \
                      vanishes). With --rigorous the parameters are enclosed as written.",
        after_long_help = "Examples:\n  bwcl classical --law hertz --n 1.5 --rigorous\n  \
                           bwcl classical --law hunt-crossley --sigma 0.75 --n 1.5 --rigorous\n  \
                           bwcl classical --law kelvin-voigt --zeta 0.3 --format json"
    )]
    Classical(ClassicalArgs),
    /// Every model fitted to the same CoR data: J, AIC, AICc, BIC, and with --error each
    /// classical law's proved feasible set.
    #[command(
        long_about = "Fit every model (the Bouc–Wen models and the classical laws, or --models) to \
                      the same CoR data and compare them by J and the information criteria AIC, \
                      AICc and BIC (Gaussian least squares; only differences mean anything). \
                      With --error E, each classical law's feasible set is paved with the \
                      rigorous engine: an empty one is a certificate that no law of the family \
                      fits the data to ±E, naming the rows that refute each range.",
        after_long_help = "Examples:\n  bwcl compare --data paper_repro/data/synthetic_dss.csv\n  \
                           bwcl compare --data d.csv --models hunt-crossley,kelvin-voigt --error 0.02"
    )]
    Compare(CompareArgs),
}

/// A classical collision law.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum LawArg {
    /// The linear spring: X″ = −X.
    Hooke,
    /// Hertz's law: X″ = −|X|^(n−1)X.
    Hertz,
    /// Simon–Hunt–Crossley: X″ = −|X|^(n−1)X − σ|X|^n X′.
    HuntCrossley,
    /// Linear Kelvin–Voigt: X″ = −X − 2ζX′.
    KelvinVoigt,
    /// Linear Maxwell: X″ = −(X − Y), Y′ = (X − Y)/c̃.
    LinearMaxwell,
}

#[derive(Args, Debug)]
pub struct ClassicalArgs {
    /// The law.
    #[arg(long, value_enum)]
    pub law: LawArg,
    /// Write the output to FILE instead of stdout (replaced whole, only when the command
    /// succeeded).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// The exponent n ≥ 1 (hertz, hunt-crossley) [default: 1.5].
    #[arg(long, allow_hyphen_values = true)]
    pub n: Option<String>,
    /// The damping σ = χv0/k ≥ 0 (hunt-crossley).
    #[arg(long, allow_hyphen_values = true)]
    pub sigma: Option<String>,
    /// The damping ratio ζ = c/(2√(mk)) ≥ 0 (kelvin-voigt).
    #[arg(long, allow_hyphen_values = true)]
    pub zeta: Option<String>,
    /// The dashpot c̃ = c/√(mk) > 0 (linear-maxwell).
    #[arg(long, allow_hyphen_values = true)]
    pub c: Option<String>,
    /// hunt-crossley: the damping from a published formula σ(e*) (a name of `bwcl laws
    /// --formulas`) instead of --sigma; needs --e-star.
    #[arg(long, value_name = "NAME")]
    pub formula: Option<String>,
    /// hunt-crossley with --formula: the target CoR e*, 0 < e* < 1.
    #[arg(long = "e-star", value_name = "E", allow_hyphen_values = true)]
    pub e_star: Option<String>,
    /// Prove enclosures of T_s and e with the interval Taylor engine.
    #[arg(long)]
    pub rigorous: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

#[derive(Args, Debug)]
pub struct LawsArgs {
    /// Comma-separated formula names, or all.
    #[arg(long, default_value = "all", value_name = "NAMES")]
    pub formulas: String,
    /// The range of target CoRs a..b, 0 < a < b < 1.
    #[arg(
        long = "e-star",
        default_value = "0.05..0.99",
        value_name = "A..B",
        allow_hyphen_values = true
    )]
    pub e_star: String,
    /// Targets on the grid (2 to 10000): the ends and points rounded to 4 decimals between.
    #[arg(long, default_value_t = 100, allow_hyphen_values = true)]
    pub points: usize,
    /// The error bound whose validity is proved over the range, in (0, 1).
    #[arg(long, default_value = "1e-3", allow_hyphen_values = true)]
    pub tol: String,
    /// Output format: the summary per formula (table), or every grid point (csv, json; json
    /// also has the proved runs).
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Write to this file (replaced whole) instead of stdout.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

/// Output of `identify`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum IdentifyFormat {
    /// The verdict, the counts and the hull as text.
    Table,
    /// One JSON object: free, boxes, hull, counts, seconds, ….
    Json,
    /// One row per box: status and each free parameter's lo and hi.
    Csv,
}

/// Most boxes `identify` processes.
pub const MAX_BOXES: RangeInclusive<u64> = 1..=100_000_000;
/// `identify --resolution`: the finest box side as a fraction 1/N of the starting box's.
pub const RESOLUTION: RangeInclusive<u64> = 1..=1 << 20;

#[derive(Args, Debug)]
pub struct IdentifyArgs {
    /// The model: shc (NDBWSHCCM), maxwell (NDBWMCM), or a classical law (its one parameter
    /// paved over --bounds, default its whole useful range).
    #[arg(long, value_enum)]
    pub model: FamilyArg,
    /// The measured data: CSV with the header v0,e (optional columns sigma, tc, tc_sigma).
    #[arg(long, value_name = "FILE.csv")]
    pub data: PathBuf,
    /// Every e is known to within ±E (E > 0); a column sigma overrides it per row.
    #[arg(long, value_name = "E", allow_hyphen_values = true, value_parser = error_bound)]
    pub error: Option<f64>,
    /// Every tc is known to within ±T (T > 0); a column tc_sigma overrides it per row.
    #[arg(long, value_name = "T", allow_hyphen_values = true, value_parser = decimal)]
    pub tc_error: Option<f64>,
    /// Ignore a tc column (CoRs alone).
    #[arg(long)]
    pub no_tc: bool,
    /// The box of the free parameters: name=lo..hi,… (names B_b, Gamma_b, kappa, sigma_b, n, p;
    /// Γ_b, κ, σ_b accepted).
    #[arg(long, value_name = "NAME=LO..HI,…", allow_hyphen_values = true)]
    pub bounds: Option<String>,
    /// Fixed parameters: name=value,….
    #[arg(long, value_name = "NAME=VALUE,…", allow_hyphen_values = true)]
    pub fix: Option<String>,
    /// The values of the parameters neither bounded nor in --fix: a base set B,Γ,κ,σ_b,n,p.
    #[arg(long, value_name = "B,Γ,κ,σ_b,n,p", allow_hyphen_values = true)]
    pub base: Option<String>,
    /// The free parameters' names (a check: they must be the bounded ones).
    #[arg(long, value_name = "NAMES", allow_hyphen_values = true)]
    pub free: Option<String>,
    /// Resolution: boxes are not split below 1/N of the starting box's side, 1 ≤ N ≤ 2^20
    /// [default: 128; for a classical law 2^20, relative to the parameter's distance from its
    /// floor].
    #[arg(long, value_name = "N", allow_hyphen_values = true,
          value_parser = RangedU64ValueParser::<u64>::new().range(RESOLUTION))]
    pub resolution: Option<u64>,
    /// The wall-clock budget, 0 < S ≤ 86400 seconds [default: 300]: when it runs out, the boxes
    /// not yet decided are reported undecided (everything reported stays proved; exit 1).
    #[arg(long, value_name = "S", allow_hyphen_values = true, value_parser = time_limit)]
    pub time_limit: Option<f64>,
    /// Most boxes processed, 1 ≤ K ≤ 10^8 (as the time limit, the rest is undecided).
    #[arg(long, value_name = "K", default_value_t = 1_000_000, allow_hyphen_values = true,
          value_parser = RangedU64ValueParser::<u64>::new().range(MAX_BOXES))]
    pub max_boxes: u64,
    /// Also sample F with the f64 engine: N uniform points of the box, then pushes from the
    /// feasible ones towards the box's faces, 0 ≤ N ≤ 10^7 [default: 0, none]. The hull of the
    /// points found feasible (an unproved inner estimate of F's hull) is printed beside the
    /// proved outer hull.
    #[arg(long, value_name = "N", default_value_t = 0, allow_hyphen_values = true,
          value_parser = count(0..=10_000_000))]
    pub sample: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t = IdentifyFormat::Table)]
    pub format: IdentifyFormat,
    /// Write the output to FILE instead of stdout (replaced whole, never half-written).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Draw the paving's 2-D projections (every pair of free parameters) to FILE.svg.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

/// Output of `fit` and `cost`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReportFormat {
    /// P*, J and the curve as aligned text.
    Table,
    /// One JSON object: P_star (named B, Gamma, kappa, sigma, n, p), J, the curve, ….
    Json,
}

#[derive(Args, Debug)]
pub struct FitArgs {
    /// The model: shc (NDBWSHCCM), maxwell (NDBWMCM), or a classical law (one parameter,
    /// searched over its range: its best value, minima, standard error and 95 % interval).
    #[arg(long, value_enum)]
    pub model: FamilyArg,
    /// Write the output to FILE instead of stdout (replaced whole, only when the command
    /// succeeded).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// The measured data: CSV with the header v0,e.
    #[arg(long, value_name = "FILE.csv")]
    pub data: PathBuf,
    /// Random starts (seeded), 0 ≤ N ≤ 256; 0 is allowed with --init. 8 fit 20 speeds to the
    /// noise level in about 25 s on a 2-core machine and, on paper_repro's synthetic DSS data,
    /// find 7 distinct minima within the noise (Γ_b of both signs, n from 1.2 to 22); more
    /// starts map the non-uniqueness of P* further.
    #[arg(long, value_name = "N", default_value_t = 8, allow_hyphen_values = true,
          value_parser = count(STARTS))]
    pub starts: usize,
    /// Seed of the random starts, 0 ≤ S < 2^64 (the same seed gives the same result).
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1,
        allow_hyphen_values = true
    )]
    pub seed: u64,
    /// Nelder–Mead iterations per run, 1 ≤ M ≤ 10000 (each start runs once and restarts once).
    #[arg(long, value_name = "M", default_value_t = 300, allow_hyphen_values = true,
          value_parser = RangedU64ValueParser::<u64>::new().range(MAX_ITER))]
    pub max_iter: u64,
    /// An extra start: a base set P* = B,Γ,κ,σ_b,n,p (e.g. a published set to refine).
    #[arg(long, value_name = "B,Γ,κ,σ_b,n,p", allow_hyphen_values = true)]
    pub init: Option<String>,
    /// Search the p = 1 slice of 𝓟 (the Maxwell model's isolated p = 1; p is then fixed).
    #[arg(long)]
    pub p1: bool,
    #[command(flatten)]
    pub search: SearchArgs,
    /// At the best fit (and, in JSON, at every minimum, there by central differences): the
    /// Jacobian of the residuals, the covariance s²(JᵀJ)⁻¹, standard errors, correlations and
    /// the singular values and directions of the Jacobian.
    #[arg(long)]
    pub uncertainty: bool,
    /// The Jacobian of --uncertainty: central (central differences of the f64 engine at
    /// rtol 1e-13; agrees with the proved one to ~1e-6) or proved (the proved sensitivities'
    /// midpoints, a column by central differences where they fail: M·k runs of the variational
    /// system: +45 % on the default fit of 20 speeds, central +3 %, medians of 3 side by side).
    #[arg(long, value_enum, default_value_t = JacobianArg::Central)]
    pub jacobian: JacobianArg,
    /// Report every start's end point as its own minimum (no hill–valley clustering).
    #[arg(long)]
    pub no_cluster: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
}

/// How the Jacobian of `fit --uncertainty` is computed.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum JacobianArg {
    /// The proved sensitivities' midpoints (central differences per column where they fail).
    Proved,
    /// Central differences of the f64 engine (tight tolerances).
    Central,
}

/// The search space and the residuals' errors of `fit` and `profile`.
#[derive(Args, Debug, Clone)]
pub struct SearchArgs {
    /// Hold parameters fixed: name=value,… (names B_b, Gamma_b, kappa, sigma_b, n, p; Greek
    /// accepted).
    #[arg(long, value_name = "NAME=VALUE,…", allow_hyphen_values = true)]
    pub fix: Option<String>,
    /// Search parameters within bounds: name=lo..hi,….
    #[arg(long, value_name = "NAME=LO..HI,…", allow_hyphen_values = true)]
    pub bounds: Option<String>,
    /// The error of every CoR without a `sigma` column value (> 0): residuals (e_i −
    /// e_model)/E, and χ² absolute. Without it and without the column, errors 1 (the paper's J).
    #[arg(long, value_name = "E", allow_hyphen_values = true, value_parser = error_bound)]
    pub error: Option<f64>,
    /// The error of every contact duration without a `tc_sigma` value (> 0; needed with a tc
    /// column that has no tc_sigma).
    #[arg(long, value_name = "E", allow_hyphen_values = true)]
    pub tc_error: Option<f64>,
    /// Ignore a tc column of the data.
    #[arg(long)]
    pub no_tc: bool,
}

#[derive(Args, Debug)]
pub struct ProfileArgs {
    /// The collision model: shc (NDBWSHCCM) or maxwell (NDBWMCM).
    #[arg(long, value_enum)]
    pub model: ModelArg,
    /// Write the output to FILE instead of stdout (replaced whole, only when the command
    /// succeeded).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// The measured data: CSV with the header v0,e.
    #[arg(long, value_name = "FILE.csv")]
    pub data: PathBuf,
    /// Profile only this parameter (default: every free one).
    #[arg(long, value_name = "NAME")]
    pub param: Option<String>,
    /// Grid points per profile, 3 ≤ K ≤ 1001.
    #[arg(long, value_name = "K", default_value_t = 21, allow_hyphen_values = true,
          value_parser = count(3..=1001))]
    pub points: usize,
    /// Random starts of the fit that finds the best point (seeded), 1 ≤ N ≤ 256.
    #[arg(long, value_name = "N", default_value_t = 8, allow_hyphen_values = true,
          value_parser = count(1..=256))]
    pub starts: usize,
    /// Seed of the random starts.
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1,
        allow_hyphen_values = true
    )]
    pub seed: u64,
    /// Nelder–Mead iterations per run, 1 ≤ M ≤ 10000.
    #[arg(long, value_name = "M", default_value_t = 300, allow_hyphen_values = true,
          value_parser = RangedU64ValueParser::<u64>::new().range(MAX_ITER))]
    pub max_iter: u64,
    #[command(flatten)]
    pub search: SearchArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ProfileFormat::Table)]
    pub format: ProfileFormat,
    /// Draw the profiles to FILE.svg: Δχ² against each parameter, the χ²_0.95(1) threshold and
    /// the 95 % interval.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

/// Output of `profile`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProfileFormat {
    Table,
    Json,
    /// One row per grid point: param,value,J,delta_chi2,B,Gamma,kappa,sigma,n,p,converged.
    Csv,
}

#[derive(Args, Debug)]
pub struct CostArgs {
    /// The collision model: shc (NDBWSHCCM) or maxwell (NDBWMCM).
    #[arg(long, value_enum)]
    pub model: ModelArg,
    /// Write the output to FILE instead of stdout (replaced whole, only when the command
    /// succeeded).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Base parameters P* = (B_b, Γ_b, κ, σ_b, n, p).
    #[arg(long, value_name = "B,Γ,κ,σ_b,n,p", allow_hyphen_values = true)]
    pub base: String,
    /// The measured data: CSV with the header v0,e.
    #[arg(long, value_name = "FILE.csv")]
    pub data: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
}

/// The model and where its parameters come from.
#[derive(Args, Debug, Clone)]
#[command(group(
    ArgGroup::new("source")
        .required(true)
        .multiple(false)
        .args(["base", "nd", "physical"])
))]
pub struct ParamArgs {
    /// The collision model: a Bouc–Wen model, shc (NDBWSHCCM, Kelvin–Voigt type) or maxwell
    /// (NDBWMCM), or a classical law (its parameters by name, see CLASSICAL LAWS).
    #[arg(long, value_enum)]
    pub model: FamilyArg,

    /// Base parameters P* = (B_b, Γ_b, κ, σ_b, n, p): the nondimensional set at v0 = 1 m/s,
    /// mapped to each --v0 by 𝓟(P*, v0). For a classical law its family by name
    /// (hunt-crossley sigma_b=…[,n=…], σ = σ_b·v0; hertz n=…; kelvin-voigt zeta=…;
    /// linear-maxwell c=…; hooke ''). Needs --v0.
    #[arg(
        long,
        value_name = "B,Γ,κ,σ_b,n,p",
        allow_hyphen_values = true,
        requires = "v0"
    )]
    pub base: Option<String>,

    /// A nondimensional parameter set P = (B, Γ, κ, σ, n, p), used as is (one case, no --v0).
    /// For a classical law by name: hunt-crossley sigma=…[,n=…]; hertz [n=…]; kelvin-voigt
    /// zeta=…; linear-maxwell c=… (c̃ = c/√(mk)); hooke '' (n is 3/2 when not given).
    #[arg(
        long,
        value_name = "B,Γ,κ,σ,n,p",
        allow_hyphen_values = true,
        conflicts_with = "v0"
    )]
    pub nd: Option<String>,

    /// Physical parameters in SI units:
    /// m=…,k=…,c=…,n=…,p=…,alpha=…,beta=…,gamma=…,A=… (see PHYSICAL PARAMETERS); for a
    /// classical law m=…,k=… and hertz [n=…], hunt-crossley chi=…[,n=…], kelvin-voigt and
    /// linear-maxwell c=… (see CLASSICAL LAWS). Needs --v0.
    #[arg(long, value_name = "KEY=VALUE,…", requires = "v0")]
    pub physical: Option<String>,

    /// Impact speed(s) v0 [m/s], each > 0, comma-separated (e.g. 0.5,1,2), at most 10000; with
    /// --rigorous each may be a range a..b.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub v0: Option<String>,
}

/// Integrator settings, float or rigorous.
#[derive(Args, Debug, Clone)]
pub struct EngineArgs {
    /// Nondimensional time after which "no separation" is reported (T_s = +∞ as far as the
    /// integration went), 0 < T ≤ 1e6.
    #[arg(long, value_name = "T", default_value_t = 100.0, allow_hyphen_values = true,
          value_parser = time)]
    pub horizon: f64,

    /// DOP853 relative tolerance, 100 ε ≤ RTOL < 1 (100 ε ≈ 2.2e-14) [default: 1e-10, the
    /// paper's].
    #[arg(long, value_name = "RTOL", conflicts_with = "rigorous",
          allow_hyphen_values = true, value_parser = rtol)]
    pub rtol: Option<f64>,

    /// DOP853 absolute tolerance, 0 < ATOL ≤ 1 [default: 1e-12, the paper's].
    #[arg(long, value_name = "ATOL", conflicts_with = "rigorous",
          allow_hyphen_values = true, value_parser = atol)]
    pub atol: Option<f64>,

    /// DOP853 largest step, nondimensional, H ≥ 1e-9 (inf: no limit) [default: 1e-2, the
    /// paper's]. At most 10⁶ steps are taken per case.
    #[arg(long, value_name = "H", conflicts_with = "rigorous",
          allow_hyphen_values = true, value_parser = max_step)]
    pub max_step: Option<f64>,

    /// Prove enclosures of T_s and e with the interval Taylor engine (parameters are enclosed
    /// as written, ranges a..b allowed).
    #[arg(long)]
    pub rigorous: bool,

    /// Taylor order of the rigorous engine, 2 ≤ K ≤ 40 [default: 16; 12 with --band]. Needs
    /// --rigorous.
    #[arg(long, value_name = "K", allow_hyphen_values = true,
          value_parser = count(ORDER))]
    pub order: Option<usize>,
    /// With --rigorous and inputs given as ranges (a..b): the ceiling of an adaptive split. A
    /// range is proved whole (the engine carries the solution's dependence on it) and cut,
    /// along its relatively widest input, where a piece cannot be proved or makes the hull of
    /// e or T_s wider than 1.1× what point runs prove they spread; at most N pieces,
    /// 1 ≤ N ≤ 1024, whose hull is the result [default: 256]. Needs --rigorous.
    #[arg(long, value_name = "N", allow_hyphen_values = true,
          value_parser = count(PIECES))]
    pub pieces: Option<usize>,
    /// With --rigorous: the wall-clock budget of the whole command, 0 < S ≤ 86400 seconds
    /// [default: 300]. When it runs out, what was proved is reported and every case or piece
    /// not yet proved says "not proved: the time budget of S s ran out" (exit 1).
    #[arg(long, value_name = "S", allow_hyphen_values = true,
          value_parser = time_limit)]
    pub time_limit: Option<f64>,
}

#[derive(Args, Debug)]
pub struct CorArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub engine: EngineArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Write to FILE instead of stdout (replaced only when everything succeeded).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Print to stderr the wall time of the computation (the cases only: no process start-up,
    /// parsing or output), in total and per case.
    #[arg(long)]
    pub timing: bool,
    /// With --rigorous, --base (or --physical) and one range of v0 (a..b): prove the CoR curve
    /// over the whole range and write it to FILE piece by piece (CSV, or JSON for a name
    /// ending in .json): v0_lo, v0_hi, v0_c, and on each piece e(v0) ∈ e_c + de·(v0 − v0_c),
    /// T_s likewise, with the hulls e, ts and the thickness (all bounds rounded outward).
    /// Created only when every piece is proved.
    #[arg(long, value_name = "FILE", requires = "rigorous")]
    pub band: Option<PathBuf>,
    /// With --rigorous: prove T_s and e to D significant digits, 1 ≤ D ≤ 100, on intervals
    /// over MPFR floats (128, 192, 256 or 384 bits: the smallest with ≥ 3.33·D + 24); the
    /// Taylor order and the tolerances follow D (30 digits take ≈ 1–2 s, 60 ≈ 5–9 s, 100 about
    /// a minute). Every digit the width allows is printed, bounds rounded outward. For --nd
    /// or --base with single values of v0.
    #[arg(long, value_name = "D", allow_hyphen_values = true,
          value_parser = count(DIGITS))]
    pub digits: Option<usize>,
    /// With --band: the curve in the second-order (interpolation) form, for thin bands
    /// (1e-9 and below): e and T_s proved at nodes, e″ and T_s″ over each piece by the second
    /// variational system; one row per node interval [v0_lo, v0_hi] with e(v0) ∈
    /// e_at_lo·(v0_hi − v0)/h + e_at_hi·(v0 − v0_lo)/h − d2e·(v0 − v0_lo)(v0_hi − v0)/2
    /// (h = v0_hi − v0_lo), T_s likewise, and the thickness. [0.1, 5] at 1e-9: ≈ 15 s on 2
    /// CPUs (the first-order form: minutes).
    #[arg(long, requires = "band")]
    pub second_order: bool,
    /// Largest thickness of --band (the vertical width of the enclosure of e at any v0),
    /// 1e-14 ≤ T ≤ 1 [default: 1e-6; 1e-9 with --second-order].
    #[arg(long, value_name = "T", requires = "band", allow_hyphen_values = true,
          value_parser = thickness)]
    pub thickness: Option<f64>,
    /// With --rigorous: also prove ∂T_s/∂u and ∂e/∂u for every input u of the case (the
    /// nondimensional, base or physical parameters and v0), at its value or over its range
    /// (JSON: a field "sensitivities").
    #[arg(long, requires = "rigorous")]
    pub sensitivities: bool,
    /// Also the derived outputs of each collision: the peak contact force F_max, the maximum
    /// indentation δ_max (max of −X) over [0, T_s], and the kinetic energy lost
    /// ΔE = (1 − e²)/2 — in SI too with --physical (N, m, J = ½ m v0² (1 − e²)). Proved with
    /// --rigorous (not computed over a range of a Bouc–Wen model's inputs, the row says why; a
    /// classical law's range is proved whole), on the dense output otherwise.
    #[arg(long)]
    pub derived: bool,
    /// With --rigorous: a case the f64-interval engine cannot decide (grazing or undecidable
    /// separation, an enclosure grown too wide, a crossing not proved) is run again on MPFR
    /// intervals at 128, 192, then 256 bits, up to B bits; 0 turns this off. The output names
    /// the precision that proved each case (a bits column — in CSV always, 53 for the f64
    /// intervals; in the table when the fallback ran — and in JSON the runs made).
    /// For --nd and --base [default: 256].
    #[arg(long, value_name = "B", requires = "rigorous", allow_hyphen_values = true,
          value_parser = fallback_bits)]
    pub fallback_bits: Option<u32>,
    /// Wall-clock budget of each precision of the fallback, 0 < S ≤ 3600 seconds: a run still
    /// going then stops, and so does the fallback [default: 60].
    #[arg(long, value_name = "S", requires = "rigorous", allow_hyphen_values = true,
          value_parser = fallback_seconds)]
    pub fallback_seconds: Option<f64>,
}

/// What `prove` proves.
#[derive(Subcommand, Debug)]
pub enum ProveCommand {
    /// Prove e(v0) strictly decreasing over a range of impact speeds (de/dv0 < 0 proved on
    /// every piece), or name the sub-ranges where it cannot.
    Monotone(MonotoneArgs),
}

#[derive(Args, Debug)]
pub struct ProveArgs {
    #[command(subcommand)]
    pub what: ProveCommand,
}

#[derive(Args, Debug)]
pub struct MonotoneArgs {
    /// The collision model: shc or maxwell.
    #[arg(long, value_enum)]
    pub model: ModelArg,
    /// Write the output to FILE instead of stdout (replaced whole, only when the command
    /// succeeded).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Base parameters P* = (B_b, Γ_b, κ, σ_b, n, p) (decimals enclosed as written).
    #[arg(long, value_name = "B,Γ,κ,σ_b,n,p", allow_hyphen_values = true)]
    pub base: String,
    /// The range of impact speeds a..b [m/s], 0 < a < b.
    #[arg(long, value_name = "a..b", allow_hyphen_values = true)]
    pub v0: String,
    /// Output format (table or json).
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
    /// The wall-clock budget, 0 < S ≤ 86400 seconds [default: 300]: when it runs out, the
    /// pieces proved so far are reported and the rest named as not proved.
    #[arg(long, value_name = "S", allow_hyphen_values = true,
          value_parser = time_limit)]
    pub time_limit: Option<f64>,
}

#[derive(Args, Debug)]
pub struct TrajectoryArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub engine: EngineArgs,
    /// Number of uniform sample times, 2 ≤ N ≤ 100000, the first at 0 and the last at the end
    /// time.
    #[arg(long, value_name = "N", default_value_t = 1000, allow_hyphen_values = true,
          value_parser = count(POINTS))]
    pub points: usize,
    /// End time T (nondimensional), 0 < T ≤ 1e6 [default: T_s, or the horizon without
    /// separation; with --rigorous the upper bound of T_s, and T may go up to the end of the
    /// proved flow].
    #[arg(long, value_name = "T", allow_hyphen_values = true, value_parser = time)]
    pub t_end: Option<f64>,
    /// With --physical: t in s, x in m, v in m/s, F in N (loop: x_mm = |x| in mm, F_N in N);
    /// the model's states stay nondimensional.
    #[arg(long, conflicts_with = "rigorous")]
    pub physical_units: bool,
    /// Write the CSV to FILE instead of stdout (created only when everything succeeded).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

/// A model fitted to data: a Bouc–Wen model or a classical law (`fit`, `identify`, `compare`).
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamilyArg {
    /// NDBWSHCCM: the Bouc–Wen–Simon–Hunt–Crossley model, P* = B_b, Γ_b, κ, σ_b, n, p.
    Shc,
    /// NDBWMCM: the Bouc–Wen–Maxwell model, P* = B_b, Γ_b, κ, σ_b, n, p.
    Maxwell,
    /// The linear spring (e = 1, no parameter).
    Hooke,
    /// Hertz's law (e = 1, no parameter).
    Hertz,
    /// Hunt–Crossley, F = k|δ|^(n−1)δ + χ|δ|^n δ̇, σ = χv0/k = σ_b·v0 (fit: sigma_b =
    /// χ·(1 m/s)/k; e does not depend on n).
    HuntCrossley,
    /// Linear Kelvin–Voigt, F = kδ + cδ̇ (zeta = c/(2√(mk)); e the same at every speed).
    KelvinVoigt,
    /// Linear Maxwell, spring and dashpot in series (c = c/√(mk); it separates for c > 1/2, e
    /// the same at every speed).
    LinearMaxwell,
}

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// The measured data: CSV with the header v0,e (a column sigma weights the rows; tc is
    /// ignored).
    #[arg(long, value_name = "FILE.csv")]
    pub data: PathBuf,
    /// The models, comma-separated [default: all: shc, maxwell, hunt-crossley, kelvin-voigt,
    /// linear-maxwell, hertz, hooke].
    #[arg(long, value_name = "NAMES", allow_hyphen_values = true)]
    pub models: Option<String>,
    /// Every e known to within ±E (E > 0; for every row: a sigma column weights the fits only):
    /// each classical law's feasible set is proved (empty: a certificate that no law of the
    /// family fits the data to ±E).
    #[arg(long, value_name = "E", allow_hyphen_values = true, value_parser = error_bound)]
    pub error: Option<f64>,
    /// Random starts of the Bouc–Wen fits, 0 ≤ N ≤ 256 (as `fit`).
    #[arg(long, value_name = "N", default_value_t = 8, allow_hyphen_values = true,
          value_parser = count(STARTS))]
    pub starts: usize,
    /// Seed of the Bouc–Wen fits' starts.
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1,
        allow_hyphen_values = true
    )]
    pub seed: u64,
    /// The wall-clock budget of each feasible set, 0 < S ≤ 86400 seconds [default: 300].
    #[arg(long, value_name = "S", allow_hyphen_values = true, value_parser = time_limit)]
    pub time_limit: Option<f64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
    /// Write the output to FILE instead of stdout (replaced whole, never half-written).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelArg {
    /// NDBWSHCCM: the Bouc–Wen–Simon–Hunt–Crossley (Kelvin–Voigt type) model, states X, Z, V.
    Shc,
    /// NDBWMCM: the Bouc–Wen–Maxwell model, states R, Y, Z, W.
    Maxwell,
}

impl From<ModelArg> for ModelKind {
    fn from(m: ModelArg) -> Self {
        match m {
            ModelArg::Shc => ModelKind::Shc,
            ModelArg::Maxwell => ModelKind::Maxwell,
        }
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Aligned columns with a header.
    Table,
    /// An array with one object per case.
    Json,
    /// A header and one row per case.
    Csv,
}
