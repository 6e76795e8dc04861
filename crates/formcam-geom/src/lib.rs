//! Geometry core of formcam.
//!
//! A mandrel is a surface of revolution about the `z` axis, described by its
//! [`Meridian`] `r(z)` on `[z_start, z_end]` with exact first and second
//! derivatives where the shape is analytic. Shapes:
//!
//! * [`Cylinder`], [`Cone`] — tubes;
//! * domes ([`DomeShape`]): hemispherical, ellipsoidal, torispherical and
//!   geodesic-isotensoid, each cut at its polar opening;
//! * [`Vessel`] — dome + cylinder + dome, the domes and openings may differ;
//! * [`Tabulated`] — a meridian from `z,r` points, smoothed by a C2 spline.
//!
//! Every constructor validates its input and returns a [`GeomError`] that
//! names the offending field. Units: millimetres and radians.
//!
//! The module layout follows the one-type-per-module rule: each shape lives in
//! its own private module and is re-exported here.

mod cone;
mod cylinder;
mod dome;
mod error;
mod isotensoid;
mod meridian;
mod mirrored;
mod pairs;
mod spline;
mod tabulated;
mod vessel;

pub use cone::Cone;
pub use cylinder::Cylinder;
pub use dome::{Dome, DomeShape};
pub use error::GeomError;
pub use isotensoid::Isotensoid;
pub use meridian::{Jet, Meridian};
pub use mirrored::Mirrored;
pub use pairs::read_pairs;
pub use spline::CubicSpline;
pub use tabulated::Tabulated;
pub use vessel::Vessel;

/// Checks that `value` is finite and strictly positive; names `field` otherwise.
pub(crate) fn positive(field: &'static str, value: f64) -> Result<f64, GeomError> {
    if !value.is_finite() {
        return Err(GeomError::NotFinite { field, value });
    }
    if value <= 0.0 {
        return Err(GeomError::NotPositive { field, value });
    }
    Ok(value)
}
