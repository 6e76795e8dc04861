use std::fmt;

use formcam_files::quote;
use formcam_schema::{Field, JobSchema, Range, SchemaError, Unit};
use thiserror::Error;

use crate::{JobField, ScenarioField, Tool};

/// Everything that can stop a correction.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CorrectError {
    /// A measurement file that cannot be read (the message names the line
    /// and the column or feature).
    #[error(transparent)]
    Measurements(#[from] MeasureError),
    /// Sections that cannot form a grid of facets.
    #[error(transparent)]
    Sections(#[from] SectionsError),
    /// A value not allowed, before anything names it (a tool or an
    /// interpolation read from its name).
    #[error(transparent)]
    Value(#[from] Rule),
    /// A milling program or node table that cannot be used.
    #[error(transparent)]
    Program(#[from] ProgramError),
    /// A G-code program that cannot be read or written.
    #[error(transparent)]
    Nc(#[from] formcam_nc::NcError),
    /// A scenario of the closed-loop check that cannot be used.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// A job file that does not match the `[correct]` job's description
    /// (not TOML, an unknown or missing field, a wrong type).
    #[error(transparent)]
    Job(Box<SchemaError>),
    /// A job file without a `[correct]` table.
    #[error(
        "no [correct] table (a correction job names measurements and program there; see \
         examples/correct-mould.toml)"
    )]
    NoCorrectTable,
    /// A job file the reader refuses after its description let it pass.
    #[error("{}", .0.message())]
    Toml(Box<toml::de::Error>),
    /// A setting out of range, named as the job file's field.
    #[error("{field} = {value}: {rule}")]
    Field {
        /// The setting.
        field: JobField,
        /// Its value as given.
        value: Given,
        /// What it breaks.
        rule: Rule,
    },
    /// A measured deviation beyond the stated limit (a typing error in the
    /// report, or a part too far off to correct by re-milling).
    #[error(
        "section `{section}`, point `{point}`: deviation {deviation_mm:.3} mm is beyond the \
         limit of {limit_mm} mm"
    )]
    Deviation {
        /// The section's name.
        section: String,
        /// The point's name.
        point: String,
        /// The length of its deviation, mm.
        deviation_mm: f64,
        /// The limit, mm.
        limit_mm: f64,
    },
    /// A node displacement beyond the stated limit.
    #[error(
        "node {node}: displacement {displacement_mm:.3} mm is beyond the limit of {limit_mm} mm"
    )]
    Displacement {
        /// The node's index among the corrected nodes (0-based).
        node: usize,
        /// The length of its displacement, mm.
        displacement_mm: f64,
        /// The limit, mm.
        limit_mm: f64,
    },
    /// A program's node whose displacement is beyond the stated limit.
    #[error(
        "line {line}: the node would move by {displacement_mm:.3} mm, beyond the limit of \
         {limit_mm} mm"
    )]
    NodeDisplacement {
        /// The node's program line (1-based).
        line: usize,
        /// The length of its displacement, mm.
        displacement_mm: f64,
        /// The limit, mm.
        limit_mm: f64,
    },
    /// The run was cancelled by its progress hook.
    #[error(transparent)]
    Cancelled(#[from] formcam_progress::Cancelled),
}

/// A value as the user gave it, written in messages after its name.
#[derive(Debug, Clone, PartialEq)]
pub enum Given {
    /// A number (`0`, `-1.5`).
    Number(f64),
    /// A word or a name, written quoted (`"flat"`).
    Word(String),
    /// A tool, written as its name (`"ball:-2"`).
    Tool(Tool),
}

impl fmt::Display for Given {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Given::Number(v) => write!(f, "{v}"),
            Given::Word(w) => write!(f, "\"{w}\""),
            Given::Tool(Tool::Point) => f.write_str("\"point\""),
            Given::Tool(Tool::Ball { radius }) => write!(f, "\"ball:{radius}\""),
        }
    }
}

