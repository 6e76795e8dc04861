//! The spindle's rule: the angle that turns the eye (or the path point) to
//! the payout point's home side.

use std::f64::consts::TAU;

use nalgebra::{Isometry3, Point3, Vector3};

use super::{joint_axis, unwrap_near};
use crate::file::SpindleFollows;
use crate::{IkFault, Machine, MachineError, Target};

/// The spindle's rule: the angle that turns the face point to the home direction.
#[derive(Debug, Clone, Copy)]
pub(super) struct Spindle {
    /// The spindle's axis.
    pub(super) axis: usize,
    /// A point on its line at home.
    pub(super) origin: Point3<f64>,
    /// Its direction at home.
    pub(super) k: Vector3<f64>,
    /// The payout point's direction from the line, across it.
    home: Vector3<f64>,
    /// What it keeps facing the payout point.
    pub(super) follows: SpindleFollows,
}

impl Spindle {
    /// The rule of `m`'s spindle, if it has one.
    pub(super) fn new(m: &Machine) -> Result<Option<Self>, MachineError> {
        let Some(axis) = m.roles.spindle else {
            return Ok(None);
        };
        let poses = m.poses(&m.home());
        let (origin, k) = joint_axis(m, &poses, m.axes[axis].link);
        let p = poses[m.points[m.roles.payout].link] * m.points[m.roles.payout].position;
        let d = p - origin;
        let perp = d - k * d.dot(&k);
        if perp.norm() < 1e-9 {
            return Err(IkFault::PayoutOnSpindleAxis.into());
        }
        Ok(Some(Self {
            axis,
            origin,
            k,
            home: perp.normalize(),
            follows: m.roles.spindle_follows,
        }))
    }

    /// The spindle value, near `prev`, that turns the face point of `t` to the
    /// home direction, given the mandrel's pose `mandrel` at spindle value `cur`.
    pub(super) fn angle(&self, t: &Target, mandrel: &Isometry3<f64>, cur: f64, prev: f64) -> f64 {
        let face = match self.follows {
            SpindleFollows::Eye => t.point,
            SpindleFollows::Path => t.path_point,
        };
        let d = mandrel * face - self.origin;
        let perp = d - self.k * d.dot(&self.k);
        let delta = self
            .k
            .dot(&perp.cross(&self.home))
            .atan2(perp.dot(&self.home));
        unwrap_near(cur + delta, prev, TAU)
    }
}
