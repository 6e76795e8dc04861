//! The correction job: what to correct and how (`Settings`), from a
//! `[correct]` job file or the command line's options.
//!
//! ```toml
//! [correct]
//! measurements = "correct/cmm.csv"   # CSV or DMIS, relative to the job's folder
//! program = "correct/mould.nc"       # G-code or a node table (.csv)
//! tool = "ball:6"                    # point | ball:R (mm)
//! interpolation = "bicubic"          # bilinear | bicubic
//! gain = 1.0                         # (0, 2]
//! margin_mm = 5.0                    # extrapolate this far beyond the measured area
//! noise_mm = 0.003                   # smooth for this CMM noise (0: as measured)
//! arc_tolerance_mm = 0.001           # G2/G3 written back as chords within this
//! # dialect = "iso"                  # iso | fanuc | sinumerik-840d | linuxcnc
//! # points_per_section = 21          # resample every section to this many points
//! # max_segment_mm = 10.0            # split longer feed moves
//! # max_deviation_mm = 5.0           # the largest plausible deviation and displacement
//! ```

use std::fmt;
use std::path::{Path, PathBuf};

use formcam_nc::Dialect;
use serde::Deserialize;

use crate::{CorrectError, Options, Tool};

/// The default of the largest plausible deviation and displacement, mm.
pub const DEFAULT_MAX_DEVIATION_MM: f64 = 5.0;

/// The default chord tolerance of arcs written back as `G1`, mm.
pub const DEFAULT_ARC_TOLERANCE_MM: f64 = 0.001;

/// A setting of a correction, as errors name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JobField {
    /// The CMM report.
    Measurements,
    /// The milling program.
    Program,
    /// `point` or `ball:R`.
    Tool,
    /// `bilinear` or `bicubic`.
    Interpolation,
    /// The gain, (0, 2].
    Gain,
    /// The extrapolation margin, mm.
    Margin,
    /// The CMM noise, mm.
    Noise,
    /// The chord tolerance of linearised arcs, mm.
    ArcTolerance,
    /// The program's syntax.
    Dialect,
    /// Points per section after resampling.
    PointsPerSection,
    /// The longest feed move kept whole, mm.
    MaxSegment,
    /// The largest plausible deviation and displacement, mm.
    MaxDeviation,
}

impl JobField {
    /// The field's key in the `[correct]` table.
    pub fn key(self) -> &'static str {
        match self {
            Self::Measurements => "measurements",
            Self::Program => "program",
            Self::Tool => "tool",
            Self::Interpolation => "interpolation",
            Self::Gain => "gain",
            Self::Margin => "margin_mm",
            Self::Noise => "noise_mm",
            Self::ArcTolerance => "arc_tolerance_mm",
            Self::Dialect => "dialect",
            Self::PointsPerSection => "points_per_section",
            Self::MaxSegment => "max_segment_mm",
            Self::MaxDeviation => "max_deviation_mm",
        }
    }
}

impl fmt::Display for JobField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "correct.{}", self.key())
    }
}

/// How to correct: the options of the correction and of reading the
/// program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Gain, tool, interpolation and margin.
    pub options: Options,
    /// The CMM's noise (standard deviation, mm); 0 takes the deviations as
    /// measured.
    pub noise_mm: f64,
    /// Arcs are written back as `G1` chords within this distance, mm.
    pub arc_tolerance_mm: f64,
    /// The program's syntax (default: from its file extension).
    pub dialect: Option<Dialect>,
    /// Resample every section to this many points (default: as measured
    /// when all sections have the same count, else the largest count).
    pub points_per_section: Option<usize>,
    /// Split straight feed moves longer than this (mm).
    pub max_segment_mm: Option<f64>,
    /// The largest plausible deviation and node displacement, mm.
    pub max_deviation_mm: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            options: Options::default(),
            noise_mm: 0.0,
            arc_tolerance_mm: DEFAULT_ARC_TOLERANCE_MM,
            dialect: None,
            points_per_section: None,
            max_segment_mm: None,
            max_deviation_mm: DEFAULT_MAX_DEVIATION_MM,
        }
    }
}

