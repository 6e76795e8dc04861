//! The `[mandrel]` and `[eye]` tables turned into a [`Mandrel`] and an
//! [`EyeSpec`](crate::eye::EyeSpec), with errors that name the dotted field.

use formcam_files::quote;
use formcam_geom::{Cone, Cylinder, DomeShape, GeomError, Tabulated, Vessel};

use super::{DomeKind, EyeJob, Mandrel, MandrelKind, MandrelSpec};
use crate::WindingError;

/// `v`, or the error that `field` is missing: `what` it should be.
pub(super) fn need(field: &str, v: Option<f64>, what: &str) -> Result<f64, WindingError> {
    v.ok_or_else(|| WindingError::field(field, format!("missing: {what}")))
}

fn geom(prefix: &str, e: GeomError) -> WindingError {
    match e {
        GeomError::NotFinite { field, value } => WindingError::field(
            format!("{prefix}.{field}"),
            format!("must be a finite number, got {value}"),
        ),
        GeomError::NotPositive { field, value } => WindingError::field(
            format!("{prefix}.{field}"),
            format!("must be > 0 mm, got {value}"),
        ),
        GeomError::OutOfRange {
            field,
            value,
            allowed,
        } => WindingError::field(
            format!("{prefix}.{field}"),
            format!("{value} is out of range: {allowed}"),
        ),
        other => WindingError::field(format!("{prefix}.file"), other.to_string()),
    }
}

fn dome_shape(
    dome: DomeKind,
    axis_ratio: (Option<f64>, &str),
    crown: (Option<f64>, &str),
    knuckle: (Option<f64>, &str),
) -> Result<DomeShape, WindingError> {
    match dome {
        DomeKind::Hemisphere => Ok(DomeShape::Hemisphere),
        DomeKind::Ellipsoid => Ok(DomeShape::Ellipsoid {
            axis_ratio: need(
                axis_ratio.1,
                axis_ratio.0,
                "dome depth / radius, > 0 (0.5 for a 2:1 head)",
            )?,
        }),
        DomeKind::Torispherical => Ok(DomeShape::Torispherical {
            crown_radius: need(crown.1, crown.0, "crown radius in mm, >= radius")?,
            knuckle_radius: need(
                knuckle.1,
                knuckle.0,
                "knuckle radius in mm, 0 < knuckle < radius",
            )?,
        }),
        DomeKind::Isotensoid => Ok(DomeShape::Isotensoid),
    }
}

impl MandrelSpec {
    /// The mandrel grown by `t` mm of laid band: every radius (and the domes'
    /// crown and knuckle radii) larger by `t`; the polar openings and lengths stay.
    /// Ellipsoidal domes keep their axis ratio, and a profile's `r` grows by `t`
    /// at every `z` (neither is the normal offset: approximations on slopes).
    pub fn grown(&self, t: f64) -> Result<MandrelSpec, WindingError> {
        if t == 0.0 {
            return Ok(self.clone());
        }
        let add = |v: Option<f64>| v.map(|v| v + t);
        if self.kind == Some(MandrelKind::Profile) {
            return Ok(MandrelSpec {
                offset_mm: Some(self.offset_mm.unwrap_or(0.0) + t),
                ..self.clone()
            });
        }
        Ok(MandrelSpec {
            radius: add(self.radius),
            radius_start: add(self.radius_start),
            radius_end: add(self.radius_end),
            crown_radius: add(self.crown_radius),
            knuckle_radius: add(self.knuckle_radius),
            crown_radius_end: add(self.crown_radius_end),
            knuckle_radius_end: add(self.knuckle_radius_end),
            ..self.clone()
        })
    }

    /// Builds the mandrel; `read` loads a file named by the job (a profile table).
    pub fn build(
        &self,
        read: impl Fn(&str) -> Result<String, String>,
    ) -> Result<Mandrel, WindingError> {
        let kind = self.kind.ok_or_else(|| {
            WindingError::field(
                "mandrel.kind",
                "missing: one of cylinder, cone, vessel, profile",
            )
        })?;
        let p = "mandrel";
        match kind {
            MandrelKind::Cylinder => Ok(Mandrel::Cylinder(
                Cylinder::new(
                    need("mandrel.radius", self.radius, "radius in mm, > 0")?,
                    need("mandrel.length", self.length, "length in mm, > 0")?,
                )
                .map_err(|e| geom(p, e))?,
            )),
            MandrelKind::Cone => Ok(Mandrel::Cone(
                Cone::new(
                    need(
                        "mandrel.radius_start",
                        self.radius_start,
                        "radius at z = 0 in mm, > 0",
                    )?,
                    need(
                        "mandrel.radius_end",
                        self.radius_end,
                        "radius at z = length in mm, > 0",
                    )?,
                    need("mandrel.length", self.length, "length in mm, > 0")?,
                )
                .map_err(|e| geom(p, e))?,
            )),
            MandrelKind::Vessel => self.vessel(),
            MandrelKind::Profile => self.profile(read),
        }
    }

