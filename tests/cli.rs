//! The `bwcl` program end to end: output formats, values against the library and the SciPy
//! reference, one-line errors with exit code 2, atomic --out, and the rigorous wiring.

use bwcl::models::scaling::PhysicalParams;
use bwcl::models::{ModelKind, Shc};
use bwcl::observables::{FloatOptions, impact};
use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

const DSS: &str = "1.43,-1.42,0.632,0.00715,1.31,1.27";
const BASEBALL: &str =
    "m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925";

fn bwcl(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bwcl"))
        .args(args)
        .output()
        .expect("bwcl runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

/// Runs and expects success with JSON on stdout.
fn json(args: &[&str]) -> Vec<Value> {
    let o = bwcl(args);
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
    rows(&o)
}

/// The JSON array on stdout.
fn rows(o: &Output) -> Vec<Value> {
    match serde_json::from_str(&stdout(o)).unwrap() {
        Value::Array(a) => a,
        v => panic!("not an array: {v}"),
    }
}

/// A file name in cargo's scratch directory for integration tests.
fn scratch(name: &str) -> PathBuf {
    let p = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("bwcl-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_file(&p);
    p
}

/// Parses a CSV with a header into (header, rows of numbers).
fn numeric_csv(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let head = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    (head, rows)
}

/// Bad input: exit 2, nothing on stdout, exactly one stderr line `bwcl: error: …`, no panic.
fn assert_bad_input(args: &[&str]) -> String {
    let o = bwcl(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(o.stdout.is_empty(), "{args:?}: stdout {}", stdout(&o));
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{args:?}: {err:?}");
    assert!(
        lines[0].starts_with("bwcl: error: ") && lines[0].len() > 13,
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    err
}

#[test]
fn dss_cor_matches_the_scipy_reference() {
    let a = json(&[
        "cor", "--model", "shc", "--base", DSS, "--v0", "1", "--format", "json",
    ]);
    assert_eq!(a.len(), 1);
    let r = &a[0];
    assert_eq!(r["model"], "shc");
    assert_eq!(r["v0"].as_f64(), Some(1.0));
    assert_eq!(r["separated"], true);
    let e = r["e"].as_f64().unwrap();
    let ts = r["ts"].as_f64().unwrap();
    assert!((e - 0.85003992947).abs() < 1e-9, "e = {e}");
    assert!((ts - 3.0909920923).abs() < 1e-8, "ts = {ts}");
    assert!(r["nfev"].as_u64().unwrap() > 0 && r["steps"].as_u64().unwrap() > 0);
}

#[test]
fn several_speeds_in_every_format() {
    let base = ["cor", "--model", "shc", "--base", DSS, "--v0", "0.1,1,5"];
    let a = json(&[&base[..], &["--format", "json"]].concat());
    let v0: Vec<f64> = a.iter().map(|r| r["v0"].as_f64().unwrap()).collect();
    assert_eq!(v0, [0.1, 1.0, 5.0]);
    for r in &a {
        let e = r["e"].as_f64().unwrap();
        assert!(r["separated"] == true && e > 0.0 && e < 1.0, "{r}");
    }

    let o = bwcl(&[&base[..], &["--format", "csv"]].concat());
    assert_eq!(o.status.code(), Some(0));
    let text = stdout(&o);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 4, "{text}");
    assert!(
        lines[0].starts_with("model,v0,separated,ts,e"),
        "{}",
        lines[0]
    );
    assert!(lines[2].starts_with("shc,1,true,"), "{}", lines[2]);
    // the CSV has the same numbers as the JSON
    let ts: f64 = lines[2].split(',').nth(3).unwrap().parse().unwrap();
    assert_eq!(ts, a[1]["ts"].as_f64().unwrap());

    let o = bwcl(&base);
    assert_eq!(o.status.code(), Some(0));
    let text = stdout(&o);
    let head = text.lines().next().unwrap();
    for col in ["model", "v0", "ts", "e", "nfev", "steps"] {
        assert!(head.split_whitespace().any(|c| c == col), "{head}");
    }
    assert_eq!(text.lines().count(), 4, "{text}");

    // --timing: one line on stderr, the same output on stdout
    let o = bwcl(&[&base[..], &["--format", "json", "--timing"]].concat());
    assert_eq!(o.status.code(), Some(0));
    let err = stderr(&o);
    let line = err.trim_end();
    assert!(!line.contains('\n'), "{err}");
    let rest = line
        .strip_prefix("bwcl: timing: 3 case(s) in ")
        .unwrap_or_else(|| panic!("{err}"));
    let secs: f64 = rest.split(' ').next().unwrap().parse().unwrap();
    assert!(secs > 0.0 && secs < 60.0, "{err}");
    assert_eq!(rows(&o), a);
}

#[test]
fn no_separation_is_reported_not_a_number() {
    let a = json(&[
        "cor",
        "--model",
        "shc",
        "--nd",
        DSS,
        "--horizon",
        "1",
        "--format",
        "json",
    ]);
    assert_eq!(a[0]["separated"], false);
    assert!(a[0]["ts"].is_null() && a[0]["v0"].is_null());
    assert_eq!(a[0]["e"].as_f64(), Some(0.0));
    let o = bwcl(&["cor", "--model", "shc", "--nd", DSS, "--horizon", "1"]);
    assert!(
        stdout(&o).contains("no separation before the horizon T = 1"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn bad_input_is_one_line_and_exit_code_two() {
    let err = assert_bad_input(&["cor", "--model", "shc", "--nd", "0,0,0.5,0,1,1"]);
    assert!(err.contains('B'), "{err}");
    let err = assert_bad_input(&[
        "cor",
        "--model",
        "shc",
        "--nd",
        "1.43,-1.5,0.632,0.00715,1.31,1.27",
    ]);
    assert!(err.contains("Γ = -1.5 must lie in (−B, B)"), "{err}");
    for v0 in ["0", "nan", "-1", "0.9..1.1", "1,abc"] {
        let err = assert_bad_input(&["cor", "--model", "shc", "--base", DSS, "--v0", v0]);
        assert!(err.contains("v0"), "{err}");
    }
    let err = assert_bad_input(&[
        "cor",
        "--model",
        "shc",
        "--base",
        "1.43,-1.42,0.632,0.00715,1.31",
        "--v0",
        "1",
    ]);
    assert!(err.contains("expected 6"), "{err}");
    let missing_a = BASEBALL.replace(",A=0.925", "");
    let err = assert_bad_input(&[
        "cor",
        "--model",
        "shc",
        "--physical",
        &missing_a,
        "--v0",
        "1",
    ]);
    assert!(err.contains("missing") && err.contains('A'), "{err}");
    let unknown = format!("{BASEBALL},mu=3");
    let err = assert_bad_input(&["cor", "--model", "shc", "--physical", &unknown, "--v0", "1"]);
    assert!(err.contains("mu"), "{err}");
    // the Maxwell model's 𝓟 excludes p ∈ (1, 2)
    assert_bad_input(&["cor", "--model", "maxwell", "--nd", DSS]);
    // conflicting or missing options, bad engine settings
    for args in [
        &["cor", "--model", "shc", "--base", DSS, "--nd", DSS][..],
        &["cor", "--model", "shc", "--nd", DSS, "--v0", "1"],
        &["cor", "--model", "shc", "--base", DSS],
        &["cor", "--model", "shc", "--v0", "1"],
        &["cor", "--model", "shc", "--nd", DSS, "--horizon", "nan"],
        &["cor", "--model", "shc", "--nd", DSS, "--rtol", "0"],
        &[
            "cor",
            "--model",
            "shc",
            "--nd",
            DSS,
            "--rigorous",
            "--rtol",
            "1e-8",
        ],
        &["cor", "--model", "shc", "--nd", DSS, "--order", "10"],
        &["cor", "--model", "shc", "--nd", DSS, "--format", "xml"],
        &["trajectory", "--model", "shc", "--base", DSS, "--v0", "1,2"],
        &[
            "trajectory",
            "--model",
            "shc",
            "--nd",
            DSS,
            "--physical-units",
        ],
        &["trajectory", "--model", "shc", "--nd", DSS, "--points", "1"],
        &["loop", "--model", "shc", "--nd", DSS, "--t-end", "-1"],
    ] {
        assert_bad_input(args);
    }
}

#[test]
fn baseball_in_physical_units() {
    let a = json(&[
        "cor",
        "--model",
        "shc",
        "--physical",
        BASEBALL,
        "--v0",
        "2.15",
        "--format",
        "json",
    ]);
    let r = &a[0];
    let e = r["e"].as_f64().unwrap();
    let ts = r["ts"].as_f64().unwrap();
    assert!(e > 0.0 && e < 1.0, "e = {e}");
    // against the library directly
    let phys = PhysicalParams::<f64>::parse(ModelKind::Shc, BASEBALL).unwrap();
    let t_c = phys.scales(&2.15).t_c;
    let lib = impact(
        &Shc::new(phys.nondimensionalize(ModelKind::Shc, &2.15).unwrap()),
        &FloatOptions::default(),
    )
    .unwrap();
    assert_eq!(lib.ts, Some(ts));
    assert_eq!(lib.e, e);
    assert_eq!(r["t_c"].as_f64(), Some(t_c));
    assert_eq!(r["ts_seconds"].as_f64(), Some(ts * t_c));
}

#[test]
fn trajectory_to_a_file_and_never_on_bad_input() {
    let out = scratch("dss.csv");
    let o = bwcl(&[
        "trajectory",
        "--model",
        "shc",
        "--base",
        DSS,
        "--v0",
        "1",
        "--points",
        "200",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(o.stdout.is_empty());
    let (head, rows) = numeric_csv(&std::fs::read_to_string(&out).unwrap());
    assert_eq!(head, ["t", "X", "Z", "V", "x", "v", "F"]);
    assert_eq!(rows.len(), 200);
    let (first, last) = (&rows[0], rows.last().unwrap());
    assert_eq!((first[0], first[3]), (0.0, -1.0));
    assert!(last[6].abs() < 1e-8, "F(T_s) = {}", last[6]);
    assert!((last[0] - 3.0909920923).abs() < 1e-8 && last[3] > 0.0);
    std::fs::remove_file(&out).unwrap();

    // the Maxwell model: its four states, and x, v from the output function
    let o = bwcl(&[
        "trajectory",
        "--model",
        "maxwell",
        "--nd",
        "0.655,-0.64,0.519,0.0118,1.94,2.28",
        "--points",
        "5",
    ]);
    let (head, rows) = numeric_csv(&stdout(&o));
    assert_eq!(head, ["t", "R", "Y", "Z", "W", "x", "v", "F"]);
    assert_eq!(rows[0][6], -1.0);

    let bad = scratch("bad.csv");
    assert_bad_input(&[
        "trajectory",
        "--model",
        "shc",
        "--base",
        "1.43,-1.5,0.632,0.00715,1.31,1.27",
        "--v0",
        "1",
        "--out",
        bad.to_str().unwrap(),
    ]);
    assert!(!bad.exists());
}

#[test]
fn loop_in_millimetres_and_newtons() {
    let o = bwcl(&[
        "loop",
        "--model",
        "shc",
        "--physical",
        BASEBALL,
        "--v0",
        "2.15",
        "--physical-units",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (head, rows) = numeric_csv(&stdout(&o));
    assert_eq!(head, ["x_mm", "F_N"]);
    assert_eq!(rows.len(), 1000);
    let fmax = rows.iter().map(|r| r[1]).fold(f64::MIN, f64::max);
    assert!(fmax > 0.0);
    for r in &rows {
        assert!(r[0] >= 0.0 && r[1] >= -1e-6, "{r:?}");
    }
}

#[test]
fn rigorous_cases_are_proved_or_say_why() {
    // not provable by construction (T_s ≈ 3.09 lies beyond the horizon): exit 1, the reason
    // in the JSON, the other case still reported
    let o = bwcl(&[
        "cor",
        "--model",
        "shc",
        "--base",
        DSS,
        "--v0",
        "1,0.9..1.1",
        "--rigorous",
        "--horizon",
        "0.5",
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let a: Vec<Value> = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(a.len(), 2);
    for r in &a {
        assert_eq!(r["proved"], false, "{r}");
        assert!(!r["reason"].as_str().unwrap().is_empty());
    }
    // the range is enclosed, not rounded
    let v = &a[1]["v0"];
    assert!(
        v[0].as_f64().unwrap() <= 0.9 && v[1].as_f64().unwrap() >= 1.1,
        "{v}"
    );

    // the DSS set: proved (an enclosure of the float T_s), or not proved with a reason
    let float_ts = json(&[
        "cor", "--model", "shc", "--base", DSS, "--v0", "1", "--format", "json",
    ])[0]["ts"]
        .as_f64()
        .unwrap();
    let o = bwcl(&[
        "cor",
        "--model",
        "shc",
        "--base",
        DSS,
        "--v0",
        "1",
        "--rigorous",
        "--format",
        "json",
    ]);
    let a: Vec<Value> = serde_json::from_str(&stdout(&o)).unwrap();
    let r = &a[0];
    match o.status.code() {
        Some(0) => {
            assert_eq!(r["proved"], true, "{r}");
            let ts = r["ts"].as_array().unwrap();
            assert_eq!(ts.len(), 2);
            let (lo, hi) = (ts[0].as_f64().unwrap(), ts[1].as_f64().unwrap());
            assert!(lo <= float_ts + 1e-8 && float_ts - 1e-8 <= hi, "{r}");
            assert!(r["width_e"].as_f64().unwrap() >= 0.0);
        }
        Some(1) => {
            assert_eq!(r["proved"], false, "{r}");
            assert!(!r["reason"].as_str().unwrap().is_empty());
        }
        c => panic!("exit code {c:?}: {}", stderr(&o)),
    }
}

#[test]
fn help_explains_the_parameters() {
    let o = bwcl(&["cor", "--help"]);
    assert_eq!(o.status.code(), Some(0));
    let h = stdout(&o);
    for s in [
        "κ",
        "σ",
        "Γ",
        "v0",
        "alpha",
        "--base 1.43,-1.42,0.632,0.00715,1.31,1.27 --v0 1",
    ] {
        assert!(h.contains(s), "{s} missing from the help");
    }
}

#[test]
fn rigorous_trajectory_encloses_or_fails_cleanly() {
    let o = bwcl(&[
        "trajectory",
        "--model",
        "shc",
        "--nd",
        DSS,
        "--rigorous",
        "--points",
        "5",
    ]);
    match o.status.code() {
        Some(0) => {
            let (head, rows) = numeric_csv(&stdout(&o));
            assert_eq!(
                head[..7],
                ["t", "X_lo", "X_hi", "Z_lo", "Z_hi", "V_lo", "V_hi"]
            );
            assert_eq!(head.len(), 13);
            assert_eq!(rows.len(), 5);
            assert_eq!((rows[0][0], rows[0][5], rows[0][6]), (0.0, -1.0, -1.0));
            for r in &rows {
                for pair in r[1..].chunks(2) {
                    assert!(pair[0] <= pair[1], "{r:?}");
                }
            }
        }
        Some(1) => {
            assert!(o.stdout.is_empty());
            assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
        }
        c => panic!("exit code {c:?}: {}", stderr(&o)),
    }
}
