//! Parameter sets and the admissible set 𝓟.
//!
//! A nondimensional parameter set P = (B, Γ, κ, σ, n, p) is validated on construction against
//! the model's 𝓟 (sec:KVCL, sec:MCL):
//! B > 0, Γ ∈ (−B, B), κ ∈ (0, 1), σ > 0, n ≥ 1, p ≥ 1, and for the Maxwell model
//! p ∈ [2, ∞) ∪ {1}. The appendices work on the closed set B ≥ 0, Γ ∈ [−B, B], σ ≥ 0
//! ([`Admissibility::Closed`], an explicit opt-in). For interval parameters every condition must
//! hold for every value in the intervals. NaN and ±∞ are rejected everywhere.

use crate::arith::Real;
use crate::arith::mpfr::decimal_value;
use rug::Rational;
use std::fmt;

/// Which collision model a parameter set belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum ModelKind {
    /// NDBWSHCCM (eq:BWSHCCM_nd), the Kelvin–Voigt-type model.
    #[serde(rename = "shc")]
    Shc,
    /// NDBWMCM (eq:BWMCM_nd), the Maxwell-type model.
    #[serde(rename = "maxwell")]
    Maxwell,
}

impl ModelKind {
    pub fn name(self) -> &'static str {
        match self {
            ModelKind::Shc => "shc",
            ModelKind::Maxwell => "maxwell",
        }
    }
}

/// The paper's Table 1 (tab:param): the base sets P* identified from the DSS and DSA data, as
/// (name, model, "B_b,Γ_b,κ,σ_b,n,p" exactly as printed).
pub const TABLE1: [(&str, ModelKind, &str); 4] = [
    (
        "SHC DSS",
        ModelKind::Shc,
        "1.43,-1.42,0.632,0.00715,1.31,1.27",
    ),
    (
        "SHC DSA",
        ModelKind::Shc,
        "0.63,-0.611,0.188,0.00594,1,2.02",
    ),
    (
        "Maxwell DSS",
        ModelKind::Maxwell,
        "0.655,-0.64,0.519,0.0118,1.94,2.28",
    ),
    (
        "Maxwell DSA",
        ModelKind::Maxwell,
        "0.44,-0.418,0.113,0.00785,1.27,3.14",
    ),
];

/// The set a parameter set is validated against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Admissibility {
    /// The main text's 𝓟: B > 0, Γ ∈ (−B, B), σ > 0.
    Open,
    /// The appendices' closed set: B ≥ 0, Γ ∈ [−B, B], σ ≥ 0.
    Closed,
    /// Enclosures of values already proved in 𝓟 exactly (the decimals as written,
    /// [`check_decimals`], or values mapped from them): the outward rounding of a value next to
    /// a strict bound may reach it (0.9999999999999999 lies strictly between the doubles
    /// 1 − 2⁻⁵³ and 1, so its enclosure ends at 1), so only what that rounding keeps is
    /// checked: B, σ ≥ 0, κ ∈ [0, 1], −sup B ≤ Γ ≤ sup B (rounding is monotone: Γ < B gives
    /// sup Γ ≤ sup B), n, p ≥ 1 and the Maxwell model's p ∈ [2, ∞) ∪ {1} (bounds that are
    /// doubles are kept by the rounding).
    Written,
}

/// A parameter outside 𝓟, or not a finite number. The message names the condition and values.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamError(pub String);

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}
impl std::error::Error for ParamError {}

/// A double as Rust prints it (the shortest decimal that reads back to it), or with an
/// exponent where that is longer than 20 characters.
pub fn short_f64(v: f64) -> String {
    let plain = format!("{v}");
    if plain.len() <= 20 {
        plain
    } else {
        format!("{v:e}")
    }
}

/// Shows a parameter compactly: the value for `f64`, the point or the range for intervals;
/// each double as Rust prints it, or with an exponent where that is longer than 20 characters
/// (5e-324, not its 324 digits). A message, not a bound: the bounds printed as results are
/// rounded outward elsewhere.
pub fn show<R: Real>(x: &R) -> String {
    if x.lo() == x.hi() {
        short_f64(x.lo())
    } else if (x.lo() > 0.0 || x.hi() < 0.0) && (x.hi() - x.lo()) <= 1e-12 * x.mid().abs() {
        short_f64(x.mid())
    } else {
        // (an end −0 shown as 0: "[-0, 5e-324]" read as a negative value)
        format!("[{}, {}]", short_f64(x.lo() + 0.0), short_f64(x.hi() + 0.0))
    }
}

