//! The layers of a job planned in order on the mandrel grown by those
//! before, their warnings and errors named by layer.

use formcam_geom::Cylinder;
use formcam_progress::{Phase, Progress, Step};
use formcam_winding::job::{LayerKind, Mandrel, WindingSpec};
use formcam_winding::{WindingError, plan_layer};

use super::{LayerBody, Wound, WoundLayer};
use crate::ProgramError;
use crate::error::in_layer;
use crate::job::{Layers, WindJob};

/// The layers `range` of a job planned in order: skips as they are, winding
/// layers on the mandrel grown by the layers before (`grown`, mm, carried
/// from batch to batch).
pub(super) fn plan_layers(
    job: &WindJob,
    range: std::ops::Range<usize>,
    grown: &mut f64,
    warnings: &mut Vec<String>,
    progress: &dyn Progress,
) -> Result<Vec<WoundLayer>, ProgramError> {
    let read = |name: &str| {
        let p = job.base_dir.join(name);
        formcam_files::read_text(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let layered = matches!(job.layers, Layers::Multi(_));
    let specs = job.layers.specs();
    let mut out = Vec::with_capacity(range.len());
    let total = specs.len() as u64;
    let end = range.end as u64;
    for (i, w) in specs.iter().enumerate().take(range.end).skip(range.start) {
        progress.checkpoint(Step::new(Phase::Path, i as u64, total))?;
        let kind = w.kind.unwrap_or_default();
        let label = if layered {
            format!("layer {} ({kind})", i + 1)
        } else {
            "layer 1".to_string()
        };
        let one_way = w.one_way == Some(true);
        // Errors name the layer: `layer[2].band_width`.
        let field = |e: WindingError| in_layer_error(layered, i + 1, e.into());
        if layered && kind == LayerKind::Skip {
            let turn_deg = w
                .mandrel_rotation_deg
                .ok_or(ProgramError::SkipTurnMissing { layer: i + 1 })?;
            out.push(WoundLayer {
                label,
                kind,
                one_way,
                body: LayerBody::Skip { turn_deg },
            });
            continue;
        }
        let mandrel = job
            .mandrel
            .grown(*grown)
            .and_then(|g| g.build(read))
            .map_err(field)?;
        let (mandrel, z_shift) = hoop_mandrel(mandrel, w).map_err(field)?;
        let spec = w.layer_spec(&mandrel).map_err(field)?;
        warnings.extend(layer_warnings(layered, i + 1, w, &mandrel));
        let layer = plan_layer(&mandrel, &spec).map_err(field)?;
        // The layer's thickness where the mandrel is widest (one ply of the
        // two for a one-way hoop).
        let plies = if one_way { 0.5 } else { 1.0 };
        let thickness = plies
            * layer
                .points
                .iter()
                .zip(&layer.thickness)
                .max_by(|a, b| a.0.r.total_cmp(&b.0.r))
                .map_or(spec.band_thickness, |(_, t)| *t);
        out.push(WoundLayer {
            label,
            kind,
            one_way,
            body: LayerBody::Wind(Box::new(Wound {
                mandrel,
                z_shift,
                layer,
                grown: *grown,
                thickness,
                eye: None,
                targets: Vec::new(),
                track: None,
            })),
        });
        *grown += thickness;
    }
    progress.checkpoint(Step::new(Phase::Path, end, total))?;
    Ok(out)
}

/// A hoop layer on a vessel covers its cylinder: planned on that cylinder,
/// its targets moved to where the cylinder starts.
pub(crate) fn hoop_mandrel(
    mandrel: Mandrel,
    w: &WindingSpec,
) -> Result<(Mandrel, f64), WindingError> {
    match (&mandrel, w.kind) {
        (Mandrel::Vessel(v), Some(LayerKind::Hoop)) => {
            let (z1, z2) = v.cylinder_range();
            let cyl = Cylinder::new(v.radius(), z2 - z1)?;
            Ok((Mandrel::Cylinder(cyl), z1))
        }
        _ => Ok((mandrel, 0.0)),
    }
}

/// A layer's implausible values, named `layer[N].*` in multi-layer jobs.
fn layer_warnings(layered: bool, layer: usize, w: &WindingSpec, mandrel: &Mandrel) -> Vec<String> {
    w.warnings(mandrel)
        .into_iter()
        .map(|s| match s.strip_prefix("winding.") {
            Some(rest) if layered => format!("layer[{layer}].{rest}"),
            _ => s,
        })
        .collect()
}

/// An error of layer `layer`, its winding fields renamed in multi-layer jobs.
pub(crate) fn in_layer_error(layered: bool, layer: usize, e: ProgramError) -> ProgramError {
    match e {
        ProgramError::Winding(w) if layered => ProgramError::Winding(in_layer(layer, w)),
        other => other,
    }
}
