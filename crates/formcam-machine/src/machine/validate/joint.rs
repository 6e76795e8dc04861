//! A link's joint checked: its type, limits and value in the joint's unit,
//! its axis when driven, its placement.

use nalgebra::{Isometry3, Vector3};

use super::numbers::{finite, positive, unit};
use super::placement::{dh_post, iso};
use crate::MachineError;
use crate::file::{JointType, LinkSpec};
use crate::machine::{Axis, Joint, JointKind};

/// The joint of a link spec, with its axis when driven (its index still unset).
pub(super) fn joint(l: &LinkSpec, place: &str) -> Result<(Joint, Option<Axis>), MachineError> {
    let kind = match l.joint.unwrap_or(JointType::Fixed) {
        JointType::Revolute => JointKind::Revolute,
        JointType::Prismatic => JointKind::Prismatic,
        JointType::Fixed => JointKind::Fixed,
    };
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
    let (wrong, own, why): (Vec<_>, [(&str, Option<f64>); 7], &str) = match kind {
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
    let val = |i: usize| -> Result<Option<f64>, MachineError> {
        own[i]
            .1
            .map(|v| finite(v, place, own[i].0).map(|v| v * scale))
            .transpose()
    };
    let min = val(0)?.unwrap_or(f64::NEG_INFINITY);
    let max = val(1)?.unwrap_or(f64::INFINITY);
    if min > max {
        return Err(MachineError::field(
            place,
            own[0].0,
            format!(
                "{} > {} = {}: the lower limit must not exceed the upper",
                own[0].1.unwrap_or(0.0),
                own[1].0,
                own[1].1.unwrap_or(0.0)
            ),
        ));
    }
    let v_max = positive(own[2].1, place, own[2].0)? * scale / 60.0;
    let dv_max = positive(own[3].1, place, own[3].0)? * scale / 60.0;
    let a_max = positive(own[6].1, place, own[6].0)? * scale;
    let axis = match (l.driven, &l.axis) {
        (true, _) if kind == JointKind::Fixed => {
            return Err(MachineError::field(
                place,
                "driven",
                "a fixed joint cannot be driven (joint = \"revolute\" or \"prismatic\")",
            ));
        }
        (true, None) => {
            return Err(MachineError::field(
                place,
                "axis",
                "missing: the NC address of the driven joint (e.g. \"X\", \"A\")",
            ));
        }
        (true, Some(name)) => {
            if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric()) {
                return Err(MachineError::field(
                    place,
                    "axis",
                    format!("\"{name}\" is not an NC address (letters and digits)"),
                ));
            }
            if own[4].1.is_some() {
                return Err(MachineError::field(
                    place,
                    own[4].0,
                    "a driven joint has no fixed value",
                ));
            }
            let home = val(5)?.unwrap_or(0.0);
            if home < min || home > max {
                return Err(MachineError::field(
                    place,
                    own[5].0,
                    "must lie within the limits",
                ));
            }
            if l.modulo == Some(true) {
                if kind != JointKind::Revolute {
                    return Err(MachineError::field(
                        place,
                        "modulo",
                        "only a revolute joint turns modulo 360 degrees",
                    ));
                }
                if min.is_finite() || max.is_finite() {
                    return Err(MachineError::field(
                        place,
                        "modulo",
                        "a modulo axis turns without end: no min_deg or max_deg",
                    ));
                }
            }
            Some(Axis {
                name: name.clone(),
                link: 0,
                kind,
                min,
                max,
                v_max,
                dv_max,
                a_max,
                home,
                // The spindle's default is set once the spindle is known.
                modulo: l.modulo.unwrap_or(false),
            })
        }
        (false, Some(_)) => {
            return Err(MachineError::field(
                place,
                "axis",
                "given for a joint that is not driven (set driven = true)",
            ));
        }
        (false, None) => None,
    };
    if axis.is_none() && l.modulo.is_some() {
        return Err(MachineError::field(
            place,
            "modulo",
            "only a driven revolute joint is a modulo axis",
        ));
    }
    if axis.is_none() && own[5].1.is_some() {
        return Err(MachineError::field(
            place,
            own[5].0,
            "only a driven joint has a home value",
        ));
    }
    let value = val(4)?.unwrap_or(0.0);
    let (pre, direction, post) = match (&l.dh, &l.origin) {
        (Some(_), Some(_)) => {
            return Err(MachineError::field(
                place,
                "dh",
                "give either dh or origin, not both",
            ));
        }
        (Some(_), None) if l.direction.is_some() => {
            return Err(MachineError::field(
                place,
                "direction",
                "a DH joint moves about/along z; direction goes with origin",
            ));
        }
        (Some(dh), None) => {
            for (f, v) in [
                ("dh.a", dh.a),
                ("dh.alpha_deg", dh.alpha_deg),
                ("dh.d", dh.d),
                ("dh.theta_deg", dh.theta_deg),
            ] {
                finite(v, place, f)?;
            }
            (Isometry3::identity(), Vector3::z_axis(), dh_post(dh))
        }
        (None, o) => {
            let o = o.unwrap_or_default();
            for (i, v) in o.xyz.iter().chain(&o.rpy_deg).enumerate() {
                finite(
                    *v,
                    place,
                    if i < 3 {
                        "origin.xyz"
                    } else {
                        "origin.rpy_deg"
                    },
                )?;
            }
            let dir = match l.direction {
                Some(d) => unit(d, place, "direction")?,
                None => Vector3::z_axis(),
            };
            (iso(&o), dir, Isometry3::identity())
        }
    };
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
