//! `bwcl cor --rigorous --digits D`: the rigorous engine at a chosen precision
//! ([`bwcl::observables::precision`]), its bounds printed with every digit their width allows,
//! lo rounded down and hi up, in the table, CSV and JSON (numbers as exact decimal text).

use super::args::{CorArgs, EngineArgs, Format};
use super::input;
use super::output::{csv, table};
use super::{CliError, EXIT_FAILED, EXIT_OK, note};
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::ModelKind;
use bwcl::observables::precision::{
    ParamText, PreciseEnclosure, bits_for_digits, outward_text, rigorous_impact_digits_or_f64,
    width_text,
};
use bwcl::observables::sets;
use inari::Interval;
use rayon::prelude::*;

/// One case: its v0 as written (or "-") and the proved enclosure or why not; a note when the
/// digits asked for were not reached and the enclosure is the f64-interval engine's.
struct Row {
    v0: String,
    out: Outcome,
}

/// What one case of `--digits` proved (the CLI's rows and the Python bindings' dict alike).
pub struct Outcome {
    /// The enclosure, or the reason as text: why it was not proved, or (with `no_separation`)
    /// what was proved instead.
    pub res: Result<PreciseEnclosure, String>,
    /// The condition was proved to fail up to the horizon (T_s > T, a result).
    pub no_separation: bool,
    /// Why the enclosure has fewer digits than asked for, where it has.
    pub note: Option<String>,
}

/// One case at `digits` digits ([`rigorous_impact_digits_or_f64`]): the enclosure with a note
/// where the digits were not reached (the f64-interval engine's in place of the precise one, or
/// a precise one that determines fewer digits), no separation before the horizon as proved, or
/// the reason nothing was.
pub fn outcome(
    kind: ModelKind,
    p: &ParamText,
    digits: usize,
    opts: &TaylorOptions,
    engine: &EngineArgs,
) -> Outcome {
    let bits = bits_for_digits(digits as u32).unwrap_or(0);
    match rigorous_impact_digits_or_f64(kind, p, digits as u32, opts) {
        Ok((enc, why)) => Outcome {
            note: why
                .map(|e| {
                    format!(
                        "{digits} digits not reached at {bits} bits ({}): the f64-interval engine's enclosure",
                        e.reason
                    )
                })
                .or_else(|| short_of(&enc, digits)),
            res: Ok(enc),
            no_separation: false,
        },
        // the condition proved to fail on [0, horizon]: T_s > horizon, a result
        Err(e) if e.no_separation() => Outcome {
            res: Err(super::commands::no_separation_text(
                opts.horizon,
                e.never_separates(),
            )),
            no_separation: true,
            note: None,
        },
        Err(e) => Outcome {
            res: Err(input::reason_text(&e, engine)),
            no_separation: false,
            note: None,
        },
    }
}

/// The significant digits an enclosure [lo, hi] determines, ⌊log₁₀(|mid|/(hi − lo))⌋ (∞ when
/// thin or exact).
fn digits_of(x: &[rug::Rational; 2]) -> f64 {
    let w = rug::Rational::from(&x[1] - &x[0]).to_f64();
    let m = (rug::Rational::from(&x[0] + &x[1]) / 2u32).to_f64().abs();
    if w > 0.0 {
        (m / w).log10().floor()
    } else {
        f64::INFINITY
    }
}

/// A note where the enclosure determines fewer than the `digits` asked for (it is proved, only
/// less precise: e.g. T_s where F has a near-double root at separation, B → 0).
fn short_of(p: &PreciseEnclosure, digits: usize) -> Option<String> {
    let short: Vec<String> = [("T_s", &p.ts), ("e", &p.e)]
        .into_iter()
        .filter_map(|(name, x)| {
            let d = digits_of(x);
            (d < digits as f64).then(|| format!("{name} to {} significant digits", d.max(0.0)))
        })
        .collect();
    (!short.is_empty()).then(|| {
        format!(
            "{} only, not {digits}: the width reached at {} bits",
            short.join(" and "),
            p.bits
        )
    })
}