/// A nondimensional parameter set P = (B, Γ, κ, σ, n, p), or a base set P* (same fields, the
/// values at v0 = 1: see [`crate::models::scaling`]).
#[derive(Clone, Debug)]
pub struct NdParams<R> {
    pub b: R,
    pub gamma: R,
    pub kappa: R,
    pub sigma: R,
    pub n: R,
    pub p: R,
}

impl<R> NdParams<R> {
    /// The set of the fields in the paper's order (B, Γ, κ, σ, n, p): the inverse of
    /// [`NdParams::as_array`], unchecked like the struct literal (see [`NdParams::new`] for a
    /// validated set).
    pub fn from_array([b, gamma, kappa, sigma, n, p]: [R; 6]) -> Self {
        Self {
            b,
            gamma,
            kappa,
            sigma,
            n,
            p,
        }
    }
}

impl<R: Real> NdParams<R> {
    /// Builds a set and validates it against `kind`'s 𝓟 (open set).
    pub fn new(
        kind: ModelKind,
        b: R,
        gamma: R,
        kappa: R,
        sigma: R,
        n: R,
        p: R,
    ) -> Result<Self, ParamError> {
        Self::with_admissibility(kind, Admissibility::Open, b, gamma, kappa, sigma, n, p)
    }

    #[allow(clippy::too_many_arguments)]
    pub fn with_admissibility(
        kind: ModelKind,
        set: Admissibility,
        b: R,
        gamma: R,
        kappa: R,
        sigma: R,
        n: R,
        p: R,
    ) -> Result<Self, ParamError> {
        let s = Self {
            b,
            gamma,
            kappa,
            sigma,
            n,
            p,
        };
        s.validate(kind, set)?;
        Ok(s)
    }

    /// Parses the six decimals "B,Γ,κ,σ,n,p" (each enclosed as written for intervals; a range
    /// a..b for intervals): the values as written are checked against 𝓟 exactly
    /// ([`check_decimals`]), their enclosures in `R` against what outward rounding keeps
    /// ([`Admissibility::Written`]).
    pub fn parse(kind: ModelKind, text: &str) -> Result<Self, ParamError> {
        let v = parse_list::<R>(text, 6, "B,Γ,κ,σ,n,p")?;
        check_decimals(kind, text)?;
        let [b, g, k, s, n, p]: [R; 6] = v.try_into().unwrap();
        Self::with_admissibility(kind, Admissibility::Written, b, g, k, s, n, p)
    }

    /// The fields in the paper's order (B, Γ, κ, σ, n, p).
    pub fn as_array(&self) -> [R; 6] {
        [
            self.b.clone(),
            self.gamma.clone(),
            self.kappa.clone(),
            self.sigma.clone(),
            self.n.clone(),
            self.p.clone(),
        ]
    }

    /// Checks the set against 𝓟 of `kind`: every condition for every value of interval fields.
    pub fn validate(&self, kind: ModelKind, set: Admissibility) -> Result<(), ParamError> {
        let names = ["B", "Γ", "κ", "σ", "n", "p"];
        for (x, name) in self.as_array().iter().zip(names) {
            if !x.is_finite() || x.lo().is_nan() || x.hi().is_nan() {
                return Err(ParamError(format!(
                    "{name} = {} is not a finite number",
                    show(x)
                )));
            }
        }
        let (b, g) = (&self.b, &self.gamma);
        if set == Admissibility::Written {
            return self.validate_written(kind);
        }
        let closed = set == Admissibility::Closed;
        if closed {
            if b.lo() < 0.0 {
                return Err(ParamError(format!("B = {} must be ≥ 0", show(b))));
            }
            if !(g.lo() >= -b.lo() && g.hi() <= b.lo()) {
                return Err(ParamError(format!(
                    "Γ = {} must lie in [−B, B] = [{}, {}]",
                    show(g),
                    -b.lo(),
                    b.lo()
                )));
            }
            if self.sigma.lo() < 0.0 {
                return Err(ParamError(format!("σ = {} must be ≥ 0", show(&self.sigma))));
            }
        } else {
            if b.lo() <= 0.0 {
                return Err(ParamError(format!("B = {} must be > 0", show(b))));
            }
            if !(g.lo() > -b.lo() && g.hi() < b.lo()) {
                return Err(ParamError(format!(
                    "Γ = {} must lie in (−B, B) = ({}, {})",
                    show(g),
                    -b.lo(),
                    b.lo()
                )));
            }
            if self.sigma.lo() <= 0.0 {
                return Err(ParamError(format!("σ = {} must be > 0", show(&self.sigma))));
            }
        }
        if !(self.kappa.lo() > 0.0 && self.kappa.hi() < 1.0) {
            return Err(ParamError(format!(
                "κ = {} must lie in (0, 1)",
                show(&self.kappa)
            )));
        }
        if self.n.lo() < 1.0 {
            return Err(ParamError(format!("n = {} must be ≥ 1", show(&self.n))));
        }
        if self.p.lo() < 1.0 {
            return Err(ParamError(format!("p = {} must be ≥ 1", show(&self.p))));
        }
        if kind == ModelKind::Maxwell {
            let is_one = self.p.lo() == 1.0 && self.p.hi() == 1.0;
            if !(is_one || self.p.lo() >= 2.0) {
                return Err(ParamError(format!(
                    "p = {} must lie in [2, ∞) ∪ {{1}} for the Maxwell model",
                    show(&self.p)
                )));
            }
        }
        Ok(())
    }
}