/// What a value breaks: the words after `field = value: ` (a job file) or
/// `--flag value: ` (the command line), the same for both.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Rule {
    /// Outside the field's range, as its description gives it: `allowed
    /// (0, 2]` between two ends, `must be >= 0 mm` with one.
    #[error("{}", range_words(range, *unit))]
    Range {
        /// The range.
        range: Range,
        /// The field's unit.
        unit: Unit,
    },
    /// A word not in the field's list.
    #[error("allowed {}", allowed.join(", "))]
    Word {
        /// The words allowed.
        allowed: &'static [&'static str],
    },
    /// A tool that is neither `point` nor `ball:R`.
    #[error("allowed `point` or `ball:R` (R in mm)")]
    ToolName,
    /// A ball whose radius is no number.
    #[error("the radius `{written}` is not a number (e.g. ball:6)")]
    BallRadiusText {
        /// The radius as written.
        written: String,
    },
    /// A ball whose radius is not above 0.
    #[error("the ball radius must be > 0 mm")]
    BallRadius,
    /// Infinite or not a number, where any finite number is allowed.
    #[error("must be a finite number")]
    Finite,
}

/// A range in the words of the messages: `allowed (0, 2]`, `must be > 0 mm`.
fn range_words(range: &Range, unit: Unit) -> String {
    let unit = match unit.symbol() {
        "" => String::new(),
        s => format!(" {s}"),
    };
    match (range.min, range.max) {
        (Some(_), Some(_)) => format!("allowed {range}{unit}"),
        _ => format!("must be {range}{unit}"),
    }
}

impl Rule {
    /// `v` against a described field's range: the rule it breaks, if any
    /// (never for a field without a range but a finite value).
    pub fn check(field: &Field, v: f64) -> Result<(), Rule> {
        let ok = match field.range {
            Some(r) => r.contains(v),
            None => v.is_finite(),
        };
        match (ok, field.range) {
            (true, _) => Ok(()),
            (false, Some(range)) => Err(Rule::Range {
                range,
                unit: field.unit,
            }),
            (false, None) => Err(Rule::Finite),
        }
    }
}

/// A description's refusal of a value out of its field's range or list,
/// as the table's and field's names, the value and the rule it breaks (the
/// words the code's own checks use); `None` for every other refusal.
pub(crate) fn refused_value(
    schema: &JobSchema,
    e: &SchemaError,
) -> Option<(&'static str, &'static str, Given, Rule)> {
    let described = |dotted: &str| {
        let (table, key) = dotted.split_once('.')?;
        let key = key.split('[').next().unwrap_or(key);
        let table = schema.table(table.split('[').next().unwrap_or(table))?;
        Some((table.name, table.field(key)?))
    };
    match e {
        SchemaError::OutOfRange { field, value, .. } => {
            let (table, f) = described(field)?;
            let v: f64 = value.replace('_', "").parse().ok()?;
            let rule = Rule::check(f, v).err()?;
            Some((table, f.name, Given::Number(v), rule))
        }
        SchemaError::NotAWord { field, value, .. } => {
            let (table, f) = described(field)?;
            let rule = Rule::Word {
                allowed: f.kind.words(),
            };
            Some((table, f.name, Given::Word(value.clone()), rule))
        }
        _ => None,
    }
}

/// Why a CMM report cannot be read.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MeasureError {
    /// A problem at a line of the file.
    #[error("line {line}: {problem}")]
    At {
        /// The line (1-based).
        line: usize,
        /// What is wrong there.
        problem: MeasureProblem,
    },
    /// A file without a header.
    #[error("the file is empty")]
    Empty,
    /// A DMIS file without point features.
    #[error("no F(..)=FEAT/POINT,CART features found")]
    NoFeatures,
    /// A file without points.
    #[error("no measured points")]
    NoPoints,
}

