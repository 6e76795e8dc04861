//! The tables as users write them: `[mandrel]`, `[winding]` (and each
//! `[[layer]]`), `[eye]`, as serde structs whose fields are optional so that a
//! missing one is reported by its dotted name, and the words they take.

use std::fmt;
use std::str::FromStr;

use formcam_files::quote;
use serde::{Deserialize, Serialize};

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
