//! `cor --band FILE --second-order`: the proved CoR curve in the interpolation form
//! ([`bwcl::observables::band_second`]), one row per node interval.

use super::CliError;
use super::args::CorArgs;
use super::band::exact_decimal;
use super::output::{self, outward};
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::{ModelKind, NdParams};
use bwcl::observables::band::Progress;
use bwcl::observables::band_second::{InterpOptions, InterpPiece, prove_band_second};
use bwcl::observables::decimal::Rounding;
use inari::Interval;

/// The columns: on [v0_lo, v0_hi], e(v0) ∈ e(v0_lo)·(v0_hi − v0)/h + e(v0_hi)·(v0 − v0_lo)/h
/// − \[d2e\]·(v0 − v0_lo)(v0_hi − v0)/2 (h = v0_hi − v0_lo), T_s likewise.
pub const HEAD: [&str; 15] = [
    "v0_lo",
    "v0_hi",
    "e_at_lo_lo",
    "e_at_lo_hi",
    "e_at_hi_lo",
    "e_at_hi_hi",
    "d2e_lo",
    "d2e_hi",
    "ts_at_lo_lo",
    "ts_at_lo_hi",
    "ts_at_hi_lo",
    "ts_at_hi_hi",
    "d2ts_lo",
    "d2ts_hi",
    "thickness",
];

/// The rows of a piece: the nodes exactly (the range's own ends too: the form is stated at
/// the doubles e was proved at, which enclose the range as given), every bound outward.
fn rows(p: &InterpPiece) -> Vec<Vec<String>> {
    let pair = |i: Interval| {
        [
            outward(i.inf(), Rounding::Down),
            outward(i.sup(), Rounding::Up),
        ]
    };
    (0..p.nodes.len() - 1)
        .map(|k| {
            let (a, b) = (&p.nodes[k], &p.nodes[k + 1]);
            let mut f = vec![exact_decimal(a.0), exact_decimal(b.0)];
            for i in [a.1, b.1, p.e2, a.2, b.2, p.ts2] {
                f.extend(pair(i));
            }
            f.push(outward(p.interval_thickness(k), Rounding::Up));
            f
        })
        .collect()
}

/// The proved band in the interpolation form: the file's bytes and the summary line.
#[allow(clippy::too_many_arguments)]
pub fn report(
    a: &CorArgs,
    kind: ModelKind,
    base: &NdParams<Interval>,
    lo: f64,
    hi: f64,
    opts: &TaylorOptions,
    json_file: bool,
    progress: Option<Progress>,
) -> Result<(Vec<u8>, String), CliError> {
    let io = InterpOptions {
        thickness: a.thickness.unwrap_or(1e-9),
        progress,
        ..InterpOptions::default()
    };
    let start = std::time::Instant::now();
    let band = prove_band_second(kind, base, lo, hi, &io, opts)
        .map_err(|e| super::band::not_proved(a, e))?;
    let secs = start.elapsed().as_secs_f64();
    let thick = band.thickness();
    let rows: Vec<Vec<String>> = band.pieces.iter().flat_map(rows).collect();
    let bytes = if json_file {
        let meta = format!(
            "\"model\":\"{}\",\"form\":\"interpolation\",\"v0\":[{},{}],\"pieces_count\":{},\"intervals_count\":{},\"thickness\":{},\"seconds\":{secs:.3}",
            kind.name(),
            outward(lo, Rounding::Up),
            outward(hi, Rounding::Down),
            band.pieces.len(),
            rows.len(),
            outward(thick, Rounding::Up)
        );
        // (the nodes exactly)
        super::band::json_rows(&meta, "intervals", &HEAD, rows, |h| {
            h == "v0_lo" || h == "v0_hi"
        })
    } else {
        output::csv(&HEAD, rows)?
    };
    let (e_lo, e_hi) = band
        .pieces
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
            (0..p.nodes.len() - 1).fold((l, h), |(l, h), k| {
                let e = p.hull_on(k);
                (l.min(e.inf()), h.max(e.sup()))
            })
        });
    let summary = format!(
        "proved band of e over v0 in [{}, {}] (second order): {} pieces, {} node intervals, {} runs over a range and {} at a point, thickness ≤ {}, e in [{}, {}], {secs:.1} s\n",
        outward(lo, Rounding::Up),
        outward(hi, Rounding::Down),
        band.pieces.len(),
        band.pieces.iter().map(|p| p.nodes.len() - 1).sum::<usize>(),
        band.range_runs,
        band.point_runs,
        outward(thick, Rounding::Up),
        outward(e_lo, Rounding::Down),
        outward(e_hi, Rounding::Up),
    );
    Ok((bytes, summary))
}
