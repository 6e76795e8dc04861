//! The job file's `[mandrel]` and `[winding]` tables, as users write them, and
//! their translation into a mandrel and a [`LayerSpec`].
//!
//! Fields are optional in the types so that a missing one is reported by its
//! dotted name (`mandrel.radius`) with what it should be. The tables'
//! descriptions ([`MANDREL`], [`WINDING`], [`LAYER`], [`EYE`]) give every
//! field's type, unit, range, default and help; the job's reader validates
//! against them first, and `docs/winding.md` lists them.

use std::fmt;
use std::str::FromStr;

use formcam_files::quote;
use formcam_geom::{Cone, Cylinder, DomeShape, GeomError, Jet, Meridian, Tabulated, Vessel};
use formcam_schema::{
    Condition, Default as Given, Field, Kind, Range, Repeat, Table, Unit, Value, field,
};
use serde::{Deserialize, Serialize};

use crate::{Ends, LayerSpec, MuSegment, Slippage, TubeTurn, WindingError};

/// `[mandrel]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MandrelSpec {
    /// `cylinder | cone | vessel | profile`.
    pub kind: Option<MandrelKind>,
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
    pub dome: Option<DomeKind>,
    /// Dome at the end.
    pub dome_end: Option<DomeKind>,
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

/// `mandrel.kind`: the mandrel's shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MandrelKind {
    /// A cylinder tube.
    Cylinder,
    /// A conical tube.
    Cone,
    /// A vessel: a cylinder between two domes.
    Vessel,
    /// A tabulated meridian.
    Profile,
}

impl MandrelKind {
    /// Every kind, in the order of [`MandrelKind::NAMES`].
    pub const ALL: [MandrelKind; 4] = [
        MandrelKind::Cylinder,
        MandrelKind::Cone,
        MandrelKind::Vessel,
        MandrelKind::Profile,
    ];

    /// The names users write.
    pub const NAMES: &'static [&'static str] = &["cylinder", "cone", "vessel", "profile"];

    /// The name users write.
    pub fn name(self) -> &'static str {
        match self {
            MandrelKind::Cylinder => "cylinder",
            MandrelKind::Cone => "cone",
            MandrelKind::Vessel => "vessel",
            MandrelKind::Profile => "profile",
        }
    }
}

impl fmt::Display for MandrelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// `mandrel.dome` and `mandrel.dome_end`: a vessel's dome shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum DomeKind {
    /// A hemisphere.
    Hemisphere,
    /// An ellipsoid (`axis_ratio`).
    Ellipsoid,
    /// A torispherical head (`crown_radius`, `knuckle_radius`).
    Torispherical,
    /// The geodesic-isotensoid dome.
    Isotensoid,
}

impl DomeKind {
    /// Every dome, in the order of [`DomeKind::NAMES`].
    pub const ALL: [DomeKind; 4] = [
        DomeKind::Hemisphere,
        DomeKind::Ellipsoid,
        DomeKind::Torispherical,
        DomeKind::Isotensoid,
    ];

    /// The names users write.
    pub const NAMES: &'static [&'static str] =
        &["hemisphere", "ellipsoid", "torispherical", "isotensoid"];

    /// The name users write.
    pub fn name(self) -> &'static str {
        match self {
            DomeKind::Hemisphere => "hemisphere",
            DomeKind::Ellipsoid => "ellipsoid",
            DomeKind::Torispherical => "torispherical",
            DomeKind::Isotensoid => "isotensoid",
        }
    }
}

