//! Progress of the long proving commands on a terminal: a bar on stderr that appears once a
//! command has run for [`SHOW_AFTER`] (a quick command prints nothing extra), only when stderr
//! is a terminal (a pipe or a file gets the output alone), and is cleared before the result is
//! printed.

use bwcl::observables::band;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// How long a command runs before its progress is shown.
pub const SHOW_AFTER: Duration = Duration::from_secs(2);

/// Scale of a range's share settled (the bar counts per mille).
const PER_MILLE: u64 = 1000;

/// A progress bar that shows itself after [`SHOW_AFTER`] on a terminal.
pub struct Progress {
    bar: ProgressBar,
    /// Finished (then never shown); the lock orders showing and finishing.
    done: Arc<Mutex<bool>>,
}

impl Progress {
    fn new(len: u64, template: &str, limit: f64) -> Self {
        let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden());
        let template = template.replace("{limit}", &format!("{limit}"));
        bar.set_style(
            ProgressStyle::with_template(&template)
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        let done = Arc::new(Mutex::new(false));
        if std::io::stderr().is_terminal() {
            let (b, d) = (bar.clone(), done.clone());
            std::thread::spawn(move || {
                std::thread::sleep(SHOW_AFTER);
                if let Ok(finished) = d.lock()
                    && !*finished
                {
                    b.set_draw_target(ProgressDrawTarget::stderr());
                    b.enable_steady_tick(Duration::from_millis(250));
                }
            });
        }
        Self { bar, done }
    }

    /// Cases counted as they finish (`cor --rigorous`, `--digits`).
    pub fn cases(what: &str, n: usize, limit: f64) -> Self {
        Self::new(
            n as u64,
            &format!(
                "{what} {{bar:30}} {{pos}}/{{len}} case(s), {{elapsed}} (time limit {{limit}} s)"
            ),
            limit,
        )
    }

    /// A range of v0 settled piece by piece (`--band`, `prove monotone`).
    pub fn range(what: &str, time_limit: Option<f64>) -> Self {
        Self::new(
            PER_MILLE,
            &format!("{what} {{bar:30}} {{msg}}, {{elapsed}} (time limit {{limit}} s)"),
            super::input::time_limit(time_limit),
        )
    }

    /// One more case done.
    pub fn inc(&self) {
        self.bar.inc(1);
    }

    /// The callback of [`band::BandOptions::progress`].
    pub fn callback(&self) -> band::Progress {
        let bar = self.bar.clone();
        band::Progress(Arc::new(move |share: f64, pieces: usize| {
            bar.set_position((share * PER_MILLE as f64) as u64);
            bar.set_message(format!(
                "{:.1} % of the range settled, {pieces} pieces",
                100.0 * share
            ));
        }))
    }

    /// Sets the settled share (0..1) and the message.
    pub fn set(&self, share: f64, msg: String) {
        self.bar
            .set_position((share.clamp(0.0, 1.0) * PER_MILLE as f64) as u64);
        self.bar.set_message(msg);
    }

    /// Clears the bar (the result is printed next).
    pub fn finish(&self) {
        if let Ok(mut finished) = self.done.lock() {
            *finished = true;
            self.bar.finish_and_clear();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}
