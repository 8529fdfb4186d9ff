//! `paper-repro`: regenerates the paper's sec:ID figures and tables (Fig. 3, Table 1, Fig. 4,
//! Table 2) as CSV, SVG and PNG in `paper_repro/out/`, fits synthetic CoR data with the
//! library's `bwcl fit` code, and writes `paper_repro/REPORT.md`.
//!
//! ```text
//! cargo run --release --bin paper-repro                  # float curves, loops, fit demo
//! cargo run --release --bin paper-repro -- --rigorous    # + proved bands, 30-digit table
//! cargo run --release --bin paper-repro -- --identifiability  # + minima, profiles, proved feasible sets
//! cargo run --release --bin paper-repro -- synth         # rewrite paper_repro/data/synthetic_dss.csv
//! cargo run --release --bin paper-repro -- laws          # redo only the damping formulas' section
//! ```

mod cor;
mod demo;
mod digits;
mod font;
mod ident;
mod laws;
mod loops;
mod plot;
mod report;

use bwcl::fit::{CorData, FitOptions};
use bwcl::models::{ModelKind, NdParams};
use clap::{Parser, Subcommand};
use std::path::PathBuf;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

#[derive(Parser, Debug)]
#[command(
    name = "paper-repro",
    about = "Regenerate the paper's sec:ID figures and tables"
)]
pub struct Args {
    #[command(subcommand)]
    pub command: Option<Cmd>,
    /// Directory for the CSVs and plots [default: paper_repro/out].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// The report [default: paper_repro/REPORT.md].
    #[arg(long, value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Plot the continuous proved band of e (interval Taylor engine, issue #13) over
    /// [0.05, 6] m/s.
    #[arg(long)]
    pub rigorous: bool,
    /// Largest thickness of the proved band (with --rigorous).
    #[arg(long, default_value_t = 1e-6)]
    pub band_thickness: f64,
    /// Identifiability of the synthetic DSS case (issue #31): the distinct minima, the profiles
    /// of J and the proved feasible sets in the (σ_b, κ) and (Γ_b, B_b) planes, from the CoRs
    /// alone and with contact durations (several minutes).
    #[arg(long)]
    pub identifiability: bool,
    /// Most seconds of each of the four pavings of --identifiability.
    #[arg(long, default_value_t = 300.0)]
    pub ident_seconds: f64,
    /// Coarse grids and a short fit (for tests).
    #[arg(long)]
    pub quick: bool,
    /// CoR data to fit [default: paper_repro/data/synthetic_dss.csv].
    #[arg(long, value_name = "FILE.csv")]
    pub data: Option<PathBuf>,
    /// Model fitted to --data.
    #[arg(long, default_value = "shc", value_parser = parse_kind)]
    pub model: ModelKind,
    /// The base set that generated --data, if known [default with the synthetic data: SHC DSS].
    #[arg(long, value_name = "B,Γ,κ,σ_b,n,p", allow_hyphen_values = true)]
    pub truth: Option<String>,
    /// σ_noise of --data, if known [default with the synthetic data: 0.005].
    #[arg(long)]
    pub noise: Option<f64>,
    /// Fit: random starts.
    #[arg(long, default_value_t = 8)]
    pub starts: usize,
    /// Fit: seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Fit: Nelder–Mead iterations per run.
    #[arg(long, default_value_t = 300)]
    pub max_iter: u64,
}

#[derive(Subcommand, Debug)]
pub enum Cmd {
    /// Redo only the section on the Hunt–Crossley damping formulas (issue #33) of an existing
    /// report, and its CSV and plot (seconds).
    Laws,
    /// Write synthetic CoR data: a base set's e at evenly spaced speeds plus seeded Gaussian
    /// noise (the defaults make paper_repro/data/synthetic_dss.csv).
    Synth {
        #[arg(long, default_value = "shc", value_parser = parse_kind)]
        model: ModelKind,
        #[arg(long, default_value = DSS, allow_hyphen_values = true)]
        base: String,
        #[arg(long, default_value_t = 20)]
        points: usize,
        #[arg(long, default_value_t = 0.1)]
        vmin: f64,
        #[arg(long, default_value_t = 5.0)]
        vmax: f64,
        #[arg(long, default_value_t = 0.005)]
        sigma: f64,
        #[arg(long, default_value_t = 2024)]
        seed: u64,
        /// [default: paper_repro/data/synthetic_dss.csv]
        #[arg(long, value_name = "FILE.csv")]
        out: Option<PathBuf>,
    },
}

