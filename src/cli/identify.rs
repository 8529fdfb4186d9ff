//! The `identify` subcommand: proved feasible sets of P* (set-membership identification,
//! [`bwcl::identify`]).

use super::args::{IdentifyArgs, IdentifyFormat};
use super::fit::read_data;
use super::output;
use super::progress::Progress;
use super::{CliError, EXIT_FAILED, EXIT_OK, note};
use bwcl::identify::paving::{Leaf, Options, Paving, Status, pave};
use bwcl::identify::sample::{Sampled, sample};
use bwcl::identify::setup::{Spec, problem};
use inari::Interval;
use serde::Serialize;
use serde_json::value::RawValue;
use std::collections::{BTreeMap, HashSet};
use std::fmt::Write as _;

/// The seed of `--sample`'s points (the same points on every run).
const SAMPLE_SEED: u64 = 31;

/// A bound rounded outward as a JSON number (null when not finite).
/// A box side [a, b] as two JSON numbers, rounded as [`output::ends_text`] says (a side
/// beyond the doubles as null).
fn bounds(a: f64, b: f64, inner: bool) -> [Box<RawValue>; 2] {
    let raw = |x: f64, mut t: String| {
        if !x.is_finite() {
            t = "null".into();
        } else if !t.contains(['.', 'e']) {
            t.push_str(".0");
        }
        RawValue::from_string(t).expect("a JSON number")
    };
    let [ta, tb] = output::ends_text(a, b, inner);
    [raw(a, ta), raw(b, tb)]
}

#[derive(Serialize)]
struct BoxOut {
    lo: Vec<Box<RawValue>>,
    hi: Vec<Box<RawValue>>,
    status: Status,
}

#[derive(Serialize)]
struct SampledOut {
    uniform: usize,
    uniform_feasible: usize,
    tested: usize,
    feasible: usize,
    hull: Option<BTreeMap<&'static str, [f64; 2]>>,
}

#[derive(Serialize)]
struct Counts {
    feasible: usize,
    infeasible: usize,
    undecided: usize,
}

#[derive(Serialize)]
struct Shares {
    feasible: f64,
    infeasible: f64,
    undecided: f64,
}

#[derive(Serialize)]
struct IdentifyOut<'a> {
    model: &'static str,
    free: Vec<&'static str>,
    /// The starting box (rounded inward: the box the claims are about), per free parameter.
    #[serde(rename = "box")]
    start: BTreeMap<&'static str, [Box<RawValue>; 2]>,
    rows: usize,
    /// What was proved, in words.
    verdict: String,
    /// F proved empty: the model is falsified by the data at the given errors.
    empty: bool,
    /// The outer hull of F per free parameter (feasible ∪ undecided boxes); null when empty.
    hull: Option<BTreeMap<&'static str, [Box<RawValue>; 2]>>,
    /// The hull of the boxes proved feasible (an inner estimate of F's hull); null when none.
    feasible_hull: Option<BTreeMap<&'static str, [Box<RawValue>; 2]>>,
    /// `--sample`: the points tested, those found feasible by the f64 engine, and their hull
    /// (not proved: an estimate of F's hull from inside; null when none was found).
    #[serde(skip_serializing_if = "Option::is_none")]
    sampled: Option<SampledOut>,
    counts: Counts,
    /// Shares of the starting box's volume (each side relative to the box's).
    shares: Shares,
    complete: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    stopped: Option<&'a str>,
    processed: usize,
    resolution: u64,
    seconds: f64,
    /// A classical law's empty F: the rows that refute each range of its parameter.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    certificate: Vec<String>,
    boxes: Vec<BoxOut>,
}

/// A box's ends are rounded inward unless it is undecided ([`output::ends_text`]): outward for
/// an enclosure (the hull of what may be consistent, an undecided box), inward for a set a
/// claim is made on (every point of a feasible box is consistent, of an infeasible one
/// inconsistent; the search covered the start box; the feasible boxes reach the feasible
/// hull's ends), so that a printed box claims no point the paving did not prove.
fn inner(s: Status) -> bool {
    s != Status::Undecided
}

