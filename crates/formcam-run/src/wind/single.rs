//! A single-layer job: the layer's outputs are the job's.

use std::path::Path;

use formcam_program::{Assembled, WindJob, WoundLayer, WoundProgram};
use formcam_results::names::{EYE_SVG, PATH_SVG, SUMMARY};
use formcam_results::winding::{AXES, BAND, EYE, PATH};
use serde_json::{Value, json};

use super::csv::{axes_csv, band_csv, eye_csv, path_csv};
use super::line::{axes_line, eye_line, single_line};
use super::program::program_files;
use super::summary::{add_axes_summary, add_eye_summary, layer_summary, pretty};
use crate::files::recorded;
use crate::{ResultFile, RunError, RunOutput};

/// A single-layer job: the layer's outputs are the job's.
pub(super) fn single(
    path: &Path,
    job: &WindJob,
    wound: &WoundProgram,
    program: Option<(&Assembled, Vec<u8>)>,
) -> Result<RunOutput, RunError> {
    let Some(l) = wound.layers.first().and_then(WoundLayer::wound) else {
        return Ok(RunOutput::default());
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let layer = &l.layer;
    let mut summary = layer_summary(&recorded(path), l.mandrel.kind(), layer);
    if let Some(w) = summary.get_mut("warnings").and_then(Value::as_array_mut) {
        w.extend(wound.warnings.iter().map(|s| json!(s)));
    }
    let title = format!("{name}: {} mandrel, one pass", l.mandrel.kind());
    let mut files = vec![
        ResultFile::new(PATH.file, path_csv(layer)),
        ResultFile::new(
            PATH_SVG,
            formcam_plot::layer_svg(&title, &l.mandrel, layer)?,
        ),
    ];
    let mut more = String::new();
    if let Some(t) = &l.eye {
        add_eye_summary(&mut summary, t);
        files.push(ResultFile::new(EYE.file, eye_csv(t)));
        files.push(ResultFile::new(
            EYE_SVG,
            formcam_plot::eye_svg(&format!("{name}: payout eye over one circuit"), t)?,
        ));
        more = eye_line(t);
    }
    if let (Some(m), Some(track), Some(jm)) = (&wound.machine, &l.track, &job.machine) {
        files.push(ResultFile::new(AXES.file, axes_csv(m, l, track)));
        let passed = l.band_passed(m);
        if !m.roles.band_path.is_empty() {
            files.push(ResultFile::new(BAND.file, band_csv(m, l, &passed)));
        }
        add_axes_summary(&mut summary, m, &jm.source, track, passed.last());
        let mut program_line = String::new();
        if let Some((p, text)) = program {
            let (pf, fields, line) = program_files(m, p, wound, text);
            files.extend(pf);
            if let Some(obj) = summary.as_object_mut() {
                obj.extend(fields);
            }
            program_line = line;
        }
        more.push_str(&axes_line(m, track));
        more.push_str(&program_line);
    }
    files.push(ResultFile::new(SUMMARY, pretty(&summary)?));
    let line = single_line(&job.title, layer, &more);
    Ok(RunOutput {
        files,
        line,
        ..RunOutput::default()
    })
}
