//! Results generator for issue #6: writes `benches/RESULTS.md` (and the work–precision plots
//! `benches/work_precision_*.{svg,png}`) from one in-process run.
//!
//! ```text
//! CARGO_TARGET_DIR=/work/target-bench cargo build --release --bin bwcl
//! CARGO_TARGET_DIR=/work/target-bench cargo run --release --features bench --example results
//! ```
//!
//! `--quick` cuts repetitions (for checking the generator, not for quoting). `--no-scipy`
//! skips `benches/scipy_side_by_side.py`. Every timing is a median over repetitions that are
//! interleaved between the things compared (float/rigorous, bwcl/peers), so a load change on
//! the shared machine hits both sides of a ratio alike.

use std::cell::RefCell;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use bwcl::arith::Real;
use bwcl::engines::taylor::TaylorOptions;
use bwcl::models::scaling::nd_from_base;
use bwcl::models::{CollisionModel, Maxwell, ModelKind, NdParams, Shc};
use bwcl::observables::rigorous::rigorous_impact;
use bwcl::observables::{FloatOptions, impact};
use inari::Interval;
use rayon::prelude::*;

#[path = "../../paper_repro/font.rs"]
mod font;

const CASES: [(&str, ModelKind, &str); 4] = bwcl::models::params::TABLE1;
/// The speeds of issue #3's acceptance set (section 1); SciPy's script runs 0.1, 1 and 5 of them.
const SPEEDS: [f64; 7] = [0.1, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0];
const RTOL: f64 = 1e-10;
const ATOL: f64 = 1e-12;
const MAX_STEP: f64 = 1e-2;
const HORIZON: f64 = 100.0;

// ---------------------------------------------------------------- small utilities

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let n = s.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    }
}

/// A rayon pool of one thread: the rigorous engine's step halves then run one after the other.
fn one_thread() -> &'static rayon::ThreadPool {
    static POOL: std::sync::OnceLock<rayon::ThreadPool> = std::sync::OnceLock::new();
    POOL.get_or_init(|| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a one-thread pool")
    })
}

/// Seconds per call of `f`, timed over a batch of `n` calls.
fn per_call(n: usize, mut f: impl FnMut()) -> f64 {
    let t0 = Instant::now();
    for _ in 0..n {
        f();
    }
    t0.elapsed().as_secs_f64() / n as f64
}

/// Lets rayon's workers go idle before a single-thread timing: after a parallel call they spin
/// for a while, and on this 2-CPU machine a spinning worker slows the timed thread (measured:
/// f64 CoRs 1.4× slower right after a two-thread rigorous run).
fn settle() {
    std::thread::sleep(Duration::from_millis(30));
}

/// Batch size so that one batch takes about `target` seconds.
fn batch_for(single: f64, target: f64) -> usize {
    ((target / single.max(1e-9)).ceil() as usize).clamp(1, 100_000)
}

fn loadavg() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".into())
}

fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "?".into())
}

fn cmd_out(cmd: &str, args: &[&str]) -> String {
    std::process::Command::new(cmd)
        .args(args)
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "?".into())
}

fn fmt_t(s: f64) -> String {
    if !s.is_finite() {
        "-".into()
    } else if s < 1e-3 {
        format!("{:.1} µs", s * 1e6)
    } else if s < 1.0 {
        format!("{:.2} ms", s * 1e3)
    } else {
        format!("{:.2} s", s)
    }
}

fn nd_f64(kind: ModelKind, base: &str, v0: f64) -> NdParams<f64> {
    let b = NdParams::<f64>::parse(kind, base).expect("base set");
    nd_from_base(kind, &b, &v0).expect("P(P*, v0)")
}

fn nd_iv(kind: ModelKind, base: &str, v0: Interval) -> NdParams<Interval> {
    let b = NdParams::<Interval>::parse(kind, base).expect("base set");
    nd_from_base(kind, &b, &v0).expect("P(P*, v0)")
}

fn point(v: f64) -> Interval {
    <Interval as Real>::parse_decimal(&format!("{v}")).expect("v0")
}

/// g = max(F, −V): T_s = inf{T ≥ 0 : F ≤ 0 ∧ V ≥ 0} is the first T > 0 with g ≤ 0.
fn gsep<M: CollisionModel<f64, N>, const N: usize>(m: &M, s: &[f64; N]) -> f64 {
    m.force::<f64>(s).max(-m.velocity::<f64>(s))
}

// ---------------------------------------------------------------- peers

/// Result of a peer run: T_s, e, RHS evaluations.
#[derive(Clone, Copy, Debug)]
struct PeerOut {
    ts: f64,
    e: f64,
    nfev: usize,
}

mod os_peer {
    //! `ode_solvers` 0.6 `Dop853`: no event location. Stop in `solout` at the first accepted
    //! step with g ≤ 0, then locate T_s in that step by Illinois (regula falsi) on g, each
    //! g(T) from one fresh `Dop853` step from the step's start (a full-order value, not an
    //! interpolant), counting those RHS evaluations too.
    use super::*;
    use ode_solvers::dop853::Dop853;
    use ode_solvers::{OutputType, SVector, System};

    pub struct Track<const N: usize> {
        pub prev: (f64, [f64; N]),
        pub cur: (f64, [f64; N]),
        pub hit: bool,
    }

