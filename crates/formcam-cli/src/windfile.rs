//! `.wind` jobs (the JSON format of Cyclone and FiberPath, schemaVersion 1.x),
//! turned into a formcam job on the X/A/B winder with a Marlin X/A/B program.
//!
//! Mapping: `mandrelParameters` → a cylinder (`diameter`, `windLength`) or a
//! cone (`endDiameter`); `towParameters` → band width and thickness; `hoop` →
//! a hoop layer; `helical` → `windAngle` (from the axis, as ours),
//! `patternNumber`, `skipIndex`, `lockDegrees` as the least dwell at each end;
//! `skip` → the mandrel turning `mandrelRotation` degrees. The eye runs parallel
//! to the axis at the machine's eye radius; a `terminal` hoop is wound one way.
//! `leadInMM`, `leadOutDegrees`, `skipInitialNearLock` and `defaultFeedRate`
//! are read and checked but not used: the delivery head's rotation follows from the
//! kinematics, the feeds from the machine's limits.

use std::fs;
use std::path::Path;

use formcam_winding::job::{EyeJob, MandrelSpec, WindingSpec};
use serde::Deserialize;

use crate::CliError;

/// The machine `.wind` jobs run on.
pub const MACHINE: &str = include_str!("../../../machines/winder-xab.toml");
/// Its eye's distance from the spindle axis, mm.
pub const EYE_RADIUS: f64 = 250.0;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
struct WindFile {
    schema_version: Option<String>,
    mandrel_parameters: MandrelParameters,
    tow_parameters: TowParameters,
    default_feed_rate: f64,
    layers: Vec<Layer>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
struct MandrelParameters {
    diameter: f64,
    wind_length: f64,
    end_diameter: Option<f64>,
    profile: Option<serde_json::Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TowParameters {
    width: f64,
    thickness: f64,
}

#[derive(Debug, Deserialize)]
#[serde(tag = "windType", rename_all = "camelCase", deny_unknown_fields)]
enum Layer {
    Hoop {
        #[serde(default)]
        terminal: bool,
    },
    #[serde(rename_all = "camelCase")]
    Helical {
        wind_angle: f64,
        pattern_number: u32,
        skip_index: u32,
        lock_degrees: f64,
        #[serde(rename = "leadInMM")]
        lead_in_mm: f64,
        lead_out_degrees: f64,
        /// Read, not used.
        #[serde(default, rename = "skipInitialNearLock")]
        _skip_initial_near_lock: bool,
        #[serde(default)]
        friction_lambda: f64,
    },
    #[serde(rename_all = "camelCase")]
    Skip { mandrel_rotation: f64 },
}

/// The parts of a formcam job a `.wind` file gives.
pub struct Imported {
    /// The mandrel.
    pub mandrel: MandrelSpec,
    /// The layers.
    pub layers: Vec<WindingSpec>,
    /// The eye: parallel to the axis at the machine's eye radius.
    pub eye: EyeJob,
}

/// Reads a `.wind` file; errors name the file and the field.
pub fn read(path: &Path) -> Result<Imported, CliError> {
    let at = |msg: String| CliError(format!("{}: {msg}", path.display()));
    let text = fs::read_to_string(path).map_err(|e| at(format!("cannot read: {e}")))?;
    let f: WindFile = serde_json::from_str(&text).map_err(|e| {
        at(format!(
            "{}:{}: {}",
            e.line(),
            e.column(),
            e.to_string().replace('\n', " ")
        ))
    })?;
    let version = f.schema_version.as_deref().unwrap_or("1.0");
    let major = version.split('.').next().unwrap_or("");
    if major != "1" {
        return Err(at(format!(
            "schemaVersion: \"{version}\" is not supported (1.x is)"
        )));
    }
    let positive = |field: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(at(format!("{field}: must be a finite number > 0, got {v}")))
        }
    };
    let m = &f.mandrel_parameters;
    if m.profile.is_some() {
        return Err(at(
            "mandrelParameters.profile: nose profiles are not read yet (cylinders and cones are)"
                .into(),
        ));
    }
    let r0 = positive("mandrelParameters.diameter", m.diameter)? / 2.0;
    let length = positive("mandrelParameters.windLength", m.wind_length)?;
    positive("defaultFeedRate", f.default_feed_rate)?;
    let mandrel = match m.end_diameter {
        None => MandrelSpec {
            kind: Some("cylinder".into()),
            radius: Some(r0),
            length: Some(length),
            ..MandrelSpec::default()
        },
        Some(d) => MandrelSpec {
            kind: Some("cone".into()),
            radius_start: Some(r0),
            radius_end: Some(positive("mandrelParameters.endDiameter", d)? / 2.0),
            length: Some(length),
            ..MandrelSpec::default()
        },
    };
    let width = positive("towParameters.width", f.tow_parameters.width)?;
    let thickness = positive("towParameters.thickness", f.tow_parameters.thickness)?;
    if f.layers.is_empty() {
        return Err(at("layers: no layers".into()));
    }
    let base = WindingSpec {
        band_width: Some(width),
        band_thickness: Some(thickness),
        ..WindingSpec::default()
    };
    let mut layers = Vec::with_capacity(f.layers.len());
    for (i, l) in f.layers.iter().enumerate() {
        let field = |name: &str| format!("layers[{i}].{name}");
        layers.push(match l {
            Layer::Hoop { terminal } => WindingSpec {
                kind: Some("hoop".into()),
                one_way: terminal.then_some(true),
                ..base.clone()
            },
            Layer::Helical {
                wind_angle,
                pattern_number,
                skip_index,
                lock_degrees,
                lead_in_mm,
                lead_out_degrees,
                friction_lambda,
                ..
            } => {
                positive(&field("windAngle"), *wind_angle)?;
                if *wind_angle >= 90.0 {
                    return Err(at(format!(
                        "{}: {wind_angle} deg: a helical angle lies in (0, 90) degrees from the axis",
                        field("windAngle")
                    )));
                }
                positive(&field("lockDegrees"), *lock_degrees)?;
                positive(&field("leadInMM"), *lead_in_mm)?;
                positive(&field("leadOutDegrees"), *lead_out_degrees)?;
                if *friction_lambda != 0.0 {
                    return Err(at(format!(
                        "{}: non-geodesic helical layers are not read yet",
                        field("frictionLambda")
                    )));
                }
                WindingSpec {
                    kind: Some("helical".into()),
                    winding_angle_deg: Some(*wind_angle),
                    pattern_number: Some(*pattern_number),
                    skip_index: Some(*skip_index),
                    dwell_min_deg: Some(*lock_degrees),
                    ..base.clone()
                }
            }
            Layer::Skip { mandrel_rotation } => {
                if !mandrel_rotation.is_finite() {
                    return Err(at(format!("{}: must be finite", field("mandrelRotation"))));
                }
                WindingSpec {
                    kind: Some("skip".into()),
                    mandrel_rotation_deg: Some(*mandrel_rotation),
                    ..WindingSpec::default()
                }
            }
        });
    }
    if r0.max(m.end_diameter.unwrap_or(0.0) / 2.0) + 10.0 >= EYE_RADIUS {
        return Err(at(format!(
            "mandrelParameters.diameter: the X/A/B winder's eye runs {EYE_RADIUS} mm from the axis; \
             mandrels up to {} mm in diameter fit",
            2.0 * (EYE_RADIUS - 10.0)
        )));
    }
    let eye = EyeJob {
        mode: Some("axis-parallel".into()),
        radius: Some(EYE_RADIUS),
        clearance: Some(10.0),
        l_max: Some(4.0 * EYE_RADIUS + length),
        ..EyeJob::default()
    };
    Ok(Imported {
        mandrel,
        layers,
        eye,
    })
}
