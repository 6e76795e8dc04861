//! The job file's `[mandrel]` and `[winding]` tables, as users write them, and
//! their translation into a mandrel and a [`LayerSpec`].
//!
//! Fields are optional in the types so that a missing one is reported by its
//! dotted name (`mandrel.radius`) with what it should be.

use std::fmt;
use std::str::FromStr;

use formcam_geom::{Cone, Cylinder, DomeShape, GeomError, Jet, Meridian, Tabulated, Vessel};
use serde::{Deserialize, Serialize};

use crate::{Ends, LayerSpec, MuSegment, Slippage, TubeTurn, WindingError};

/// `[mandrel]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MandrelSpec {
    /// `cylinder | cone | vessel | profile`.
    pub kind: Option<String>,
    /// Cylinder radius, mm.
    pub radius: Option<f64>,
    /// Tube length, mm.
    pub length: Option<f64>,
    /// Cone radius at `z = 0`, mm.
    pub radius_start: Option<f64>,
    /// Cone radius at `z = length`, mm.
    pub radius_end: Option<f64>,
    /// Cylinder length of a vessel, mm.
    pub cylinder_length: Option<f64>,
    /// Dome at the start (and at the end unless `dome_end` is given).
    pub dome: Option<String>,
    /// Dome at the end.
    pub dome_end: Option<String>,
    /// Polar opening radius at the start (and end unless `polar_opening_end`), mm.
    pub polar_opening: Option<f64>,
    /// Polar opening radius at the end, mm.
    pub polar_opening_end: Option<f64>,
    /// Ellipsoidal dome: depth / radius.
    pub axis_ratio: Option<f64>,
    /// Ellipsoidal end dome: depth / radius.
    pub axis_ratio_end: Option<f64>,
    /// Torispherical dome: crown radius, mm.
    pub crown_radius: Option<f64>,
    /// Torispherical dome: knuckle radius, mm.
    pub knuckle_radius: Option<f64>,
    /// Torispherical end dome: crown radius, mm.
    pub crown_radius_end: Option<f64>,
    /// Torispherical end dome: knuckle radius, mm.
    pub knuckle_radius_end: Option<f64>,
    /// Profile: CSV file of `z,r` points, relative to the job file.
    pub file: Option<String>,
    /// Profile: spline smoothing (0 = interpolate).
    pub smoothing: Option<f64>,
    /// Profile: a radial offset added to every `r` of the table, mm (multi-layer
    /// jobs grow it by the thickness of the layers laid).
    pub offset_mm: Option<f64>,
}

/// `mu` as users write it: a number, `"auto"` or `"minimax"`.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum MuField {
    /// A constant slippage.
    Number(f64),
    /// A method name.
    Word(String),
}

/// `[winding]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WindingSpec {
    /// Slippage: number, `"auto"` or `"minimax"`.
    pub mu: Option<MuField>,
    /// Piecewise-constant slippage.
    pub mu_segments: Option<Vec<MuSegmentSpec>>,
    /// Band width, mm.
    pub band_width: Option<f64>,
    /// Band thickness, mm.
    pub band_thickness: Option<f64>,
    /// Overlap of neighbouring bands, fraction of the band width (default 0).
    pub overlap: Option<f64>,
    /// Tubes: winding angle at `z = 0`, degrees.
    pub winding_angle_deg: Option<f64>,
    /// Required pattern number.
    pub pattern_number: Option<u32>,
    /// Required skip index.
    pub skip_index: Option<u32>,
    /// Least dwell at each turn-around, degrees (default 0 for vessels, 180 for tubes).
    pub dwell_min_deg: Option<f64>,
    /// Largest slippage the band holds (default 0.6).
    pub mu_limit: Option<f64>,
    /// Points written per pass (default 2001).
    pub samples: Option<usize>,
    /// Tubes: `extension` (default: the band turns beyond the ends) or `friction`
    /// (it turns on the tube, held by `mu`).
    pub turnaround: Option<String>,
    /// Multi-layer jobs (`[[layer]]`): `helical` (default), `hoop` (tubes: the
    /// band advances one width per turn) or `skip` (the mandrel turns alone).
    pub kind: Option<LayerKind>,
    /// Skip layers: how far the mandrel turns, degrees.
    pub mandrel_rotation_deg: Option<f64>,
    /// Hoop layers: one pass only, ending at the far end (a terminal hoop);
    /// default false (out and back).
    pub one_way: Option<bool>,
}

