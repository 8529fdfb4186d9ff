//! The writers: table, JSON and CSV for `cor`, CSV for trajectories, and the atomic output to a
//! file or stdout.

use super::CliError;
use super::args::Format;
use bwcl::observables::decimal::{self, Rounding};
use inari::Interval;
use serde::{Serialize, Serializer};
use serde_json::value::RawValue;
use std::io::Write;
use std::path::Path;

/// The nondimensional parameters of a case, as written to JSON.
#[derive(Serialize, Clone, Debug)]
pub struct ParamsOut<T> {
    #[serde(rename = "B")]
    pub b: T,
    #[serde(rename = "Gamma")]
    pub gamma: T,
    pub kappa: T,
    pub sigma: T,
    pub n: T,
    pub p: T,
}

/// The parameters of a row: the six of a Bouc–Wen set, or a classical law's by name (JSON: an
/// object either way).
#[derive(Serialize, Clone, Debug)]
#[serde(untagged)]
pub enum RowParams<T> {
    BoucWen(ParamsOut<T>),
    Law(std::collections::BTreeMap<&'static str, T>),
}

/// The derived outputs of a case (--derived, [`bwcl::observables::derived`]): F_max, δ_max and
/// ΔE nondimensional, and in SI (N, m, J) for --physical; `reason` where they were not
/// computed. `T` is f64 for the float engine, [`JsonPair`] (bounds rounded outward) for the
/// rigorous one.
#[derive(Serialize, Clone, Debug)]
pub struct DerivedOut<T> {
    pub peak_force: Option<T>,
    pub max_indentation: Option<T>,
    pub energy_lost: Option<T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_force_newtons: Option<T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_indentation_m: Option<T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_lost_joules: Option<T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

impl<T: Copy> DerivedOut<T> {
    /// Not computed, for `reason`.
    pub fn not(reason: impl Into<String>) -> Self {
        DerivedOut {
            peak_force: None,
            max_indentation: None,
            energy_lost: None,
            peak_force_newtons: None,
            max_indentation_m: None,
            energy_lost_joules: None,
            reason: Some(reason.into()),
        }
    }

    /// From the nondimensional values and, for --physical, the SI ones.
    pub fn of<R>(
        d: &bwcl::observables::derived::Derived<R>,
        si: Option<&bwcl::observables::derived::Derived<R>>,
        f: impl Fn(&R) -> T,
    ) -> Self {
        DerivedOut {
            peak_force: Some(f(&d.peak_force)),
            max_indentation: Some(f(&d.max_indentation)),
            energy_lost: Some(f(&d.energy_lost)),
            peak_force_newtons: si.map(|s| f(&s.peak_force)),
            max_indentation_m: si.map(|s| f(&s.max_indentation)),
            energy_lost_joules: si.map(|s| f(&s.energy_lost)),
            reason: None,
        }
    }

    /// The six values in column order (nondimensional, then SI).
    pub fn values(&self) -> [Option<T>; 6] {
        [
            self.peak_force,
            self.max_indentation,
            self.energy_lost,
            self.peak_force_newtons,
            self.max_indentation_m,
            self.energy_lost_joules,
        ]
    }
}

/// The derived columns' names, nondimensional then SI (`physical`).
pub fn derived_columns(physical: bool) -> &'static [&'static str] {
    let all: &'static [&'static str] = &[
        "peak_force",
        "max_indentation",
        "energy_lost",
        "peak_force_newtons",
        "max_indentation_m",
        "energy_lost_joules",
    ];
    if physical { all } else { &all[..3] }
}

/// One float case of `cor`.
#[derive(Serialize, Clone, Debug)]
pub struct FloatRow {
    pub model: &'static str,
    /// None for --nd.
    pub v0: Option<f64>,
    pub separated: bool,
    /// None without separation before the horizon (or on failure).
    pub ts: Option<f64>,
    /// 0 without separation; None on failure.
    pub e: Option<f64>,
    /// Only for --physical: T_s·T_c \[s\] (null without separation).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ts_seconds: Option<Option<f64>>,
    /// Only for --physical: the time scale T_c \[s\].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t_c: Option<f64>,
    pub nfev: usize,
    pub steps: usize,
    pub horizon: f64,
    pub params: RowParams<f64>,
    /// Why the integration failed (the case is then not a result).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// With --derived: F_max, δ_max, ΔE.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub derived: Option<DerivedOut<f64>>,
}

