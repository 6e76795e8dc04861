//! Where a run's files go: a whole folder (`-o OUT`) or single files
//! (`correct -o x.nc`, `machine fk -o points.csv`), written by
//! `formcam_files`, which checks every output against the run's inputs,
//! swaps a folder in whole and places single files atomically.

use std::path::{Path, PathBuf};

use crate::CliError;

/// Writes the files of a run as the folder `dir`, whole, never over one of
/// the run's inputs.
pub fn write_run(dir: &Path, run: &formcam_run::RunOutput) -> Result<(), CliError> {
    let files: Vec<(&str, &[u8])> = run
        .files
        .iter()
        .map(|f| (f.name.as_str(), f.bytes.as_slice()))
        .collect();
    formcam_files::write_folder(dir, &files, &run.inputs)?;
    Ok(())
}

/// Prints the run's warnings, writes its files as the folder `dir` and
/// returns its line.
pub fn emit(dir: &Path, run: formcam_run::RunOutput) -> Result<String, CliError> {
    for w in &run.warnings {
        eprintln!("formcam: warning: {w}");
    }
    write_run(dir, &run)?;
    Ok(run.line)
}

/// Places single files (path, contents) in the order given, the main file
/// last, never over one of `inputs`.
pub fn write_files(files: &[(PathBuf, &[u8])], inputs: &[PathBuf]) -> Result<(), CliError> {
    formcam_files::write_files(files, inputs)?;
    Ok(())
}
