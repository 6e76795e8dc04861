//! `formcam check PROGRAM --machine MACHINE [--mandrel JOB] [-o report.json]`:
//! the verdict on stdout, the report written when asked.

use std::path::{Path, PathBuf};

use crate::CliError;
use crate::output::write_files;

/// Checks the program, prints the one-line verdict and writes the report to
/// `output` (never over an input); `Ok(true)` when clean. `mandrel`: the
/// winding job whose mandrel is checked too.
pub fn run(
    program: &Path,
    machine: &Path,
    mandrel: Option<PathBuf>,
    output: Option<&Path>,
) -> Result<bool, CliError> {
    let run = formcam_run::check(program, machine, mandrel.as_deref())?;
    if let Some(out) = output {
        let json = run.report_json()?;
        write_files(&[(out.to_path_buf(), json.as_bytes())], &run.inputs)?;
    }
    println!("{}", run.line);
    Ok(run.clean())
}