impl FloatRow {
    /// A case not yet computed: its model, speed, time scale (--physical), horizon and
    /// parameters.
    pub fn new(
        model: &'static str,
        v0: Option<f64>,
        t_c: Option<f64>,
        horizon: f64,
        params: RowParams<f64>,
    ) -> Self {
        FloatRow {
            model,
            v0,
            separated: false,
            ts: None,
            e: None,
            ts_seconds: t_c.map(|_| None),
            t_c,
            nfev: 0,
            steps: 0,
            horizon,
            params,
            error: None,
            derived: None,
        }
    }
}

/// One rigorous case of `cor`: proved enclosures, or the reason they could not be proved.
///
/// In every format each bound is printed rounded outward ([`decimal`]): lower bounds toward
/// −∞, upper bounds and widths toward +∞.
#[derive(Serialize, Clone, Debug)]
pub struct RigorousRow {
    pub model: &'static str,
    /// The impact speeds the result holds for: the enclosure of v0 as written (a range for a..b),
    /// its ends rounded inward ([`inner_pair`]); None for --nd.
    #[serde(serialize_with = "json_inner")]
    pub v0: Option<[f64; 2]>,
    pub proved: bool,
    /// Proved: the separation happens (T_s is finite and in `ts`).
    pub separated: bool,
    #[serde(serialize_with = "json_pair")]
    pub ts: Option<[f64; 2]>,
    #[serde(serialize_with = "json_width")]
    pub width_ts: Option<f64>,
    #[serde(serialize_with = "json_pair")]
    pub e: Option<[f64; 2]>,
    #[serde(serialize_with = "json_width")]
    pub width_e: Option<f64>,
    /// Only for --physical: an enclosure of T_s·T_c \[s\].
    #[serde(
        skip_serializing_if = "Option::is_none",
        serialize_with = "json_opt_pair"
    )]
    pub ts_seconds: Option<Option<[f64; 2]>>,
    pub horizon: f64,
    pub order: usize,
    #[serde(serialize_with = "json_params")]
    pub params: RowParams<[f64; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// With --sensitivities: proved ∂T_s/∂u and ∂e/∂u of every input u (JSON only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sensitivities: Option<Vec<Sensitivity>>,
    /// The precision of the run that proved the case (bits of the interval ends: 53 for the
    /// f64-interval engine, 128/192/256 for the precision fallback; also when not proved, the
    /// last precision tried).
    pub bits: u32,
    /// The runs of the precision fallback, when it ran (JSON only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fallback: Option<Vec<FallbackRun>>,
    /// Inputs given as ranges: how the range was split and how tight the hull is (JSON; a
    /// note on stderr otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<RangeOut>,
    /// With --derived: enclosures of F_max, δ_max, ΔE.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub derived: Option<DerivedOut<JsonPair>>,
}

impl RigorousRow {
    /// A case not yet proved: its model, speed, whether it has T_s in seconds (--physical),
    /// horizon, Taylor order and parameters.
    pub fn new(
        model: &'static str,
        v0: Option<[f64; 2]>,
        physical: bool,
        horizon: f64,
        order: usize,
        params: RowParams<[f64; 2]>,
    ) -> Self {
        RigorousRow {
            model,
            v0,
            proved: false,
            separated: false,
            ts: None,
            width_ts: None,
            e: None,
            width_e: None,
            ts_seconds: physical.then_some(None),
            horizon,
            order,
            params,
            reason: None,
            sensitivities: None,
            bits: 53,
            fallback: None,
            range: None,
            derived: None,
        }
    }
}