    pub struct Sys<'a, M, const N: usize> {
        pub m: &'a M,
        pub track: Option<&'a RefCell<Track<N>>>,
    }

    fn arr<const N: usize>(y: &SVector<f64, N>) -> [f64; N] {
        std::array::from_fn(|i| y[i])
    }

    impl<M: CollisionModel<f64, N>, const N: usize> System<f64, SVector<f64, N>> for Sys<'_, M, N> {
        fn system(&self, _x: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
            let f = self.m.field::<f64>(&arr(y));
            for i in 0..N {
                dy[i] = f[i];
            }
        }
        fn solout(&mut self, x: f64, y: &SVector<f64, N>, _dy: &SVector<f64, N>) -> bool {
            if let Some(t) = self.track {
                let mut t = t.borrow_mut();
                let s = arr(y);
                t.prev = t.cur;
                t.cur = (x, s);
                if x > 0.0 && gsep(self.m, &s) <= 0.0 {
                    t.hit = true;
                    return true;
                }
            }
            false
        }
    }

    fn solver<'a, M: CollisionModel<f64, N>, const N: usize>(
        sys: Sys<'a, M, N>,
        x0: f64,
        x1: f64,
        y: [f64; N],
        h0: f64,
    ) -> Dop853<f64, SVector<f64, N>, Sys<'a, M, N>> {
        Dop853::from_param(
            sys,
            x0,
            x1,
            0.0,
            SVector::<f64, N>::from(y),
            RTOL,
            ATOL,
            0.9,
            0.0,
            0.333,
            6.0,
            MAX_STEP,
            h0,
            100_000,
            1000,
            OutputType::Sparse,
        )
    }

    pub fn cor<M: CollisionModel<f64, N>, const N: usize>(m: &M) -> Option<PeerOut> {
        let y0 = m.initial_state();
        let cell = RefCell::new(Track {
            prev: (0.0, y0),
            cur: (0.0, y0),
            hit: false,
        });
        let mut s = solver(
            Sys {
                m,
                track: Some(&cell),
            },
            0.0,
            HORIZON,
            y0,
            0.0,
        );
        let st = s.integrate().ok()?;
        let mut nfev = st.num_eval as usize;
        let tr = cell.borrow();
        if !tr.hit {
            return None;
        }
        let (a0, ya) = tr.prev;
        let (b0, yb0) = tr.cur;
        let mut eval = |t: f64| -> [f64; N] {
            let mut s = solver(Sys { m, track: None }, a0, t, ya, t - a0);
            let st = s.integrate().expect("refinement step");
            nfev += st.num_eval as usize;
            arr(s.y_out().last().unwrap())
        };
        let (mut a, mut b) = (a0, b0);
        let (mut fa, mut fb) = (gsep(m, &ya), gsep(m, &yb0));
        let mut yb = yb0;
        let mut side = 0;
        for _ in 0..200 {
            if b - a <= 4.0 * f64::EPSILON * b.abs().max(1.0) {
                break;
            }
            let mut c = (a * fb - b * fa) / (fb - fa);
            if !(c > a && c < b) {
                c = 0.5 * (a + b);
            }
            let yc = eval(c);
            let fc = gsep(m, &yc);
            if fc <= 0.0 {
                b = c;
                fb = fc;
                yb = yc;
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
                if fc == 0.0 {
                    break;
                }
            } else {
                a = c;
                fa = fc;
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            }
        }
        Some(PeerOut {
            ts: b,
            e: m.velocity::<f64>(&yb),
            nfev,
        })
    }
}

mod de_peer {
    //! `differential-equations` 0.7 `ExplicitRungeKutta::dop853()` with its `Event` (Brent on
    //! the method's dense output, terminal, direction Negative) on g = max(F, −V).
    use super::*;
    use differential_equations::prelude::*;

    pub struct Sys<'a, M>(pub &'a M);

    impl<M: CollisionModel<f64, N>, const N: usize> ODE<f64, [f64; N]> for Sys<'_, M> {
        fn diff(&self, _t: f64, y: &[f64; N], dydt: &mut [f64; N]) {
            *dydt = self.0.field::<f64>(y);
        }
    }

    impl<M: CollisionModel<f64, N>, const N: usize> Event<f64, [f64; N]> for Sys<'_, M> {
        fn config(&self) -> EventConfig {
            EventConfig::new(CrossingDirection::Negative, Some(1))
        }
        fn event(&self, t: f64, y: &[f64; N]) -> f64 {
            if t == 0.0 { 1.0 } else { gsep(self.0, y) }
        }
    }

    pub fn cor<M: CollisionModel<f64, N>, const N: usize>(m: &M) -> Option<PeerOut> {
        let sys = Sys(m);
        let sol = IVP::ode(&sys, 0.0, HORIZON, m.initial_state())
            .event(&sys)
            .method(
                ExplicitRungeKutta::dop853()
                    .rtol(RTOL)
                    .atol(ATOL)
                    .h_max(MAX_STEP),
            )
            .solve()
            .ok()?;
        if !matches!(sol.status, Status::Interrupted) {
            return None;
        }
        let ts = *sol.t.last()?;
        let y = sol.y.last()?;
        Some(PeerOut {
            ts,
            e: m.velocity::<f64>(y),
            nfev: sol.evals.function,
        })
    }
}

// ---------------------------------------------------------------- sections

struct Ctx {
    quick: bool,
    md: String,
}

impl Ctx {
    fn line(&mut self, s: impl AsRef<str>) {
        println!("{}", s.as_ref());
        self.md.push_str(s.as_ref());
        self.md.push('\n');
    }
    fn reps(&self, full: usize) -> usize {
        if self.quick { full.min(3) } else { full }
    }
}