/// The cases of --nd or --base/--v0 as texts (validated by the usual parser first, so bad input
/// gets its usual message; the texts are the cases' own, [`input::Case::text`]); ranges and
/// --physical are refused.
fn cases(a: &CorArgs) -> Result<Vec<(String, ParamText)>, CliError> {
    texts(input::cases::<Interval>(&a.params)?)
}

/// `cases` of cases already parsed (the Python bindings parse their speeds in batches): (v0
/// as written, or "-" for --nd; the parameters as written).
pub fn texts(checked: Vec<input::Case<Interval>>) -> Result<Vec<(String, ParamText)>, CliError> {
    // a range as written (a..b), not a value whose enclosure is wide because it lies below the
    // doubles' normal range (B = 1e-320: MPFR holds it)
    let written_range = |c: &input::Case<Interval>| match &c.text {
        Some(ParamText::Nd(t)) => t.contains(".."),
        Some(ParamText::Base { base, v0 }) => base.contains("..") || v0.contains(".."),
        None => c.inputs.values().iter().any(sets::is_range),
    };
    if checked.iter().any(written_range) {
        return Err(CliError::Input(
            "--digits proves single values: inputs given as ranges (a..b) are not supported with it".into(),
        ));
    }
    checked
        .into_iter()
        .map(|c| {
            let t = c.text.ok_or_else(|| {
                CliError::Input(
                    "--digits supports --nd and --base with --v0 (not --physical)".into(),
                )
            })?;
            let v0 = match &t {
                ParamText::Base { v0, .. } => v0.clone(),
                ParamText::Nd(_) => "-".into(),
            };
            Ok((v0, t))
        })
        .collect()
}

/// Runs `cor --rigorous --digits D`; `Ok` carries the exit code.
pub fn cor(a: &CorArgs, digits: usize) -> Result<i32, CliError> {
    if a.sensitivities {
        return Err(CliError::Input(
            "--sensitivities is not supported with --digits".into(),
        ));
    }
    let d = digits as u32;
    let bits = bits_for_digits(d)
        .ok_or_else(|| CliError::Input(format!("--digits {digits}: must be in 1..=100")))?;
    input::out_path(a.out.as_deref())?;
    let opts = input::taylor_options(&a.engine)?;
    let kind = input::bouc_wen_only(a.params.model, "--digits")?;
    let cases = cases(a)?;
    let start = std::time::Instant::now();
    let bar = super::progress::Progress::cases(
        &format!("cor --digits {digits}"),
        cases.len(),
        input::time_limit(a.engine.time_limit),
    );
    let rows: Vec<Row> = cases
        .par_iter()
        .map(|(v0, p)| Row {
            v0: v0.clone(),
            out: outcome(kind, p, digits, &opts, &a.engine),
        })
        .inspect(|_| bar.inc())
        .collect();
    bar.finish();
    let elapsed = start.elapsed();
    let failed = rows
        .iter()
        .filter(|r| r.out.res.is_err() && !r.out.no_separation)
        .count();
    let bytes = render(kind, &rows, bits, a.format)?;
    let timing = || {
        if a.timing {
            let s = elapsed.as_secs_f64();
            note(&format!(
                "bwcl: timing: {} case(s) in {s:.6} s, {:.3} µs per case ({} thread(s)), {bits} bits",
                rows.len(),
                s / rows.len().max(1) as f64 * 1e6,
                rayon::current_num_threads()
            ));
        }
    };
    if failed == 0 {
        super::output::emit(a.out.as_deref(), &bytes)?;
        timing();
        return Ok(EXIT_OK);
    }
    super::output::emit(None, &bytes)?;
    timing();
    note(&format!(
        "bwcl: {failed} of {} case(s) not proved (the reason is in the output)",
        rows.len()
    ));
    Ok(EXIT_FAILED)
}

