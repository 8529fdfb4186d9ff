//! Which base parameters are searched, and where: each of P* = (B_b, Γ_b, κ, σ_b, n, p) is
//! either fixed to a value or free within bounds (lmfit's `vary` and `min`/`max`), as the
//! options `--fix name=value,…` and `--bounds name=lo..hi,…` of `fit`, `profile` and `identify`
//! give them.
//!
//! Names are ASCII words — `B_b, Gamma_b, kappa, sigma_b, n, p` — and the Greek letters are
//! accepted too (`Γ_b`, `κ`, `σ_b`), as are the nondimensional names without `_b` (`B`,
//! `Gamma`, `sigma`); case matters only to tell nothing apart (all are matched in lower case).

use super::data::echo;
use crate::models::ModelKind;

/// The parameters' names, in the order of P* (and of every vector of free values).
pub const NAMES: [&str; 6] = ["B_b", "Gamma_b", "kappa", "sigma_b", "n", "p"];

/// The index of a parameter in P* from its name (see the module doc), `None` if unknown.
pub fn param_index(name: &str) -> Option<usize> {
    let n = name.trim().to_lowercase();
    match n.as_str() {
        "b_b" | "b" | "bb" => Some(0),
        "gamma_b" | "γ_b" | "gamma" | "γ" | "gammab" => Some(1),
        "kappa" | "κ" => Some(2),
        "sigma_b" | "σ_b" | "sigma" | "σ" | "sigmab" => Some(3),
        "n" => Some(4),
        "p" => Some(5),
        _ => None,
    }
}

fn unknown(name: &str) -> String {
    format!(
        "'{}' is not a parameter name (one of {})",
        echo(name),
        NAMES.join(", ")
    )
}

/// Why `value` (a part of `item`) is no number: it is missing, or not a finite number.
fn not_a_number(item: &str, value: &str) -> String {
    if value.trim().is_empty() {
        format!("'{}' lacks a number", echo(item.trim()))
    } else {
        format!("'{}' is not a finite number", echo(value.trim()))
    }
}

/// A list `name=value,…` (`--fix`): each name once.
pub fn parse_fix(text: &str) -> Result<Vec<(usize, f64)>, String> {
    let mut out: Vec<(usize, f64)> = Vec::new();
    for item in text.split(',').filter(|s| !s.trim().is_empty()) {
        let Some((name, value)) = item.split_once('=') else {
            return Err(format!("'{}' is not name=value", echo(item)));
        };
        let i = param_index(name).ok_or_else(|| unknown(name))?;
        let v: f64 = value
            .trim()
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| not_a_number(item, value))?;
        if out.iter().any(|(j, _)| *j == i) {
            return Err(format!("{} is given twice", NAMES[i]));
        }
        out.push((i, v));
    }
    if out.is_empty() {
        return Err(format!("'{}' names no parameter", echo(text)));
    }
    Ok(out)
}

/// A list `name=lo..hi,…` (`--bounds`): each name once, lo < hi, both finite.
pub fn parse_bounds(text: &str) -> Result<Vec<(usize, f64, f64)>, String> {
    let mut out: Vec<(usize, f64, f64)> = Vec::new();
    for item in text.split(',').filter(|s| !s.trim().is_empty()) {
        let Some((name, range)) = item.split_once('=') else {
            return Err(format!("'{}' is not name=lo..hi", echo(item)));
        };
        let i = param_index(name).ok_or_else(|| unknown(name))?;
        let Some((a, b)) = range.split_once("..") else {
            return Err(format!("'{}' is not a range lo..hi", echo(range.trim())));
        };
        let num = |t: &str| -> Result<f64, String> {
            t.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| not_a_number(item, t))
        };
        let (lo, hi) = (num(a)?, num(b)?);
        if lo >= hi {
            return Err(format!(
                "{}: the range '{}' is empty or a point (lo < hi needed; a point is --fix)",
                NAMES[i],
                echo(range.trim())
            ));
        }
        if out.iter().any(|(j, _, _)| *j == i) {
            return Err(format!("{} is given twice", NAMES[i]));
        }
        out.push((i, lo, hi));
    }
    if out.is_empty() {
        return Err(format!("'{}' names no parameter", echo(text)));
    }
    Ok(out)
}

