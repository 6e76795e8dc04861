//! A link's solid (`[[link.visual]]`) checked.

use super::placement::iso;
use crate::MachineError;
use crate::file::VisualSpec;
use crate::machine::{Shape, Visual};

pub(crate) fn visual(v: &VisualSpec, place: &str) -> Result<Visual, MachineError> {
    let need = |x: Option<f64>, field: &str| -> Result<f64, MachineError> {
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
    };
    let shape = match v.shape.as_str() {
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
    };
    let color = v.color.clone().unwrap_or_else(|| "#9aa4b1".to_string());
    let hex = color.strip_prefix('#').unwrap_or("");
    if hex.len() != 6 || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
        return Err(MachineError::field(
            place,
            "visual.color",
            format!("\"{color}\" is not a colour #rrggbb"),
        ));
    }
    let scale = match (v.scale, &shape) {
        (None, _) => [1.0; 3],
        (Some(s), Shape::Mesh(_)) => {
            for c in s {
                need(Some(c), "scale")?;
            }
            s
        }
        (Some(_), _) => {
            return Err(MachineError::field(
                place,
                "visual.scale",
                "only for a mesh",
            ));
        }
    };
    Ok(Visual {
        shape,
        origin: iso(&v.origin),
        color,
        scale,
    })
}
