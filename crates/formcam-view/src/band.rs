//! The band laid on the mandrel as the program runs: every circuit of every
//! layer's path (`eye.csv`: the path point being laid per laid length `x`),
//! each circuit starting where the one before ends, in the mandrel link's
//! frame, and per point the spindle angle at which it is laid (the
//! circuit's `axes.csv` by `x`, each circuit turned on by the circuit's
//! spindle turn, the layer ending where `blocks.csv` ends it). A time's
//! spindle angle (the timeline's) says how much of it is laid.

use std::path::Path;

use formcam_machine::Machine;
use formcam_results::names;
use formcam_results::winding::{AXES, BLOCKS, EYE, axes, blocks, eye};
use serde::Serialize;
use serde_json::{Map, Value};
use ts_rs::TS;

use crate::ViewError;
use crate::scene::thin;
use crate::table::Table;
use crate::timeline::Timeline;

/// The most band points sent for drawing (over every circuit and layer).
pub const BAND_POINTS: usize = 20_000;

/// How far short of a point's spindle angle it counts as laid, degrees:
/// ten written units (the program's angles are rounded to 1e-4 deg, the
/// tables' are not).
const LAID_SLACK_DEG: f64 = 1e-3;

/// The band over the whole program, for drawing.
#[derive(Debug, Clone, Serialize, TS)]
pub struct Band {
    /// The link carrying the mandrel (the points' frame).
    pub link: usize,
    /// The band's width for drawing, mm: the width the pattern covers per
    /// circuit at the widest parallel (per turn for a one-circuit layer).
    pub width_mm: f64,
    /// The path points in laying order, `[x, y, z]` in the mandrel link's
    /// frame, mm (thinned per circuit for drawing).
    pub points: Vec<[f64; 3]>,
    /// Where each layer's points start (indices into `points`).
    pub layers: Vec<usize>,
    /// Rows of the layers' `eye.csv` tables (one circuit each), before thinning.
    pub table_points: usize,
    /// The spindle angle (NC units, the timeline's) at which each point is
    /// laid, times its layer's direction of turning: never decreasing
    /// within a layer.
    #[serde(skip)]
    keys: Vec<f64>,
    /// Per layer: its first point, its end, the direction its spindle turns.
    #[serde(skip)]
    spans: Vec<(usize, usize, f64)>,
    /// The spindle axis (an index into the timeline's axes).
    #[serde(skip)]
    spindle: usize,
}

/// One winding layer's tables.
struct LayerTables {
    /// The layer's number (1-based; 1 for a one-layer result).
    number: usize,
    /// Its circuits.
    circuits: usize,
    /// Per row of `eye.csv`: `x`, then the path point `z`, `r`, `v`, `alpha`.
    path: Vec<[f64; 5]>,
    /// `axes.csv`: `x` and the spindle angle.
    spindle: Vec<[f64; 2]>,
}

