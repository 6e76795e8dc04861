//! What the simulator needs of a planned winding job, handed on by the
//! planner so that the simulator never plans: the laminate (the mandrel
//! grown by the layers, one solid per layer, formcam-sim's [`Laminate`]),
//! each wound layer's circuit for the free fibre ([`WoundCircuit`]), and
//! both together as a [`MandrelCheck`], gathered as [`plan_each`] hands each
//! layer on ([`MandrelCheckBuilder`]) or from a job planned whole.

use std::path::Path;

use formcam_machine::MachineKind;
use formcam_progress::Silent;
use formcam_sim::{FreeFibre, Laminate, MandrelCheck, SimError, WoundCircuit, revolution_solid};

use crate::{
    EYE_CLEARANCE_MM, JobFileError, LayerBody, ProgramError, Stage, WindJob, WoundLayer,
    WoundProgram, plan_each, plan_until,
};

/// The winding job file `path`: a `.wind` document (by its extension) with
/// the eye `eye_clearance` mm over the mandrel (formcam's
/// [`EYE_CLEARANCE_MM`] when `None`), else a TOML job, its files relative
/// to its folder.
pub fn read_job(path: &Path, eye_clearance: Option<f64>) -> Result<WindJob, JobFileError> {
    read_job_from(path, path.parent().unwrap_or(Path::new("")), eye_clearance)
}

/// [`read_job`] for a job file kept apart from its folder (the copy a
/// result keeps of the job it ran): the files it names are relative to
/// `base`, the job's own folder; errors name `path`.
pub fn read_job_from(
    path: &Path,
    base: &Path,
    eye_clearance: Option<f64>,
) -> Result<WindJob, JobFileError> {
    let text = formcam_files::read_text(path)?;
    if is_wind_file(path) {
        WindJob::from_wind(&text, eye_clearance.unwrap_or(EYE_CLEARANCE_MM), &[])
    } else {
        WindJob::from_toml(&text, base)
    }
    .map_err(|e| JobFileError::job(path, e))
}

/// Whether the job file `path` is a Cyclone/FiberPath `.wind` document, by
/// its extension (in any case); every other job file is TOML.
pub fn is_wind_file(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("wind"))
}

/// The job file `path` (TOML, or a `.wind` document with formcam's eye
/// clearance) read and planned once for a check.
pub fn mandrel_check_of_file(path: &Path) -> Result<MandrelCheck, JobFileError> {
    mandrel_check(&read_job(path, None)?).map_err(|e| JobFileError::job(path, e))
}

/// The check of `job`, planned once: to its program when it writes one
/// (every layer, whole), else a single layer to its path (its thickness is
/// all the mandrel needs).
pub fn mandrel_check(job: &WindJob) -> Result<MandrelCheck, ProgramError> {
    let stage = if job.furthest_stage() == Stage::Program || job.is_layered() {
        Stage::Program
    } else {
        Stage::Path
    };
    let wound = plan_until(job, stage)?;
    let mut builder = MandrelCheckBuilder::new(job)?;
    for layer in &wound.layers {
        builder.add(layer)?;
    }
    builder.finish(job, &wound)
}

/// A [`MandrelCheck`] gathered as the planner hands on each layer
/// ([`plan_each`], which drops a layer's points after): the free fibre
/// takes each wound layer's circuit as it comes.
#[derive(Debug)]
pub struct MandrelCheckBuilder {
    fibre: Option<FreeFibre>,
}

impl MandrelCheckBuilder {
    /// For `job`: a free fibre when the job writes a program on a winder.
    pub fn new(job: &WindJob) -> Result<Self, SimError> {
        let fibre = match &job.machine {
            Some(jm)
                if job.furthest_stage() == Stage::Program
                    && jm.machine.roles.kind == MachineKind::Winder =>
            {
                Some(FreeFibre::new(jm.machine.clone())?)
            }
            _ => None,
        };
        Ok(Self { fibre })
    }

    /// The next layer in winding order, planned to its program.
    pub fn add(&mut self, layer: &WoundLayer) -> Result<(), SimError> {
        match (&mut self.fibre, wound_circuit(layer)) {
            (Some(f), Some(c)) => f.add(&c),
            _ => Ok(()),
        }
    }

