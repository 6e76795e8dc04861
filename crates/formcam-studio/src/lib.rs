//! `formcam studio`: a job editor in the browser. A folder of job files is
//! opened on 127.0.0.1; the page draws each job as a form from the one
//! description of its kind (`formcam-schema`), checks it as the command
//! line would, runs it through `formcam-run` into a run folder of its own
//! (`DIR/runs/<time>-<job>/`) with progress and cancel, shows the result
//! with `formcam view`'s page, and saves the job back (comments and order
//! kept, the previous version as `.bak`).

mod check;
mod error;
mod examples;
mod runs;
mod save;
mod server;
mod studio;
mod values;

pub use check::{Applied, FieldError, apply_job, check_job};
pub use error::{NameProblem, StudioError, ValuesProblem};
pub use examples::{Example, example, examples, start_example};
pub use formcam_run::JobKind;
pub use runs::{RUN_FILE, RUNS_FOLDER, RunEntry, RunOrder, RunState, RunStatus, Runs};
pub use save::{backup_path, job_path, save_job, save_job_with};
pub use server::StudioServer;
pub use studio::{Answer, MAX_BODY_BYTES, Studio, StudioMethod};
pub use values::{apply_values, apply_values_as, values_of};
