//! A link's joint checked: its type, its numbers in the joint's unit, its
//! limits, its axis when driven, its value and its placement.

use nalgebra::Isometry3;

use super::axis::axis;
use super::numbers::{finite, positive};
use super::placement::{Placement, placement};
use crate::MachineError;
use crate::file::{JointType, LinkSpec};
use crate::machine::{Axis, Joint, JointKind};

/// A number of a link spec as written: its field's name and its value.
pub(super) type Written = (&'static str, Option<f64>);

/// A joint's numbers in its unit (degrees or mm), each with its field's name.
pub(super) struct Fields<'a> {
    /// Lower limit.
    pub(super) min: Written,
    /// Upper limit.
    pub(super) max: Written,
    /// Velocity limit, per minute.
    pub(super) v_max: Written,
    /// Velocity-jump limit, per minute.
    pub(super) dv_max: Written,
    /// The value of an undriven joint.
    pub(super) value: Written,
    /// The home value of a driven joint.
    pub(super) home: Written,
    /// Acceleration limit, per s².
    pub(super) a_max: Written,
    /// The factor from the unit to radians or mm.
    scale: f64,
    /// Where the errors are.
    pub(super) place: &'a str,
}

/// A joint's limits, rad or mm, and rates per second.
pub(super) struct Limits {
    /// Lower limit (`-inf` when not given).
    pub(super) min: f64,
    /// Upper limit (`inf` when not given).
    pub(super) max: f64,
    /// Velocity limit (`inf` when not given).
    pub(super) v_max: f64,
    /// Velocity-jump limit (`inf` when not given).
    pub(super) dv_max: f64,
    /// Acceleration limit (`inf` when not given).
    pub(super) a_max: f64,
}

/// The joint of a link spec, with its axis when driven (its index still unset).
pub(super) fn joint(l: &LinkSpec, place: &str) -> Result<(Joint, Option<Axis>), MachineError> {
    let kind = match l.joint.unwrap_or(JointType::Fixed) {
        JointType::Revolute => JointKind::Revolute,
        JointType::Prismatic => JointKind::Prismatic,
        JointType::Fixed => JointKind::Fixed,
    };
    let fields = Fields::of(l, kind, place)?;
    let limits = fields.limits()?;
    let axis = axis(l, kind, &fields, &limits)?;
    let value = fields.scaled(fields.value)?.unwrap_or(0.0);
    let Placement {
        pre,
        direction,
        post,
    } = placement(l, place)?;
    Ok((
        Joint {
            kind,
            pre,
            direction,
            post,
            axis: None,
            value,
            plain: post == Isometry3::identity(),
            dh: pre == Isometry3::identity(),
        },
        axis,
    ))
}

impl<'a> Fields<'a> {
    /// The fields of `l` in the unit of its joint `kind`; none given in the
    /// other unit (a fixed joint: none at all).
    fn of(l: &LinkSpec, kind: JointKind, place: &'a str) -> Result<Self, MachineError> {
        let deg = [
            ("min_deg", l.min_deg),
            ("max_deg", l.max_deg),
            ("v_max_deg_min", l.v_max_deg_min),
            ("dv_max_deg_min", l.dv_max_deg_min),
            ("value_deg", l.value_deg),
            ("home_deg", l.home_deg),
            ("a_max_deg_s2", l.a_max_deg_s2),
        ];
        let mm = [
            ("min_mm", l.min_mm),
            ("max_mm", l.max_mm),
            ("v_max_mm_min", l.v_max_mm_min),
            ("dv_max_mm_min", l.dv_max_mm_min),
            ("value_mm", l.value_mm),
            ("home_mm", l.home_mm),
            ("a_max_mm_s2", l.a_max_mm_s2),
        ];
        let (wrong, own, why): (Vec<_>, [Written; 7], &str) = match kind {
            JointKind::Revolute => (mm.to_vec(), deg, "a revolute joint takes degrees (*_deg)"),
            JointKind::Prismatic => (deg.to_vec(), mm, "a prismatic joint takes mm (*_mm)"),
            JointKind::Fixed => (
                [deg, mm].concat(),
                deg,
                "a fixed joint has no limits or value",
            ),
        };
        if let Some((field, _)) = wrong.iter().find(|(_, v)| v.is_some()) {
            return Err(MachineError::field(place, *field, why));
        }
        // Degrees and per-minute rates become radians and per-second rates.
        let scale = if kind == JointKind::Revolute {
            1f64.to_radians()
        } else {
            1.0
        };
        let [min, max, v_max, dv_max, value, home, a_max] = own;
        Ok(Self {
            min,
            max,
            v_max,
            dv_max,
            value,
            home,
            a_max,
            scale,
            place,
        })
    }

    /// The field's value in rad or mm, when given; finite.
    pub(super) fn scaled(&self, (field, v): Written) -> Result<Option<f64>, MachineError> {
        v.map(|v| finite(v, self.place, field).map(|v| v * self.scale))
            .transpose()
    }

    /// The limits: the lower not above the upper, the rates positive.
    fn limits(&self) -> Result<Limits, MachineError> {
        let min = self.scaled(self.min)?.unwrap_or(f64::NEG_INFINITY);
        let max = self.scaled(self.max)?.unwrap_or(f64::INFINITY);
        if min > max {
            return Err(MachineError::field(
                self.place,
                self.min.0,
                format!(
                    "{} > {} = {}: the lower limit must not exceed the upper",
                    self.min.1.unwrap_or(0.0),
                    self.max.0,
                    self.max.1.unwrap_or(0.0)
                ),
            ));
        }
        Ok(Limits {
            min,
            max,
            v_max: positive(self.v_max.1, self.place, self.v_max.0)? * self.scale / 60.0,
            dv_max: positive(self.dv_max.1, self.place, self.dv_max.0)? * self.scale / 60.0,
            a_max: positive(self.a_max.1, self.place, self.a_max.0)? * self.scale,
        })
    }
}