    /// The check of `job` once every layer is added: the laminate from
    /// the program's layers, the fibre when the job was planned to its
    /// program.
    pub fn finish(self, job: &WindJob, wound: &WoundProgram) -> Result<MandrelCheck, ProgramError> {
        let laminate = laminate(job, &wound.layers)?;
        let fibre = self.fibre.filter(|_| wound.stage == Stage::Program);
        Ok(MandrelCheck::new(laminate, fibre))
    }
}

/// A wound layer's circuit as the free fibre takes it (`None` for a skip
/// layer).
pub fn wound_circuit(layer: &WoundLayer) -> Option<WoundCircuit<'_>> {
    let LayerBody::Wind(w) = &layer.body else {
        return None;
    };
    Some(WoundCircuit {
        label: &layer.label,
        mandrel: &w.mandrel,
        z_shift: w.z_shift,
        targets: &w.targets,
        track: w.track.as_ref(),
        circuits: w.layer.pattern.circuits,
    })
}

/// The free fibre of a job planned to its program ([`Stage::Program`]) on a
/// winder, every layer kept whole.
pub fn free_fibre(wound: &WoundProgram) -> Result<FreeFibre, SimError> {
    let machine = wound.machine.clone().ok_or_else(|| SimError::Fibre {
        what: "the job names no machine".into(),
    })?;
    let mut fibre = FreeFibre::new(machine)?;
    for c in wound.layers.iter().filter_map(wound_circuit) {
        fibre.add(&c)?;
    }
    Ok(fibre)
}

/// The laminate of `job` planned already (its `layers`, whole): each
/// layer's label and the thickness laid by its end.
pub fn laminate(job: &WindJob, layers: &[WoundLayer]) -> Result<Laminate, ProgramError> {
    let mut labels = Vec::new();
    let mut thickness = Vec::new();
    let mut laid = 0.0;
    for layer in layers {
        if let LayerBody::Wind(w) = &layer.body {
            laid = w.grown + w.thickness;
        }
        labels.push(layer.label.clone());
        thickness.push(laid);
    }
    grown_solids(job, labels, thickness)
}

/// The laminate of `job`: a single-layer job's path planned (its
/// thickness), a multi-layer job's program planned whole (each layer's
/// thickness as the planner grows the mandrel for the next).
pub fn laminate_of_job(job: &WindJob) -> Result<Laminate, ProgramError> {
    if !job.is_layered() {
        return laminate(job, &plan_until(job, Stage::Path)?.layers);
    }
    let mut labels = Vec::new();
    let mut thickness = Vec::new();
    let mut laid = 0.0;
    plan_each(
        job,
        Stage::Program,
        &Silent,
        &mut |_, layer: &WoundLayer| {
            if let LayerBody::Wind(w) = &layer.body {
                laid = w.grown + w.thickness;
            }
            labels.push(layer.label.clone());
            thickness.push(laid);
            Ok::<(), ProgramError>(())
        },
    )?;
    grown_solids(job, labels, thickness)
}

/// One solid per layer: the job's mandrel grown by `thickness` (layers of
/// one thickness share their solid).
fn grown_solids(
    job: &WindJob,
    labels: Vec<String>,
    thickness: Vec<f64>,
) -> Result<Laminate, ProgramError> {
    let read = |name: &str| {
        let p = job.base_dir.join(name);
        formcam_files::read_text(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let mut solids = Vec::with_capacity(thickness.len());
    for (k, &t) in thickness.iter().enumerate() {
        let same = k > 0 && thickness[k - 1] == t;
        let solid = match solids.last() {
            Some(before) if same => Clone::clone(before),
            _ => {
                let mandrel = job.mandrel.grown(t).and_then(|g| g.build(read))?;
                revolution_solid(&mandrel).ok_or(ProgramError::MandrelSolid { layer: k + 1 })?
            }
        };
        solids.push(solid);
    }
    Ok(Laminate {
        labels,
        solids,
        thickness,
    })
}
