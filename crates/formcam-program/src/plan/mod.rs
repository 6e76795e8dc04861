//! The winding pipeline: job → layers → payout eye → machine axes → timed
//! NC blocks. One path for every job: a single-layer job is a one-layer job,
//! and the stages of `formcam wind path|eye|axes` stop it early.
//!
//! [`plan`] reads as its phases: the checks before planning, the layers in
//! batches (`layers`: each layer's path in order; `wind`: the eye, axes and
//! blocks of a batch in parallel; `held`: what the layers handed on keep),
//! the whole program (`order`).

mod held;
mod layers;
mod order;
mod wind;

use formcam_machine::{AxisTrack, MachineKind};
use formcam_machine::{BandPassed, Machine, Target, band_passed};
use formcam_progress::{Progress, Silent};
use formcam_winding::Layer;
use formcam_winding::eye::{EyeSpec, EyeTrajectory};
use formcam_winding::job::{LayerKind, Mandrel};
use rayon::prelude::*;

use crate::ProgramError;
use crate::blocks::{Assembled, LayerBlocks};
use crate::job::{JobMachine, Post, WindJob};
use crate::size::{LAYER_BATCH, estimate};
use held::{Held, shed};
use layers::plan_layers;
use order::whole_program;
use wind::{Phases, wind_layer};

pub(crate) use layers::{hoop_mandrel, in_layer_error};

/// How far the pipeline goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Stage {
    /// The path, the pattern and the layer report.
    Path,
    /// ... and the payout eye's trajectory.
    Eye,
    /// ... and the machine's axes.
    Axes,
    /// ... and the NC program (blocks, times, the checks).
    Program,
}

/// A job planned up to a stage.
#[derive(Debug, Clone)]
pub struct WoundProgram {
    /// The stage reached.
    pub stage: Stage,
    /// The layers in winding order.
    pub layers: Vec<WoundLayer>,
    /// The machine (from [`Stage::Axes`]).
    pub machine: Option<Machine>,
    /// Remarks on implausible values, one line each naming the field.
    pub warnings: Vec<String>,
    /// The whole program (at [`Stage::Program`]).
    pub program: Option<Assembled>,
    /// Each layer's blocks (at [`Stage::Program`]).
    pub blocks: Vec<LayerBlocks>,
    /// The post-processor that writes it.
    pub post: Post,
    /// The most per-point records (path points, eye points, targets) its
    /// layers held at once while it was planned: every layer's with
    /// [`plan_until_with`], a batch's with [`plan_each`].
    pub peak_points: usize,
}

impl WoundProgram {
    /// The total fibre length of the winding layers, mm.
    pub fn fibre_length_mm(&self) -> f64 {
        self.layers
            .iter()
            .filter_map(|l| l.wound())
            .map(|w| w.layer.report.fibre_length_mm)
            .sum()
    }
}

/// One layer of a program.
#[derive(Debug, Clone)]
pub struct WoundLayer {
    /// The layer's label in messages, comments and the summary (`layer 2
    /// (helical)`; a single-layer job's is `layer 1`).
    pub label: String,
    /// The layer's kind (`helical` by default).
    pub kind: LayerKind,
    /// A hoop wound one way (a terminal hoop): its outgoing pass only.
    pub one_way: bool,
    /// What the layer does.
    pub body: LayerBody,
}

impl WoundLayer {
    /// The wound layer, unless it is a skip.
    pub fn wound(&self) -> Option<&Wound> {
        match &self.body {
            LayerBody::Wind(w) => Some(w),
            LayerBody::Skip { .. } => None,
        }
    }
}

/// What a layer does.
#[derive(Debug, Clone)]
pub enum LayerBody {
    /// The mandrel turns by `turn_deg` alone.
    Skip {
        /// The turn, degrees.
        turn_deg: f64,
    },
    /// Band is laid.
    Wind(Box<Wound>),
}

/// A wound layer through the stages reached.
#[derive(Debug, Clone)]
pub struct Wound {
    /// The mandrel it is planned on (grown by the layers before; a vessel's
    /// cylinder for a hoop).
    pub mandrel: Mandrel,
    /// Where that mandrel's `z = 0` lies on the machine's mandrel, mm.
    pub z_shift: f64,
    /// The layer: path, pattern, report.
    pub layer: Layer,
    /// How much the layers before grew the mandrel, mm.
    pub grown: f64,
    /// The layer's thickness where the mandrel is widest, mm.
    pub thickness: f64,
    /// The eye's trajectory over a circuit (winders, from [`Stage::Eye`]).
    pub eye: Option<EyeTrajectory>,
    /// What the machine reaches over a circuit (from [`Stage::Axes`]).
    pub targets: Vec<Target>,
    /// The machine's axes there (from [`Stage::Axes`]).
    pub track: Option<AxisTrack>,
}

