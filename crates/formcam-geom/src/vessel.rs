use crate::{Dome, DomeShape, GeomError, Jet, Meridian, positive};

/// A pressure vessel: start dome + cylinder + end dome, `z = 0` at the start
/// dome's polar opening.
#[derive(Debug, Clone, PartialEq)]
pub struct Vessel {
    start: Dome,
    end: Dome,
    cylinder_length: f64,
}

impl Vessel {
    /// A vessel of cylinder `radius` and `cylinder_length` (>= 0) with a dome at each end.
    pub fn new(
        radius: f64,
        cylinder_length: f64,
        start: (DomeShape, f64),
        end: (DomeShape, f64),
    ) -> Result<Self, GeomError> {
        let radius = positive("radius", radius)?;
        if !cylinder_length.is_finite() {
            return Err(GeomError::NotFinite {
                field: "cylinder_length",
                value: cylinder_length,
            });
        }
        if cylinder_length < 0.0 {
            return Err(GeomError::OutOfRange {
                field: "cylinder_length",
                value: cylinder_length,
                allowed: "cylinder_length >= 0 mm".into(),
            });
        }
        let start = Dome::new(start.0, radius, start.1)?;
        let end = Dome::new(end.0, radius, end.1).map_err(|e| match e {
            GeomError::OutOfRange {
                field: "polar_opening",
                value,
                allowed,
            } => GeomError::OutOfRange {
                field: "polar_opening_end",
                value,
                allowed,
            },
            other => other,
        })?;
        Ok(Self {
            start,
            end,
            cylinder_length,
        })
    }

    /// The dome at `z = z_start`.
    pub fn start_dome(&self) -> &Dome {
        &self.start
    }

    /// The dome at `z = z_end`.
    pub fn end_dome(&self) -> &Dome {
        &self.end
    }

    /// Cylinder radius, mm.
    pub fn radius(&self) -> f64 {
        self.start.radius()
    }

    /// Cylinder length, mm.
    pub fn cylinder_length(&self) -> f64 {
        self.cylinder_length
    }

    /// `z` of the start and end of the cylindrical part.
    pub fn cylinder_range(&self) -> (f64, f64) {
        let a = self.start.height();
        (a, a + self.cylinder_length)
    }
}

impl Meridian for Vessel {
    fn z_range(&self) -> (f64, f64) {
        (
            0.0,
            self.start.height() + self.cylinder_length + self.end.height(),
        )
    }

    fn eval(&self, z: f64) -> Jet {
        let (z1, z2) = self.cylinder_range();
        if z < z1 {
            let j = self.start.eval_w(z1 - z);
            Jet {
                r: j.r,
                dr: -j.dr,
                d2r: j.d2r,
            }
        } else if z <= z2 {
            Jet {
                r: self.radius(),
                dr: 0.0,
                d2r: 0.0,
            }
        } else {
            self.end.eval_w(z - z2)
        }
    }

    fn r(&self, z: f64) -> f64 {
        let (z1, z2) = self.cylinder_range();
        if z < z1 {
            self.start.r_w(z1 - z)
        } else if z <= z2 {
            self.radius()
        } else {
            self.end.r_w(z - z2)
        }
    }

    fn breakpoints(&self) -> Vec<f64> {
        let (z1, z2) = self.cylinder_range();
        let mut v: Vec<f64> = self.start.joints().iter().rev().map(|w| z1 - w).collect();
        v.push(z1);
        if z2 > z1 {
            v.push(z2);
        }
        v.extend(self.end.joints().iter().map(|w| z2 + w));
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hemisphere_vessel_geometry() {
        let v = Vessel::new(
            100.0,
            300.0,
            (DomeShape::Hemisphere, 30.0),
            (DomeShape::Hemisphere, 40.0),
        )
        .unwrap();
        let (a, b) = v.z_range();
        assert_eq!(a, 0.0);
        let h1 = (100.0f64 * 100.0 - 900.0).sqrt();
        let h2 = (100.0f64 * 100.0 - 1600.0).sqrt();
        assert!((b - (h1 + 300.0 + h2)).abs() < 1e-12);
        assert!((v.r(0.0) - 30.0).abs() < 1e-9);
        assert!((v.r(b) - 40.0).abs() < 1e-9);
        assert!(v.dr(0.0) > 0.0 && v.dr(b) < 0.0);
        assert_eq!(v.r(h1 + 10.0), 100.0);
        assert_eq!(v.breakpoints(), vec![h1, h1 + 300.0]);
        // Continuity of r and r' at the joints.
        for z in [h1, h1 + 300.0] {
            let (l, r) = (v.eval(z - 1e-9), v.eval(z + 1e-9));
            assert!((l.r - r.r).abs() < 1e-6 && (l.dr - r.dr).abs() < 1e-6);
        }
    }

    #[test]
    fn end_opening_errors_name_their_field() {
        let e = Vessel::new(
            100.0,
            10.0,
            (DomeShape::Hemisphere, 30.0),
            (DomeShape::Hemisphere, 120.0),
        )
        .unwrap_err();
        assert!(matches!(
            e,
            GeomError::OutOfRange {
                field: "polar_opening_end",
                ..
            }
        ));
        assert!(
            Vessel::new(
                100.0,
                -1.0,
                (DomeShape::Hemisphere, 30.0),
                (DomeShape::Hemisphere, 30.0)
            )
            .is_err()
        );
    }
}
