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

use formcam_nc::{Aliases, Dialect};
use formcam_schema::{
    Default as Preset, Field, JobSchema, Kind, Range, Repeat, SchemaError, Table, Unit, Value,
    field, validate,
};
use serde::Deserialize;

use crate::error::refused_value;
use crate::{
    CorrectError, DEFAULT_GAIN, GAIN_RANGE, Given, Interpolation, MARGIN_RANGE, Options, Rule,
};

/// The default of the largest plausible deviation and displacement, mm.
pub const DEFAULT_MAX_DEVIATION_MM: f64 = 5.0;

/// The default chord tolerance of arcs written back as `G1`, mm.
pub const DEFAULT_ARC_TOLERANCE_MM: f64 = 0.001;

/// The interpolations' names.
pub const INTERPOLATIONS: &[&str] = <Interpolation as strum::VariantNames>::VARIANTS;

/// The dialects a milling program is read in.
const MILLING: [Dialect; 4] = [
    Dialect::Iso,
    Dialect::Sinumerik840d,
    Dialect::LinuxCnc,
    Dialect::MarlinXab,
];

/// The names of [`MILLING`]'s dialects, each with its aliases (any case).
pub const MILLING_DIALECTS: &[&str] = &Dialect::names_of::<7>(&MILLING, Aliases::Each);

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
    /// Every setting, in the order of the `[correct]` table's description.
    pub const ALL: [JobField; 12] = [
        Self::Measurements,
        Self::Program,
        Self::Tool,
        Self::Interpolation,
        Self::Gain,
        Self::Margin,
        Self::Noise,
        Self::ArcTolerance,
        Self::Dialect,
        Self::PointsPerSection,
        Self::MaxSegment,
        Self::MaxDeviation,
    ];

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

    /// The setting whose key is `key`.
    pub fn from_key(key: &str) -> Option<JobField> {
        Self::ALL.into_iter().find(|f| f.key() == key)
    }

    /// The field's description in [`CORRECT_JOB`]: its kind, unit, range,
    /// default and help.
    pub fn described(self) -> Option<&'static Field> {
        CORRECT.field(self.key())
    }

    /// `v` against the field's range.
    fn check(self, v: f64) -> Result<(), CorrectError> {
        match self.described().map(|f| Rule::check(f, v)) {
            Some(Err(rule)) => Err(CorrectError::Field {
                field: self,
                value: Given::Number(v),
                rule,
            }),
            _ => Ok(()),
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
    /// Checks every range against the `[correct]` table's description; the
    /// error names the field ([`CorrectError::Field`]).
    pub fn check(&self) -> Result<(), CorrectError> {
        self.options.validate()?;
        JobField::Noise.check(self.noise_mm)?;
        JobField::MaxDeviation.check(self.max_deviation_mm)?;
        if let Some(m) = self.max_segment_mm {
            JobField::MaxSegment.check(m)?;
        }
        JobField::ArcTolerance.check(self.arc_tolerance_mm)?;
        if let Some(n) = self.points_per_section {
            JobField::PointsPerSection.check(n as f64)?;
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

    /// Reads a `[correct]` job, validated first against [`CORRECT_JOB`];
    /// its paths are taken relative to `base_dir` (the job file's folder).
    /// Errors name the job's field: a value out of its range or list as
    /// [`CorrectError::Field`] (the words of [`Settings::check`]), other
    /// refusals with their `line:column`.
    pub fn from_toml(text: &str, base_dir: &Path) -> Result<Self, CorrectError> {
        let checked = validate(&CORRECT_JOB, text);
        if let Err(e @ SchemaError::Syntax { .. }) = checked {
            return Err(CorrectError::Job(Box::new(e)));
        }
        let table: toml::Table =
            toml::from_str(text).map_err(|e| CorrectError::Toml(Box::new(e)))?;
        if !Self::is_job(&table) {
            return Err(CorrectError::NoCorrectTable);
        }
        checked.map_err(job_error)?;
        let f: JobFile = toml::from_str(text).map_err(|e| CorrectError::Toml(Box::new(e)))?;
        let j = f.correct;
        let named = |field: JobField, value: &str, rule: Rule| CorrectError::Field {
            field,
            value: Given::Word(value.into()),
            rule,
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
            Some(s) => Some(Dialect::from_name(s).map_err(|_| {
                named(
                    JobField::Dialect,
                    s,
                    Rule::Word {
                        allowed: MILLING_DIALECTS,
                    },
                )
            })?),
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

/// The description's refusal of a job: a value out of its range or list
/// in the words of [`Settings::check`], any other as it is.
fn job_error(e: SchemaError) -> CorrectError {
    match refused_value(&CORRECT_JOB, &e) {
        Some((_, key, value, rule)) => match JobField::from_key(key) {
            Some(field) => CorrectError::Field { field, value, rule },
            None => CorrectError::Job(Box::new(e)),
        },
        None => CorrectError::Job(Box::new(e)),
    }
}

const POSITIVE_MM: Option<Range> = Some(Range::above(0.0));
const NOT_NEGATIVE_MM: Option<Range> = Some(Range::at_least(0.0));

/// `[correct]`: what to correct and how.
pub const CORRECT: Table = Table {
    name: "correct",
    repeat: Repeat::Single,
    required: true,
    help: "the CMM report, the milling program and how to correct it",
    fields: &[
        field(
            "measurements",
            Kind::File,
            Unit::None,
            None,
            Preset::Required,
            "the CMM report: CSV, or DMIS (`.dmi`, `.dmis`, `.dms`, `.dmo`)",
        ),
        field(
            "program",
            Kind::File,
            Unit::None,
            None,
            Preset::Required,
            "the milling program (G-code) or a node table (`.csv`)",
        ),
        field(
            "tool",
            Kind::Text,
            Unit::None,
            None,
            Preset::Value(Value::Text("point")),
            "`point` (nodes on the surface) or `ball:R` (nodes at the centre of a ball-end tool \
             of radius R mm, > 0)",
        ),
        field(
            "interpolation",
            Kind::Word(INTERPOLATIONS),
            Unit::None,
            None,
            Preset::Value(Value::Text("bilinear")),
            "bilinear Coons patches (eq. 1) or bicubic Hermite patches (C1)",
        ),
        field(
            "gain",
            Kind::Number,
            Unit::None,
            Some(GAIN_RANGE),
            Preset::Value(Value::Number(DEFAULT_GAIN)),
            "displacement = −gain × interpolated deviation",
        ),
        field(
            "margin_mm",
            Kind::Number,
            Unit::Mm,
            Some(MARGIN_RANGE),
            Preset::Value(Value::Number(0.0)),
            "nodes up to this far beyond the measured area are corrected by extrapolation; 0 \
             leaves every node outside unchanged",
        ),
        field(
            "noise_mm",
            Kind::Number,
            Unit::Mm,
            NOT_NEGATIVE_MM,
            Preset::Value(Value::Number(0.0)),
            "the CMM's noise (standard deviation): the deviations are smoothed for it; 0 takes \
             them as measured",
        ),
        field(
            "arc_tolerance_mm",
            Kind::Number,
            Unit::Mm,
            POSITIVE_MM,
            Preset::Value(Value::Number(DEFAULT_ARC_TOLERANCE_MM)),
            "`G2/G3` arcs are written back as `G1` chords within this",
        ),
        field(
            "dialect",
            Kind::Name(MILLING_DIALECTS),
            Unit::None,
            None,
            Preset::Described("from the program's extension"),
            "the program's syntax (`fanuc` is `iso`; `sinumerik` and `840d` are \
             `sinumerik-840d`)",
        ),
        field(
            "points_per_section",
            Kind::Integer,
            Unit::None,
            Some(Range::closed(2.0, 100_000.0)),
            Preset::Described(
                "as measured when all sections have the same count, else the largest count",
            ),
            "resample every section to this many points",
        ),
        field(
            "max_segment_mm",
            Kind::Number,
            Unit::Mm,
            POSITIVE_MM,
            Preset::Described("none: moves kept whole"),
            "split straight feed moves longer than this into equal `G1` pieces first, so that \
             the correction can bend them",
        ),
        field(
            "max_deviation_mm",
            Kind::Number,
            Unit::Mm,
            POSITIVE_MM,
            Preset::Value(Value::Number(DEFAULT_MAX_DEVIATION_MM)),
            "the largest plausible deviation and node displacement: one beyond it stops the run \
             (a typing error in the report, or a part too far off to correct by re-milling)",
        ),
    ],
};

/// The correction job: `[correct]`.
pub const CORRECT_JOB: JobSchema = JobSchema {
    name: "correction",
    help: "a correction job: the CMM report of a moulded part, the program that milled its \
           mould, and how to correct the program",
    tables: &[CORRECT],
};

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

    #[test]
    fn every_key_the_reader_takes_is_described_and_every_setting_too() {
        assert_eq!(
            formcam_schema::reader_keys::<JobTable>(),
            CORRECT.field_names()
        );
        assert_eq!(formcam_schema::reader_keys::<JobFile>(), ["correct"]);
        for f in JobField::ALL {
            assert_eq!(f.described().map(|d| d.name), Some(f.key()));
        }
        assert_eq!(JobField::ALL.len(), CORRECT.fields.len());
    }
}
