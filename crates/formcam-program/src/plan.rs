//! The winding pipeline: job → layers → payout eye → machine axes → timed
//! NC blocks. One path for every job: a single-layer job is a one-layer job,
//! and the stages of `formcam wind path|eye|axes` stop it early.

use formcam_geom::Cylinder;
use formcam_machine::{AxisTrack, MachineKind, solve};
use formcam_machine::{BandPassed, Machine, Target, band_passed};
use formcam_progress::{Phase, Progress, Silent, Step, Tally};
use formcam_winding::eye::{EyeSpec, EyeTrajectory, eye_trajectory};
use formcam_winding::job::{LayerKind, Mandrel, WindingSpec};
use formcam_winding::{Circuit, Layer, PassPath, WindingError, plan_layer};
use rayon::prelude::*;

use crate::ProgramError;
use crate::blocks::{Assembled, LayerBlocks, assemble, layer_blocks, nc, skip_blocks};
use crate::checks::{Violated, enforce, eye_violations};
use crate::error::in_layer;
use crate::job::{JobMachine, Layers, Post, WindJob};
use crate::size::{LAYER_BATCH, estimate, kept_bytes, mib};
use crate::targets::{placement_targets, winder_targets};

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
    let machine = if stage >= Stage::Axes {
        Some(job.machine.as_ref().ok_or(if layered {
            ProgramError::NoMachine
        } else {
            ProgramError::MissingTable { table: "[machine]" }
        })?)
    } else {
        None
    };
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
    let specs = job.layers.specs();
    let total = specs.len();
    let phases = Phases::new(stage, job, progress);
    let axes = machine.map_or(0, |m| m.machine.axes.len() as u64);
    let mut layers: Vec<WoundLayer> = Vec::with_capacity(total);
    let mut own: Vec<Option<LayerBlocks>> = Vec::with_capacity(total);
    let mut grown = 0.0;
    let mut held = Held::default();
    for first in (0..total).step_by(LAYER_BATCH) {
        let range = first..(first + LAYER_BATCH).min(total);
        let mut batch = plan_layers(job, range, &mut grown, &mut warnings, progress)?;
        if first == 0 && with_eye && eye.is_none() {
            return Err(ProgramError::MissingTable { table: "[eye]" }.into());
        }
        let done: Vec<Result<Option<LayerBlocks>, ProgramError>> = batch
            .par_iter_mut()
            .enumerate()
            .map(|(k, l)| match &mut l.body {
                LayerBody::Skip { .. } => Ok(None),
                LayerBody::Wind(w) => {
                    wind_layer(job, &phases, machine, eye_used, &l.label, l.one_way, w)
                        .map_err(|e| in_layer_error(layered, first + k + 1, e))
                }
            })
            .collect();
        held.batch(&batch);
        for (k, (mut l, d)) in batch.into_iter().zip(done).enumerate() {
            let blocks = d?;
            each(first + k, &l)?;
            held.keep(&l, blocks.as_ref(), axes, budget)?;
            if keep == Keep::Summary {
                shed(&mut l);
            }
            layers.push(l);
            own.push(blocks);
        }
        if keep == Keep::Whole {
            held.kept_whole(&layers);
        }
    }
    let mut wound = WoundProgram {
        stage,
        layers,
        machine: machine.map(|m| m.machine.clone()),
        warnings,
        program: None,
        blocks: Vec::new(),
        post: job.post(),
        peak_points: held.peak,
    };
    if let (Stage::Program, Some(m)) = (stage, machine) {
        // 3. In order: the layers' blocks (a skip starts where the layer
        // before ends), the checks, the whole program.
        progress
            .checkpoint(Step::new(Phase::Assembly, 0, 1))
            .map_err(ProgramError::from)?;
        let blocks = in_order(job, &m.machine, &wound.layers, own)?;
        let violated: Vec<Violated> = blocks.iter().flat_map(|b| b.violated.clone()).collect();
        enforce(&job.allow, &violated)?;
        let program = assemble(
            &job.title,
            &job.program_name,
            &m.machine,
            &blocks,
            &job.motion,
        )?;
        enforce(&job.allow, &program.violated)?;
        wound.blocks = blocks;
        wound.program = Some(program);
        progress
            .checkpoint(Step::new(Phase::Assembly, 1, 1))
            .map_err(ProgramError::from)?;
    }
    Ok(wound)
}

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
struct Held {
    peak: usize,
    blocks: u64,
    bytes: u64,
    layers: usize,
}

impl Held {
    /// A batch planned: its layers' points are held together.
    fn batch(&mut self, batch: &[WoundLayer]) {
        self.peak = self.peak.max(batch.iter().map(points_held).sum());
    }

    /// Every layer kept whole: all their points are held.
    fn kept_whole(&mut self, layers: &[WoundLayer]) {
        self.peak = self.peak.max(layers.iter().map(points_held).sum());
    }

    /// A layer handed on: what it keeps, against the budget.
    fn keep(
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
fn shed(l: &mut WoundLayer) {
    if let LayerBody::Wind(w) = &mut l.body {
        w.eye = None;
        w.targets = Vec::new();
        w.track = None;
        w.layer.points = Vec::new();
        w.layer.thickness = Vec::new();
        w.layer.pass_path = PassPath::Points(Vec::new());
    }
}

/// The layers `range` of a job planned in order: skips as they are, winding
/// layers on the mandrel grown by the layers before (`grown`, mm, carried
/// from batch to batch).
fn plan_layers(
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

/// How far a run goes and the count of its per-layer phases, which the
/// layers report in parallel.
struct Phases<'p> {
    stage: Stage,
    eye: Tally<'p>,
    axes: Tally<'p>,
    blocks: Tally<'p>,
}

impl<'p> Phases<'p> {
    fn new(stage: Stage, job: &WindJob, progress: &'p dyn Progress) -> Self {
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

/// The eye, the axes and the blocks of one winding layer, as far as `stage`.
fn wind_layer(
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
