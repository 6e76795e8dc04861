//! A multi-layer job's files: each layer's outputs in `layer-NN/`
//! ([`LayerFiles`], made as the layers are planned), the program's axes over
//! time in `axes.csv`.

use std::path::Path;

use formcam_machine::Machine;
use formcam_program::{Assembled, WindJob, WoundLayer, WoundProgram};
use formcam_results::names::{self, EYE_SVG, PATH_SVG, SUMMARY};
use formcam_results::winding::{AXES, BAND, EYE, PATH, PROGRAM_AXES};
use serde_json::Value;

use super::csv::{axes_csv, band_csv, eye_csv, path_csv, program_axes};
use super::line::layered_line;
use super::program::program_files;
use super::summary::{layered_summary, pretty};
use crate::files::recorded;
use crate::{ResultFile, RunError, RunOutput};

/// A multi-layer job's per-layer files (`layer-NN/`), made as each layer is
/// planned, and each layer's axes summary: limits kept, the largest IK
/// residual.
#[derive(Default)]
pub(super) struct LayerFiles {
    files: Vec<ResultFile>,
    axes: Vec<(bool, f64)>,
}

impl LayerFiles {
    /// Layer `i` (0-based), planned on `m`: its files and its axes summary.
    pub(super) fn add(&mut self, m: &Machine, i: usize, l: &WoundLayer) -> Result<(), RunError> {
        let Some(w) = l.wound() else {
            self.axes.push((true, 0.0));
            return Ok(());
        };
        let files = &mut self.files;
        let title = format!("{}: {} mandrel, one pass", l.label, w.mandrel.kind());
        files.push(ResultFile::new(
            names::in_layer(i + 1, PATH.file),
            path_csv(&w.layer),
        ));
        files.push(ResultFile::new(
            names::in_layer(i + 1, PATH_SVG),
            formcam_plot::layer_svg(&title, &w.mandrel, &w.layer)?,
        ));
        if let Some(t) = &w.eye {
            files.push(ResultFile::new(
                names::in_layer(i + 1, EYE.file),
                eye_csv(t),
            ));
            files.push(ResultFile::new(
                names::in_layer(i + 1, EYE_SVG),
                formcam_plot::eye_svg(&format!("{}: payout eye over one circuit", l.label), t)?,
            ));
        }
        let axes = match &w.track {
            Some(track) => {
                files.push(ResultFile::new(
                    names::in_layer(i + 1, AXES.file),
                    axes_csv(m, w, track),
                ));
                (track.limits_ok(), track.max_residual_mm())
            }
            None => (true, 0.0),
        };
        if !m.roles.band_path.is_empty() {
            let passed = w.band_passed(m);
            files.push(ResultFile::new(
                names::in_layer(i + 1, BAND.file),
                band_csv(m, w, &passed),
            ));
        }
        self.axes.push(axes);
        Ok(())
    }
}

/// A multi-layer job (the file at `path`): each layer's outputs in
/// `layer-NN/` (made as the layers were planned), the program's axes over
/// time in `axes.csv`.
pub(super) fn layered(
    path: &Path,
    job: &WindJob,
    wound: &WoundProgram,
    program: Option<(&Assembled, Vec<u8>)>,
    each: LayerFiles,
) -> Result<RunOutput, RunError> {
    let (Some(m), Some(jm), Some((p, text))) = (&wound.machine, &job.machine, program) else {
        return Ok(RunOutput::default());
    };
    let mut files = each.files;
    let fibre = wound.fibre_length_mm();
    let mut summary = layered_summary(
        &recorded(path),
        job,
        m,
        &jm.source,
        wound,
        &each.axes,
        fibre,
    );
    let (pf, fields, program_line) = program_files(m, p, wound, text);
    summary.extend(fields);
    files.extend(pf);
    let (axes, _) = program_axes(m, p);
    files.push(ResultFile::new(PROGRAM_AXES.file, axes));
    files.push(ResultFile::new(SUMMARY, pretty(&Value::Object(summary))?));
    let line = layered_line(job, wound, m, fibre, &program_line);
    Ok(RunOutput {
        files,
        line,
        ..RunOutput::default()
    })
}