impl fmt::Display for DomeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
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
                format!(
                    "kind: \"{}\" is not a layer kind; allowed: helical, hoop, skip",
                    quote(s)
                )
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
            MandrelKind::Vessel => {
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
                        .map_err(|e| geom(p, e))?,
                ))
            }
            MandrelKind::Profile => {
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
                            "\"{}\" is not a slippage; allowed: a number, \"auto\", \"minimax\"",
                            quote(other)
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
                    format!("\"{}\" is not a layer kind here (helical or hoop)", other),
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
                        "\"{}\" is not a turn-around; allowed: \"extension\" (beyond the tube's \
                         ends), \"friction\" (on the tube, held by mu)",
                        quote(other)
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
            samples: self.samples.unwrap_or(defaults.samples),
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

const fn when(field: &'static str, words: &'static [&'static str]) -> Given {
    Given::RequiredWhen(Condition::Is { field, words })
}

const POSITIVE: Option<Range> = Some(Range::above(0.0));
const NOT_NEGATIVE: Option<Range> = Some(Range::at_least(0.0));

/// The fields of `[mandrel]`.
pub const MANDREL_FIELDS: &[Field] = &[
    field(
        "kind",
        Kind::Word(MandrelKind::NAMES),
        Unit::None,
        None,
        Given::Required,
        "the mandrel's shape",
    ),
    field(
        "radius",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["cylinder", "vessel"]),
        "a cylinder's radius; a vessel's cylinder radius",
    ),
    field(
        "length",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["cylinder", "cone"]),
        "a tube's length",
    ),
    field(
        "radius_start",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["cone"]),
        "a cone's radius at `z = 0`",
    ),
    field(
        "radius_end",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["cone"]),
        "a cone's radius at `z = length`",
    ),
    field(
        "cylinder_length",
        Kind::Number,
        Unit::Mm,
        NOT_NEGATIVE,
        when("kind", &["vessel"]),
        "a vessel's cylinder length",
    ),
    field(
        "dome",
        Kind::Word(DomeKind::NAMES),
        Unit::None,
        None,
        Given::Value(Value::Text("hemisphere")),
        "a vessel's dome at the start (and at the end unless `dome_end`); `isotensoid` is the \
         geodesic-isotensoid",
    ),
    field(
        "dome_end",
        Kind::Word(DomeKind::NAMES),
        Unit::None,
        None,
        Given::Described("`dome`"),
        "a vessel's dome at the end",
    ),
    field(
        "polar_opening",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("kind", &["vessel"]),
        "the **radius** of the polar opening at the start (not its diameter), below `radius`; \
         also at the end unless `polar_opening_end`",
    ),
    field(
        "polar_opening_end",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Described("`polar_opening`"),
        "the radius of the polar opening at the end",
    ),
    field(
        "axis_ratio",
        Kind::Number,
        Unit::None,
        POSITIVE,
        when("dome", &["ellipsoid"]),
        "an ellipsoidal dome's depth / radius (0.5 for a 2:1 head)",
    ),
    field(
        "axis_ratio_end",
        Kind::Number,
        Unit::None,
        POSITIVE,
        Given::Described("`axis_ratio`"),
        "the same for the end dome",
    ),
    field(
        "crown_radius",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("dome", &["torispherical"]),
        "a torispherical dome's crown radius, >= `radius`",
    ),
    field(
        "knuckle_radius",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("dome", &["torispherical"]),
        "a torispherical dome's knuckle radius, below `radius`",
    ),
    field(
        "crown_radius_end",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Described("`crown_radius`"),
        "the same for the end dome",
    ),
    field(
        "knuckle_radius_end",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Described("`knuckle_radius`"),
        "the same for the end dome",
    ),
    field(
        "file",
        Kind::File,
        Unit::None,
        None,
        when("kind", &["profile"]),
        "a profile's CSV of `z,r` points (mm), relative to the job's folder; the meridian runs \
         between the first and the last point, which are the polar openings",
    ),
    field(
        "smoothing",
        Kind::Number,
        Unit::None,
        NOT_NEGATIVE,
        Given::Value(Value::Number(0.0)),
        "a profile's spline smoothing (0: interpolate)",
    ),
    field(
        "offset_mm",
        Kind::Number,
        Unit::Mm,
        None,
        Given::Value(Value::Number(0.0)),
        "added to every `r` of a profile",
    ),
];

const MU_SEGMENT_FIELDS: &[Field] = &[
    field(
        "z_from",
        Kind::Number,
        Unit::Mm,
        None,
        Given::Required,
        "the interval's start",
    ),
    field(
        "z_to",
        Kind::Number,
        Unit::Mm,
        None,
        Given::Required,
        "the interval's end",
    ),
    field(
        "mu",
        Kind::Number,
        Unit::None,
        None,
        Given::Required,
        "the slippage on it",
    ),
];

