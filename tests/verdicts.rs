//! Every proving command ends with a verdict (issue #30): proved, disproved with the sub-range
//! that refutes the claim, or not proved with its reason — within its time budget
//! (`--time-limit`), never silence. Each case below is a command that once ran for minutes or
//! hours without an answer, answered wrongly about itself, or refused admissible input.
//!
//! The runs are bounded twice: by `--time-limit` (the command's own budget, which is what is
//! tested) and by a kill after that budget plus a margin for start-up and a loaded machine (a
//! hang fails the test instead of stalling the suite). No test here asserts a speed.

use rug::Rational;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::common;
use common::hunt_crossley_bracket;

/// Seconds a run may take beyond its --time-limit before it counts as a hang (start-up, the
/// last step after the deadline, a machine shared with other builds).
const MARGIN: u64 = 60;

/// Runs `bwcl` with `args`, killed after `secs`: the output and the wall time, or a panic
/// naming the command that did not answer.
fn run_within(args: &[&str], secs: u64) -> (Output, Duration) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_bwcl"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("bwcl runs");
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return (child.wait_with_output().unwrap(), start.elapsed());
        }
        if start.elapsed() >= Duration::from_secs(secs) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("no verdict from bwcl {args:?} within {secs} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn text(b: &[u8]) -> String {
    String::from_utf8(b.to_vec()).unwrap()
}

/// A verdict within the budget: exit 0 or 1, no panic, something on stdout.
fn verdict(args: &[&str], limit: u64) -> (i32, String, String) {
    let (o, _) = run_within(args, limit + MARGIN);
    let (out, err) = (text(&o.stdout), text(&o.stderr));
    let code = o.status.code().expect("exited");
    assert!(code == 0 || code == 1, "{args:?}: exit {code}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert!(!out.trim().is_empty(), "{args:?}: nothing on stdout; {err}");
    (code, out, err)
}

/// The f64 engine's e at one speed (the DOP853 engine at tight tolerances: ≈ 1e-11 accurate,
/// far inside the differences compared below).
fn f64_e(base: &str, v0: f64) -> f64 {
    let o = common::bwcl(&[
        "cor",
        "--model",
        "shc",
        "--base",
        base,
        "--v0",
        &v0.to_string(),
        "--rtol",
        "1e-13",
        "--atol",
        "1e-15",
        "--format",
        "csv",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    let row = out.lines().nth(1).unwrap();
    row.split(',').nth(4).unwrap().parse().unwrap()
}

/// A base set whose e(v0) has its minimum near v0 = 3.24 and rises beyond (f64: by 6.3e-4 up
/// to v0 = 3.6).
const RISING: &str = "0.6754,-0.3949,0.455,0.00162,2,2";

/// The sub-ranges a DISPROVED verdict names (the lines "  [a, b]" after it).
fn increasing_ranges(out: &str) -> Vec<(f64, f64)> {
    out.lines()
        .filter_map(|l| {
            let l = l.trim();
            let inner = l.strip_prefix('[')?.strip_suffix(']')?;
            let (a, b) = inner.split_once(", ")?;
            Some((a.parse().ok()?, b.parse().ok()?))
        })
        .collect()
}

#[test]
fn a_false_monotonicity_claim_is_refuted_with_the_rising_sub_range() {
    // e increases on all of [4, 6]: once 34 min without an answer
    let (code, out, err) = verdict(
        &[
            "prove",
            "monotone",
            "--model",
            "shc",
            "--base",
            RISING,
            "--v0",
            "4..6",
            "--time-limit",
            "120",
        ],
        120,
    );
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.starts_with("DISPROVED"), "{out}");
    let rising = increasing_ranges(&out);
    assert!(!rising.is_empty(), "{out}");
    for &(a, b) in &rising {
        assert!((4.0..=6.0).contains(&a) && a < b && b <= 6.0, "{out}");
        // an independent look: the f64 engine sees e rise across each named sub-range
        assert!(f64_e(RISING, b) > f64_e(RISING, a), "[{a}, {b}]: {out}");
    }
    // the JSON verdict says the same
    let (code, out, _) = verdict(
        &[
            "prove",
            "monotone",
            "--model",
            "shc",
            "--base",
            RISING,
            "--v0",
            "4..6",
            "--format",
            "json",
            "--time-limit",
            "120",
        ],
        120,
    );
    assert_eq!(code, 1);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["verdict"], "disproved", "{out}");
    assert_eq!(v["proved_decreasing"], false);
    assert!(!v["increasing"].as_array().unwrap().is_empty(), "{out}");
}

#[test]
fn a_claim_false_only_at_the_end_of_its_range_is_refuted_there() {
    // the minimum near 3.24 lies inside [2, 3.245]: decreasing before it, rising after it
    let (code, out, err) = verdict(
        &[
            "prove",
            "monotone",
            "--model",
            "shc",
            "--base",
            RISING,
            "--v0",
            "2..3.245",
            "--time-limit",
            "120",
        ],
        120,
    );
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.starts_with("DISPROVED"), "{out}");
    let rising = increasing_ranges(&out);
    assert!(!rising.is_empty(), "{out}");
    for &(a, b) in &rising {
        // where the f64 engine puts the minimum, and where e rises
        assert!(a >= 3.2 && b <= 3.245, "{out}");
        assert!(f64_e(RISING, b) > f64_e(RISING, a), "[{a}, {b}]: {out}");
    }
    // a true claim is still proved: the DSS set is decreasing on [0.5, 1]
    let (code, out, _) = verdict(
        &[
            "prove",
            "monotone",
            "--model",
            "shc",
            "--base",
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--v0",
            "0.5..1",
            "--time-limit",
            "120",
        ],
        120,
    );
    assert_eq!(code, 0, "{out}");
    assert!(out.starts_with("PROVED"), "{out}");
}