/// A parameter's role in a search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Slot {
    /// Held at this value.
    Fixed(f64),
    /// Searched within [lo, hi] (either end may be infinite for `fit`: no bound).
    Free { lo: f64, hi: f64 },
}

/// The search space: one [`Slot`] per parameter of P*.
#[derive(Clone, Debug, PartialEq)]
pub struct Space {
    pub kind: ModelKind,
    pub slots: [Slot; 6],
}

/// The interval of values 𝓟 allows each parameter alone (Γ_b's also depends on B_b: |Γ_b| < B_b),
/// and whether its ends are open.
pub fn admissible_range(kind: ModelKind, i: usize) -> (f64, f64, &'static str) {
    match (i, kind) {
        (0, _) => (0.0, f64::INFINITY, "B_b > 0"),
        (1, _) => (f64::NEG_INFINITY, f64::INFINITY, "|Γ_b| < B_b"),
        (2, _) => (0.0, 1.0, "κ ∈ (0, 1)"),
        (3, _) => (0.0, f64::INFINITY, "σ_b > 0"),
        (4, _) => (1.0, f64::INFINITY, "n ≥ 1"),
        (_, ModelKind::Shc) => (1.0, f64::INFINITY, "p ≥ 1"),
        (_, ModelKind::Maxwell) => (2.0, f64::INFINITY, "p ≥ 2 (the maxwell p = 1 is a point)"),
    }
}

impl Space {
    /// Every parameter free over all of 𝓟 (no bounds).
    pub fn unbounded(kind: ModelKind) -> Self {
        Self {
            kind,
            slots: [Slot::Free {
                lo: f64::NEG_INFINITY,
                hi: f64::INFINITY,
            }; 6],
        }
    }

    /// The space of `--fix`/`--bounds`: a fixed parameter at its value (checked against 𝓟
    /// alone), a bounded one free within its bounds (which must lie in 𝓟's range of it:
    /// closed ends allowed where 𝓟's end is closed), the others as `rest` gives them (free
    /// without bounds for `fit`; for `identify`, fixed at a `--base` value or an error).
    pub fn build(
        kind: ModelKind,
        fix: &[(usize, f64)],
        bounds: &[(usize, f64, f64)],
        rest: impl Fn(usize) -> Result<Slot, String>,
    ) -> Result<Self, String> {
        let mut slots = [Slot::Fixed(f64::NAN); 6];
        for (i, slot) in slots.iter_mut().enumerate() {
            let f = fix.iter().find(|(j, _)| *j == i);
            let b = bounds.iter().find(|(j, _, _)| *j == i);
            let (lo, hi, rule) = admissible_range(kind, i);
            let closed_lo = matches!(i, 4 | 5);
            *slot = match (f, b) {
                (Some(_), Some(_)) => {
                    return Err(format!("{} is both fixed and bounded", NAMES[i]));
                }
                (Some(&(_, v)), None) => {
                    let ok = (v > lo || (closed_lo && v == lo) || (i == 5 && v == 1.0)) && v < hi;
                    if !ok {
                        return Err(format!("{}={v} is outside 𝓟 ({rule})", NAMES[i]));
                    }
                    Slot::Fixed(v)
                }
                (None, Some(&(_, a, c))) => {
                    let ok = (a > lo || (closed_lo && a == lo)) && c <= hi;
                    if !ok || (i == 2 && c >= 1.0) {
                        return Err(format!("{}={a}..{c} reaches outside 𝓟 ({rule})", NAMES[i]));
                    }
                    Slot::Free { lo: a, hi: c }
                }
                (None, None) => rest(i)?,
            };
        }
        let s = Self { kind, slots };
        if let Some(why) = s.outside() {
            return Err(why);
        }
        Ok(s)
    }

    /// Why no point of the space is in 𝓟 (|Γ_b| < B_b fails everywhere), or `None`.
    pub fn outside(&self) -> Option<String> {
        let range = |i: usize| match self.slots[i] {
            Slot::Fixed(v) => (v, v),
            Slot::Free { lo, hi } => (lo, hi),
        };
        let (b_hi, (g_lo, g_hi)) = (range(0).1, range(1));
        let min_abs_gamma = if g_lo <= 0.0 && g_hi >= 0.0 {
            0.0
        } else {
            g_lo.abs().min(g_hi.abs())
        };
        (min_abs_gamma >= b_hi).then(|| {
            format!(
                "no point of the box has |Γ_b| < B_b (Γ_b ∈ [{g_lo}, {g_hi}], B_b ≤ {b_hi}): \
                 the box is outside 𝓟"
            )
        })
    }