impl<R: Real> NdParams<R> {
    /// [`Admissibility::Written`] (the values are finite, checked by [`NdParams::validate`]).
    fn validate_written(&self, kind: ModelKind) -> Result<(), ParamError> {
        let (b, g) = (&self.b, &self.gamma);
        let fail = |what: String| Err(ParamError(what));
        if b.lo() < 0.0 {
            return fail(format!("B = {} must be > 0", show(b)));
        }
        if !(g.lo() >= -b.hi() && g.hi() <= b.hi()) {
            return fail(format!(
                "Γ = {} must lie in (−B, B) = ({}, {})",
                show(g),
                -b.hi(),
                b.hi()
            ));
        }
        if self.sigma.lo() < 0.0 {
            return fail(format!("σ = {} must be > 0", show(&self.sigma)));
        }
        if !(self.kappa.lo() >= 0.0 && self.kappa.hi() <= 1.0) {
            return fail(format!("κ = {} must lie in (0, 1)", show(&self.kappa)));
        }
        if self.n.lo() < 1.0 {
            return fail(format!("n = {} must be ≥ 1", show(&self.n)));
        }
        if self.p.lo() < 1.0 {
            return fail(format!("p = {} must be ≥ 1", show(&self.p)));
        }
        if kind == ModelKind::Maxwell {
            let is_one = self.p.lo() == 1.0 && self.p.hi() == 1.0;
            if !(is_one || self.p.lo() >= 2.0) {
                return fail(format!(
                    "p = {} must lie in [2, ∞) ∪ {{1}} for the Maxwell model",
                    show(&self.p)
                ));
            }
        }
        Ok(())
    }
}

/// The exact values of a decimal or a range "a..b" as written: [a, b] as rationals.
pub fn decimal_range(token: &str) -> Result<[Rational; 2], String> {
    let t = token.trim();
    let one = |s: &str| {
        let s = s.trim();
        crate::arith::real::check_plain_decimal(s)?;
        decimal_value(s)
    };
    match t.split_once("..") {
        None => {
            let x = one(t)?;
            Ok([x.clone(), x])
        }
        Some((a, b)) => {
            let (a, b) = (one(a)?, one(b)?);
            if a > b {
                return Err(format!(
                    "the range '{t}' is empty (its start exceeds its end)"
                ));
            }
            Ok([a, b])
        }
    }
}