/// One Table 1 case at one speed: float and rigorous, interleaved.
struct Row1 {
    name: &'static str,
    v0: f64,
    t_f: f64,
    nfev: usize,
    e_f: f64,
    t_r: f64,
    /// The rigorous time with rayon's global pool (the step's two halves on two threads).
    t_r2: f64,
    e_r: Result<Interval, String>,
}

fn float_vs_rigorous<Mf, Mi, const N: usize>(
    ctx: &Ctx,
    mf: &Mf,
    mi: &Mi,
) -> (f64, usize, f64, f64, f64, Result<Interval, String>)
where
    Mf: CollisionModel<f64, N>,
    Mi: CollisionModel<Interval, N>,
{
    let fo = FloatOptions::default();
    let to = TaylorOptions::default();
    let r = impact(mf, &fo).expect("float CoR");
    let t0 = Instant::now();
    let enc = rigorous_impact(mi, &to);
    let t_r1 = t0.elapsed().as_secs_f64();
    let t_f1 = per_call(5, || {
        black_box(impact(black_box(mf), &fo).unwrap().e);
    });
    let nb_f = batch_for(t_f1, 0.02);
    let nb_r = batch_for(t_r1, 0.02);
    let reps = ctx.reps(11);
    let one = one_thread();
    let (mut tf, mut tr, mut tr2) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..reps {
        settle();
        tf.push(per_call(nb_f, || {
            black_box(impact(black_box(mf), &fo).unwrap().e);
        }));
        tr.push(one.install(|| {
            per_call(nb_r, || {
                let _ = black_box(rigorous_impact(black_box(mi), &to).map(|e| e.e));
            })
        }));
        tr2.push(per_call(nb_r, || {
            let _ = black_box(rigorous_impact(black_box(mi), &to).map(|e| e.e));
        }));
    }
    (
        median(&tf),
        r.stats.nfev,
        r.e,
        median(&tr),
        median(&tr2),
        enc.map(|e| e.e).map_err(|e| format!("{e:?}")),
    )
}

fn section1(ctx: &mut Ctx) -> Vec<Row1> {
    ctx.line("## 1. Interval vs float (Table 1 sets)");
    ctx.line("");
    let (order, tol) = (TaylorOptions::default().order, TaylorOptions::default().tol);
    ctx.line(format!(
        "f64: `impact` with `FloatOptions::default()` (DOP853 rtol {RTOL:e}, atol {ATOL:e}, \
         max_step {MAX_STEP:e}, event location). Rigorous: `rigorous_impact` with \
         `TaylorOptions::default()` (order {order}, tol {tol:e}), v0 a point interval. Times are \
         medians of {} interleaved repetitions, each a batch of ≈20 ms. f64 and \"rigorous\" \
         run on one thread (the rigorous engine in a one-thread rayon pool); \"rigorous, 2 \
         threads\" is the same call with the global pool, where each Taylor step's two \
         independent halves run as a `rayon::join` (identical enclosures; on this shared \
         machine the second core is not always free). The ratio is the one-thread one. \
         load at start: {}",
        ctx.reps(11),
        loadavg()
    ));
    ctx.line("");
    ctx.line("| case | v0 | f64 time | nfev | rigorous time | rigorous, 2 threads | e enclosure width | ratio rig/f64 | f64 e − mid(e) | f64 e inside |");
    ctx.line("|---|---:|---:|---:|---:|---:|---:|---:|---:|:-:|");
    let mut rows = Vec::new();
    for (name, kind, base) in CASES {
        for v0 in SPEEDS {
            let (t_f, nfev, e_f, t_r, t_r2, e_r) = match kind {
                ModelKind::Shc => float_vs_rigorous(
                    ctx,
                    &Shc::new(nd_f64(kind, base, v0)),
                    &Shc::new(nd_iv(kind, base, point(v0))),
                ),
                ModelKind::Maxwell => float_vs_rigorous(
                    ctx,
                    &Maxwell::new(nd_f64(kind, base, v0)),
                    &Maxwell::new(nd_iv(kind, base, point(v0))),
                ),
            };
            let (w, d, inside) = match &e_r {
                Ok(iv) => (
                    format!("{:.2e}", iv.wid()),
                    format!("{:+.2e}", e_f - iv.mid()),
                    if iv.contains(e_f) { "yes" } else { "no" }.to_string(),
                ),
                Err(err) => (
                    format!("failed: {}", &err[..err.len().min(60)]),
                    "-".into(),
                    "-".into(),
                ),
            };
            ctx.line(format!(
                "| {name} | {v0} | {} | {nfev} | {} | {} | {w} | {:.0}× | {d} | {inside} |",
                fmt_t(t_f),
                fmt_t(t_r),
                fmt_t(t_r2),
                t_r / t_f
            ));
            rows.push(Row1 {
                name,
                v0,
                t_f,
                nfev,
                e_f,
                t_r,
                t_r2,
                e_r,
            });
        }
    }
    ctx.line(format!("\nload at end: {}\n", loadavg()));
    rows
}

