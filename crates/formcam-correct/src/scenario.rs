//! The closed-loop scenario file: `[surface]`, `[program]`, `[warp]`,
//! `[cmm]` and `[loop]` (with an optional section-spacing study).
//!
//! ```toml
//! [surface]
//! kind = "panel"          # panel (radius_x, radius_y) | nose-cone (radius_start, radius_end)
//! length = 400.0          # mm along x
//! width = 300.0           # mm along y
//! radius_x = 1200.0
//! radius_y = 900.0
//! [program]
//! tool = "ball:6"         # point | ball:R (mm)
//! step = 1.0              # mm between nodes along a raster line
//! step_over = 2.0         # mm between raster lines
//! feed = 3000.0           # mm/min
//! [warp]
//! amplitude = 0.4         # mm along the normal
//! [cmm]
//! sections = 17
//! points = 13
//! noise = 0.002           # mm (default 0)
//! seed = 1                # (default 0)
//! [loop]
//! iterations = 3
//! interpolation = "bicubic"   # bilinear (default) | bicubic
//! gain = 1.0
//! margin_mm = 2.0
//! smoothing = false
//! section_study = [3, 5, 9, 17, 33]
//! ```

use std::fmt;

use formcam_schema::{
    Condition, Default as Preset, EmptyList, Field, JobSchema, Kind, Range, Repeat, SchemaError,
    Table, Unit, Value, field, validate,
};
use serde::Deserialize;

use crate::error::refused_value;
use crate::job::INTERPOLATIONS;
use crate::simulate::{Scenario, Shape};
use crate::{
    CorrectError, DEFAULT_GAIN, GAIN_RANGE, Given, Interpolation, MARGIN_RANGE, Options, Rule,
    ScenarioError, Tool,
};

/// A scenario file: the loop to run and the section counts of the spacing
/// study (none: no study).
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioJob {
    /// The loop.
    pub scenario: Scenario,
    /// Section counts of the spacing study.
    pub section_study: Vec<usize>,
}

/// A field of the scenario file, as errors name it (`program.step`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScenarioField {
    /// `surface.kind`.
    SurfaceKind,
    /// `surface.length`, mm.
    Length,
    /// `surface.width`, mm.
    Width,
    /// `surface.radius_x`, mm.
    RadiusX,
    /// `surface.radius_y`, mm.
    RadiusY,
    /// `surface.radius_start`, mm.
    RadiusStart,
    /// `surface.radius_end`, mm.
    RadiusEnd,
    /// `program.tool`.
    Tool,
    /// `program.step`, mm.
    Step,
    /// `program.step_over`, mm.
    StepOver,
    /// `program.feed`, mm/min.
    Feed,
    /// `warp.amplitude`, mm.
    Amplitude,
    /// `cmm.sections`.
    Sections,
    /// `cmm.points`.
    Points,
    /// `cmm.noise`, mm.
    Noise,
    /// `cmm.seed`.
    Seed,
    /// `loop.iterations`.
    Iterations,
    /// `loop.interpolation`.
    Interpolation,
    /// `loop.gain`.
    Gain,
    /// `loop.margin_mm`, mm.
    Margin,
    /// `loop.smoothing`.
    Smoothing,
    /// `loop.section_study`.
    SectionStudy,
}

impl ScenarioField {
    /// Every field, in the order of the scenario's description.
    pub const ALL: [ScenarioField; 22] = [
        Self::SurfaceKind,
        Self::Length,
        Self::Width,
        Self::RadiusX,
        Self::RadiusY,
        Self::RadiusStart,
        Self::RadiusEnd,
        Self::Tool,
        Self::Step,
        Self::StepOver,
        Self::Feed,
        Self::Amplitude,
        Self::Sections,
        Self::Points,
        Self::Noise,
        Self::Seed,
        Self::Iterations,
        Self::Interpolation,
        Self::Gain,
        Self::Margin,
        Self::Smoothing,
        Self::SectionStudy,
    ];

