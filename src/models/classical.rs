//! The classical collision laws' parameters as a user gives them — nondimensional, as a family
//! over the impact speed (base), or physical (SI) — and the nondimensional model each gives at
//! an impact speed: what `cor`, `trajectory` and `loop` run for `--model <law>`.
//!
//! ```text
//! law              physical (SI)      nondimensional     base (at v0 = 1 m/s)   the model at v0
//! hooke            m, k               —                  —                      X″ = −X
//! hertz            m, k, n            n                  n                      X″ = −|X|^(n−1)X
//! hunt-crossley    m, k, n, chi       sigma, n           sigma_b, n             σ = χ v0/k = σ_b v0
//! kelvin-voigt     m, k, c            zeta               zeta                   ζ = c/(2√(mk))
//! linear-maxwell   m, k, c            c                  c                      c̃ = c/√(mk)
//! ```
//!
//! n is optional (3/2, Hertz's, when not given). The laws are F = kδ (Hooke), F = k|δ|^(n−1)δ
//! (Hertz), F = k|δ|^(n−1)δ + χ|δ|^n δ̇ (Hunt–Crossley, [`super::hunt_crossley`]), F = kδ + cδ̇
//! (Kelvin–Voigt, [`super::kelvin_voigt`]) and the spring and dashpot in series (linear
//! Maxwell, [`super::linear_maxwell`]), for a body of mass m meeting the contact at speed v0.
//! With n = 1 for the linear laws, the scales are
//!
//! ```text
//! L = (m v0²/k)^(1/(n+1)),   T_c = L/v0,   δ = L·X,   t = T_c·T,   v = v0·V,   F = (m v0/T_c)·F̃
//! ```
//!
//! (for n = 1: T_c = √(m/k)); m δ̈ = −F then is the nondimensional law from X = 0, V = −1, and
//! e = V(T_s) is the same number in both forms.
//!
//! The values are checked as written, exactly (as rationals, each a decimal or a range a..b):
//! m, k > 0, n ≥ 1, χ, σ, σ_b, ζ ≥ 0 and the Kelvin–Voigt dashpot c ≥ 0, the Maxwell dashpot
//! c > 0 (c̃ ≤ 1/2 is admissible: that law never separates, which the engines prove as "no
//! separation before the horizon").

use super::hunt_crossley::HuntCrossley;
use super::kelvin_voigt::KelvinVoigt;
use super::linear_maxwell::LinearMaxwell;
use super::params::{ParamError, decimal_range, show};
use super::scaling::{Scales, check_speed};
use crate::arith::Real;
use rug::Rational;

/// A classical collision law.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Law {
    Hooke,
    Hertz,
    HuntCrossley,
    KelvinVoigt,
    LinearMaxwell,
}

impl Law {
    pub const ALL: [Law; 5] = [
        Law::Hooke,
        Law::Hertz,
        Law::HuntCrossley,
        Law::KelvinVoigt,
        Law::LinearMaxwell,
    ];

    /// The law's name on the command line.
    pub fn key(self) -> &'static str {
        match self {
            Law::Hooke => "hooke",
            Law::Hertz => "hertz",
            Law::HuntCrossley => "hunt-crossley",
            Law::KelvinVoigt => "kelvin-voigt",
            Law::LinearMaxwell => "linear-maxwell",
        }
    }

    pub fn from_key(key: &str) -> Option<Law> {
        Law::ALL.into_iter().find(|l| l.key() == key)
    }

    /// The keys of the law's parameters given as `source` (module doc), in order.
    pub fn keys(self, source: LawSource) -> &'static [&'static str] {
        use LawSource::*;
        match (self, source) {
            (Law::Hooke, Physical) => &["m", "k"],
            (Law::Hooke, _) => &[],
            (Law::Hertz, Physical) => &["m", "k", "n"],
            (Law::Hertz, _) => &["n"],
            (Law::HuntCrossley, Physical) => &["m", "k", "n", "chi"],
            (Law::HuntCrossley, Nd) => &["sigma", "n"],
            (Law::HuntCrossley, Base) => &["sigma_b", "n"],
            (Law::KelvinVoigt, Physical) => &["m", "k", "c"],
            (Law::KelvinVoigt, _) => &["zeta"],
            (Law::LinearMaxwell, Physical) => &["m", "k", "c"],
            (Law::LinearMaxwell, _) => &["c"],
        }
    }
}

