//! `bwcl classical`: T_s and e of a classical collision law (Hooke, Hertz, Hunt–Crossley,
//! linear Kelvin–Voigt, linear Maxwell) on the f64 or the rigorous engine — the same engines and separation
//! rule as the Bouc–Wen models ([`bwcl::models::hunt_crossley`], [`bwcl::models::kelvin_voigt`]).

use super::CliError;
use super::args::{ClassicalArgs, Format, LawArg};
use super::output::{self, outward_pair};
use bwcl::arith::Real;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::fit::data::echo;
use bwcl::models::CollisionModel;
use bwcl::models::hunt_crossley::{DampingFormula, HuntCrossley};
use bwcl::models::kelvin_voigt::KelvinVoigt;
use bwcl::models::linear_maxwell::LinearMaxwell;
use bwcl::observables::decimal::{sci_up, width_up};
use bwcl::observables::restitution::{Big, formula_sigma as formula_sigma_of};
use bwcl::observables::rigorous::rigorous_impact;
use bwcl::observables::{FloatOptions, impact};
use inari::Interval;
use serde_json::json;

/// The law's name on the command line.
fn name(l: LawArg) -> &'static str {
    match l {
        LawArg::Hooke => "hooke",
        LawArg::Hertz => "hertz",
        LawArg::HuntCrossley => "hunt-crossley",
        LawArg::KelvinVoigt => "kelvin-voigt",
        LawArg::LinearMaxwell => "linear-maxwell",
    }
}

/// A parameter as written, parsed in the arithmetic `R` (a decimal enclosed exactly by the
/// interval types), or refused naming the option.
fn value<R: Real>(opt: &str, text: &str) -> Result<R, CliError> {
    R::parse_decimal(text).map_err(|e| {
        // the parser's reason (not a number, not finite, below the smallest double), with the
        // value as written
        let why = if e.contains("below the smallest positive double") {
            "is below the smallest positive double (it would be read as 0)"
        } else if e.contains("finite") {
            "is not a finite number"
        } else {
            "is not a number"
        };
        CliError::Input(format!("--{opt} '{}' {why}", echo(text)))
    })
}

/// Which parameters the law takes; any other given is refused.
fn check_options(a: &ClassicalArgs) -> Result<(), CliError> {
    let takes = |opt: &str| {
        matches!(
            (a.law, opt),
            (LawArg::Hertz | LawArg::HuntCrossley, "n")
                | (LawArg::HuntCrossley, "sigma")
                | (LawArg::KelvinVoigt, "zeta")
                | (LawArg::LinearMaxwell, "c")
                | (LawArg::HuntCrossley, "formula" | "e-star")
        )
    };
    for (opt, given) in [
        ("n", &a.n),
        ("sigma", &a.sigma),
        ("zeta", &a.zeta),
        ("c", &a.c),
        ("formula", &a.formula),
        ("e-star", &a.e_star),
    ] {
        if given.is_some() && !takes(opt) {
            return Err(CliError::Input(format!(
                "--{opt} is not a parameter of the law {}",
                name(a.law)
            )));
        }
    }
    if a.sigma.is_some() && (a.formula.is_some() || a.e_star.is_some()) {
        return Err(CliError::Input(
            "give the damping either as --sigma or as --formula with --e-star, not both".into(),
        ));
    }
    let needs = match a.law {
        LawArg::HuntCrossley if a.formula.is_some() && a.e_star.is_none() => Some("--e-star"),
        LawArg::HuntCrossley if a.e_star.is_some() && a.formula.is_none() => Some("--formula"),
        LawArg::HuntCrossley if a.sigma.is_none() && a.formula.is_none() => {
            Some("--sigma (or --formula with --e-star)")
        }
        LawArg::KelvinVoigt if a.zeta.is_none() => Some("--zeta"),
        LawArg::LinearMaxwell if a.c.is_none() => Some("--c"),
        _ => None,
    };
    match needs {
        Some(opt) => Err(CliError::Input(format!(
            "the law {} needs {opt}",
            name(a.law)
        ))),
        None => Ok(()),
    }
}