#[test]
fn an_undecided_monotonicity_claim_stops_at_its_budget_and_says_so() {
    // 1 s is far too short for [0.1, 5]: pieces proved so far and the rest named
    let (code, out, _) = verdict(
        &[
            "prove",
            "monotone",
            "--model",
            "shc",
            "--base",
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--v0",
            "0.1..5",
            "--time-limit",
            "1",
        ],
        1,
    );
    assert_eq!(code, 1, "{out}");
    assert!(out.starts_with("NOT PROVED"), "{out}");
    assert!(
        out.contains("the time budget of 1 s ran out (--time-limit)"),
        "{out}"
    );
}

/// `cor --rigorous --digits D --format csv` of an --nd set: (e_lo, e_hi, width_e, bits), the
/// bounds read as exact rationals from the printed text.
fn digits_e(model: &str, nd: &str, digits: &str) -> (Rational, Rational, f64, u64) {
    let (code, out, err) = verdict(
        &[
            "cor",
            "--model",
            model,
            "--nd",
            nd,
            "--rigorous",
            "--digits",
            digits,
            "--format",
            "csv",
            "--time-limit",
            "200",
        ],
        200,
    );
    assert_eq!(code, 0, "{out}{err}");
    // model,v0,proved,ts_lo,ts_hi,width_ts,e_lo,e_hi,width_e,bits,pieces,reason
    let row: Vec<&str> = out.lines().nth(1).unwrap().split(',').collect();
    assert_eq!(row[2], "true", "{out}");
    let rat = |s: &str| bwcl::observables::decimal::parse_rational(s).unwrap();
    (
        rat(row[6]),
        rat(row[7]),
        row[8].parse().unwrap(),
        row[9].parse().unwrap(),
    )
}

