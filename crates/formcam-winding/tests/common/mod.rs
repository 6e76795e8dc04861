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

/// A waisted shell whose ends flare: `r = 40 + 30 cos^2(pi z / L) + (z - L/2)^2 / 3000`
/// (r' = -0.1 at z = 0 and +0.1 at z = L, steepest near the quarter points).
pub struct Flare {
    /// Length of the mandrel, mm.
    pub len: f64,
}

impl Meridian for Flare {
    fn z_range(&self) -> (f64, f64) {
        (0.0, self.len)
    }
    fn eval(&self, z: f64) -> Jet {
        let k = PI / self.len;
        let b = 1.0 / 3000.0;
        let d = z - 0.5 * self.len;
        Jet {
            r: 40.0 + 30.0 * (k * z).cos().powi(2) + b * d * d,
            dr: -30.0 * k * (2.0 * k * z).sin() + 2.0 * b * d,
            d2r: -60.0 * k * k * (2.0 * k * z).cos() + 2.0 * b,
        }
    }
}

/// A parabolic waist whose ends flare: `r = 50 + a (z - L/2)^2`.
pub struct Parabola {
    /// Length of the mandrel, mm.
    pub len: f64,
    /// Curvature coefficient `a`, 1/mm.
    pub a: f64,
}

impl Meridian for Parabola {
    fn z_range(&self) -> (f64, f64) {
        (0.0, self.len)
    }
    fn eval(&self, z: f64) -> Jet {
        let d = z - 0.5 * self.len;
        Jet {
            r: 50.0 + self.a * d * d,
            dr: 2.0 * self.a * d,
            d2r: 2.0 * self.a,
        }
    }
}
