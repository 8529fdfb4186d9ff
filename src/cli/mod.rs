//! The `bwcl` program: argument parsing, the subcommands, and the mapping of errors to one
//! stderr line and an exit code (0 success, 1 not proved / integration failure, 2 bad input).

// pub: the Python bindings (src/python/, the crate bwcl-python) reuse its parsers, checks and
// rows
pub mod args;
pub mod band;
pub mod band_second;
pub mod classical;
pub mod commands;
pub mod compare;
pub mod fit;
pub mod identify;
pub mod input;
pub mod law_runs;
pub mod laws;
pub mod output;
pub mod precise;
pub mod profile;
pub mod progress;

use bwcl::fit::data::echo;
use clap::Parser;
use clap::error::{ContextValue, ErrorKind};
use std::io::Write;

/// Exit code of a successful run.
pub const EXIT_OK: i32 = 0;
/// Exit code when a case could not be proved or integrated (the input was fine).
pub const EXIT_FAILED: i32 = 1;
/// Exit code for bad input.
pub const EXIT_BAD_INPUT: i32 = 2;

/// Why a command stopped without output.
#[derive(Debug)]
pub enum CliError {
    /// Bad input: the message names the option and the value (exit code 2).
    Input(String),
    /// The computation failed on valid input (exit code 1).
    Failed(String),
}

impl CliError {
    fn code(&self) -> i32 {
        match self {
            CliError::Input(_) => EXIT_BAD_INPUT,
            CliError::Failed(_) => EXIT_FAILED,
        }
    }
    fn message(&self) -> &str {
        match self {
            CliError::Input(m) | CliError::Failed(m) => m,
        }
    }
}

/// Runs the program on the process's arguments and returns the exit code.
pub fn run() -> i32 {
    let cli = match args::Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return clap_error(e),
    };
    match commands::run(cli) {
        Ok(code) => code,
        Err(e) => {
            report(e.message());
            e.code()
        }
    }
}

/// Prints the one error line.
fn report(message: &str) {
    note(&format!("bwcl: error: {}", error_line(message)));
}

/// A message as the one line `report` prints after "bwcl: error: ".
pub fn error_line(message: &str) -> String {
    // a message is one line by construction, its user values escaped; fold any stray
    // whitespace and escape any stray control character to keep it so
    let line: Vec<&str> = message.split_whitespace().collect();
    line.join(" ")
        .chars()
        .map(|c| {
            if c.is_control() {
                echo(&c.to_string())
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// Writes a line to stderr; a closed or full stderr is ignored (`eprintln!` would panic, and
/// the exit code still tells what happened).
pub fn note(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// Help and version go to stdout (exit 0); a usage error becomes one line (exit 2).
fn clap_error(e: clap::Error) -> i32 {
    match e.kind() {
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // `bwcl prove` lacks its own subcommand, `bwcl` one of the commands
            let prove = std::env::args_os().nth(1).is_some_and(|a| a == "prove");
            report(if prove {
                "prove: a subcommand is needed: monotone (see prove --help)"
            } else {
                "a subcommand is needed: cor, trajectory, loop, fit, cost, profile, prove, \
                 identify, laws, classical or compare (see --help)"
            });
            EXIT_BAD_INPUT
        }
        ErrorKind::InvalidUtf8 => {
            report(&invalid_utf8());
            EXIT_BAD_INPUT
        }
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            // not e.print(): a closed stdout must not turn --help into an error
            let text = e.render().to_string();
            let _ = std::io::stdout().lock().write_all(text.as_bytes());
            e.exit_code()
        }
        _ => {
            report(&usage_message(&e));
            EXIT_BAD_INPUT
        }
    }
}

/// A usage error of clap (an unknown option, a value out of its range) as the CLI reports it.
pub fn usage_message(e: &clap::Error) -> String {
    one_line(&escape_values(e))
}

/// Which argument is not UTF-8 (clap does not say): the first such, after the option it
/// follows.
fn invalid_utf8() -> String {
    let args: Vec<std::ffi::OsString> = std::env::args_os().skip(1).collect();
    let Some(i) = args.iter().position(|a| a.to_str().is_none()) else {
        return "an argument is not valid UTF-8".into();
    };
    let shown = echo(&args[i].to_string_lossy());
    match i.checked_sub(1).and_then(|j| args[j].to_str()) {
        Some(opt) if opt.starts_with("--") => {
            format!("the value '{shown}' of {} is not valid UTF-8", echo(opt))
        }
        _ => format!("the argument '{shown}' is not valid UTF-8"),
    }
}

/// clap's message with the user's values in it (an unknown argument, an invalid value)
/// escaped and shortened: clap shows them raw and whole.
fn escape_values(e: &clap::Error) -> String {
    // the text with its styles (Display would strip every escape sequence, the user's too)
    let mut text = e.render().ansi().to_string();
    let mut values: Vec<&str> = Vec::new();
    for (_, v) in e.context() {
        match v {
            ContextValue::String(s) => values.push(s),
            ContextValue::Strings(list) => values.extend(list.iter().map(String::as_str)),
            _ => {}
        }
    }
    // longest first, so that a value containing another is replaced whole
    values.sort_by_key(|v| std::cmp::Reverse(v.len()));
    for v in values {
        if !v.is_empty() && echo(v) != v {
            text = text.replace(v, &echo(v));
        }
    }
    strip_styles(&text)
}

/// `text` without its ANSI SGR sequences (ESC [ … m), the styles clap adds.
fn strip_styles(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find("\x1b[") {
        out.push_str(&rest[..i]);
        let tail = &rest[i + 2..];
        match tail.find(|c: char| !(c.is_ascii_digit() || c == ';')) {
            Some(j) if tail[j..].starts_with('m') => rest = &tail[j + 1..],
            _ => {
                out.push_str("\x1b[");
                rest = tail;
            }
        }
    }
    out.push_str(rest);
    out
}

/// clap's multi-paragraph error as one line: the message and its tips, without the usage.
fn one_line(text: &str) -> String {
    let parts: Vec<String> = text
        .split("\n\n")
        .map(str::trim)
        .filter(|p| {
            !p.is_empty() && !p.starts_with("Usage:") && !p.starts_with("For more information")
        })
        .map(|p| p.split_whitespace().collect::<Vec<_>>().join(" "))
        .collect();
    let joined = parts.join("; ");
    let msg = joined.strip_prefix("error: ").unwrap_or(&joined);
    format!("{msg} (see --help)")
}
