//! `formcam machine show|fk`: the machine's table printed, or its key points
//! at each row of an axes CSV written.

use std::path::Path;

use crate::CliError;
use crate::output::write_files;

/// `formcam machine show MACHINE`.
pub fn show(path: &Path) -> Result<String, CliError> {
    Ok(formcam_run::machine_show(path)?)
}

/// `formcam machine fk MACHINE --axes AXES -o POINTS`: the points written,
/// the line returned.
pub fn fk(machine: &Path, axes: &Path, out: &Path) -> Result<String, CliError> {
    let run = formcam_run::machine_fk(machine, axes, out)?;
    write_files(&[(out.to_path_buf(), run.csv.as_bytes())], &run.inputs)?;
    Ok(run.line)
}
