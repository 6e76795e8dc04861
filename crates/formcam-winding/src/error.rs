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
    #[error("{}.mu = \"auto\": {fault}", table(.layer))]
    Shooting {
        /// The layer (1-based) of a multi-layer job; `None`: `[winding]`.
        layer: Option<usize>,
        /// Why no slippage was found.
        fault: ShootingFault,
    },
    /// The ODE integrator could not resolve the path.
    #[error("path integration failed near z = {z:.3} mm: {reason}")]
    Integration {
        /// Where it failed.
        z: f64,
        /// Why.
        reason: String,
    },
}

/// Why shooting found no constant slippage.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ShootingFault {
    /// The root was bracketed but the path does not turn where it should.
    #[error(
        "shooting did not converge: the path turns at z = {z_turn:.6} mm instead of {z_far:.6} mm"
    )]
    NotConverged {
        /// Where the path turns, mm.
        z_turn: f64,
        /// Where it should turn, mm.
        z_far: f64,
    },
    /// No slippage within the limit reaches the far opening.
    #[error(
        "no constant slippage with |mu| <= {mu_limit} makes the path end tangent to the far polar \
         opening (closest miss {miss_mm:+.3} mm at mu = {mu}); try mu_segments or a larger mu_limit"
    )]
    NoSlippage {
        /// `winding.mu_limit`.
        mu_limit: f64,
        /// The closest miss, mm.
        miss_mm: f64,
        /// The slippage of the closest miss.
        mu: f64,
    },
    /// Neither shooting nor the minimax path (tried after it) lays the pass.
    #[error(
        "no constant slippage within mu_limit = {mu_limit} meets both polar openings, and {minimax}"
    )]
    NorMinimax {
        /// `winding.mu_limit`.
        mu_limit: f64,
        /// Why the minimax path failed.
        minimax: Box<WindingError>,
    },
}

/// The table owning `mu`: `winding` or `layer[N]`.
fn table(layer: &Option<usize>) -> String {
    match layer {
        Some(n) => format!("layer[{n}]"),
        None => "winding".to_string(),
    }
}

impl WindingError {
    /// A shooting failure of a `[winding]` job.
    pub fn shooting(fault: ShootingFault) -> Self {
        Self::Shooting { layer: None, fault }
    }

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
