//! `formcam dress JOB -o OUT`: the dressing program of a grinding wheel for
//! ball-screw nut raceways, with the simulation of forming and feed control
//! (computed by `formcam_run::dress`).

use std::path::Path;

use crate::CliError;
use crate::output::emit;

/// Runs the dressing job `job`, writing its outputs into `out`; returns the
/// line to print.
pub fn run(job: &Path, out: &Path) -> Result<String, CliError> {
    let run = formcam_run::dressing_for(job, out, formcam_run::dress(job)?);
    emit(out, run)
}
