//! `formcam check PROGRAM --machine MACHINE [--mandrel JOB] [-o report.json]`:
//! the verdict on stdout, the report written when asked.

use std::path::Path;

use crate::CliError;
use crate::output::write_files;

/// Checks the program (with `mandrel`, the winding job, its free fibre
/// too), prints the one-line verdict and writes the report to `output`
/// (never over an input); `Ok(true)` when clean.
pub fn run(
    program: &Path,
    machine: &Path,
    output: Option<&Path>,
    mandrel: Option<&Path>,
) -> Result<bool, CliError> {
    let run = formcam_sim::check_files_with(program, machine, mandrel)?;
    if let Some(out) = output {
        let json = run.report_json()?;
        write_files(&[(out.to_path_buf(), json.as_bytes())], &run.inputs)?;
    }
    println!("{}", run.line);
    Ok(run.clean())
}
