//! How large a program will be, known before any layer is planned: every
//! layer's fields checked on the job's mandrel, its circuits estimated from
//! the band and the winding angle, its points from the job's samples, and the
//! bytes a run keeps (each layer's files and the program's blocks) and holds
//! while planning a batch of layers, compared with the memory budget.

use formcam_geom::Meridian;
use formcam_winding::eye::EyeSpec;
use formcam_winding::job::{LayerKind, Mandrel};
use formcam_winding::{Ends, WindingError};

use crate::ProgramError;
use crate::job::WindJob;
use crate::plan::{Stage, hoop_mandrel, in_layer_error};

/// Layers planned at once (in parallel); the layers before a batch keep only
/// their blocks and summary values while it is planned.
pub const LAYER_BATCH: usize = 8;

/// Bytes a run keeps per path point of a layer: its row of `path.csv` and its
/// share of `path.svg`.
const KEPT_PER_PATH_POINT: u64 = 200;
/// ... per point of a circuit (eye and targets): its rows of `eye.csv`,
/// `axes.csv` and `band.csv` and its share of `eye.svg`.
const KEPT_PER_CIRCUIT_POINT: u64 = 450;
/// Bytes held per path point while its layer is planned (the pass, its dense
/// output, the thickness).
const HELD_PER_PATH_POINT: u64 = 256;
/// ... per circuit point (eye point, target, axes, residuals, the fit).
const HELD_PER_CIRCUIT_POINT: u64 = 512;
/// Bytes per block and axis of the program (the layer's blocks, the joined
/// and timed blocks, the NC blocks and their text in the program,
/// `blocks.csv` and `axes.csv`), and per block beyond the axes.
const PER_BLOCK_AXIS: u64 = 128;
const PER_BLOCK: u64 = 256;
/// Circuit points per block in the estimate: the shipped examples' circuits
/// take one block per 27 to 170 points within the default tolerances, so 16
/// keeps the estimate on the large side.
const POINTS_PER_BLOCK: u64 = 16;
/// The most blocks per circuit in the estimate: a circuit's blocks follow its
/// shape within the tolerances, not its sampling (the benchmark's vessel,
/// 333 334 points a circuit, takes about 200 blocks a circuit).
const MAX_BLOCKS_PER_CIRCUIT: u64 = 1024;
/// The circuit's points of a placement head without an `[eye]`.
const PLACEMENT_POINTS: u64 = 2001;

/// A program's size as estimated before planning.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ProgramSize {
    /// The job's layers (skips too).
    pub layers: usize,
    /// The circuits of all winding layers, estimated.
    pub circuits: u64,
    /// The points planned: each winding layer's path points and its
    /// circuit's points (eye, targets, axes).
    pub points: u64,
    /// The program's blocks, estimated (0 before [`Stage::Program`]).
    pub blocks: u64,
    /// The bytes a run holds at its peak: every layer's files and the
    /// program's blocks, and a batch of layers being planned.
    pub bytes: u64,
}

impl ProgramSize {
    /// [`ProgramError::TooLarge`] when the estimate exceeds `budget` bytes.
    pub fn within(&self, budget: u64) -> Result<(), ProgramError> {
        if self.bytes > budget {
            return Err(ProgramError::TooLarge {
                layers: self.layers,
                points: self.points,
                blocks: self.blocks,
                mib: mib(self.bytes),
                budget_mib: mib(budget),
            });
        }
        Ok(())
    }
}

/// Bytes in MiB, rounded up.
pub(crate) fn mib(bytes: u64) -> u64 {
    bytes.div_ceil(1024 * 1024)
}

/// The bytes a run keeps of a planned layer until its files are written:
/// the layer's files for its `path_points` and `circuit_points`, and its
/// `blocks` on a machine of `axes` axes.
pub(crate) fn kept_bytes(path_points: u64, circuit_points: u64, blocks: u64, axes: u64) -> u64 {
    path_points * KEPT_PER_PATH_POINT
        + circuit_points * KEPT_PER_CIRCUIT_POINT
        + blocks * (PER_BLOCK + PER_BLOCK_AXIS * axes)
}