/// The adaptive split of a range ([`crate::observables::split`]).
#[derive(Serialize, Clone, Debug)]
pub struct RangeOut {
    pub pieces: usize,
    /// "tight", "pieces", "time" or "unsplittable": why the split stopped.
    pub stop: &'static str,
    /// Inner bounds [a, b] of e over the range, proved at points: min e ≤ a and max e ≥ b
    /// (printed inward: a rounded up, b down); null when unknown.
    #[serde(serialize_with = "json_inner")]
    pub e_inner: Option<[f64; 2]>,
    #[serde(serialize_with = "json_inner")]
    pub ts_inner: Option<[f64; 2]>,
    /// Upper bounds of wid(e)/(b − a) and of the same for T_s (null: unknown).
    #[serde(serialize_with = "json_ratio")]
    pub e_ratio: f64,
    #[serde(serialize_with = "json_ratio")]
    pub ts_ratio: f64,
    /// The same in words.
    pub note: String,
}

/// Inner bounds: [a rounded up, b rounded down] (the claims min ≤ a, max ≥ b stay true).
fn json_inner<S: Serializer>(b: &Option<[f64; 2]>, s: S) -> Result<S::Ok, S::Error> {
    match b {
        Some(p) => json_directed_pair(*p, [Rounding::Up, Rounding::Down], s),
        None => s.serialize_none(),
    }
}

/// A ratio bound, rounded up (null when not finite).
fn json_ratio<S: Serializer>(r: &f64, s: S) -> Result<S::Ok, S::Error> {
    json_bound(*r, Rounding::Up, s)
}

/// One run of the precision fallback.
#[derive(Serialize, Clone, Debug)]
pub struct FallbackRun {
    pub bits: u32,
    pub seconds: f64,
    pub proved: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// Proved ∂T_s/∂u and ∂e/∂u of one input (bounds rounded outward), or why not.
#[derive(Serialize, Clone, Debug)]
pub struct Sensitivity {
    pub input: &'static str,
    #[serde(serialize_with = "json_pair")]
    pub dts: Option<[f64; 2]>,
    #[serde(serialize_with = "json_pair")]
    pub de: Option<[f64; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// The bounds of an interval.
pub fn bounds(x: Interval) -> [f64; 2] {
    [x.inf(), x.sup()]
}

/// hi − lo rounded upward (an upper bound of the true width).
pub fn width(x: Interval) -> f64 {
    let (lo, hi) = (x.inf(), x.sup());
    match (Interval::try_from((hi, hi)), Interval::try_from((lo, lo))) {
        (Ok(h), Ok(l)) => (h - l).sup(),
        _ => f64::INFINITY,
    }
}

/// A bound rounded in direction `dir`, as a JSON number with the exact digits of
/// [`decimal::outward`] (null when not finite, as serde_json writes a non-finite f64).
fn json_bound<S: Serializer>(x: f64, dir: Rounding, s: S) -> Result<S::Ok, S::Error> {
    if !x.is_finite() {
        return s.serialize_none();
    }
    let mut text = decimal::outward(x, dir);
    // a float as serde_json writes one (`1.0`, not `1`), so readers keep the field's type
    if !text.contains(['.', 'e']) {
        text.push_str(".0");
    }
    let raw = RawValue::from_string(text).map_err(serde::ser::Error::custom)?;
    raw.serialize(s)
}

/// An enclosure [lo, hi] rounded outward, as a JSON array of two numbers.
#[derive(Clone, Copy, Debug)]
pub struct JsonPair(pub [f64; 2]);

impl Serialize for JsonPair {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        json_directed_pair(self.0, [Rounding::Down, Rounding::Up], s)
    }
}

/// Two bounds as a JSON array of two numbers, each rounded in its own direction.
fn json_directed_pair<S: Serializer>(
    p: [f64; 2],
    dirs: [Rounding; 2],
    s: S,
) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeTuple;
    struct B(f64, Rounding);
    impl Serialize for B {
        fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            json_bound(self.0, self.1, s)
        }
    }
    let mut t = s.serialize_tuple(2)?;
    t.serialize_element(&B(p[0], dirs[0]))?;
    t.serialize_element(&B(p[1], dirs[1]))?;
    t.end()
}

fn json_pair<S: Serializer>(b: &Option<[f64; 2]>, s: S) -> Result<S::Ok, S::Error> {
    b.map(JsonPair).serialize(s)
}

