//! A fuzz test of the `bwcl` program: seeded command lines of mixed bad input (bad numbers,
//! NaN, ∞, huge, negative and overflowing integers, control characters, long tokens, malformed
//! lists and ranges, unknown options, bad CSV files, bad --out targets), for every subcommand.
//!
//! Every run must: exit with 0, 1 or 2 (never a signal or 101); print no panic text; for exit
//! 2 print exactly one stderr line `bwcl: error: …` naming an option or a value, and nothing on
//! stdout; leave a pre-existing --out file unchanged (bytes and mtime) unless it exited 0, and
//! leave no stray file next to it; finish within 20 s.
//!
//! CI runs `BWCL_FUZZ_CASES` (default 1000, some 7 s) cases from a fixed seed. Soak mode, like the
//! property tests: `BWCL_FUZZ_CASES=10000 BWCL_FUZZ_RANDOM=1 cargo test --release --test
//! cli_fuzz -- --nocapture` (a random seed, printed; `BWCL_FUZZ_SEED=S` replays one).
//!
//! Soak run (2026-11-23, 2 shared cores, release build): 10000 cases, seed
//! 1795430995268918361, 60.4 s; exit 0/1/2: 69/3/9928; 0 panics, 0 hangs, 0 unclear messages,
//! 0 touched files, 0 other exit codes. (The soak before it, seed 1795430801825076091, found 2
//! unclear messages: a stderr note written before an --out error, and a file name over 255
//! bytes found only when writing; both fixed, that seed now passes.)

use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant, SystemTime};

const DSS: &str = "1.43,-1.42,0.632,0.00715,1.31,1.27";
const MAXWELL: &str = "0.655,-0.64,0.519,0.0118,1.94,2.28";
const BASEBALL: &str =
    "m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925";
/// Longest a run may take.
const LIMIT: Duration = Duration::from_secs(20);

/// splitmix64: a small, seedable generator (the test needs no statistical quality).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn pick<T: Clone>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())].clone()
    }
    fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }
}

/// Files the cases point at, made once.
struct Fixtures {
    dir: PathBuf,
    good_csv: PathBuf,
    bad_csvs: Vec<PathBuf>,
}