/// What is wrong at a line of a CMM report.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MeasureProblem {
    /// A required column missing in the header.
    #[error(
        "no column `{column}` (the header needs section, point, x_nom, y_nom, z_nom, and x_act, \
         y_act, z_act or dev with nx, ny, nz)"
    )]
    NoColumn {
        /// The column.
        column: &'static str,
    },
    /// Some of the normal's columns only.
    #[error("give all of nx, ny, nz or none")]
    SomeNormals,
    /// Neither the actual point's columns nor `dev` with a normal.
    #[error("give x_act, y_act, z_act, or dev with nx, ny, nz")]
    NoActualColumns,
    /// A row shorter than the header.
    #[error("no value for `{}`", quote(column))]
    NoValue {
        /// The column.
        column: String,
    },
    /// A value that is no number.
    #[error("`{}` = `{}` is not a number", quote(column), quote(text))]
    NotANumber {
        /// The column.
        column: String,
        /// The value as written.
        text: String,
    },
    /// A value that is infinite or not a number.
    #[error("`{}` = `{}` is not finite", quote(column), quote(text))]
    NotFinite {
        /// The column.
        column: String,
        /// The value as written.
        text: String,
    },
    /// A row without section or point name.
    #[error("a row needs `section` and `point`")]
    NoName,
    /// A zero normal.
    #[error("the normal nx, ny, nz is zero")]
    ZeroNormal,
    /// A row without an actual point.
    #[error("no actual point")]
    NoActualPoint,
    /// A point given twice.
    #[error(
        "point `{}` of section `{}` is given twice",
        quote(point),
        quote(section)
    )]
    PointTwice {
        /// The section.
        section: String,
        /// The point.
        point: String,
    },
    /// A DMIS length unit not known.
    #[error("unknown length unit `{}`", quote(unit))]
    Unit {
        /// The unit as written.
        unit: String,
    },
    /// A DMIS feature label not closed.
    #[error("a feature label without `)`")]
    OpenLabel,
    /// A DMIS point that is not Cartesian.
    #[error("feature {}: only CART points are read", quote(label))]
    NotCartesian {
        /// The feature's label.
        label: String,
    },
    /// A DMIS point with fewer than three coordinates.
    #[error("feature {}: too few coordinates", quote(label))]
    FewCoordinates {
        /// The feature's label.
        label: String,
    },
    /// A DMIS coordinate that is no number.
    #[error("feature {}: `{}` is not a number", quote(label), quote(text))]
    FeatureNotANumber {
        /// The feature's label.
        label: String,
        /// The value as written.
        text: String,
    },
    /// A DMIS coordinate that is infinite or not a number.
    #[error("feature {}: `{}` is not finite", quote(label), quote(text))]
    FeatureNotFinite {
        /// The feature's label.
        label: String,
        /// The value as written.
        text: String,
    },
    /// A measured feature given twice.
    #[error("FA({}) is given twice", quote(label))]
    ActualTwice {
        /// The feature's label.
        label: String,
    },
    /// A nominal feature without its measured one.
    #[error("F({}) has no measured FA({})", quote(label), quote(label))]
    NoMeasuredFeature {
        /// The feature's label.
        label: String,
    },
    /// A label that names no section and point.
    #[error(
        "DMIS label `{}`: name points `<section>_<point>` (e.g. `S1_P3`)",
        quote(label)
    )]
    LabelName {
        /// The label.
        label: String,
    },
}

/// Why measured sections cannot form a grid of facets.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SectionsError {
    /// Fewer than two sections.
    #[error("{count} section(s) measured: the correction needs at least 2 sections")]
    TooFew {
        /// The sections measured.
        count: usize,
    },
    /// A resampling count out of range.
    #[error("points per section = {count}: {rule}")]
    PointsPerSection {
        /// The count asked for.
        count: usize,
        /// Its range.
        rule: Rule,
    },
    /// Normals on some points only.
    #[error("{with_normals} of {points} points have a normal: give normals for all or none")]
    SomeNormals {
        /// Points with a normal.
        with_normals: usize,
        /// All points.
        points: usize,
    },
    /// A section with fewer than two points.
    #[error("section `{section}` has {points} point(s): a section needs at least 2")]
    ShortSection {
        /// The section.
        section: String,
        /// Its points.
        points: usize,
    },
    /// Two sections at the same place.
    #[error("sections `{first}` and `{second}` lie at the same place: sections must be apart")]
    SamePlace {
        /// One section.
        first: String,
        /// The other.
        second: String,
    },
    /// Two consecutive points of a section at the same place.
    #[error(
        "section `{section}`: points `{first}` and `{second}` are at the same place (duplicate \
         point)"
    )]
    DuplicatePoint {
        /// The section.
        section: String,
        /// One point.
        first: String,
        /// The next.
        second: String,
    },
    /// A section listed the other way than its neighbour.
    #[error(
        "section `{section}` runs the other way than section `{previous}`: list the points of \
         every section in the same direction"
    )]
    Reversed {
        /// The section.
        section: String,
        /// Its neighbour before it.
        previous: String,
    },
}

