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

use formcam_machine::IkMethod;
use formcam_machine::shipped::shipped;
use formcam_winding::job::{EyeJob, LayerKind, MandrelKind, MandrelSpec, WindingSpec};
use serde_json::{Map, Value};

use crate::ProgramError;
use crate::checks::Check;
use crate::error::WindFileError;
use crate::job::{JobMachine, Layers, MachineSource, MotionJob, Post, WindImport, WindJob};

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

/// One JSON object being read: the members asked for are remembered, so that
/// the others can be reported as unknown.
struct Obj<'a> {
    path: String,
    map: &'a Map<String, Value>,
    seen: Vec<&'static str>,
}

impl<'a> Obj<'a> {
    fn new(path: &str, v: Option<&'a Value>) -> Result<Self, WindFileError> {
        match v {
            Some(Value::Object(map)) => Ok(Self {
                path: path.to_string(),
                map,
                seen: Vec::new(),
            }),
            Some(_) => Err(WindFileError::NotAnObject {
                member: path.to_string(),
            }),
            None => Err(WindFileError::Missing {
                member: path.to_string(),
                unknown: Vec::new(),
            }),
        }
    }

    fn name(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    fn get(&mut self, key: &'static str) -> Option<&'a Value> {
        self.seen.push(key);
        self.map.get(key)
    }

    /// A missing required member; unknown members beside it are named, as they
    /// may be it misspelt.
    fn missing(&self, key: &str) -> WindFileError {
        WindFileError::Missing {
            member: self.name(key),
            unknown: self.unknown(),
        }
    }

    fn number(&mut self, key: &'static str) -> Result<Option<f64>, WindFileError> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => match v.as_f64() {
                Some(x) if x.is_finite() => Ok(Some(x)),
                _ => Err(WindFileError::NotFinite {
                    member: self.name(key),
                }),
            },
        }
    }

    fn required(&mut self, key: &'static str) -> Result<f64, WindFileError> {
        self.number(key)?.ok_or_else(|| self.missing(key))
    }

    /// A required number > 0.
    fn positive(&mut self, key: &'static str, unit: &'static str) -> Result<f64, WindFileError> {
        let value = self.required(key)?;
        if value > 0.0 {
            Ok(value)
        } else {
            Err(WindFileError::NotPositive {
                member: self.name(key),
                unit,
                value,
            })
        }
    }

    /// A required integer >= 1.
    fn count(&mut self, key: &'static str) -> Result<u32, WindFileError> {
        let v = self.required(key)?;
        if v >= 1.0 && v.fract() == 0.0 && v <= f64::from(u32::MAX) {
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            Ok(v as u32)
        } else {
            Err(WindFileError::NotACount {
                member: self.name(key),
                value: v,
            })
        }
    }

    fn boolean(&mut self, key: &'static str) -> Result<Option<bool>, WindFileError> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Bool(b)) => Ok(Some(*b)),
            Some(_) => Err(WindFileError::NotABoolean {
                member: self.name(key),
            }),
        }
    }

    fn unknown(&self) -> Vec<String> {
        self.map
            .keys()
            .filter(|k| !self.seen.contains(&k.as_str()))
            .map(|k| self.name(k))
            .collect()
    }

    /// Warnings for the members not read (the specification asks consumers
    /// to ignore them).
    fn ignored(&self, version: &str, out: &mut Vec<String>) {
        for k in self.unknown() {
            out.push(format!(
                "{k}: not a member of .wind {}.{} (the document says {version}); ignored",
                SPEC_VERSION.0, SPEC_VERSION.1
            ));
        }
    }
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
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

/// A helical layer's coverage rules: coprime pattern, the lead-in shorter than
/// the wind length, the circuit count (`ceil(pi D cos(angle) / width)`)
/// divisible by the pattern number, and for patterns of several circuits a
/// `lockDegrees` that steps the circuits onto distinct slots.
fn coverage(
    field: &dyn Fn(&str) -> String,
    h: &Helical,
    diameter: f64,
    wind_length: f64,
    width: f64,
) -> Result<(), WindFileError> {
    let p = h.pattern_number;
    if gcd(h.skip_index, p) != 1 {
        return Err(WindFileError::NotCoprime {
            member: field("skipIndex"),
            skip_index: h.skip_index,
            pattern: p,
            gcd: gcd(h.skip_index, p),
        });
    }
    if h.lead_in_mm >= wind_length {
        return Err(WindFileError::LeadInTooLong {
            member: field("leadInMM"),
            lead_in_mm: h.lead_in_mm,
            wind_length_mm: wind_length,
        });
    }
    let circuits = (std::f64::consts::PI * diameter * h.wind_angle.to_radians().cos() / width
        - 1e-9)
        .ceil()
        .max(0.0);
    if circuits % f64::from(p) != 0.0 {
        return Err(WindFileError::PatternDoesNotDivide {
            member: field("patternNumber"),
            pattern: p,
            circuits,
        });
    }
    if p > 1 {
        let slot = 360.0 / f64::from(p);
        let half = slot / 2.0;
        let advance = (2.0 * h.lock_degrees).rem_euclid(360.0);
        let slots = advance / slot;
        if (slots - slots.round()).abs() > 1e-6 {
            let k = (h.lock_degrees / half).floor().max(1.0);
            return Err(WindFileError::LockOffSlot {
                member: field("lockDegrees"),
                lock_deg: h.lock_degrees,
                half_slot_deg: half,
                below_deg: k * half,
                above_deg: (k + 1.0) * half,
            });
        }
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let stride = (slots.round() as u32 + h.skip_index) % p;
        if gcd(stride, p) != 1 {
            return Err(WindFileError::LockStride {
                member: field("lockDegrees"),
                lock_deg: h.lock_degrees,
                skip_index: h.skip_index,
                stride,
                pattern: p,
            });
        }
    }
    Ok(())
}