#[test]
fn digits_in_the_hunt_crossley_limit_prove_at_least_what_f64_proves() {
    // once: no output after 600 s at 30 digits (steps of length 0 at T_s ≈ 3.39)
    let nd = "1e-300,0,0.5,0.7,1.5,1.5";
    let (lo, hi) = hunt_crossley_bracket(&Rational::from((7, 10)));
    // the f64-interval engine's width of e here: ≈ 9e-14
    for (digits, widest) in [("30", 1e-30), ("60", 1e-30)] {
        let (el, eh, w, bits) = digits_e("shc", nd, digits);
        assert!(bits > 53, "{digits}: {bits}");
        assert!(
            el <= lo && hi <= eh,
            "{digits}: [{el}, {eh}] misses the closed form"
        );
        assert!(w <= widest, "{digits}: width {w:e}");
    }
    // once refused at once ("cannot cross a switching surface … at T = 0") though f64 proves it
    let nd = "1e-300,0,0.5,0.8,1.5,1";
    let (el, eh, w, _) = digits_e("maxwell", nd, "60");
    let (code, out, _) = verdict(
        &[
            "cor",
            "--model",
            "maxwell",
            "--nd",
            nd,
            "--rigorous",
            "--format",
            "json",
        ],
        60,
    );
    assert_eq!(code, 0, "{out}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let f =
        |i: usize| bwcl::observables::decimal::parse_rational(&v[0]["e"][i].to_string()).unwrap();
    let wf = v[0]["width_e"].as_f64().unwrap();
    // both hold the true e: they meet, and the precise one is no wider
    assert!(
        el <= f(1) && f(0) <= eh,
        "[{el}, {eh}] and [{}, {}]",
        f(0),
        f(1)
    );
    assert!(w <= wf, "{w:e} > {wf:e}");
}

#[test]
fn cases_without_an_answer_once_now_end_within_their_budget() {
    for args in [
        vec![
            "cor",
            "--model",
            "maxwell",
            "--nd",
            "1e-300,0,0.5,2,1,1",
            "--rigorous",
        ],
        vec![
            "cor",
            "--model",
            "shc",
            "--nd",
            "1,0,0.5,0.2,1..10,1..10",
            "--rigorous",
        ],
        vec![
            "cor",
            "--model",
            "maxwell",
            "--base",
            "0.44,-0.418,0.113,0.00785,1.27,3.14",
            "--v0",
            "0.001..1000",
            "--rigorous",
        ],
        vec![
            "cor",
            "--model",
            "shc",
            "--nd",
            "299.5..300.5,-299,0.4,0.1,1.5,1.5",
            "--rigorous",
        ],
        vec![
            "cor",
            "--model",
            "shc",
            "--nd",
            "1e16,0,0.5,1,1.3,1.2",
            "--rigorous",
        ],
        vec![
            "cor",
            "--model",
            "maxwell",
            "--nd",
            "1,0,0.5,1,1.3,1e16",
            "--rigorous",
        ],
    ] {
        // a 1-s budget: the shorter, the stricter the check that the budget is kept
        let mut a = args.clone();
        a.extend(["--time-limit", "1"]);
        let (o, took) = run_within(&a, 1 + MARGIN);
        let (out, err) = (text(&o.stdout), text(&o.stderr));
        let code = o.status.code().expect("exited");
        assert!(code == 0 || code == 1, "{a:?}: exit {code}: {err}");
        assert!(!err.contains("panicked"), "{a:?}: {err}");
        // one row with a result or the reason
        assert!(out.lines().count() == 2, "{a:?}: {out}");
        if code == 1 {
            assert!(out.contains("not proved: "), "{a:?}: {out}");
        }
        eprintln!("{a:?}: exit {code} in {took:?}");
    }
}

#[test]
fn a_horizon_reached_without_separation_is_a_proved_result() {
    // once exit 1 "not proved" although its reason was a proof
    let (code, out, err) = verdict(
        &[
            "cor",
            "--model",
            "maxwell",
            "--nd",
            "1,0,0.5,1,1.3,500",
            "--rigorous",
        ],
        60,
    );
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains("proved: no separation before the horizon T = 100 (T_s > 100"),
        "{out}"
    );
    assert!(!out.contains("not proved"), "{out}");
    let (code, out, _) = verdict(
        &[
            "cor",
            "--model",
            "maxwell",
            "--nd",
            "1,0,0.5,1,1.3,500",
            "--rigorous",
            "--format",
            "json",
        ],
        60,
    );
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v[0]["proved"], true);
    assert_eq!(v[0]["separated"], false);
    assert!(v[0]["e"].is_null() && v[0]["ts"].is_null(), "{out}");
    // a shorter horizon: proved up to it
    let (code, out, _) = verdict(
        &[
            "cor",
            "--model",
            "maxwell",
            "--nd",
            "1,0,0.5,1,1.3,500",
            "--rigorous",
            "--horizon",
            "0.5",
        ],
        60,
    );
    assert!(code == 0 && out.contains("T = 0.5"), "{out}");
}

