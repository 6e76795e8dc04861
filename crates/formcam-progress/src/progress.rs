//! The hook a pipeline takes, the cancellation it returns, and the hooks
//! that report nothing.

use crate::Step;

/// A run stopped because its hook asked it to; nothing was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, thiserror::Error)]
#[error("cancelled")]
pub struct Cancelled;

/// A progress and cancel hook. A pipeline calls [`Progress::checkpoint`] at
/// its phase boundaries and every few thousand items; from worker threads
/// too (hence `Sync`).
pub trait Progress: Sync {
    /// How far the run has come.
    fn report(&self, step: Step);

    /// Whether the run is to stop (false unless the hook says otherwise).
    fn cancelled(&self) -> bool {
        false
    }

    /// Reports `step`, then [`Cancelled`] when the run is to stop.
    fn checkpoint(&self, step: Step) -> Result<(), Cancelled> {
        self.report(step);
        if self.cancelled() {
            Err(Cancelled)
        } else {
            Ok(())
        }
    }
}

/// Reports nothing and never cancels.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Silent;

impl Progress for Silent {
    fn report(&self, _: Step) {}
}

/// Forwards another hook's cancel flag, not its reports: the inner phases
/// of a pipeline that reports its own outer steps (the closed loop's
/// rounds) still stop when asked.
#[derive(Clone, Copy)]
pub struct Muted<'a>(pub &'a dyn Progress);

impl Progress for Muted<'_> {
    fn report(&self, _: Step) {}

    fn cancelled(&self) -> bool {
        self.0.cancelled()
    }
}

impl std::fmt::Debug for Muted<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Muted")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Hook, Phase};

    #[test]
    fn silent_never_cancels() {
        assert_eq!(Silent.checkpoint(Step::new(Phase::Path, 0, 1)), Ok(()));
    }

    #[test]
    fn muted_forwards_the_cancel_flag_only() {
        let seen = std::sync::atomic::AtomicUsize::new(0);
        let hook = Hook::new(|_| {
            seen.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        });
        let muted = Muted(&hook);
        assert_eq!(muted.checkpoint(Step::new(Phase::Nodes, 1, 2)), Ok(()));
        hook.cancel();
        assert_eq!(
            muted.checkpoint(Step::new(Phase::Nodes, 2, 2)),
            Err(Cancelled)
        );
        assert_eq!(seen.load(std::sync::atomic::Ordering::Relaxed), 0);
    }
}
