//! What several integration tests share: the `bwcl` program, and the Hunt–Crossley closed form
//! of the CoR.
//!
//! **The reference.** With B → 0 and Γ = 0 the NDBWSHCCM (eq:BWSHCCM_nd) has Ż = V, so Z = X
//! and (κ + κ_c = 1) F = |X|^p(−sgn X − σV); dV/dT = F and dX/dT = V give V dV/dX = F, i.e. for
//! X < 0 (compression) V dV/(1 − σV) = |X|^p dX. Over the contact X goes from 0 and back to 0,
//! so ∫_{−1}^{e} V/(1 − σV) dV = 0, i.e. with u = σe
//!
//! ```text
//! −u − ln(1 − u) = σ − ln(1 + σ)
//! ```
//!
//! (the Hunt–Crossley restitution law; p does not enter). g(u) = −u − ln(1 − u) − c is
//! increasing on (0, 1); its root is bracketed at 400 bits by the signs of g at u* ∓ 10⁻⁹⁰
//! (|g| there ≈ g′·10⁻⁹⁰ ≫ the rounding ≈ 10⁻¹¹⁵), and an enclosure must contain the whole
//! bracket (compared as exact rationals). The cases use B = 10⁻³⁰⁰ (𝓟 is open): their e differs
//! from the limit's by ≈ 10⁻³⁰⁰, far inside the bracket's 10⁻⁹⁰.

// (each test crate uses its own part of this module)
#![allow(dead_code)]

use rug::ops::Pow;
use rug::{Float, Rational};
use std::process::{Command, Output};

/// Runs the `bwcl` program with `args` and waits for it.
pub fn bwcl(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bwcl"))
        .args(args)
        .output()
        .expect("bwcl runs")
}

/// The standard output of `bwcl args`, its success asserted (stderr in the message).
pub fn bwcl_ok(args: &[&str]) -> String {
    let o = bwcl(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

const BITS: u32 = 400;

/// The bracket [lo, hi] of the Hunt–Crossley e(σ), exact rationals, for a rational σ > 0 (taken
/// to 400 bits: the root moves by ≈ 10⁻¹²⁰, far inside the bracket).
pub fn hunt_crossley_bracket(sigma: &Rational) -> (Rational, Rational) {
    assert!(*sigma > 0u32);
    let one = || Float::with_val(BITS, 1u32);
    let s = Float::with_val(BITS, sigma);
    let c = s.clone() - (s.clone() + 1u32).ln();
    let g = |u: &Float| -u.clone() - (one() - u).ln() - &c;
    let mut u = Float::with_val(BITS, 0.5);
    // Newton converges quadratically: it stops once a step moves u by less than 1e−115 (the
    // bracket's check below fails if it stopped short)
    let tiny = Float::with_val(BITS, Float::parse("1e-115").unwrap());
    for _ in 0..400 {
        let dg = one() / (one() - &u) - 1u32;
        let mut next = u.clone() - g(&u) / dg;
        if next >= 1u32 {
            next = (u.clone() + 1u32) / 2u32;
        }
        let step = Float::with_val(BITS, &next - &u).abs();
        u = next;
        if step < tiny {
            break;
        }
    }
    let eps = Float::with_val(BITS, Float::parse("1e-90").unwrap());
    let (a, b) = (u.clone() - &eps, u.clone() + &eps);
    assert!(g(&a) < 0u32 && g(&b) > 0u32, "the root is bracketed");
    let r = |x: Float| x.to_rational().unwrap() / sigma;
    (r(a), r(b))
}

/// The precision of the classical laws' closed forms below (error ≈ 10⁻⁵⁸).
pub const CLOSED_BITS: u32 = 200;

/// [x − 10⁻⁵⁰, x + 10⁻⁵⁰] as rationals, for x computed at [`CLOSED_BITS`].
pub fn around(x: &Float) -> (Rational, Rational) {
    let eps = Float::with_val(CLOSED_BITS, Float::parse("1e-50").unwrap());
    (
        Float::with_val(CLOSED_BITS, x - &eps)
            .to_rational()
            .unwrap(),
        Float::with_val(CLOSED_BITS, x + &eps)
            .to_rational()
            .unwrap(),
    )
}

/// Hertz's nondimensional contact time for the exponent n: with X_m = ((n+1)/2)^(1/(n+1)),
/// T_s = 2 X_m B(1/(n+1), 1/2)/(n+1) (the Beta function through Γ).
pub fn hertz_ts(n: &Float) -> Float {
    let b = CLOSED_BITS;
    let n1 = Float::with_val(b, n + 1u32);
    let xm = Float::with_val(
        b,
        Float::with_val(b, &n1 / 2u32).pow(Float::with_val(b, 1u32 / &n1)),
    );
    let a = Float::with_val(b, 1u32 / &n1);
    let half = Float::with_val(b, 0.5);
    let beta = Float::with_val(b, a.clone().gamma() * half.clone().gamma())
        / Float::with_val(b, a + half).gamma();
    Float::with_val(b, xm * 2u32 * beta / n1)
}

/// Linear Kelvin–Voigt with ζ < 1 (src/models/kelvin_voigt.rs): ω = √(1 − ζ²),
/// φ = atan2(2ζω, 1 − 2ζ²), T_s = (π − φ)/ω, e = e^(−ζT_s). Returns (T_s, e).
pub fn kelvin_voigt_closed(z: &Float) -> (Float, Float) {
    use rug::float::Constant;
    let b = CLOSED_BITS;
    let w = Float::with_val(b, 1u32 - Float::with_val(b, z * z)).sqrt();
    let phi = Float::with_val(b, Float::with_val(b, z * &w) * 2u32)
        .atan2(&Float::with_val(b, 1u32 - Float::with_val(b, z * z) * 2u32));
    let ts = Float::with_val(b, Float::with_val(b, Constant::Pi) - phi) / &w;
    let e = Float::with_val(b, -Float::with_val(b, z * &ts)).exp();
    (ts, e)
}

/// Linear Maxwell with c̃ > 1/2 (src/models/linear_maxwell.rs): β = 1/(2c̃), ω = √(1 − β²),
/// T_s = π/ω, e = e^(−βT_s). Returns (T_s, e).
pub fn linear_maxwell_closed(c: &Float) -> (Float, Float) {
    use rug::float::Constant;
    let b = CLOSED_BITS;
    let beta = Float::with_val(b, 1u32 / Float::with_val(b, c * 2u32));
    let w = Float::with_val(b, 1u32 - Float::with_val(b, &beta * &beta)).sqrt();
    let ts = Float::with_val(b, Constant::Pi) / &w;
    let e = Float::with_val(b, -Float::with_val(b, &beta * &ts)).exp();
    (ts, e)
}
