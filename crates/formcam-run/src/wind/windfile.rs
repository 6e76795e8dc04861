//! `.wind` documents (Cyclone/FiberPath) run on the shipped X/A/B winder:
//! the job read from the document, run to its program, the eye's placement
//! added to the line.

use std::path::Path;
use std::time::Instant;

use formcam_program::{Check, Stage, WindJob};
use formcam_progress::{Progress, Silent};
use formcam_results::names;

use super::{ProgramCheck, read_job_text, run};
use crate::{ResultFile, RunError, RunOutput};

/// `formcam wind JOB.wind -o OUT`: a Cyclone/FiberPath `.wind` job on the
/// shipped X/A/B winder with its eye `eye_clearance` mm over the mandrel,
/// written for Marlin X/A/B; `allow` accepts failed checks (`slack` always).
pub fn wind_file(
    path: &Path,
    out: &Path,
    eye_clearance: f64,
    allow: &[Check],
) -> Result<RunOutput, RunError> {
    wind_file_with(path, out, eye_clearance, allow, &Silent)
}

/// [`wind_file`] reporting to `progress`.
pub fn wind_file_with(
    path: &Path,
    out: &Path,
    eye_clearance: f64,
    allow: &[Check],
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    wind_file_checked_with(path, out, eye_clearance, allow, ProgramCheck::On, progress)
}

/// [`wind_file_with`], checking the written program or not (`check`).
pub fn wind_file_checked_with(
    path: &Path,
    out: &Path,
    eye_clearance: f64,
    allow: &[Check],
    check: ProgramCheck,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let t0 = Instant::now();
    let text = read_job_text(path)?;
    let wj = WindJob::from_wind(&text, eye_clearance, allow)
        .map_err(|e| RunError::wind(path, e))?
        .named(path);
    let mut output = run(path, out, &wj, Stage::Program, check, t0, progress)?;
    output.inputs = vec![path.to_path_buf()];
    output.files.push(ResultFile::new(names::JOB_WIND, text));
    if let Some(w) = &wj.wind_file {
        // Before the check's verdict, which ends the line.
        let at = output.line.find("; checked").unwrap_or(output.line.len());
        output.line.insert_str(
            at,
            &format!(
                "; eye {:.1} mm from the axis ({:.1} mm over the mandrel)",
                w.eye_radius_mm, w.eye_clearance_mm
            ),
        );
    }
    Ok(output)
}