/// One case's result.
enum Outcome {
    /// (T_s, e) as intervals (points for the f64 engine).
    Separated(Interval, Interval),
    /// No separation before the horizon H (proved on the rigorous engine: T_s > H; e = 0 by
    /// the paper's convention if it never separates), and the closed form's argument when the
    /// law never separates at all.
    NoSeparation(f64, Option<String>),
}

type Result2 = Result<Outcome, String>;

fn run_rigorous<M: CollisionModel<Interval, N>, const N: usize>(m: &M) -> Result2 {
    let opts = TaylorOptions::default();
    match rigorous_impact(m, &opts) {
        Ok(r) => Ok(Outcome::Separated(r.ts, r.e)),
        Err(e) if e.no_separation() => Ok(Outcome::NoSeparation(
            opts.horizon,
            e.never_separates().map(String::from),
        )),
        Err(e) => Err(e.reason),
    }
}

/// `never`: the closed form's argument for the law as written ([`CollisionModel::never_separates`]
/// of its enclosure).
fn run_float<M: CollisionModel<f64, N>, const N: usize>(
    m: &M,
    never: Option<&'static str>,
) -> Result2 {
    let r = impact(m, &FloatOptions::default()).map_err(|e| e.to_string())?;
    let p = |x: f64| Interval::try_from((x, x)).unwrap();
    Ok(match r.ts {
        Some(ts) => Outcome::Separated(p(ts), p(r.e)),
        None => Outcome::NoSeparation(r.horizon, never.map(String::from)),
    })
}

/// σ of `--formula` at `--e-star` (0 < e* < 1, enclosed as written): an enclosure for the
/// rigorous engine and a double for the float one (the exact damping through its proved
/// bracket).
fn formula_sigma(a: &ClassicalArgs) -> Result<(Interval, f64), CliError> {
    let key = a.formula.as_deref().unwrap_or_default();
    let f = DampingFormula::from_key(key).ok_or_else(|| {
        CliError::Input(format!(
            "--formula '{}' is not a formula (one of {})",
            echo(key),
            DampingFormula::ALL.map(|f| f.key()).join(", ")
        ))
    })?;
    let text = a.e_star.as_deref().unwrap_or_default();
    let bad = || {
        CliError::Input(format!(
            "--e-star '{}' must be a target CoR in (0, 1)",
            echo(text)
        ))
    };
    let e = Big::parse_decimal(text).map_err(|_| bad())?;
    if e.lo() <= 0.0 || e.hi() >= 1.0 {
        return Err(bad());
    }
    let s = formula_sigma_of(f, &e).map_err(|m| CliError::Failed(format!("σ of {key}: {m}")))?;
    let si = s.to_interval();
    Ok((si, si.mid()))
}

/// Builds the law in both arithmetics and runs the chosen engine.
fn compute(a: &ClassicalArgs) -> Result<Result2, CliError> {
    let n = a.n.as_deref().unwrap_or("1.5");
    let given: Vec<String> = params(a)
        .iter()
        .map(|(k, v)| format!("--{k} '{}'", echo(v)))
        .collect();
    let bad = |m: String| CliError::Input(format!("{} {}: {m}", name(a.law), given.join(" ")));
    // the law on intervals is built for the float run too: its values are checked as written
    // (n = 0.99999999999999999999 is below 1 though its double is 1), and a closed form's
    // claim is made for the value as written (c = 0.50000000000000000001 may separate)
    macro_rules! go {
        ($iv:expr, $fl:expr) => {{
            // the float law first: its reading of a value names the double it becomes
            // ("below the smallest positive double")
            let fl = if a.rigorous {
                None
            } else {
                Some($fl.map_err(bad)?)
            };
            let iv = $iv.map_err(bad)?;
            match fl {
                None => Ok(run_rigorous(&iv)),
                Some(fl) => Ok(run_float(&fl, iv.never_separates())),
            }
        }};
    }
    match a.law {
        LawArg::Hooke => go!(
            Ok::<_, String>(HuntCrossley::<Interval>::hooke()),
            Ok::<_, String>(HuntCrossley::<f64>::hooke())
        ),
        LawArg::Hertz => go!(
            HuntCrossley::hertz(value::<Interval>("n", n)?),
            HuntCrossley::hertz(value::<f64>("n", n)?)
        ),
        LawArg::HuntCrossley if a.formula.is_some() => {
            let (si, sf) = formula_sigma(a)?;
            go!(
                HuntCrossley::new(si, value::<Interval>("n", n)?),
                HuntCrossley::new(sf, value::<f64>("n", n)?)
            )
        }
        LawArg::HuntCrossley => {
            let s = a.sigma.as_deref().unwrap_or_default();
            go!(
                HuntCrossley::new(value::<Interval>("sigma", s)?, value::<Interval>("n", n)?),
                HuntCrossley::new(value::<f64>("sigma", s)?, value::<f64>("n", n)?)
            )
        }
        LawArg::KelvinVoigt => {
            let z = a.zeta.as_deref().unwrap_or_default();
            go!(
                KelvinVoigt::new(value::<Interval>("zeta", z)?),
                KelvinVoigt::new(value::<f64>("zeta", z)?)
            )
        }
        LawArg::LinearMaxwell => {
            let c = a.c.as_deref().unwrap_or_default();
            go!(
                LinearMaxwell::new(value::<Interval>("c", c)?),
                LinearMaxwell::new(value::<f64>("c", c)?)
            )
        }
    }
}

