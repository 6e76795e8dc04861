use thiserror::Error;

/// Everything that can stop cutting blocks or timing them.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MotionError {
    /// A limit or tolerance is out of range.
    #[error("{field}: {reason}")]
    Field {
        /// The field, e.g. `motion.tolerance_mm` or `axis X: v_max`.
        field: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// The trajectory's shape is inconsistent (lengths, NaN).
    #[error("trajectory: {0}")]
    Trajectory(#[from] TrajectoryFault),
    /// The optimiser failed.
    #[error("block times: {0}")]
    Solver(#[from] SolverFault),
}

/// How a trajectory handed to the block cutter is inconsistent.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum TrajectoryFault {
    /// The samples, values and tolerances do not match in number.
    #[error(
        "{samples} samples of {width} axes need {needed} values and {width} tolerances (got \
         {values} and {tolerances})"
    )]
    Shape {
        /// Samples of the parameter.
        samples: usize,
        /// Axes per sample.
        width: usize,
        /// Values needed, `samples * width`.
        needed: usize,
        /// Values given.
        values: usize,
        /// Tolerances given.
        tolerances: usize,
    },
    /// A sample is NaN or infinite.
    #[error("a sample is not finite")]
    NotFinite,
    /// The parameter does not increase from sample to sample.
    #[error("the parameter x must increase")]
    NotIncreasing,
}

/// Which part of the cone program could not be set up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetupStage {
    /// The solver's settings.
    Settings,
    /// The solver with its problem.
    Setup,
}

impl std::fmt::Display for SetupStage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            SetupStage::Settings => "settings",
            SetupStage::Setup => "setup",
        })
    }
}

/// How the block-time optimiser failed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SolverFault {
    /// The pairwise sweeps (eq. 18) went on without settling.
    #[error("the pairwise sweeps did not settle in {rounds} rounds")]
    PairwiseUnsettled {
        /// The rounds swept.
        rounds: usize,
    },
    /// The sweeps for the acceleration limits went on without settling.
    #[error("the acceleration sweeps did not settle")]
    AccelerationUnsettled,
    /// The cone program's solver refused its settings or its problem.
    #[error("{stage}: {detail}")]
    Refused {
        /// Settings or setup.
        stage: SetupStage,
        /// Clarabel's own description (its error type can be neither
        /// cloned nor compared, so it is kept as it prints).
        detail: String,
    },
    /// The cone program's solver stopped without a solution.
    #[error("the solver stopped with {0:?}")]
    Stopped(clarabel::solver::SolverStatus),
}
