//! Turning --base / --nd / --physical (+ --v0) and the engine options into validated cases.
//!
//! Everything is generic over the arithmetic: `f64` for the float engine, `Interval` for the
//! rigorous one (decimals enclosed as written, ranges a..b allowed).

use super::CliError;
use super::args::{EngineArgs, FamilyArg, ParamArgs, TIME_LIMIT};
use bwcl::arith::Real;
use bwcl::engines::dop853::Options;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::engines::taylor::{DEADLINE, RigorError};
use bwcl::fit::data::echo;
use bwcl::models::classical::{Law, LawParams, LawSource};
use bwcl::models::params::show;
use bwcl::models::scaling::{PhysicalParams, Scales, nd_from_base, parse_speeds};
use bwcl::models::{ModelKind, NdParams, ParamError};
use bwcl::observables::FloatOptions;
use bwcl::observables::precision::{FallbackBudget, ParamText};
use bwcl::observables::sets::Inputs;
use std::path::{Path, PathBuf};

/// Most impact speeds in one --v0 list.
pub const MAX_SPEEDS: usize = 10_000;
/// Default --pieces.
const PIECES: usize = 256;

/// The names of the six values of --nd, --base and --init, as parameter errors name them.
const ND_NAMES: [&str; 6] = ["B", "Γ", "κ", "σ", "n", "p"];

/// One collision to compute: its impact speed (none for --nd), its nondimensional parameters,
/// and for --physical the scales at that speed.
#[derive(Clone, Debug)]
pub struct Case<R> {
    pub v0: Option<R>,
    pub params: NdParams<R>,
    pub scales: Option<Scales<R>>,
    /// The base set P* (with --base, or of the --physical set).
    pub base: Option<NdParams<R>>,
    /// The inputs as given (any of them may be a range with --rigorous): what
    /// [`bwcl::observables::sets`] proves over.
    pub inputs: Inputs<R>,
    /// The parameters as written (--nd, or --base with this case's --v0 token), enclosed anew
    /// at each precision by the precision fallback; `None` for --physical.
    pub text: Option<ParamText>,
}

/// The Bouc–Wen model of --model, or the refusal of a classical law for `what` (an option or
/// a command that only the Bouc–Wen models have).
pub fn bouc_wen_only(model: FamilyArg, what: &str) -> Result<ModelKind, CliError> {
    model.kind().ok_or_else(|| {
        CliError::Input(format!(
            "--model {}: {what} is for the Bouc–Wen models (shc, maxwell), not the classical laws",
            model.key()
        ))
    })
}

/// One collision of a classical law: its impact speed (none for --nd), its nondimensional
/// parameters there, and for --physical the scales at that speed.
#[derive(Clone, Debug)]
pub struct LawCase<R> {
    pub v0: Option<R>,
    pub nd: LawParams<R>,
    pub scales: Option<Scales<R>>,
}

/// The validated cases of a classical law (`--model <law>`), in the order of --v0.
pub fn law_cases<R: Real>(p: &ParamArgs, law: Law) -> Result<Vec<LawCase<R>>, CliError> {
    let (opt, text, source) = match (&p.nd, &p.base, &p.physical) {
        (Some(t), _, _) => ("--nd", t, LawSource::Nd),
        (_, Some(t), _) => ("--base", t, LawSource::Base),
        (_, _, Some(t)) => ("--physical", t, LawSource::Physical),
        _ => {
            return Err(CliError::Input(
                "give exactly one of --base, --nd, --physical".into(),
            ));
        }
    };
    let given =
        LawParams::<R>::parse(law, source, text).map_err(|e| keyed_error::<R>(opt, text, e))?;
    if source == LawSource::Nd {
        return Ok(vec![LawCase {
            v0: None,
            nd: given,
            scales: None,
        }]);
    }
    let Some(v0_text) = &p.v0 else {
        return Err(CliError::Input(
            "--v0 is required with --base and --physical".into(),
        ));
    };
    speeds::<R>(v0_text)?
        .into_iter()
        .zip(v0_text.split(','))
        .map(|(v0, token)| {
            let at = |e: ParamError| {
                CliError::Input(format!(
                    "{opt} at v0 = {}: {}",
                    echo(token.trim()),
                    compact(&e.0)
                ))
            };
            Ok(LawCase {
                nd: given.at(&v0).map_err(at)?,
                scales: given.scales(&v0).map_err(at)?,
                v0: Some(v0),
            })
        })
        .collect()
}