#[test]
fn decimals_inside_the_admissible_set_are_accepted_as_written() {
    // each once refused: the decimal is inside 𝓟, only its enclosure touches the bound
    for nd in [
        "1,0,0.9999999999999999,0.2,1.5,1.5",
        "1,0.9999999999999999,0.5,0.2,1.5,1.5",
        "1,-0.9999999999999999,0.5,0.2,1.5,1.5",
        "4.9e-324,0,0.5,0.2,1.5,1.5",
    ] {
        for rigorous in [false, true] {
            let mut a = vec!["cor", "--model", "shc", "--nd", nd];
            if rigorous {
                a.push("--rigorous");
            }
            let (code, out, err) = verdict(&a, 60);
            assert_eq!(code, 0, "{a:?}: {out}{err}");
        }
    }
    // and decimals outside are refused exactly, named as written
    for (nd, says) in [
        ("1,0,1,0.2,1.5,1.5", "κ = 1 must lie in (0, 1)"),
        ("1,1,0.5,0.2,1.5,1.5", "Γ = 1 must lie in (−B, B) = (-1, 1)"),
        (
            "1,0,0.5,0.2,0.99999999999999999999,1.5",
            "n = 0.99999999999999999999 must be ≥ 1",
        ),
    ] {
        let o = common::bwcl(&["cor", "--model", "shc", "--nd", nd, "--rigorous"]);
        assert_eq!(o.status.code(), Some(2), "{nd}");
        assert!(text(&o.stderr).contains(says), "{nd}: {}", text(&o.stderr));
    }
    // p just above 1 is outside the Maxwell model's 𝓟 ([2, ∞) ∪ {1}), though its double is 1
    let o = common::bwcl(&[
        "cor",
        "--model",
        "maxwell",
        "--nd",
        "1,0,0.5,0.2,1.5,1.00000000000000000001",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o.stderr).contains("[2, ∞) ∪ {1}"),
        "{}",
        text(&o.stderr)
    );
}

#[test]
fn physical_parameters_are_refused_as_the_help_states() {
    let phys =
        "m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=981.05,A=0.925";
    let o = common::bwcl(&["cor", "--model", "shc", "--physical", phys, "--v0", "2"]);
    assert_eq!(o.status.code(), Some(2));
    let err = text(&o.stderr);
    assert!(
        err.contains("gamma = 981.05 must lie in (−beta, beta) = (-981.05, 981.05)"),
        "{err}"
    );
    let help = text(&common::bwcl(&["cor", "--help"]).stdout);
    assert!(help.contains("γ ∈ (−β, β)") && help.contains("β > 0") && help.contains("c > 0"));
    // γ just inside is accepted
    let phys = phys.replace("gamma=981.05", "gamma=981.0499999999999");
    let (code, out, err) = verdict(
        &[
            "cor",
            "--model",
            "shc",
            "--physical",
            &phys,
            "--v0",
            "2",
            "--rigorous",
        ],
        60,
    );
    assert_eq!(code, 0, "{out}{err}");
    // the Maxwell model's p ∈ [2, ∞) ∪ {1} as written, on the f64 path too (p just off 1 or
    // just below 2 rounds to the double 1 or 2)
    for p in ["1.00000000000000000001", "1.99999999999999999999"] {
        let phys = phys
            .replace("p=1.7", &format!("p={p}"))
            .replace("gamma=981.0499999999999", "gamma=-961.4");
        let o = common::bwcl(&[
            "cor",
            "--model",
            "maxwell",
            "--physical",
            &phys,
            "--v0",
            "2",
        ]);
        assert_eq!(o.status.code(), Some(2), "p = {p}");
        let err = text(&o.stderr);
        assert!(
            err.contains(&format!(
                "p = {p} must lie in [2, ∞) ∪ {{1}} for the Maxwell model"
            )),
            "{err}"
        );
    }
}

#[test]
fn a_band_out_of_time_says_what_it_proved_and_writes_nothing() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(format!("bwcl-verdict-band-{}.csv", std::process::id()));
    let _ = std::fs::remove_file(&path);
    let p = path.to_str().unwrap();
    let (o, _) = run_within(
        &[
            "cor",
            "--model",
            "shc",
            "--base",
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--v0",
            "0.1..5",
            "--rigorous",
            "--band",
            p,
            "--time-limit",
            "2",
        ],
        2 + MARGIN,
    );
    assert_eq!(o.status.code(), Some(1));
    let err = text(&o.stderr);
    assert!(
        err.contains("the time budget of 2 s ran out (--time-limit)"),
        "{err}"
    );
    assert!(err.contains("proved so far:"), "{err}");
    assert!(!path.exists());
}

