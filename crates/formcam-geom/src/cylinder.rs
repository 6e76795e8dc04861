use crate::{GeomError, Jet, Meridian, positive};

/// A circular cylinder of radius `radius` on `[0, length]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    radius: f64,
    length: f64,
}

impl Cylinder {
    /// A cylinder; both numbers must be finite and positive.
    pub fn new(radius: f64, length: f64) -> Result<Self, GeomError> {
        Ok(Self {
            radius: positive("radius", radius)?,
            length: positive("length", length)?,
        })
    }

    /// Radius, mm.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Length, mm.
    pub fn length(&self) -> f64 {
        self.length
    }
}

impl Meridian for Cylinder {
    fn z_range(&self) -> (f64, f64) {
        (0.0, self.length)
    }
    fn eval(&self, _z: f64) -> Jet {
        Jet {
            r: self.radius,
            dr: 0.0,
            d2r: 0.0,
        }
    }
}