/// The single case of a classical law's trajectory/loop: exactly one impact speed.
pub fn single_law_case<R: Real>(p: &ParamArgs, law: Law) -> Result<LawCase<R>, CliError> {
    only_one(p, law_cases::<R>(p, law)?)
}

/// The one case of `all`, or the refusal of a --v0 list of several speeds.
fn only_one<C>(p: &ParamArgs, mut all: Vec<C>) -> Result<C, CliError> {
    if all.len() != 1 {
        return Err(CliError::Input(format!(
            "--v0 '{}': this command takes exactly one impact speed, got {}",
            echo(p.v0.as_deref().unwrap_or("")),
            all.len()
        )));
    }
    Ok(all.remove(0))
}

/// The validated cases of the parameter options, in the order of --v0 (a Bouc–Wen model).
pub fn cases<R: Real>(p: &ParamArgs) -> Result<Vec<Case<R>>, CliError> {
    let kind = bouc_wen_only(p.model, "this command")?;
    if let Some(text) = &p.nd {
        let params =
            NdParams::<R>::parse(kind, text).map_err(|e| nd_error::<R>("--nd", text, e))?;
        return Ok(vec![Case {
            v0: None,
            inputs: Inputs::Nd(params.clone()),
            params,
            scales: None,
            base: None,
            text: Some(ParamText::Nd(text.clone())),
        }]);
    }
    // clap guarantees one of --base / --physical, and --v0 with them.
    let Some(v0_text) = &p.v0 else {
        return Err(CliError::Input(
            "--v0 is required with --base and --physical".into(),
        ));
    };
    if let Some(text) = &p.base {
        let base =
            NdParams::<R>::parse(kind, text).map_err(|e| nd_error::<R>("--base", text, e))?;
        let speeds = speeds::<R>(v0_text)?;
        speeds
            .into_iter()
            .zip(v0_text.split(','))
            .map(|(v0, token)| {
                let params = nd_from_base(kind, &base, &v0).map_err(|e| {
                    CliError::Input(format!(
                        "--base mapped to v0 = {}: {}",
                        echo(token.trim()),
                        compact(&e.0)
                    ))
                })?;
                Ok(Case {
                    inputs: Inputs::Base {
                        base: base.clone(),
                        v0: v0.clone(),
                    },
                    v0: Some(v0),
                    params,
                    scales: None,
                    base: Some(base.clone()),
                    text: Some(ParamText::Base {
                        base: text.clone(),
                        v0: token.trim().to_string(),
                    }),
                })
            })
            .collect()
    } else if let Some(text) = &p.physical {
        let phys = PhysicalParams::<R>::parse(kind, text)
            .map_err(|e| keyed_error::<R>("--physical", text, e))?;
        let speeds = speeds::<R>(v0_text)?;
        speeds
            .into_iter()
            .zip(v0_text.split(','))
            .map(|(v0, token)| {
                let params = nondimensionalize(kind, &phys, &v0).map_err(|e| {
                    CliError::Input(format!(
                        "--physical at v0 = {}: {}",
                        echo(token.trim()),
                        compact(&e.0)
                    ))
                })?;
                let scales = phys.scales(&v0);
                Ok(Case {
                    inputs: Inputs::Physical {
                        phys: phys.clone(),
                        v0: v0.clone(),
                    },
                    v0: Some(v0),
                    params,
                    scales: Some(scales),
                    base: phys.base(kind).ok(),
                    text: None,
                })
            })
            .collect()
    } else {
        Err(CliError::Input(
            "give exactly one of --base, --nd, --physical".into(),
        ))
    }
}