#[test]
fn band_pieces_are_printed_so_that_they_cover_the_range() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(format!("bwcl-verdict-cover-{}.csv", std::process::id()));
    let p = path.to_str().unwrap();
    let (o, _) = run_within(
        &[
            "cor",
            "--model",
            "shc",
            "--base",
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--v0",
            "0.5..0.7",
            "--rigorous",
            "--band",
            p,
            "--thickness",
            "1e-5",
        ],
        300,
    );
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let csv = std::fs::read_to_string(&path).unwrap();
    let _ = std::fs::remove_file(&path);
    let rows: Vec<Vec<String>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    assert!(rows.len() >= 2, "{csv}");
    let rat = |s: &str| bwcl::observables::decimal::parse_rational(s).unwrap();
    for w in rows.windows(2) {
        // the printed end of a piece is the printed start of the next: no gap between them
        assert_eq!(w[0][1], w[1][0], "{csv}");
    }
    // the printed ends hold the claim: inside the range as enclosed, and the first and last
    // at its ends (inward, within a few ulps)
    assert!(
        rat(&rows[0][0]) >= rat("0.49999999999999994"),
        "{}",
        rows[0][0]
    );
    assert!(rat(&rows[rows.len() - 1][1]) <= rat("0.7000000000000001"));
    for r in &rows {
        assert!(rat(&r[0]) < rat(&r[1]), "{r:?}");
    }
}

#[test]
fn digits_and_flows_stop_at_their_budget() {
    // 100 digits take about a minute: 1 s is not enough
    let (code, out, _) = verdict(
        &[
            "cor",
            "--model",
            "shc",
            "--base",
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--v0",
            "1",
            "--rigorous",
            "--digits",
            "100",
            "--time-limit",
            "1",
        ],
        1,
    );
    assert_eq!(code, 1);
    assert!(
        out.contains("the time budget of 1 s ran out (--time-limit)"),
        "{out}"
    );
    let o = run_within(
        &[
            "trajectory",
            "--model",
            "shc",
            "--base",
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--v0",
            "1",
            "--rigorous",
            "--order",
            "2",
            "--time-limit",
            "0.001",
        ],
        MARGIN,
    )
    .0;
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
    assert!(
        text(&o.stderr).contains("time budget"),
        "{}",
        text(&o.stderr)
    );
}