/// The parameters as given, for the output.
fn params(a: &ClassicalArgs) -> Vec<(&'static str, String)> {
    let mut p = Vec::new();
    if matches!(a.law, LawArg::Hertz | LawArg::HuntCrossley) {
        p.push(("n", a.n.clone().unwrap_or_else(|| "1.5".into())));
    }
    if let Some(s) = &a.sigma {
        p.push(("sigma", s.clone()));
    }
    if let Some(z) = &a.zeta {
        p.push(("zeta", z.clone()));
    }
    if let Some(c) = &a.c {
        p.push(("c", c.clone()));
    }
    if let Some(f) = &a.formula {
        p.push(("formula", f.clone()));
    }
    if let Some(e) = &a.e_star {
        p.push(("e_star", e.clone()));
    }
    p
}

/// The parameters as `key=value` words.
fn pars_text(pars: &[(&'static str, String)]) -> String {
    let p: Vec<String> = pars.iter().map(|(k, v)| format!("{k}={v}")).collect();
    p.join(" ")
}

/// The CSV columns: the values, then whether the case separated and, when not, why.
fn csv_head(rigorous: bool) -> Vec<&'static str> {
    let mut h = if rigorous {
        vec![
            "law", "params", "ts_lo", "ts_hi", "width_ts", "e_lo", "e_hi", "width_e",
        ]
    } else {
        vec!["law", "params", "ts", "e"]
    };
    h.extend(["separated", "reason"]);
    h
}

pub fn classical(a: &ClassicalArgs) -> Result<i32, CliError> {
    super::input::out_path(a.out.as_deref())?;
    let (bytes, code, note) = report_and_note(a)?;
    if code == super::EXIT_OK {
        output::emit(a.out.as_deref(), &bytes)?;
        if let Some(n) = note {
            super::note(&n);
        }
        return Ok(code);
    }
    // as `bwcl cor`: --out is replaced only when the command succeeded; the reason goes to
    // stdout, and one line on stderr says so
    output::emit(None, &bytes)?;
    let kept = output::out_kept(a.out.as_deref());
    super::note(&format!(
        "bwcl: the case was not {} (the reason is in the output){kept}",
        if a.rigorous { "proved" } else { "integrated" }
    ));
    Ok(code)
}

/// The output of `bwcl classical` and its exit code (1 when the case was not proved or not
/// integrated).
pub fn report(a: &ClassicalArgs) -> Result<(Vec<u8>, i32), CliError> {
    report_and_note(a).map(|(bytes, code, _)| (bytes, code))
}

/// [`report`], and as `bwcl cor` a note for stderr where the float run's separation has e below
/// its absolute tolerance ([`super::commands::resolution_note`]).
fn report_and_note(a: &ClassicalArgs) -> Result<(Vec<u8>, i32, Option<String>), CliError> {
    check_options(a)?;
    let result = compute(a)?;
    let atol = FloatOptions::default().ode.atol;
    let note = match &result {
        Ok(Outcome::Separated(ts, e)) if !a.rigorous && e.inf().abs() < atol => Some(
            super::commands::resolution_note(None, e.inf(), Some(ts.inf()), atol),
        ),
        _ => None,
    };
    let law = name(a.law);
    let pars = params(a);
    let named: std::collections::BTreeMap<_, _> = pars.iter().cloned().collect();
    let bytes = match (&result, a.format) {
        (Err(why), Format::Json) => {
            output::json(&json!({"law": law, "params": named, "error": why}))?
        }
        (Err(why), f) => {
            let text = format!(
                "not {}: {why}",
                if a.rigorous { "proved" } else { "integrated" }
            );
            if f == Format::Csv {
                // the same columns as a result, the reason in the last
                let head = csv_head(a.rigorous);
                let mut row = vec![law.to_string(), pars_text(&pars)];
                row.resize(head.len() - 1, String::new());
                row.push(text);
                output::csv(&head, [row])?
            } else {
                format!("{law}: {text}\n").into_bytes()
            }
        }
        (Ok(Outcome::NoSeparation(h, never)), f) => {
            // as `bwcl cor`: the horizon rounded down where the run proved T_s > H
            let text = if a.rigorous {
                super::commands::no_separation_text(*h, never.as_deref())
            } else if let Some(why) = never {
                format!("the law never separates ({why}; closed form): e = 0")
            } else {
                format!(
                    "no separation before the horizon T = {} (e = 0)",
                    output::num(*h)
                )
            };
            match f {
                Format::Json => output::json(&json!({
                    "law": law,
                    "params": named,
                    "rigorous": a.rigorous,
                    "separated": false,
                    "ts": null,
                    // e = 0 by the paper's convention where T_s = +∞ (the float run, or a
                    // closed form); after a proved T_s > H alone e is not known
                    "e": match (a.rigorous, never) {
                        (false, _) => json!(0.0),
                        (true, Some(_)) => json!(["0", "0"]),
                        (true, None) => json!(null),
                    },
                    "never_separates": never.is_some(),
                    "horizon": h,
                    "reason": text,
                }))?,
                Format::Csv => {
                    // the value columns empty, but the float run's e = 0
                    let head = csv_head(a.rigorous);
                    let mut row: Vec<String> = head
                        .iter()
                        .map(|&h| match h {
                            "e" => "0".into(),
                            "separated" => "false".into(),
                            _ => String::new(),
                        })
                        .collect();
                    row[0] = law.to_string();
                    row[1] = pars_text(&pars);
                    *row.last_mut().expect("a reason column") = text;
                    output::csv(&head, [row])?
                }
                _ => format!("{law} {}: {text}\n", pars_text(&pars)).into_bytes(),
            }
        }
        (Ok(Outcome::Separated(ts, e)), Format::Json) => {
            let cell = |x: &Interval| -> serde_json::Value {
                if a.rigorous {
                    json!(outward_pair(*x))
                } else {
                    json!(x.inf())
                }
            };
            output::json(&json!({
                "law": law,
                "params": named,
                "rigorous": a.rigorous,
                "separated": true,
                "ts": cell(ts),
                "e": cell(e),
            }))?
        }
        (Ok(Outcome::Separated(ts, e)), f) => {
            let mut row: Vec<String> = if a.rigorous {
                let [tl, th] = outward_pair(*ts);
                let [el, eh] = outward_pair(*e);
                vec![
                    law.into(),
                    pars_text(&pars),
                    tl,
                    th,
                    sci_up(width_up(ts.inf(), ts.sup()), 3),
                    el,
                    eh,
                    sci_up(width_up(e.inf(), e.sup()), 3),
                ]
            } else {
                vec![
                    law.into(),
                    pars_text(&pars),
                    output::num(ts.inf()),
                    output::num(e.inf()),
                ]
            };
            let mut head = csv_head(a.rigorous);
            match f {
                Format::Csv => {
                    row.extend(["true".to_string(), String::new()]);
                    output::csv(&head, [row])?
                }
                _ => {
                    head.truncate(row.len());
                    output::table(&head, &[row]).into_bytes()
                }
            }
        }
    };
    let code = match result {
        Ok(_) => super::EXIT_OK,
        Err(_) => super::EXIT_FAILED,
    };
    Ok((bytes, code, note))
}
