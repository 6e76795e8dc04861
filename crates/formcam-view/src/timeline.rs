//! The timeline the page draws: the simulator's [`formcam_sim::Timeline`]
//! (the program read back from its text, each block's start and time from
//! its own feeds by the dialect's rule, the axes linear within a block,
//! every link's world pose and key point by forward kinematics), in the
//! shape the page receives ([`Sample`], [`TimelineHead`]).

use formcam_machine::{JointKind, Machine};
use formcam_nc::{Dialect, read_cldata_lines, read_gcode_lines_in};
use formcam_sim::{FeedRule, SimError, program_axes};
use nalgebra::Isometry3;
use serde::Serialize;
use ts_rs::TS;

use crate::ViewError;

/// The program on the machine, block by block.
#[derive(Debug, Clone)]
pub struct Timeline {
    machine: Machine,
    sim: formcam_sim::Timeline,
    /// Per block: end time, s (the shown block at `t` is the first ending
    /// at or after it).
    ends: Vec<f64>,
}

/// The state at one time: what the page shows.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct Sample {
    /// Time since the program's start, s.
    pub t: f64,
    /// The block running (0-based index of the motion blocks).
    pub block: usize,
    /// Its line in the program text (1-based; 0 when unknown).
    pub line: usize,
    /// Axis values in the machine's order: degrees for rotary axes, mm.
    pub axes: Vec<f64>,
    /// Every link's world pose: `[x, y, z, qx, qy, qz, qw]` (mm, a unit quaternion).
    pub poses: Vec<[f64; 7]>,
    /// Every key point's world position, mm.
    pub points: Vec<[f64; 3]>,
}

/// What the samples' arrays mean.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct TimelineHead {
    /// The program's time, s.
    pub duration_s: f64,
    /// Motion blocks.
    pub blocks: usize,
    /// The axes: name and unit (`deg` or `mm`).
    pub axes: Vec<AxisHead>,
    /// The links' names (the order of [`Sample::poses`]).
    pub links: Vec<String>,
    /// The key points' names (the order of [`Sample::points`]).
    pub points: Vec<String>,
    /// The payout point: an index into `points`.
    pub payout: usize,
}

/// An axis of the timeline.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct AxisHead {
    /// NC address.
    pub name: String,
    /// `deg` or `mm`.
    #[ts(type = "\"deg\" | \"mm\"")]
    pub unit: &'static str,
}

impl Timeline {
    /// Reads `text` (written in `dialect` for `machine`) back and plays it
    /// on the simulator: from the machine's home, per-minute feeds by the
    /// dialect's rule, rapids at the axes' velocity limits.
    ///
    /// # Errors
    ///
    /// The reader's error (with the line), a block the simulator cannot
    /// time, or a program without blocks, named `path` (the program file).
    pub fn from_program(
        machine: Machine,
        text: &str,
        dialect: Dialect,
        path: &std::path::Path,
    ) -> Result<Self, ViewError> {
        let axes = program_axes(&machine);
        let (program, lines) = match dialect {
            Dialect::Cldata => read_cldata_lines(text, &axes),
            d => read_gcode_lines_in(text, &axes, d),
        }
        .map_err(|source| ViewError::Program {
            path: path.to_path_buf(),
            source,
        })?;
        if program.blocks.is_empty() {
            return Err(ViewError::EmptyProgram {
                path: path.to_path_buf(),
            });
        }
        let sim = formcam_sim::Timeline::new(&program, &lines, FeedRule::of(dialect), &machine)
            .map_err(|source| match source {
                SimError::Program { path, source } => ViewError::Program { path, source },
                source => ViewError::Timeline {
                    path: path.to_path_buf(),
                    source: Box::new(source),
                },
            })?;
        let ends = sim.blocks().map(|b| b.start_s + b.duration_s).collect();
        Ok(Self { machine, sim, ends })
    }

    /// The simulator's timeline (what the checks run on).
    pub fn sim(&self) -> &formcam_sim::Timeline {
        &self.sim
    }

    /// The program's time, s.
    pub fn duration_s(&self) -> f64 {
        self.sim.duration_s()
    }

    /// The machine.
    pub fn machine(&self) -> &Machine {
        &self.machine
    }

