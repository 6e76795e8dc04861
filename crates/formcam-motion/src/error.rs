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
    Trajectory(String),
    /// The optimiser failed.
    #[error("block times: {0}")]
    Solver(String),
}
