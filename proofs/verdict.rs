//! The closing line every proof program prints, and its exit code.

use std::process::ExitCode;
use std::time::Instant;

/// Prints "{what} {elapsed}: {word}" (`word` when `ok`, else FAILED) and returns success or
/// failure.
pub fn finish(what: &str, t0: Instant, ok: bool, word: &str) -> ExitCode {
    println!(
        "{what} {:.2?}: {}",
        t0.elapsed(),
        if ok { word } else { "FAILED" }
    );
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
