//! The mandrel a job describes: one of the shapes, as one meridian.

use formcam_geom::{Cone, Cylinder, Jet, Meridian, Tabulated, Vessel};

/// A mandrel built from a job.
#[derive(Debug, Clone)]
pub enum Mandrel {
    /// A cylinder tube.
    Cylinder(Cylinder),
    /// A conical tube.
    Cone(Cone),
    /// A vessel with domes.
    Vessel(Vessel),
    /// A tabulated meridian.
    Profile(Tabulated),
}

impl Meridian for Mandrel {
    fn z_range(&self) -> (f64, f64) {
        match self {
            Mandrel::Cylinder(m) => m.z_range(),
            Mandrel::Cone(m) => m.z_range(),
            Mandrel::Vessel(m) => m.z_range(),
            Mandrel::Profile(m) => m.z_range(),
        }
    }
    fn eval(&self, z: f64) -> Jet {
        match self {
            Mandrel::Cylinder(m) => m.eval(z),
            Mandrel::Cone(m) => m.eval(z),
            Mandrel::Vessel(m) => m.eval(z),
            Mandrel::Profile(m) => m.eval(z),
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        match self {
            Mandrel::Cylinder(m) => m.breakpoints(),
            Mandrel::Cone(m) => m.breakpoints(),
            Mandrel::Vessel(m) => m.breakpoints(),
            Mandrel::Profile(m) => m.breakpoints(),
        }
    }
}

impl Mandrel {
    /// `cylinder`, `cone`, `vessel` or `profile`.
    pub fn kind(&self) -> &'static str {
        match self {
            Mandrel::Cylinder(_) => "cylinder",
            Mandrel::Cone(_) => "cone",
            Mandrel::Vessel(_) => "vessel",
            Mandrel::Profile(_) => "profile",
        }
    }

    /// Whether the mandrel is an open tube (no polar openings).
    pub fn is_tube(&self) -> bool {
        matches!(self, Mandrel::Cylinder(_) | Mandrel::Cone(_))
    }
}
