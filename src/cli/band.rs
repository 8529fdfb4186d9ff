//! `cor --band` (a proved CoR curve over a range of v0) and `prove monotone`.

use super::CliError;
use super::args::{CorArgs, MonotoneArgs, ReportFormat};
use super::input::{self, Case};
use super::output::{self, outward};
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::band::{BandOptions, BandPiece, prove_band, prove_decreasing};
use bwcl::observables::decimal::Rounding;
use inari::Interval;
use rug::ops::Pow;
use rug::{Integer, Rational};
use std::path::Path;

/// The exact decimal of a double (every double is a finite decimal).
pub fn exact_decimal(x: f64) -> String {
    let r = Rational::from_f64(x).expect("finite");
    let (num, den) = r.into_numer_denom();
    // den = 2^m: x = num·5^m / 10^m
    let m = den.significant_bits() - 1;
    let digits = (num.clone().abs() * Integer::from(5).pow(m)).to_string();
    let m = m as usize;
    let (int, frac) = if digits.len() > m {
        digits.split_at(digits.len() - m)
    } else {
        ("", digits.as_str())
    };
    let frac = format!("{:0>m$}", frac);
    let frac = frac.trim_end_matches('0');
    let int = if int.is_empty() { "0" } else { int };
    let sign = if num < 0 { "-" } else { "" };
    if frac.is_empty() {
        format!("{sign}{int}")
    } else {
        format!("{sign}{int}.{frac}")
    }
}

const HEAD: [&str; 16] = [
    "v0_lo",
    "v0_hi",
    "v0_c",
    "e_c_lo",
    "e_c_hi",
    "de_lo",
    "de_hi",
    "e_lo",
    "e_hi",
    "ts_c_lo",
    "ts_c_hi",
    "dts_lo",
    "dts_hi",
    "ts_lo",
    "ts_hi",
    "thickness",
];

/// One piece's fields, printed outward: the v0 range inward (the claim holds on it) — an end
/// shared with the next piece exactly (the cuts are doubles with short exact decimals,
/// [`bwcl::observables::band::short_cuts`]), so that the printed pieces cover the range without
/// gaps; the ends of the whole range [`lo`, `hi`] inward — the centre exactly, lower bounds
/// down, upper bounds and the thickness up.
fn fields(p: &BandPiece, lo: f64, hi: f64) -> Vec<String> {
    let end = |x: f64, dir: Rounding| {
        if x == lo || x == hi {
            outward(x, dir)
        } else {
            exact_decimal(x)
        }
    };
    let pair = |i: Interval| {
        [
            outward(i.inf(), Rounding::Down),
            outward(i.sup(), Rounding::Up),
        ]
    };
    let mut f = vec![
        end(p.v0_lo, Rounding::Up),
        end(p.v0_hi, Rounding::Down),
        exact_decimal(p.v0_c),
    ];
    for i in [p.e_c, p.de, p.e, p.ts_c, p.dts, p.ts] {
        f.extend(pair(i));
    }
    f.push(outward(p.thickness(), Rounding::Up));
    f
}

/// A band report as JSON: `{meta, "key": [{column: value, …}, …]}`, one object per row of
/// `head`'s columns, a column named by `exact` written as a string (an exact decimal: a JSON
/// number reader would round it), every other as the number it is.
pub(super) fn json_rows(
    meta: &str,
    key: &str,
    head: &[&str],
    rows: impl IntoIterator<Item = Vec<String>>,
    exact: impl Fn(&str) -> bool,
) -> Vec<u8> {
    let mut s = format!("{{{meta},\"{key}\":[");
    for (k, r) in rows.into_iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        s.push('{');
        for (i, (h, v)) in head.iter().zip(r).enumerate() {
            if i > 0 {
                s.push(',');
            }
            if exact(h) {
                s.push_str(&format!("\"{h}\":\"{v}\""));
            } else {
                s.push_str(&format!("\"{h}\":{v}"));
            }
        }
        s.push('}');
    }
    s.push_str("]}\n");
    s.into_bytes()
}

