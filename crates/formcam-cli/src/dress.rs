//! `formcam dress JOB -o OUT`: the dressing program of a grinding wheel for
//! ball-screw nut raceways, with the simulation of forming and feed control
//! (computed by `formcam_run::dress`).

use std::path::Path;

use crate::CliError;
use crate::output::emit;
use crate::progress::with_bar;

/// Runs the dressing job `job`, writing its outputs into `out`; returns the
/// line to print.
pub fn run(job: &Path, out: &Path) -> Result<String, CliError> {
    let done = with_bar(|p| formcam_run::dress_with(job, p))?;
    let run = formcam_run::dressing_for(job, out, done);
    emit(out, run)
}