/// How a law's parameters are given (module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LawSource {
    /// The nondimensional model, used as is (no impact speed).
    Nd,
    /// The family over the impact speed, at v0 = 1 m/s.
    Base,
    /// SI units: m \[kg\], k \[N/m^n\], χ \[N s/m^(n+1)\], c \[N s/m\].
    Physical,
}

/// A law's parameters as given: the exponent n (1 for the linear laws), the damping d (σ, σ_b,
/// ζ or c̃ — or χ or c for physical ones; 0 for Hooke and Hertz), and for physical ones m, k
/// (1 otherwise).
#[derive(Clone, Debug)]
pub struct LawParams<R> {
    pub law: Law,
    pub source: LawSource,
    pub n: R,
    pub d: R,
    pub m: R,
    pub k: R,
}

/// Whether parameter `key` of `law` must be > 0 (m, k, and the linear Maxwell law's c).
fn must_be_positive(law: Law, key: &str) -> bool {
    matches!(key, "m" | "k") || (key == "c" && law == Law::LinearMaxwell)
}

/// The condition a value must satisfy as written: > 0 (`true`) or ≥ 0, and n ≥ 1.
fn check_value(law: Law, key: &str, v: &[Rational; 2], token: &str) -> Result<(), ParamError> {
    let zero = Rational::new();
    let fail = |what: &str| Err(ParamError(format!("{key} = {token} must be {what}")));
    match key {
        "n" if v[0] < 1 => fail("≥ 1"),
        _ if must_be_positive(law, key) && v[0] <= zero => fail("> 0"),
        "chi" | "sigma" | "sigma_b" | "zeta" | "c" if v[0] < zero => fail("≥ 0"),
        _ => Ok(()),
    }
}

impl<R: Real> LawParams<R> {
    /// Parses "key=value,…" (the keys of [`Law::keys`]; n may be left out; Hooke's nondimensional
    /// and base sets are the empty text), each value checked exactly as written (module doc).
    pub fn parse(law: Law, source: LawSource, text: &str) -> Result<Self, ParamError> {
        let keys = law.keys(source);
        let mut vals: Vec<Option<R>> = vec![None; keys.len()];
        let expected = || {
            if keys.is_empty() {
                format!("{} takes no parameter here: give ''", law.key())
            } else {
                format!("{} takes {}", law.key(), keys.join(", "))
            }
        };
        let items: Vec<&str> = match text.trim() {
            "" => vec![],
            t => t.split(',').collect(),
        };
        for item in items {
            let (key, val) = item.split_once('=').ok_or_else(|| {
                ParamError(format!("'{}' is not of the form key=value", item.trim()))
            })?;
            let key = key.trim();
            let i = keys
                .iter()
                .position(|k| *k == key)
                .ok_or_else(|| ParamError(format!("unknown parameter '{key}' ({})", expected())))?;
            if vals[i].is_some() {
                return Err(ParamError(format!("parameter '{key}' given twice")));
            }
            let exact = decimal_range(val).map_err(|e| ParamError(format!("{key}: {e}")))?;
            check_value(law, key, &exact, val.trim())?;
            let parsed = R::parse_decimal(val).map_err(|e| ParamError(format!("{key}: {e}")))?;
            // > 0 as written but not as enclosed: a decimal below the smallest positive double
            if must_be_positive(law, key) && parsed.lo() <= 0.0 {
                return Err(ParamError(format!(
                    "{key} = {} is below the smallest positive double (its enclosure reaches 0)",
                    val.trim()
                )));
            }
            vals[i] = Some(parsed);
        }
        let get = |name: &str| -> Result<Option<R>, ParamError> {
            match keys.iter().position(|k| *k == name) {
                None => Ok(None),
                Some(i) => match &vals[i] {
                    Some(v) => Ok(Some(v.clone())),
                    None if name == "n" => Ok(Some(
                        R::from_int(3) / R::from_int(2), // exact: 3/2 is a double
                    )),
                    None => Err(ParamError(format!(
                        "missing parameter '{name}' ({})",
                        expected()
                    ))),
                },
            }
        };
        let damping = ["chi", "sigma", "sigma_b", "zeta", "c"];
        let d = match damping.iter().find(|k| keys.contains(k)) {
            Some(k) => get(k)?.expect("a key of the law"),
            None => R::zero(),
        };
        let linear = matches!(law, Law::Hooke | Law::KelvinVoigt | Law::LinearMaxwell);
        Ok(Self {
            law,
            source,
            n: if linear {
                R::one()
            } else {
                get("n")?.expect("n")
            },
            d,
            m: get("m")?.unwrap_or_else(R::one),
            k: get("k")?.unwrap_or_else(R::one),
        })
    }