/// The kind of a layer (`kind` of a `[[layer]]` table), read by its name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Deserialize, Serialize)]
#[serde(rename_all = "lowercase", try_from = "String")]
pub enum LayerKind {
    /// Helical (or polar) circuits, the pattern covering the mandrel.
    #[default]
    Helical,
    /// Hoop winding: the band advances one width per turn.
    Hoop,
    /// No band: the mandrel turns alone.
    Skip,
}

impl LayerKind {
    /// The name in job files and messages: `helical`, `hoop`, `skip`.
    pub fn name(self) -> &'static str {
        match self {
            LayerKind::Helical => "helical",
            LayerKind::Hoop => "hoop",
            LayerKind::Skip => "skip",
        }
    }
}

impl FromStr for LayerKind {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        [LayerKind::Helical, LayerKind::Hoop, LayerKind::Skip]
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| {
                format!("kind: \"{s}\" is not a layer kind; allowed: helical, hoop, skip")
            })
    }
}

impl TryFrom<String> for LayerKind {
    type Error = String;

    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

impl fmt::Display for LayerKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// One `mu_segments` entry.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MuSegmentSpec {
    /// Start, mm.
    pub z_from: f64,
    /// End, mm.
    pub z_to: f64,
    /// Slippage.
    pub mu: f64,
}

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

fn need(field: &str, v: Option<f64>, what: &str) -> Result<f64, WindingError> {
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
    name: &str,
    field: &str,
    axis_ratio: (Option<f64>, &str),
    crown: (Option<f64>, &str),
    knuckle: (Option<f64>, &str),
) -> Result<DomeShape, WindingError> {
    match name {
        "hemisphere" => Ok(DomeShape::Hemisphere),
        "ellipsoid" => Ok(DomeShape::Ellipsoid {
            axis_ratio: need(
                axis_ratio.1,
                axis_ratio.0,
                "dome depth / radius, > 0 (0.5 for a 2:1 head)",
            )?,
        }),
        "torispherical" => Ok(DomeShape::Torispherical {
            crown_radius: need(crown.1, crown.0, "crown radius in mm, >= radius")?,
            knuckle_radius: need(
                knuckle.1,
                knuckle.0,
                "knuckle radius in mm, 0 < knuckle < radius",
            )?,
        }),
        "isotensoid" => Ok(DomeShape::Isotensoid),
        other => Err(WindingError::field(
            field,
            format!(
                "unknown dome \"{other}\"; allowed: hemisphere, ellipsoid, torispherical, isotensoid"
            ),
        )),
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
        if self.kind.as_deref() == Some("profile") {
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
        let kind = self.kind.as_deref().ok_or_else(|| {
            WindingError::field(
                "mandrel.kind",
                "missing: one of cylinder, cone, vessel, profile",
            )
        })?;
        let p = "mandrel";
        match kind {
            "cylinder" => Ok(Mandrel::Cylinder(
                Cylinder::new(
                    need("mandrel.radius", self.radius, "radius in mm, > 0")?,
                    need("mandrel.length", self.length, "length in mm, > 0")?,
                )
                .map_err(|e| geom(p, e))?,
            )),
            "cone" => Ok(Mandrel::Cone(
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
            "vessel" => {
                let radius = need("mandrel.radius", self.radius, "cylinder radius in mm, > 0")?;
                let length = need("mandrel.cylinder_length", self.cylinder_length, "mm, >= 0")?;
                let dome = self.dome.as_deref().unwrap_or("hemisphere");
                let start = dome_shape(
                    dome,
                    "mandrel.dome",
                    (self.axis_ratio, "mandrel.axis_ratio"),
                    (self.crown_radius, "mandrel.crown_radius"),
                    (self.knuckle_radius, "mandrel.knuckle_radius"),
                )?;
                let end = dome_shape(
                    self.dome_end.as_deref().unwrap_or(dome),
                    "mandrel.dome_end",
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
                        .map_err(|e| geom(p, e))?,
                ))
            }
            "profile" => {
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
                        let pts: Vec<(f64, f64)> =
                            pts.into_iter().map(|(z, r)| (z, r + offset)).collect();
                        Tabulated::new(&pts, self.smoothing.unwrap_or(0.0))
                    })
                    .map_err(|e| WindingError::field("mandrel.file", format!("{file}: {e}")))?;
                Ok(Mandrel::Profile(t))
            }
            other => Err(WindingError::field(
                "mandrel.kind",
                format!("unknown kind \"{other}\"; allowed: cylinder, cone, vessel, profile"),
            )),
        }
    }
}

