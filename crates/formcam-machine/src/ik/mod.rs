//! Inverse kinematics (eq. 2, docs/machines.md): axis values that put the payout point
//! on the target, `T(x) (r + l tau) = Y(x)`, with the orientation equations where
//! the machine has more than three driven axes besides the spindle.
//!
//! * The spindle turns the mandrel so that the eye (or the path point,
//!   `spindle_follows = "path"`) faces the payout point's home direction.
//! * The other axes: Levenberg–Marquardt (`levenberg-marquardt`), seeded from the
//!   previous point; residuals are the position (mm) and, scaled by
//!   [`ORIENTATION_SCALE`], the orientation equations: a winder's eye roller
//!   perpendicular to the free band (and to the band's normal when a fifth axis
//!   allows), a placement head pressing along the inward normal with its roller
//!   across the path.
//! * Lathe-type winders (spindle, carriage along it, optional radial cross feed,
//!   optional eye rotation about the cross feed) are solved in closed form.

use nalgebra::{Isometry3, Point3, Vector3};

use crate::{IkFault, Machine, MachineError, Target};

mod equations;
mod feasibility;
mod lathe;
mod residuals;
mod solver;
mod spindle;

pub use feasibility::{Issue, IssueKind};

use feasibility::feasibility;
use lathe::Lathe;
use residuals::residuals;
use solver::by_solver;
use spindle::Spindle;

/// Orientation residuals (dimensionless) are weighed as lengths of this many mm.
pub const ORIENTATION_SCALE: f64 = 100.0;

/// Which solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IkMethod {
    /// The closed form where the machine has one, else the solver.
    Auto,
    /// Levenberg–Marquardt for every machine.
    Solver,
    /// The closed form (an error where the machine has none).
    ClosedForm,
}

/// The axis values of a whole trajectory.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisTrack {
    /// Which solver produced it.
    pub closed_form: bool,
    /// Axis values, point after point (rad or mm, in the order of the
    /// machine's axes): see [`AxisTrack::rows`].
    pub values: Vec<f64>,
    /// Axes per point.
    pub width: usize,
    /// Position residual per point, mm.
    pub residual_mm: Vec<f64>,
    /// Orientation residual per point (largest of the equations' cosines).
    pub residual_orientation: Vec<f64>,
    /// Problems found.
    pub issues: Vec<Issue>,
}

impl AxisTrack {
    /// The axis values of each point.
    pub fn rows(&self) -> std::slice::ChunksExact<'_, f64> {
        self.values.chunks_exact(self.width.max(1))
    }

    /// The axis values of point `i`.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.values[i * self.width..(i + 1) * self.width]
    }

    /// Whether every axis stays within its limits.
    pub fn limits_ok(&self) -> bool {
        !self.issues.iter().any(|i| i.kind == IssueKind::Limit)
    }

    /// The largest position residual, mm.
    pub fn max_residual_mm(&self) -> f64 {
        self.residual_mm.iter().copied().fold(0.0, f64::max)
    }
}

/// Solves the axes for every target, seeded point after point.
pub fn solve(m: &Machine, targets: &[Target], method: IkMethod) -> Result<AxisTrack, MachineError> {
    let spindle = Spindle::new(m)?;
    let lathe = match method {
        IkMethod::Solver => None,
        IkMethod::Auto => Lathe::detect(m, spindle),
        IkMethod::ClosedForm => Some(Lathe::detect(m, spindle).ok_or_else(|| {
            MachineError::from(IkFault::NoClosedForm {
                machine: m.name.clone(),
            })
        })?),
    };
    let values = match &lathe {
        Some(l) => l.track(targets),
        None => by_solver(m, spindle, targets),
    };
    let mut track = AxisTrack {
        closed_form: lathe.is_some(),
        values,
        width: m.axes.len(),
        residual_mm: Vec::new(),
        residual_orientation: Vec::new(),
        issues: Vec::new(),
    };
    (track.residual_mm, track.residual_orientation) = residuals(m, targets, &track.values);
    track.issues = feasibility(m, targets, &track);
    Ok(track)
}

/// Where a joint moves: the world frame of its motion at a pose.
fn joint_axis(m: &Machine, poses: &[Isometry3<f64>], link: usize) -> (Point3<f64>, Vector3<f64>) {
    let l = &m.links[link];
    let f = match l.parent {
        Some(p) => poses[p] * l.joint.pre,
        None => l.joint.pre,
    };
    (
        Point3::from(f.translation.vector),
        f.rotation * l.joint.direction.into_inner(),
    )
}

/// `a` shifted by a multiple of `period` to lie nearest `near`.
fn unwrap_near(a: f64, near: f64, period: f64) -> f64 {
    a + period * ((near - a) / period).round()
}
