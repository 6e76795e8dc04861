//! A phase's count shared by workers in parallel.

use std::sync::Mutex;

use crate::{Cancelled, Phase, Progress, Step};

/// Counts the finished items of one phase whose items run in parallel (a
/// program's layers): each [`Tally::add`] reports the new count, in
/// order, under a lock (held only for the report).
pub struct Tally<'a> {
    progress: &'a dyn Progress,
    phase: Phase,
    total: u64,
    done: Mutex<u64>,
}

impl<'a> Tally<'a> {
    /// A count of `total` items of `phase`, reported to `progress`.
    pub fn new(progress: &'a dyn Progress, phase: Phase, total: u64) -> Self {
        Self {
            progress,
            phase,
            total,
            done: Mutex::new(0),
        }
    }

    /// Reports the phase's start (0 done).
    pub fn start(&self) -> Result<(), Cancelled> {
        self.add(0)
    }

    /// `n` more items finished: reported, then [`Cancelled`] when the run is
    /// to stop.
    pub fn add(&self, n: u64) -> Result<(), Cancelled> {
        let mut done = self
            .done
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        *done += n;
        self.progress
            .checkpoint(Step::new(self.phase, *done, self.total))
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
        assert_eq!(tally.start(), Ok(()));
        std::thread::scope(|sc| {
            for _ in 0..8 {
                sc.spawn(|| tally.add(1));
            }
        });
        let seen = seen.into_inner().unwrap_or_default();
        assert_eq!(seen, (0..=8).collect::<Vec<u64>>());
    }
}