    /// The field's table and key.
    pub fn path(self) -> (&'static str, &'static str) {
        match self {
            Self::SurfaceKind => ("surface", "kind"),
            Self::Length => ("surface", "length"),
            Self::Width => ("surface", "width"),
            Self::RadiusX => ("surface", "radius_x"),
            Self::RadiusY => ("surface", "radius_y"),
            Self::RadiusStart => ("surface", "radius_start"),
            Self::RadiusEnd => ("surface", "radius_end"),
            Self::Tool => ("program", "tool"),
            Self::Step => ("program", "step"),
            Self::StepOver => ("program", "step_over"),
            Self::Feed => ("program", "feed"),
            Self::Amplitude => ("warp", "amplitude"),
            Self::Sections => ("cmm", "sections"),
            Self::Points => ("cmm", "points"),
            Self::Noise => ("cmm", "noise"),
            Self::Seed => ("cmm", "seed"),
            Self::Iterations => ("loop", "iterations"),
            Self::Interpolation => ("loop", "interpolation"),
            Self::Gain => ("loop", "gain"),
            Self::Margin => ("loop", "margin_mm"),
            Self::Smoothing => ("loop", "smoothing"),
            Self::SectionStudy => ("loop", "section_study"),
        }
    }

    /// The field at `table.key`.
    pub fn from_path(table: &str, key: &str) -> Option<ScenarioField> {
        Self::ALL.into_iter().find(|f| f.path() == (table, key))
    }

    /// The field's description in [`SCENARIO_JOB`].
    pub fn described(self) -> Option<&'static Field> {
        let (table, key) = self.path();
        SCENARIO_JOB.table(table)?.field(key)
    }

    /// `v` against the field's range.
    pub(crate) fn check(self, v: f64) -> Result<(), ScenarioError> {
        match self.described().map(|f| Rule::check(f, v)) {
            Some(Err(rule)) => Err(ScenarioError::Field {
                field: self,
                value: Given::Number(v),
                rule,
            }),
            _ => Ok(()),
        }
    }
}

impl fmt::Display for ScenarioField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (table, key) = self.path();
        write!(f, "{table}.{key}")
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ScenarioFile {
    surface: SurfaceTable,
    program: ProgramTable,
    warp: WarpTable,
    cmm: CmmTable,
    #[serde(rename = "loop")]
    rounds: LoopTable,
}

/// The surface's kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum SurfaceKind {
    Panel,
    NoseCone,
}

