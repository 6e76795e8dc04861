use thiserror::Error;

/// Everything that can be wrong with a shape's input.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GeomError {
    /// A number is NaN or infinite.
    #[error("{field} must be a finite number, got {value}")]
    NotFinite {
        /// Name of the input field.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// A length or radius that must be strictly positive is not.
    #[error("{field} must be > 0 mm, got {value}")]
    NotPositive {
        /// Name of the input field.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// A value lies outside its allowed range.
    #[error("{field} = {value} is out of range: {allowed}")]
    OutOfRange {
        /// Name of the input field.
        field: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range in words, e.g. `"0 < polar_opening < radius (100)"`.
        allowed: String,
    },
    /// A table of meridian points is unusable.
    #[error("point {row}: {reason}")]
    Table {
        /// 1-based row number in the table (data rows, header not counted).
        row: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// A table has too few points for a spline.
    #[error("{count} points, at least 4 are needed")]
    TooFewPoints {
        /// Number of points found.
        count: usize,
    },
}
