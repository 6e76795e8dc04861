//! The point features of a DMIS output file, read statement by statement.

use super::{MeasuredPoint, Measurements, bad};
use crate::vec3::{V3, norm, scale, unit};
use crate::{CorrectError, MeasureError, MeasureProblem};

/// The statements of a DMIS text, each with the line it starts on: `$$`
/// comments cut, `$` continuations joined (a statement still continued at
/// the end is dropped).
pub(super) fn dmis_statements(text: &str) -> Vec<(usize, String)> {
    let mut statements = Vec::new();
    let mut stmt = String::new();
    let mut stmt_line = 0;
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let l = match raw.find("$$") {
            Some(k) => &raw[..k],
            None => raw,
        }
        .trim();
        if stmt.is_empty() {
            stmt_line = line;
        }
        if let Some(c) = l.strip_suffix('$') {
            stmt.push_str(c);
            continue;
        }
        stmt.push_str(l);
        statements.push((stmt_line, std::mem::take(&mut stmt)));
    }
    statements
}

/// The point features of a DMIS file as read so far: the nominals in order
/// (label, line, point, normal), the actuals by label (line, point), and the
/// length unit in mm.
pub(super) struct DmisFeatures {
    nominal: Vec<(String, usize, V3, Option<V3>)>,
    actual: std::collections::HashMap<String, (usize, V3)>,
    unit_scale: f64,
}

impl DmisFeatures {
    pub(super) fn new() -> Self {
        Self {
            nominal: Vec::new(),
            actual: std::collections::HashMap::new(),
            unit_scale: 1.0,
        }
    }

    /// One statement `s` starting on `line`: a unit, a point feature, or
    /// another statement passed over.
    pub(super) fn read(&mut self, line: usize, s: &str) -> Result<(), CorrectError> {
        let u = s.to_ascii_uppercase();
        if let Some(rest) = u.strip_prefix("UNITS/") {
            self.unit_scale = dmis_unit(line, rest)?;
            return Ok(());
        }
        let Some(DmisPoint {
            is_actual,
            label,
            parts,
        }) = dmis_point(line, s, &u)?
        else {
            return Ok(());
        };
        let p = scale(
            [
                dmis_number(line, &label, &parts, 2)?,
                dmis_number(line, &label, &parts, 3)?,
                dmis_number(line, &label, &parts, 4)?,
            ],
            self.unit_scale,
        );
        let n = if parts.len() >= 8 {
            let n = [
                dmis_number(line, &label, &parts, 5)?,
                dmis_number(line, &label, &parts, 6)?,
                dmis_number(line, &label, &parts, 7)?,
            ];
            (norm(n) > 1e-9).then(|| unit(n))
        } else {
            None
        };
        if is_actual {
            if self.actual.insert(label.clone(), (line, p)).is_some() {
                return Err(bad(line, MeasureProblem::ActualTwice { label }));
            }
        } else {
            self.nominal.push((label, line, p, n));
        }
        Ok(())
    }

    /// Each nominal with its actual, in the nominals' order, as the point
    /// its label names.
    pub(super) fn measurements(self) -> Result<Measurements, CorrectError> {
        let mut m = Measurements::default();
        for (label, line, p, n) in self.nominal {
            let Some(&(_, a)) = self.actual.get(&label) else {
                return Err(bad(line, MeasureProblem::NoMeasuredFeature { label }));
            };
            let Some(k) = label.rfind(['_', '.', '-']) else {
                return Err(bad(line, MeasureProblem::LabelName { label }));
            };
            m.push(
                label[..k].to_string(),
                MeasuredPoint {
                    point: label[k + 1..].to_string(),
                    nominal: p,
                    actual: a,
                    normal: n,
                },
                line,
            )?;
        }
        if m.is_empty() {
            return Err(MeasureError::NoFeatures.into());
        }
        m.finish()
    }
}

/// The length unit of `UNITS/<rest>` in mm.
fn dmis_unit(line: usize, rest: &str) -> Result<f64, CorrectError> {
    let unit = rest.split(',').next().unwrap_or("").trim();
    match unit {
        "MM" => Ok(1.0),
        "INCH" => Ok(25.4),
        "CM" => Ok(10.0),
        "METER" => Ok(1000.0),
        other => Err(bad(line, MeasureProblem::Unit { unit: other.into() })),
    }
}

/// A point feature: whether it is an actual, its label (as written) and the
/// fields of its definition (upper-cased).
struct DmisPoint<'u> {
    is_actual: bool,
    label: String,
    parts: Vec<&'u str>,
}

/// The point feature of statement `s` (`u` upper-cased); `None` for a
/// statement that is no point feature.
fn dmis_point<'u>(line: usize, s: &str, u: &'u str) -> Result<Option<DmisPoint<'u>>, CorrectError> {
    let (is_actual, rest) = if let Some(r) = u.strip_prefix("FA(") {
        (true, r)
    } else if let Some(r) = u.strip_prefix("F(") {
        (false, r)
    } else {
        return Ok(None);
    };
    let Some(close) = rest.find(')') else {
        return Err(bad(line, MeasureProblem::OpenLabel));
    };
    let label = s[s.find('(').map_or(0, |k| k + 1)..][..close]
        .trim()
        .to_string();
    let def = rest[close + 1..].trim_start();
    let Some(def) = def.strip_prefix('=') else {
        return Ok(None);
    };
    let def = def.trim();
    if !def.starts_with("FEAT/POINT") {
        return Ok(None);
    }
    let parts: Vec<&str> = def.split(',').map(str::trim).collect();
    if parts.get(1) != Some(&"CART") {
        return Err(bad(line, MeasureProblem::NotCartesian { label }));
    }
    Ok(Some(DmisPoint {
        is_actual,
        label,
        parts,
    }))
}

/// Field `k` of feature `label`'s definition as a finite number.
fn dmis_number(line: usize, label: &str, parts: &[&str], k: usize) -> Result<f64, CorrectError> {
    let s = parts.get(k).ok_or_else(|| {
        bad(
            line,
            MeasureProblem::FewCoordinates {
                label: label.to_string(),
            },
        )
    })?;
    let v: f64 = s.parse().map_err(|_| {
        bad(
            line,
            MeasureProblem::FeatureNotANumber {
                label: label.to_string(),
                text: (*s).into(),
            },
        )
    })?;
    if !v.is_finite() {
        return Err(bad(
            line,
            MeasureProblem::FeatureNotFinite {
                label: label.to_string(),
                text: (*s).into(),
            },
        ));
    }
    Ok(v)
}
