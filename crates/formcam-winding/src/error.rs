use formcam_geom::GeomError;
use thiserror::Error;

/// Everything that can stop a winding computation.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WindingError {
    /// The mandrel's geometry is invalid.
    #[error("mandrel: {0}")]
    Geometry(#[from] GeomError),
    /// A job field is missing, unknown or out of range.
    #[error("{field}: {reason}")]
    Field {
        /// Dotted name of the field, e.g. `winding.band_width`.
        field: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// The path cannot be laid as asked (it turns early, leaves the mandrel, bridges...).
    #[error("{field}: {reason}")]
    Infeasible {
        /// The field whose value makes it infeasible.
        field: String,
        /// What happens and where.
        reason: String,
    },
    /// Shooting for the slippage did not converge.
    #[error("winding.mu = \"auto\": {0}")]
    Shooting(String),
    /// The ODE integrator could not resolve the path.
    #[error("path integration failed near z = {z:.3} mm: {reason}")]
    Integration {
        /// Where it failed.
        z: f64,
        /// Why.
        reason: String,
    },
}

impl WindingError {
    /// A field error.
    pub fn field(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Field {
            field: field.into(),
            reason: reason.into(),
        }
    }

    /// An infeasibility caused by `field`.
    pub fn infeasible(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Infeasible {
            field: field.into(),
            reason: reason.into(),
        }
    }
}
