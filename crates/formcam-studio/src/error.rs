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
    /// A job's text that is not TOML (so it cannot be shown as a form).
    #[error("{line}:{column}: {message}")]
    NotToml {
        /// Line (1-based).
        line: usize,
        /// Column (1-based).
        column: usize,
        /// What the parser said.
        message: String,
    },
    /// Form values that cannot be written as the job's TOML: `field` names
    /// the table or `table.field` (`layer[1].kind`, the index 0-based as in
    /// the values).
    #[error("{field}: {problem}")]
    Values {
        /// Where in the values.
        field: String,
        /// What is wrong there.
        problem: ValuesProblem,
    },
    /// A job file name that is not a plain `*.toml` name in the folder.
    #[error("{}: not a job file name: {reason}", formcam_files::quote(name))]
    JobName {
        /// The name as given.
        name: String,
        /// Why it is refused.
        reason: NameProblem,
    },
    /// The job file to replace could not be read (for its `.bak`).
    #[error("{}: cannot read the job file: {source}", path.display())]
    ReadJob {
        /// The job file.
        path: PathBuf,
        /// The reason.
        source: formcam_files::ReadError,
    },
    /// A job file (or its `.bak`, or an example's file) could not be
    /// written.
    #[error(transparent)]
    Write(#[from] formcam_files::WriteError),
    /// An example that is not bundled.
    #[error("{}: no such example (bundled: {known})", formcam_files::quote(name))]
    UnknownExample {
        /// The name asked for.
        name: String,
        /// The bundled examples' names.
        known: String,
    },
    /// An example's file that would replace a different file in the folder.
    #[error(
        "{}: exists with other content; the example {example} was not started (move the file \
         away or start it in another folder)",
        path.display()
    )]
    ExampleClash {
        /// The file in the folder.
        path: PathBuf,
        /// The example.
        example: &'static str,
    },
}

/// What is wrong with form values at a field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum ValuesProblem {
    /// The values are not one JSON object of tables.
    #[error("the values must be an object of tables")]
    NotAnObject,
    /// A table given as something other than an object.
    #[error("a table must be an object of fields")]
    NotATable,
    /// A repeated table (`[[layer]]`) given as something other than a list
    /// of objects.
    #[error("repeated tables must be a list of objects of fields")]
    NotTables,
}

/// Why a job file name is refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum NameProblem {
    /// Empty, or only `.toml`.
    #[error("the name is empty")]
    Empty,
    /// A name holding `/`, `\` or another path component.
    #[error("give a plain file name in the studio's folder (no folders, no `..`)")]
    NotPlain,
    /// A name starting with `.` (hidden, and the writer's temporaries).
    #[error("a name may not start with `.`")]
    Hidden,
    /// A name not ending `.toml`.
    #[error("job files end in `.toml`")]
    NotToml,
    /// A name with control characters.
    #[error("the name holds control characters")]
    Control,
}
