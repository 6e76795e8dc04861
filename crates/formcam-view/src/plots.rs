//! The plots of a winding result (`/api/plots`): per layer the winding
//! angle and the laminate thickness along the meridian (`path.csv`) and the
//! pull speed over a circuit (`eye.csv`); each axis's position and velocity
//! against time and each block's time, from the program's timeline.
//!
//! Every number is one the result wrote or the timeline gives; nothing is
//! decimated: the page draws them as they come.

use std::path::{Path, PathBuf};

use formcam_results::names;
use formcam_results::winding::{EYE, PATH, eye, path};
use formcam_sim::Timeline;
use serde::Serialize;
use ts_rs::TS;

use crate::ViewError;
use crate::table::Table;

/// What `/api/plots` sends.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct WindingPlots {
    /// Per winding layer, along the meridian (`path.csv`).
    pub meridian: Vec<MeridianPlot>,
    /// Per winding layer with an eye trajectory, over a circuit (`eye.csv`).
    pub pull: Vec<PullPlot>,
    /// Each axis against time, from the program's timeline (absent without
    /// a program).
    pub axes: Option<AxisPlots>,
}

/// One layer's pass along the meridian.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct MeridianPlot {
    /// The layer's number (1 for a single-layer job).
    pub layer: usize,
    /// Axial position, mm, ascending.
    pub z: Vec<f64>,
    /// Winding angle from the meridian, degrees.
    pub alpha_deg: Vec<f64>,
    /// Laminate thickness of the layer (two plies), mm.
    pub thickness: Vec<f64>,
}

/// One layer's pull speed over a circuit.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct PullPlot {
    /// The layer's number.
    pub layer: usize,
    /// Laid band length along the circuit, mm.
    pub x: Vec<f64>,
    /// Relative pull speed `u = d lambda / dx`.
    pub u: Vec<f64>,
}

/// Each axis against time and each block's time, from a [`Timeline`].
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct AxisPlots {
    /// The axes: name, position unit, velocity unit.
    pub names: Vec<String>,
    /// `deg` or `mm` per axis.
    pub units: Vec<&'static str>,
    /// `deg/min` or `mm/min` per axis.
    pub velocity_units: Vec<&'static str>,
    /// Each block's start, then the program's end, s (`blocks + 1` values).
    pub t: Vec<f64>,
    /// Per axis: the start point, then each block's end (NC units).
    pub position: Vec<Vec<f64>>,
    /// Per axis: each block's velocity (its axis change over its time, per
    /// minute), the last repeated at the end (a step plot); `None` for a
    /// block that takes no time.
    pub velocity: Vec<Vec<Option<f64>>>,
    /// Each block's time, s.
    pub block_s: Vec<f64>,
    /// Each block's line in the program (1-based).
    pub block_line: Vec<usize>,
}

impl AxisPlots {
    /// The axes of `tl` block by block: positions at the block ends,
    /// velocities constant within a block, as the timeline moves them.
    pub fn of(tl: &Timeline) -> Self {
        let axes = tl.axes();
        let n = tl.len();
        let mut t = Vec::with_capacity(n + 1);
        let mut position: Vec<Vec<f64>> = vec![Vec::with_capacity(n + 1); axes.len()];
        let mut velocity: Vec<Vec<Option<f64>>> = vec![Vec::with_capacity(n + 1); axes.len()];
        let mut block_s = Vec::with_capacity(n);
        let mut block_line = Vec::with_capacity(n);
        for b in tl.blocks() {
            if b.index == 0 {
                for (p, v) in position.iter_mut().zip(b.from) {
                    p.push(*v);
                }
            }
            t.push(b.start_s);
            block_s.push(b.duration_s);
            block_line.push(b.line);
            for (k, (from, to)) in b.from.iter().zip(b.to).enumerate() {
                position[k].push(*to);
                velocity[k].push((b.duration_s > 0.0).then(|| (to - from) / b.duration_s * 60.0));
            }
        }
        if n > 0 {
            t.push(tl.duration_s());
            for v in &mut velocity {
                let last = v.last().copied().flatten();
                v.push(last);
            }
        }
        Self {
            names: axes.iter().map(|a| a.name.clone()).collect(),
            units: axes
                .iter()
                .map(|a| if a.rotary { "deg" } else { "mm" })
                .collect(),
            velocity_units: axes
                .iter()
                .map(|a| if a.rotary { "deg/min" } else { "mm/min" })
                .collect(),
            t,
            position,
            velocity,
            block_s,
            block_line,
        }
    }
}

impl WindingPlots {
    /// The plots of the winding result in `root`: its layers' tables (the
    /// folder's own `path.csv`/`eye.csv`, else each `layer-NN/`'s) and the
    /// program's timeline `tl`, if it has a program.
    ///
    /// # Errors
    ///
    /// [`ViewError::Read`] or [`ViewError::Table`] naming the file, the line
    /// and the column.
    pub fn read(root: &Path, tl: Option<&Timeline>) -> Result<Self, ViewError> {
        let mut meridian = Vec::new();
        let mut pull = Vec::new();
        for (layer, dir) in layer_folders(root)? {
            let path_file = dir.join(PATH.file);
            if path_file.is_file() {
                // A path table without the angle and thickness (written by
                // other tools, or cut down) has no meridian plot.
                let t = Table::read(&path_file)?;
                if [path::Z, path::ALPHA_DEG, path::THICKNESS]
                    .iter()
                    .all(|c| t.has(c))
                {
                    meridian.push(meridian_plot(layer, &t)?);
                }
            }
            let eye_file = dir.join(EYE.file);
            if eye_file.is_file() {
                let t = Table::read(&eye_file)?;
                if t.has(eye::U) {
                    pull.push(PullPlot {
                        layer,
                        x: t.numbers(eye::X)?,
                        u: t.numbers(eye::U)?,
                    });
                }
            }
        }
        Ok(Self {
            meridian,
            pull,
            axes: tl.map(AxisPlots::of),
        })
    }
}

