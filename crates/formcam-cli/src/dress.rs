//! `formcam dress JOB -o OUT`: the dressing program of a grinding wheel for
//! ball-screw nut raceways, with the simulation of forming and feed control
//! (computed by `formcam_run::dress`).

use std::path::Path;

use formcam_run::RunOutput;

use crate::CliError;
use crate::output::write_all;

/// Whether a job's top-level table is a dressing job (it has `[wheel]`).
pub fn is_job(table: &toml::Table) -> bool {
    formcam_run::is_dress_job(table)
}

/// Runs the dressing job `job`, writing its outputs into `out`; returns the
/// line to print.
pub fn run(job: &Path, out: &Path) -> Result<String, CliError> {
    write(job, formcam_run::dress(job), out)
}

/// [`run`] for a job already read.
pub fn run_text(job: &Path, text: &str, out: &Path) -> Result<String, CliError> {
    write(job, formcam_run::dress_text(job, text), out)
}

/// Shows the run's warnings, writes its files into `out` and returns its line.
fn write(
    job: &Path,
    run: Result<RunOutput, formcam_run::RunError>,
    out: &Path,
) -> Result<String, CliError> {
    let run = run.map_err(|e| CliError(e.to_string()))?;
    for w in &run.warnings {
        eprintln!("formcam: warning: {}: {w}", job.display());
    }
    let files: Vec<(String, Vec<u8>)> = run.files.into_iter().map(|f| (f.name, f.bytes)).collect();
    write_all(out, &files)?;
    Ok(format!("{} -> {}", run.line, out.display()))
}