fn fixtures() -> Fixtures {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("bwcl-fuzz-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, bytes: &[u8]| {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    };
    let good_csv = write("good.csv", b"v0,e\n0.5,0.9\n1,0.85\n2,0.8\n");
    let mut bad_csvs = vec![
        write("bom.csv", "\u{feff}v0,e\n1,0.85\n".as_bytes()),
        write("dup.csv", b"v0,e,e\n1,0.85,0.85\n"),
        write("alias.csv", b"v0,v_0,e\n1,1,0.85\n"),
        write("nul.csv", b"v0,e\n1,0.8\0\n"),
        write("nulhead.csv", b"v0\0,e\n1,0.8\n"),
        write("empty.csv", b""),
        write("header.csv", b"v0,e\n"),
        write("noheader.csv", b"1,0.5\n2,0.4\n"),
        write("nan.csv", b"v0,e\nnan,0.5\n1,inf\n"),
        write("range.csv", b"v0,e\n-1,0.5\n1,1.5\n"),
        write("fields.csv", b"v0,e\n1,0.5,3\n"),
        write("latin1.csv", b"v0,e\n1,0.5\xff\n"),
        write("ctrl.csv", b"v0,e\x1b[2J\n1,0.5\n"),
        write(
            "longline.csv",
            format!("v0,e\n1,0.5{}\n", "9".repeat(5000)).as_bytes(),
        ),
        write(
            "bigheader.csv",
            format!("v0,e{}\n1,0.5\n", "x".repeat(5 << 20)).as_bytes(),
        ),
        write(
            "rows.csv",
            format!("v0,e\n{}", "1,0.5\n".repeat(10_001)).as_bytes(),
        ),
        PathBuf::from("/dev/zero"),
        dir.join("missing.csv"),
        dir.clone(),
    ];
    let fifo_free = write("big_e.csv", b"v0,e\n1e308,1\n1e-320,0\n");
    bad_csvs.push(fifo_free);
    Fixtures {
        dir,
        good_csv,
        bad_csvs,
    }
}

/// A bad or odd number.
fn bad_number(r: &mut Rng) -> String {
    let fixed = [
        "nan",
        "NaN",
        "inf",
        "-inf",
        "+inf",
        "1e309",
        "-1e309",
        "1e-400",
        "4.9e-324",
        "-0",
        "0",
        "-1",
        "1e300",
        "-1e300",
        "1.797e308",
        "18446744073709551615",
        "18446744073709551616",
        "-9223372036854775809",
        "99999999999999999999999999",
        "0x10",
        "1_000",
        "1,5",
        "1..",
        "..1",
        "2..1",
        "1..2..3",
        "",
        " ",
        "1e",
        "e5",
        ".",
        "-",
        "--",
        "+-1",
        "١",
        "1 2",
        "0.1.2",
        "1e-5",
        "41",
        "1000",
        "1025",
        "100001",
        "257",
        "10001",
        "2.5",
    ];
    match r.below(6) {
        0 => long_token(r),
        1 => {
            let s = r.pick(&fixed).to_string();
            with_control(r, &s)
        }
        2 => format!("{}", r.next() as i64),
        3 => format!("{:e}", f64::from_bits(r.next())),
        _ => r.pick(&fixed).to_string(),
    }
}

fn long_token(r: &mut Rng) -> String {
    let unit = r.pick(&["9", "x", "1,", "é", "-", "\u{1b}", "1..2,"]);
    unit.repeat(1 + r.below(20_000) / unit.len())
}

fn with_control(r: &mut Rng, s: &str) -> String {
    let c = r.pick(&[
        "\n",
        "\r",
        "\t",
        "\u{1b}[31m",
        "\u{7}",
        "\u{85}",
        "\u{202e}",
        "\u{feff}",
    ]);
    let at = r.below(s.len() + 1);
    if s.is_char_boundary(at) {
        format!("{}{c}{}", &s[..at], &s[at..])
    } else {
        format!("{s}{c}")
    }
}

/// A parameter list with one value spoiled, or a malformed list.
fn bad_list(r: &mut Rng, good: &str) -> String {
    let mut items: Vec<String> = good.split(',').map(String::from).collect();
    match r.below(5) {
        0 => {
            let i = r.below(items.len());
            items[i] = bad_number(r);
        }
        1 => {
            items.pop();
        }
        2 => items.push(bad_number(r)),
        3 => {
            return r
                .pick(&["", ",", ",,,,,", "a,b,c,d,e,f", "1;2;3;4;5;6"])
                .to_string();
        }
        _ => {
            let i = r.below(items.len());
            items[i] = format!("{}..{}", items[i], bad_number(r));
        }
    }
    items.join(",")
}

/// One generated case: the arguments and, when it writes --out, the file to watch.
struct Case {
    args: Vec<OsString>,
    watched: Option<PathBuf>,
}

fn generate(r: &mut Rng, fx: &Fixtures, case_dir: &Path) -> Case {
    let cmd = r.pick(&["cor", "trajectory", "loop", "fit", "cost"]);
    let model = if r.chance(90) {
        r.pick(&["shc", "maxwell"]).to_string()
    } else {
        bad_number(r)
    };
    let set = if model == "maxwell" { MAXWELL } else { DSS };
    let mut args: Vec<String> = vec![cmd.into(), "--model".into(), model];
    // a cheap valid baseline, then one to three spoils
    match cmd {
        "fit" => {
            let data = if r.chance(70) {
                r.pick(&fx.bad_csvs)
            } else {
                fx.good_csv.clone()
            };
            args.extend([
                "--data".into(),
                data.to_string_lossy().into_owned(),
                "--init".into(),
                set.into(),
                "--starts".into(),
                "0".into(),
                "--max-iter".into(),
                "3".into(),
            ]);
        }
        "cost" => {
            let data = if r.chance(70) {
                r.pick(&fx.bad_csvs)
            } else {
                fx.good_csv.clone()
            };
            args.extend([
                "--base".into(),
                set.into(),
                "--data".into(),
                data.to_string_lossy().into_owned(),
            ]);
        }
        _ => match r.below(3) {
            0 => args.extend(["--nd".into(), set.into()]),
            1 => args.extend(["--base".into(), set.into(), "--v0".into(), "1".into()]),
            _ => args.extend([
                "--physical".into(),
                BASEBALL.into(),
                "--v0".into(),
                "2.15".into(),
            ]),
        },
    }
    let spoils = 1 + r.below(3);
    for _ in 0..spoils {
        spoil(r, cmd, set, &mut args);
    }
    let mut watched = None;
    if matches!(cmd, "cor" | "trajectory" | "loop") && r.chance(40) {
        let (path, watch) = out_target(r, case_dir);
        args.extend(["--out".into(), path]);
        watched = watch;
    }
    let mut args: Vec<OsString> = args.into_iter().map(OsString::from).collect();
    if r.chance(2) {
        // an argument that is not UTF-8
        let i = 1 + r.below(args.len());
        args.insert(
            i.min(args.len()),
            OsString::from_vec(vec![b'1', 0xff, b'2']),
        );
    }
    Case { args, watched }
}

/// Spoils one thing of the command line.
fn spoil(r: &mut Rng, cmd: &str, set: &str, args: &mut Vec<String>) {
    let numeric = [
        "--order",
        "--pieces",
        "--points",
        "--t-end",
        "--horizon",
        "--rtol",
        "--atol",
        "--max-step",
        "--starts",
        "--max-iter",
        "--seed",
    ];
    match r.below(10) {
        0 | 1 => {
            let opt = r.pick(&numeric);
            args.extend([opt.to_string(), bad_number(r)]);
            if matches!(opt, "--order" | "--pieces") && r.chance(50) {
                args.push("--rigorous".into());
            }
        }
        2 => {
            let opt = r.pick(&["--nd", "--base", "--init", "--v0", "--physical"]);
            let text = match opt {
                "--v0" => bad_list(r, "0.5,1,2"),
                "--physical" => bad_physical(r),
                _ => bad_list(r, set),
            };
            if let Some(i) = args
                .iter()
                .position(|a| a == opt)
                .filter(|i| i + 1 < args.len())
            {
                args[i + 1] = text;
            } else {
                args.extend([opt.to_string(), text]);
            }
        }
        3 => args.push(
            r.pick(&[
                "--bogus",
                "-x",
                "--",
                "-",
                "--rigorous=yes",
                "--format",
                "--format=xml",
                "--physical-units",
                "--p1",
                "--timing",
                "--help=1",
            ])
            .into(),
        ),
        4 => {
            // a valid option in an odd combination
            let extra: &[&str] = r.pick(&[
                &["--rigorous"][..],
                &["--rtol", "1e-8", "--order", "10"],
                &["--pieces", "0"],
                &["--atol", "0"],
                &["--v0", "0.9..1.1", "--rigorous", "--pieces", "3"],
                &["--v0", "1,2"],
                &["--t-end", "1e300"],
                &["--points", "1000000000"],
                &["--order", "1000", "--rigorous"],
                &["--horizon", "0.001"],
                &["--nd", DSS],
                &["--format", "json"],
                &["--format", "csv"],
            ]);
            args.extend(extra.iter().map(|s| s.to_string()));
        }
        5 => {
            // drop a token
            if args.len() > 1 {
                let i = 1 + r.below(args.len() - 1);
                args.remove(i);
            }
        }
        6 => {
            // a control character or a long tail in some token
            let i = r.below(args.len());
            args[i] = if r.chance(50) {
                with_control(r, &args[i])
            } else {
                format!("{}{}", args[i], long_token(r))
            };
        }
        7 if cmd == "fit" || cmd == "cost" => {
            args.extend(["--data".into(), bad_number(r)]);
        }
        _ => args.extend([bad_number(r), bad_number(r)]),
    }
}

fn bad_physical(r: &mut Rng) -> String {
    let mut items: Vec<String> = BASEBALL.split(',').map(String::from).collect();
    let i = r.below(items.len());
    match r.below(4) {
        0 => {
            let key = items[i].split('=').next().unwrap().to_string();
            items[i] = format!("{key}={}", bad_number(r));
        }
        1 => {
            items.remove(i);
        }
        2 => items.push(r.pick(&["mu=3", "m=1", "=", "k", "A=1=2"]).into()),
        _ => items[i] = bad_number(r),
    }
    items.join(",")
}

/// An --out target: a pre-existing file to watch, a new name, a symlink, a directory, a file
/// in a missing directory, or a name too long.
fn out_target(r: &mut Rng, dir: &Path) -> (String, Option<PathBuf>) {
    let existing = dir.join("existing.txt");
    std::fs::write(&existing, b"sentinel\n").unwrap();
    let old = SystemTime::UNIX_EPOCH + Duration::from_secs(1_500_000_000);
    std::fs::File::options()
        .write(true)
        .open(&existing)
        .unwrap()
        .set_modified(old)
        .unwrap();
    let s = |p: &Path| p.to_string_lossy().into_owned();
    match r.below(7) {
        0 | 1 => (s(&existing), Some(existing)),
        2 => {
            let link = dir.join("link.txt");
            let _ = std::os::unix::fs::symlink(&existing, &link);
            (s(&link), Some(existing))
        }
        3 => (s(dir), None),
        4 => (s(&dir.join("missing").join("x.csv")), None),
        5 => (s(&dir.join("n".repeat(300))), None),
        _ => (s(&dir.join(with_control(r, "new.csv"))), None),
    }
}

/// What one run did.
#[derive(Default, Debug)]
struct Tally {
    cases: usize,
    by_code: [usize; 3],
    panics: usize,
    hangs: usize,
    unclear: usize,
    touched: usize,
    bad_codes: usize,
    failures: Vec<String>,
}

fn run_case(case: &Case, case_dir: &Path, t: &mut Tally) {
    let before = case.watched.as_ref().map(|p| {
        let m = std::fs::metadata(p).unwrap();
        (std::fs::read(p).unwrap(), m.modified().unwrap())
    });
    let listing = |d: &Path| -> Vec<OsString> {
        let mut v: Vec<OsString> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        v.sort();
        v
    };
    let files_before = listing(case_dir);
    let out_dir = case_dir.to_path_buf();
    let mut child = Command::new(env!("CARGO_BIN_EXE_bwcl"))
        .args(&case.args)
        .current_dir(&out_dir)
        .env_remove("RUST_BACKTRACE")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // read the pipes on threads so that a large output cannot block the child
    let mut so = child.stdout.take().unwrap();
    let mut se = child.stderr.take().unwrap();
    let so = std::thread::spawn(move || {
        let mut b = Vec::new();
        let _ = std::io::Read::read_to_end(&mut so, &mut b);
        b
    });
    let se = std::thread::spawn(move || {
        let mut b = Vec::new();
        let _ = std::io::Read::read_to_end(&mut se, &mut b);
        b
    });
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break Some(s);
        }
        if start.elapsed() > LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let (stdout, stderr) = (so.join().unwrap(), se.join().unwrap());
    let err = String::from_utf8_lossy(&stderr);
    let shown = || format!("{:?}", case.args);
    t.cases += 1;
    let Some(status) = status else {
        t.hangs += 1;
        t.failures.push(format!("hang (> {LIMIT:?}): {}", shown()));
        return;
    };
    let code = status.code();
    match code {
        Some(c @ 0..=2) => t.by_code[c as usize] += 1,
        _ => {
            t.bad_codes += 1;
            t.failures.push(format!("exit {status}: {} {err}", shown()));
        }
    }
    if err.contains("panicked") || err.contains("RUST_BACKTRACE") {
        t.panics += 1;
        t.failures.push(format!("panic: {} {err}", shown()));
    }
    if code == Some(2) {
        let lines: Vec<&str> = err.lines().collect();
        let clear = lines.len() == 1
            && lines[0].starts_with("bwcl: error: ")
            && (lines[0].contains("--") || lines[0].contains('\''))
            && lines[0].chars().count() <= 400
            && !lines[0].chars().any(char::is_control)
            && stdout.is_empty();
        if !clear {
            t.unclear += 1;
            t.failures.push(format!(
                "unclear: {} stderr {err:?} stdout {} bytes",
                shown(),
                stdout.len()
            ));
        }
    }
    if code != Some(0) {
        let mut touched = listing(case_dir) != files_before;
        if let (Some(p), Some((bytes, mtime))) = (&case.watched, &before) {
            let m = std::fs::metadata(p).unwrap();
            touched |= std::fs::read(p).unwrap() != *bytes || m.modified().unwrap() != *mtime;
        }
        if touched {
            t.touched += 1;
            t.failures
                .push(format!("touched --out on exit {code:?}: {}", shown()));
        }
    }
}