fn named(
    free: &[&'static str],
    h: &[(f64, f64)],
    inner: bool,
) -> BTreeMap<&'static str, [Box<RawValue>; 2]> {
    free.iter()
        .zip(h)
        .map(|(n, &(a, b))| (*n, bounds(a, b, inner)))
        .collect()
}

/// "lo..hi" of a box's side, rounded as [`output::ends_text`] says.
fn range_text(a: f64, b: f64, inner: bool) -> String {
    let [ta, tb] = output::ends_text(a, b, inner);
    format!("{ta}..{tb}")
}

/// A share as a percentage with two decimals, rounded up (`up`) or down exactly.
fn percent(v: f64, up: bool) -> String {
    let Some(r) = rug::Rational::from_f64(v) else {
        return format!("{v} %");
    };
    let r = r * 10_000u32;
    let (q, _) = if up {
        r.ceil().into_numer_denom()
    } else {
        r.floor().into_numer_denom()
    };
    let (whole, frac) = q.div_rem_floor(rug::Integer::from(100));
    format!("{whole}.{frac:02} %")
}

/// The verdict line.
fn verdict(p: &Paving, d: &Done) -> String {
    let free = &d.free;
    let what = if d.refuted.is_some() {
        "parameter"
    } else {
        "P*"
    };
    if free.is_empty() {
        return match p.boxes.first().map(|b| b.status) {
            Some(Status::Feasible) => "proved: the law (e = 1) is consistent with the data".into(),
            Some(Status::Infeasible) => {
                "proved: the law (e = 1) is inconsistent with the data at these errors".into()
            }
            _ => "not proved either way: e = 1 lies on a row's bound (or the engine failed)".into(),
        };
    }
    match p.hull() {
        None if matches!(d.refuted, Some((_, _, true))) => "proved: no value of the parameter \
             is consistent with the data, in the box or beyond it (e is monotone in it): F is \
             empty, the law is falsified by the data at these errors"
            .into(),
        None => format!(
            "proved: no {what} in the box is consistent with the data (F is empty: the model is \
             falsified by the data at these errors)"
        ),
        Some(h) => {
            let parts: Vec<String> = free
                .iter()
                .zip(&h)
                .map(|(n, &(a, b))| {
                    let [ta, tb] = output::ends_text(a, b, false);
                    format!("{n} ∈ [{ta}, {tb}]")
                })
                .collect();
            let feasible = if p.counts()[0] > 0 {
                "some values are proved consistent"
            } else {
                "no box is proved feasible at this resolution"
            };
            format!(
                "proved: every {what} in the box consistent with the data has {}; {feasible}",
                parts.join(", ")
            )
        }
    }
}

/// A paving done, with what its reports need.
pub struct Done {
    /// The model's name.
    pub model: &'static str,
    pub rows: usize,
    pub start: Vec<Interval>,
    pub free: Vec<&'static str>,
    pub paving: Paving,
    /// A classical law's refutations (with the data, to name the rows,
    /// and whether they cover the parameter's whole admissible set).
    pub refuted: Option<(
        Vec<bwcl::identify::laws::Refutation>,
        bwcl::fit::CorData,
        bool,
    )>,
    /// `--sample N`: the f64-feasible points found (not proved).
    pub sampled: Option<Sampled>,
}

