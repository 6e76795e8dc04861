//! The whole program: every layer's blocks in order, the checks, the
//! assembly.

use formcam_machine::Machine;
use formcam_progress::{Phase, Progress, Step};

use super::{LayerBody, WoundLayer};
use crate::ProgramError;
use crate::blocks::{Assembled, LayerBlocks, assemble, nc, skip_blocks};
use crate::checks::{Violated, enforce};
use crate::job::WindJob;

/// In order: the layers' blocks (a skip starts where the layer before ends),
/// the checks, the whole program; progress reported as the assembly.
pub(super) fn whole_program(
    job: &WindJob,
    m: &Machine,
    layers: &[WoundLayer],
    own: Vec<Option<LayerBlocks>>,
    progress: &dyn Progress,
) -> Result<(Vec<LayerBlocks>, Assembled), ProgramError> {
    progress
        .checkpoint(Step::new(Phase::Assembly, 0, 1))
        .map_err(ProgramError::from)?;
    let blocks = in_order(job, m, layers, own)?;
    let violated: Vec<Violated> = blocks.iter().flat_map(|b| b.violated.clone()).collect();
    enforce(&job.allow, &violated)?;
    let program = assemble(&job.title, &job.program_name, m, &blocks, &job.motion)?;
    enforce(&job.allow, &program.violated)?;
    progress
        .checkpoint(Step::new(Phase::Assembly, 1, 1))
        .map_err(ProgramError::from)?;
    Ok((blocks, program))
}

/// Every layer's blocks in order: a skip layer turns the mandrel from where
/// the layer before ends (skips before the first winding layer from where
/// that layer starts, else from the machine's home).
fn in_order(
    job: &WindJob,
    m: &Machine,
    layers: &[WoundLayer],
    own: Vec<Option<LayerBlocks>>,
) -> Result<Vec<LayerBlocks>, ProgramError> {
    let tau = job.motion.tau_s.unwrap_or(formcam_motion::DEFAULT_TAU_S);
    let first_start: Vec<f64> = own
        .iter()
        .flatten()
        .next()
        .map(|b| b.start.clone())
        .unwrap_or_else(|| {
            m.axes
                .iter()
                .enumerate()
                .map(|(a, ax)| nc(m, a, ax.home))
                .collect()
        });
    let mut blocks: Vec<LayerBlocks> = Vec::with_capacity(layers.len());
    for (l, b) in layers.iter().zip(own) {
        match (&l.body, b) {
            (LayerBody::Skip { turn_deg }, _) => {
                let from = blocks
                    .last()
                    .and_then(|b| b.blocks.last())
                    .map_or_else(|| first_start.clone(), |b| b.0.clone());
                blocks.push(skip_blocks(&l.label, m, &from, *turn_deg, tau)?);
            }
            (LayerBody::Wind(_), Some(b)) => blocks.push(b),
            (LayerBody::Wind(_), None) => {}
        }
    }
    Ok(blocks)
}