/// The nondimensional set of physical parameters at v0; for a range of speeds through the
/// base set: P = 𝓟(P*, v0) holds for every v0, and the map keeps 𝓟 (the direct formulas would
/// compare the enclosures of Γ and B as if independent).
fn nondimensionalize<R: Real>(
    kind: ModelKind,
    phys: &PhysicalParams<R>,
    v0: &R,
) -> Result<NdParams<R>, ParamError> {
    if v0.lo() < v0.hi() {
        nd_from_base(kind, &phys.base(kind)?, v0)
    } else {
        phys.nondimensionalize(kind, v0)
    }
}

/// The impact speeds of --v0 (at most [`MAX_SPEEDS`]).
fn speeds<R: Real>(text: &str) -> Result<Vec<R>, CliError> {
    let n = text.split(',').count();
    if n > MAX_SPEEDS {
        return Err(CliError::Input(format!(
            "--v0 '{}': {n} speeds, at most {MAX_SPEEDS} are taken",
            echo(text)
        )));
    }
    parse_speeds::<R>(text).map_err(|e| {
        let pairs: Vec<(&str, &str)> = text.split(',').map(|t| ("v0", t.trim())).collect();
        input_error::<R>("--v0", text, &pairs, e)
    })
}

/// A parameter error of --nd, --base or --init (the six values B,Γ,κ,σ,n,p of `text`).
pub fn nd_error<R: Real>(opt: &str, text: &str, e: ParamError) -> CliError {
    let pairs: Vec<(&str, &str)> = ND_NAMES
        .iter()
        .copied()
        .zip(text.split(',').map(str::trim))
        .collect();
    input_error::<R>(opt, text, &pairs, e)
}

/// A parameter error of an option written "key=value,…" (`text`), each value named by its key.
fn keyed_error<R: Real>(opt: &str, text: &str, e: ParamError) -> CliError {
    let pairs: Vec<(&str, &str)> = text
        .split(',')
        .filter_map(|item| item.split_once('='))
        .map(|(k, v)| (k.trim(), v.trim()))
        .collect();
    input_error::<R>(opt, text, &pairs, e)
}

/// A parameter error of option `opt` whose text was `text`, rendered with what the user wrote:
/// the value the message names ("Γ = …", from `pairs` of names and tokens) is replaced by the
/// user's token (escaped, shortened; for an interval with the enclosure it was read as), any
/// other echo of the text is escaped and shortened, long decimals are written with an exponent,
/// and a range without --rigorous gets a hint.
fn input_error<R: Real>(opt: &str, text: &str, pairs: &[(&str, &str)], e: ParamError) -> CliError {
    let mut msg = e.0;
    // an empty item ('1,2,', '0.1..') is named in the text the user wrote, not as ''
    if msg.contains("'' is not") {
        return CliError::Input(format!(
            "{opt} '{}': an item or an end of a range is empty",
            echo(text)
        ));
    }
    for (name, token) in pairs {
        let Ok(x) = R::parse_decimal(token) else {
            continue;
        };
        // (the values are checked as written, exactly: a message about a value is about the
        // token, not its enclosure)
        let prefix = format!("{name} = {}", show(&x));
        let written = format!("{name} = {token}");
        if let Some(rest) = msg
            .strip_prefix(&written)
            .or_else(|| msg.strip_prefix(&prefix))
        {
            msg = format!("{name} = {}{}", echo(token), compact(rest));
            return CliError::Input(format!("{opt}: {msg}"));
        }
    }
    let items = text.split(',').map(str::trim);
    for token in std::iter::once(text)
        .chain(items)
        .chain(pairs.iter().map(|p| p.1))
    {
        if !token.is_empty() && echo(token) != token {
            msg = msg.replace(token, &echo(token));
        }
    }
    let hint = if msg.contains("needs the rigorous engine") {
        " (add --rigorous)"
    } else {
        ""
    };
    CliError::Input(format!("{opt}: {}{hint}", compact(&msg)))
}