impl Wound {
    /// The band length past each key point of the band path of `m` (the
    /// machine it was planned on), per target, mm; empty before
    /// [`Stage::Axes`]. Computed on demand: only `band.csv` and the summary
    /// read it, a program does not.
    pub fn band_passed(&self, m: &Machine) -> BandPassed {
        self.track
            .as_ref()
            .map_or_else(BandPassed::default, |track| {
                band_passed(m, &self.targets, track)
            })
    }
}

/// Plans the whole program of `job`.
pub fn plan_program(job: &WindJob) -> Result<WoundProgram, ProgramError> {
    plan_until(job, Stage::Program)
}

/// Plans `job` up to `stage`. A program that breaks a check the job does
/// not accept is refused.
pub fn plan_until(job: &WindJob, stage: Stage) -> Result<WoundProgram, ProgramError> {
    plan_until_with(job, stage, &Silent)
}

/// [`plan_until`] reporting to `progress` per layer and phase (path, eye,
/// axes, blocks, assembly); [`ProgramError::Cancelled`] when it asks to stop.
/// Every layer is kept whole (eye, targets, axes).
pub fn plan_until_with(
    job: &WindJob,
    stage: Stage,
    progress: &dyn Progress,
) -> Result<WoundProgram, ProgramError> {
    plan(job, stage, progress, Keep::Whole, &mut |_, _| Ok(()))
}

/// [`plan_until_with`] handing each layer, once planned, to `each` (its index
/// and the layer with its path, eye, targets and axes), in winding order,
/// and then dropping that per-point data: the program returned keeps each
/// layer's report, pattern and blocks, and the memory of a run stays bounded
/// by a batch of [`LAYER_BATCH`] layers, its blocks and what `each` keeps.
/// An error of `each` stops the run.
pub fn plan_each<E: From<ProgramError>>(
    job: &WindJob,
    stage: Stage,
    progress: &dyn Progress,
    each: &mut dyn FnMut(usize, &WoundLayer) -> Result<(), E>,
) -> Result<WoundProgram, E> {
    plan(job, stage, progress, Keep::Summary, each)
}

/// What the program keeps of a layer once it is handed on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Keep {
    /// Everything planned.
    Whole,
    /// The report, the pattern and the blocks.
    Summary,
}

