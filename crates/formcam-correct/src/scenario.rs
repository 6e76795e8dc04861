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

use serde::Deserialize;

use crate::simulate::{Scenario, Shape};
use crate::{CorrectError, Interpolation, Options, Tool};

/// A scenario file: the loop to run and the section counts of the spacing
/// study (none: no study).
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioJob {
    /// The loop.
    pub scenario: Scenario,
    /// Section counts of the spacing study.
    pub section_study: Vec<usize>,
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

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SurfaceTable {
    kind: String,
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

    /// Reads and checks a scenario; errors name the field
    /// ([`CorrectError::Scenario`]).
    pub fn from_toml(text: &str) -> Result<Self, CorrectError> {
        let bad = CorrectError::Scenario;
        let f: ScenarioFile = toml::from_str(text).map_err(|e| bad(e.message().to_string()))?;
        let need = |v: Option<f64>, name: &str| {
            v.ok_or_else(|| {
                bad(format!(
                    "surface.{name}: missing for surface.kind = \"{}\"",
                    f.surface.kind
                ))
            })
        };
        let shape = match f.surface.kind.as_str() {
            "panel" => Shape::Panel {
                radius_x: need(f.surface.radius_x, "radius_x")?,
                radius_y: need(f.surface.radius_y, "radius_y")?,
            },
            "nose-cone" => Shape::NoseCone {
                radius_start: need(f.surface.radius_start, "radius_start")?,
                radius_end: need(f.surface.radius_end, "radius_end")?,
            },
            other => {
                return Err(bad(format!(
                    "surface.kind = \"{other}\": allowed panel, nose-cone"
                )));
            }
        };
        let tool: Tool = f
            .program
            .tool
            .parse()
            .map_err(|e| bad(format!("program.tool = \"{}\": {e}", f.program.tool)))?;
        let interpolation: Interpolation = match &f.rounds.interpolation {
            Some(s) => s
                .parse()
                .map_err(|e| bad(format!("loop.interpolation = \"{s}\": {e}")))?,
            None => Interpolation::Bilinear,
        };
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
                gain: f.rounds.gain.unwrap_or(1.0),
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
