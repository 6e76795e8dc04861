//! One winding layer through the eye, the axes and its blocks, as far as the
//! run goes, each phase counted.

use formcam_machine::{Machine, Target, solve};
use formcam_progress::{Phase, Progress, Tally};
use formcam_winding::eye::{EyeSpec, EyeTrajectory, eye_trajectory};
use formcam_winding::job::{LayerKind, Mandrel, WindingSpec};
use formcam_winding::{Circuit, Layer};

use super::{Stage, Wound};
use crate::ProgramError;
use crate::blocks::{LayerBlocks, layer_blocks};
use crate::checks::eye_violations;
use crate::job::{JobMachine, WindJob};
use crate::targets::{placement_targets, winder_targets};

/// How far a run goes and the count of its per-layer phases, which the
/// layers report in parallel.
pub(super) struct Phases<'p> {
    stage: Stage,
    eye: Tally<'p>,
    axes: Tally<'p>,
    blocks: Tally<'p>,
}

impl<'p> Phases<'p> {
    pub(super) fn new(stage: Stage, job: &WindJob, progress: &'p dyn Progress) -> Self {
        let skip = |w: &&WindingSpec| job.is_layered() && w.kind == Some(LayerKind::Skip);
        let n = job.layers.specs().iter().filter(|w| !skip(w)).count() as u64;
        Self {
            stage,
            eye: Tally::new(progress, Phase::Eye, n),
            axes: Tally::new(progress, Phase::Axes, n),
            blocks: Tally::new(progress, Phase::Blocks, n),
        }
    }
}

/// The eye, the axes and the blocks of one winding layer, as far as `stage`.
pub(super) fn wind_layer(
    job: &WindJob,
    phases: &Phases<'_>,
    machine: Option<&JobMachine>,
    eye: Option<&EyeSpec>,
    label: &str,
    one_way: bool,
    w: &mut Wound,
) -> Result<Option<LayerBlocks>, ProgramError> {
    if let Some(spec) = eye {
        phases.eye.start()?;
        w.eye = Some(eye_trajectory(&w.mandrel, &w.layer, spec)?);
        phases.eye.add(1)?;
    }
    let Some(jm) = machine else {
        return Ok(None);
    };
    let m = &jm.machine;
    phases.axes.start()?;
    let mut targets = targets_for(m, &w.mandrel, &w.layer, w.eye.as_ref(), eye);
    for t in &mut targets {
        t.point.z += w.z_shift;
        t.path_point.z += w.z_shift;
    }
    if one_way {
        // A terminal hoop: the outgoing pass only.
        let pass = w.layer.pass_path.length();
        targets.retain(|t| t.x <= pass + 1e-9);
    }
    let track = solve(m, &targets, jm.ik).map_err(|source| ProgramError::Ik {
        layer: if job.is_layered() {
            format!("{label}: ")
        } else {
            String::new()
        },
        file: jm.source.as_str().to_string(),
        source,
    })?;
    phases.axes.add(1)?;
    let blocks = if phases.stage == Stage::Program {
        phases.blocks.start()?;
        let mut b = layer_blocks(
            label,
            m,
            &targets,
            &track,
            &job.motion,
            w.layer.pattern.circuits,
        )?;
        if let Some(t) = &w.eye {
            b.violated.extend(eye_violations(label, &t.violations));
        }
        phases.blocks.add(1)?;
        Some(b)
    } else {
        None
    };
    w.targets = targets;
    w.track = Some(track);
    Ok(blocks)
}

/// What the machine must reach over a circuit of `layer`: the eye trajectory's
/// points (winders) or the path with the roller's radius (placement heads).
fn targets_for(
    m: &Machine,
    mandrel: &Mandrel,
    layer: &Layer,
    traj: Option<&EyeTrajectory>,
    eye: Option<&EyeSpec>,
) -> Vec<Target> {
    match traj {
        Some(t) => winder_targets(mandrel, t),
        None => {
            let circuit = Circuit::new(mandrel, layer);
            let n = eye.map_or(2000, |e| e.samples - 1);
            let path: Vec<_> = circuit
                .points(n)
                .iter()
                .map(|p| (p.x, p.z, p.r, p.v, p.alpha))
                .collect();
            placement_targets(mandrel, &path, m.roles.roller_radius)
        }
    }
}