/// The one pipeline: checks before planning, the layers in batches, the
/// assembly.
fn plan<E: From<ProgramError>>(
    job: &WindJob,
    stage: Stage,
    progress: &dyn Progress,
    keep: Keep,
    each: &mut dyn FnMut(usize, &WoundLayer) -> Result<(), E>,
) -> Result<WoundProgram, E> {
    let layered = job.is_layered();
    if layered && stage < Stage::Program {
        return Err(ProgramError::LayeredStage.into());
    }
    let machine = machine_for(job, stage, layered)?;
    let read = |name: &str| {
        let p = job.base_dir.join(name);
        formcam_files::read_text(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let mut warnings = job.warnings.clone();
    warnings.extend(job.mandrel.warnings());
    let eye = job
        .eye
        .as_ref()
        .map(|e| e.spec(read))
        .transpose()
        .map_err(ProgramError::from)?;
    let placement = machine.is_some_and(|m| m.machine.roles.kind == MachineKind::Placement);
    let with_eye = stage >= Stage::Eye && !placement;
    // 1. Before planning: every layer's fields and the program's size.
    let budget = formcam_files::max_memory_bytes();
    let eye_used = if with_eye { eye.as_ref() } else { None };
    estimate(job, stage, eye_used)?.within(budget)?;
    // 2. The layers in batches: each layer's path in order on the mandrel
    // grown by those before, then the batch's eye, axes and blocks in
    // parallel, each layer handed on in order.
    let batches = Batches {
        job,
        stage,
        progress,
        keep,
        machine,
        eye: eye_used,
        eye_missing: with_eye && eye.is_none(),
        layered,
        budget,
    };
    let (layers, own, peak_points) = batches.plan(&mut warnings, each)?;
    let mut wound = WoundProgram {
        stage,
        layers,
        machine: machine.map(|m| m.machine.clone()),
        warnings,
        program: None,
        blocks: Vec::new(),
        post: job.post(),
        peak_points,
    };
    if let (Stage::Program, Some(m)) = (stage, machine) {
        // 3. In order: the layers' blocks, the checks, the whole program.
        let (blocks, program) = whole_program(job, &m.machine, &wound.layers, own, progress)?;
        wound.blocks = blocks;
        wound.program = Some(program);
    }
    Ok(wound)
}

/// The job's machine from [`Stage::Axes`] on (an error where it names none),
/// else `None`.
fn machine_for(
    job: &WindJob,
    stage: Stage,
    layered: bool,
) -> Result<Option<&JobMachine>, ProgramError> {
    if stage >= Stage::Axes {
        Ok(Some(job.machine.as_ref().ok_or(if layered {
            ProgramError::NoMachine
        } else {
            ProgramError::MissingTable { table: "[machine]" }
        })?))
    } else {
        Ok(None)
    }
}

/// What the layers are planned with, batch after batch.
struct Batches<'a> {
    /// The job.
    job: &'a WindJob,
    /// How far the run goes.
    stage: Stage,
    /// Where progress goes.
    progress: &'a dyn Progress,
    /// What a layer handed on keeps.
    keep: Keep,
    /// The machine (from [`Stage::Axes`]).
    machine: Option<&'a JobMachine>,
    /// The eye the layers use, if any.
    eye: Option<&'a EyeSpec>,
    /// Whether the run needs an eye the job does not give.
    eye_missing: bool,
    /// Whether the job is a multi-layer one.
    layered: bool,
    /// The memory budget, bytes.
    budget: u64,
}

impl Batches<'_> {
    /// Plans every layer in batches of [`LAYER_BATCH`], each handed to `each`
    /// in order: the layers, each one's own blocks and the most per-point
    /// records held at once.
    #[allow(clippy::type_complexity)]
    fn plan<E: From<ProgramError>>(
        &self,
        warnings: &mut Vec<String>,
        each: &mut dyn FnMut(usize, &WoundLayer) -> Result<(), E>,
    ) -> Result<(Vec<WoundLayer>, Vec<Option<LayerBlocks>>, usize), E> {
        let job = self.job;
        let total = job.layers.specs().len();
        let phases = Phases::new(self.stage, job, self.progress);
        let axes = self.machine.map_or(0, |m| m.machine.axes.len() as u64);
        let mut layers: Vec<WoundLayer> = Vec::with_capacity(total);
        let mut own: Vec<Option<LayerBlocks>> = Vec::with_capacity(total);
        let mut grown = 0.0;
        let mut held = Held::default();
        for first in (0..total).step_by(LAYER_BATCH) {
            let range = first..(first + LAYER_BATCH).min(total);
            let mut batch = plan_layers(job, range, &mut grown, warnings, self.progress)?;
            if first == 0 && self.eye_missing {
                return Err(ProgramError::MissingTable { table: "[eye]" }.into());
            }
            let done = self.wind_batch(&phases, first, &mut batch);
            held.batch(&batch);
            for (k, (mut l, d)) in batch.into_iter().zip(done).enumerate() {
                let blocks = d?;
                each(first + k, &l)?;
                held.keep(&l, blocks.as_ref(), axes, self.budget)?;
                if self.keep == Keep::Summary {
                    shed(&mut l);
                }
                layers.push(l);
                own.push(blocks);
            }
            if self.keep == Keep::Whole {
                held.kept_whole(&layers);
            }
        }
        Ok((layers, own, held.peak))
    }

    /// The eye, axes and blocks of the batch starting at layer `first`, its
    /// layers in parallel.
    fn wind_batch(
        &self,
        phases: &Phases<'_>,
        first: usize,
        batch: &mut [WoundLayer],
    ) -> Vec<Result<Option<LayerBlocks>, ProgramError>> {
        batch
            .par_iter_mut()
            .enumerate()
            .map(|(k, l)| match &mut l.body {
                LayerBody::Skip { .. } => Ok(None),
                LayerBody::Wind(w) => wind_layer(
                    self.job,
                    phases,
                    self.machine,
                    self.eye,
                    &l.label,
                    l.one_way,
                    w,
                )
                .map_err(|e| in_layer_error(self.layered, first + k + 1, e)),
            })
            .collect()
    }
}
