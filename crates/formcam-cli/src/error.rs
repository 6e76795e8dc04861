//! The command line's error: one line for the user, naming the file and the
//! field. Every failure exits with status 2.

use std::io;
use std::path::PathBuf;

use formcam_run::RunError;

/// Why a command failed.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The run of a job failed.
    #[error(transparent)]
    Run(#[from] RunError),
    /// `formcam check` could not read its program or machine.
    #[error(transparent)]
    Sim(#[from] formcam_sim::SimError),
    /// A result folder cannot be shown (`formcam view`).
    #[error(transparent)]
    View(#[from] formcam_view::ViewError),
    /// The studio cannot open its folder or listen (`formcam studio`).
    #[error(transparent)]
    Studio(#[from] formcam_studio::StudioError),
    /// An input file (a correction job, scenario or report) could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The reason.
        source: io::Error,
    },
    /// The outputs could not be written (an input in the way, a folder
    /// formcam did not write, another run writing there, the file system).
    #[error(transparent)]
    Write(#[from] formcam_files::WriteError),
    /// An output that would land on an input of the command.
    #[error("{}: {flag} would overwrite the input {what}; give another {flag}", path.display())]
    Refused {
        /// The output.
        path: PathBuf,
        /// The option naming it (`-o`, `--report`).
        flag: &'static str,
        /// The input (`program`, `measurements`).
        what: &'static str,
    },
    /// A result file of a correction job that would land on its input.
    #[error("{}: -o would overwrite the input {what} of {}; give another -o", path.display(), job.display())]
    RefusedByJob {
        /// The result file.
        path: PathBuf,
        /// The input (`program`, `measurements`).
        what: &'static str,
        /// The job file.
        job: PathBuf,
    },
    /// `--report` and `-o` name the same file.
    #[error("{}: --report and -o are the same file; give another --report", path.display())]
    SameReport {
        /// The report.
        path: PathBuf,
    },
    /// `formcam correct` without one of its required options.
    #[error("correct: give {flag} (see formcam correct --help)")]
    CorrectNeeds {
        /// The option and an example value.
        flag: &'static str,
    },
    /// `formcam correct JOB` without `-o`.
    #[error("correct {}: give -o OUTDIR (the folder for the corrected program, report.json and the plots)", job.display())]
    CorrectJobNeedsOutput {
        /// The job file.
        job: PathBuf,
    },
    /// `--allow` given with a TOML winding job.
    #[error("--allow: TOML jobs name the checks they accept in [checks] allow")]
    AllowForToml,
    /// `--eye-clearance` given with a TOML winding job.
    #[error("--eye-clearance: for .wind jobs; TOML jobs place the eye in [eye]")]
    EyeClearanceForToml,
}
