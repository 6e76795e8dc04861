//! A link's solid (`[[link.visual]]`) checked: its shape, its colour, a
//! mesh's scale.

use super::placement::iso;
use crate::MachineError;
use crate::file::VisualSpec;
use crate::machine::{Shape, Visual};

/// The solid `v` of `place` (a link, or the bed).
pub(crate) fn visual(v: &VisualSpec, place: &str) -> Result<Visual, MachineError> {
    let shape = shape(v, place)?;
    let color = color(v, place)?;
    let scale = scale(v, &shape, place)?;
    Ok(Visual {
        shape,
        origin: iso(&v.origin),
        color,
        scale,
    })
}

/// The shape with its dimensions, each finite and positive.
fn shape(v: &VisualSpec, place: &str) -> Result<Shape, MachineError> {
    let need = |x, field| dimension(v, x, place, field);
    Ok(match v.shape.as_str() {
        "box" => {
            let s = v.size.ok_or_else(|| {
                MachineError::field(place, "visual.size", "missing for a box: [x, y, z] in mm")
            })?;
            for c in s {
                need(Some(c), "size")?;
            }
            Shape::Box(s)
        }
        "cylinder" => Shape::Cylinder {
            radius: need(v.radius, "radius")?,
            length: need(v.length, "length")?,
        },
        "sphere" => Shape::Sphere(need(v.radius, "radius")?),
        "mesh" => Shape::Mesh(v.file.clone().ok_or_else(|| {
            MachineError::field(
                place,
                "visual.file",
                "missing for a mesh: an STL or OBJ file",
            )
        })?),
        other => {
            return Err(MachineError::field(
                place,
                "visual.shape",
                format!("unknown shape \"{other}\" (box, cylinder, sphere or mesh)"),
            ));
        }
    })
}

/// The colour `#rrggbb`, grey when not given.
fn color(v: &VisualSpec, place: &str) -> Result<String, MachineError> {
    let color = v.color.clone().unwrap_or_else(|| "#9aa4b1".to_string());
    let hex = color.strip_prefix('#').unwrap_or("");
    if hex.len() != 6 || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
        return Err(MachineError::field(
            place,
            "visual.color",
            format!("\"{color}\" is not a colour #rrggbb"),
        ));
    }
    Ok(color)
}

/// A mesh's factor per axis, each finite and positive (1 when not given).
fn scale(v: &VisualSpec, shape: &Shape, place: &str) -> Result<[f64; 3], MachineError> {
    match (v.scale, shape) {
        (None, _) => Ok([1.0; 3]),
        (Some(s), Shape::Mesh(_)) => {
            for c in s {
                dimension(v, Some(c), place, "scale")?;
            }
            Ok(s)
        }
        (Some(_), _) => Err(MachineError::field(
            place,
            "visual.scale",
            "only for a mesh",
        )),
    }
}

/// The dimension `x` of the solid `v`'s `field`: given, finite and positive.
fn dimension(
    v: &VisualSpec,
    x: Option<f64>,
    place: &str,
    field: &str,
) -> Result<f64, MachineError> {
    match x {
        Some(x) if x.is_finite() && x > 0.0 => Ok(x),
        Some(x) => Err(MachineError::field(
            place,
            format!("visual.{field}"),
            format!("must be a finite number > 0, got {x}"),
        )),
        None => Err(MachineError::field(
            place,
            format!("visual.{field}"),
            format!("missing for a {}", v.shape),
        )),
    }
}