/// The base set and the range of v0 of a `--band` case.
fn band_case(
    kind: ModelKind,
    cases: &[Case<Interval>],
) -> Result<(NdParams<Interval>, f64, f64), CliError> {
    let [c] = cases else {
        return Err(CliError::Input(format!(
            "--band needs one range of v0 (a..b), not {} speeds",
            cases.len()
        )));
    };
    let (Some(base), Some(v0)) = (&c.base, c.v0) else {
        return Err(CliError::Input(
            "--band needs --base (or --physical) and --v0 a..b".into(),
        ));
    };
    if !bwcl::observables::sets::is_range(&v0) {
        return Err(CliError::Input(
            "--band needs a range of v0 (a..b), not one speed".into(),
        ));
    }
    let _ = kind;
    Ok((base.clone(), v0.inf(), v0.sup()))
}

/// `cor --rigorous --band FILE`: the proved band, written to FILE; the summary on stdout.
pub fn band(a: &CorArgs, path: &Path) -> Result<i32, CliError> {
    input::out_path_as("--band", Some(path))?;
    let json = path.extension().is_some_and(|e| e == "json");
    let (bytes, summary) = band_report(a, json, None)?;
    output::emit_as("--band", Some(path), &bytes)?;
    output::emit(None, summary.as_bytes())?;
    Ok(super::EXIT_OK)
}

/// The proved band of `cor --rigorous --band` (the file's bytes, JSON or CSV) and its
/// one-line summary; a band not proved is a `CliError::Failed` naming why. Its progress goes
/// to `watch` when given, else to a bar on a terminal.
pub fn band_report(
    a: &CorArgs,
    json_file: bool,
    watch: Option<bwcl::observables::band::Progress>,
) -> Result<(Vec<u8>, String), CliError> {
    let kind = input::bouc_wen_only(a.params.model, "--band")?;
    let opts: TaylorOptions = input::taylor_options(&a.engine)?;
    let cases = input::cases::<Interval>(&a.params)?;
    let (base, lo, hi) = band_case(kind, &cases)?;
    let bar = watch
        .is_none()
        .then(|| super::progress::Progress::range("cor --band", a.engine.time_limit));
    if a.second_order {
        let progress = watch.or_else(|| bar.as_ref().map(|b| b.callback()));
        let r = super::band_second::report(a, kind, &base, lo, hi, &opts, json_file, progress);
        if let Some(b) = &bar {
            b.finish();
        }
        return r;
    }
    let bo = BandOptions {
        thickness: a.thickness.unwrap_or(1e-6),
        // --order when given, else the band's own default
        order: a.engine.order.unwrap_or(BandOptions::default().order),
        progress: watch.or_else(|| bar.as_ref().map(|b| b.callback())),
        ..BandOptions::default()
    };
    let start = std::time::Instant::now();
    let band = prove_band(kind, &base, lo, hi, &bo, &opts);
    if let Some(b) = &bar {
        b.finish();
    }
    let band = band.map_err(|e| not_proved(a, e))?;
    let secs = start.elapsed().as_secs_f64();
    let thick = band.thickness();
    let bytes = if json_file {
        let meta = format!(
            "\"model\":\"{}\",\"v0\":[{},{}],\"pieces_count\":{},\"thickness\":{},\"seconds\":{secs:.3}",
            kind.name(),
            outward(lo, Rounding::Up),
            outward(hi, Rounding::Down),
            band.pieces.len(),
            outward(thick, Rounding::Up)
        );
        // (v0_c exactly)
        json_rows(
            &meta,
            "pieces",
            &HEAD,
            band.pieces.iter().map(|p| fields(p, lo, hi)),
            |h| h == "v0_c",
        )
    } else {
        output::csv(&HEAD, band.pieces.iter().map(|p| fields(p, lo, hi)))?
    };
    let summary = format!(
        "proved band of e over v0 in [{}, {}]: {} pieces, thickness ≤ {}, e in [{}, {}], {secs:.1} s\n",
        outward(lo, Rounding::Up),
        outward(hi, Rounding::Down),
        band.pieces.len(),
        outward(thick, Rounding::Up),
        outward(
            band.pieces
                .iter()
                .map(|p| p.e.inf())
                .fold(f64::INFINITY, f64::min),
            Rounding::Down
        ),
        outward(
            band.pieces
                .iter()
                .map(|p| p.e.sup())
                .fold(f64::NEG_INFINITY, f64::max),
            Rounding::Up
        ),
    );
    Ok((bytes, summary))
}

