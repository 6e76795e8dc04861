//! What planning holds of its layers, checked against the memory budget,
//! and what a layer handed on drops.

use formcam_winding::PassPath;

use super::{LayerBody, WoundLayer};
use crate::ProgramError;
use crate::blocks::LayerBlocks;
use crate::size::{kept_bytes, mib};

/// The per-point records a planned layer holds: its path points, its eye's
/// points and its targets.
fn points_held(l: &WoundLayer) -> usize {
    l.wound().map_or(0, |w| {
        w.layer.points.len() + w.eye.as_ref().map_or(0, |e| e.points.len()) + w.targets.len()
    })
}

/// What planning holds: the most per-point records at once, and the bytes
/// the layers handed on keep (their files and blocks), checked against the
/// budget as each layer comes.
#[derive(Debug, Default)]
pub(super) struct Held {
    pub(super) peak: usize,
    blocks: u64,
    bytes: u64,
    layers: usize,
}

impl Held {
    /// A batch planned: its layers' points are held together.
    pub(super) fn batch(&mut self, batch: &[WoundLayer]) {
        self.peak = self.peak.max(batch.iter().map(points_held).sum());
    }

    /// Every layer kept whole: all their points are held.
    pub(super) fn kept_whole(&mut self, layers: &[WoundLayer]) {
        self.peak = self.peak.max(layers.iter().map(points_held).sum());
    }

    /// A layer handed on: what it keeps, against the budget.
    pub(super) fn keep(
        &mut self,
        l: &WoundLayer,
        blocks: Option<&LayerBlocks>,
        axes: u64,
        budget: u64,
    ) -> Result<(), ProgramError> {
        let n = blocks.map_or(1, |b| b.blocks.len() as u64);
        let (path, circuit) = l.wound().map_or((0, 0), |w| {
            (w.layer.points.len() as u64, w.targets.len() as u64)
        });
        self.layers += 1;
        self.blocks += n;
        self.bytes += kept_bytes(path, circuit, n, axes);
        if self.bytes > budget {
            return Err(ProgramError::OverBudget {
                layers: self.layers,
                blocks: self.blocks,
                mib: mib(self.bytes),
                budget_mib: mib(budget),
            });
        }
        Ok(())
    }
}

/// A layer handed on keeps its report, pattern and blocks: its path, eye,
/// targets and axes are dropped.
pub(super) fn shed(l: &mut WoundLayer) {
    if let LayerBody::Wind(w) = &mut l.body {
        w.eye = None;
        w.targets = Vec::new();
        w.track = None;
        w.layer.points = Vec::new();
        w.layer.thickness = Vec::new();
        w.layer.pass_path = PassPath::Points(Vec::new());
    }
}