/// The members of a helical layer.
struct Helical {
    wind_angle: f64,
    pattern_number: u32,
    skip_index: u32,
    lock_degrees: f64,
    lead_in_mm: f64,
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

    // The mandrel.
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
    m.ignored(&version_text, &mut warnings);

    // The tow and the feed.
    let mut t = Obj::new("towParameters", root.get("towParameters"))?;
    let width = t.positive("width", "mm")?;
    let thickness = t.positive("thickness", "mm")?;
    t.ignored(&version_text, &mut warnings);
    root.positive("defaultFeedRate", "mm/min")?;

    // The layers.
    let layers = match root.get("layers") {
        Some(Value::Array(a)) => a,
        Some(_) => return Err(WindFileError::LayersNotAnArray),
        None => return Err(root.missing("layers")),
    };
    let base = WindingSpec {
        band_width: Some(width),
        band_thickness: Some(thickness),
        ..WindingSpec::default()
    };
    let mut out = Vec::with_capacity(layers.len());
    for (i, v) in layers.iter().enumerate() {
        let mut l = Obj::new(&format!("layers[{i}]"), Some(v))?;
        let path = l.path.clone();
        let field = |name: &str| format!("{path}.{name}");
        let kind = match l.get("windType") {
            Some(Value::String(s)) => s.clone(),
            Some(_) => {
                return Err(WindFileError::NotAString {
                    member: field("windType"),
                });
            }
            None => return Err(l.missing("windType")),
        };
        let hoop = |l: &mut Obj<'_>, terminal: bool| -> Result<WindingSpec, WindFileError> {
            if cone.is_some() {
                return Err(WindFileError::HoopOnCone {
                    layer: l.path.clone(),
                });
            }
            if terminal && i + 1 != layers.len() {
                return Err(WindFileError::TerminalNotLast {
                    member: field("terminal"),
                });
            }
            Ok(WindingSpec {
                kind: Some(LayerKind::Hoop),
                one_way: terminal.then_some(true),
                ..base.clone()
            })
        };
        let spec = match kind.as_str() {
            "hoop" => {
                let terminal = l.boolean("terminal")?.unwrap_or(false);
                hoop(&mut l, terminal)?
            }
            "helical" => {
                let wind_angle = l.required("windAngle")?;
                if !(wind_angle > 0.0 && wind_angle <= 90.0) {
                    return Err(WindFileError::WindAngle {
                        member: field("windAngle"),
                        angle_deg: wind_angle,
                    });
                }
                let h = Helical {
                    wind_angle,
                    pattern_number: l.count("patternNumber")?,
                    skip_index: l.count("skipIndex")?,
                    lock_degrees: l.positive("lockDegrees", "deg")?,
                    lead_in_mm: l.positive("leadInMM", "mm")?,
                };
                l.positive("leadOutDegrees", "deg")?;
                l.boolean("skipInitialNearLock")?;
                match l.number("frictionLambda")? {
                    Some(f) if f < 0.0 => {
                        return Err(WindFileError::FrictionNegative {
                            member: field("frictionLambda"),
                            value: f,
                        });
                    }
                    Some(f) if f != 0.0 => {
                        return Err(WindFileError::FrictionNotGeodesic {
                            member: field("frictionLambda"),
                            value: f,
                            cone: cone.is_some(),
                        });
                    }
                    _ => {}
                }
                if let Some(e) = cone
                    && diameter * wind_angle.to_radians().sin() > e
                {
                    return Err(WindFileError::TooSteepForCone {
                        member: field("windAngle"),
                        angle_deg: wind_angle,
                        max_deg: (e / diameter).asin().to_degrees(),
                    });
                }
                coverage(&field, &h, diameter, wind_length, width)?;
                if wind_angle == 90.0 {
                    // The specification's limit of a helical layer: a hoop.
                    hoop(&mut l, false)?
                } else {
                    WindingSpec {
                        kind: Some(LayerKind::Helical),
                        winding_angle_deg: Some(wind_angle),
                        pattern_number: Some(h.pattern_number),
                        skip_index: Some(h.skip_index),
                        dwell_min_deg: Some(h.lock_degrees),
                        ..base.clone()
                    }
                }
            }
            "skip" => WindingSpec {
                kind: Some(LayerKind::Skip),
                mandrel_rotation_deg: Some(l.required("mandrelRotation")?),
                ..WindingSpec::default()
            },
            other => {
                return Err(WindFileError::UnknownLayerType {
                    member: field("windType"),
                    kind: other.into(),
                });
            }
        };
        l.ignored(&version_text, &mut warnings);
        out.push(spec);
    }
    root.ignored(&version_text, &mut warnings);
    if out.is_empty() {
        warnings.push("layers: none; the program holds no motion".into());
    }

    let r_max = diameter / 2.0;
    let mandrel = match cone {
        None => MandrelSpec {
            kind: Some(MandrelKind::Cylinder),
            radius: Some(r_max),
            length: Some(wind_length),
            ..MandrelSpec::default()
        },
        Some(e) => MandrelSpec {
            kind: Some(MandrelKind::Cone),
            radius_start: Some(r_max),
            radius_end: Some(e / 2.0),
            length: Some(wind_length),
            ..MandrelSpec::default()
        },
    };
    let eye_radius = r_max + eye_clearance;
    let eye = EyeJob {
        mode: Some("axis-parallel".into()),
        radius: Some(eye_radius),
        // The laid band may come up to half the clearance.
        clearance: Some(eye_clearance / 2.0),
        // The format knows no free-length limit.
        l_max: Some(1.0e6),
        ..EyeJob::default()
    };
    Ok(Imported {
        mandrel,
        layers: out,
        eye,
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