/// The cells of a proved row: ts lo, hi, width, e lo, hi, width.
fn cells(p: &PreciseEnclosure) -> [String; 6] {
    let (tl, th) = outward_text(&p.ts, p.bits);
    let (el, eh) = outward_text(&p.e, p.bits);
    [
        tl,
        th,
        width_text(&p.width_ts()),
        el,
        eh,
        width_text(&p.width_e()),
    ]
}

fn json_str(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".into())
}

fn render(kind: ModelKind, rows: &[Row], bits: u32, format: Format) -> Result<Vec<u8>, CliError> {
    match format {
        Format::Table => {
            let noted = rows.iter().any(|r| r.out.note.is_some());
            let mut head = vec![
                "model", "v0", "ts", "width_ts", "e", "width_e", "bits", "pieces",
            ];
            if noted {
                head.push("note");
            }
            let body: Vec<Vec<String>> = rows
                .iter()
                .map(|r| {
                    let mut c = vec![kind.name().to_string(), r.v0.clone()];
                    match &r.out.res {
                        Ok(p) => {
                            let [tl, th, tw, el, eh, ew] = cells(p);
                            c.extend([
                                format!("[{tl}, {th}]"),
                                tw,
                                format!("[{el}, {eh}]"),
                                ew,
                                p.bits.to_string(),
                                p.pieces.to_string(),
                            ]);
                            if noted {
                                c.push(r.out.note.clone().unwrap_or_default());
                            }
                        }
                        Err(e) => c.push(e.clone()),
                    }
                    c
                })
                .collect();
            Ok(table(&head, &body).into_bytes())
        }
        Format::Csv => {
            let head = [
                "model", "v0", "proved", "ts_lo", "ts_hi", "width_ts", "e_lo", "e_hi", "width_e",
                "bits", "pieces", "reason",
            ];
            let body = rows.iter().map(|r| {
                let mut c = vec![kind.name().to_string(), r.v0.clone()];
                match &r.out.res {
                    Ok(p) => {
                        c.push("true".into());
                        c.extend(cells(p));
                        c.extend([
                            p.bits.to_string(),
                            p.pieces.to_string(),
                            r.out.note.clone().unwrap_or_default(),
                        ]);
                    }
                    Err(e) => {
                        c.push(r.out.no_separation.to_string());
                        c.extend(std::iter::repeat_n(String::new(), 6));
                        c.extend([bits.to_string(), String::new(), e.clone()]);
                    }
                }
                c
            });
            csv(&head, body)
        }
        Format::Json => {
            let objs: Vec<String> = rows
                .iter()
                .map(|r| {
                    let v0 = if r.v0 == "-" {
                        "null".to_string()
                    } else {
                        json_str(&r.v0)
                    };
                    // the precision that proved the case (53: the f64-interval engine's proof)
                    let b = r.out.res.as_ref().map_or(bits, |p| p.bits);
                    let common = format!(
                        "\"model\": {}, \"v0\": {v0}, \"bits\": {b}",
                        json_str(kind.name())
                    );
                    match &r.out.res {
                        Ok(p) => {
                            let [tl, th, tw, el, eh, ew] = cells(p);
                            let note = r
                                .out
                                .note
                                .as_ref()
                                .map(|n| format!(", \"note\": {}", json_str(n)))
                                .unwrap_or_default();
                            format!(
                                "  {{{common}, \"proved\": true, \"separated\": true, \"ts\": [{tl}, {th}], \"width_ts\": {tw}, \"e\": [{el}, {eh}], \"width_e\": {ew}, \"pieces\": {}{note}}}",
                                p.pieces
                            )
                        }
                        Err(e) if r.out.no_separation => format!(
                            "  {{{common}, \"proved\": true, \"separated\": false, \"reason\": {}}}",
                            json_str(e)
                        ),
                        Err(e) => format!(
                            "  {{{common}, \"proved\": false, \"reason\": {}}}",
                            json_str(e)
                        ),
                    }
                })
                .collect();
            Ok(format!("[\n{}\n]\n", objs.join(",\n")).into_bytes())
        }
    }
}
