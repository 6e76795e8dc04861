//! The studio's errors, each naming the file or the field.

use std::path::PathBuf;

/// Why the studio cannot open a folder, read or write a job, or run it.
#[derive(Debug, thiserror::Error)]
pub enum StudioError {
    /// The folder the studio was started in does not exist or is no folder.
    #[error("{}: not a folder", path.display())]
    NoFolder {
        /// The path given.
        path: PathBuf,
    },
}