/// Checks the six decimals "B,Γ,κ,σ,n,p" as written (each a decimal or a range a..b) against
/// `kind`'s 𝓟, exactly: every value of every range, compared as rationals — not their
/// enclosures, which may touch a bound the decimal does not (κ = 0.9999999999999999 < 1 is
/// enclosed in [1 − 2⁻⁵³, 1]). The message names the value as written.
pub fn check_decimals(kind: ModelKind, text: &str) -> Result<(), ParamError> {
    let tokens: Vec<&str> = text.split(',').map(str::trim).collect();
    let names = ["B", "Γ", "κ", "σ", "n", "p"];
    if tokens.len() != 6 {
        return Err(ParamError(format!(
            "expected 6 comma-separated values B,Γ,κ,σ,n,p, got {} in '{text}'",
            tokens.len()
        )));
    }
    let mut v: Vec<[Rational; 2]> = Vec::with_capacity(6);
    for (t, name) in tokens.iter().zip(names) {
        v.push(decimal_range(t).map_err(|e| ParamError(format!("{name}: {e}")))?);
    }
    let zero = Rational::new();
    let one = Rational::from(1);
    let two = Rational::from(2);
    let [b, g, k, s, n, p] = [&v[0], &v[1], &v[2], &v[3], &v[4], &v[5]];
    let [tb, tg, tk, ts, tn, tp] = [
        tokens[0], tokens[1], tokens[2], tokens[3], tokens[4], tokens[5],
    ];
    let fail = |what: String| Err(ParamError(what));
    if b[0] <= zero {
        return fail(format!("B = {tb} must be > 0"));
    }
    if !(g[0] > -b[0].clone() && g[1] < b[0]) {
        let lo = tb.split("..").next().unwrap_or(tb).trim();
        let lo = lo.strip_prefix('+').unwrap_or(lo);
        return fail(format!("Γ = {tg} must lie in (−B, B) = (-{lo}, {lo})"));
    }
    if s[0] <= zero {
        return fail(format!("σ = {ts} must be > 0"));
    }
    if !(k[0] > zero && k[1] < one) {
        return fail(format!("κ = {tk} must lie in (0, 1)"));
    }
    if n[0] < one {
        return fail(format!("n = {tn} must be ≥ 1"));
    }
    if p[0] < one {
        return fail(format!("p = {tp} must be ≥ 1"));
    }
    if kind == ModelKind::Maxwell && !((p[0] == one && p[1] == one) || p[0] >= two) {
        return fail(format!(
            "p = {tp} must lie in [2, ∞) ∪ {{1}} for the Maxwell model"
        ));
    }
    Ok(())
}

/// Parses `count` comma-separated decimals; `what` names them for the error message.
pub fn parse_list<R: Real>(text: &str, count: usize, what: &str) -> Result<Vec<R>, ParamError> {
    let items: Vec<&str> = text.split(',').map(str::trim).collect();
    if items.len() != count {
        return Err(ParamError(format!(
            "expected {count} comma-separated values {what}, got {} in '{text}'",
            items.len()
        )));
    }
    let names: Vec<&str> = what.split(',').collect();
    items
        .iter()
        .enumerate()
        .map(|(i, s)| {
            R::parse_decimal(s)
                .map_err(|e| ParamError(format!("{}: {e}", names.get(i).unwrap_or(&"value"))))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use inari::Interval;

    #[test]
    fn paper_sets_are_admissible() {
        for s in [
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "0.63,-0.611,0.188,0.00594,1,2.02",
        ] {
            NdParams::<f64>::parse(ModelKind::Shc, s).unwrap();
            NdParams::<Interval>::parse(ModelKind::Shc, s).unwrap();
        }
        for s in [
            "0.655,-0.64,0.519,0.0118,1.94,2.28",
            "0.44,-0.418,0.113,0.00785,1.27,3.14",
        ] {
            NdParams::<f64>::parse(ModelKind::Maxwell, s).unwrap();
        }
    }

    #[test]
    fn violations_name_condition_and_values() {
        let e = NdParams::<f64>::parse(ModelKind::Shc, "1.43,-1.5,0.632,0.00715,1.31,1.27")
            .unwrap_err();
        assert_eq!(e.0, "Γ = -1.5 must lie in (−B, B) = (-1.43, 1.43)");
        let e = NdParams::<f64>::parse(ModelKind::Maxwell, "1,0,0.5,1,1,1.5").unwrap_err();
        assert!(e.0.contains("[2, ∞) ∪ {1}"), "{e}");
        assert!(
            NdParams::<f64>::parse(ModelKind::Shc, "1,0,1.2,1,1,1")
                .unwrap_err()
                .0
                .contains("κ")
        );
        assert!(NdParams::<f64>::parse(ModelKind::Shc, "NaN,0,0.5,1,1,1").is_err());
        assert!(NdParams::<f64>::parse(ModelKind::Shc, "inf,0,0.5,1,1,1").is_err());
        assert!(NdParams::<f64>::parse(ModelKind::Shc, "1,0,0.5,1,1").is_err());
        // Γ = ±B is only in the closed set
        assert!(NdParams::<f64>::parse(ModelKind::Shc, "1,1,0.5,1,1,1").is_err());
        NdParams::with_admissibility(
            ModelKind::Shc,
            Admissibility::Closed,
            1.0,
            1.0,
            0.5,
            0.0,
            1.0,
            1.0,
        )
        .unwrap();
        // an interval Γ that reaches B is refused
        assert!(NdParams::<Interval>::parse(ModelKind::Shc, "1,0.5..1,0.5,1,1,1").is_err());
    }
}
