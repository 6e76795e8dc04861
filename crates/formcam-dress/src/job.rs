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

use serde::Deserialize;

use crate::{Allowance, DressError, DressSpec, DresserSpec, FeedSpec, Point, WheelSpec};

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
    /// Reads a job; errors give the line and column and what the reader said
    /// (unknown fields, missing fields, types).
    pub fn from_toml(text: &str) -> Result<DressJob, DressError> {
        toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((0, 0), |s| line_col(text, s.start));
            DressError::Toml {
                line,
                column,
                message: e.message().replace('\n', " "),
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
                return Err(DressError::Contour(format!("{file} was not read")));
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

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

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
            e.contains("unknown field `r3`") && e.starts_with("line 7"),
            "{e}"
        );
        let e = DressJob::from_toml(&SEED.replace("step = 0.01\n", ""))
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing field `step`"), "{e}");
        let job = DressJob::from_toml(&SEED.replace("depth = 0.05\n", "")).unwrap();
        let e = job.spec(None).unwrap_err().to_string();
        assert!(e.starts_with("process.depth"), "{e}");
        let nan = DressJob::from_toml(&SEED.replace("r1 = 1.937", "r1 = nan")).unwrap();
        assert!(nan.spec(None).is_ok());
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
