//! The simulator's error: what could not be read, naming the file.

use std::path::PathBuf;

use formcam_files::ReadError;
use formcam_machine::MachineError;
use formcam_nc::NcError;

/// Why a program could not be simulated. Every variant names its file.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// An input could not be read (not a regular file, too large, not UTF-8).
    #[error("{}: {source}", source.path().display())]
    Read {
        /// The reason, with the path.
        #[from]
        source: ReadError,
    },
    /// The machine file is invalid (naming the link or point and the field).
    #[error("{}: {source}", path.display())]
    Machine {
        /// The machine file.
        path: PathBuf,
        /// What is wrong.
        source: MachineError,
    },
    /// The program cannot be read (naming the line and what is allowed).
    #[error("{}: {source}", path.display())]
    Program {
        /// The program file.
        path: PathBuf,
        /// What is wrong.
        source: NcError,
    },
    /// The program's extension names no dialect.
    #[error("{}: the extension does not say the dialect; allowed: {allowed}", path.display())]
    Extension {
        /// The program file.
        path: PathBuf,
        /// The extensions read.
        allowed: &'static str,
    },
    /// The program's blocks and the timeline's lines disagree in number.
    #[error("{count} blocks but {lines} program lines")]
    Lines {
        /// Blocks.
        count: usize,
        /// Lines.
        lines: usize,
    },
    /// A value the timeline needs is not finite or out of range.
    #[error("block {block} (line {line}): {what}")]
    Block {
        /// The block (1-based).
        block: usize,
        /// Its program line.
        line: usize,
        /// What is wrong.
        what: String,
    },
    /// A mesh solid of the machine could not be read (naming its file).
    #[error("{0}")]
    Mesh(#[from] formcam_machine::MeshError),
    /// The free fibre cannot be followed along the program.
    #[error("free fibre: {what}")]
    Fibre {
        /// Why.
        what: String,
    },
    /// The report could not be serialised.
    #[error("report.json: {0}")]
    Report(#[from] serde_json::Error),
}
