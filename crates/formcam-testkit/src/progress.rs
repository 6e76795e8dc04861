//! A progress hook that records every report and cancels at the first one
//! its rule picks.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use formcam_progress::{Progress, Step};

/// Records every [`Step`] reported; cancelled from the first step `stop`
/// picks on.
#[derive(Debug)]
pub struct Recorder<S> {
    seen: Mutex<Vec<Step>>,
    stop: S,
    stopped: AtomicBool,
}

impl<S: Fn(&Step) -> bool + Sync> Recorder<S> {
    /// A recorder cancelling at the first step `stop` picks.
    pub fn new(stop: S) -> Self {
        Self {
            seen: Mutex::new(Vec::new()),
            stop,
            stopped: AtomicBool::new(false),
        }
    }

    /// The steps reported so far, in order.
    pub fn steps(&self) -> Vec<Step> {
        self.seen.lock().map(|s| s.clone()).unwrap_or_default()
    }
}

impl<S: Fn(&Step) -> bool + Sync> Progress for Recorder<S> {
    fn report(&self, step: Step) {
        if let Ok(mut s) = self.seen.lock() {
            s.push(step);
        }
        if (self.stop)(&step) {
            self.stopped.store(true, Ordering::Relaxed);
        }
    }

    fn cancelled(&self) -> bool {
        self.stopped.load(Ordering::Relaxed)
    }
}
