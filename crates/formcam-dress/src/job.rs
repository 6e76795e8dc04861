//! The job users write: `[wheel]`, `[dresser]` and `[process]` tables (TOML).
//!
//! ```toml
//! [wheel]
//! ball_radius = 1.85        # mm
//! contact_angle_deg = 45.0
//! r1 = 1.937                # mm, flank arc
//! r2 = 0.296                # mm, fillet
//! width = 6.0               # mm
//! flank_tilt_deg = 10.0
//! # arc_angle_deg = 15.0    # where the flank arc ends (0.2618 rad)
//! # diameter = 40.0         # mm, for volume rates
//! [dresser]
//! width = 2.9
//! corner_radius_left = 0.258
//! corner_radius_right = 0.279
//! # yo = 1.45               # point A from the dresser's left face (b / 2)
//! [process]
//! depth = 0.05              # mm dressing allowance (or initial_contour = "worn.csv", columns z,x)
//! step = 0.01               # mm
//! feed_min = 50.0           # mm/min
//! feed_max = 300.0
//! # target_mrr = 10.0       # mm²/min; default: the largest the feed range allows
//! # feed_change_max = 25.0  # mm/min between neighbouring points
//! ```

use formcam_files::line_col;
use formcam_schema::{
    Condition, Default as Given, JobSchema, Kind, Range, Repeat, SchemaError, Table, Unit, Value,
    field, validate,
};
use serde::Deserialize;

use crate::{
    Allowance, ContourFault, DressError, DressSpec, DresserSpec, FeedSpec, Point, WheelSpec,
};

/// The default arc angle (0.2618 rad), degrees.
pub const ARC_ANGLE_DEG: f64 = 15.0;

/// A dressing job.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DressJob {
    /// The grinding wheel.
    pub wheel: WheelJob,
    /// The dressing wheel.
    pub dresser: DresserJob,
    /// Allowance, step and feeds.
    pub process: ProcessJob,
}

/// The `[wheel]` table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WheelJob {
    /// The ball's radius `Rs`, mm.
    pub ball_radius: f64,
    /// The contact angle, degrees in (0, 90).
    pub contact_angle_deg: f64,
    /// The flank arcs' radius `R1` (> `Rs`), mm.
    pub r1: f64,
    /// The fillets' radius `R2`, mm.
    pub r2: f64,
    /// The wheel's width `B`, mm.
    pub width: f64,
    /// The flanks' tilt from the wheel's axis, degrees (positive: falling outward).
    pub flank_tilt_deg: f64,
    /// Where the flank arc ends about its centre, degrees; default 15.
    pub arc_angle_deg: Option<f64>,
    /// The wheel's diameter, mm, for volume rates.
    pub diameter: Option<f64>,
}

/// The `[dresser]` table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DresserJob {
    /// The width `b`, mm.
    pub width: f64,
    /// The corner dressing the left half, mm.
    pub corner_radius_left: f64,
    /// The corner dressing the right half, mm.
    pub corner_radius_right: f64,
    /// Point A's distance from the dresser's left face, mm; default `b / 2`.
    pub yo: Option<f64>,
}

/// The `[process]` table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProcessJob {
    /// The dressing allowance, mm (the profile offset outward).
    pub depth: Option<f64>,
    /// A CSV file of the wheel's contour before dressing (columns `z,x`, mm,
    /// the program's axes; the older `x,y` too), read by the caller with
    /// [`crate::read_contour`]; instead of `depth`.
    pub initial_contour: Option<String>,
    /// The step `h`, mm.
    pub step: f64,
    /// The lowest feed, mm/min.
    pub feed_min: f64,
    /// The highest feed, mm/min.
    pub feed_max: f64,
    /// The removal rate to hold, mm²/min of the section.
    pub target_mrr: Option<f64>,
    /// The largest feed change between neighbouring points, mm/min.
    pub feed_change_max: Option<f64>,
    /// The program's name.
    pub name: Option<String>,
}