fn json_opt_pair<S: Serializer>(b: &Option<Option<[f64; 2]>>, s: S) -> Result<S::Ok, S::Error> {
    json_pair(&b.flatten(), s)
}

/// A width, rounded up.
fn json_width<S: Serializer>(w: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
    match w {
        Some(w) => json_bound(*w, Rounding::Up, s),
        None => s.serialize_none(),
    }
}

/// The interval parameters, each rounded outward.
fn json_params<S: Serializer>(p: &RowParams<[f64; 2]>, s: S) -> Result<S::Ok, S::Error> {
    match p {
        RowParams::BoucWen(p) => ParamsOut {
            b: JsonPair(p.b),
            gamma: JsonPair(p.gamma),
            kappa: JsonPair(p.kappa),
            sigma: JsonPair(p.sigma),
            n: JsonPair(p.n),
            p: JsonPair(p.p),
        }
        .serialize(s),
        RowParams::Law(m) => {
            let named: std::collections::BTreeMap<_, _> =
                m.iter().map(|(k, v)| (*k, JsonPair(*v))).collect();
            named.serialize(s)
        }
    }
}

/// A lower bound (`Rounding::Down`) or an upper bound or width (`Rounding::Up`) as the
/// shortest decimal on that side that reads back to the same double.
pub fn outward(x: f64, dir: Rounding) -> String {
    decimal::outward(x, dir)
}

/// The ends of [lo, hi] as decimals: outward (the lower end rounded down, the upper up) for an
/// enclosure of a result; `inner` (the lower end up, the upper down, each still reading back to
/// its double) for a set a claim is made on — a range of v0 the result holds for, a feasible or
/// infeasible box — so that the printed set claims no point the run did not cover. A single
/// double printed inward is its exact decimal (the two inward ends of 1.0000000000000002 would
/// cross: 1.0000000000000003, 1.0000000000000002).
pub fn ends_text(lo: f64, hi: f64, inner: bool) -> [String; 2] {
    if !inner {
        return [outward(lo, Rounding::Down), outward(hi, Rounding::Up)];
    }
    if lo == hi {
        let x = decimal::exact(lo);
        return [x.clone(), x];
    }
    [outward(lo, Rounding::Up), outward(hi, Rounding::Down)]
}

/// The ends of a range a result is claimed for (a range of v0 given as a..b), rounded inward
/// ([`ends_text`]).
pub fn inner_pair(lo: f64, hi: f64) -> [String; 2] {
    ends_text(lo, hi, true)
}

/// The cells of an enclosure in a CSV: lower bound rounded down, upper bound up.
pub fn outward_pair(i: Interval) -> [String; 2] {
    ends_text(i.inf(), i.sup(), false)
}

/// The tail of a failure's stderr line when `--out` was given: the file is left as it was and
/// the output (with the reasons) went to stdout; empty without `--out`.
pub fn out_kept(out: Option<&std::path::Path>) -> String {
    match out {
        Some(p) => format!(
            "; --out '{}' left unchanged, the output is on stdout",
            bwcl::fit::data::echo(&p.to_string_lossy())
        ),
        None => String::new(),
    }
}

