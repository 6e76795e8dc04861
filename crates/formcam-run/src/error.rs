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
    /// A dressing job could not be run: the file (the job, or a file it
    /// names), where in it, and what is wrong (naming the field).
    #[error("{}{at}: {message}", file.display())]
    Dress {
        /// The file.
        file: PathBuf,
        /// Where in the file: `:line` or `:line:column`, or empty.
        at: String,
        /// What is wrong, naming the job field and what is allowed.
        message: String,
    },
    /// A plot could not be drawn.
    #[error(transparent)]
    Plot(#[from] formcam_plot::PlotError),
}
