//! Nondimensionalization both ways and the base-parameter map 𝓟(P*, v0).
//!
//! Physical parameters (m, k, c, n, p, α, β, γ, A) and an impact speed v0 give
//! (eq:BWSHCCM_T_c, eq:BWSHCCM_X_c, eq:BWSHCCM_Z_c and their BWMCM twins):
//!
//! ```text
//! D   = α + α_c A^p
//! T_c = D^(−1/(p+1)) (m/k)^(1/(p+1)) v0^(−(p−1)/(p+1))
//! X_c = D^(−1/(p+1)) (m/k)^(1/(p+1)) v0^(2/(p+1)),     Z_c = A X_c
//! B   = (A^(p+1)/D)^(n/(p+1)) (β/A) (m/k)^(n/(p+1)) v0^(2n/(p+1))      (Γ: γ for β)
//! κ   = α/D
//! σ   = c v0 / (D k)                                   (BWSHCCM)
//! σ   = D^(1/(p+1)) (m^p k)^(1/(p+1)) v0^((p−1)/(p+1)) / c   (BWMCM)
//! ```
//!
//! The base-parameter map 𝓟(P*, v0) (sec:KVCL, sec:MCL) carries P* = (B_b, Γ_b, κ, σ_b, n, p)
//! to P = (B_b v0^(2n/(p+1)), Γ_b v0^(2n/(p+1)), κ, σ_b v0^e, n, p) with e = 1 for the
//! BWSHCCM and e = (p−1)/(p+1) for the BWMCM. The base set of a physical set is its P at v0 = 1.
//! All of it is computed in the arithmetic of `R`: for intervals, every derived constant is an
//! enclosure.

use super::params::{Admissibility, ModelKind, NdParams, ParamError, parse_list, show};
use crate::arith::Real;

/// 𝓟(P*, v0): the nondimensional parameters of base set `base` at impact speed `v0` (> 0).
///
/// The base set is in 𝓟 (P* ∈ ℙ*) as its maker checked it ([`NdParams::new`], or
/// [`NdParams::parse`] on the decimals as written); here its enclosures are checked as
/// [`Admissibility::Written`] (a decimal next to a strict bound has an enclosure that touches
/// it). The map keeps every point in 𝓟, since B and Γ are scaled by the same
/// s = v0^(2n/(p+1)) > 0 and σ by a positive factor. The mapped set is therefore not
/// re-validated field by field: for a range of v0 that check would compare the enclosures of Γ
/// and B as if independent and refuse admissible input.
pub fn nd_from_base<R: Real>(
    kind: ModelKind,
    base: &NdParams<R>,
    v0: &R,
) -> Result<NdParams<R>, ParamError> {
    check_speed(v0)?;
    base.validate(kind, Admissibility::Written)?;
    let one = R::one();
    let p1 = base.p.clone() + one.clone();
    let s = v0.pow(&(R::from_int(2) * base.n.clone() / p1.clone()));
    let sigma_exp = match kind {
        ModelKind::Shc => one.clone(),
        ModelKind::Maxwell => (base.p.clone() - one) / p1,
    };
    let sigma = base.sigma.clone() * v0.pow(&sigma_exp);
    let mapped = NdParams {
        b: base.b.clone() * s.clone(),
        gamma: base.gamma.clone() * s,
        kappa: base.kappa.clone(),
        sigma,
        n: base.n.clone(),
        p: base.p.clone(),
    };
    // what can still fail is arithmetic, not admissibility: overflow to ±∞, an underflow to 0
    for (x, name) in [(&mapped.b, "B"), (&mapped.sigma, "σ")] {
        if !x.is_finite() || x.lo() <= 0.0 {
            return Err(ParamError(format!(
                "{name} = {} at v0 = {} is not a finite positive number",
                show(x),
                show(v0)
            )));
        }
    }
    Ok(mapped)
}