impl Settings {
    /// Checks every range; the error names the field
    /// ([`CorrectError::Field`]).
    pub fn check(&self) -> Result<(), CorrectError> {
        let bad = |field: JobField, value: f64, rule: &str| {
            Err(CorrectError::Field {
                field,
                value: value.to_string(),
                rule: rule.to_string(),
            })
        };
        let o = &self.options;
        if !(o.gain.is_finite() && o.gain > 0.0 && o.gain <= 2.0) {
            return bad(JobField::Gain, o.gain, "allowed (0, 2]");
        }
        if let Tool::Ball { radius } = o.tool
            && !(radius.is_finite() && radius > 0.0)
        {
            return Err(CorrectError::Field {
                field: JobField::Tool,
                value: format!("ball:{radius}"),
                rule: "the ball radius must be > 0 mm".into(),
            });
        }
        if !(o.margin_mm.is_finite() && o.margin_mm >= 0.0) {
            return bad(JobField::Margin, o.margin_mm, "must be >= 0 mm");
        }
        if !(self.noise_mm.is_finite() && self.noise_mm >= 0.0) {
            return bad(JobField::Noise, self.noise_mm, "must be >= 0 mm");
        }
        if !(self.max_deviation_mm.is_finite() && self.max_deviation_mm > 0.0) {
            return bad(
                JobField::MaxDeviation,
                self.max_deviation_mm,
                "must be > 0 mm",
            );
        }
        if let Some(m) = self.max_segment_mm
            && !(m.is_finite() && m > 0.0)
        {
            return bad(JobField::MaxSegment, m, "must be > 0 mm");
        }
        if !(self.arc_tolerance_mm.is_finite() && self.arc_tolerance_mm > 0.0) {
            return bad(
                JobField::ArcTolerance,
                self.arc_tolerance_mm,
                "must be > 0 mm",
            );
        }
        Ok(())
    }
}

/// A correction job: the CMM report, the program and the settings.
#[derive(Debug, Clone, PartialEq)]
pub struct CorrectionJob {
    /// The CMM report (CSV, or DMIS by its extension `.dmi`, `.dmis`,
    /// `.dms`, `.dmo`).
    pub measurements: PathBuf,
    /// The milling program (G-code, or a node table `.csv`).
    pub program: PathBuf,
    /// How to correct.
    pub settings: Settings,
}

/// The file form: `[correct]` and nothing else.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct JobFile {
    correct: JobTable,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct JobTable {
    measurements: PathBuf,
    program: PathBuf,
    tool: Option<String>,
    interpolation: Option<String>,
    gain: Option<f64>,
    margin_mm: Option<f64>,
    noise_mm: Option<f64>,
    arc_tolerance_mm: Option<f64>,
    dialect: Option<String>,
    points_per_section: Option<usize>,
    max_segment_mm: Option<f64>,
    max_deviation_mm: Option<f64>,
}

impl CorrectionJob {
    /// Whether a TOML table is a correction job (it has `[correct]`).
    pub fn is_job(table: &toml::Table) -> bool {
        table.contains_key("correct")
    }

    /// Reads a `[correct]` job; its paths are taken relative to `base_dir`
    /// (the job file's folder). Errors name the job's field.
    pub fn from_toml(text: &str, base_dir: &Path) -> Result<Self, CorrectError> {
        let table: toml::Table =
            toml::from_str(text).map_err(|e| CorrectError::Job(e.message().to_string()))?;
        if !Self::is_job(&table) {
            return Err(CorrectError::Job(
                "no [correct] table (a correction job names measurements and program there; \
                 see examples/correct-mould.toml)"
                    .into(),
            ));
        }
        let f: JobFile =
            toml::from_str(text).map_err(|e| CorrectError::Job(e.message().to_string()))?;
        let j = f.correct;
        let named = |field: JobField, value: &str, e: CorrectError| CorrectError::Field {
            field,
            value: format!("\"{value}\""),
            rule: e.to_string(),
        };
        let d = Settings::default();
        let tool = match &j.tool {
            Some(s) => s.parse().map_err(|e| named(JobField::Tool, s, e))?,
            None => d.options.tool,
        };
        let interpolation = match &j.interpolation {
            Some(s) => s
                .parse()
                .map_err(|e| named(JobField::Interpolation, s, e))?,
            None => d.options.interpolation,
        };
        let dialect = match &j.dialect {
            Some(s) => Some(
                Dialect::from_name(s)
                    .map_err(|e| named(JobField::Dialect, s, CorrectError::from(e)))?,
            ),
            None => None,
        };
        let settings = Settings {
            options: Options {
                gain: j.gain.unwrap_or(d.options.gain),
                tool,
                interpolation,
                margin_mm: j.margin_mm.unwrap_or(d.options.margin_mm),
            },
            noise_mm: j.noise_mm.unwrap_or(d.noise_mm),
            arc_tolerance_mm: j.arc_tolerance_mm.unwrap_or(d.arc_tolerance_mm),
            dialect,
            points_per_section: j.points_per_section,
            max_segment_mm: j.max_segment_mm,
            max_deviation_mm: j.max_deviation_mm.unwrap_or(d.max_deviation_mm),
        };
        settings.check()?;
        Ok(Self {
            measurements: base_dir.join(&j.measurements),
            program: base_dir.join(&j.program),
            settings,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_minimal_job_takes_the_defaults_and_its_paths_from_the_folder() {
        let j = CorrectionJob::from_toml(
            "[correct]\nmeasurements = \"cmm.csv\"\nprogram = \"m.nc\"\n",
            Path::new("jobs"),
        );
        assert_eq!(
            j,
            Ok(CorrectionJob {
                measurements: Path::new("jobs").join("cmm.csv"),
                program: Path::new("jobs").join("m.nc"),
                settings: Settings::default(),
            })
        );
    }
}