impl DressJob {
    /// Reads a job, validated first against [`DRESS_JOB`]: errors name the
    /// field, its line and column and what is allowed (unknown tables and
    /// fields, types, ranges, missing fields).
    pub fn from_toml(text: &str) -> Result<DressJob, DressError> {
        validate(&DRESS_JOB, text).map_err(|e| match e {
            SchemaError::Syntax {
                line,
                column,
                message,
            } => DressError::Toml {
                line,
                column,
                message,
            },
            other => DressError::Schema(other),
        })?;
        toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((0, 0), |s| line_col(text, s.start));
            DressError::Toml {
                line,
                column,
                message: formcam_files::syntax_message(
                    e.message(),
                    text,
                    e.span().map_or(text.len(), |s| s.start),
                ),
            }
        })
    }

    /// Values that are allowed but implausible (a wrong unit, most likely), as
    /// lines naming the field: a feed under 1 mm/min (mm/s?).
    pub fn warnings(&self) -> Vec<String> {
        let p = &self.process;
        [
            ("process.feed_min", Some(p.feed_min)),
            ("process.feed_max", Some(p.feed_max)),
            ("process.feed_change_max", p.feed_change_max),
        ]
        .into_iter()
        .filter_map(|(field, v)| match v {
            Some(f) if f > 0.0 && f < 1.0 => Some(format!(
                "{field}: {f} mm/min is under 1 mm/min; feeds are in mm/min (mm/s?)"
            )),
            _ => None,
        })
        .collect()
    }

    /// The dressing this job asks for. `initial` is the contour of
    /// `process.initial_contour`, read by the caller (`None` when the job
    /// gives `process.depth`).
    pub fn spec(&self, initial: Option<Vec<Point>>) -> Result<DressSpec, DressError> {
        let w = &self.wheel;
        let p = &self.process;
        let allowance = match (p.depth, &p.initial_contour, initial) {
            (Some(_), Some(_), _) => {
                return Err(DressError::Missing {
                    field: "process.depth".into(),
                    reason: "give the allowance or process.initial_contour, not both".into(),
                });
            }
            (Some(d), None, _) => Allowance::Depth(d),
            (None, Some(_), Some(points)) => Allowance::Contour(points),
            (None, Some(file), None) => {
                return Err(ContourFault::NotRead { file: file.clone() }.into());
            }
            (None, None, _) => {
                return Err(DressError::Missing {
                    field: "process.depth".into(),
                    reason: "the dressing allowance is missing (or give process.initial_contour)"
                        .into(),
                });
            }
        };
        Ok(DressSpec {
            name: p.name.clone().unwrap_or_else(|| "DRESS".into()),
            wheel: WheelSpec {
                ball_radius: w.ball_radius,
                contact_angle: w.contact_angle_deg.to_radians(),
                r1: w.r1,
                r2: w.r2,
                width: w.width,
                flank_tilt: w.flank_tilt_deg.to_radians(),
                arc_angle: w.arc_angle_deg.unwrap_or(ARC_ANGLE_DEG).to_radians(),
            },
            wheel_diameter: w.diameter,
            dresser: DresserSpec {
                width: self.dresser.width,
                corner_radius_left: self.dresser.corner_radius_left,
                corner_radius_right: self.dresser.corner_radius_right,
                yo: self.dresser.yo,
            },
            allowance,
            step: p.step,
            feed: FeedSpec {
                feed_min: p.feed_min,
                feed_max: p.feed_max,
                target_mrr: p.target_mrr,
                feed_change_max: p.feed_change_max,
            },
        })
    }
}

const POSITIVE: Option<Range> = Some(Range::above(0.0));
/// The least corner radius of the dressing wheel, mm.
const CORNER_MIN: Option<Range> = Some(Range::at_least(0.0002));

/// `[wheel]`: the grinding wheel's profile.
pub const WHEEL: Table = Table {
    name: "wheel",
    repeat: Repeat::Single,
    required: true,
    help: "the grinding wheel's gothic-arch profile",
    fields: &[
        field(
            "ball_radius",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Given::Required,
            "the ball's radius `Rs`",
        ),
        field(
            "contact_angle_deg",
            Kind::Number,
            Unit::Deg,
            Some(Range::open(0.0, 90.0)),
            Given::Required,
            "the contact angle `α`",
        ),
        field(
            "r1",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Given::Required,
            "the flank arcs' radius `R1`, above `Rs` (usually 1.03–1.05 `Rs`)",
        ),
        field(
            "r2",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Given::Required,
            "the fillets' radius `R2`, small enough that the fillet ends inside the width",
        ),
        field(
            "width",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Given::Required,
            "the wheel's width `B`",
        ),
        field(
            "flank_tilt_deg",
            Kind::Number,
            Unit::Deg,
            Some(Range::closed_open(0.0, 90.0)),
            Given::Required,
            "the flanks' tilt `τ`, below 90 − `arc_angle_deg`: the flanks fall toward the edges",
        ),
        field(
            "arc_angle_deg",
            Kind::Number,
            Unit::Deg,
            Some(Range::open(0.0, 90.0)),
            Given::Value(Value::Number(ARC_ANGLE_DEG)),
            "where the flank arc ends about its centre, `α2`, below `contact_angle_deg`",
        ),
        field(
            "diameter",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Given::Described("none (rates of the section only)"),
            "the wheel's diameter `D`, for volume rates",
        ),
    ],
};

/// `[dresser]`: the dressing wheel.
pub const DRESSER: Table = Table {
    name: "dresser",
    repeat: Repeat::Single,
    required: true,
    help: "the diamond dressing wheel",
    fields: &[
        field(
            "width",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Given::Required,
            "the width `b`, at least `rL + rR`; the dresser must not cut into the profile \
             elsewhere",
        ),
        field(
            "corner_radius_left",
            Kind::Number,
            Unit::Mm,
            CORNER_MIN,
            Given::Required,
            "`rL`, the corner dressing the left half, up to `R2`",
        ),
        field(
            "corner_radius_right",
            Kind::Number,
            Unit::Mm,
            CORNER_MIN,
            Given::Required,
            "`rR`, the corner dressing the right half, up to `R2`",
        ),
        field(
            "yo",
            Kind::Number,
            Unit::Mm,
            Some(Range::at_least(0.0)),
            Given::Described("`b / 2`"),
            "point A's distance from the dresser's left face, up to `b`",
        ),
    ],
};