impl Band {
    /// The band of the result under `root` (`summary` its `summary.json`),
    /// or `None` when the result has no circuit tables (`eye.csv` and
    /// `axes.csv` by `x`), no `blocks.csv` or the machine no spindle.
    ///
    /// # Errors
    ///
    /// A table without a column it needs or with a bad number, naming the
    /// file and line.
    pub fn read(
        root: &Path,
        summary: &Map<String, Value>,
        tl: &Timeline,
    ) -> Result<Option<Self>, ViewError> {
        let m: &Machine = tl.machine();
        let Some(spindle) = m.roles.spindle else {
            return Ok(None);
        };
        let name = m.axes[spindle].name.as_str();
        let layers = layer_tables(root, summary, name)?;
        let blocks = root.join(BLOCKS.file);
        if layers.is_empty() || !blocks.is_file() {
            return Ok(None);
        }
        let ends = layer_ends(&blocks, name)?;
        // `blocks.csv` leaves out the program's first move (from the home);
        // its times follow from there.
        let total = ends.iter().map(|e| e.time_s).fold(0.0, f64::max);
        let lead = tl.duration_s() - total;
        // The points drawn shared by band length: as dense on every layer.
        let length = |l: &LayerTables| (l.path[l.path.len() - 1][0] - l.path[0][0]).abs();
        let whole: f64 = layers.iter().map(|l| l.circuits as f64 * length(l)).sum();
        let per_circuit = |l: &LayerTables| {
            let share = BAND_POINTS as f64 * length(l) / whole;
            if share.is_finite() {
                (share as usize).max(8)
            } else {
                l.path.len()
            }
        };
        let mut band = Self {
            link: m.roles.mandrel,
            width_mm: layers.first().map_or(10.0, width),
            points: Vec::new(),
            layers: Vec::new(),
            table_points: layers.iter().map(|l| l.path.len()).sum(),
            keys: Vec::new(),
            spans: Vec::new(),
            spindle,
        };
        for l in &layers {
            let Some(end) = ends.iter().find(|e| e.layer == l.number) else {
                continue;
            };
            // The timeline's spindle angle is the written one unwound from
            // its first value; `blocks.csv` has the planner's: whole turns
            // apart.
            let there = tl.sim().sample(end.time_s + lead)[spindle];
            let turns = ((there - end.angle) / 360.0).round() * 360.0;
            let (first, last) = (l.spindle[0], l.spindle[l.spindle.len() - 1]);
            let turn = last[1] - first[1];
            let direction = if turn < 0.0 { -1.0 } else { 1.0 };
            let start = end.angle + turns - turn * l.circuits as f64;
            let dv = l.path[l.path.len() - 1][3] - l.path[0][3];
            let kept = thin(&l.path, per_circuit(l));
            let from = band.points.len();
            for c in 0..l.circuits {
                for (k, row) in kept.iter().enumerate() {
                    // A circuit's last point is the next one's first.
                    if c > 0 && k == 0 {
                        continue;
                    }
                    let [x, z, r, v, _] = *row;
                    let v = v + dv * c as f64;
                    let a = start + turn * c as f64 + interpolate(&l.spindle, x) - first[1];
                    band.points.push([r * v.cos(), r * v.sin(), z]);
                    // Never decreasing (rounding of the tables aside).
                    let key = band.keys[from..]
                        .last()
                        .map_or(a * direction, |p| p.max(a * direction));
                    band.keys.push(key);
                }
            }
            band.layers.push(from);
            band.spans.push((from, band.points.len(), direction));
        }
        Ok((!band.points.is_empty()).then_some(band))
    }

    /// What [`Band::laid`] reads: per point its key angle, per layer its
    /// first point, end and direction, the spindle axis, the slack (deg).
    pub(crate) fn laid_table(&self) -> crate::report::LaidTable {
        crate::report::LaidTable {
            spindle: self.spindle,
            keys: self.keys.clone(),
            spans: self.spans.clone(),
            slack_deg: LAID_SLACK_DEG,
        }
    }

    /// How many of [`Band::points`] are laid when the axes stand at `axes`
    /// (the timeline's values): the layers before in whole, and of the
    /// layer being wound the points whose spindle angle is reached.
    pub fn laid(&self, axes: &[f64]) -> usize {
        let Some(&a) = axes.get(self.spindle) else {
            return 0;
        };
        let mut laid = 0;
        for &(from, to, direction) in &self.spans {
            // Within the rounding of the written angles it is laid.
            let n = self.keys[from..to].partition_point(|&k| k <= a * direction + LAID_SLACK_DEG);
            laid = from + n;
            if from + n < to {
                break;
            }
        }
        laid
    }
}

/// The width the pattern covers per circuit where the path is widest
/// (`2 pi r cos(alpha) / circuits`), or for one circuit the axial advance
/// per turn; 10 mm where neither is a length.
fn width(l: &LayerTables) -> f64 {
    let widest = l
        .path
        .iter()
        .fold(l.path[0], |a, b| if b[2] > a[2] { *b } else { a });
    let turns = (l.path[l.path.len() - 1][3] - l.path[0][3]).abs() / std::f64::consts::TAU;
    let w = if l.circuits > 1 {
        std::f64::consts::TAU * widest[2] * widest[4].cos().abs() / l.circuits as f64
    } else {
        let (lo, hi) = l
            .path
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[1]), hi.max(p[1]))
            });
        (hi - lo) / turns.max(1.0)
    };
    if w.is_finite() && w > 0.01 {
        w.min(200.0)
    } else {
        10.0
    }
}

