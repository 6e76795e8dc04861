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
    /// A file given to the studio that is no job file of a kind it edits
    /// (winding, dressing, correction, closed-loop scenario: `*.toml`).
    #[error(
        "{}: not a job file the studio edits (a *.toml winding, dressing, correction or scenario job) nor a folder",
        path.display()
    )]
    NotAJob {
        /// The path given.
        path: PathBuf,
    },
    /// The port could not be listened on.
    #[error("cannot listen on 127.0.0.1:{port}: {source}")]
    Bind {
        /// The port asked for.
        port: u16,
        /// The reason.
        source: std::io::Error,
    },
    /// The thread that runs the jobs could not start, or has stopped.
    #[error("the studio's run worker: {source}")]
    Worker {
        /// The reason.
        source: std::io::Error,
    },
}
