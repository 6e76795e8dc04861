//! The written program checked on its machine, as `formcam check --mandrel
//! JOB` would: [`Checked`], its report and time, the line's verdict and
//! `check.json`.

use std::path::Path;
use std::time::{Duration, Instant};

use formcam_program::{MachineSource, MandrelCheckBuilder, Post, WindJob, WoundProgram};
use formcam_results::names;

use crate::RunError;

/// The check of a written program: its report and how long it took.
pub(super) struct Checked {
    pub(super) report: formcam_sim::Report,
    pub(super) time: Duration,
}

impl Checked {
    /// The line's end: `; checked: clean (T ms)`, or the number of
    /// violations and the first to happen, told where it is worst.
    pub(super) fn verdict(&self) -> String {
        let ms = self.time.as_secs_f64() * 1e3;
        match self.report.violations.first() {
            None => format!("; checked: clean ({ms:.1} ms)"),
            Some(first) => {
                let k = self.report.violations.len();
                let s = if k == 1 { "" } else { "s" };
                format!("; checked: {k} violation{s} ({ms:.1} ms): {first}")
            }
        }
    }

    /// `check.json`: the report as `formcam check -o` writes it.
    pub(super) fn json(&self) -> Result<Vec<u8>, RunError> {
        let mut v = serde_json::to_vec_pretty(&self.report)
            .map_err(|source| RunError::Summary { source })?;
        v.push(b'\n');
        Ok(v)
    }
}

/// Checks the program `text` written for `job` (the job file at `path`) on
/// its machine, as `formcam check OUT/program.<ext> --machine M --mandrel
/// JOB` does: read back in the dialect of its extension, each block timed
/// by its own feed, every axis's position, velocity, jump and acceleration
/// limits, the collisions of the machine's solids (mesh files relative to
/// the machine file), the bed and the mandrel grown by the laminate, and
/// the free fibre (`mandrel`: the job's laminate and fibre, from this
/// planning). `None` for a user template's program (no reader knows its
/// text).
pub(super) fn check_program(
    path: &Path,
    out: &Path,
    job: &WindJob,
    wound: &WoundProgram,
    text: &[u8],
    mandrel: MandrelCheckBuilder,
) -> Result<Option<Checked>, RunError> {
    let (Some(m), Some(jm), Post::Dialect(_)) = (&wound.machine, &job.machine, &wound.post) else {
        return Ok(None);
    };
    let t = Instant::now();
    let program = out.join(names::program(wound.post.extension()));
    let (machine, mesh_dir) = match &jm.source {
        MachineSource::Shipped(n) => (n.clone(), None),
        MachineSource::File(f) => {
            let file = job.base_dir.join(f);
            (
                file.display().to_string(),
                file.parent().map(Path::to_path_buf),
            )
        }
    };
    let fail = |source| check_error(path, source);
    let mandrel = mandrel
        .finish(job, wound)
        .map_err(|e| RunError::wind(path, e))?;
    let text = String::from_utf8_lossy(text);
    let report = formcam_sim::check_text_with(
        &program,
        &text,
        m,
        &machine,
        mesh_dir.as_deref(),
        Some(&mandrel),
    )
    .map_err(fail)?;
    Ok(Some(Checked {
        report,
        time: t.elapsed(),
    }))
}

/// The check of the program written for the job file `path` failed.
pub(super) fn check_error(path: &Path, source: formcam_sim::SimError) -> RunError {
    RunError::Check {
        path: path.to_path_buf(),
        source: Box::new(source),
    }
}
