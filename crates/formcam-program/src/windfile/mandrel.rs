//! The mandrel of a `.wind` document (`mandrelParameters`): a cylinder or a
//! reducing cone, and the eye carried over it.

use formcam_winding::job::{EyeJob, MandrelKind, MandrelSpec};
use serde_json::Value;

use super::obj::Obj;
use crate::error::WindFileError;

/// The members of `mandrelParameters`, checked.
#[derive(Clone, Copy)]
pub(super) struct Mandrel {
    /// The diameter at the start, mm.
    pub(super) diameter: f64,
    /// The length wound, mm.
    pub(super) wind_length: f64,
    /// A reducing cone's end diameter, mm; `None` for a cylinder.
    pub(super) cone: Option<f64>,
}

impl Mandrel {
    /// Reads `mandrelParameters` of `root`; members not read are warned of.
    pub(super) fn read(
        root: &mut Obj<'_>,
        version: &str,
        warnings: &mut Vec<String>,
    ) -> Result<Mandrel, WindFileError> {
        let mut m = Obj::new("mandrelParameters", root.get("mandrelParameters"))?;
        let diameter = m.positive("diameter", "mm")?;
        let wind_length = m.positive("windLength", "mm")?;
        let end_diameter = match m.number("endDiameter")? {
            Some(e) if e <= 0.0 => {
                return Err(WindFileError::NotPositive {
                    member: "mandrelParameters.endDiameter".into(),
                    unit: "mm",
                    value: e,
                });
            }
            e => e,
        };
        if let Some(profile) = m.get("profile") {
            if end_diameter.is_some() {
                return Err(WindFileError::ProfileAndEndDiameter);
            }
            let kind = profile.get("type").and_then(Value::as_str).unwrap_or("?");
            return Err(WindFileError::ProfileMandrel { kind: kind.into() });
        }
        let cone = match end_diameter {
            Some(e) if e > diameter => {
                return Err(WindFileError::ExpandingCone {
                    end_mm: e,
                    diameter_mm: diameter,
                });
            }
            Some(e) if e < diameter => Some(e),
            _ => None,
        };
        m.ignored(version, warnings);
        Ok(Mandrel {
            diameter,
            wind_length,
            cone,
        })
    }

    /// The mandrel as a formcam job's, its largest radius `r_max`.
    pub(super) fn spec(&self, r_max: f64) -> MandrelSpec {
        match self.cone {
            None => MandrelSpec {
                kind: Some(MandrelKind::Cylinder),
                radius: Some(r_max),
                length: Some(self.wind_length),
                ..MandrelSpec::default()
            },
            Some(e) => MandrelSpec {
                kind: Some(MandrelKind::Cone),
                radius_start: Some(r_max),
                radius_end: Some(e / 2.0),
                length: Some(self.wind_length),
                ..MandrelSpec::default()
            },
        }
    }
}

/// The eye parallel to the axis at `eye_radius`, `eye_clearance` over the
/// mandrel.
pub(super) fn eye(eye_radius: f64, eye_clearance: f64) -> EyeJob {
    EyeJob {
        mode: Some("axis-parallel".into()),
        radius: Some(eye_radius),
        // The laid band may come up to half the clearance.
        clearance: Some(eye_clearance / 2.0),
        // The format knows no free-length limit.
        l_max: Some(1.0e6),
        ..EyeJob::default()
    }
}