    /// What the samples' arrays mean.
    pub fn head(&self) -> TimelineHead {
        let m = &self.machine;
        TimelineHead {
            duration_s: self.duration_s(),
            blocks: self.sim.len(),
            axes: m
                .axes
                .iter()
                .map(|a| AxisHead {
                    name: a.name.clone(),
                    unit: if a.kind == JointKind::Revolute {
                        "deg"
                    } else {
                        "mm"
                    },
                })
                .collect(),
            links: m.links.iter().map(|l| l.name.clone()).collect(),
            points: m.points.iter().map(|p| p.name.clone()).collect(),
            payout: m.roles.payout,
        }
    }

    /// The block shown at `t` s: the first that ends at or after it (at a
    /// block's end, that block and its line).
    pub fn block_shown(&self, t: f64) -> usize {
        self.ends
            .partition_point(|&e| e < t)
            .min(self.ends.len().saturating_sub(1))
    }

    /// The state at `t` s (clamped to the program): the block shown, the
    /// axes, the poses and key points as the simulator gives them.
    pub fn sample(&self, t: f64) -> Sample {
        let t = if t.is_finite() {
            t.clamp(0.0, self.duration_s())
        } else {
            0.0
        };
        let block = self.block_shown(t);
        let poses = self.sim.poses_at(&self.machine, t);
        Sample {
            t,
            block,
            line: self.sim.block(block).map_or(0, |b| b.line),
            axes: poses.axes,
            poses: poses.links.iter().map(pose).collect(),
            points: poses.points.iter().map(|p| [p.x, p.y, p.z]).collect(),
        }
    }

    /// `n` samples (at least 2) at equal steps from the start to the end.
    pub fn samples(&self, n: usize) -> Vec<Sample> {
        let n = n.max(2);
        let d = self.duration_s();
        (0..n)
            .map(|i| self.sample(d * i as f64 / (n - 1) as f64))
            .collect()
    }

    /// Per block: its line in the program text (1-based).
    pub fn lines(&self) -> Vec<usize> {
        self.sim.blocks().map(|b| b.line).collect()
    }

    /// Per block: start and end time, s.
    pub fn block_span(&self, block: usize) -> Option<(f64, f64)> {
        let b = self.sim.block(block)?;
        Some((b.start_s, b.start_s + b.duration_s))
    }
}

fn pose(p: &Isometry3<f64>) -> [f64; 7] {
    let v = p.translation.vector;
    let q = p.rotation.quaternion();
    [v.x, v.y, v.z, q.i, q.j, q.k, q.w]
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use formcam_nc::{Block, Feed, Program, write};

    fn machine() -> Machine {
        formcam_machine::shipped::shipped("winder-4axis")
            .unwrap()
            .machine()
            .unwrap()
    }

    #[test]
    fn every_dialect_gives_the_simulators_times_and_lines() {
        let m = machine();
        let mut p = Program::new("LINES", program_axes(&m));
        p.blocks.push(Block::rapid(vec![0.0, 0.0, 250.0, 0.0]));
        for i in 1..40 {
            let v = f64::from(i);
            p.blocks.push(
                Block::linear(
                    vec![v * 100.0, v, 250.0 + v, v / 10.0],
                    Feed::InverseTime(0.5),
                )
                .with_comment(format!("block X{i}")),
            );
        }
        for d in Dialect::ALL {
            let mut text = String::new();
            write(&p, d, &mut text).unwrap();
            let tl =
                Timeline::from_program(m.clone(), &text, d, std::path::Path::new("p")).unwrap();
            assert_eq!(tl.head().blocks, tl.sim().len(), "{d:?}");
            let all: Vec<&str> = text.lines().collect();
            for (k, b) in tl.sim().blocks().enumerate() {
                // The block's X value stands on its line.
                let x = b.to[1];
                let line = all[b.line - 1];
                assert!(
                    line.contains(&format!("{x}")) || (x == 0.0 && line.contains('0')),
                    "{d:?} block {k}: {line}"
                );
                // At its end the sample shows it, at the simulator's values.
                let (_, end) = tl.block_span(k).unwrap();
                let s = tl.sample(end);
                if b.duration_s > 0.0 {
                    assert_eq!(s.block, k, "{d:?}");
                }
                assert_eq!(s.axes, tl.sim().sample(end), "{d:?}");
            }
        }
    }
}
