//! The reference forward kinematics: each joint's transform, every link's
//! world pose and every key point's position for the axis values.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion};

use super::{Joint, JointKind, Machine};

impl Joint {
    /// The joint's transform for the joint value `q` (rad or mm).
    #[inline]
    pub fn transform(&self, q: f64) -> Isometry3<f64> {
        let motion = match self.kind {
            JointKind::Revolute => Isometry3::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&self.direction, q),
            ),
            JointKind::Prismatic => Isometry3::from_parts(
                Translation3::from(self.direction.into_inner() * q),
                UnitQuaternion::identity(),
            ),
            JointKind::Fixed => return self.pre * self.post,
        };
        // One side is the identity (DH: `pre`; a plain origin: `post`).
        if self.plain {
            self.pre * motion
        } else if self.dh {
            motion * self.post
        } else {
            self.pre * motion * self.post
        }
    }
}

impl Machine {
    /// World poses of every link for the axis values `q` (rad or mm, in the order
    /// of [`Machine::axes`]).
    pub fn poses(&self, q: &[f64]) -> Vec<Isometry3<f64>> {
        let mut out = Vec::with_capacity(self.links.len());
        self.poses_into(q, &mut out);
        out
    }

    /// [`Machine::poses`] into a buffer (cleared first), for repeated calls.
    pub fn poses_into(&self, q: &[f64], out: &mut Vec<Isometry3<f64>>) {
        out.clear();
        for l in &self.links {
            let v = l
                .joint
                .axis
                .map_or(l.joint.value, |a| q.get(a).copied().unwrap_or(0.0));
            let t = l.joint.transform(v);
            let pose = match l.parent {
                Some(p) => out[p] * t,
                None => t,
            };
            out.push(pose);
        }
    }

    /// World positions of every key point for the axis values `q`.
    pub fn key_points(&self, q: &[f64]) -> Vec<Point3<f64>> {
        let poses = self.poses(q);
        self.points
            .iter()
            .map(|p| poses[p.link] * p.position)
            .collect()
    }
}