/// `[process]`: allowance, step and feeds.
pub const PROCESS: Table = Table {
    name: "process",
    repeat: Repeat::Single,
    required: true,
    help: "the allowance, the step and the feeds",
    fields: &[
        field(
            "depth",
            Kind::Number,
            Unit::Mm,
            POSITIVE,
            Given::RequiredWhen(Condition::Absent {
                field: "initial_contour",
            }),
            "the dressing allowance (the profile offset outward), below min(`R2`, the profile's \
             height)",
        ),
        field(
            "initial_contour",
            Kind::File,
            Unit::None,
            None,
            Given::None,
            "a CSV of the wheel before dressing (columns `z,x`, mm; the older `x,y` too), \
             relative to the job's folder (else the current folder); instead of `depth`",
        ),
        field(
            "step",
            Kind::Number,
            Unit::Mm,
            Some(Range::at_least(0.0001)),
            Given::Required,
            "the step `h`, up to min(`rL`, `rR`) / 2, not so small that the work explodes",
        ),
        field(
            "feed_min",
            Kind::Number,
            Unit::MmPerMin,
            Some(Range::at_least(0.1)),
            Given::Required,
            "the lowest feed",
        ),
        field(
            "feed_max",
            Kind::Number,
            Unit::MmPerMin,
            Some(Range::closed(0.1, 100_000.0)),
            Given::Required,
            "the highest feed, at least `feed_min`",
        ),
        field(
            "target_mrr",
            Kind::Number,
            Unit::Mm2PerMin,
            POSITIVE,
            Given::Described("eq. 19: the largest the feed range allows"),
            "the removal rate `T` to hold, of the section",
        ),
        field(
            "feed_change_max",
            Kind::Number,
            Unit::MmPerMin,
            POSITIVE,
            Given::Described("(`feed_max` − `feed_min`) / 10"),
            "the largest feed change `ΔF` between neighbouring points",
        ),
        field(
            "name",
            Kind::Text,
            Unit::None,
            None,
            Given::Value(Value::Text("DRESS")),
            "the program's name",
        ),
    ],
};

/// The dressing job: `[wheel]`, `[dresser]` and `[process]`.
pub const DRESS_JOB: JobSchema = JobSchema {
    name: "dressing",
    help: "a dressing job: the grinding wheel's profile, the dressing wheel, the allowance, the \
           step and the feeds",
    tables: &[WHEEL, DRESSER, PROCESS],
};

#[cfg(test)]
mod tests {
    use super::*;

    const SEED: &str = r#"
[wheel]
ball_radius = 1.85
contact_angle_deg = 45.0
r1 = 1.937
r2 = 0.296
width = 6.0
flank_tilt_deg = 10.0
[dresser]
width = 2.9
corner_radius_left = 0.258
corner_radius_right = 0.279
[process]
depth = 0.05
step = 0.01
feed_min = 50.0
feed_max = 300.0
"#;

    #[test]
    fn the_seed_job_reads() {
        let job = DressJob::from_toml(SEED).unwrap();
        let spec = job.spec(None).unwrap();
        assert!((spec.wheel.arc_angle - 0.2618).abs() < 1e-4);
        assert_eq!(spec.allowance, Allowance::Depth(0.05));
        assert_eq!(spec.dresser.corner_radius_right, 0.279);
    }

    #[test]
    fn unknown_and_missing_fields_are_refused() {
        let e = DressJob::from_toml(&SEED.replace("r2 = 0.296", "r2 = 0.296\nr3 = 1.0"))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("wheel.r3 at 7:1: unknown field `r3`; allowed: ball_radius"),
            "{e}"
        );
        let e = DressJob::from_toml(&SEED.replace("step = 0.01\n", ""))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("process.step: missing") && e.contains(">= 0.0001 mm"),
            "{e}"
        );
        let e = DressJob::from_toml(&SEED.replace("depth = 0.05\n", ""))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("process.depth: missing") && e.contains("unless initial_contour"),
            "{e}"
        );
        let e = DressJob::from_toml(&SEED.replace("r1 = 1.937", "r1 = nan"))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("wheel.r1 = nan at 5:6: out of range"), "{e}");
    }

    #[test]
    fn feeds_under_one_mm_per_min_warn() {
        assert!(DressJob::from_toml(SEED).unwrap().warnings().is_empty());
        let slow = DressJob::from_toml(
            &SEED
                .replace("feed_min = 50.0", "feed_min = 0.8")
                .replace("feed_max = 300.0", "feed_max = 5.0"),
        )
        .unwrap();
        let w = slow.warnings();
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(w[0].starts_with("process.feed_min") && w[0].contains("mm/s?"));
    }
}
