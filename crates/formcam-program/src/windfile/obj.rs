//! One JSON object of a `.wind` document being read, its members checked and
//! the members not read reported.

use serde_json::{Map, Value};

use super::SPEC_VERSION;
use crate::error::WindFileError;

/// One JSON object being read: the members asked for are remembered, so that
/// the others can be reported as unknown.
pub(super) struct Obj<'a> {
    pub(super) path: String,
    map: &'a Map<String, Value>,
    seen: Vec<&'static str>,
}

impl<'a> Obj<'a> {
    pub(super) fn new(path: &str, v: Option<&'a Value>) -> Result<Self, WindFileError> {
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

    pub(super) fn name(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    pub(super) fn get(&mut self, key: &'static str) -> Option<&'a Value> {
        self.seen.push(key);
        self.map.get(key)
    }

    /// A missing required member; unknown members beside it are named, as they
    /// may be it misspelt.
    pub(super) fn missing(&self, key: &str) -> WindFileError {
        WindFileError::Missing {
            member: self.name(key),
            unknown: self.unknown(),
        }
    }

    pub(super) fn number(&mut self, key: &'static str) -> Result<Option<f64>, WindFileError> {
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

    pub(super) fn required(&mut self, key: &'static str) -> Result<f64, WindFileError> {
        self.number(key)?.ok_or_else(|| self.missing(key))
    }

    /// A required number > 0.
    pub(super) fn positive(
        &mut self,
        key: &'static str,
        unit: &'static str,
    ) -> Result<f64, WindFileError> {
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
    pub(super) fn count(&mut self, key: &'static str) -> Result<u32, WindFileError> {
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

    pub(super) fn boolean(&mut self, key: &'static str) -> Result<Option<bool>, WindFileError> {
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
    pub(super) fn ignored(&self, version: &str, out: &mut Vec<String>) {
        for k in self.unknown() {
            out.push(format!(
                "{k}: not a member of .wind {}.{} (the document says {version}); ignored",
                SPEC_VERSION.0, SPEC_VERSION.1
            ));
        }
    }
}