const MU: Field = field(
    "mu",
    Kind::NumberOrWord(&["auto", "minimax", "geodesic"]),
    Unit::None,
    None,
    Given::Value(Value::Number(0.0)),
    "the slippage: a number (constant, `|mu| <= mu_limit`; 0 = geodesic), `auto` (shooting, \
     vessels and profiles), `minimax` (vessels and profiles) or `geodesic`",
);
const MU_SEGMENTS: Field = field(
    "mu_segments",
    Kind::Tables(MU_SEGMENT_FIELDS),
    Unit::None,
    None,
    Given::None,
    "instead of `mu`: piecewise-constant slippage on `z` intervals in order, not overlapping, \
     within the mandrel",
);
const NOT_SKIP: Given = Given::RequiredWhen(Condition::Not {
    field: "kind",
    words: &["skip"],
});
const BAND_WIDTH: Field = field(
    "band_width",
    Kind::Number,
    Unit::Mm,
    POSITIVE,
    NOT_SKIP,
    "the band's width",
);
const BAND_THICKNESS: Field = field(
    "band_thickness",
    Kind::Number,
    Unit::Mm,
    POSITIVE,
    NOT_SKIP,
    "the band's thickness",
);
const OVERLAP: Field = field(
    "overlap",
    Kind::Number,
    Unit::None,
    Some(Range::closed_open(0.0, 1.0)),
    Given::Value(Value::Number(0.0)),
    "overlap of neighbouring bands, a fraction of the band width",
);
const WINDING_ANGLE: Field = field(
    "winding_angle_deg",
    Kind::Number,
    Unit::Deg,
    Some(Range::open(0.0, 90.0)),
    Given::Described("required for helical layers on tubes"),
    "tubes only: the winding angle at `z = 0`; an error on a vessel or a profile and for hoop \
     layers (their angle follows from the band width)",
);
const TURNAROUND: Field = field(
    "turnaround",
    Kind::Word(&["extension", "friction"]),
    Unit::None,
    None,
    Given::Described("`extension` (tubes only)"),
    "tubes only: `extension` (the band turns beyond the tube's ends) or `friction` (on the tube, \
     held by `mu` > 0)",
);
const PATTERN_NUMBER: Field = field(
    "pattern_number",
    Kind::Integer,
    Unit::None,
    Some(Range::closed(1.0, u32::MAX as f64)),
    Given::Described("chosen"),
    "the pattern number",
);
const SKIP_INDEX: Field = field(
    "skip_index",
    Kind::Integer,
    Unit::None,
    Some(Range::closed(0.0, u32::MAX as f64)),
    Given::Described("chosen"),
    "the skip index",
);
const DWELL_MIN: Field = field(
    "dwell_min_deg",
    Kind::Number,
    Unit::Deg,
    NOT_NEGATIVE,
    Given::Described("180 for tubes turned on an extension, else 0"),
    "the least dwell per turn-around",
);
const MU_LIMIT: Field = field(
    "mu_limit",
    Kind::Number,
    Unit::None,
    POSITIVE,
    Given::Value(Value::Number(0.6)),
    "the largest slippage the band holds; bounds `auto` and `minimax`",
);
const SAMPLES: Field = field(
    "samples",
    Kind::Integer,
    Unit::None,
    Some(Range::closed(2.0, 10_000_000.0)),
    Given::Value(Value::Integer(2001)),
    "points of `path.csv` per pass",
);
const ONE_WAY: Field = field(
    "one_way",
    Kind::Boolean,
    Unit::None,
    None,
    Given::Described("false (out and back); hoop layers only"),
    "hoop layers: one pass only, ending at the far end (a terminal hoop)",
);

/// The fields of `[winding]` (a single-layer job).
pub const WINDING_FIELDS: &[Field] = &[
    MU,
    MU_SEGMENTS,
    BAND_WIDTH,
    BAND_THICKNESS,
    OVERLAP,
    WINDING_ANGLE,
    TURNAROUND,
    PATTERN_NUMBER,
    SKIP_INDEX,
    DWELL_MIN,
    MU_LIMIT,
    SAMPLES,
    field(
        "kind",
        Kind::Word(&["helical", "hoop"]),
        Unit::None,
        None,
        Given::Value(Value::Text("helical")),
        "`helical` (or polar) circuits, or `hoop` (tubes: the band advances one width per turn)",
    ),
    ONE_WAY,
];