#[test]
fn the_time_limit_is_an_option_of_the_rigorous_engine_with_a_range() {
    for bad in ["0", "-1", "1e9", "nan", "x"] {
        let o = common::bwcl(&[
            "cor",
            "--model",
            "shc",
            "--base",
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--v0",
            "1",
            "--rigorous",
            "--time-limit",
            bad,
        ]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        assert!(text(&o.stderr).contains("--time-limit"), "{bad}");
    }
    let o = common::bwcl(&[
        "cor",
        "--model",
        "shc",
        "--base",
        "1.43,-1.42,0.632,0.00715,1.31,1.27",
        "--v0",
        "1",
        "--time-limit",
        "10",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o.stderr).contains("add --rigorous"));
}

#[test]
fn progress_shows_on_a_terminal_only() {
    // `script` gives the command a terminal; without one (a pipe) nothing but the result
    if Command::new("script").arg("--version").output().is_err() {
        eprintln!("no `script` here: skipped");
        return;
    }
    let cmd = format!(
        "{} prove monotone --model shc --base 1.43,-1.42,0.632,0.00715,1.31,1.27 --v0 0.1..5 --time-limit 5",
        env!("CARGO_BIN_EXE_bwcl")
    );
    let o = Command::new("script")
        .args(["-qec", &cmd, "/dev/null"])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let seen = text(&o.stdout);
    assert!(
        seen.contains("prove monotone") && seen.contains("% of the range settled"),
        "{seen}"
    );
    let (_, _, err) = verdict(
        &[
            "prove",
            "monotone",
            "--model",
            "shc",
            "--base",
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--v0",
            "0.1..5",
            "--time-limit",
            "5",
        ],
        5,
    );
    assert!(!err.contains("settled"), "{err}");
}

/// A range of α in the physical parameters: κ = 1/(1 + (1/α − 1)A^p) uses α once, so its
/// interval value stays inside (0, 1) and the range is proved (with κ = α/(α + (1 − α)A^p), α
/// twice, sup κ > 1 and the range was refused as outside 𝓟). The enclosure holds the proved
/// values at both ends of the range.
#[test]
fn a_range_of_alpha_is_proved_and_holds_its_ends() {
    let phys = |alpha: &str| {
        format!(
            "m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha={alpha},beta=981.05,gamma=-961.4,A=0.925"
        )
    };
    let run = |alpha: &str| {
        let p = phys(alpha);
        let (code, out, err) = verdict(
            &[
                "cor",
                "--model",
                "shc",
                "--physical",
                &p,
                "--v0",
                "2",
                "--rigorous",
                "--format",
                "json",
            ],
            120,
        );
        assert_eq!(code, 0, "alpha={alpha}: {out}{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let e = &v[0]["e"];
        (e[0].as_f64().unwrap(), e[1].as_f64().unwrap())
    };
    let hull = run("0.05..0.15");
    for a in ["0.05", "0.15"] {
        let end = run(a);
        assert!(
            hull.0 <= end.0 && end.1 <= hull.1,
            "alpha={a}: {end:?} ⊄ {hull:?}"
        );
    }
    assert!(hull.1 - hull.0 < 0.2, "{hull:?}");
}

/// `--band --second-order`: node intervals that cover the range, each thinner than the target,
/// and the printed bounds at a node hold e and T_s proved there to 30 digits (as rationals).
#[test]
fn a_second_order_band_covers_the_range_and_its_printed_nodes_hold_precise_values() {
    use bwcl::engines::taylor::TaylorOptions;
    use bwcl::models::ModelKind;
    use bwcl::observables::precision::{ParamText, rigorous_impact_digits};
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(format!("bwcl-verdict-second-{}.csv", std::process::id()));
    let p = path.to_str().unwrap();
    let base = "0.44,-0.418,0.113,0.00785,1.27,3.14";
    let (o, _) = run_within(
        &[
            "cor",
            "--model",
            "maxwell",
            "--base",
            base,
            "--v0",
            "1.5..1.6",
            "--rigorous",
            "--band",
            p,
            "--second-order",
            "--thickness",
            "1e-9",
        ],
        300,
    );
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    assert!(
        text(&o.stdout).contains("(second order)"),
        "{}",
        text(&o.stdout)
    );
    let csv = std::fs::read_to_string(&path).unwrap();
    let _ = std::fs::remove_file(&path);
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    assert!(rows.len() >= 2, "{csv}");
    let rat = |s: &str| bwcl::observables::decimal::parse_rational(s).unwrap();
    assert_eq!(rat(&rows[0][col("v0_lo")]), rat("1.5"));
    // (the nodes exactly: the range's ends are the doubles that enclose it)
    let last = rat(&rows[rows.len() - 1][col("v0_hi")]);
    assert!(
        last >= rat("1.6") && last <= rat("1.6000000000000001"),
        "{last}"
    );
    for w in rows.windows(2) {
        assert_eq!(w[0][col("v0_hi")], w[1][col("v0_lo")], "no gap");
    }
    for r in &rows {
        assert!(rat(&r[col("v0_lo")]) < rat(&r[col("v0_hi")]), "{r:?}");
        assert!(rat(&r[col("thickness")]) <= rat("1e-9"), "{r:?}");
    }
    // a node inside the range: its printed enclosures against 30 digits
    let r = &rows[rows.len() / 2];
    let v = &r[col("v0_lo")];
    let precise = rigorous_impact_digits(
        ModelKind::Maxwell,
        &ParamText::Base {
            base: base.into(),
            v0: v.clone(),
        },
        30,
        &TaylorOptions::default(),
    )
    .unwrap();
    assert!(
        rat(&r[col("e_at_lo_lo")]) <= precise.e[0] && precise.e[1] <= rat(&r[col("e_at_lo_hi")])
    );
    assert!(
        rat(&r[col("ts_at_lo_lo")]) <= precise.ts[0]
            && precise.ts[1] <= rat(&r[col("ts_at_lo_hi")])
    );
}

#[test]
fn a_second_order_band_out_of_time_says_so_and_writes_nothing() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(format!(
        "bwcl-verdict-second-time-{}.csv",
        std::process::id()
    ));
    let p = path.to_str().unwrap();
    let (o, _) = run_within(
        &[
            "cor",
            "--model",
            "shc",
            "--base",
            "1.43,-1.42,0.632,0.00715,1.31,1.27",
            "--v0",
            "0.1..5",
            "--rigorous",
            "--band",
            p,
            "--second-order",
            "--time-limit",
            "1",
        ],
        60,
    );
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
    let err = text(&o.stderr);
    assert!(
        err.contains("the time budget of 1 s ran out (--time-limit)"),
        "{err}"
    );
    assert!(!path.exists());
}
