//! `formcam studio`: a job editor in the browser. A folder of job files is
//! opened on 127.0.0.1; the page draws each job as a form from the one
//! description of its kind (`formcam-schema`), checks it as the command
//! line would, runs it through `formcam-run` into a run folder of its own
//! (`DIR/runs/<time>-<job>/`) with progress and cancel, shows the result
//! with `formcam view`'s page, and saves the job back (comments and order
//! kept, the previous version as `.bak`).

mod error;
mod runs;
mod server;
mod studio;

pub use error::StudioError;
pub use runs::{
    RUN_FILE, RUN_JOB_FILE, RUNS_FOLDER, RunEntry, RunOrder, RunState, RunStatus, Runs,
};
pub use server::StudioServer;
pub use studio::{Answer, MAX_BODY_BYTES, Studio, StudioMethod};