/// Why a milling program or node table cannot be used.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ProgramError {
    /// An empty program.
    #[error("the program is empty")]
    Empty,
    /// A program without motion blocks.
    #[error("the program has no motion blocks")]
    NoMotion,
    /// A node table without nodes.
    #[error("the node table has no nodes")]
    NoNodes,
    /// A node table's row with fewer than three values.
    #[error("line {line}: `{row}`: a node needs x, y, z")]
    ShortRow {
        /// The line (1-based).
        line: usize,
        /// The row as written.
        row: String,
    },
    /// A node table's value that is no number.
    #[error("line {line}: `{row}`: `{text}` is not a number")]
    NotANumber {
        /// The line (1-based).
        line: usize,
        /// The row as written.
        row: String,
        /// The value as written.
        text: String,
    },
    /// A node table's value that is infinite or not a number.
    #[error("line {line}: `{row}`: `{text}` is not finite")]
    NotFinite {
        /// The line (1-based).
        line: usize,
        /// The row as written.
        row: String,
        /// The value as written.
        text: String,
    },
}

/// Why a closed-loop scenario cannot be used.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ScenarioError {
    /// A file that does not match the scenario's description (not TOML, an
    /// unknown or missing field, a wrong type).
    #[error(transparent)]
    Schema(Box<SchemaError>),
    /// A file the reader refuses after its description let it pass.
    #[error("{}", .0.message())]
    Toml(Box<toml::de::Error>),
    /// A value out of its range or list.
    #[error("{field} = {value}: {rule}")]
    Field {
        /// The field.
        field: ScenarioField,
        /// Its value as given.
        value: Given,
        /// What it breaks.
        rule: Rule,
    },
    /// A radius the surface's kind needs, left out.
    #[error("{field}: missing for surface.kind = \"{kind}\"")]
    Missing {
        /// The radius.
        field: ScenarioField,
        /// The surface's kind.
        kind: &'static str,
    },
    /// A nose-cone panel too wide for its radii.
    #[error(
        "surface.width = {width}: a nose-cone panel must be narrower than 1.9 x the smaller \
         radius ({radius})"
    )]
    NoseConeWidth {
        /// The width, mm.
        width: f64,
        /// The smaller radius, mm.
        radius: f64,
    },
    /// A raster of too many nodes.
    #[error("program.step, program.step_over: {lines} x {per_line} nodes is more than 2e7")]
    Nodes {
        /// Raster lines.
        lines: usize,
        /// Nodes per line.
        per_line: usize,
    },
    /// A ball as large as the surface's curvature.
    #[error(
        "program.tool ball radius {radius} mm: must be below the surface's radius of curvature \
         {curvature} mm"
    )]
    BallRadius {
        /// The ball's radius, mm.
        radius: f64,
        /// The smallest radius of curvature, mm.
        curvature: f64,
    },
    /// A program read back with another count of feed nodes than the
    /// raster's.
    #[error("the program has {feed} feed nodes, the raster {raster}")]
    Raster {
        /// Feed nodes read.
        feed: usize,
        /// Nodes of the raster.
        raster: usize,
    },
    /// A loop that ran no round.
    #[error("the loop ran no round")]
    NoRound,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_read_as_allowed_between_two_ends_and_must_be_with_one() {
        let two = Rule::Range {
            range: Range::open_closed(0.0, 2.0),
            unit: Unit::None,
        };
        assert_eq!(two.to_string(), "allowed (0, 2]");
        let one = Rule::Range {
            range: Range::at_least(0.0),
            unit: Unit::Mm,
        };
        assert_eq!(one.to_string(), "must be >= 0 mm");
        assert_eq!(Given::Number(-1.0).to_string(), "-1");
        assert_eq!(Given::Word("flat".into()).to_string(), "\"flat\"");
    }
}
