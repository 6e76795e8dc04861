//! A dressing result (`formcam dress`): the wheel's profile, the contour
//! before dressing (the profile and its allowance) and after, the
//! dresser's path per pass, the removal rate and feed per step — and the
//! program (`program.mpf`) played in its own time, so that the page moves
//! the dresser along its path (`/api/dressing`, `/api/dressing/sample`).
//! The contour after each pass (`contour_passes.csv`, formcam-dress's
//! simulation of forming) and each block's pass let the page show the
//! contour as cut so far.

use std::path::Path;

use formcam_nc::{AxisSpec, Dialect, Motion, read_gcode_lines_in};
use formcam_sim::{FeedRule, Timeline};
use serde::Serialize;
use serde_json::{Map, Value};
use ts_rs::TS;

use formcam_results::dressing::{
    CONTOUR_FINAL, CONTOUR_INITIAL, CONTOUR_PASSES, DRESSER, MRR, PROFILE, contour_passes, dresser,
    mrr, zx,
};
use formcam_results::names;

use crate::ViewError;
use crate::table::Table;

/// The program the dressing view plays.
pub const DRESSING_PROGRAM: &str = names::DRESSING_PROGRAM;

/// A dressing result, read once.
#[derive(Debug, Clone)]
pub struct DressingView {
    timeline: Timeline,
    body: DressingBody,
}

/// What `/api/dressing` sends: the drawing and the program's time.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct DressingBody {
    /// The profile (`profile.csv`): `[z, x]`, mm.
    pub profile: Vec<[f64; 2]>,
    /// The wheel before dressing (`contour_initial.csv`: the profile offset
    /// by the allowance, or the given contour).
    pub initial: Vec<[f64; 2]>,
    /// The wheel after dressing (`contour_final.csv`).
    pub final_contour: Vec<[f64; 2]>,
    /// The wheel after each pass (`contour_passes.csv`), pass after pass;
    /// empty for a result written without that file.
    pub contours: Vec<Vec<[f64; 2]>>,
    /// Per pass (`dresser.csv`): point A's path and the dressing corner.
    pub passes: Vec<DresserPass>,
    /// Per step (`mrr.csv`): `z`, removal rate and feed.
    pub mrr: MrrPlot,
    /// The program's time, s (its feeds; rapid moves take none).
    pub duration_s: f64,
    /// Each block's start, then the program's end, s.
    pub t: Vec<f64>,
    /// Point A at the program's start, then at each block's end: `[z, x]`, mm.
    pub points: Vec<[f64; 2]>,
    /// Each block's line in the program (1-based).
    pub lines: Vec<usize>,
    /// Each block's pass (1-based): the passes are the runs of feed moves
    /// between rapid moves; a rapid move belongs to the pass before it (0
    /// before the first).
    pub block_pass: Vec<usize>,
    /// The program's text.
    pub program: String,
}

/// One pass of the dresser.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct DresserPass {
    /// The pass's number (1-based).
    pub pass: usize,
    /// Point A per path point: `[z, x]`, mm.
    pub path: Vec<[f64; 2]>,
    /// The dressing corner's centre relative to point A: `[dz, dx]`, mm.
    pub corner_offset: [f64; 2],
    /// The dressing corner's radius, mm (0 when the summary does not say).
    pub corner_radius: f64,
}

/// The removal rate and feed per step, with feed control (the program's
/// feeds) and without (the constant feed of the same time).
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct MrrPlot {
    /// The step's pass (1-based).
    pub pass: Vec<usize>,
    /// Where the step ends along the wheel's axis (point A), mm.
    pub z: Vec<f64>,
    /// Point A's radial position at the step's end, mm.
    pub x: Vec<f64>,
    /// Removal rate with feed control, mm²/min of the section.
    pub mrr: Vec<f64>,
    /// Feed with feed control, mm/min.
    pub feed: Vec<f64>,
    /// Removal rate without feed control (at `feed_uncontrolled`), mm²/min.
    pub mrr_uncontrolled: Vec<f64>,
    /// The constant feed without feed control, mm/min (the summary's
    /// `feed_uncontrolled_mm_min`; `None` when it does not say).
    pub feed_uncontrolled: Option<f64>,
    /// The removal rate the feeds were planned for, mm²/min (the summary's
    /// `target_mrr_mm2_min`).
    pub target: Option<f64>,
}

