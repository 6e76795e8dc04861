//! Runs a formcam job to its result files.
//!
//! The top of the layered crates (truck's style): each process module takes
//! a job as its library crate reads it, calls that crate's pipeline, and
//! returns the files of the result (programs, tables, `summary.json`, plots)
//! with the one line a caller prints. The command line, the local server and
//! bindings call these functions and only decide where the files go.

mod correct;
mod dress;
mod error;
mod files;
mod job;
mod wind;

pub use correct::{
    CorrectRunError, Corrected, History, correct, correct_job, correct_simulate, output_folder,
    read_measurements,
};
pub use dress::{dress, dress_text, is_dress_job};
pub use error::RunError;
pub use files::{ResultFile, RunOutput};
pub use job::{JobKind, demo, demo_folder, dressing_for, run_job_file, run_job_text};
pub use wind::{wind, wind_file, wind_furthest};
