//! The roles of the `[machine]` table found: the payout point, the spindle,
//! the compaction roller, the band path, the mandrel's link, the roller's
//! and the head's directions.

use super::links::link_named;
use super::numbers::unit;
use crate::MachineError;
use crate::file::{LinkSpec, MachineKind, MachineTable, SpindleFollows};
use crate::machine::{Axis, KeyPoint, Link, Roles};

/// Where the roles' errors are.
const PLACE: &str = "[machine]";

/// The roles `m` gives, on the checked links, axes and points.
pub(super) fn roles(
    m: &MachineTable,
    links: &[Link],
    axes: &[Axis],
    points: &[KeyPoint],
) -> Result<Roles, MachineError> {
    let payout = point_named(points, &m.payout, "payout")?;
    let spindle = spindle(m, axes)?;
    let roller_radius = roller_radius(m)?;
    let band_path = band_path(m, points, payout)?;
    let roles = Roles {
        kind: m.kind,
        mandrel: link_named(links, &m.mandrel, PLACE, "mandrel")?,
        spindle,
        spindle_follows: m.spindle_follows.unwrap_or(SpindleFollows::Eye),
        payout,
        roller_axis: m
            .roller_axis
            .map(|v| unit(v, PLACE, "roller_axis"))
            .transpose()?,
        head_normal: m
            .head_normal
            .map(|v| unit(v, PLACE, "head_normal"))
            .transpose()?,
        roller_radius,
        band_path,
    };
    if roles.kind == MachineKind::Placement && roles.head_normal.is_none() {
        return Err(MachineError::field(
            PLACE,
            "head_normal",
            "a placement head needs the direction that presses into the mandrel",
        ));
    }
    Ok(roles)
}

/// The spindle turns modulo 360 degrees unless the file says otherwise or it
/// has limits.
pub(super) fn spindle_modulo(
    axes: &mut [Axis],
    spindle: Option<usize>,
    specs: &[LinkSpec],
    link_of_axis: &[usize],
) {
    if let Some(i) = spindle {
        let a = &mut axes[i];
        let given = specs.get(link_of_axis[i]).and_then(|l| l.modulo);
        a.modulo = given.unwrap_or(a.min.is_infinite() && a.max.is_infinite());
    }
}

/// The index of the key point named `name`, which `field` names.
fn point_named(points: &[KeyPoint], name: &str, field: &str) -> Result<usize, MachineError> {
    points
        .iter()
        .position(|q| q.name == name)
        .ok_or_else(|| MachineError::field(PLACE, field, format!("no point is named \"{name}\"")))
}

/// The spindle's axis: a driven revolute one.
fn spindle(m: &MachineTable, axes: &[Axis]) -> Result<Option<usize>, MachineError> {
    let Some(name) = &m.spindle else {
        return Ok(None);
    };
    let i = axes.iter().position(|a| &a.name == name).ok_or_else(|| {
        MachineError::field(
            PLACE,
            "spindle",
            format!("no driven axis is named \"{name}\""),
        )
    })?;
    if !axes[i].is_rotary() {
        return Err(MachineError::field(
            PLACE,
            "spindle",
            format!("axis \"{name}\" is prismatic; the spindle turns"),
        ));
    }
    Ok(Some(i))
}

/// The compaction roller's radius: a placement head's, none for a winder.
fn roller_radius(m: &MachineTable) -> Result<f64, MachineError> {
    match (m.kind, m.roller_radius) {
        (MachineKind::Placement, Some(h)) if h.is_finite() && h > 0.0 => Ok(h),
        (MachineKind::Placement, _) => Err(MachineError::field(
            PLACE,
            "roller_radius",
            "a placement head needs the compaction roller's radius h > 0, mm",
        )),
        (MachineKind::Winder, None) => Ok(0.0),
        (MachineKind::Winder, Some(_)) => Err(MachineError::field(
            PLACE,
            "roller_radius",
            "only for kind = \"placement\"",
        )),
    }
}

/// The band path's key points, ending at the payout point.
fn band_path(
    m: &MachineTable,
    points: &[KeyPoint],
    payout: usize,
) -> Result<Vec<usize>, MachineError> {
    let band_path = m
        .band_path
        .iter()
        .flatten()
        .map(|n| point_named(points, n, "band_path"))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(&last) = band_path.last()
        && last != payout
    {
        return Err(MachineError::field(
            PLACE,
            "band_path",
            "must end at the payout point",
        ));
    }
    Ok(band_path)
}