fn wp_case<Mf, Mi, const N: usize>(ctx: &mut Ctx, title: &str, stem: &str, mf: &Mf, mi: &Mi)
where
    Mf: CollisionModel<f64, N>,
    Mi: CollisionModel<Interval, N>,
{
    let orders = [12usize, 16, 20, 24];
    let tols = [1e-17, 1e-16, 1e-15, 1e-14, 1e-13];
    let reps = ctx.reps(5);
    ctx.line(format!("### {title}"));
    ctx.line("");
    ctx.line("| order | tol | time | e width | pieces |");
    ctx.line("|---:|---:|---:|---:|---:|");
    let mut series: Vec<(usize, Vec<(f64, f64)>)> = Vec::new();
    for &order in &orders {
        let mut pts = Vec::new();
        for &tol in &tols {
            let to = TaylorOptions {
                order,
                tol,
                ..TaylorOptions::default()
            };
            let r = rigorous_impact(mi, &to);
            let mut ts = Vec::new();
            for _ in 0..reps {
                // one thread, as the rigorous column of section 1
                ts.push(one_thread().install(|| {
                    let t0 = Instant::now();
                    let _ = black_box(rigorous_impact(black_box(mi), &to).map(|e| e.e));
                    t0.elapsed().as_secs_f64()
                }));
            }
            let t = median(&ts);
            match r {
                Ok(enc) => {
                    ctx.line(format!(
                        "| {order} | {tol:e} | {} | {:.2e} | {} |",
                        fmt_t(t),
                        enc.e.wid(),
                        enc.flow.len()
                    ));
                    if enc.e.wid() > 0.0 {
                        pts.push((t * 1e3, enc.e.wid()));
                    }
                }
                Err(e) => {
                    let s = format!("{e:?}");
                    ctx.line(format!(
                        "| {order} | {tol:e} | {} | failed: {} | - |",
                        fmt_t(t),
                        &s[..s.len().min(60)]
                    ));
                }
            }
        }
        series.push((order, pts));
    }
    // f64 reference: time and |e − mid| against the default enclosure.
    let fo = FloatOptions::default();
    let tf = median(
        &(0..ctx.reps(7))
            .map(|_| {
                per_call(20, || {
                    let _ = black_box(impact(mf, &fo).unwrap().e);
                })
            })
            .collect::<Vec<_>>(),
    );
    let ef = impact(mf, &fo).unwrap().e;
    let float_err = rigorous_impact(mi, &TaylorOptions::default())
        .ok()
        .map(|enc| (ef - enc.e.mid()).abs());
    ctx.line(format!(
        "\nf64 DOP853 for reference: {} per CoR, |e − mid(enclosure)| = {}\n",
        fmt_t(tf),
        float_err.map_or("-".into(), |d| format!("{d:.2e}"))
    ));
    match plot_wp(
        title,
        stem,
        &series,
        float_err.map(|d| (tf * 1e3, d.max(1e-17))),
    ) {
        Ok(files) => ctx.line(format!("Plot: {}\n", files.join(", "))),
        Err(e) => ctx.line(format!("Plot failed: {e}\n")),
    }
}

