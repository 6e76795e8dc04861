//! Everything that can stop a dressing computation.

use formcam_files::quote;
use formcam_nc::NcError;
use thiserror::Error;

/// Everything that can stop a dressing computation. Messages are one line and
/// name the job field (dotted, as users write it) and what is allowed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DressError {
    /// A job field is out of range or inconsistent with the others.
    #[error("{field} = {value}: {reason}")]
    Field {
        /// Dotted name of the field, e.g. `wheel.r2`.
        field: String,
        /// The value as given, with its unit.
        value: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// A job field that must be there is missing.
    #[error("{field}: {reason}")]
    Missing {
        /// Dotted name of the field.
        field: String,
        /// What it is needed for.
        reason: String,
    },
    /// The job's TOML could not be read (syntax, unknown fields, types).
    #[error("line {line}, column {column}: {message}")]
    Toml {
        /// 1-based line of the problem (0 when unknown).
        line: usize,
        /// 1-based column.
        column: usize,
        /// What the TOML reader said.
        message: String,
    },
    /// The job does not match its description ([`crate::DRESS_JOB`]): an
    /// unknown table or field, a wrong type, a value out of range, a missing
    /// field; each names the field, its `line:column` and what is allowed.
    #[error(transparent)]
    Schema(formcam_schema::SchemaError),
    /// A user's initial wheel contour cannot be used.
    #[error("process.initial_contour: {0}")]
    Contour(#[from] ContourFault),
    /// A line of the initial contour's CSV cannot be read.
    #[error("process.initial_contour, line {line}: {problem}")]
    ContourLine {
        /// 1-based line of the file.
        line: usize,
        /// What is wrong and what is expected.
        problem: ContourLineProblem,
    },
    /// The NC program could not be written.
    #[error("program: {0}")]
    Nc(#[from] NcError),
    /// The run was cancelled by its progress hook.
    #[error(transparent)]
    Cancelled(#[from] formcam_progress::Cancelled),
}

/// Why a wheel contour cannot be used.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ContourFault {
    /// Fewer than two points.
    #[error("a contour needs at least two points")]
    TooFewPoints,
    /// The contour's file holds fewer than two points.
    #[error("the file holds fewer than two points z,x")]
    FileTooShort,
    /// A point that is NaN or infinite.
    #[error("point {point} is not finite")]
    NotFinite {
        /// The point (1-based).
        point: usize,
    },
    /// Points out of order along the wheel's axis.
    #[error("x decreases from {from} to {to} at point {point}")]
    Decreasing {
        /// The point before, mm.
        from: f64,
        /// This point, mm.
        to: f64,
        /// The point (1-based).
        point: usize,
    },
    /// The contour does not span the wheel's width.
    #[error(
        "it spans z from {} to {}; it must cover the wheel's width, -{} to {}",
        mm(*.from),
        mm(*.to),
        mm(*.half_width),
        mm(*.half_width)
    )]
    NotCovering {
        /// Where it starts, mm.
        from: f64,
        /// Where it ends, mm.
        to: f64,
        /// Half the wheel's width, mm.
        half_width: f64,
    },
    /// The contour lies below the profile, which dressing cannot restore.
    #[error(
        "it lies {} below the profile at z = {}: the dresser cannot restore the profile there",
        mm(*.depth),
        mm(*.z)
    )]
    BelowProfile {
        /// How far below, mm.
        depth: f64,
        /// Where, mm.
        z: f64,
    },
    /// The job names a contour file whose points were not given.
    #[error("{} was not read", quote(.file))]
    NotRead {
        /// The file as the job names it.
        file: String,
    },
}

/// Why a line of the initial contour's CSV cannot be read.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ContourLineProblem {
    /// A cell that is not a number after the header.
    #[error("expected numbers z,x (mm) in every column")]
    NotNumbers,
    /// A header naming other columns.
    #[error(
        "the header names the columns {}; expected z,x (mm: z along the wheel's axis, x radial) \
         or the older x,y",
        quote(.header)
    )]
    Header {
        /// The header as written (its cells joined by commas).
        header: String,
    },
    /// A coordinate that is NaN or infinite.
    #[error("z and x must be finite numbers (mm)")]
    NotFinite,
    /// A row with fewer than two numbers.
    #[error("expected two numbers z,x (mm)")]
    TooFewNumbers,
    /// `z` smaller than on the row before.
    #[error("z decreases from {from} to {to}: the points must run along the wheel's axis")]
    Decreasing {
        /// `z` on the row before, mm.
        from: f64,
        /// `z` on this row, mm.
        to: f64,
    },
}

impl DressError {
    /// A field error: `field = value: reason`.
    pub fn field(
        field: impl Into<String>,
        value: impl Into<String>,
        reason: impl Into<String>,
    ) -> Self {
        Self::Field {
            field: field.into(),
            value: value.into(),
            reason: reason.into(),
        }
    }
}

/// A length for messages: `0.296 mm` (up to 6 decimals, trailing zeros cut).
pub(crate) fn mm(v: f64) -> String {
    format!("{} mm", num(v))
}

/// An angle for messages in degrees: `45°`.
pub(crate) fn deg(v: f64) -> String {
    format!("{}°", num(v))
}

/// A number for messages: up to 6 decimals, trailing zeros cut; `NaN`, `inf`.
pub(crate) fn num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    // Six decimals, or six significant digits for small values (so that a
    // tiny value never reads as 0).
    let s = if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:.5e}")
    } else {
        format!("{v:.6}")
    };
    let (mantissa, exp) = match s.find('e') {
        Some(k) => (&s[..k], &s[k..]),
        None => (s.as_str(), ""),
    };
    let m = if mantissa.contains('.') {
        mantissa.trim_end_matches('0').trim_end_matches('.')
    } else {
        mantissa
    };
    let out = format!("{m}{exp}");
    if out == "-0" { "0".into() } else { out }
}

/// Checks that `v` is finite, naming `field` (with `unit` for the message).
pub(crate) fn finite(field: &str, v: f64, unit: &str) -> Result<f64, DressError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(DressError::field(
            field,
            format!("{v}{unit}"),
            "must be a finite number",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_for_messages() {
        assert_eq!(num(0.296), "0.296");
        assert_eq!(num(6.0), "6");
        assert_eq!(num(-0.0000001), "-1e-7");
        assert_eq!(num(1.23456789e-4), "1.23457e-4");
        assert_eq!(num(-0.0), "0");
        assert_eq!(mm(0.9), "0.9 mm");
        assert_eq!(deg(45.0), "45°");
        assert_eq!(num(f64::NAN), "NaN");
    }

    #[test]
    fn field_message_is_one_line() {
        let e = DressError::field("wheel.r2", mm(0.9), "too big");
        assert_eq!(e.to_string(), "wheel.r2 = 0.9 mm: too big");
        assert!(finite("process.step", f64::NAN, " mm").is_err());
    }
}
