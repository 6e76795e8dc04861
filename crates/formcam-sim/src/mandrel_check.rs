//! What a winding job adds to a program's check (`--mandrel JOB`): its
//! mandrel grown by the laminate ([`Laminate`]) for the collision check and
//! its free fibre ([`FreeFibre`]) for the snag check, both from one
//! planning of the job.

use std::path::Path;

use formcam_machine::MachineKind;
use formcam_program::{EYE_CLEARANCE_MM, Stage, WindJob, WoundLayer, WoundProgram, plan_until};

use crate::{FreeFibre, Laminate, SimError};

/// A winding job's part of a check: the laminate the collision check grows
/// the mandrel by, and the free fibre the snag check follows (none for a
/// job that writes no program, or one for a placement head, which has no
/// free fibre).
#[derive(Debug)]
pub struct MandrelCheck {
    laminate: Laminate,
    fibre: Option<FreeFibre>,
}

impl MandrelCheck {
    /// The parts, built elsewhere.
    pub fn new(laminate: Laminate, fibre: Option<FreeFibre>) -> Self {
        Self { laminate, fibre }
    }

    /// The winding job file `path` (TOML, or a `.wind` document with
    /// formcam's eye clearance), read and planned once.
    pub fn from_job_file(path: &Path) -> Result<Self, SimError> {
        Self::of_job(&read_job(path, None)?, path)
    }

    /// The job `job` (read from the file `path`, which errors name), planned
    /// once: to its program when it writes one (every layer, whole), else a
    /// single layer to its path (its thickness is all the mandrel needs).
    pub fn of_job(job: &WindJob, path: &Path) -> Result<Self, SimError> {
        let stage = if job.furthest_stage() == Stage::Program || job.is_layered() {
            Stage::Program
        } else {
            Stage::Path
        };
        let wound = plan_until(job, stage).map_err(|source| SimError::Job {
            path: path.to_path_buf(),
            source: Box::new(source),
        })?;
        Self::of_planned(job, &wound, path)
    }

    /// The job `job` planned already, every layer kept whole
    /// ([`plan_until`]); `path` names the job in errors.
    pub fn of_planned(job: &WindJob, wound: &WoundProgram, path: &Path) -> Result<Self, SimError> {
        let mut builder = MandrelCheckBuilder::new(job)?;
        for layer in &wound.layers {
            builder.add(layer)?;
        }
        builder.finish(job, wound, path)
    }

    /// The laminate (the mandrel's solid while each layer is wound).
    pub fn laminate(&self) -> &Laminate {
        &self.laminate
    }

    /// The free fibre, for a job that writes a program for a winder.
    pub fn fibre(&self) -> Option<&FreeFibre> {
        self.fibre.as_ref()
    }
}

/// A [`MandrelCheck`] gathered as the planner hands on each layer
/// ([`formcam_program::plan_each`], which drops a layer's points after):
/// the free fibre takes each wound layer's circuit as it comes.
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
        match &mut self.fibre {
            Some(f) => f.add(layer),
            None => Ok(()),
        }
    }

    /// The check of `job` once every layer is added: the laminate from
    /// the program's layers (`path` names the job in errors), the fibre when
    /// the job was planned to its program.
    pub fn finish(
        self,
        job: &WindJob,
        wound: &WoundProgram,
        path: &Path,
    ) -> Result<MandrelCheck, SimError> {
        let laminate = Laminate::of_planned(job, &wound.layers).map_err(|e| e.at(path))?;
        let fibre = self.fibre.filter(|_| wound.stage == Stage::Program);
        Ok(MandrelCheck::new(laminate, fibre))
    }
}

/// The winding job file `path`: a `.wind` document (by its extension) with
/// the eye `eye_clearance` mm over the mandrel (formcam's
/// [`EYE_CLEARANCE_MM`] when `None`), else a TOML job, its files relative
/// to its folder.
pub fn read_job(path: &Path, eye_clearance: Option<f64>) -> Result<WindJob, SimError> {
    let text = formcam_files::read_text(path)?;
    let base = path.parent().unwrap_or(Path::new(""));
    let wind = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("wind"));
    if wind {
        WindJob::from_wind(&text, eye_clearance.unwrap_or(EYE_CLEARANCE_MM), &[])
    } else {
        WindJob::from_toml(&text, base)
    }
    .map_err(|source| SimError::Job {
        path: path.to_path_buf(),
        source: Box::new(source),
    })
}