fn plot_wp(
    title: &str,
    stem: &str,
    series: &[(usize, Vec<(f64, f64)>)],
    float_pt: Option<(f64, f64)>,
) -> Result<Vec<String>, String> {
    use plotters::prelude::*;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches");
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.1.iter().copied())
        .chain(float_pt)
        .collect();
    if all.is_empty() {
        return Err("no points".into());
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in &all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let (x0, x1, y0, y1) = (x0 / 1.5, x1 * 1.5, y0 / 3.0, y1 * 3.0);
    fn draw<DB: DrawingBackend>(
        area: DrawingArea<DB, plotters::coord::Shift>,
        title: &str,
        r: (f64, f64, f64, f64),
        series: &[(usize, Vec<(f64, f64)>)],
        float_pt: Option<(f64, f64)>,
    ) -> Result<(), String>
    where
        DB::ErrorType: 'static,
    {
        let e = |x: DrawingAreaErrorKind<DB::ErrorType>| format!("{x:?}");
        area.fill(&WHITE).map_err(e)?;
        let mut ch = ChartBuilder::on(&area)
            .caption(title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d((r.0..r.1).log_scale(), (r.2..r.3).log_scale())
            .map_err(e)?;
        ch.configure_mesh()
            .x_desc("time per CoR [ms]")
            .y_desc("width of the e enclosure")
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .draw()
            .map_err(e)?;
        let pal = [BLUE, RED, GREEN, MAGENTA, CYAN];
        for (i, (order, pts)) in series.iter().enumerate() {
            let c = pal[i % pal.len()];
            ch.draw_series(LineSeries::new(pts.iter().copied(), c.stroke_width(2)))
                .map_err(e)?
                .label(format!("Taylor order {order} (tol 1e-17 … 1e-13)"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
            ch.draw_series(pts.iter().map(|&p| Circle::new(p, 4, c.filled())))
                .map_err(e)?;
        }
        if let Some(p) = float_pt {
            ch.draw_series(std::iter::once(TriangleMarker::new(p, 7, BLACK.filled())))
                .map_err(e)?
                .label("f64 DOP853: |e − mid| (an error, not a bound)")
                .legend(|(x, y)| TriangleMarker::new((x + 10, y), 6, BLACK.filled()));
        }
        ch.configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 13))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(e)?;
        area.present().map_err(e)?;
        Ok(())
    }
    let svg = dir.join(format!("{stem}.svg"));
    let png = dir.join(format!("{stem}.png"));
    let r = (x0, x1, y0, y1);
    draw(
        SVGBackend::new(&svg, (860, 600)).into_drawing_area(),
        title,
        r,
        series,
        float_pt,
    )?;
    draw(
        BitMapBackend::new(&png, (860, 600)).into_drawing_area(),
        title,
        r,
        series,
        float_pt,
    )?;
    Ok(vec![
        format!("`benches/{stem}.svg`"),
        format!("`benches/{stem}.png`"),
    ])
}

fn section1b(ctx: &mut Ctx) {
    ctx.line("## 1b. Work–precision of the rigorous engine");
    ctx.line("");
    ctx.line(format!(
        "e enclosure width against time over Taylor order × tol; time = median of {} runs, one thread. \
         load: {}",
        ctx.reps(5),
        loadavg()
    ));
    ctx.line("");
    let (k, b) = (ModelKind::Shc, CASES[0].2);
    wp_case(
        ctx,
        "SHC DSS, v0 = 1",
        "work_precision_shc_dss_v0_1",
        &Shc::new(nd_f64(k, b, 1.0)),
        &Shc::new(nd_iv(k, b, point(1.0))),
    );
    let (k, b) = (ModelKind::Maxwell, CASES[3].2);
    wp_case(
        ctx,
        "Maxwell DSA, v0 = 5",
        "work_precision_maxwell_dsa_v0_5",
        &Maxwell::new(nd_f64(k, b, 5.0)),
        &Maxwell::new(nd_iv(k, b, point(5.0))),
    );
}

fn peers_case<Mf, Mi, const N: usize>(ctx: &mut Ctx, title: &str, mf: &Mf, mi: &Mi)
where
    Mf: CollisionModel<f64, N>,
    Mi: CollisionModel<Interval, N>,
{
    let enc = rigorous_impact(mi, &TaylorOptions::default()).ok();
    let fo = FloatOptions::default();
    let b = impact(mf, &fo).unwrap();
    let bw = PeerOut {
        ts: b.ts.unwrap_or(f64::INFINITY),
        e: b.e,
        nfev: b.stats.nfev,
    };
    let os = os_peer::cor(mf);
    let de = de_peer::cor(mf);
    let single = |f: &dyn Fn()| per_call(3, f);
    let t1 = [
        single(&|| {
            let _ = black_box(impact(mf, &fo).unwrap().e);
        }),
        single(&|| {
            let _ = black_box(os_peer::cor(mf));
        }),
        single(&|| {
            let _ = black_box(de_peer::cor(mf));
        }),
    ];
    let nb: Vec<usize> = t1.iter().map(|&t| batch_for(t, 0.02)).collect();
    let mut ts = [Vec::new(), Vec::new(), Vec::new()];
    for _ in 0..ctx.reps(15) {
        ts[0].push(per_call(nb[0], || {
            let _ = black_box(impact(mf, &fo).unwrap().e);
        }));
        ts[1].push(per_call(nb[1], || {
            let _ = black_box(os_peer::cor(mf));
        }));
        ts[2].push(per_call(nb[2], || {
            let _ = black_box(de_peer::cor(mf));
        }));
    }
    let med: Vec<f64> = ts.iter().map(|v| median(v)).collect();
    let (order, tol) = (TaylorOptions::default().order, TaylorOptions::default().tol);
    ctx.line(format!("### {title}"));
    ctx.line("");
    match &enc {
        Some(e) => ctx.line(format!(
            "rigorous (order {order}, tol {tol:e}): T_s ∈ [{:.15}, {:.15}], e ∈ [{:.16}, {:.16}] \
             (width {:.1e})\n",
            e.ts.inf(),
            e.ts.sup(),
            e.e.inf(),
            e.e.sup(),
            e.e.wid()
        )),
        None => ctx.line("rigorous enclosure: failed\n"),
    }
    ctx.line("| solver | time (median) | vs bwcl | RHS evals | T_s | e | e − mid(e) | inside |");
    ctx.line("|---|---:|---:|---:|---:|---:|---:|:-:|");
    let names = [
        "bwcl `impact` (DOP853 + event)",
        "ode_solvers 0.6.2 `Dop853` (+ own T_s search)",
        "differential-equations 0.7.0 DOP853 + `Event`",
    ];
    for (i, (n, r)) in names.iter().zip([Some(bw), os, de]).enumerate() {
        match r {
            Some(r) => {
                let (d, ins) = match &enc {
                    Some(e) => (
                        format!("{:+.2e}", r.e - e.e.mid()),
                        if e.e.contains(r.e) { "yes" } else { "no" },
                    ),
                    None => ("-".into(), "-"),
                };
                ctx.line(format!(
                    "| {n} | {} | {:.2}× | {} | {:.15} | {:.16} | {d} | {ins} |",
                    fmt_t(med[i]),
                    med[i] / med[0],
                    r.nfev,
                    r.ts,
                    r.e
                ));
            }
            None => ctx.line(format!(
                "| {n} | {} | - | - | failed | - | - | - |",
                fmt_t(med[i])
            )),
        }
    }
    ctx.line("");
}

fn section2(ctx: &mut Ctx) {
    ctx.line("## 2. DOP853 against Rust peers");
    ctx.line("");
    ctx.line(format!(
        "Same RHS (`model.field(&y)`), rtol {RTOL:e}, atol {ATOL:e}, max_step {MAX_STEP:e}, \
         horizon {HORIZON}. Medians of {} interleaved repetitions (batches of ≈20 ms). \
         ode_solvers has no event location: the run stops in `solout` at the first accepted \
         step with g = max(F, −V) ≤ 0 and T_s is then located inside that step by Illinois \
         regula falsi on g, each g(T) from one fresh full-order `Dop853` step from the step's \
         start (RHS evaluations of those steps included). differential-equations: \
         `IVP::ode(..).event(..)` with g, direction Negative, terminal (Brent on its dense \
         output, its default tolerances 1e-12 rel / 1e-14 abs in t), default solout (stores \
         every step). load: {}",
        ctx.reps(15),
        loadavg()
    ));
    ctx.line("");
    let (k, b) = (ModelKind::Shc, CASES[0].2);
    peers_case(
        ctx,
        "NDBWSHCCM, SHC DSS, v0 = 1",
        &Shc::new(nd_f64(k, b, 1.0)),
        &Shc::new(nd_iv(k, b, point(1.0))),
    );
    let (k, b) = (ModelKind::Maxwell, CASES[3].2);
    peers_case(
        ctx,
        "NDBWMCM, Maxwell DSA, v0 = 5",
        &Maxwell::new(nd_f64(k, b, 5.0)),
        &Maxwell::new(nd_iv(k, b, point(5.0))),
    );
}

fn section3(ctx: &mut Ctx, rows: &[Row1]) {
    ctx.line("## 3. SciPy side by side");
    ctx.line("");
    let exe = std::env::current_exe().unwrap();
    let bin: PathBuf = exe
        .parent()
        .and_then(|p| p.parent())
        .map(|p| p.join("bwcl"))
        .unwrap();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/scipy_side_by_side.py");
    let json = std::env::temp_dir().join(format!("bwcl_scipy_{}.json", std::process::id()));
    let mut cmd = std::process::Command::new("python3");
    cmd.arg(&script).arg("--json").arg(&json);
    if ctx.quick {
        cmd.args(["--repeat", "20"]);
    }
    if bin.is_file() {
        cmd.env("BWCL_BIN", &bin);
    } else {
        cmd.arg("--no-bwcl");
    }
    ctx.line(format!("load before: {}", loadavg()));
    let out = cmd.output();
    let out = match out {
        Ok(o) => o,
        Err(e) => {
            ctx.line(format!("could not run python3: {e}\n"));
            return;
        }
    };
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    ctx.line(format!(
        "\nOutput of `python3 benches/scipy_side_by_side.py` (BWCL_BIN = {}):\n",
        if bin.is_file() {
            bin.display().to_string()
        } else {
            "not built".into()
        }
    ));
    ctx.line("```text");
    ctx.line(stdout.trim_end());
    ctx.line("```");
    ctx.line(format!("load after: {}\n", loadavg()));
    let Ok(text) = std::fs::read_to_string(&json) else {
        ctx.line("(no JSON from the script)\n");
        return;
    };
    let _ = std::fs::remove_file(&json);
    let Ok(v) = serde_json::from_str::<serde_json::Value>(&text) else {
        ctx.line("(unparsable JSON from the script)\n");
        return;
    };
    ctx.line(
        "Columns: the script times each case in 7 rounds (after a warm-up round), each one \
         `solve_ivp(method=\"DOP853\", events=g)` call (Python RHS, in a running interpreter) \
         right beside one `bwcl cor --timing` call with REPEAT copies of v0 \
         (RAYON_NUM_THREADS=1). t_bwcl CLI is the computation's time as `--timing` reports \
         it / REPEAT (like t_scipy: no start-up, parsing or output); t_wall is the call's wall \
         time / REPEAT (process start-up, argument parsing and JSON output included, \
         amortized). Times are the medians over the rounds; each ratio is the median of the 7 \
         per-round ratios, so that a slow spell of the machine slows both sides of the ratios \
         it enters. t_bwcl in-process = median of 7 batches (≈20 ms each) of one `impact` \
         call, single thread, re-timed here right after the script (not interleaved with it; \
         compare section 1 for its spread).",
    );
    ctx.line("");
    ctx.line("| case | v0 | t_scipy | t_bwcl in-process | ratio (in-process) | t_bwcl CLI | ratio (CLI, interleaved) | t_wall | ratio (wall) | |e_scipy − e_bwcl| |");
    ctx.line("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut ratios = Vec::new();
    let (mut cli, mut rounds, mut wall) = (Vec::new(), Vec::new(), Vec::new());
    for r in v.as_array().into_iter().flatten() {
        let case = r["case"].as_str().unwrap_or("?");
        let v0 = r["v0"].as_f64().unwrap_or(f64::NAN);
        let ts = r["t_scipy"].as_f64().unwrap_or(f64::NAN);
        let tc = r["t_bwcl"].as_f64().unwrap_or(f64::NAN);
        let es = r["e_scipy"].as_f64();
        let row = rows.iter().find(|x| x.name == case && x.v0 == v0);
        // Re-timed right after the script (closer in time to its SciPy runs than section 1).
        let ti = CASES
            .iter()
            .find(|c| c.0 == case)
            .map_or(f64::NAN, |&(_, kind, base)| retime(ctx, kind, base, v0));
        let de = match (es, row) {
            (Some(a), Some(x)) => format!("{:.1e}", (a - x.e_f).abs()),
            _ => "-".into(),
        };
        ratios.push(ts / ti);
        let rc = r["ratio"].as_f64().unwrap_or(f64::NAN);
        let tw = r["t_wall"].as_f64().unwrap_or(f64::NAN);
        let rw = r["ratio_wall"].as_f64().unwrap_or(f64::NAN);
        cli.push(rc);
        wall.push(rw);
        rounds.extend(
            r["ratios"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|x| x.as_f64()),
        );
        ctx.line(format!(
            "| {case} | {v0} | {} | {} | {:.0}× | {} | {:.0}× | {} | {:.0}× | {de} |",
            fmt_t(ts),
            fmt_t(ti),
            ts / ti,
            fmt_t(tc),
            rc,
            fmt_t(tw),
            rw
        ));
    }
    for (what, r) in [
        ("CLI, per case", &mut cli),
        ("CLI, every round", &mut rounds),
        ("CLI wall time, per case", &mut wall),
        ("in-process", &mut ratios),
    ] {
        r.retain(|x| x.is_finite());
        r.sort_by(|a, b| a.partial_cmp(b).unwrap());
        if !r.is_empty() {
            ctx.line(format!(
                "\nSciPy / bwcl ({what}): min {:.0}×, median {:.0}×, max {:.0}×; {} of {} at 300× or more",
                r[0],
                median(r),
                r[r.len() - 1],
                r.iter().filter(|&&x| x >= 300.0).count(),
                r.len()
            ));
        }
    }
    ctx.line("");
}

fn retime(ctx: &Ctx, kind: ModelKind, base: &str, v0: f64) -> f64 {
    fn go<M: CollisionModel<f64, N>, const N: usize>(ctx: &Ctx, m: &M) -> f64 {
        let fo = FloatOptions::default();
        let t1 = per_call(5, || {
            let _ = black_box(impact(black_box(m), &fo).unwrap().e);
        });
        let nb = batch_for(t1, 0.02);
        let ts: Vec<f64> = (0..ctx.reps(7))
            .map(|_| {
                per_call(nb, || {
                    let _ = black_box(impact(black_box(m), &fo).unwrap().e);
                })
            })
            .collect();
        median(&ts)
    }
    match kind {
        ModelKind::Shc => go(ctx, &Shc::new(nd_f64(kind, base, v0))),
        ModelKind::Maxwell => go(ctx, &Maxwell::new(nd_f64(kind, base, v0))),
    }
}

fn section4(ctx: &mut Ctx) {
    ctx.line("## 4. Scaling");
    ctx.line("");
    let (kind, base) = (ModelKind::Shc, CASES[0].2);
    let bp = NdParams::<f64>::parse(kind, base).unwrap();
    let fo = FloatOptions::default();
    ctx.line(format!(
        "### f64 CoR against the number of impact speeds\n\nSHC DSS, v0 log-spaced on [0.1, 5]; \
         `speeds.par_iter().map(|v0| impact(&Shc::new(nd_from_base(..)), ..))` with rayon \
         ({} threads). Median of the repetitions shown. load: {}\n",
        rayon::current_num_threads(),
        loadavg()
    ));
    ctx.line("| speeds | reps | wall time | per CoR | CoR/s |");
    ctx.line("|---:|---:|---:|---:|---:|");
    for &n in &[1usize, 10, 100, 1000, 10_000, 100_000] {
        if ctx.quick && n > 10_000 {
            continue;
        }
        let speeds: Vec<f64> = (0..n)
            .map(|i| {
                let f = if n == 1 {
                    0.5
                } else {
                    i as f64 / (n - 1) as f64
                };
                0.1 * 50f64.powf(f)
            })
            .collect();
        let reps = match n {
            ..=1000 => ctx.reps(7),
            10_000 => ctx.reps(3),
            _ => 1,
        };
        let mut ts = Vec::new();
        for _ in 0..reps {
            let t0 = Instant::now();
            let s: f64 = speeds
                .par_iter()
                .map(|&v0| {
                    let m = Shc::new(nd_from_base(kind, &bp, &v0).unwrap());
                    impact(&m, &fo).map(|r| r.e).unwrap_or(f64::NAN)
                })
                .sum();
            black_box(s);
            ts.push(t0.elapsed().as_secs_f64());
        }
        let t = median(&ts);
        ctx.line(format!(
            "| {n} | {reps} | {} | {} | {:.0} |",
            fmt_t(t),
            fmt_t(t / n as f64),
            n as f64 / t
        ));
    }
    ctx.line("");
}

fn section4b(ctx: &mut Ctx) {
    let limit = if ctx.quick { 20.0 } else { 120.0 };
    ctx.line(format!(
        "### Rigorous CoR against the width of a v0 range around 1\n\nv0 = [1 − w/2, 1 + w/2] \
         (decimal endpoints, outward-rounded), `TaylorOptions::default()`, one run each \
         (abandoned after {limit} s). load: {}\n",
        loadavg()
    ));
    ctx.line("| case | w | max_width | time | e enclosure | e width | T_s width |");
    ctx.line("|---|---:|---:|---:|---|---:|---:|");
    for (name, kind, base) in [CASES[0], CASES[3]] {
        for w in [0.0, 1e-6, 1e-4, 1e-3, 1e-2] {
            let v0 = if w == 0.0 {
                point(1.0)
            } else {
                <Interval as Real>::parse_decimal(&format!("{}..{}", 1.0 - w / 2.0, 1.0 + w / 2.0))
                    .expect("range")
            };
            // The default first; on failure again with max_width = 1 (the default 1e-3 is the
            // engine's give-up width).
            for max_width in [TaylorOptions::default().max_width, 1.0] {
                let p = nd_iv(kind, base, v0);
                let (tx, rx) = mpsc::channel();
                std::thread::spawn(move || {
                    let to = TaylorOptions {
                        max_width,
                        ..TaylorOptions::default()
                    };
                    let t0 = Instant::now();
                    let r = match kind {
                        ModelKind::Shc => rigorous_impact(&Shc::new(p), &to).map(|e| (e.e, e.ts)),
                        ModelKind::Maxwell => {
                            rigorous_impact(&Maxwell::new(p), &to).map(|e| (e.e, e.ts))
                        }
                    };
                    let _ = tx.send((t0.elapsed().as_secs_f64(), r.map_err(|e| format!("{e:?}"))));
                });
                let ok = match rx.recv_timeout(Duration::from_secs_f64(limit)) {
                    Ok((t, Ok((e, ts)))) => {
                        ctx.line(format!(
                            "| {name} | {w:e} | {max_width:e} | {} | [{:.12}, {:.12}] | {:.2e} | {:.2e} |",
                            fmt_t(t),
                            e.inf(),
                            e.sup(),
                            e.wid(),
                            ts.wid()
                        ));
                        true
                    }
                    Ok((t, Err(e))) => {
                        ctx.line(format!(
                            "| {name} | {w:e} | {max_width:e} | {} | failed: {} | - | - |",
                            fmt_t(t),
                            &e[..e.len().min(110)]
                        ));
                        false
                    }
                    Err(_) => {
                        ctx.line(format!(
                            "| {name} | {w:e} | {max_width:e} | > {limit} s | abandoned | - | - |"
                        ));
                        // The thread keeps running: nothing after this is timed.
                        return;
                    }
                };
                if ok {
                    break;
                }
            }
        }
    }
    ctx.line("");
}

/// Where the part of benches/RESULTS.md that other generators and sessions wrote begins.
const KEPT_FROM: &str = "<!-- sets:begin -->";

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let quick = args.iter().any(|a| a == "--quick");
    let no_scipy = args.iter().any(|a| a == "--no-scipy");
    let mut ctx = Ctx {
        quick,
        md: String::new(),
    };
    if let Err(e) = font::init_font() {
        eprintln!("font: {e}");
    }
    let t_all = Instant::now();
    ctx.line("# bwcl benchmark results (issue #6)");
    ctx.line("");
    ctx.line(
        "Generated by `cargo build --release --bin bwcl && cargo run --release --features bench --example \
         results` (source `benches/generator/results.rs`; SciPy from `pip install scipy`); do \
         not edit by hand.",
    );
    ctx.line("");
    ctx.line(format!(
        "- date: {}",
        cmd_out("date", &["-u", "+%Y-%m-%d %H:%M:%S UTC"])
    ));
    ctx.line(format!(
        "- machine: {} logical CPUs (nproc), {}; shared, so timings are noisy — ratios are \
         from interleaved runs in one process",
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        cpu_model()
    ));
    ctx.line(format!(
        "- load average (1/5/15 min) at start: {}",
        loadavg()
    ));
    ctx.line(format!(
        "- build: release, target-cpu=haswell (.cargo/config.toml); rustc: {}",
        cmd_out("rustc", &["--version"])
    ));
    if quick {
        ctx.line("- **--quick run: reduced repetitions, not for quoting**");
    }
    ctx.line("");
    let rows = section1(&mut ctx);
    section1b(&mut ctx);
    section2(&mut ctx);
    if !no_scipy {
        section3(&mut ctx, &rows);
    }
    section4(&mut ctx);
    section4b(&mut ctx);
    summary(&mut ctx, &rows);
    ctx.line(format!(
        "\nTotal generator time {:.0} s; load average at end: {}",
        t_all.elapsed().as_secs_f64(),
        loadavg()
    ));
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/RESULTS.md");
    // the sections after these (the sets generator's, between its markers, and the later
    // issues' measurements) are not this generator's: they are kept as they are
    let kept = std::fs::read_to_string(&path)
        .ok()
        .and_then(|old| old.find(KEPT_FROM).map(|i| old[i..].to_string()));
    let md = match kept {
        Some(rest) => format!("{}\n{rest}", ctx.md),
        None => ctx.md.clone(),
    };
    std::fs::write(&path, md).expect("write RESULTS.md");
    eprintln!("wrote {}", path.display());
    std::process::exit(0);
}

fn summary(ctx: &mut Ctx, rows: &[Row1]) {
    ctx.line("## Summary: rigorous / f64 (section 1)");
    ctx.line("");
    let ok: Vec<f64> = rows
        .iter()
        .filter(|r| r.e_r.as_ref().is_ok_and(|e| e.wid() <= 1e-10))
        .map(|r| r.t_r / r.t_f)
        .collect();
    let nfail = rows.iter().filter(|r| r.e_r.is_err()).count();
    if !ok.is_empty() {
        let mut s = ok.clone();
        s.sort_by(|a, b| a.partial_cmp(b).unwrap());
        ctx.line(format!(
            "Cases with e width ≤ 1e-10: {} of {}; rigorous/f64 time ratio min {:.0}×, median \
             {:.0}×, max {:.0}× (target ≤ 200×: met in {} of {}). Rigorous failures: {nfail}. \
             Mean f64 nfev {:.0}.",
            ok.len(),
            rows.len(),
            s[0],
            median(&s),
            s[s.len() - 1],
            s.iter().filter(|&&x| x <= 200.0).count(),
            s.len(),
            rows.iter().map(|r| r.nfev as f64).sum::<f64>() / rows.len() as f64
        ));
    }
    let t1: Vec<f64> = rows.iter().map(|r| r.t_r).collect();
    let t2: Vec<f64> = rows.iter().map(|r| r.t_r2).collect();
    let widest = rows
        .iter()
        .filter_map(|r| r.e_r.as_ref().ok().map(|e| e.wid()))
        .fold(0.0, f64::max);
    ctx.line("");
    ctx.line(format!(
        "Rigorous CoR over the {} cases: median {} on one thread, {} with the step halves on two \
         threads (target ≤ 20 ms); widest e enclosure {widest:.2e}.",
        rows.len(),
        fmt_t(median(&t1)),
        fmt_t(median(&t2)),
    ));
}
