//! The view's error: one line naming the file and the field.

use std::io;
use std::path::PathBuf;

use formcam_correct::CorrectError;
use formcam_files::ReadError;
use formcam_machine::MachineError;
use formcam_nc::NcError;
use formcam_sim::SimError;

/// Why a result folder cannot be shown.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// The page was not built when formcam was compiled.
    #[error(
        "the viewer page is not built into this formcam: run `npm ci && npm run build` in viewer/, then build formcam again"
    )]
    PageNotBuilt,
    /// A report's output inside the result folder it reports.
    #[error(
        "{}: inside the result folder {}, which belongs to the run; write the report elsewhere",
        output.display(),
        folder.display()
    )]
    ReportInResult {
        /// The output given.
        output: PathBuf,
        /// The result folder.
        folder: PathBuf,
    },
    /// The result folder is missing or no folder.
    #[error("{}: not a result folder (no such folder)", path.display())]
    NoFolder {
        /// The folder given.
        path: PathBuf,
    },
    /// A file of the result could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The reason.
        source: ReadError,
    },
    /// `summary.json` is no JSON object.
    #[error("{}: not a JSON object: {reason}", path.display())]
    Summary {
        /// The summary file.
        path: PathBuf,
        /// What the JSON reader said.
        reason: String,
    },
    /// A field the view needs is missing from `summary.json`.
    #[error("{}: no field `{field}` ({what})", path.display())]
    SummaryField {
        /// The summary file.
        path: PathBuf,
        /// The field.
        field: &'static str,
        /// What the view needs it for, or what to do.
        what: &'static str,
    },
    /// `summary.json` names a shipped machine that does not exist.
    #[error("{}: `machine_shipped` = {name}: no shipped machine of that name", path.display())]
    UnknownShipped {
        /// The summary file.
        path: PathBuf,
        /// The name, quoted.
        name: String,
    },
    /// The machine file named by the result could not be found.
    #[error(
        "{}: machine file {} not found (it is named relative to the job {}); give it with --machine",
        summary.display(),
        machine.display(),
        job.display()
    )]
    MachineNotFound {
        /// The summary file.
        summary: PathBuf,
        /// The machine file as resolved.
        machine: PathBuf,
        /// The job the summary names.
        job: PathBuf,
    },
    /// The machine file is no valid machine.
    #[error("{}: {source}", path.display())]
    Machine {
        /// The machine file (or shipped name).
        path: PathBuf,
        /// What is wrong.
        source: MachineError,
    },
    /// The program's extension names no dialect formcam reads.
    #[error(
        "{}: `program_file` = {name}: the extension names no dialect (allowed: cls, mpf, spf, nc, ngc, gcode)",
        path.display()
    )]
    ProgramDialect {
        /// The summary file.
        path: PathBuf,
        /// The program file's name, quoted.
        name: String,
    },
    /// The program could not be read back.
    #[error("{}: {source}", path.display())]
    Program {
        /// The program file.
        path: PathBuf,
        /// What the reader said (with the line).
        source: NcError,
    },
    /// The simulator cannot time the program (a block without a feed, a
    /// time that is not finite).
    #[error("{}: {source}", path.display())]
    Timeline {
        /// The program file.
        path: PathBuf,
        /// What the simulator said (with the block and line).
        source: Box<SimError>,
    },
    /// A program without motion blocks.
    #[error("{}: no motion blocks", path.display())]
    EmptyProgram {
        /// The program file.
        path: PathBuf,
    },
    /// `path.csv` lacks a column or holds a bad number.
    #[error("{}:{line}: {problem}", path.display())]
    PathTable {
        /// The path table.
        path: PathBuf,
        /// The line (1-based; 1 for the header).
        line: usize,
        /// What is wrong.
        problem: String,
    },
    /// A table of the result (`check.json`, `eye.csv`, `axes.csv`,
    /// `blocks.csv`) lacks a column or key, or holds a bad value.
    #[error("{}:{line}: {problem}", path.display())]
    Table {
        /// The file.
        path: PathBuf,
        /// The line (1-based; 1 for the header; 0 for a JSON file).
        line: usize,
        /// What is wrong.
        problem: String,
    },
    /// The folder is no result `formcam view` knows.
    #[error(
        "{}: not a result folder: no summary.json (a winding or dressing result) and no report.json naming its measurements (a correction) or its rounds (a closed-loop simulation)",
        path.display()
    )]
    UnknownResult {
        /// The folder.
        path: PathBuf,
    },
    /// A winding result without a program: its path and tables only.
    #[error(
        "{}: a winding result without a program (its summary.json names no `program_file`: the job wrote its path and tables but no NC program); formcam view plays a winding program, so it opens the result of a job that writes one (with `[machine]`, `[motion]` and `[post]`), a dressing or a correction result",
        path.display()
    )]
    NoProgram {
        /// The folder.
        path: PathBuf,
    },
    /// The folder holds results in its subfolders (as `formcam demo`
    /// writes), not one itself.
    #[error(
        "{}: not a result folder but a folder of results: view one of its subfolders ({names})",
        path.display()
    )]
    ResultsWithin {
        /// The folder.
        path: PathBuf,
        /// The subfolders holding results, by name, comma-separated.
        names: String,
    },
    /// The measurements a correction report names cannot be read.
    #[error("{}: `measurements` = {}: {source}", report.display(), measurements.display())]
    Measurements {
        /// The report naming them.
        report: PathBuf,
        /// The measurement file as the report names it.
        measurements: PathBuf,
        /// What is wrong.
        source: Box<CorrectError>,
    },
    /// The server could not listen.
    #[error("cannot listen on 127.0.0.1:{port}: {source}")]
    Bind {
        /// The port asked for.
        port: u16,
        /// The reason.
        source: io::Error,
    },
}
