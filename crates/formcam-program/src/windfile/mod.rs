//! `.wind` jobs (the JSON format of Cyclone and FiberPath, schemaVersion 1.x),
//! turned into a formcam job on the X/A/B winder with a Marlin X/A/B program.
//!
//! formcam reads `.wind` as a conforming 1.x consumer of the format's
//! specification (1.3): any `1.<minor>` is read, an absent `schemaVersion` is
//! 1.0, other majors are refused; members it does not know are ignored with a
//! warning, and members that would change the geometry but that formcam does
//! not wind (a `profile` mandrel, a non-zero `frictionLambda`) are refused. Every
//! validation rule of the specification is applied, each error naming the
//! member by its JSON path (`layers[1].windAngle`).
//!
//! Mapping: `mandrelParameters` → a cylinder (`diameter`, `windLength`) or a
//! reducing cone (`endDiameter`); `towParameters` → band width and thickness;
//! `hoop` → a hoop layer (a `terminal` one wound one way); `helical` →
//! `windAngle` (from the axis, as ours; 90° is the hoop), `patternNumber`,
//! `skipIndex`, `lockDegrees` as the least dwell at each end; `skip` → the
//! mandrel turning `mandrelRotation` degrees. The eye runs parallel to the axis
//! just over the mandrel (its radius plus a clearance), as FiberPath's machines
//! carry it: FiberPath's `X` is the band's own position. `leadInMM`,
//! `leadOutDegrees`, `skipInitialNearLock` and `defaultFeedRate` are checked but
//! not used: the delivery head's rotation follows from the kinematics, the feeds
//! from the machine's limits.

mod layers;
mod mandrel;
mod obj;

use formcam_machine::IkMethod;
use formcam_machine::shipped::shipped;
use formcam_winding::job::{EyeJob, MandrelSpec, WindingSpec};
use serde_json::Value;

use crate::ProgramError;
use crate::checks::Check;
use crate::error::WindFileError;
use crate::job::{JobMachine, Layers, MachineSource, MotionJob, Post, WindImport, WindJob};
use layers::{Tow, read_layers};
use mandrel::{Mandrel, eye};
use obj::Obj;

/// The shipped machine `.wind` jobs run on (its eye 250 mm from the axis;
/// moved to the job's eye radius by [`machine_text`]).
pub const MACHINE: &str = "winder-xab";
/// The latest version of the specification formcam reads: `(major, minor)`.
pub const SPEC_VERSION: (u32, u32) = (1, 3);
/// The eye's default clearance over the mandrel, mm: clear of the eye's own
/// solid (a roller of 12 mm radius).
pub const EYE_CLEARANCE_MM: f64 = 25.0;

/// The line of the shipped machine that places the eye's arm.
const ARM_ORIGIN: &str = "origin = { xyz = [0.0, 250.0, 1000.0] }";

/// The X/A/B winder with its eye `eye_radius` mm from the spindle axis.
pub fn machine_text(eye_radius: f64) -> Result<String, ProgramError> {
    let text = shipped(MACHINE).map_or("", |s| s.text);
    if text.matches(ARM_ORIGIN).count() != 1 {
        return Err(WindFileError::ArmMoved { machine: MACHINE }.into());
    }
    Ok(text.replace(
        ARM_ORIGIN,
        &format!("origin = {{ xyz = [0.0, {eye_radius}, 1000.0] }}"),
    ))
}

impl WindJob {
    /// A Cyclone/FiberPath `.wind` document as a job on the shipped X/A/B
    /// winder with its eye `eye_clearance` mm over the mandrel, written for
    /// Marlin X/A/B.
    ///
    /// The format knows no eye: FiberPath's machines lay the band where `X`
    /// says and take up a little slack at the turn-arounds with their
    /// tensioner, so the eye's `slack` check is accepted (and reported);
    /// `allow` accepts more. Errors name the member.
    pub fn from_wind(
        text: &str,
        eye_clearance: f64,
        allow: &[Check],
    ) -> Result<WindJob, ProgramError> {
        let imported = parse(text, eye_clearance)?;
        let machine = formcam_machine::Machine::from_toml(&machine_text(imported.eye_radius)?)
            .map_err(|e| ProgramError::machine(MACHINE, e))?;
        let mut checks = vec![Check::Slack];
        checks.extend(allow.iter().filter(|c| **c != Check::Slack));
        Ok(WindJob {
            title: "job.wind".into(),
            program_name: "job".into(),
            base_dir: std::path::PathBuf::new(),
            mandrel: imported.mandrel,
            layers: Layers::Multi(imported.layers),
            eye: Some(imported.eye),
            machine: Some(JobMachine {
                machine,
                source: MachineSource::Shipped(MACHINE.into()),
                ik: IkMethod::Auto,
            }),
            motion: MotionJob::default(),
            post: Some(Post::Dialect(formcam_nc::Dialect::MarlinXab)),
            allow: checks,
            warnings: imported.warnings,
            wind_file: Some(WindImport {
                schema_version: imported.schema_version,
                eye_radius_mm: imported.eye_radius,
                eye_clearance_mm: imported.eye_clearance,
            }),
        })
    }
}