/// A double as a short decimal that reads back to it (with an exponent when long).
pub fn short(x: f64) -> String {
    bwcl::models::params::short_f64(if x == 0.0 { 0.0 } else { x })
}

/// `msg` with every decimal longer than 20 characters (a double printed in full, e.g. 10³⁰⁰
/// with its 301 digits) rewritten by [`short`]: the same double, read back. A value quoted as
/// the user wrote it ('…', the quote after a space, '(', '=' or at the start) is kept as
/// written: `1.00000000000000000001x` is not a number, but its digits would read back as 1.
pub fn compact(msg: &str) -> String {
    let mut out = String::new();
    let mut run = String::new();
    let flush = |run: &mut String, out: &mut String| {
        match run.parse::<f64>() {
            Ok(x) if run.len() > 20 => out.push_str(&short(x)),
            _ => out.push_str(run),
        }
        run.clear();
    };
    let mut quoted = false;
    let mut prev = ' ';
    for c in msg.chars() {
        if quoted {
            quoted = c != '\'';
            out.push(c);
        } else if c == '\'' && matches!(prev, ' ' | '(' | '=' | ':' | ',') {
            flush(&mut run, &mut out);
            quoted = true;
            out.push(c);
        } else if c.is_ascii_digit() || c == '.' || (c == '-' && run.is_empty()) {
            run.push(c);
        } else {
            flush(&mut run, &mut out);
            out.push(c);
        }
        prev = c;
    }
    flush(&mut run, &mut out);
    out
}

/// The single case of trajectory/loop: exactly one impact speed.
pub fn single_case<R: Real>(p: &ParamArgs) -> Result<Case<R>, CliError> {
    only_one(p, cases::<R>(p)?)
}

/// --order and --pieces belong to the rigorous engine (clap's `requires` does not see every
/// combination, e.g. with --rtol).
fn rigorous_only(e: &EngineArgs) -> Result<(), CliError> {
    if e.rigorous {
        return Ok(());
    }
    for (name, given) in [("--order", e.order), ("--pieces", e.pieces)] {
        if let Some(k) = given {
            return Err(CliError::Input(format!(
                "{name} {k} is an option of the rigorous engine: add --rigorous"
            )));
        }
    }
    if let Some(s) = e.time_limit {
        return Err(CliError::Input(format!(
            "--time-limit {s} is an option of the rigorous engine: add --rigorous"
        )));
    }
    Ok(())
}

/// --time-limit, or its default.
pub fn time_limit(given: Option<f64>) -> f64 {
    given.unwrap_or(TIME_LIMIT)
}

/// The instant the command's time budget ends (from now).
pub fn deadline(given: Option<f64>) -> std::time::Instant {
    std::time::Instant::now() + std::time::Duration::from_secs_f64(time_limit(given))
}

/// A not-proved case's reason as printed: a run stopped by the command's budget names it.
pub fn reason_text(e: &RigorError, engine: &EngineArgs) -> String {
    limit_text(e, engine.time_limit)
}

/// [`reason_text`] with the --time-limit given (or not).
pub fn limit_text(e: &RigorError, given: Option<f64>) -> String {
    if e.out_of_time() {
        let s = time_limit(given);
        let rest = e.reason.strip_prefix(DEADLINE).unwrap_or("");
        let at = if e.t > 0.0 || e.width > 0.0 {
            format!(" (at T = {}, enclosure width {:e})", e.t, e.width)
        } else {
            String::new()
        };
        format!("not proved: the time budget of {s} s ran out (--time-limit){rest}{at}")
    } else {
        e.to_string()
    }
}

/// DOP853 settings: the paper's, with the given overrides (their ranges checked by clap).
pub fn float_options(e: &EngineArgs) -> Result<FloatOptions, CliError> {
    rigorous_only(e)?;
    let mut ode = Options::paper();
    if let Some(r) = e.rtol {
        ode.rtol = r;
    }
    if let Some(a) = e.atol {
        ode.atol = a;
    }
    if let Some(h) = e.max_step {
        ode.max_step = h;
    }
    Ok(FloatOptions {
        ode,
        horizon: e.horizon,
    })
}

