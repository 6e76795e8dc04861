//! The error of a run: what failed, naming the file and the field.

use std::path::PathBuf;

use formcam_correct::CorrectError;
use formcam_machine::{AxesCsvError, MachineError};
use formcam_program::ProgramError;
use formcam_progress::Cancelled;

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
    /// A file a job names (by `field`) could not be read.
    #[error("{}: {field}: cannot read {}: {source}", job.display(), path.display())]
    ReadNamed {
        /// The job file.
        job: PathBuf,
        /// The job's field naming the file (`correct.measurements`).
        field: &'static str,
        /// The file.
        path: PathBuf,
        /// The reason.
        source: std::io::Error,
    },
    /// A job file could not be read.
    #[error("{}: cannot read the job file: {source}", path.display())]
    ReadJob {
        /// The job file.
        path: PathBuf,
        /// The reason.
        source: std::io::Error,
    },
    /// The folder of example jobs could not be listed.
    #[error("{}: cannot list the examples: {source}", path.display())]
    Examples {
        /// The folder.
        path: PathBuf,
        /// The reason.
        source: std::io::Error,
    },
    /// The folder of example jobs holds no job.
    #[error("{}: no *.toml or *.wind jobs found", path.display())]
    NoExamples {
        /// The folder.
        path: PathBuf,
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
    /// A winding job that cannot be read, planned or written.
    #[error("{}{}{source}", path.display(), if source.is_syntax() { ":" } else { ": " })]
    Wind {
        /// The job file.
        path: PathBuf,
        /// What failed.
        source: Box<formcam_program::ProgramError>,
    },
    /// The program a winding run wrote could not be read back for its
    /// check (the job file named).
    #[error("{}: checking the written program: {source}", path.display())]
    Check {
        /// The job file.
        path: PathBuf,
        /// What failed.
        source: Box<formcam_sim::SimError>,
    },
    /// A program could not be checked (`formcam check`): the program or
    /// machine file, naming it.
    #[error(transparent)]
    Sim(Box<formcam_sim::SimError>),
    /// The winding job a check takes its mandrel from (`--mandrel JOB`)
    /// could not be read or planned, naming the file.
    #[error(transparent)]
    JobFile(#[from] formcam_program::JobFileError),
    /// A machine file could not be read.
    #[error("{}: cannot read the machine file: {source}", path.display())]
    ReadMachine {
        /// The machine file.
        path: PathBuf,
        /// The reason.
        source: std::io::Error,
    },
    /// An axes file could not be read.
    #[error("{}: cannot read the axes file: {source}", path.display())]
    ReadAxes {
        /// The axes file.
        path: PathBuf,
        /// The reason.
        source: std::io::Error,
    },
    /// A machine file that is no valid machine.
    #[error("{}{}{source}", path.display(), if matches!(source, MachineError::Syntax { .. }) { ":" } else { ": " })]
    Machine {
        /// The machine file.
        path: PathBuf,
        /// What is wrong, naming the link or point and the field.
        source: MachineError,
    },
    /// An axes file that cannot be read: no header, a missing column, a
    /// cell that is no finite number.
    #[error("{}{}{source}", path.display(), if source.line().is_some() { ":" } else { ": " })]
    Axes {
        /// The axes file.
        path: PathBuf,
        /// What is wrong, naming the line and the column.
        source: AxesCsvError,
    },
    /// `summary.json` could not be written.
    #[error("summary.json: {source}")]
    Summary {
        /// The reason.
        source: serde_json::Error,
    },
    /// A correction or a closed loop that failed.
    #[error(transparent)]
    Correct(crate::correct::CorrectRunError),
    /// The run was cancelled by its progress hook; nothing is written.
    #[error(transparent)]
    Cancelled(#[from] Cancelled),
}

impl From<formcam_sim::SimError> for RunError {
    fn from(e: formcam_sim::SimError) -> Self {
        Self::Sim(Box::new(e))
    }
}

impl From<crate::correct::CorrectRunError> for RunError {
    /// A correction's error; a cancelled one is [`RunError::Cancelled`].
    fn from(e: crate::correct::CorrectRunError) -> Self {
        use crate::correct::CorrectRunError as E;
        match e {
            E::Other(CorrectError::Cancelled(c))
            | E::File {
                source: CorrectError::Cancelled(c),
                ..
            } => Self::Cancelled(c),
            e => Self::Correct(e),
        }
    }
}

impl RunError {
    /// A winding job's error, naming the job file (a cancelled run is
    /// [`RunError::Cancelled`]).
    pub fn wind(path: &std::path::Path, source: ProgramError) -> Self {
        match source {
            ProgramError::Cancelled(c) => Self::Cancelled(c),
            source => Self::Wind {
                path: path.to_path_buf(),
                source: Box::new(source),
            },
        }
    }

    /// Whether the run was cancelled by its progress hook.
    pub fn is_cancelled(&self) -> bool {
        matches!(self, Self::Cancelled(_))
    }
}
