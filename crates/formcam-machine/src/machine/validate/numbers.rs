//! The checks of a number or a vector a machine file gives.

use nalgebra::{Unit, Vector3};

use crate::MachineError;

pub(super) fn unit(
    v: [f64; 3],
    place: &str,
    field: &str,
) -> Result<Unit<Vector3<f64>>, MachineError> {
    let v = Vector3::from(v);
    if v.iter().all(|c| c.is_finite()) && v.norm() > 1e-12 {
        Ok(Unit::new_normalize(v))
    } else {
        Err(MachineError::field(
            place,
            field,
            "must be a finite non-zero vector [x, y, z]",
        ))
    }
}

pub(super) fn finite(v: f64, place: &str, field: &str) -> Result<f64, MachineError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(MachineError::field(place, field, "must be a finite number"))
    }
}

pub(super) fn positive(v: Option<f64>, place: &str, field: &str) -> Result<f64, MachineError> {
    match v {
        None => Ok(f64::INFINITY),
        Some(v) if v.is_finite() && v > 0.0 => Ok(v),
        Some(v) => Err(MachineError::field(
            place,
            field,
            format!("must be a finite number > 0, got {v}"),
        )),
    }
}