/// The folders holding a layer's tables, with the layer's number: the
/// result folder itself (layer 1) when it has `path.csv`, else every
/// `layer-NN/` in order.
fn layer_folders(root: &Path) -> Result<Vec<(usize, PathBuf)>, ViewError> {
    if root.join(PATH.file).is_file() {
        return Ok(vec![(1, root.to_path_buf())]);
    }
    let entries = std::fs::read_dir(root).map_err(|_| ViewError::NoFolder {
        path: root.to_path_buf(),
    })?;
    let mut out: Vec<(usize, PathBuf)> = entries
        .filter_map(Result::ok)
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let n = names::layer_of(&name)?;
            Some((n, e.path()))
        })
        .collect();
    out.sort();
    Ok(out)
}

/// A pass's winding angle and thickness by ascending `z` (a pass from the
/// far end is read backwards; one that turns back on itself is sorted).
fn meridian_plot(layer: usize, t: &Table) -> Result<MeridianPlot, ViewError> {
    let z = t.numbers(path::Z)?;
    let alpha = t.numbers(path::ALPHA_DEG)?;
    let thickness = t.numbers(path::THICKNESS)?;
    let mut order: Vec<usize> = (0..z.len()).collect();
    if z.windows(2).all(|w| w[0] >= w[1]) {
        order.reverse();
    } else if !z.windows(2).all(|w| w[0] <= w[1]) {
        order.sort_by(|&a, &b| z[a].total_cmp(&z[b]));
    }
    Ok(MeridianPlot {
        layer,
        z: order.iter().map(|&i| z[i]).collect(),
        alpha_deg: order.iter().map(|&i| alpha[i]).collect(),
        thickness: order.iter().map(|&i| thickness[i]).collect(),
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use formcam_nc::{AxisSpec, Block, Feed, Program};
    use formcam_sim::FeedRule;

    #[test]
    fn velocities_are_each_blocks_axis_change_over_its_time() {
        let mut p = Program::new("T", vec![AxisSpec::rotary("A"), AxisSpec::linear("X")]);
        p.blocks
            .push(Block::linear(vec![90.0, 10.0], Feed::InverseTime(0.5)));
        p.blocks
            .push(Block::linear(vec![90.0, 40.0], Feed::PerMinute(600.0)));
        p.blocks.push(Block::rapid(vec![90.0, 40.0]));
        let tl =
            Timeline::from_start(&p, &[3, 4, 5], FeedRule::Iso, &[0.0, 0.0], &[1.0, 1.0]).unwrap();
        let a = AxisPlots::of(&tl);
        assert_eq!(a.names, ["A", "X"]);
        assert_eq!(a.units, ["deg", "mm"]);
        assert_eq!(a.velocity_units, ["deg/min", "mm/min"]);
        // 0.5 s, then 30 mm at 600 mm/min = 3 s, then a rapid that moves nothing.
        for (t, want) in a.t.iter().zip([0.0, 0.5, 3.5, 3.5]) {
            assert!((t - want).abs() < 1e-12, "{:?}", a.t);
        }
        assert_eq!(a.position[0], [0.0, 90.0, 90.0, 90.0]);
        assert_eq!(a.position[1], [0.0, 10.0, 40.0, 40.0]);
        assert_eq!(a.velocity[0], [Some(10800.0), Some(0.0), None, None]);
        let vx = a.velocity[1][1].unwrap();
        assert!((vx - 600.0).abs() < 1e-9, "{vx}");
        assert_eq!(a.velocity[1][0], Some(1200.0));
        assert_eq!(a.block_s.len(), 3);
        assert!((a.block_s[1] - 3.0).abs() < 1e-12 && a.block_s[2] == 0.0);
        assert_eq!(a.block_line, [3, 4, 5]);
    }

    #[test]
    fn a_pass_from_the_far_end_is_read_by_ascending_z() {
        let t = Table::parse(
            "z,alpha_deg,thickness\n3,30,0.5\n2,20,0.4\n1,10,0.3\n",
            Path::new(PATH.file),
        )
        .unwrap();
        let m = meridian_plot(2, &t).unwrap();
        assert_eq!(m.z, [1.0, 2.0, 3.0]);
        assert_eq!(m.alpha_deg, [10.0, 20.0, 30.0]);
        assert_eq!(m.thickness, [0.3, 0.4, 0.5]);
        let t = Table::parse(
            "z,alpha_deg,thickness\n1,10,0\n3,30,0\n2,20,0\n",
            Path::new(PATH.file),
        )
        .unwrap();
        assert_eq!(meridian_plot(1, &t).unwrap().alpha_deg, [10.0, 20.0, 30.0]);
    }
}
