use thiserror::Error;

/// Everything that can stop reading a machine or solving its kinematics.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MachineError {
    /// The file is not valid TOML or does not match the format.
    #[error("{line}:{column}: {message}")]
    Syntax {
        /// Line of the error (1-based; 0 when unknown).
        line: usize,
        /// Column of the error (1-based; 0 when unknown).
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A field of a link, joint, point or the `[machine]` table is wrong.
    #[error("{place}: {field}: {reason}")]
    Field {
        /// Where: `link "carriage"`, `point "payout"`, `[machine]`.
        place: String,
        /// The field's name.
        field: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// A URDF document that cannot be read.
    #[error("URDF: {0}")]
    Urdf(String),
    /// The inverse kinematics cannot be set up for this machine and target.
    #[error("inverse kinematics: {0}")]
    Ik(String),
}

impl MachineError {
    /// A field error at `place`.
    pub fn field(
        place: impl Into<String>,
        field: impl Into<String>,
        reason: impl Into<String>,
    ) -> Self {
        Self::Field {
            place: place.into(),
            field: field.into(),
            reason: reason.into(),
        }
    }
}