/// The dresser at one time.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct DresserSample {
    /// The time, s.
    pub t: f64,
    /// The block running (0-based).
    pub block: usize,
    /// Its line in the program (1-based).
    pub line: usize,
    /// Point A: `[x, z]` (radial, axial), mm.
    pub dresser: [f64; 2],
}

impl DressingView {
    /// Reads the dressing result in `root` (its `summary`, already read).
    ///
    /// # Errors
    ///
    /// [`ViewError`] naming the file, the line and the column.
    pub fn read(root: &Path, summary: &Map<String, Value>) -> Result<Self, ViewError> {
        let program_path = root.join(DRESSING_PROGRAM);
        let program = crate::folder::read_text(&program_path)?;
        let timeline = program_timeline(&program, &program_path)?;
        let pairs = |name: &str| -> Result<Vec<[f64; 2]>, ViewError> {
            let t = Table::read(&root.join(name))?;
            Ok(zip(&t.numbers(zx::Z)?, &t.numbers(zx::X)?))
        };
        let dresser = Table::read(&root.join(DRESSER.file))?;
        let mrr_table = Table::read(&root.join(MRR.file))?;
        let mut t = Vec::with_capacity(timeline.len() + 1);
        let mut points = Vec::with_capacity(timeline.len() + 1);
        let mut lines = Vec::with_capacity(timeline.len());
        let mut block_pass = Vec::with_capacity(timeline.len());
        let (mut pass, mut moving) = (0, false);
        for b in timeline.blocks() {
            if b.index == 0 {
                points.push([b.from[0], b.from[1]]);
            }
            t.push(b.start_s);
            points.push([b.to[0], b.to[1]]);
            lines.push(b.line);
            let feed = b.kind == Motion::Linear;
            if feed && !moving {
                pass += 1;
            }
            moving = feed;
            block_pass.push(pass);
        }
        t.push(timeline.duration_s());
        let body = DressingBody {
            profile: pairs(PROFILE.file)?,
            initial: pairs(CONTOUR_INITIAL.file)?,
            final_contour: pairs(CONTOUR_FINAL.file)?,
            contours: contours(root)?,
            passes: passes(&dresser, summary)?,
            mrr: MrrPlot {
                pass: mrr_table
                    .numbers(mrr::PASS)?
                    .iter()
                    .map(|p| *p as usize)
                    .collect(),
                z: mrr_table.numbers(mrr::Z)?,
                x: mrr_table.numbers(mrr::X)?,
                mrr: mrr_table.numbers(mrr::MRR)?,
                feed: mrr_table.numbers(mrr::FEED)?,
                mrr_uncontrolled: mrr_table.numbers(mrr::MRR_UNCONTROLLED)?,
                feed_uncontrolled: summary
                    .get("feed_uncontrolled_mm_min")
                    .and_then(Value::as_f64),
                target: summary.get("target_mrr_mm2_min").and_then(Value::as_f64),
            },
            duration_s: timeline.duration_s(),
            t,
            points,
            lines,
            block_pass,
            program,
        };
        Ok(Self { timeline, body })
    }

    /// What `/api/dressing` sends.
    pub fn body(&self) -> &DressingBody {
        &self.body
    }

    /// The program's timeline (axes `Z`, `X`).
    pub fn timeline(&self) -> &Timeline {
        &self.timeline
    }

