//! Mandrels shared by the integration tests.

#![allow(dead_code, clippy::unwrap_used)]

use std::f64::consts::PI;

use formcam_geom::{DomeShape, Jet, Meridian, Vessel};

/// A hemisphere vessel of radius 100 mm and cylinder 300 mm with openings `rp1`, `rp2`.
pub fn vessel(rp1: f64, rp2: f64) -> Vessel {
    Vessel::new(
        100.0,
        300.0,
        (DomeShape::Hemisphere, rp1),
        (DomeShape::Hemisphere, rp2),
    )
    .unwrap()
}

/// A mandrel with a waist: concave in the middle.
pub struct Waist {
    /// Length of the mandrel, mm.
    pub len: f64,
}

impl Meridian for Waist {
    fn z_range(&self) -> (f64, f64) {
        (0.0, self.len)
    }
    fn eval(&self, z: f64) -> Jet {
        let k = PI / self.len;
        let w = 40.0;
        let u = (z - 0.5 * self.len) / w;
        let g = (-u * u).exp();
        Jet {
            r: 40.0 + 60.0 * (k * z).sin() - 15.0 * g,
            dr: 60.0 * k * (k * z).cos() + 15.0 * g * 2.0 * u / w,
            d2r: -60.0 * k * k * (k * z).sin() + 15.0 * g * (2.0 - 4.0 * u * u) / (w * w),
        }
    }
}