pub const DSS: &str = "1.43,-1.42,0.632,0.00715,1.31,1.27";

fn parse_kind(s: &str) -> Result<ModelKind, String> {
    match s {
        "shc" => Ok(ModelKind::Shc),
        "maxwell" => Ok(ModelKind::Maxwell),
        _ => Err(format!("'{s}' is not a model (shc or maxwell)")),
    }
}

fn synthetic_path() -> PathBuf {
    PathBuf::from(ROOT).join("paper_repro/data/synthetic_dss.csv")
}

fn main() {
    let args = Args::parse();
    if let Err(e) = run(args) {
        eprintln!("paper-repro: error: {e}");
        std::process::exit(1);
    }
}

fn run(args: Args) -> Result<(), String> {
    if let Some(Cmd::Synth {
        model,
        base,
        points,
        vmin,
        vmax,
        sigma,
        seed,
        out,
    }) = &args.command
    {
        let s = demo::Synth {
            kind: *model,
            base: base.clone(),
            points: *points,
            vmin: *vmin,
            vmax: *vmax,
            sigma: *sigma,
            seed: *seed,
        };
        let data = demo::synthesize(&s)?;
        let path = out.clone().unwrap_or_else(synthetic_path);
        let header = format!(
            "# synthetic CoR data: model {}, P* = {}, {} speeds in [{}, {}] m/s, Gaussian noise \
             sigma = {}, seed {} (ChaCha8, Box-Muller), e rounded to 6 decimals\n\
             # generated by: cargo run --release --bin paper-repro -- synth --model {} --base={} \
             --points {} --vmin {} --vmax {} --sigma {} --seed {}\n",
            model.name(),
            base,
            points,
            vmin,
            vmax,
            sigma,
            seed,
            model.name(),
            base,
            points,
            vmin,
            vmax,
            sigma,
            seed
        );
        std::fs::write(&path, header + &data.to_csv())
            .map_err(|e| format!("writing '{}': {e}", path.display()))?;
        println!("wrote {} ({} rows)", path.display(), data.len());
        return Ok(());
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(ROOT).join("paper_repro/out"));
    let report_path = args
        .report
        .clone()
        .unwrap_or_else(|| PathBuf::from(ROOT).join("paper_repro/REPORT.md"));
    std::fs::create_dir_all(&out).map_err(|e| format!("creating '{}': {e}", out.display()))?;
    let font = font::init_font()?;
    let t_all = std::time::Instant::now();
    if let Some(Cmd::Laws) = &args.command {
        eprintln!("the Hunt–Crossley damping formulas, proved…");
        let l = laws::run(args.quick)?;
        let files = laws::write(&out, &l)?;
        laws::replace_section(&report_path, &l)?;
        eprintln!(
            "wrote {} files into {} and the section of {} ({:.1} s)",
            files.len(),
            out.display(),
            report_path.display(),
            l.seconds
        );
        return Ok(());
    }

    // Fig. 3
    let float_points = if args.quick { 12 } else { 120 };
    eprintln!("Fig. 3: CoR of the Table 1 sets at {float_points} speeds (f64)…");
    let t = std::time::Instant::now();
    let v0 = cor::grid(float_points);
    let curves: Vec<_> = cor::TABLE1
        .iter()
        .map(|s| cor::float_curve(s, &v0))
        .collect();
    let float_seconds = t.elapsed().as_secs_f64();
    // the continuous proved band of e over [0.05, 6] m/s (issue #13), drawn at the ends and
    // centres of its pieces
    let mut band_stats: Vec<(usize, f64, f64, f64)> = Vec::new();
    let proved = if args.rigorous {
        let thickness = if args.quick {
            1e-3
        } else {
            args.band_thickness
        };
        eprintln!("Fig. 3: the proved band of e over [0.05, 6] m/s, thickness ≤ {thickness:e}…");
        let t = std::time::Instant::now();
        let mut p = Vec::new();
        for s in cor::TABLE1.iter() {
            let t1 = std::time::Instant::now();
            match cor::band_curve(s, 0.05, 6.0, thickness) {
                Ok((pts, pieces, thick, slope)) => {
                    band_stats.push((pieces, thick, t1.elapsed().as_secs_f64(), slope));
                    p.push(pts);
                }
                Err(why) => {
                    band_stats.push((0, f64::NAN, t1.elapsed().as_secs_f64(), f64::NAN));
                    p.push(vec![cor::Proved {
                        v0: 0.05,
                        e: Err(why),
                        seconds: 0.0,
                    }]);
                }
            }
        }
        Some((p, t.elapsed().as_secs_f64()))
    } else {
        None
    };
    let mut files = report::write_cor(&out, &v0, &curves, proved.as_ref().map(|p| &p.0))?;
    // the 30-digit reference table (issue #15): into out/ and, with the default out/, the copy
    // in paper_repro/data/ that tests/precision.rs checks the f64-interval engine against
    let reference = if args.rigorous && !args.quick {
        eprintln!(
            "Reference table: the 28 cases proved to {} digits…",
            digits::DIGITS
        );
        let rows = digits::table();
        let text = digits::csv(&rows);
        let mut paths = vec![out.join("reference_30_digits.csv")];
        if args.out.is_none() {
            paths.push(PathBuf::from(ROOT).join(digits::DATA));
        }
        for p in &paths {
            std::fs::write(p, &text).map_err(|e| format!("writing '{}': {e}", p.display()))?;
        }
        files.push(paths[0].display().to_string());
        Some(rows)
    } else {
        None
    };

    // Fig. 4
    eprintln!("Fig. 4: baseball hysteresis loops…");
    let samples = if args.quick { 200 } else { 1000 };
    let loops: Vec<loops::Loop> = loops::SPEEDS
        .iter()
        .map(|&v| loops::simulate(v, samples))
        .collect::<Result<_, _>>()?;
    files.extend(report::write_loops(&out, &loops)?);

    // fit demo
    let (data_path, synthetic) = match &args.data {
        Some(p) => (p.clone(), false),
        None => (synthetic_path(), true),
    };
    let data = CorData::read(&data_path).map_err(|e| e.to_string())?;
    let truth = match (&args.truth, synthetic) {
        (Some(t), _) => Some(t.clone()),
        (None, true) => Some(DSS.to_string()),
        (None, false) => None,
    }
    .map(|t| NdParams::<f64>::parse(args.model, &t).map_err(|e| format!("--truth: {e}")))
    .transpose()?;
    let sigma = args.noise.or(if synthetic { Some(0.005) } else { None });
    let opts = FitOptions {
        starts: if args.quick { 2 } else { args.starts },
        seed: args.seed,
        max_iter: if args.quick { 40 } else { args.max_iter },
        ..FitOptions::default()
    };
    eprintln!(
        "fit: {} on '{}' ({} starts × ≤ {} iterations, restarted once)…",
        args.model.name(),
        data_path.display(),
        opts.starts,
        opts.max_iter
    );
    let d = demo::run(args.model, data, &opts, truth, sigma)?;
    files.extend(report::write_fit(&out, args.model, &d)?);

    // identifiability (issue #31)
    let ident = if args.identifiability {
        if !(args.ident_seconds.is_finite() && args.ident_seconds > 0.0) {
            return Err(format!(
                "--ident-seconds {} must be > 0",
                args.ident_seconds
            ));
        }
        let seconds = if args.quick {
            args.ident_seconds.min(5.0)
        } else {
            args.ident_seconds
        };
        let id = ident::run(args.quick, seconds)?;
        files.extend(ident::write(&out, &id)?);
        Some(id)
    } else {
        None
    };

    // the classical damping formulas (issue #33)
    eprintln!("the Hunt–Crossley damping formulas, proved…");
    let laws = laws::run(args.quick)?;
    files.extend(laws::write(&out, &laws)?);

    let ctx = report::Context {
        args: &args,
        font,
        float_seconds,
        float_points,
        rig: proved.as_ref(),
        band: &band_stats,
        reference: reference.as_deref(),
        loops: &loops,
        curves: &curves,
        v0: &v0,
        demo: &d,
        ident: ident.as_ref(),
        laws: &laws,
        data_path: &data_path,
        fit_opts: &opts,
        files: &files,
        out: &out,
        total_seconds: t_all.elapsed().as_secs_f64(),
    };
    let text = report::render(&ctx);
    std::fs::write(&report_path, text)
        .map_err(|e| format!("writing '{}': {e}", report_path.display()))?;
    eprintln!(
        "wrote {} files into {} and {}",
        files.len(),
        out.display(),
        report_path.display()
    );
    Ok(())
}
