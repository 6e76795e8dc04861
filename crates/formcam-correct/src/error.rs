use thiserror::Error;

use crate::JobField;

/// Everything that can stop a correction.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CorrectError {
    /// A measurement file that cannot be read (the message names the line and field).
    #[error("{0}")]
    Measurements(String),
    /// Sections that cannot form a grid of facets.
    #[error("{0}")]
    Sections(String),
    /// An option out of range (the message names the option and the range).
    #[error("{0}")]
    Option(String),
    /// A milling program that cannot be read or written.
    #[error("{0}")]
    Program(String),
    /// A scenario of the closed-loop check that cannot be used.
    #[error("{0}")]
    Scenario(String),
    /// A job file that cannot be read (not TOML, no `[correct]` table, an
    /// unknown or missing field).
    #[error("{0}")]
    Job(String),
    /// A setting out of range, named as the job file's field.
    #[error("{field} = {value}: {rule}")]
    Field {
        /// The setting.
        field: JobField,
        /// Its value as given.
        value: String,
        /// What is allowed.
        rule: String,
    },
    /// A measured deviation beyond the stated limit (a typing error in the
    /// report, or a part too far off to correct by re-milling).
    #[error(
        "section `{section}`, point `{point}`: deviation {deviation_mm:.3} mm is beyond the \
         limit of {limit_mm} mm"
    )]
    Deviation {
        /// The section's name.
        section: String,
        /// The point's name.
        point: String,
        /// The length of its deviation, mm.
        deviation_mm: f64,
        /// The limit, mm.
        limit_mm: f64,
    },
    /// A node displacement beyond the stated limit.
    #[error(
        "node {node}: displacement {displacement_mm:.3} mm is beyond the limit of {limit_mm} mm"
    )]
    Displacement {
        /// The node's index among the corrected nodes (0-based).
        node: usize,
        /// The length of its displacement, mm.
        displacement_mm: f64,
        /// The limit, mm.
        limit_mm: f64,
    },
    /// A program's node whose displacement is beyond the stated limit.
    #[error(
        "line {line}: the node would move by {displacement_mm:.3} mm, beyond the limit of \
         {limit_mm} mm"
    )]
    NodeDisplacement {
        /// The node's program line (1-based).
        line: usize,
        /// The length of its displacement, mm.
        displacement_mm: f64,
        /// The limit, mm.
        limit_mm: f64,
    },
    /// The run was cancelled by its progress hook.
    #[error(transparent)]
    Cancelled(#[from] formcam_progress::Cancelled),
}

impl From<formcam_nc::NcError> for CorrectError {
    fn from(e: formcam_nc::NcError) -> Self {
        Self::Program(e.to_string())
    }
}
