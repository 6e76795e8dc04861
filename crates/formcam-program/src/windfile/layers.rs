//! The tow and the layers of a `.wind` document: hoop, helical (its coverage
//! rules) and skip layers as formcam's.

use formcam_winding::job::{LayerKind, WindingSpec};
use serde_json::Value;

use super::mandrel::Mandrel;
use super::obj::Obj;
use crate::error::WindFileError;

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
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

/// The members of `towParameters`, checked.
pub(super) struct Tow {
    /// The band's width, mm.
    pub(super) width: f64,
    /// The band's thickness, mm.
    pub(super) thickness: f64,
}

impl Tow {
    /// Reads `towParameters` of `root`; members not read are warned of.
    pub(super) fn read(
        root: &mut Obj<'_>,
        version: &str,
        warnings: &mut Vec<String>,
    ) -> Result<Tow, WindFileError> {
        let mut t = Obj::new("towParameters", root.get("towParameters"))?;
        let width = t.positive("width", "mm")?;
        let thickness = t.positive("thickness", "mm")?;
        t.ignored(version, warnings);
        Ok(Tow { width, thickness })
    }
}

/// Reads `layers` of `root` on `mandrel` with `tow`; members not read are
/// warned of.
pub(super) fn read_layers(
    root: &mut Obj<'_>,
    mandrel: &Mandrel,
    tow: &Tow,
    version: &str,
    warnings: &mut Vec<String>,
) -> Result<Vec<WindingSpec>, WindFileError> {
    let layers = match root.get("layers") {
        Some(Value::Array(a)) => a,
        Some(_) => return Err(WindFileError::LayersNotAnArray),
        None => return Err(root.missing("layers")),
    };
    let reader = LayerReader {
        mandrel,
        width: tow.width,
        base: WindingSpec {
            band_width: Some(tow.width),
            band_thickness: Some(tow.thickness),
            ..WindingSpec::default()
        },
        count: layers.len(),
    };
    let mut out = Vec::with_capacity(layers.len());
    for (i, v) in layers.iter().enumerate() {
        let mut l = Obj::new(&format!("layers[{i}]"), Some(v))?;
        let spec = reader.layer(i, &mut l)?;
        l.ignored(version, warnings);
        out.push(spec);
    }
    Ok(out)
}

/// What every layer is read against.
struct LayerReader<'m> {
    /// The mandrel.
    mandrel: &'m Mandrel,
    /// The band's width, mm.
    width: f64,
    /// Every wound layer's band.
    base: WindingSpec,
    /// How many layers the document holds.
    count: usize,
}

impl LayerReader<'_> {
    /// Layer `i`, `l`, by its `windType`.
    fn layer(&self, i: usize, l: &mut Obj<'_>) -> Result<WindingSpec, WindFileError> {
        let kind = match l.get("windType") {
            Some(Value::String(s)) => s.clone(),
            Some(_) => {
                return Err(WindFileError::NotAString {
                    member: l.name("windType"),
                });
            }
            None => return Err(l.missing("windType")),
        };
        match kind.as_str() {
            "hoop" => {
                let terminal = l.boolean("terminal")?.unwrap_or(false);
                self.hoop(i, l, terminal)
            }
            "helical" => self.helical(i, l),
            "skip" => Ok(WindingSpec {
                kind: Some(LayerKind::Skip),
                mandrel_rotation_deg: Some(l.required("mandrelRotation")?),
                ..WindingSpec::default()
            }),
            other => Err(WindFileError::UnknownLayerType {
                member: l.name("windType"),
                kind: other.into(),
            }),
        }
    }

    /// A hoop layer, `terminal` wound one way (only the last may be).
    fn hoop(&self, i: usize, l: &Obj<'_>, terminal: bool) -> Result<WindingSpec, WindFileError> {
        if self.mandrel.cone.is_some() {
            return Err(WindFileError::HoopOnCone {
                layer: l.path.clone(),
            });
        }
        if terminal && i + 1 != self.count {
            return Err(WindFileError::TerminalNotLast {
                member: l.name("terminal"),
            });
        }
        Ok(WindingSpec {
            kind: Some(LayerKind::Hoop),
            one_way: terminal.then_some(true),
            ..self.base.clone()
        })
    }

    /// A helical layer: its members, friction, the cone's limit and the
    /// coverage checked; at 90° a hoop.
    fn helical(&self, i: usize, l: &mut Obj<'_>) -> Result<WindingSpec, WindFileError> {
        let h = helical_members(l)?;
        self.check_friction(l)?;
        let Mandrel {
            diameter,
            wind_length,
            cone,
        } = *self.mandrel;
        if let Some(e) = cone
            && diameter * h.wind_angle.to_radians().sin() > e
        {
            return Err(WindFileError::TooSteepForCone {
                member: l.name("windAngle"),
                angle_deg: h.wind_angle,
                max_deg: (e / diameter).asin().to_degrees(),
            });
        }
        coverage(&|name| l.name(name), &h, diameter, wind_length, self.width)?;
        if h.wind_angle == 90.0 {
            // The specification's limit of a helical layer: a hoop.
            self.hoop(i, l, false)
        } else {
            Ok(WindingSpec {
                kind: Some(LayerKind::Helical),
                winding_angle_deg: Some(h.wind_angle),
                pattern_number: Some(h.pattern_number),
                skip_index: Some(h.skip_index),
                dwell_min_deg: Some(h.lock_degrees),
                ..self.base.clone()
            })
        }
    }

    /// `frictionLambda`: absent or zero (formcam winds geodesics only).
    fn check_friction(&self, l: &mut Obj<'_>) -> Result<(), WindFileError> {
        match l.number("frictionLambda")? {
            Some(f) if f < 0.0 => Err(WindFileError::FrictionNegative {
                member: l.name("frictionLambda"),
                value: f,
            }),
            Some(f) if f != 0.0 => Err(WindFileError::FrictionNotGeodesic {
                member: l.name("frictionLambda"),
                value: f,
                cone: self.mandrel.cone.is_some(),
            }),
            _ => Ok(()),
        }
    }
}

/// A helical layer's members, checked one by one, and those it checks but
/// does not use (`leadOutDegrees`, `skipInitialNearLock`).
fn helical_members(l: &mut Obj<'_>) -> Result<Helical, WindFileError> {
    let wind_angle = l.required("windAngle")?;
    if !(wind_angle > 0.0 && wind_angle <= 90.0) {
        return Err(WindFileError::WindAngle {
            member: l.name("windAngle"),
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
    Ok(h)
}