impl SurfaceKind {
    fn name(self) -> &'static str {
        match self {
            Self::Panel => "panel",
            Self::NoseCone => "nose-cone",
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SurfaceTable {
    kind: SurfaceKind,
    length: f64,
    width: f64,
    radius_x: Option<f64>,
    radius_y: Option<f64>,
    radius_start: Option<f64>,
    radius_end: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ProgramTable {
    tool: String,
    step: f64,
    step_over: f64,
    feed: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct WarpTable {
    amplitude: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CmmTable {
    sections: usize,
    points: usize,
    #[serde(default)]
    noise: f64,
    #[serde(default)]
    seed: u64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoopTable {
    iterations: usize,
    interpolation: Option<String>,
    gain: Option<f64>,
    #[serde(default)]
    margin_mm: f64,
    #[serde(default)]
    smoothing: bool,
    #[serde(default)]
    section_study: Vec<usize>,
}

impl ScenarioJob {
    /// Whether a TOML table is a scenario (it has `[surface]` and `[warp]`).
    pub fn is_scenario(table: &toml::Table) -> bool {
        table.contains_key("surface") && table.contains_key("warp")
    }

    /// Reads a scenario, validated first against [`SCENARIO_JOB`], and
    /// checks it; errors name the field ([`ScenarioError`]): a value out of
    /// its range or list in the words of [`Scenario::validate`], other
    /// refusals with their `line:column`.
    pub fn from_toml(text: &str) -> Result<Self, CorrectError> {
        validate(&SCENARIO_JOB, text).map_err(scenario_error)?;
        let f: ScenarioFile = toml::from_str(text).map_err(|e| ScenarioError::Toml(Box::new(e)))?;
        let kind = f.surface.kind;
        let need = |v: Option<f64>, field: ScenarioField| {
            v.ok_or(ScenarioError::Missing {
                field,
                kind: kind.name(),
            })
        };
        let shape = match kind {
            SurfaceKind::Panel => Shape::Panel {
                radius_x: need(f.surface.radius_x, ScenarioField::RadiusX)?,
                radius_y: need(f.surface.radius_y, ScenarioField::RadiusY)?,
            },
            SurfaceKind::NoseCone => Shape::NoseCone {
                radius_start: need(f.surface.radius_start, ScenarioField::RadiusStart)?,
                radius_end: need(f.surface.radius_end, ScenarioField::RadiusEnd)?,
            },
        };
        let named = |field: ScenarioField, value: &str, rule: Rule| ScenarioError::Field {
            field,
            value: Given::Word(value.into()),
            rule,
        };
        let tool: Tool = f
            .program
            .tool
            .parse()
            .map_err(|e| named(ScenarioField::Tool, &f.program.tool, e))?;
        let interpolation: Interpolation = match &f.rounds.interpolation {
            Some(s) => s
                .parse()
                .map_err(|e| named(ScenarioField::Interpolation, s, e))?,
            None => Interpolation::Bilinear,
        };
        for &count in &f.rounds.section_study {
            ScenarioField::SectionStudy.check(count as f64)?;
        }
        let scenario = Scenario {
            shape,
            length: f.surface.length,
            width: f.surface.width,
            tool,
            step_over: f.program.step_over,
            step: f.program.step,
            feed: f.program.feed,
            warp_amplitude: f.warp.amplitude,
            sections: f.cmm.sections,
            points: f.cmm.points,
            noise: f.cmm.noise,
            smoothing: f.rounds.smoothing,
            seed: f.cmm.seed,
            iterations: f.rounds.iterations,
            options: Options {
                gain: f.rounds.gain.unwrap_or(DEFAULT_GAIN),
                tool,
                interpolation,
                margin_mm: f.rounds.margin_mm,
            },
        };
        scenario.validate()?;
        Ok(Self {
            scenario,
            section_study: f.rounds.section_study,
        })
    }
}

/// The description's refusal of a scenario: a value out of its range or
/// list in the words of [`Scenario::validate`], any other as it is.
fn scenario_error(e: SchemaError) -> ScenarioError {
    match refused_value(&SCENARIO_JOB, &e) {
        Some((table, key, value, rule)) => match ScenarioField::from_path(table, key) {
            Some(field) => ScenarioError::Field { field, value, rule },
            None => ScenarioError::Schema(Box::new(e)),
        },
        None => ScenarioError::Schema(Box::new(e)),
    }
}

const POSITIVE: Option<Range> = Some(Range::above(0.0));
const NOT_NEGATIVE: Option<Range> = Some(Range::at_least(0.0));
/// Sections and points of the CMM and of the spacing study.
const COUNT: Option<Range> = Some(Range::closed(2.0, 10_000.0));

/// `[surface]`: the mould's nominal surface.
pub const SURFACE: Table = Table {
    name: "surface",
    repeat: Repeat::Single,
    required: true,
    help: "the mould's nominal surface",
    fields: &[
        field(
            "kind",
            Kind::Word(&["panel", "nose-cone"]),
            Unit::None,
            None,
            Preset::Required,
            "`panel`: `z = (x - L/2)^2 / (2 radius_x) + (y - W/2)^2 / (2 radius_y)`; \
             `nose-cone`: a panel of a cone, `z = sqrt(r(x)^2 - (y - W/2)^2)`, `r` linear from \
             `radius_start` to `radius_end`",
        ),
        field(
            "length",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Preset::Required,
            "`L`, along x",
        ),
        field(
            "width",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Preset::Required,
            "`W`, along y; a nose-cone panel narrower than 1.9 × its smaller radius",
        ),
        field(
            "radius_x",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Preset::RequiredWhen(Condition::Is {
                field: "kind",
                words: &["panel"],
            }),
            "the panel's radius of curvature along x",
        ),
        field(
            "radius_y",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Preset::RequiredWhen(Condition::Is {
                field: "kind",
                words: &["panel"],
            }),
            "the panel's radius of curvature along y",
        ),
        field(
            "radius_start",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Preset::RequiredWhen(Condition::Is {
                field: "kind",
                words: &["nose-cone"],
            }),
            "the nose cone's radius at `x = 0`",
        ),
        field(
            "radius_end",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Preset::RequiredWhen(Condition::Is {
                field: "kind",
                words: &["nose-cone"],
            }),
            "the nose cone's radius at `x = L`",
        ),
    ],
};

/// `[program]`: the raster program that mills the mould.
pub const PROGRAM: Table = Table {
    name: "program",
    repeat: Repeat::Single,
    required: true,
    help: "the raster program that mills the mould",
    fields: &[
        field(
            "tool",
            Kind::Text,
            Unit::None,
            None,
            Preset::Required,
            "`point` or `ball:R` (R in mm, > 0, below the panel's radii of curvature)",
        ),
        field(
            "step",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Preset::Required,
            "between nodes along a raster line (x); at most 2e7 nodes in all",
        ),
        field(
            "step_over",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Preset::Required,
            "between raster lines (y)",
        ),
        field(
            "feed",
            Kind::Number,
            Unit::MmPerMin,
            POSITIVE,
            Preset::Required,
            "the program's feed",
        ),
    ],
};

/// `[warp]`: the moulding's error.
pub const WARP: Table = Table {
    name: "warp",
    repeat: Repeat::Single,
    required: true,
    help: "the moulding's warp, the same every round",
    fields: &[field(
        "amplitude",
        Kind::Number,
        Unit::Mm,
        NOT_NEGATIVE,
        Preset::Required,
        "the warp's amplitude along the normal",
    )],
};

/// `[cmm]`: the measurement of each part.
pub const CMM: Table = Table {
    name: "cmm",
    repeat: Repeat::Single,
    required: true,
    help: "the CMM's control sections and its noise",
    fields: &[
        field(
            "sections",
            Kind::Integer,
            Unit::None,
            COUNT,
            Preset::Required,
            "control sections `x = const` over the length",
        ),
        field(
            "points",
            Kind::Integer,
            Unit::None,
            COUNT,
            Preset::Required,
            "points per section, over the width",
        ),
        field(
            "noise",
            Kind::Number,
            Unit::Mm,
            NOT_NEGATIVE,
            Preset::Value(Value::Number(0.0)),
            "the standard deviation of the probing along the normal",
        ),
        field(
            "seed",
            Kind::Integer,
            Unit::None,
            NOT_NEGATIVE,
            Preset::Value(Value::Integer(0)),
            "the seed of the noise",
        ),
    ],
};

/// `[loop]`: the correction rounds.
pub const LOOP: Table = Table {
    name: "loop",
    repeat: Repeat::Single,
    required: true,
    help: "the correction rounds and the section-spacing study",
    fields: &[
        field(
            "iterations",
            Kind::Integer,
            Unit::None,
            Some(Range::closed(0.0, 20.0)),
            Preset::Required,
            "correction rounds",
        ),
        field(
            "interpolation",
            Kind::Word(INTERPOLATIONS),
            Unit::None,
            None,
            Preset::Value(Value::Text("bilinear")),
            "as for `formcam correct`",
        ),
        field(
            "gain",
            Kind::Number,
            Unit::None,
            Some(GAIN_RANGE),
            Preset::Value(Value::Number(DEFAULT_GAIN)),
            "as for `formcam correct`",
        ),
        field(
            "margin_mm",
            Kind::Number,
            Unit::Mm,
            Some(MARGIN_RANGE),
            Preset::Value(Value::Number(0.0)),
            "as for `formcam correct`",
        ),
        field(
            "smoothing",
            Kind::Boolean,
            Unit::None,
            None,
            Preset::Value(Value::Boolean(false)),
            "smooth the measured deviations for the CMM's noise before correcting",
        ),
        field(
            "section_study",
            Kind::Integers,
            Unit::None,
            COUNT,
            Preset::Value(Value::EmptyList(EmptyList)),
            "section counts for which to report the residual after one correction, bilinear \
             and bicubic",
        ),
    ],
};

/// The closed-loop scenario of `formcam correct simulate`.
pub const SCENARIO_JOB: JobSchema = JobSchema {
    name: "scenario",
    help: "a closed-loop check of the correction: a mould milled, a warped part moulded and \
           measured, the program corrected, again",
    tables: &[SURFACE, PROGRAM, WARP, CMM, LOOP],
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_the_reader_takes_is_described_and_every_field_too() {
        assert_eq!(
            formcam_schema::reader_keys::<SurfaceTable>(),
            SURFACE.field_names()
        );
        assert_eq!(
            formcam_schema::reader_keys::<ProgramTable>(),
            PROGRAM.field_names()
        );
        assert_eq!(
            formcam_schema::reader_keys::<WarpTable>(),
            WARP.field_names()
        );
        assert_eq!(formcam_schema::reader_keys::<CmmTable>(), CMM.field_names());
        assert_eq!(
            formcam_schema::reader_keys::<LoopTable>(),
            LOOP.field_names()
        );
        let mut tables: Vec<String> = SCENARIO_JOB.tables.iter().map(|t| t.name.into()).collect();
        tables.sort();
        assert_eq!(formcam_schema::reader_keys::<ScenarioFile>(), tables);
        for f in ScenarioField::ALL {
            assert_eq!(f.described().map(|d| d.name), Some(f.path().1), "{f}");
        }
        let fields: usize = SCENARIO_JOB.tables.iter().map(|t| t.fields.len()).sum();
        assert_eq!(ScenarioField::ALL.len(), fields);
    }
}