/// Reads the data, builds the problem and paves the box (a progress bar on a terminal when
/// `bar` is set; `watch` told the share of the box decided and a message, for a Bouc–Wen
/// model).
pub fn compute(
    a: &IdentifyArgs,
    bar: bool,
    watch: Option<&(dyn Fn(f64, String) + Sync)>,
) -> Result<Done, CliError> {
    let kind = match (a.model.kind(), a.model.law()) {
        (Some(kind), _) => kind,
        (_, Some(law)) => return super::compare::identify(a, law, bar),
        _ => unreachable!("a model or a law"),
    };
    let data = read_data(&a.data)?;
    let spec = Spec {
        base: a.base.as_deref(),
        fix: a.fix.as_deref(),
        bounds: a.bounds.as_deref(),
        free: a.free.as_deref(),
        error: a.error,
        tc_error: a.tc_error,
        no_tc: a.no_tc,
    };
    let (prob, start) = problem(kind, &data, &spec).map_err(CliError::Input)?;
    let mut opts = Options::new(&start, resolution(a) as f64);
    opts.max_boxes = a.max_boxes as usize;
    opts.taylor.deadline = Some(super::input::deadline(a.time_limit));
    opts.slope_taylor.deadline = opts.taylor.deadline;
    let progress = bar.then(|| Progress::range("identify", a.time_limit));
    let cb = |p: bwcl::identify::Progress| {
        let message = || {
            format!(
                "{:.1} % of the box decided, {} boxes done, {} waiting",
                100.0 * (1.0 - p.undecided),
                p.processed,
                p.queued
            )
        };
        if let Some(b) = &progress {
            b.set(1.0 - p.undecided, message())
        }
        if let Some(w) = watch {
            w(1.0 - p.undecided, message())
        }
    };
    let paving = pave(&prob, &start, &opts, Some(&cb));
    if let Some(b) = &progress {
        b.finish();
    }
    let sampled = (a.sample > 0).then(|| sample(&prob, &start, a.sample, SAMPLE_SEED));
    Ok(Done {
        model: kind.name(),
        rows: prob.rows.len(),
        start,
        free: prob.space.free_names(),
        paving,
        refuted: None,
        sampled,
    })
}

/// The JSON report of a paving (the shape).
pub fn json_report(d: &Done, resolution: u64) -> Result<Vec<u8>, CliError> {
    let (paving, free, start) = (&d.paving, &d.free, &d.start);
    let [nf, ni, nu] = paving.counts();
    let [sf, si, su] = paving.shares(start);
    let hull = paving.hull();
    let out = IdentifyOut {
        model: d.model,
        free: free.clone(),
        start: named(
            free,
            &start.iter().map(|x| (x.inf(), x.sup())).collect::<Vec<_>>(),
            true,
        ),
        rows: d.rows,
        verdict: verdict(paving, d),
        empty: hull.is_none(),
        hull: hull.as_ref().map(|h| named(free, h, false)),
        feasible_hull: paving.feasible_hull().map(|h| named(free, &h, true)),
        sampled: d.sampled.as_ref().map(|s| SampledOut {
            uniform: s.uniform,
            uniform_feasible: s.uniform_feasible,
            tested: s.tested,
            feasible: s.points.len(),
            hull: s
                .hull()
                .map(|h| free.iter().zip(h).map(|(n, (a, b))| (*n, [a, b])).collect()),
        }),
        counts: Counts {
            feasible: nf,
            infeasible: ni,
            undecided: nu,
        },
        shares: Shares {
            feasible: sf,
            infeasible: si,
            undecided: su,
        },
        complete: paving.stopped.is_none(),
        stopped: paving.stopped.as_deref(),
        processed: paving.processed,
        resolution,
        seconds: paving.seconds,
        certificate: certificate(d),
        boxes: paving.boxes.iter().map(box_out).collect(),
    };
    super::output::json(&out)
}

