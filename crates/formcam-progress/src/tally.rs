//! A phase's count shared by workers in parallel.

use std::sync::Mutex;

use crate::{Cancelled, Phase, Progress, Step};

/// Counts the finished items of one phase whose items run in parallel (a
/// program's layers): the first [`Tally::start`] reports 0, each
/// [`Tally::add`] the new count, in order, under a lock (held only for the
/// report).
pub struct Tally<'a> {
    progress: &'a dyn Progress,
    phase: Phase,
    total: u64,
    /// Items done; `None` before the phase started.
    done: Mutex<Option<u64>>,
}

impl<'a> Tally<'a> {
    /// A count of `total` items of `phase`, reported to `progress`.
    pub fn new(progress: &'a dyn Progress, phase: Phase, total: u64) -> Self {
        Self {
            progress,
            phase,
            total,
            done: Mutex::new(None),
        }
    }

    /// Reports the phase's start (0 done) the first time a worker starts
    /// it; then only asks whether to stop.
    pub fn start(&self) -> Result<(), Cancelled> {
        let mut done = self.lock();
        if done.is_some() {
            return if self.progress.cancelled() {
                Err(Cancelled)
            } else {
                Ok(())
            };
        }
        *done = Some(0);
        self.progress
            .checkpoint(Step::new(self.phase, 0, self.total))
    }

    /// `n` more items finished: reported, then [`Cancelled`] when the run is
    /// to stop. A phase not started reports its start first.
    pub fn add(&self, n: u64) -> Result<(), Cancelled> {
        let mut done = self.lock();
        let before = match *done {
            Some(d) => d,
            None => {
                self.progress
                    .checkpoint(Step::new(self.phase, 0, self.total))?;
                0
            }
        };
        *done = Some(before + n);
        self.progress
            .checkpoint(Step::new(self.phase, before + n, self.total))
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Option<u64>> {
        self.done
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

impl std::fmt::Debug for Tally<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Tally")
            .field("phase", &self.phase)
            .field("total", &self.total)
            .finish_non_exhaustive()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Hook;

    #[test]
    fn workers_in_parallel_report_every_count_in_order() {
        let seen = Mutex::new(Vec::new());
        let hook = Hook::new(|s: Step| seen.lock().map(|mut v| v.push(s.done)).unwrap_or(()));
        let tally = Tally::new(&hook, Phase::Eye, 8);
        std::thread::scope(|sc| {
            for _ in 0..8 {
                sc.spawn(|| tally.start().and_then(|()| tally.add(1)));
            }
        });
        let seen = seen.into_inner().unwrap_or_default();
        assert_eq!(seen, (0..=8).collect::<Vec<u64>>());
    }
}
