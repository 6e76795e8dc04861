use crate::{GeomError, Jet, Meridian, positive};

/// A truncated cone from `radius_start` at `z = 0` to `radius_end` at `z = length`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone {
    radius_start: f64,
    radius_end: f64,
    length: f64,
}

impl Cone {
    /// A cone; all numbers must be finite and positive.
    pub fn new(radius_start: f64, radius_end: f64, length: f64) -> Result<Self, GeomError> {
        Ok(Self {
            radius_start: positive("radius_start", radius_start)?,
            radius_end: positive("radius_end", radius_end)?,
            length: positive("length", length)?,
        })
    }

    /// Slope `dr/dz`.
    pub fn slope(&self) -> f64 {
        (self.radius_end - self.radius_start) / self.length
    }

    /// Half angle of the cone, rad (signed: positive when it widens with `z`).
    pub fn half_angle(&self) -> f64 {
        self.slope().atan()
    }
}

impl Meridian for Cone {
    fn z_range(&self) -> (f64, f64) {
        (0.0, self.length)
    }
    fn eval(&self, z: f64) -> Jet {
        let k = self.slope();
        Jet {
            r: self.radius_start + k * z,
            dr: k,
            d2r: 0.0,
        }
    }
}