impl WindingSpec {
    /// The layer specification for `mandrel`.
    pub fn layer_spec(&self, mandrel: &Mandrel) -> Result<LayerSpec, WindingError> {
        let slippage = match (&self.mu, &self.mu_segments) {
            (Some(_), Some(_)) => {
                return Err(WindingError::field(
                    "winding.mu",
                    "give either mu or mu_segments, not both",
                ));
            }
            (None, Some(segs)) => Slippage::Segments(
                segs.iter()
                    .map(|s| MuSegment {
                        z_from: s.z_from,
                        z_to: s.z_to,
                        mu: s.mu,
                    })
                    .collect(),
            ),
            (None, None) | (Some(MuField::Number(0.0)), None) => Slippage::Geodesic,
            (Some(MuField::Number(m)), None) => Slippage::Constant(*m),
            (Some(MuField::Word(w)), None) => match w.as_str() {
                "auto" => Slippage::Auto,
                "minimax" => Slippage::Minimax,
                "geodesic" => Slippage::Geodesic,
                other => {
                    return Err(WindingError::field(
                        "winding.mu",
                        format!(
                            "\"{other}\" is not a slippage; allowed: a number, \"auto\", \"minimax\""
                        ),
                    ));
                }
            },
        };
        let hoop = match self.kind {
            None | Some(LayerKind::Helical) => false,
            Some(LayerKind::Hoop) => true,
            Some(other) => {
                return Err(WindingError::field(
                    "winding.kind",
                    format!("\"{other}\" is not a layer kind here (helical or hoop)"),
                ));
            }
        };
        if self.mandrel_rotation_deg.is_some() {
            return Err(WindingError::field(
                "winding.mandrel_rotation_deg",
                "only for kind = \"skip\"",
            ));
        }
        if self.one_way.is_some() && !hoop {
            return Err(WindingError::field(
                "winding.one_way",
                "only for kind = \"hoop\"",
            ));
        }
        let ends = match mandrel {
            Mandrel::Cylinder(_) | Mandrel::Cone(_) if hoop => {
                if self.winding_angle_deg.is_some() {
                    return Err(WindingError::field(
                        "winding.winding_angle_deg",
                        "a hoop layer's angle follows from the band width; leave it out",
                    ));
                }
                let w = need(
                    "winding.band_width",
                    self.band_width,
                    "band width in mm, > 0",
                )?;
                let (z0, _) = mandrel.z_range();
                // One band width per turn: tan(alpha) = 2 pi r / w.
                Ends::Tube {
                    winding_angle: (std::f64::consts::TAU * mandrel.r(z0) / w).atan(),
                }
            }
            _ if hoop => {
                return Err(WindingError::field(
                    "winding.kind",
                    "hoop layers are wound on tubes and on a vessel's cylinder (multi-layer jobs)",
                ));
            }
            Mandrel::Cylinder(_) | Mandrel::Cone(_) => {
                let deg = need(
                    "winding.winding_angle_deg",
                    self.winding_angle_deg,
                    "the winding angle at z = 0 for a tube, degrees in (0, 90)",
                )?;
                Ends::Tube {
                    winding_angle: deg.to_radians(),
                }
            }
            Mandrel::Vessel(_) | Mandrel::Profile(_) if self.winding_angle_deg.is_some() => {
                return Err(WindingError::field(
                    "winding.winding_angle_deg",
                    format!(
                        "does not apply to a {}: the angle follows from the polar openings \
                         (Clairaut); leave it out",
                        mandrel.kind()
                    ),
                ));
            }
            Mandrel::Vessel(v) => Ends::Poles {
                start: v.start_dome().polar_opening(),
                end: v.end_dome().polar_opening(),
            },
            Mandrel::Profile(t) => {
                let (a, b) = t.z_range();
                Ends::Poles {
                    start: t.r(a),
                    end: t.r(b),
                }
            }
        };
        let turnaround = match self.turnaround.as_deref() {
            Some(_) if !mandrel.is_tube() => {
                return Err(WindingError::field(
                    "winding.turnaround",
                    "only for tubes (cylinder, cone); a vessel's pass turns at its polar openings",
                ));
            }
            None | Some("extension") => TubeTurn::Extension,
            Some("friction") if mandrel.is_tube() && !hoop => TubeTurn::Friction,
            Some("friction") => {
                return Err(WindingError::field(
                    "winding.turnaround",
                    "\"friction\" is for helical layers on tubes (cylinder, cone)",
                ));
            }
            Some(other) => {
                return Err(WindingError::field(
                    "winding.turnaround",
                    format!(
                        "\"{other}\" is not a turn-around; allowed: \"extension\" (beyond the tube's \
                         ends), \"friction\" (on the tube, held by mu)"
                    ),
                ));
            }
        };
        let default_dwell = if mandrel.is_tube() && turnaround == TubeTurn::Extension {
            180.0
        } else {
            0.0
        };
        let defaults = LayerSpec::default();
        Ok(LayerSpec {
            slippage,
            ends,
            band_width: need(
                "winding.band_width",
                self.band_width,
                "band width in mm, > 0",
            )?,
            band_thickness: need(
                "winding.band_thickness",
                self.band_thickness,
                "band thickness in mm, > 0",
            )?,
            overlap: self.overlap.unwrap_or(0.0),
            pattern_number: self.pattern_number,
            skip_index: self.skip_index,
            dwell_min: self.dwell_min_deg.unwrap_or(default_dwell).to_radians(),
            mu_limit: self.mu_limit.unwrap_or(defaults.mu_limit),
            samples: match self.samples {
                Some(n) if !(2..=10_000_000).contains(&n) => {
                    return Err(WindingError::field(
                        "winding.samples",
                        "must be in [2, 10000000]",
                    ));
                }
                Some(n) => n,
                None => defaults.samples,
            },
            minimax_nodes: defaults.minimax_nodes,
            turnaround,
        })
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

impl WindingSpec {
    /// Values that are allowed but implausible on `mandrel`, as lines naming
    /// the field: a band wider than half the circumference of a polar opening
    /// (it cannot lie flat round the opening).
    pub fn warnings(&self, mandrel: &Mandrel) -> Vec<String> {
        let mut out = Vec::new();
        let openings = match mandrel {
            Mandrel::Vessel(v) => [v.start_dome().polar_opening(), v.end_dome().polar_opening()],
            _ => return out,
        };
        let smallest = openings[0].min(openings[1]);
        if let Some(w) = self.band_width
            && w > std::f64::consts::PI * smallest
        {
            out.push(format!(
                "winding.band_width: {w} mm is wider than half the circumference of the \
                 {smallest} mm polar opening ({:.1} mm)",
                std::f64::consts::PI * smallest
            ));
        }
        out
    }
}

/// `[eye]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EyeJob {
    /// `axis-parallel | equidistant | curve | pull-speed`.
    pub mode: Option<String>,
    /// Axis-parallel: radius of the eye's line, mm (also the comparison in pull-speed).
    pub radius: Option<f64>,
    /// Least clearance to the mandrel (and the equidistant's), mm; default 20.
    pub clearance: Option<f64>,
    /// Largest free length, mm.
    pub l_max: Option<f64>,
    /// `true`: the bath moves with the eye (`k = 0`); `false`: fixed bath (`k = 1`).
    pub bath_moves_with_eye: Option<bool>,
    /// Curve mode: CSV file of `Z,R` points, relative to the job file.
    pub curve: Option<String>,
    /// Points of a geometric trajectory (default 2001).
    pub samples: Option<usize>,
    /// Intervals of the optimised `l(x)` (default 2000).
    pub nodes: Option<usize>,
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
                        "unknown mode \"{other}\"; allowed: axis-parallel, equidistant, curve, pull-speed"
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
                formcam_geom::read_pairs(&text, ("Z", "R"))
                    .map_err(|e| WindingError::field("eye.curve", format!("{file}: {e}")))?
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
