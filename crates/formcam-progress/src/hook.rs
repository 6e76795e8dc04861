//! A ready-made hook: a callback for the reports and a shared cancel flag.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::{Progress, Step};

/// Reports to a callback; cancelled once its flag is set (by
/// [`Hook::cancel`], or by whoever holds [`Hook::flag`]: a Ctrl-C handler,
/// a server's cancel request).
pub struct Hook<F> {
    flag: Arc<AtomicBool>,
    on_report: F,
}

impl<F: Fn(Step) + Sync> Hook<F> {
    /// A hook with a fresh flag, calling `on_report` with every report.
    pub fn new(on_report: F) -> Self {
        Self::with_flag(Arc::new(AtomicBool::new(false)), on_report)
    }

    /// A hook over an existing `flag`.
    pub fn with_flag(flag: Arc<AtomicBool>, on_report: F) -> Self {
        Self { flag, on_report }
    }

    /// The cancel flag, to set from elsewhere.
    pub fn flag(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.flag)
    }

    /// Asks the run to stop at its next checkpoint.
    pub fn cancel(&self) {
        self.flag.store(true, Ordering::Relaxed);
    }
}

impl<F: Fn(Step) + Sync> Progress for Hook<F> {
    fn report(&self, step: Step) {
        (self.on_report)(step);
    }

    fn cancelled(&self) -> bool {
        self.flag.load(Ordering::Relaxed)
    }
}

impl<F> std::fmt::Debug for Hook<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Hook")
            .field("cancelled", &self.flag.load(Ordering::Relaxed))
            .finish_non_exhaustive()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Cancelled, Phase};
    use std::sync::Mutex;

    #[test]
    fn the_callback_sees_each_report_and_the_flag_stops_the_run() {
        let seen = Mutex::new(Vec::new());
        let hook = Hook::new(|s| seen.lock().map(|mut v| v.push(s)).unwrap_or(()));
        let step = Step::new(Phase::Forming, 3, 8);
        assert_eq!(hook.checkpoint(step), Ok(()));
        let flag = hook.flag();
        flag.store(true, Ordering::Relaxed);
        assert!(hook.cancelled());
        assert_eq!(hook.checkpoint(step), Err(Cancelled));
        assert_eq!(seen.lock().map(|v| v.len()).unwrap_or(0), 2);
    }
}