    /// The indices of the free parameters, in the order of P*.
    pub fn free(&self) -> Vec<usize> {
        (0..6)
            .filter(|&i| matches!(self.slots[i], Slot::Free { .. }))
            .collect()
    }

    /// The names of the free parameters.
    pub fn free_names(&self) -> Vec<&'static str> {
        self.free().into_iter().map(|i| NAMES[i]).collect()
    }

    /// The full P* from the values of the free parameters (in the order of [`Space::free`]).
    pub fn point<T: Clone>(&self, free: &[T], fixed: impl Fn(f64) -> T) -> [T; 6] {
        let mut it = free.iter();
        std::array::from_fn(|i| match self.slots[i] {
            Slot::Fixed(v) => fixed(v),
            Slot::Free { .. } => it.next().expect("a value per free parameter").clone(),
        })
    }

    /// The bounds of the free parameters (in the order of [`Space::free`]).
    pub fn free_bounds(&self) -> Vec<(f64, f64)> {
        self.slots
            .iter()
            .filter_map(|s| match *s {
                Slot::Free { lo, hi } => Some((lo, hi)),
                Slot::Fixed(_) => None,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_ascii_and_greek() {
        for (n, i) in [
            ("B_b", 0),
            ("Gamma_b", 1),
            ("Γ_b", 1),
            ("kappa", 2),
            ("κ", 2),
            ("sigma_b", 3),
            ("σ_b", 3),
            ("n", 4),
            ("P", 5),
        ] {
            assert_eq!(param_index(n), Some(i), "{n}");
        }
        assert_eq!(param_index("alpha"), None);
    }

    #[test]
    fn fix_and_bounds_parse_and_refuse() {
        assert_eq!(parse_fix("kappa=0.632").unwrap(), vec![(2, 0.632)]);
        assert_eq!(
            parse_bounds("sigma_b=0.001..0.1, κ=0.4..0.8").unwrap(),
            vec![(3, 0.001, 0.1), (2, 0.4, 0.8)]
        );
        for bad in ["kappa", "zeta=1", "kappa=x", "kappa=1,kappa=2", "kappa=nan"] {
            assert!(parse_fix(bad).is_err(), "{bad}");
        }
        for bad in [
            "kappa=0.5",
            "kappa=0.8..0.4",
            "kappa=0.4..0.4",
            "q=1..2",
            "n=1..inf",
        ] {
            assert!(parse_bounds(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_box_outside_the_admissible_set_is_refused() {
        let free = |_| {
            Ok(Slot::Free {
                lo: f64::NEG_INFINITY,
                hi: f64::INFINITY,
            })
        };
        let k = ModelKind::Shc;
        assert!(Space::build(k, &[], &[(2, 0.5, 1.2)], free).is_err());
        assert!(Space::build(k, &[], &[(4, 0.5, 1.2)], free).is_err());
        assert!(Space::build(k, &[(2, 1.0)], &[], free).is_err());
        assert!(Space::build(k, &[], &[(4, 1.0, 1.2)], free).is_ok());
        // |Γ_b| ≥ B_b on the whole box
        let e = Space::build(k, &[(0, 1.0)], &[(1, 1.0, 2.0)], free).unwrap_err();
        assert!(e.contains("outside 𝓟"), "{e}");
        // partly inside: accepted (𝓟 bounds the set)
        let s = Space::build(k, &[], &[(0, 0.8, 1.6), (1, -1.6, 1.0)], free).unwrap();
        assert_eq!(s.free(), (0..6).collect::<Vec<_>>());
        let rest = |i: usize| Ok(Slot::Fixed([1.2, -1.0, 0.0, 0.0, 1.3, 1.4][i]));
        let s = Space::build(k, &[(2, 0.6)], &[(3, 0.001, 0.1)], rest).unwrap();
        assert_eq!(s.free_names(), vec!["sigma_b"]);
        assert_eq!(s.point(&[0.05], |v| v), [1.2, -1.0, 0.6, 0.05, 1.3, 1.4]);
    }
}
