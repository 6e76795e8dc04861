//! What a winding job adds to a program's check (`--mandrel JOB`): its
//! mandrel grown by the laminate ([`Laminate`]) for the collision check and
//! its free fibre ([`FreeFibre`]) for the snag check, both handed on by the
//! planner from one planning of the job (formcam-program's
//! `MandrelCheckBuilder`); the simulator never plans.

use crate::{FreeFibre, Laminate};

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

    /// The laminate (the mandrel's solid while each layer is wound).
    pub fn laminate(&self) -> &Laminate {
        &self.laminate
    }

    /// The free fibre, for a job that writes a program for a winder.
    pub fn fibre(&self) -> Option<&FreeFibre> {
        self.fibre.as_ref()
    }
}