/// Every layer of `job` checked as far as its fields go on the job's mandrel
/// (an error names the layer, `layer[1000].band_width`), and the program's
/// size up to `stage` with the eye `eye` (none for a placement head or before
/// [`Stage::Eye`]); nothing is planned.
pub fn estimate(
    job: &WindJob,
    stage: Stage,
    eye: Option<&EyeSpec>,
) -> Result<ProgramSize, ProgramError> {
    let read = |name: &str| {
        let p = job.base_dir.join(name);
        formcam_files::read_text(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let layered = job.is_layered();
    let specs = job.layers.specs();
    let mandrel = job.mandrel.build(read)?;
    let axes = job
        .machine
        .as_ref()
        .map_or(0, |m| m.machine.axes.len() as u64);
    let circuit_points = match (stage, eye) {
        (Stage::Path, _) => 0,
        (_, Some(e)) => e.samples as u64,
        (Stage::Eye, None) => 0,
        (_, None) => PLACEMENT_POINTS,
    };
    let mut size = ProgramSize {
        layers: specs.len(),
        ..ProgramSize::default()
    };
    let (mut kept, mut held) = (0_u64, 0_u64);
    // The mandrel grows by about two band thicknesses a layer.
    let mut grown = 0.0;
    for (i, w) in specs.iter().enumerate() {
        let kind = w.kind.unwrap_or_default();
        if layered && kind == LayerKind::Skip {
            if w.mandrel_rotation_deg.is_none() {
                return Err(ProgramError::SkipTurnMissing { layer: i + 1 });
            }
            size.blocks += 1;
            continue;
        }
        let field = |e: WindingError| in_layer_error(layered, i + 1, e.into());
        let (on, _) = hoop_mandrel(mandrel.clone(), w).map_err(field)?;
        let spec = w.layer_spec(&on).map_err(field)?;
        // A hoop layer is one circuit: its angle follows from the band.
        let circuits = if kind == LayerKind::Hoop {
            1
        } else {
            circuits(&on, &spec.ends, spec.band_width, spec.overlap, grown)
        };
        let path_points = spec.samples as u64;
        let blocks = if stage == Stage::Program {
            circuits
                * circuit_points
                    .div_ceil(POINTS_PER_BLOCK)
                    .clamp(1, MAX_BLOCKS_PER_CIRCUIT)
        } else {
            0
        };
        size.circuits += circuits;
        size.points += path_points + circuit_points;
        size.blocks += blocks;
        kept += kept_bytes(path_points, circuit_points, blocks, axes);
        held =
            held.max(path_points * HELD_PER_PATH_POINT + circuit_points * HELD_PER_CIRCUIT_POINT);
        grown += 2.0 * spec.band_thickness;
    }
    let batch = specs.len().min(LAYER_BATCH) as u64;
    size.bytes = kept + batch * held;
    Ok(size)
}

/// The circuits that cover `m` grown by `grown` mm with bands of `width` mm
/// (`overlap` a fraction of it): the circumference where it is widest over
/// the band's width across the path, `2 pi R cos(alpha) / (w (1 - overlap))`,
/// `alpha` the tube's winding angle or the geodesic's at the widest radius,
/// `asin(r0 / R)` for the wider polar opening `r0`.
fn circuits(m: &Mandrel, ends: &Ends, width: f64, overlap: f64, grown: f64) -> u64 {
    let (a, b) = m.z_range();
    let widest = (0..=64)
        .map(|k| m.r(a + (b - a) * f64::from(k) / 64.0))
        .fold(0.0, f64::max)
        + grown;
    let alpha = match *ends {
        Ends::Tube { winding_angle } => winding_angle,
        Ends::Poles { start, end } => ((start.max(end) + grown) / widest).clamp(0.0, 1.0).asin(),
    };
    let across = width * (1.0 - overlap.clamp(0.0, 0.95));
    let n = (std::f64::consts::TAU * widest * alpha.cos() / across).ceil();
    if n.is_finite() && n >= 1.0 {
        // Saturating: a circuit count past u32 cannot be planned anyway.
        n.min(f64::from(u32::MAX)) as u64
    } else {
        1
    }
}
