//! The files a run produces, held in memory until the caller writes them,
//! and the files it read (which no output may overwrite).

use std::path::{Path, PathBuf};

/// One file of a run's result: its name inside the output folder and its
/// contents.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ResultFile {
    /// The file's name inside the output folder (may contain `/` for a
    /// subfolder, e.g. `layer-01/path.csv`).
    pub name: String,
    /// The file's contents.
    pub bytes: Vec<u8>,
}

impl ResultFile {
    /// A file named `name` holding `bytes`.
    pub fn new(name: impl Into<String>, bytes: impl Into<Vec<u8>>) -> Self {
        Self {
            name: name.into(),
            bytes: bytes.into(),
        }
    }
}

/// What a run produced: its files, in the order they are best written, and
/// the one line that says what was done.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct RunOutput {
    /// The result files.
    pub files: Vec<ResultFile>,
    /// One line for the user: what was written and the key figures.
    pub line: String,
    /// Values the job allows but that look wrong (a unit, most likely), one
    /// line each naming the field; shown before `line`.
    pub warnings: Vec<String>,
    /// Every file the run read (the job and each file it names: machine,
    /// meridian, eye curve, template, measurements, program, contour), as
    /// the run opened them; the writer refuses an output on any of them.
    pub inputs: Vec<PathBuf>,
    /// How many violations the check of the written program found (one per
    /// kind and axis, as `formcam check` counts them; its report is the
    /// run's `check.json`); `None` when no program was checked.
    pub violations: Option<usize>,
}

impl RunOutput {
    /// The file named `name`, if the run produced one.
    pub fn file(&self, name: &str) -> Option<&ResultFile> {
        self.files.iter().find(|f| f.name == name)
    }
}

/// How a result records a file it read (the job, a correction's
/// measurements and program): absolute, with `.`, `..` and symlinks
/// resolved, so that it is found from any folder the result is opened in;
/// as given where the current folder cannot be read.
pub(crate) fn recorded(path: &Path) -> String {
    formcam_files::resolve(path)
        .unwrap_or_else(|_| path.to_path_buf())
        .display()
        .to_string()
}