    /// A vessel: the cylinder and its domes (the end one as the start one unless
    /// given) with their polar openings.
    fn vessel(&self) -> Result<Mandrel, WindingError> {
        let radius = need("mandrel.radius", self.radius, "cylinder radius in mm, > 0")?;
        let length = need("mandrel.cylinder_length", self.cylinder_length, "mm, >= 0")?;
        let dome = self.dome.unwrap_or(DomeKind::Hemisphere);
        let start = dome_shape(
            dome,
            (self.axis_ratio, "mandrel.axis_ratio"),
            (self.crown_radius, "mandrel.crown_radius"),
            (self.knuckle_radius, "mandrel.knuckle_radius"),
        )?;
        let end = dome_shape(
            self.dome_end.unwrap_or(dome),
            (
                self.axis_ratio_end.or(self.axis_ratio),
                "mandrel.axis_ratio_end",
            ),
            (
                self.crown_radius_end.or(self.crown_radius),
                "mandrel.crown_radius_end",
            ),
            (
                self.knuckle_radius_end.or(self.knuckle_radius),
                "mandrel.knuckle_radius_end",
            ),
        )?;
        let po = need(
            "mandrel.polar_opening",
            self.polar_opening,
            "radius in mm, 0 < it < radius",
        )?;
        let po_end = self.polar_opening_end.unwrap_or(po);
        Ok(Mandrel::Vessel(
            Vessel::new(radius, length, (start, po), (end, po_end))
                .map_err(|e| geom("mandrel", e))?,
        ))
    }

    /// A profile: the `z,r` table `read` loads, offset by `offset_mm` and smoothed.
    fn profile(
        &self,
        read: impl Fn(&str) -> Result<String, String>,
    ) -> Result<Mandrel, WindingError> {
        let file = self.file.as_deref().ok_or_else(|| {
            WindingError::field("mandrel.file", "missing: a CSV file of z,r points (mm)")
        })?;
        let text = read(file).map_err(|e| WindingError::field("mandrel.file", e))?;
        let offset = self.offset_mm.unwrap_or(0.0);
        if !offset.is_finite() {
            return Err(WindingError::field("mandrel.offset_mm", "must be finite"));
        }
        let t = formcam_geom::read_pairs(&text, ("z", "r"))
            .and_then(|pts| {
                let pts: Vec<(f64, f64)> = pts.into_iter().map(|(z, r)| (z, r + offset)).collect();
                Tabulated::new(&pts, self.smoothing.unwrap_or(0.0))
            })
            .map_err(|e| WindingError::field("mandrel.file", format!("{file}: {e}")))?;
        Ok(Mandrel::Profile(t))
    }
}

impl MandrelSpec {
    /// Values that are allowed but implausible (a wrong unit, most likely), as
    /// lines naming the field: a radius under 1 mm (metres?).
    pub fn warnings(&self) -> Vec<String> {
        [
            ("mandrel.radius", self.radius),
            ("mandrel.radius_start", self.radius_start),
            ("mandrel.radius_end", self.radius_end),
        ]
        .into_iter()
        .filter_map(|(field, v)| match v {
            Some(r) if r > 0.0 && r < 1.0 => Some(format!(
                "{field}: {r} mm is under 1 mm; radii are in mm (metres?)"
            )),
            _ => None,
        })
        .collect()
    }
}

impl EyeJob {
    /// The eye specification; `read` loads a file named by the job (the curve).
    pub fn spec(
        &self,
        read: impl Fn(&str) -> Result<String, String>,
    ) -> Result<crate::eye::EyeSpec, WindingError> {
        use crate::eye::{EyeMode, EyeSpec};
        let mode = match self.mode.as_deref() {
            Some("axis-parallel") => EyeMode::AxisParallel,
            Some("equidistant") => EyeMode::Equidistant,
            Some("curve") => EyeMode::Curve,
            Some("pull-speed") | None => EyeMode::PullSpeed,
            Some(other) => {
                return Err(WindingError::field(
                    "eye.mode",
                    format!(
                        "unknown mode \"{}\"; allowed: axis-parallel, equidistant, curve, pull-speed",
                        quote(other)
                    ),
                ));
            }
        };
        let curve = match (mode, self.curve.as_deref()) {
            (EyeMode::Curve, None) => {
                return Err(WindingError::field(
                    "eye.curve",
                    "missing: a CSV file of Z,R points (mm)",
                ));
            }
            (_, Some(file)) => {
                let text = read(file).map_err(|e| WindingError::field("eye.curve", e))?;
                let points = formcam_geom::read_pairs(&text, ("Z", "R"))
                    .map_err(|e| WindingError::field("eye.curve", format!("{file}: {e}")))?;
                if let Some(fault) = crate::eye::curve_fault(&points) {
                    return Err(WindingError::field("eye.curve", format!("{file}: {fault}")));
                }
                points
            }
            (_, None) => Vec::new(),
        };
        let defaults = EyeSpec::default();
        Ok(EyeSpec {
            mode,
            radius: self.radius,
            clearance: self.clearance.unwrap_or(defaults.clearance),
            l_max: need(
                "eye.l_max",
                self.l_max,
                "the largest free length in mm, > 0",
            )?,
            bath_moves_with_eye: self.bath_moves_with_eye.unwrap_or(true),
            curve,
            samples: self.samples.unwrap_or(defaults.samples),
            nodes: self.nodes.unwrap_or(defaults.nodes),
        })
    }
}