/// The parts of a formcam job a `.wind` file gives.
#[derive(Debug)]
struct Imported {
    /// The mandrel.
    mandrel: MandrelSpec,
    /// The layers.
    layers: Vec<WindingSpec>,
    /// The eye: parallel to the axis at [`Imported::eye_radius`].
    eye: EyeJob,
    /// The eye's distance from the spindle axis, mm.
    eye_radius: f64,
    /// The eye's clearance over the mandrel's largest radius, mm.
    eye_clearance: f64,
    /// The document's `schemaVersion` (1.0 when absent).
    schema_version: String,
    /// Members ignored and other remarks, one line each.
    warnings: Vec<String>,
}

/// The `schemaVersion` as `(major, minor)`: `1.<digits>`.
fn version(v: Option<&Value>) -> Result<(String, u32), WindFileError> {
    let text = match v {
        None => return Ok(("1.0".into(), 0)),
        Some(Value::String(s)) => s.trim().to_string(),
        Some(_) => return Err(WindFileError::VersionNotAString),
    };
    let (major, minor) = text.split_once('.').unwrap_or((text.as_str(), ""));
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if !digits(major) || !digits(minor) {
        return Err(WindFileError::VersionForm { text });
    }
    if major.parse::<u32>().ok() != Some(SPEC_VERSION.0) {
        return Err(WindFileError::VersionUnsupported { text });
    }
    let minor = minor.parse::<u32>().unwrap_or(u32::MAX);
    Ok((text, minor))
}

/// Reads the text of a `.wind` document; errors name the member.
fn parse(text: &str, eye_clearance: f64) -> Result<Imported, WindFileError> {
    if !(eye_clearance.is_finite() && eye_clearance > 0.0) {
        return Err(WindFileError::EyeClearance {
            value: eye_clearance,
        });
    }
    let doc: Value = serde_json::from_str(text).map_err(WindFileError::Json)?;
    let mut root = Obj::new("", Some(&doc)).map_err(|_| WindFileError::NotADocument)?;
    let (version_text, minor) = version(root.get("schemaVersion"))?;
    let mut warnings = Vec::new();
    if minor > SPEC_VERSION.1 {
        warnings.push(format!(
            "schemaVersion: {version_text} is newer than the {}.{} formcam reads; members it \
             does not know are ignored",
            SPEC_VERSION.0, SPEC_VERSION.1
        ));
    }
    let mandrel = Mandrel::read(&mut root, &version_text, &mut warnings)?;
    let tow = Tow::read(&mut root, &version_text, &mut warnings)?;
    root.positive("defaultFeedRate", "mm/min")?;
    let layers = read_layers(&mut root, &mandrel, &tow, &version_text, &mut warnings)?;
    root.ignored(&version_text, &mut warnings);
    if layers.is_empty() {
        warnings.push("layers: none; the program holds no motion".into());
    }
    let r_max = mandrel.diameter / 2.0;
    let eye_radius = r_max + eye_clearance;
    Ok(Imported {
        mandrel: mandrel.spec(r_max),
        layers,
        eye: eye(eye_radius, eye_clearance),
        eye_radius,
        eye_clearance,
        schema_version: version_text,
        warnings,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn the_built_in_winder_carries_its_eye_at_the_radius_asked() {
        for radius in [42.5, 250.0, 600.0] {
            let text = machine_text(radius).unwrap();
            let m = formcam_machine::Machine::from_toml(&text).unwrap();
            let q = m.home();
            let eye = m.key_points(&q)[m.roles.payout];
            let local = m.poses(&q)[m.roles.mandrel].inverse_transform_point(&eye);
            let r = local.x.hypot(local.y);
            assert!((r - radius).abs() < 1e-9, "{r} vs {radius}");
        }
    }

    #[test]
    fn versions_of_major_one_are_read() {
        assert_eq!(version(None).unwrap(), ("1.0".into(), 0));
        assert_eq!(version(Some(&Value::from("1.3"))).unwrap().1, 3);
        assert_eq!(version(Some(&Value::from("1.27"))).unwrap().1, 27);
        for bad in ["2.0", "0.9", "1", "1.x", "1.2.3", ""] {
            assert!(version(Some(&Value::from(bad))).is_err(), "{bad}");
        }
        assert!(version(Some(&Value::from(1.0))).is_err());
    }

    #[test]
    fn a_later_minor_warns_and_unknown_members_are_listed() {
        let doc = r#"{"schemaVersion": "1.9", "extra": 1,
            "mandrelParameters": {"diameter": 100, "windLength": 400},
            "towParameters": {"width": 10, "thickness": 0.3},
            "defaultFeedRate": 1500, "layers": [{"windType": "hoop", "tension": 3}]}"#;
        let i = parse(doc, EYE_CLEARANCE_MM).unwrap();
        assert_eq!(i.schema_version, "1.9");
        assert_eq!(i.eye_radius, 75.0);
        assert_eq!(i.warnings.len(), 3, "{:?}", i.warnings);
        assert!(i.warnings[0].starts_with("schemaVersion"));
        assert!(
            i.warnings
                .iter()
                .any(|w| w.starts_with("layers[0].tension"))
        );
        assert!(i.warnings.iter().any(|w| w.starts_with("extra")));
    }
}