/// The error of a band not proved, naming why (the time budget, or the engine's reason).
pub fn not_proved(a: &CorArgs, e: bwcl::engines::taylor::RigorError) -> CliError {
    let why = if e.out_of_time() {
        let rest = e
            .reason
            .strip_prefix(bwcl::engines::taylor::DEADLINE)
            .unwrap_or("");
        format!(
            "the time budget of {} s ran out (--time-limit){rest}",
            input::time_limit(a.engine.time_limit)
        )
    } else {
        e.reason
    };
    CliError::Failed(format!("band not proved: {why}"))
}

/// `prove monotone`: the report on stdout; exit 1 unless proved.
pub fn monotone(a: &MonotoneArgs) -> Result<i32, CliError> {
    input::out_path(a.out.as_deref())?;
    let (text, proved) = monotone_report(a, None)?;
    output::emit(a.out.as_deref(), text.as_bytes())?;
    Ok(if proved {
        super::EXIT_OK
    } else {
        super::EXIT_FAILED
    })
}

/// The report of `prove monotone` in its format, and whether the claim was proved. Its
/// progress goes to `watch` when given, else to a bar on a terminal.
pub fn monotone_report(
    a: &MonotoneArgs,
    watch: Option<bwcl::observables::band::Progress>,
) -> Result<(String, bool), CliError> {
    let kind = ModelKind::from(a.model);
    let base = NdParams::<Interval>::parse(kind, &a.base).map_err(|e| {
        CliError::Input(format!(
            "--base '{}': {}",
            bwcl::fit::data::echo(&a.base),
            e.0
        ))
    })?;
    // the decimals enclosed as written: the claim covers the range the user wrote
    let range =
        a.v0.contains("..")
            .then(|| <Interval as bwcl::arith::Real>::parse_decimal(&a.v0));
    let (lo, hi) = match range {
        Some(Ok(r)) => (r.inf(), r.sup()),
        // why the range is none (reversed, not a number, not finite), from its parser
        Some(Err(why)) => {
            return Err(CliError::Input(format!(
                "--v0: {}",
                super::input::compact(&why)
            )));
        }
        None => {
            return Err(CliError::Input(format!(
                "--v0 '{}': expected a range a..b of two numbers",
                bwcl::fit::data::echo(&a.v0)
            )));
        }
    };
    if !(lo > 0.0 && lo < hi && hi.is_finite()) {
        return Err(CliError::Input(format!(
            "--v0 '{}': expected 0 < a < b (finite)",
            bwcl::fit::data::echo(&a.v0)
        )));
    }
    let start = std::time::Instant::now();
    let bar = watch
        .is_none()
        .then(|| super::progress::Progress::range("prove monotone", a.time_limit));
    let m = prove_decreasing(
        kind,
        &base,
        lo,
        hi,
        &BandOptions {
            min_width: (hi - lo) * 1e-6,
            progress: watch.or_else(|| bar.as_ref().map(|b| b.callback())),
            ..BandOptions::default()
        },
        &TaylorOptions {
            deadline: Some(input::deadline(a.time_limit)),
            ..TaylorOptions::default()
        },
    );
    if let Some(b) = &bar {
        b.finish();
    }
    let secs = start.elapsed().as_secs_f64();
    let limit = input::time_limit(a.time_limit);
    // a piece stopped by the budget: named with the budget
    let why_text = |why: &str| {
        if why.starts_with(bwcl::engines::taylor::DEADLINE) {
            format!("the time budget of {limit} s ran out (--time-limit)")
        } else {
            why.to_string()
        }
    };
    let range_text = |a: f64, b: f64, inward: bool| {
        if inward {
            format!(
                "[{}, {}]",
                outward(a, Rounding::Up),
                outward(b, Rounding::Down)
            )
        } else {
            format!(
                "[{}, {}]",
                outward(a, Rounding::Down),
                outward(b, Rounding::Up)
            )
        }
    };
    let verdict = if m.proved() {
        "proved"
    } else if m.refuted() {
        "disproved"
    } else {
        "not proved"
    };
    // the least proved rise of e where it increases
    let min_rise = m
        .increasing
        .iter()
        .map(|p| p.2.inf())
        .fold(f64::INFINITY, f64::min);
    let text = match a.format {
        ReportFormat::Json => {
            let und: Vec<String> = m
                .undecided
                .iter()
                .map(|(a, b, why)| {
                    format!(
                        "{{\"v0\":[{},{}],\"reason\":{}}}",
                        outward(*a, Rounding::Down),
                        outward(*b, Rounding::Up),
                        serde_json::to_string(&why_text(why)).unwrap_or_default()
                    )
                })
                .collect();
            // the increasing pieces (the claim holds on the printed range: ends inward)
            let inc: Vec<String> = m
                .increasing
                .iter()
                .map(|(a, b, de)| {
                    format!(
                        "{{\"v0\":[{},{}],\"de_dv0\":[{},{}]}}",
                        outward(*a, Rounding::Up),
                        outward(*b, Rounding::Down),
                        outward(de.inf(), Rounding::Down),
                        outward(de.sup(), Rounding::Up)
                    )
                })
                .collect();
            format!(
                "{{\"model\":\"{}\",\"v0\":[{},{}],\"verdict\":\"{verdict}\",\"proved_decreasing\":{},\"pieces\":{},\"max_slope\":{},\"increasing\":[{}],\"undecided\":[{}],\"seconds\":{secs:.3}}}\n",
                kind.name(),
                outward(lo, Rounding::Up),
                outward(hi, Rounding::Down),
                m.proved(),
                m.pieces.len(),
                if m.pieces.is_empty() {
                    "null".into()
                } else {
                    outward(m.max_slope(), Rounding::Up)
                },
                inc.join(","),
                und.join(",")
            )
        }
        ReportFormat::Table => {
            if m.proved() {
                format!(
                    "PROVED: e(v0) is strictly decreasing for v0 in [{}, {}] ({} pieces, de/dv0 ≤ {} < 0 on each), {secs:.1} s\n",
                    outward(lo, Rounding::Up),
                    outward(hi, Rounding::Down),
                    m.pieces.len(),
                    outward(m.max_slope(), Rounding::Up)
                )
            } else if m.refuted() {
                let mut s = format!(
                    "DISPROVED: e(v0) is not decreasing on [{}, {}]: it is strictly increasing (de/dv0 ≥ {} > 0) for v0 in\n",
                    outward(lo, Rounding::Up),
                    outward(hi, Rounding::Down),
                    outward(min_rise, Rounding::Down)
                );
                for (a, b, _) in &m.increasing {
                    s.push_str(&format!("  {}\n", range_text(*a, *b, true)));
                }
                s.push_str(&format!(
                    "(decreasing proved on {} pieces, {} sub-range(s) undecided or not examined), {secs:.1} s\n",
                    m.pieces.len(),
                    m.undecided.len()
                ));
                s
            } else {
                let mut s = format!(
                    "NOT PROVED on all of [{}, {}]: decreasing on {} pieces; undecided on:\n",
                    outward(lo, Rounding::Up),
                    outward(hi, Rounding::Down),
                    m.pieces.len()
                );
                for (a, b, why) in &m.undecided {
                    s.push_str(&format!(
                        "  {}: {}\n",
                        range_text(*a, *b, false),
                        why_text(why)
                    ));
                }
                s
            }
        }
    };
    Ok((text, m.proved()))
}