/// The winding layers' tables: `layer-NN/` for each layer of `per_layer`
/// in the summary with circuits, else the folder's own (a one-layer result).
fn layer_tables(
    root: &Path,
    summary: &Map<String, Value>,
    spindle: &str,
) -> Result<Vec<LayerTables>, ViewError> {
    let mut out = Vec::new();
    let circuits = |v: &Value| {
        v.get("circuits")
            .and_then(Value::as_u64)
            .map(|c| c as usize)
    };
    match summary.get("per_layer").and_then(Value::as_array) {
        Some(layers) => {
            for l in layers {
                let (Some(n), Some(c)) = (l.get("layer").and_then(Value::as_u64), circuits(l))
                else {
                    continue;
                };
                let dir = root.join(names::layer_dir(n as usize));
                if let Some(t) = tables(&dir, n as usize, c, spindle)? {
                    out.push(t);
                }
            }
        }
        None => {
            if let Some(c) = summary.get("circuits").and_then(Value::as_u64)
                && let Some(t) = tables(root, 1, c as usize, spindle)?
            {
                out.push(t);
            }
        }
    }
    Ok(out)
}

/// A layer's `eye.csv` and `axes.csv` (of one circuit, by `x`), when both
/// are there.
fn tables(
    dir: &Path,
    number: usize,
    circuits: usize,
    spindle: &str,
) -> Result<Option<LayerTables>, ViewError> {
    let (eye_path, axes_path) = (dir.join(EYE.file), dir.join(AXES.file));
    if circuits == 0 || !eye_path.is_file() || !axes_path.is_file() {
        return Ok(None);
    }
    let e = Table::read(&eye_path)?;
    let a = Table::read(&axes_path)?;
    // A whole program's `axes.csv` is by time, not by laid length.
    if a.names().first().map(String::as_str) != Some(axes::X.name) || e.len() < 2 || a.len() < 2 {
        return Ok(None);
    }
    let columns = [eye::X, eye::Z, eye::R, eye::V, eye::ALPHA]
        .map(|c| e.numbers(c))
        .into_iter()
        .collect::<Result<Vec<_>, _>>()?;
    let path = (0..e.len())
        .map(|i| [0, 1, 2, 3, 4].map(|c| columns[c][i]))
        .collect();
    let spindle = a
        .numbers(axes::X)?
        .into_iter()
        .zip(a.numbers(spindle)?)
        .map(|(x, s)| [x, s])
        .collect();
    Ok(Some(LayerTables {
        number,
        circuits,
        path,
        spindle,
    }))
}

/// Where a layer ends in `blocks.csv`.
struct LayerEnd {
    /// The layer's number.
    layer: usize,
    /// The time at its last block's end, s from the first block's start.
    time_s: f64,
    /// The spindle angle there (the planner's, NC units).
    angle: f64,
}

/// Per layer, where its last block in `blocks.csv` ends.
fn layer_ends(path: &Path, spindle: &str) -> Result<Vec<LayerEnd>, ViewError> {
    let t = Table::read(path)?;
    let (layers, times, angles) = (
        t.numbers(blocks::LAYER)?,
        t.numbers(blocks::T)?,
        t.numbers(spindle)?,
    );
    let mut out: Vec<LayerEnd> = Vec::new();
    let mut time_s = 0.0;
    for ((layer, dt), angle) in layers.into_iter().zip(times).zip(angles) {
        time_s += dt;
        let layer = layer as usize;
        let end = LayerEnd {
            layer,
            time_s,
            angle,
        };
        match out.iter_mut().find(|e| e.layer == layer) {
            Some(e) => *e = end,
            None => out.push(end),
        }
    }
    Ok(out)
}

/// `table`'s second column at `x` (linear between rows sorted by `x`,
/// held beyond the ends).
fn interpolate(table: &[[f64; 2]], x: f64) -> f64 {
    let k = table.partition_point(|r| r[0] < x);
    if k == 0 {
        return table[0][1];
    }
    if k >= table.len() {
        return table[table.len() - 1][1];
    }
    let (a, b) = (table[k - 1], table[k]);
    if b[0] > a[0] {
        a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0])
    } else {
        b[1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_is_linear_between_rows_and_held_beyond() {
        let t = [[0.0, 10.0], [2.0, 30.0], [4.0, 30.0]];
        assert_eq!(interpolate(&t, -1.0), 10.0);
        assert_eq!(interpolate(&t, 1.0), 20.0);
        assert_eq!(interpolate(&t, 3.0), 30.0);
        assert_eq!(interpolate(&t, 9.0), 30.0);
    }
}