#[test]
fn bad_command_lines_never_crash_hang_or_touch_files() {
    let env = |k: &str| std::env::var(k).ok();
    let cases: usize = env("BWCL_FUZZ_CASES")
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    let seed: u64 = match env("BWCL_FUZZ_SEED").and_then(|s| s.parse().ok()) {
        Some(s) => s,
        None if env("BWCL_FUZZ_RANDOM").is_some() => SystemTime::now()
            .duration_since(SystemTime::UNIX_EPOCH)
            .unwrap()
            .as_nanos() as u64,
        None => 20261123,
    };
    let fx = fixtures();
    let mut r = Rng(seed);
    let mut t = Tally::default();
    let start = Instant::now();
    for i in 0..cases {
        let case_dir = fx.dir.join(format!("case{i}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        let case = generate(&mut r, &fx, &case_dir);
        run_case(&case, &case_dir, &mut t);
        let _ = std::fs::remove_dir_all(&case_dir);
    }
    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "cli_fuzz: seed {seed}: {} cases in {secs:.1} s (exit 0/1/2: {}/{}/{}), {} panics, {} hangs, \
         {} unclear messages, {} touched files, {} other exit codes",
        t.cases,
        t.by_code[0],
        t.by_code[1],
        t.by_code[2],
        t.panics,
        t.hangs,
        t.unclear,
        t.touched,
        t.bad_codes
    );
    let _ = std::fs::remove_dir_all(&fx.dir);
    assert!(
        t.failures.is_empty(),
        "seed {seed}: {} failure(s):\n{}",
        t.failures.len(),
        t.failures
            .iter()
            .take(20)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}