/// The fields of a `[[layer]]` (multi-layer jobs): those of `[winding]`
/// and the layer's kind.
pub const LAYER_FIELDS: &[Field] = &[
    field(
        "kind",
        Kind::Word(&["helical", "hoop", "skip"]),
        Unit::None,
        None,
        Given::Value(Value::Text("helical")),
        "`helical` (or polar) circuits, `hoop` (the band advances one width per turn; tubes and \
         a vessel's cylinder) or `skip` (the mandrel turns alone)",
    ),
    MU,
    MU_SEGMENTS,
    BAND_WIDTH,
    BAND_THICKNESS,
    OVERLAP,
    WINDING_ANGLE,
    TURNAROUND,
    PATTERN_NUMBER,
    SKIP_INDEX,
    DWELL_MIN,
    MU_LIMIT,
    SAMPLES,
    ONE_WAY,
    field(
        "mandrel_rotation_deg",
        Kind::Number,
        Unit::Deg,
        None,
        when("kind", &["skip"]),
        "skip layers: how far the mandrel turns alone",
    ),
];

/// The fields of `[eye]`.
pub const EYE_FIELDS: &[Field] = &[
    field(
        "mode",
        Kind::Word(&["pull-speed", "axis-parallel", "equidistant", "curve"]),
        Unit::None,
        None,
        Given::Value(Value::Text("pull-speed")),
        "the eye's trajectory: the pull-speed optimum, a line parallel to the axis, the \
         equidistant at `clearance`, or a user curve",
    ),
    field(
        "radius",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        when("mode", &["axis-parallel"]),
        "axis-parallel: the radius of the eye's line, outside the mandrel (pull-speed: compared \
         with it)",
    ),
    field(
        "clearance",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Value(Value::Number(20.0)),
        "the least clearance round the mandrel for every mode, and the equidistant's distance",
    ),
    field(
        "l_max",
        Kind::Number,
        Unit::Mm,
        POSITIVE,
        Given::Required,
        "the largest free length",
    ),
    field(
        "bath_moves_with_eye",
        Kind::Boolean,
        Unit::None,
        None,
        Given::Value(Value::Boolean(true)),
        "`true`: `k = 0` in eq. 12; `false`: a fixed bath, `k = 1`",
    ),
    field(
        "curve",
        Kind::File,
        Unit::None,
        None,
        when("mode", &["curve"]),
        "curve mode: CSV of `Z,R` points (mm), `Z` increasing, `R > 0`, relative to the job's \
         folder; covering the winding zone, outside the mandrel",
    ),
    field(
        "samples",
        Kind::Integer,
        Unit::None,
        Some(Range::closed(101.0, 10_000_000.0)),
        Given::Value(Value::Integer(2001)),
        "points of a geometric trajectory",
    ),
    field(
        "nodes",
        Kind::Integer,
        Unit::None,
        Some(Range::closed(100.0, 200_000.0)),
        Given::Value(Value::Integer(2000)),
        "intervals of the optimised `l(x)` (pull-speed)",
    ),
];

/// `[mandrel]`: the mandrel before any layer.
pub const MANDREL: Table = Table {
    name: "mandrel",
    repeat: Repeat::Single,
    required: true,
    help: "the mandrel before any layer",
    fields: MANDREL_FIELDS,
};

/// `[winding]`: the one layer of a single-layer job.
pub const WINDING: Table = Table {
    name: "winding",
    repeat: Repeat::Single,
    required: false,
    help: "the one layer of a single-layer job (instead of `[[layer]]`)",
    fields: WINDING_FIELDS,
};

/// `[[layer]]`: the layers of a multi-layer job, in winding order.
pub const LAYER: Table = Table {
    name: "layer",
    repeat: Repeat::Array,
    required: false,
    help: "the layers of a multi-layer job, in winding order (instead of `[winding]`)",
    fields: LAYER_FIELDS,
};

/// `[eye]`: the payout eye.
pub const EYE: Table = Table {
    name: "eye",
    repeat: Repeat::Single,
    required: false,
    help: "the payout eye's trajectory",
    fields: EYE_FIELDS,
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_described_words_are_the_enums_names() {
        assert_eq!(MandrelKind::ALL.map(MandrelKind::name), MandrelKind::NAMES);
        assert_eq!(DomeKind::ALL.map(DomeKind::name), DomeKind::NAMES);
        let layer = LAYER.field("kind").map(|f| f.kind.words());
        let names = [LayerKind::Helical, LayerKind::Hoop, LayerKind::Skip].map(LayerKind::name);
        assert_eq!(layer, Some(&names[..]));
    }
}
