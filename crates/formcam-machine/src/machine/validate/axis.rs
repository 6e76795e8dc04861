//! A joint's axis: a driven joint's NC address, home and modulo; an undriven
//! joint has none of them.

use super::joint::{Fields, Limits};
use crate::MachineError;
use crate::file::LinkSpec;
use crate::machine::{Axis, JointKind};

/// The axis of the joint of `l`, of `kind`, when driven (its link still unset).
pub(super) fn axis(
    l: &LinkSpec,
    kind: JointKind,
    fields: &Fields<'_>,
    limits: &Limits,
) -> Result<Option<Axis>, MachineError> {
    let place = fields.place;
    match (l.driven, &l.axis) {
        (true, _) if kind == JointKind::Fixed => Err(MachineError::field(
            place,
            "driven",
            "a fixed joint cannot be driven (joint = \"revolute\" or \"prismatic\")",
        )),
        (true, None) => Err(MachineError::field(
            place,
            "axis",
            "missing: the NC address of the driven joint (e.g. \"X\", \"A\")",
        )),
        (true, Some(name)) => driven(l, kind, name, fields, limits).map(Some),
        (false, Some(_)) => Err(MachineError::field(
            place,
            "axis",
            "given for a joint that is not driven (set driven = true)",
        )),
        (false, None) => undriven(l, fields).map(|()| None),
    }
}

/// The axis `name` of a driven joint: an NC address, no fixed value, home
/// within the limits, modulo only where it turns without end.
fn driven(
    l: &LinkSpec,
    kind: JointKind,
    name: &str,
    fields: &Fields<'_>,
    limits: &Limits,
) -> Result<Axis, MachineError> {
    let place = fields.place;
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric()) {
        return Err(MachineError::field(
            place,
            "axis",
            format!("\"{name}\" is not an NC address (letters and digits)"),
        ));
    }
    if fields.value.1.is_some() {
        return Err(MachineError::field(
            place,
            fields.value.0,
            "a driven joint has no fixed value",
        ));
    }
    let &Limits {
        min,
        max,
        v_max,
        dv_max,
        a_max,
    } = limits;
    let home = fields.scaled(fields.home)?.unwrap_or(0.0);
    if home < min || home > max {
        return Err(MachineError::field(
            place,
            fields.home.0,
            "must lie within the limits",
        ));
    }
    if l.modulo == Some(true) {
        modulo(kind, limits, place)?;
    }
    Ok(Axis {
        name: name.to_string(),
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

/// A modulo axis: revolute, without limits.
fn modulo(kind: JointKind, limits: &Limits, place: &str) -> Result<(), MachineError> {
    if kind != JointKind::Revolute {
        return Err(MachineError::field(
            place,
            "modulo",
            "only a revolute joint turns modulo 360 degrees",
        ));
    }
    if limits.min.is_finite() || limits.max.is_finite() {
        return Err(MachineError::field(
            place,
            "modulo",
            "a modulo axis turns without end: no min_deg or max_deg",
        ));
    }
    Ok(())
}

/// An undriven joint: neither modulo nor a home value.
fn undriven(l: &LinkSpec, fields: &Fields<'_>) -> Result<(), MachineError> {
    if l.modulo.is_some() {
        return Err(MachineError::field(
            fields.place,
            "modulo",
            "only a driven revolute joint is a modulo axis",
        ));
    }
    if fields.home.1.is_some() {
        return Err(MachineError::field(
            fields.place,
            fields.home.0,
            "only a driven joint has a home value",
        ));
    }
    Ok(())
}
