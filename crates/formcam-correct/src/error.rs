use thiserror::Error;

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
}

impl From<formcam_nc::NcError> for CorrectError {
    fn from(e: formcam_nc::NcError) -> Self {
        Self::Program(e.to_string())
    }
}
