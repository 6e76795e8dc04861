//! What a pipeline reports: the phase it is in and how far it has come.

use std::fmt;

/// A phase of a long pipeline, as a progress display names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Phase {
    /// Winding: each layer's path, pattern and report.
    Path,
    /// Winding: each layer's payout-eye trajectory.
    Eye,
    /// Winding: each layer's machine axes (targets, inverse kinematics).
    Axes,
    /// Winding: each layer's NC blocks, cut and timed.
    Blocks,
    /// Winding: the layers joined into one program, the checks.
    Assembly,
    /// Winding: the program written by its post-processor.
    Post,
    /// Correction: the measured sections into a grid (smoothed for noise).
    Grid,
    /// Correction: the program's nodes corrected.
    Nodes,
    /// Correction: the rounds of the closed loop.
    Round,
    /// Correction: the corrections of the section-spacing study.
    Study,
    /// Dressing: the simulation of forming, step by step.
    Forming,
    /// Any run: the result files (tables, plots, summary) laid out.
    Files,
}

impl Phase {
    /// The phase's name in displays and event streams (`path`, `eye`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Self::Path => "path",
            Self::Eye => "eye",
            Self::Axes => "axes",
            Self::Blocks => "blocks",
            Self::Assembly => "assembly",
            Self::Post => "post",
            Self::Grid => "grid",
            Self::Nodes => "nodes",
            Self::Round => "round",
            Self::Study => "study",
            Self::Forming => "forming",
            Self::Files => "files",
        }
    }
}

impl fmt::Display for Phase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One report: `done` of the phase's `total` items are finished (layers,
/// nodes, steps, rounds). A phase's reports start at 0 and end at `total`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Step {
    /// The phase.
    pub phase: Phase,
    /// Items finished, `<= total`.
    pub done: u64,
    /// Items in the phase.
    pub total: u64,
}

impl Step {
    /// `done` of `total` items of `phase` (`done` capped at `total`).
    pub fn new(phase: Phase, done: u64, total: u64) -> Self {
        Self {
            phase,
            done: done.min(total),
            total,
        }
    }

    /// The fraction done, in `[0, 1]` (1 for a phase without items).
    pub fn fraction(&self) -> f64 {
        if self.total == 0 {
            1.0
        } else {
            self.done as f64 / self.total as f64
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_never_passes_its_total() {
        let s = Step::new(Phase::Nodes, 12, 10);
        assert_eq!((s.done, s.total), (10, 10));
        assert_eq!(s.fraction(), 1.0);
        assert_eq!(Step::new(Phase::Forming, 1, 4).fraction(), 0.25);
        assert_eq!(Step::new(Phase::Grid, 0, 0).fraction(), 1.0);
    }

    #[test]
    fn phases_are_named_as_displays_show_them() {
        assert_eq!(Phase::Assembly.to_string(), "assembly");
        assert_eq!(Phase::Forming.name(), "forming");
    }
}
