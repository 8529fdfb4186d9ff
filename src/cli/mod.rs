//! The `bwcl` program: argument parsing, the subcommands, and the mapping of errors to one
//! stderr line and an exit code (0 success, 1 not proved / integration failure, 2 bad input).

mod args;
mod commands;
mod fit;
mod input;
mod output;

use clap::Parser;
use clap::error::ErrorKind;

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
    // a message is one line by construction; fold any stray newline to keep it so
    let line: Vec<&str> = message.split_whitespace().collect();
    eprintln!("bwcl: error: {}", line.join(" "));
}

/// Help and version go to stdout (exit 0); a usage error becomes one line (exit 2).
fn clap_error(e: clap::Error) -> i32 {
    match e.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            e.exit_code()
        }
        _ => {
            report(&one_line(&e.render().to_string()));
            EXIT_BAD_INPUT
        }
    }
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