/// Rigorous-engine settings: the engine's defaults with --order and --horizon.
pub fn taylor_options(e: &EngineArgs) -> Result<TaylorOptions, CliError> {
    rigorous_only(e)?;
    let default = TaylorOptions::default();
    Ok(TaylorOptions {
        horizon: e.horizon,
        order: e.order.unwrap_or(default.order),
        deadline: Some(deadline(e.time_limit)),
        ..default
    })
}

/// --pieces, or its default.
pub fn pieces(e: &EngineArgs) -> usize {
    e.pieces.unwrap_or(PIECES)
}

/// The budget of the precision fallback of `cor --rigorous`: --fallback-bits (0: off) and
/// --fallback-seconds, else the library's defaults.
pub fn fallback(bits: Option<u32>, seconds: Option<f64>) -> FallbackBudget {
    let d = FallbackBudget::default();
    FallbackBudget {
        max_bits: bits.unwrap_or(d.max_bits),
        seconds: seconds.unwrap_or(d.seconds),
    }
}

/// Where `path` leads: the file at the end of its chain of symbolic links (the link itself is
/// kept and its target replaced), the chain capped at 40 links; `option` names the path in a
/// message (`--out`, `--plot`, `--band`).
pub fn resolve_links(option: &str, path: &Path) -> Result<PathBuf, CliError> {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let link = std::fs::read_link(&p).map_err(|e| out_error(option, path, e))?;
                p = match p.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(CliError::Input(format!(
        "{option} '{}': too many levels of symbolic links",
        echo(&path.to_string_lossy())
    )))
}

fn out_error(option: &str, path: &Path, e: std::io::Error) -> CliError {
    CliError::Input(format!("{option} '{}': {e}", echo(&path.to_string_lossy())))
}

/// --out: see [`out_path_as`].
pub fn out_path(out: Option<&Path>) -> Result<(), CliError> {
    out_path_as("--out", out)
}

/// An output file given by `option` (--out, --plot, --band): a regular file or a new name, in
/// a directory that exists and takes a new file (checked before any computation; through
/// symbolic links), so that a run never computes for minutes and then fails to write.
pub fn out_path_as(option: &str, out: Option<&Path>) -> Result<(), CliError> {
    let Some(path) = out else { return Ok(()) };
    let shown = echo(&path.to_string_lossy());
    // `new/` names a directory even where none exists (its parent would be taken for it)
    let text = path.as_os_str().as_encoded_bytes();
    if text.is_empty() || path.is_dir() || text.ends_with(b"/") {
        return Err(CliError::Input(format!(
            "{option} '{shown}' is not a file name"
        )));
    }
    let target = resolve_links(option, path)?;
    // NAME_MAX of Linux and most file systems: found now, not after the computation
    if target.file_name().is_some_and(|n| n.len() > 255) {
        return Err(CliError::Input(format!(
            "{option} '{shown}': the file name is longer than 255 bytes"
        )));
    }
    if target.exists() && !target.is_file() {
        return Err(CliError::Input(format!(
            "{option} '{shown}' is not a regular file (it would not be replaced)"
        )));
    }
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        let what = if dir.exists() {
            "is not a directory"
        } else {
            "does not exist"
        };
        return Err(CliError::Input(format!(
            "{option} '{shown}': the directory '{}' {what}",
            echo(&dir.to_string_lossy())
        )));
    }
    // the file is written as a new file in that directory and renamed into place
    // (`output::emit`): try that now, with the same temporary name
    let probe = super::output::temporary(&target);
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
    {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
        Err(e) => Err(CliError::Input(format!(
            "{option} '{shown}': cannot write in the directory '{}': {e}",
            echo(&dir.to_string_lossy())
        ))),
    }
}