/// Checks an impact speed: finite and > 0 (every value, for an interval).
pub fn check_speed<R: Real>(v0: &R) -> Result<(), ParamError> {
    if !v0.is_finite() || v0.lo().is_nan() {
        return Err(ParamError(format!(
            "v0 = {} is not a finite number",
            show(v0)
        )));
    }
    if v0.lo() <= 0.0 {
        // a positive decimal below the smallest positive double: its enclosure reaches 0
        let why = if v0.hi() > 0.0 && v0.hi() < f64::MIN_POSITIVE {
            " (this one is below the smallest positive double: its enclosure reaches 0)"
        } else {
            ""
        };
        return Err(ParamError(format!("v0 = {} must be > 0{why}", show(v0))));
    }
    Ok(())
}

/// Physical parameters of the BWSHCCM (eq:BWSHCCM) or the BWMCM (eq:BWMCM), SI units:
/// m \[kg\], k \[kg m^(1−p) s^−2\], c \[kg m^−p s^−1\] (BWSHCCM) or \[kg s^−1\] (BWMCM), β, γ \[m^−n\].
#[derive(Clone, Debug)]
pub struct PhysicalParams<R> {
    pub m: R,
    pub k: R,
    pub c: R,
    pub n: R,
    pub p: R,
    pub alpha: R,
    pub beta: R,
    pub gamma: R,
    pub a: R,
}

/// The scales of a nondimensionalization: t = T·T_c, x = X·X_c, z = Z·Z_c, v = V·X_c/T_c,
/// force = F_P · m X_c / T_c².
#[derive(Clone, Debug)]
pub struct Scales<R> {
    pub t_c: R,
    pub x_c: R,
    pub z_c: R,
    /// X_c / T_c: the velocity scale.
    pub v_c: R,
    /// m X_c / T_c²: the force scale.
    pub f_c: R,
}