pub fn identify(a: &IdentifyArgs) -> Result<i32, CliError> {
    super::input::out_path(a.out.as_deref())?;
    super::input::out_path_as("--plot", a.plot.as_deref())?;
    let done = compute(a, true, None)?;
    let d = &done;
    let start = &d.start;
    let paving = &d.paving;
    let prob_rows = d.rows;
    let free = d.free.clone();
    let [nf, ni, nu] = paving.counts();
    let [sf, si, su] = paving.shares(start);
    let verdict = verdict(paving, d);
    let resolution = resolution(a);
    let hull = paving.hull();
    let bytes = match a.format {
        IdentifyFormat::Json => json_report(d, resolution)?,
        IdentifyFormat::Csv => {
            let mut head = vec!["status".to_string()];
            for n in &free {
                head.push(format!("{n}_lo"));
                head.push(format!("{n}_hi"));
            }
            let head: Vec<&str> = head.iter().map(String::as_str).collect();
            let rows = paving.boxes.iter().map(|b| {
                let mut r = vec![status_name(b.status).to_string()];
                for (&lo, &hi) in b.lo.iter().zip(&b.hi) {
                    r.extend(output::ends_text(lo, hi, inner(b.status)));
                }
                r
            });
            output::csv(&head, rows)?
        }
        IdentifyFormat::Table => {
            let mut s = format!(
                "model {}: {} data rows, free {} (resolution 1/{resolution})\n{verdict}\n\n",
                d.model,
                prob_rows,
                if free.is_empty() {
                    "none".into()
                } else {
                    free.join(", ")
                },
            );
            for c in certificate(d) {
                let _ = writeln!(s, "  {c}");
            }
            if d.refuted.is_some() && !certificate(d).is_empty() {
                s.push('\n');
            }
            let rows: Vec<Vec<String>> = [
                ("feasible", nf, sf),
                ("infeasible", ni, si),
                ("undecided", nu, su),
            ]
            .iter()
            .map(|(n, c, v)| {
                // the undecided share rounded up, the proved ones down
                vec![n.to_string(), c.to_string(), percent(*v, *n == "undecided")]
            })
            .collect();
            s.push_str(&output::table(
                &["boxes", "count", "share of the box"],
                &rows,
            ));
            if let Some(h) = &hull {
                s.push('\n');
                let fh = paving.feasible_hull();
                let sh = d.sampled.as_ref().and_then(Sampled::hull);
                let rows: Vec<Vec<String>> = free
                    .iter()
                    .enumerate()
                    .map(|(j, n)| {
                        vec![
                            n.to_string(),
                            range_text(start[j].inf(), start[j].sup(), true),
                            range_text(h[j].0, h[j].1, false),
                            fh.as_ref()
                                .map_or("-".into(), |f| range_text(f[j].0, f[j].1, true)),
                        ]
                        .into_iter()
                        .chain(d.sampled.as_ref().map(|_| match &sh {
                            Some(sh) => format!(
                                "{:.6}..{:.6} ({:.2}×)",
                                sh[j].0,
                                sh[j].1,
                                (h[j].1 - h[j].0) / (sh[j].1 - sh[j].0)
                            ),
                            None => "none found".into(),
                        }))
                        .collect()
                    })
                    .collect();
                let mut head = vec![
                    "parameter",
                    "box",
                    "hull of F (proved)",
                    "hull of the feasible boxes",
                ];
                if d.sampled.is_some() {
                    head.push("hull of f64-sampled points (proved width / its)");
                }
                s.push_str(&output::table(&head, &rows));
                if let Some(sp) = &d.sampled {
                    let _ = writeln!(
                        s,
                        "\n--sample: {} of {} uniform points feasible by the f64 engine, {} of {} \
                         with the pushes towards the faces (not proved)",
                        sp.uniform_feasible,
                        sp.uniform,
                        sp.points.len(),
                        sp.tested
                    );
                }
            }
            let _ = writeln!(
                s,
                "\n{} boxes processed in {:.1} s{}",
                paving.processed,
                paving.seconds,
                paving
                    .stopped
                    .as_ref()
                    .map(|r| format!("; stopped: {r} (the rest is undecided)"))
                    .unwrap_or_default()
            );
            s.into_bytes()
        }
    };
    if let Some(p) = &a.plot {
        output::emit_as("--plot", Some(p), svg(paving, start, &free).as_bytes())?;
    }
    output::emit(a.out.as_deref(), &bytes)?;
    match &paving.stopped {
        None => Ok(EXIT_OK),
        Some(r) => {
            note(&format!(
                "bwcl: identify: {r}: {} of the box is undecided (what is reported is proved)",
                percent(su, true)
            ));
            Ok(EXIT_FAILED)
        }
    }
}

/// The effective `--resolution` (its default depends on the model).
pub fn resolution(a: &IdentifyArgs) -> u64 {
    a.resolution.unwrap_or(if a.model.law().is_some() {
        super::compare::LAW_RESOLUTION as u64
    } else {
        128
    })
}

/// A classical law's certificate of an empty F (empty otherwise).
fn certificate(d: &Done) -> Vec<String> {
    match (&d.refuted, d.paving.hull()) {
        (Some((r, data, _)), None) => {
            let law = bwcl::fit::laws::Law::from_key(d.model).expect("a law's name");
            super::compare::certificate(law, r, data)
        }
        _ => vec![],
    }
}

