//! Runs a formcam job to its result files.
//!
//! The top of the layered crates (truck's style): each process module takes
//! a job as its library crate reads it, calls that crate's pipeline, and
//! returns the files of the result (programs, tables, `summary.json`, plots)
//! with the one line a caller prints. The command line, the local server and
//! bindings call these functions and only decide where the files go.
//!
//! A result records the files it read by their absolute paths (its
//! summary's `job`, a correction report's `measurements` and `program`),
//! and keeps the job's text as it ran ([`formcam_results::names::JOB`]),
//! so that it opens from any folder, even once the job file has changed.
//!
//! Each run has a `_with` form taking a progress and cancel hook
//! ([`progress::Progress`]); a cancelled run is [`RunError::Cancelled`] and
//! returns no files.

mod check;
mod correct;
mod dress;
mod error;
mod files;
mod job;
mod machine;
mod wind;

pub use check::check;
pub use correct::{
    CorrectRunError, Corrected, History, correct, correct_job, correct_job_with, correct_simulate,
    correct_simulate_with, correct_with, output_folder, read_measurements,
};
pub use dress::{dress, dress_text, dress_text_with, dress_with, is_dress_job};
pub use error::RunError;
pub use files::{ResultFile, RunOutput};
pub use formcam_progress as progress;
pub use job::{
    JobKind, demo, demo_folder, dressing_for, run_job_file, run_job_file_with, run_job_text,
    run_job_text_with,
};
pub use machine::{MachineFk, machine_fk, machine_show, read_machine};
pub use wind::{
    ProgramCheck, wind, wind_checked_with, wind_file, wind_file_checked_with, wind_file_with,
    wind_furthest, wind_furthest_text_with, wind_furthest_with, wind_with,
};
