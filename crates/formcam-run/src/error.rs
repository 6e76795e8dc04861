//! The error of a run: what failed, naming the file and the field.

use std::path::PathBuf;

/// Why a run failed. Every variant names the file it concerns.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// A file could not be read.
    #[error("{}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The reason.
        source: std::io::Error,
    },
    /// A plot could not be drawn.
    #[error(transparent)]
    Plot(#[from] formcam_plot::PlotError),
    /// A correction or a closed loop that failed.
    #[error(transparent)]
    Correct(#[from] crate::correct::CorrectRunError),
}