fn status_name(s: Status) -> &'static str {
    match s {
        Status::Feasible => "feasible",
        Status::Infeasible => "infeasible",
        Status::Undecided => "undecided",
    }
}

fn box_out(b: &Leaf) -> BoxOut {
    let (lo, hi) =
        b.lo.iter()
            .zip(&b.hi)
            .map(|(&a, &c)| {
                let [x, y] = bounds(a, c, inner(b.status));
                (x, y)
            })
            .unzip();
    BoxOut {
        lo,
        hi,
        status: b.status,
    }
}

/// The paving's 2-D projections as SVG: one panel per pair of free parameters (one panel for
/// one parameter), infeasible boxes (grey) only for two free parameters, undecided (orange)
/// and feasible (green) drawn over them.
pub fn svg(p: &Paving, start: &[Interval], free: &[&str]) -> String {
    const S: f64 = 260.0;
    const M: f64 = 50.0;
    let dim = start.len();
    let pairs: Vec<(usize, usize)> = if dim == 1 {
        vec![(0, 0)]
    } else {
        (0..dim)
            .flat_map(|i| (i + 1..dim).map(move |j| (i, j)))
            .collect()
    };
    let cols = (pairs.len() as f64).sqrt().ceil() as usize;
    let rows = pairs.len().div_ceil(cols);
    let (w, h) = (cols as f64 * (S + M) + M, rows as f64 * (S + M) + M);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    for (k, &(i, j)) in pairs.iter().enumerate() {
        let (ox, oy) = (
            M + (k % cols) as f64 * (S + M),
            M / 2.0 + (k / cols) as f64 * (S + M),
        );
        let x = |v: f64| ox + S * (v - start[i].inf()) / start[i].wid();
        let y = |v: f64| {
            if i == j {
                oy
            } else {
                oy + S - S * (v - start[j].inf()) / start[j].wid()
            }
        };
        let _ = writeln!(
            s,
            "<rect x=\"{ox}\" y=\"{oy}\" width=\"{S}\" height=\"{S}\" fill=\"none\" stroke=\"black\"/>"
        );
        let mut seen = HashSet::new();
        for status in [Status::Infeasible, Status::Undecided, Status::Feasible] {
            if status == Status::Infeasible && dim != 2 {
                continue;
            }
            let fill = match status {
                Status::Infeasible => "#d9d9d9",
                Status::Undecided => "#f4a341",
                Status::Feasible => "#3c9b4b",
            };
            for b in p.boxes.iter().filter(|b| b.status == status) {
                let (x0, x1) = (x(b.lo[i]), x(b.hi[i]));
                let (y0, y1) = if i == j {
                    (oy, oy + S)
                } else {
                    (y(b.hi[j]), y(b.lo[j]))
                };
                let key = (
                    status as u8,
                    (x0 * 2.0) as i64,
                    (x1 * 2.0) as i64,
                    (y0 * 2.0) as i64,
                    (y1 * 2.0) as i64,
                );
                if !seen.insert(key) {
                    continue;
                }
                let _ = writeln!(
                    s,
                    "<rect x=\"{x0:.2}\" y=\"{y0:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{fill}\"/>",
                    (x1 - x0).max(0.3),
                    (y1 - y0).max(0.3)
                );
            }
        }
        let lab = |v: f64| format!("{v:.4}");
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\
             <text x=\"{ox}\" y=\"{}\">{}</text><text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>",
            ox + S / 2.0,
            oy + S + 28.0,
            free[i],
            oy + S + 14.0,
            lab(start[i].inf()),
            ox + S,
            oy + S + 14.0,
            lab(start[i].sup())
        );
        if i != j {
            let _ = writeln!(
                s,
                "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\
                 <text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\
                 <text x=\"{}\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 {} {})\">{}</text>",
                ox - 3.0,
                oy + S,
                lab(start[j].inf()),
                ox - 3.0,
                oy + 10.0,
                lab(start[j].sup()),
                ox - 38.0,
                oy + S / 2.0,
                ox - 38.0,
                oy + S / 2.0,
                free[j]
            );
        }
    }
    s.push_str("</svg>\n");
    s
}
