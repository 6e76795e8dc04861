//! The progress bar on stderr: hidden for runs under a second and when
//! stderr is not a terminal (tests and pipes see nothing), else the phase
//! and its fraction.

use std::io::IsTerminal;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use formcam_run::progress::{Progress, Step};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long a run goes before its bar shows.
const SHOW_AFTER: Duration = Duration::from_secs(1);

/// An indicatif bar fed by a run's reports.
struct Bar {
    bar: ProgressBar,
}

impl Progress for Bar {
    fn report(&self, step: Step) {
        self.bar.set_message(step.phase.name());
        self.bar.set_length(step.total);
        self.bar.set_position(step.done);
    }
}

impl Bar {
    fn new() -> Self {
        let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::hidden());
        let style =
            ProgressStyle::with_template("{msg:>8} [{bar:32}] {pos}/{len} {elapsed_precise}")
                .map(|s| s.progress_chars("=> "))
                .unwrap_or_else(|_| ProgressStyle::default_bar());
        bar.set_style(style);
        Self { bar }
    }

    /// Draws the bar on stderr from now on, if stderr is a terminal.
    fn show(&self) {
        if std::io::stderr().is_terminal() {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
            self.bar.enable_steady_tick(Duration::from_millis(200));
        }
    }
}

/// Runs `run` with a progress bar that shows once the run has taken
/// [`SHOW_AFTER`]; the bar is cleared before the run's result is returned.
pub fn with_bar<T>(run: impl FnOnce(&dyn Progress) -> T) -> T {
    let bar = Bar::new();
    let (finished, wait) = mpsc::channel::<()>();
    let bar = &bar;
    let out = std::thread::scope(|s| {
        s.spawn(move || {
            if wait.recv_timeout(SHOW_AFTER) == Err(RecvTimeoutError::Timeout) {
                bar.show();
            }
        });
        let out = run(bar);
        drop(finished);
        out
    });
    bar.bar.finish_and_clear();
    out
}