    /// The dresser at `t` s (clamped to the program): point A moving
    /// linearly within each block.
    pub fn sample(&self, t: f64) -> DresserSample {
        let t = if t.is_finite() {
            t.clamp(0.0, self.timeline.duration_s())
        } else {
            0.0
        };
        let block = self.timeline.block_at(t).unwrap_or(0);
        let at = self.timeline.sample(t);
        DresserSample {
            t,
            block,
            line: self.body.lines.get(block).copied().unwrap_or(0),
            dresser: [at[1], at[0]],
        }
    }
}

/// The dressing program (840D, plane G18, axes `Z`, `X`) timed by its own
/// feeds: from its first point, rapid moves taking no time.
fn program_timeline(text: &str, path: &Path) -> Result<Timeline, ViewError> {
    let axes = [AxisSpec::linear("Z"), AxisSpec::linear("X")];
    let (program, lines) =
        read_gcode_lines_in(text, &axes, Dialect::Sinumerik840d).map_err(|source| {
            ViewError::Program {
                path: path.to_path_buf(),
                source,
            }
        })?;
    let start = program
        .blocks
        .first()
        .map(|b| b.target.clone())
        .ok_or_else(|| ViewError::EmptyProgram {
            path: path.to_path_buf(),
        })?;
    Timeline::from_start(
        &program,
        &lines,
        FeedRule::of(Dialect::Sinumerik840d),
        &start,
        &[f64::INFINITY; 2],
    )
    .map_err(|source| ViewError::Timeline {
        path: path.to_path_buf(),
        source: Box::new(source),
    })
}

/// The contour after each pass (`contour_passes.csv`: `z,x,pass`), pass
/// after pass; none for a result written before that file was.
fn contours(root: &Path) -> Result<Vec<Vec<[f64; 2]>>, ViewError> {
    let path = root.join(CONTOUR_PASSES.file);
    if !path.exists() {
        return Ok(Vec::new());
    }
    let t = Table::read(&path)?;
    let (z, x, pass) = (
        t.numbers(zx::Z)?,
        t.numbers(zx::X)?,
        t.numbers(contour_passes::PASS)?,
    );
    let mut out: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut current = None;
    for i in 0..z.len() {
        if current != Some(pass[i]) {
            current = Some(pass[i]);
            out.push(Vec::new());
        }
        if let Some(c) = out.last_mut() {
            c.push([z[i], x[i]]);
        }
    }
    Ok(out)
}

fn zip(a: &[f64], b: &[f64]) -> Vec<[f64; 2]> {
    a.iter().zip(b).map(|(a, b)| [*a, *b]).collect()
}

/// The passes of `dresser.csv` in order, each with its corner: the offset
/// of the corner's centre from point A (the same along a pass) and the
/// radius from the summary's `passes`.
fn passes(t: &Table, summary: &Map<String, Value>) -> Result<Vec<DresserPass>, ViewError> {
    let (z, x) = (t.numbers(dresser::Z)?, t.numbers(dresser::X)?);
    let (cz, cx) = (t.numbers(dresser::CORNER_Z)?, t.numbers(dresser::CORNER_X)?);
    let pass = t.numbers(dresser::PASS)?;
    let radius = |n: usize| {
        summary
            .get("passes")
            .and_then(Value::as_array)
            .and_then(|p| p.get(n - 1))
            .and_then(|p| p.get("corner_radius_mm"))
            .and_then(Value::as_f64)
            .unwrap_or(0.0)
    };
    let mut out: Vec<DresserPass> = Vec::new();
    for i in 0..z.len() {
        let n = pass[i] as usize;
        if out.last().is_none_or(|p| p.pass != n) {
            out.push(DresserPass {
                pass: n,
                path: Vec::new(),
                corner_offset: [cz[i] - z[i], cx[i] - x[i]],
                corner_radius: radius(n.max(1)),
            });
        }
        if let Some(p) = out.last_mut() {
            p.path.push([z[i], x[i]]);
        }
    }
    Ok(out)
}