/// A double in the shortest form that reads back exactly: plain for ordinary magnitudes,
/// exponent form for very small or large ones.
pub fn num(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || (1e-5..1e16).contains(&a) || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// An interval bound at fixed width (17 significant digits, aligned in a table), rounded in
/// direction `dir` exactly: within one unit of the 17th digit of the double, on its outer side
/// (it may read back to the neighbouring double, which is still a bound).
fn bound(x: f64, dir: Rounding) -> String {
    match decimal::directed(x, 17, dir) {
        Some(d) => d.scientific(17),
        None => format!("{x}"),
    }
}

fn interval_text(b: [f64; 2]) -> String {
    format!(
        "[{}, {}]",
        bound(b[0], Rounding::Down),
        bound(b[1], Rounding::Up)
    )
}

/// The shortest decimal whose double lies in [l, h], for an interval that is the enclosure
/// of a decimal the user wrote (a few ulps wide): the table shows "0.1", not its enclosure.
/// `None` for a real range.
fn short_decimal_in(l: f64, h: f64) -> Option<String> {
    if h - l > 4.0 * f64::EPSILON * l.abs().max(h.abs()) || (h - l).is_nan() {
        return None;
    }
    let m = 0.5 * (l + h);
    (0..17).find_map(|p| {
        let x: f64 = format!("{m:.p$e}").parse().ok()?;
        (l <= x && x <= h).then(|| format!("{x}"))
    })
}

/// The v0 cell of a table or CSV.
fn opt_num(x: Option<f64>) -> String {
    x.map(num).unwrap_or_default()
}

/// Renders the float rows of `cor`.
pub fn float_cor(rows: &[FloatRow], format: Format) -> Result<Vec<u8>, CliError> {
    let physical = rows.iter().any(|r| r.ts_seconds.is_some());
    let any_error = rows.iter().any(|r| r.error.is_some());
    let derived = rows.iter().any(|r| r.derived.is_some());
    let ncols = derived_columns(physical).len();
    match format {
        Format::Json => json(rows),
        Format::Csv => {
            let mut head = vec!["model", "v0", "separated", "ts", "e"];
            if physical {
                head.extend(["ts_seconds", "t_c"]);
            }
            head.extend(["nfev", "steps"]);
            if derived {
                head.extend(derived_columns(physical));
            }
            if any_error {
                head.push("error");
            }
            let body = rows.iter().map(|r| {
                let mut c = vec![
                    r.model.to_string(),
                    opt_num(r.v0),
                    r.separated.to_string(),
                    opt_num(r.ts),
                    opt_num(r.e),
                ];
                if physical {
                    c.push(opt_num(r.ts_seconds.flatten()));
                    c.push(opt_num(r.t_c));
                }
                c.push(r.nfev.to_string());
                c.push(r.steps.to_string());
                if derived {
                    let v = r.derived.as_ref().map(|d| d.values()).unwrap_or_default();
                    c.extend(v[..ncols].iter().map(|x| opt_num(*x)));
                }
                if any_error {
                    c.push(r.error.clone().unwrap_or_default());
                }
                c
            });
            csv(&head, body)
        }
        Format::Table => {
            let mut head = vec!["model", "v0", "ts", "e"];
            if physical {
                head.push("ts_seconds");
            }
            head.extend(["nfev", "steps"]);
            if derived {
                head.extend(derived_columns(physical));
            }
            let body: Vec<Vec<String>> = rows
                .iter()
                .map(|r| {
                    let v0 = r.v0.map(num).unwrap_or_else(|| "-".into());
                    let mut c = vec![r.model.to_string(), v0];
                    if let Some(err) = &r.error {
                        c.push(format!("integration failed: {err}"));
                        return c;
                    }
                    match r.ts {
                        None => {
                            c.push(format!(
                                "no separation before the horizon T = {} (e = 0)",
                                num(r.horizon)
                            ));
                            return c;
                        }
                        Some(ts) => {
                            c.push(num(ts));
                            c.push(opt_num(r.e));
                        }
                    }
                    if physical {
                        c.push(opt_num(r.ts_seconds.flatten()));
                    }
                    c.push(r.nfev.to_string());
                    c.push(r.steps.to_string());
                    if derived {
                        let v = r.derived.as_ref().map(|d| d.values()).unwrap_or_default();
                        c.extend(v[..ncols].iter().map(|x| opt_num(*x)));
                    }
                    c
                })
                .collect();
            Ok(table(&head, &body).into_bytes())
        }
    }
}

/// Renders the rigorous rows of `cor`.
pub fn rigorous_cor(rows: &[RigorousRow], format: Format) -> Result<Vec<u8>, CliError> {
    let physical = rows.iter().any(|r| r.ts_seconds.is_some());
    // the table has a bits column when the fallback ran (the f64-interval engine's 53
    // otherwise implied); the CSV always has it, so that runs written in batches share one
    // header (as `--digits`' CSV does)
    let bits = rows.iter().any(|r| r.fallback.is_some());
    let derived = rows.iter().any(|r| r.derived.is_some());
    let dcols = derived_columns(physical);
    let derived_of = |r: &RigorousRow| {
        r.derived
            .as_ref()
            .map(|d| d.values().map(|x| x.map(|p| p.0)))
            .unwrap_or_default()
    };
    match format {
        Format::Json => json(rows),
        Format::Csv => {
            let mut head = vec![
                "model", "v0_lo", "v0_hi", "proved", "ts_lo", "ts_hi", "width_ts", "e_lo", "e_hi",
                "width_e",
            ];
            if physical {
                head.extend(["ts_seconds_lo", "ts_seconds_hi"]);
            }
            head.push("bits");
            let dheads: Vec<String> = dcols
                .iter()
                .flat_map(|c| [format!("{c}_lo"), format!("{c}_hi")])
                .collect();
            if derived {
                head.extend(dheads.iter().map(String::as_str));
            }
            head.push("reason");
            let pair = |b: Option<[f64; 2]>| match b {
                Some([l, h]) => [outward(l, Rounding::Down), outward(h, Rounding::Up)],
                None => [String::new(), String::new()],
            };
            let up = |w: Option<f64>| w.map(|w| outward(w, Rounding::Up)).unwrap_or_default();
            let body = rows.iter().map(|r| {
                let mut c = vec![r.model.to_string()];
                c.extend(r.v0.map_or([String::new(), String::new()], |[l, h]| inner_pair(l, h)));
                c.push(r.proved.to_string());
                c.extend(pair(r.ts));
                c.push(up(r.width_ts));
                c.extend(pair(r.e));
                c.push(up(r.width_e));
                if physical {
                    c.extend(pair(r.ts_seconds.flatten()));
                }
                c.push(r.bits.to_string());
                if derived {
                    for x in &derived_of(r)[..dcols.len()] {
                        c.extend(pair(*x));
                    }
                }
                // (a derived output not computed says why after the case's own reason)
                let why = r.derived.as_ref().and_then(|d| d.reason.as_deref());
                c.push(match (r.reason.as_deref(), why) {
                    (Some(a), Some(b)) => format!("{a}; derived outputs: {b}"),
                    (None, Some(b)) => format!("derived outputs: {b}"),
                    (a, None) => a.unwrap_or_default().to_string(),
                });
                c
            });
            csv(&head, body)
        }
        Format::Table => {
            let mut head = vec!["model", "v0", "ts", "width_ts", "e", "width_e"];
            if physical {
                head.push("ts_seconds");
            }
            if bits {
                head.push("bits");
            }
            if derived {
                head.extend(dcols);
            }
            let body: Vec<Vec<String>> = rows
                .iter()
                .map(|r| {
                    let v0 = match r.v0 {
                        None => "-".to_string(),
                        Some([l, h]) if l == h => num(l),
                        Some([l, h]) => short_decimal_in(l, h).unwrap_or_else(|| {
                            let [a, b] = inner_pair(l, h);
                            format!("[{a}, {b}]")
                        }),
                    };
                    let mut c = vec![r.model.to_string(), v0];
                    match (r.ts, r.e) {
                        (Some(ts), Some(e)) if r.proved => {
                            let up = |w: Option<f64>| {
                                w.map(|w| outward(w, Rounding::Up)).unwrap_or_default()
                            };
                            c.push(interval_text(ts));
                            c.push(up(r.width_ts));
                            c.push(interval_text(e));
                            c.push(up(r.width_e));
                            if physical {
                                c.push(
                                    r.ts_seconds
                                        .flatten()
                                        .map(interval_text)
                                        .unwrap_or_default(),
                                );
                            }
                            if bits {
                                c.push(r.bits.to_string());
                            }
                            if let Some(why) = r.derived.as_ref().and_then(|d| d.reason.as_ref()) {
                                c.push(format!("derived outputs not proved: {why}"));
                            } else if derived {
                                for x in &derived_of(r)[..dcols.len()] {
                                    c.push(x.map(interval_text).unwrap_or_default());
                                }
                            }
                        }
                        // proved without separation: the reason is the result
                        _ if r.proved => c.push(r.reason.clone().unwrap_or_default()),
                        _ => {
                            let reason = r.reason.as_deref().unwrap_or("no reason given");
                            c.push(if reason.starts_with("not proved") {
                                reason.to_string()
                            } else {
                                format!("not proved: {reason}")
                            })
                        }
                    }
                    c
                })
                .collect();
            Ok(table(&head, &body).into_bytes())
        }
    }
}

/// Pretty JSON with a final newline.
pub fn json<T: Serialize + ?Sized>(rows: &T) -> Result<Vec<u8>, CliError> {
    let mut v = serde_json::to_vec_pretty(rows)
        .map_err(|e| CliError::Failed(format!("writing JSON: {e}")))?;
    v.push(b'\n');
    Ok(v)
}

/// CSV with a header.
pub fn csv<I, R>(head: &[&str], rows: I) -> Result<Vec<u8>, CliError>
where
    I: IntoIterator<Item = R>,
    R: IntoIterator,
    R::Item: AsRef<[u8]>,
{
    let err = |e: csv::Error| CliError::Failed(format!("writing CSV: {e}"));
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(head).map_err(err)?;
    for r in rows {
        w.write_record(r).map_err(err)?;
    }
    w.into_inner()
        .map_err(|e| CliError::Failed(format!("writing CSV: {e}")))
}

/// Aligned columns with a header. A row shorter than the header ends with a message cell that
/// spans the remaining columns (it does not widen them).
pub fn table(head: &[&str], rows: &[Vec<String>]) -> String {
    let len = |s: &str| s.chars().count();
    let mut w: Vec<usize> = head.iter().map(|h| len(h)).collect();
    for r in rows {
        let full = r.len() == head.len();
        for (i, c) in r.iter().enumerate() {
            if full || i + 1 < r.len() {
                w[i] = w[i].max(len(c));
            }
        }
    }
    let line = |cells: &mut dyn Iterator<Item = &str>| {
        let mut s = String::new();
        for (i, c) in cells.enumerate() {
            if i > 0 {
                s.push_str("  ");
            }
            s.push_str(c);
            s.extend(std::iter::repeat_n(' ', w[i].saturating_sub(len(c))));
        }
        s.truncate(s.trim_end().len());
        s.push('\n');
        s
    };
    let mut out = line(&mut head.iter().copied());
    for r in rows {
        out.push_str(&line(&mut r.iter().map(String::as_str)));
    }
    out
}

/// Writes `bytes` to stdout, or to `path` through a temporary file in the same directory that
/// is renamed into place (so a failed run never leaves a partial or stale-looking file). A
/// symbolic link is kept: the file it leads to is replaced. The temporary name is short, so
/// that any name the file system takes for `path` works.
pub fn emit(out: Option<&Path>, bytes: &[u8]) -> Result<(), CliError> {
    emit_as("--out", out, bytes)
}

/// The temporary file beside `target` that [`emit_as`] writes and renames into place.
pub fn temporary(target: &Path) -> std::path::PathBuf {
    target.with_file_name(format!(".bwcl-{}.tmp", std::process::id()))
}

/// [`emit`] of the file given by `option` (--out, --plot, --band), which its messages name.
pub fn emit_as(option: &str, out: Option<&Path>, bytes: &[u8]) -> Result<(), CliError> {
    let Some(path) = out else {
        let mut so = std::io::stdout().lock();
        return match so.write_all(bytes).and_then(|_| so.flush()) {
            Ok(()) => Ok(()),
            // `bwcl … | head`: the reader has what it wanted
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
            Err(e) => Err(CliError::Failed(format!("writing to stdout: {e}"))),
        };
    };
    let target = super::input::resolve_links(option, path)?;
    let tmp = temporary(&target);
    let io = |what: &str, e: std::io::Error| {
        let _ = std::fs::remove_file(&tmp);
        let shown = bwcl::fit::data::echo(&path.to_string_lossy());
        CliError::Input(format!("{option} '{shown}': {what}: {e}"))
    };
    std::fs::write(&tmp, bytes).map_err(|e| io("cannot write", e))?;
    // a replaced file keeps its permissions
    if let Ok(m) = std::fs::metadata(&target) {
        let _ = std::fs::set_permissions(&tmp, m.permissions());
    }
    std::fs::rename(&tmp, &target).map_err(|e| io("cannot replace", e))
}