    /// The nondimensional parameters at impact speed v0 (module doc); an `Nd` set is its own.
    /// A derived value that is not a finite number (an overflow of m/k, say) is refused.
    pub fn at(&self, v0: &R) -> Result<Self, ParamError> {
        check_speed(v0)?;
        let d = match (self.source, self.law) {
            (LawSource::Nd, _) => return Ok(self.clone()),
            (_, Law::Hooke | Law::Hertz) => R::zero(),
            (LawSource::Base, Law::HuntCrossley) => self.d.clone() * v0.clone(),
            (LawSource::Base, _) => self.d.clone(),
            (LawSource::Physical, Law::HuntCrossley) => {
                self.d.clone() * v0.clone() / self.k.clone()
            }
            (LawSource::Physical, Law::KelvinVoigt) => {
                self.d.clone() / (R::from_int(2) * (self.m.clone() * self.k.clone()).sqrt())
            }
            (LawSource::Physical, Law::LinearMaxwell) => {
                self.d.clone() / (self.m.clone() * self.k.clone()).sqrt()
            }
        };
        if !d.is_finite() || d.lo().is_nan() {
            return Err(ParamError(format!(
                "the nondimensional damping at v0 = {} is {}, not a finite number",
                show(v0),
                show(&d)
            )));
        }
        Ok(Self {
            source: LawSource::Nd,
            d,
            m: R::one(),
            k: R::one(),
            ..self.clone()
        })
    }

    /// The scales of a physical set at v0 (module doc); `None` for the other sources.
    pub fn scales(&self, v0: &R) -> Result<Option<Scales<R>>, ParamError> {
        if self.source != LawSource::Physical {
            return Ok(None);
        }
        let one = R::one();
        // L = (m v0²/k)^(1/(n+1)) as (m^q/k^q)·v0^(2q), q = 1/(n+1), F_c = m v0/T_c: neither
        // m·v0² nor m/k is formed, which may lie beyond the doubles while L does not (m = k =
        // v0 = 1e300: L = 1e300 m, T_c = 1 s; m = 1e-300, k = 1e300: L = 1e-300 m)
        let q = one.clone() / (self.n.clone() + one);
        let l = self.m.pow(&q) / self.k.pow(&q) * v0.pow(&(q.clone() + q.clone()));
        let t_c = l.clone() / v0.clone();
        let f_c = self.m.clone() * v0.clone() / t_c.clone();
        for (name, x) in [("length L", &l), ("time T_c", &t_c), ("force F_c", &f_c)] {
            if !(x.is_finite() && x.lo() > 0.0) {
                return Err(ParamError(format!(
                    "the {name} scale at v0 = {} is {}: beyond the range of the arithmetic (an \
                     overflow or underflow: the physical values' scales are too far apart)",
                    show(v0),
                    show(x)
                )));
            }
        }
        Ok(Some(Scales {
            t_c,
            x_c: l.clone(),
            // the Maxwell dashpot's displacement has the scale of δ
            z_c: l,
            v_c: v0.clone(),
            f_c,
        }))
    }

    /// The nondimensional values by name, for output: n, sigma, zeta or c as the law has them.
    pub fn named(&self) -> Vec<(&'static str, R)> {
        let names = self.law.keys(self.source);
        let mut out = Vec::new();
        for k in names {
            let v = match *k {
                "n" => self.n.clone(),
                "m" => self.m.clone(),
                "k" => self.k.clone(),
                _ => self.d.clone(),
            };
            out.push((*k, v));
        }
        out
    }