impl<R: Real> PhysicalParams<R> {
    /// The keys of the `m=…,k=…` syntax, in order.
    pub const KEYS: [&'static str; 9] = ["m", "k", "c", "n", "p", "alpha", "beta", "gamma", "A"];

    /// Parses "m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925".
    pub fn parse(kind: ModelKind, text: &str) -> Result<Self, ParamError> {
        let mut vals: [Option<R>; 9] = Default::default();
        for item in text.split(',') {
            let (key, val) = item.split_once('=').ok_or_else(|| {
                ParamError(format!("'{}' is not of the form key=value", item.trim()))
            })?;
            let key = key.trim();
            let i = Self::KEYS.iter().position(|k| *k == key).ok_or_else(|| {
                ParamError(format!(
                    "unknown physical parameter '{key}' (expected {})",
                    Self::KEYS.join(", ")
                ))
            })?;
            if vals[i].is_some() {
                return Err(ParamError(format!(
                    "physical parameter '{key}' given twice"
                )));
            }
            vals[i] = Some(R::parse_decimal(val).map_err(|e| ParamError(format!("{key}: {e}")))?);
        }
        let missing: Vec<&str> = Self::KEYS
            .iter()
            .zip(&vals)
            .filter(|(_, v)| v.is_none())
            .map(|(k, _)| *k)
            .collect();
        if !missing.is_empty() {
            return Err(ParamError(format!(
                "missing physical parameter(s): {}",
                missing.join(", ")
            )));
        }
        check_physical_decimals(kind, text)?;
        let [m, k, c, n, p, alpha, beta, gamma, a] = vals.map(Option::unwrap);
        let s = Self {
            m,
            k,
            c,
            n,
            p,
            alpha,
            beta,
            gamma,
            a,
        };
        s.validate(kind)?;
        Ok(s)
    }

    /// The enclosures of values checked exactly ([`check_physical_decimals`]): finite, and what
    /// outward rounding keeps of m, k, c, A > 0, α ∈ (0, 1), β > 0, γ ∈ (−β, β), n, p ≥ 1 (the
    /// closed bounds; −sup β ≤ γ ≤ sup β), as [`Admissibility::Written`] does for P.
    pub fn validate(&self, kind: ModelKind) -> Result<(), ParamError> {
        let _ = kind;
        let all = [
            &self.m,
            &self.k,
            &self.c,
            &self.n,
            &self.p,
            &self.alpha,
            &self.beta,
            &self.gamma,
            &self.a,
        ];
        for (x, key) in all.iter().zip(Self::KEYS) {
            if !x.is_finite() {
                return Err(ParamError(format!(
                    "{key} = {} is not a finite number",
                    show(*x)
                )));
            }
        }
        for (x, key) in [
            (&self.m, "m"),
            (&self.k, "k"),
            (&self.a, "A"),
            (&self.c, "c"),
            (&self.beta, "beta"),
        ] {
            if x.lo() < 0.0 {
                return Err(ParamError(format!("{key} = {} must be > 0", show(x))));
            }
        }
        if !(self.alpha.lo() >= 0.0 && self.alpha.hi() <= 1.0) {
            return Err(ParamError(format!(
                "alpha = {} must lie in (0, 1)",
                show(&self.alpha)
            )));
        }
        if !(self.gamma.lo() >= -self.beta.hi() && self.gamma.hi() <= self.beta.hi()) {
            return Err(ParamError(format!(
                "gamma = {} must lie in (−beta, beta) = ({}, {})",
                show(&self.gamma),
                -self.beta.hi(),
                self.beta.hi()
            )));
        }
        if self.n.lo() < 1.0 {
            return Err(ParamError(format!("n = {} must be ≥ 1", show(&self.n))));
        }
        if self.p.lo() < 1.0 {
            return Err(ParamError(format!("p = {} must be ≥ 1", show(&self.p))));
        }
        Ok(())
    }

    /// D = α + α_c A^p.
    fn d(&self) -> R {
        self.alpha.clone() + (R::one() - self.alpha.clone()) * self.a.pow(&self.p)
    }

    /// T_c, X_c, Z_c and the velocity and force scales at impact speed v0.
    pub fn scales(&self, v0: &R) -> Scales<R> {
        let one = R::one();
        let p1 = self.p.clone() + one.clone();
        let e = one.clone() / p1.clone();
        let common = (one.clone() / self.d()).pow(&e) * (self.m.clone() / self.k.clone()).pow(&e);
        let t_c = common.clone() * v0.pow(&(-(self.p.clone() - one.clone()) / p1.clone()));
        let x_c = common * v0.pow(&(R::from_int(2) / p1));
        let z_c = self.a.clone() * x_c.clone();
        let v_c = x_c.clone() / t_c.clone();
        let f_c = self.m.clone() * v_c.clone() / t_c.clone();
        Scales {
            t_c,
            x_c,
            z_c,
            v_c,
            f_c,
        }
    }

    /// The nondimensional parameters P at impact speed v0 (sec:KVCL / sec:MCL), validated
    /// against 𝓟.
    pub fn nondimensionalize(&self, kind: ModelKind, v0: &R) -> Result<NdParams<R>, ParamError> {
        check_speed(v0)?;
        let one = R::one();
        let p1 = self.p.clone() + one.clone();
        let d = self.d();
        let mk = self.m.clone() / self.k.clone();
        let en = self.n.clone() / p1.clone();
        let common =
            (self.a.pow(&p1) / d.clone()).pow(&en) * mk.pow(&en) * v0.pow(&(R::from_int(2) * en))
                / self.a.clone();
        let b = common.clone() * self.beta.clone();
        let gamma = common * self.gamma.clone();
        // κ = α/D written with α once, 1/(1 + (1/α − 1)A^p): over a range of α (and of A, p)
        // its interval value is the exact range, inside (0, 1); α/D would use α twice and
        // exceed 1 (α = 0.05..0.15 at the baseball set: sup κ > 1, a range refused as outside 𝓟)
        let kappa = one.clone()
            / (one.clone()
                + (one.clone() / self.alpha.clone() - one.clone()) * self.a.pow(&self.p));
        let sigma = match kind {
            ModelKind::Shc => self.c.clone() * v0.clone() / (d * self.k.clone()),
            ModelKind::Maxwell => {
                let e = one.clone() / p1.clone();
                d.pow(&e)
                    * (self.m.pow(&self.p) * self.k.clone()).pow(&e)
                    * v0.pow(&((self.p.clone() - one) / p1))
                    / self.c.clone()
            }
        };
        // (in 𝓟 exactly for the values checked by `check_physical_decimals`: B, Γ scale β, γ by
        // one factor > 0, κ = α/D ∈ (0, 1) for A > 0, σ > 0 for c > 0). A value that is not a
        // finite number or is 0 here is the arithmetic's range, not 𝓟: said as such
        for (name, x) in [("B", &b), ("Γ", &gamma), ("κ", &kappa), ("σ", &sigma)] {
            let zero_from_positive = x.lo() <= 0.0 && x.hi() >= 0.0 && name != "Γ";
            if !x.is_finite() || x.lo().is_nan() || x.hi().is_nan() || zero_from_positive {
                return Err(ParamError(format!(
                    "the nondimensional {name} = {} is beyond the range of the arithmetic (an \
                     overflow or underflow: the physical values' scales are too far apart)",
                    show(x)
                )));
            }
        }
        NdParams::with_admissibility(
            kind,
            Admissibility::Written,
            b,
            gamma,
            kappa,
            sigma,
            self.n.clone(),
            self.p.clone(),
        )
        .map_err(|e| ParamError(format!("the nondimensional set is outside 𝓟: {}", e.0)))
    }

    /// The base parameters P* of this physical system: 𝓟(P*, v0) = the nondimensional set at
    /// v0, for every v0 (its value at v0 = 1).
    pub fn base(&self, kind: ModelKind) -> Result<NdParams<R>, ParamError> {
        self.nondimensionalize(kind, &R::one())
    }
}

/// Checks the physical parameters "m=…,k=…,…" as written (each a decimal or a range a..b;
/// keys and syntax already checked by [`PhysicalParams::parse`]) exactly: every value of every
/// range, as rationals, must give a nondimensional set in 𝓟 — m, k, c, A > 0, α ∈ (0, 1),
/// β > 0, γ ∈ (−β, β) (Γ/B = γ/β), n, p ≥ 1, and for the Maxwell model p ∈ [2, ∞) ∪ {1}. (The paper's BWHCL allows c = 0, β = 0 and
/// γ = ±β; 𝓟 needs σ > 0, B > 0 and |Γ| < B.) The message names the value as written.
pub fn check_physical_decimals(kind: ModelKind, text: &str) -> Result<(), ParamError> {
    use super::params::decimal_range;
    let mut v: std::collections::HashMap<&str, ([rug::Rational; 2], &str)> = Default::default();
    for item in text.split(',') {
        let Some((key, val)) = item.split_once('=') else {
            continue;
        };
        let r = decimal_range(val).map_err(|e| ParamError(format!("{}: {e}", key.trim())))?;
        v.insert(key.trim(), (r, val.trim()));
    }
    let get = |k: &str| {
        v.get(k)
            .cloned()
            .ok_or_else(|| ParamError(format!("missing physical parameter(s): {k}")))
    };
    let zero = rug::Rational::new();
    let one = rug::Rational::from(1);
    for key in ["m", "k", "c", "A", "beta"] {
        let (r, t) = get(key)?;
        if r[0] <= zero {
            return Err(ParamError(format!("{key} = {t} must be > 0")));
        }
    }
    let (alpha, ta) = get("alpha")?;
    if !(alpha[0] > zero && alpha[1] < one) {
        return Err(ParamError(format!("alpha = {ta} must lie in (0, 1)")));
    }
    let (beta, tb) = get("beta")?;
    let (gamma, tg) = get("gamma")?;
    if !(gamma[0] > -beta[0].clone() && gamma[1] < beta[0]) {
        let lo = tb.split("..").next().unwrap_or(tb).trim();
        let lo = lo.strip_prefix('+').unwrap_or(lo);
        return Err(ParamError(format!(
            "gamma = {tg} must lie in (−beta, beta) = (-{lo}, {lo}) (the nondimensional Γ/B = γ/β must lie in (−1, 1))"
        )));
    }
    for key in ["n", "p"] {
        let (r, t) = get(key)?;
        if r[0] < one {
            return Err(ParamError(format!("{key} = {t} must be ≥ 1")));
        }
        let two = rug::Rational::from(2);
        if key == "p"
            && kind == ModelKind::Maxwell
            && !((r[0] == one && r[1] == one) || r[0] >= two)
        {
            return Err(ParamError(format!(
                "p = {t} must lie in [2, ∞) ∪ {{1}} for the Maxwell model"
            )));
        }
    }
    Ok(())
}

/// Parses a list of impact speeds "1,2.5,3" (each > 0; for intervals each may be a range a..b).
pub fn parse_speeds<R: Real>(text: &str) -> Result<Vec<R>, ParamError> {
    let n = text.split(',').count();
    let v = parse_list::<R>(text, n, &vec!["v0"; n].join(","))?;
    for x in &v {
        check_speed(x)?;
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn baseball() -> PhysicalParams<f64> {
        PhysicalParams::parse(
            ModelKind::Shc,
            "m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925",
        )
        .unwrap()
    }

    #[test]
    fn base_map_agrees_with_direct_nondimensionalization() {
        for kind in [ModelKind::Shc, ModelKind::Maxwell] {
            let phys = PhysicalParams {
                p: if kind == ModelKind::Maxwell { 2.3 } else { 1.7 },
                ..baseball()
            };
            let base = phys.base(kind).unwrap();
            for v0 in [0.3, 1.0, 2.15, 5.02] {
                let direct = phys.nondimensionalize(kind, &v0).unwrap();
                let mapped = nd_from_base(kind, &base, &v0).unwrap();
                for (a, b) in direct.as_array().iter().zip(mapped.as_array()) {
                    assert!(
                        (a - b).abs() <= 1e-13 * a.abs(),
                        "{kind:?} v0={v0}: {a} vs {b}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_range_of_speeds_maps_to_an_admissible_set() {
        use inari::Interval;
        let base =
            NdParams::<Interval>::parse(ModelKind::Shc, "1.43,-1.42,0.632,0.00715,1.31,1.27")
                .unwrap();
        let v0 = Interval::parse_decimal("0.9..1.1").unwrap();
        let p = nd_from_base(ModelKind::Shc, &base, &v0).unwrap();
        assert!(p.b.inf() < 1.43 && p.b.sup() > 1.43);
        // a base set outside ℙ* is refused before mapping
        let bad = NdParams {
            gamma: Interval::parse_decimal("-1.5").unwrap(),
            ..base
        };
        assert!(
            nd_from_base(ModelKind::Shc, &bad, &v0)
                .unwrap_err()
                .0
                .contains("Γ = -1.5")
        );
    }

    #[test]
    fn scales_satisfy_their_definitions() {
        let phys = baseball();
        let v0 = 3.03;
        let s = phys.scales(&v0);
        // v0 in units of X_c/T_c is 1 … by construction V(0) = −1.
        assert!((v0 / s.v_c - 1.0).abs() < 1e-13);
        // κ = α/D and B, Γ keep the ratio β/γ
        let nd = phys.nondimensionalize(ModelKind::Shc, &v0).unwrap();
        assert!((nd.b / nd.gamma - 981.05 / -961.4).abs() < 1e-12);
        assert!((s.z_c / s.x_c - 0.925).abs() < 1e-15);
    }

    #[test]
    fn bad_physical_input_is_named() {
        let e = PhysicalParams::<f64>::parse(ModelKind::Shc, "m=0.146,k=1").unwrap_err();
        assert!(e.0.starts_with("missing physical parameter(s): c"), "{e}");
        let e = PhysicalParams::<f64>::parse(
            ModelKind::Shc,
            "m=-1,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925",
        )
        .unwrap_err();
        assert_eq!(e.0, "m = -1 must be > 0");
        assert!(check_speed(&0.0).is_err() && check_speed(&f64::NAN).is_err());
        assert!(parse_speeds::<f64>("1,abc").is_err());
    }
}