    /// The model of a nondimensional set (after [`Self::at`]).
    pub fn model(&self) -> Result<LawModel<R>, String> {
        debug_assert_eq!(self.source, LawSource::Nd);
        Ok(match self.law {
            Law::Hooke => LawModel::Force(HuntCrossley::hooke()),
            Law::Hertz => LawModel::Force(HuntCrossley::hertz(self.n.clone())?),
            Law::HuntCrossley => {
                LawModel::Force(HuntCrossley::new(self.d.clone(), self.n.clone())?)
            }
            Law::KelvinVoigt => LawModel::KelvinVoigt(KelvinVoigt::new(self.d.clone())?),
            Law::LinearMaxwell => LawModel::LinearMaxwell(LinearMaxwell::new(self.d.clone())?),
        })
    }
}

/// A classical law's nondimensional model: Hooke, Hertz and Hunt–Crossley are one force law
/// ([`HuntCrossley`] with σ = 0, and n = 1 for Hooke).
#[derive(Clone, Debug)]
pub enum LawModel<R: Real> {
    Force(HuntCrossley<R>),
    KelvinVoigt(KelvinVoigt<R>),
    LinearMaxwell(LinearMaxwell<R>),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn physical_hunt_crossley_gives_sigma_and_scales() {
        let p =
            LawParams::<f64>::parse(Law::HuntCrossley, LawSource::Physical, "m=2,k=8,chi=4,n=1")
                .unwrap();
        let nd = p.at(&3.0).unwrap();
        // σ = χ v0/k = 4·3/8
        assert_eq!(nd.d, 1.5);
        assert_eq!(nd.n, 1.0);
        let s = p.scales(&3.0).unwrap().unwrap();
        // n = 1: T_c = √(m/k) = 1/2, L = v0 T_c
        assert_eq!(s.t_c, 0.5);
        assert_eq!(s.x_c, 1.5);
        assert_eq!(s.f_c, 12.0);
    }

    #[test]
    fn linear_laws_take_the_damping_ratio() {
        let kv =
            LawParams::<f64>::parse(Law::KelvinVoigt, LawSource::Physical, "m=1,k=4,c=2").unwrap();
        assert_eq!(kv.at(&7.0).unwrap().d, 0.5); // ζ = c/(2√(mk))
        let lm = LawParams::<f64>::parse(Law::LinearMaxwell, LawSource::Physical, "m=1,k=4,c=2")
            .unwrap();
        assert_eq!(lm.at(&7.0).unwrap().d, 1.0); // c̃ = c/√(mk)
        let b =
            LawParams::<f64>::parse(Law::HuntCrossley, LawSource::Base, "sigma_b=0.25").unwrap();
        let nd = b.at(&2.0).unwrap();
        assert_eq!((nd.d, nd.n), (0.5, 1.5));
    }

    #[test]
    fn values_are_checked_as_written() {
        let bad = |law, src, text: &str| LawParams::<f64>::parse(law, src, text).unwrap_err().0;
        // 1e-400 > 0 as written, but its double is 0: refused as read, with that reason (it
        // was refused later, σ = χv0/k not finite)
        assert!(
            bad(Law::HuntCrossley, LawSource::Physical, "m=1,k=1e-400,chi=1")
                .contains("'1e-400' is below the smallest positive double")
        );
        assert_eq!(
            bad(Law::HuntCrossley, LawSource::Physical, "m=1,k=0,chi=1"),
            "k = 0 must be > 0"
        );
        assert!(bad(Law::HuntCrossley, LawSource::Physical, "m=1,k=-0,chi=1").contains("> 0"));
        assert!(bad(Law::Hertz, LawSource::Nd, "n=0.999").contains("≥ 1"));
        assert!(bad(Law::LinearMaxwell, LawSource::Nd, "c=0").contains("> 0"));
        assert!(bad(Law::KelvinVoigt, LawSource::Nd, "zeta=-1e-30").contains("≥ 0"));
        assert!(bad(Law::KelvinVoigt, LawSource::Nd, "sigma=1").contains("unknown parameter"));
        assert!(bad(Law::KelvinVoigt, LawSource::Nd, "").contains("missing parameter 'zeta'"));
        assert!(bad(Law::Hooke, LawSource::Nd, "n=1").contains("no parameter"));
        assert!(LawParams::<f64>::parse(Law::Hooke, LawSource::Nd, "").is_ok());
        assert!(LawParams::<f64>::parse(Law::KelvinVoigt, LawSource::Nd, "zeta=0").is_ok());
    }
}
