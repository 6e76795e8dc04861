//! The timeline of a program: when each block starts, how long it takes and
//! where the axes are at any time.

use formcam_machine::{JointKind, Machine};
use formcam_nc::{AxisSpec, Feed, Motion, Program};
use nalgebra::{Isometry3, Point3};

use crate::{FeedRule, SimError};

/// A program played in time: block `i` runs from `start_s(i)` for
/// `duration_s(i)`, its axes moving linearly from the end of the block
/// before (or the start point) to its target. Values are in NC units (mm,
/// degrees for rotary axes; modulo axes unwound), in the program's axis
/// order.
#[derive(Debug, Clone, PartialEq)]
pub struct Timeline {
    axes: Vec<AxisSpec>,
    /// The start point, then each block's end: `(n + 1) * width` values.
    points: Vec<f64>,
    /// Each block's start time, then the end of the last: `n + 1` values.
    starts: Vec<f64>,
    kinds: Vec<Motion>,
    /// Whether each block is a dwell (`G4`): no axis moves for its time.
    dwells: Vec<bool>,
    lines: Vec<usize>,
    /// Each block's relative time uncertainty from the written text.
    rel_dt: Vec<f64>,
}

/// One block of a [`Timeline`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockSpan<'a> {
    /// The block's index (0-based).
    pub index: usize,
    /// Its line in the program text (1-based).
    pub line: usize,
    /// Rapid or linear (a dwell is linear: no axis moves).
    pub kind: Motion,
    /// A dwell (`G4`): the axes stand still for its time.
    pub dwell: bool,
    /// When it starts, s.
    pub start_s: f64,
    /// How long it takes, s.
    pub duration_s: f64,
    /// The axis values where it starts (NC units).
    pub from: &'a [f64],
    /// The axis values where it ends.
    pub to: &'a [f64],
}

/// The machine at one time: every link's world pose and every key point.
#[derive(Debug, Clone, PartialEq)]
pub struct Poses {
    /// The time, s.
    pub time_s: f64,
    /// The block running then (`None` for an empty program).
    pub block: Option<usize>,
    /// The axis values (NC units: mm, degrees).
    pub axes: Vec<f64>,
    /// World pose of each link, in the order of [`Machine::links`].
    pub links: Vec<Isometry3<f64>>,
    /// World position of each key point (mm), in the order of [`Machine::points`].
    pub points: Vec<Point3<f64>>,
}

impl Timeline {
    /// The timeline of `program` (whose block `i` stands on line `lines[i]`)
    /// on `machine`, whose axes are the program's in the same order
    /// ([`crate::program_axes`]): starting at the machine's home, per-minute
    /// feeds measured by `rule`, rapids at the machine's velocity limits.
    pub fn new(
        program: &Program,
        lines: &[usize],
        rule: FeedRule,
        machine: &Machine,
    ) -> Result<Self, SimError> {
        let to_nc = |a: &formcam_machine::Axis, v: f64| {
            if a.kind == JointKind::Revolute {
                v.to_degrees()
            } else {
                v
            }
        };
        let start: Vec<f64> = machine.axes.iter().map(|a| to_nc(a, a.home)).collect();
        let rapid: Vec<f64> = machine.axes.iter().map(|a| to_nc(a, a.v_max)).collect();
        Self::from_start(program, lines, rule, &start, &rapid)
    }

    /// The timeline of `program` from the axis values `start` (NC units),
    /// rapids at `rapid_per_s` per axis (NC units per second; the slowest
    /// axis decides; an infinite rate takes no time). Each of the program's
    /// dwells ([`Program::dwells`]) is a block of its own, on its own line,
    /// that moves nothing for its time, so the timeline's block `i` is the
    /// program's only when the program has no dwell.
    pub fn from_start(
        program: &Program,
        lines: &[usize],
        rule: FeedRule,
        start: &[f64],
        rapid_per_s: &[f64],
    ) -> Result<Self, SimError> {
        let n = program.blocks.len();
        if lines.len() != n {
            return Err(SimError::Lines {
                count: n,
                lines: lines.len(),
            });
        }
        let w = program.axes.len();
        let mut points = Vec::with_capacity((n + 1) * w);
        points.extend_from_slice(&start[..w.min(start.len())]);
        points.resize(w, 0.0);
        let mut starts = Vec::with_capacity(n + 1);
        let mut rel_dt = Vec::with_capacity(n);
        // How far a written length may be off: every axis word one unit.
        let res_norm = program
            .axes
            .iter()
            .map(|a| crate::limits::resolution(a.rotary).powi(2))
            .sum::<f64>()
            .sqrt();
        let mut t = 0.0;
        let mut kinds = Vec::with_capacity(n);
        let mut dwells = Vec::with_capacity(n);
        let mut block_lines = Vec::with_capacity(n);
        let mut pending_dwells = program.dwells.iter().peekable();
        for (i, b) in program.blocks.iter().enumerate() {
            // Dwells before this block: blocks that move nothing for their time.
            while let Some(d) = pending_dwells.next_if(|d| d.blocks_before <= i) {
                dwell_block(&mut points, w, &mut starts, &mut t, d.seconds);
                rel_dt.push(0.0);
                kinds.push(Motion::Linear);
                dwells.push(true);
                block_lines.push(d.line);
            }
            let from_at = points.len() - w;
            let fail = |what: String| SimError::Block {
                block: i + 1,
                line: lines[i],
                what,
            };
            if b.target.len() != w || b.target.iter().any(|v| !v.is_finite()) {
                return Err(fail(format!("needs {w} finite axis values")));
            }
            let from = &points[from_at..from_at + w];
            let (d, rel) = match (b.kind, b.feed) {
                (Motion::Rapid, _) => (
                    from.iter()
                        .zip(&b.target)
                        .zip(rapid_per_s)
                        .map(|((p, q), v)| (q - p).abs() / v)
                        .fold(0.0, f64::max),
                    0.0,
                ),
                // `F = 60 / t` written to 3 decimals.
                (Motion::Linear, Feed::InverseTime(s)) => (s, 0.0005 * s / 60.0),
                (Motion::Linear, Feed::PerMinute(f)) => {
                    let len = rule.length(&program.axes, from, &b.target);
                    // The length from rounded words, `F` to 1 decimal.
                    let rel = if len > 0.0 {
                        res_norm / len + 0.05 / f
                    } else {
                        0.0
                    };
                    (len / f * 60.0, rel)
                }
                (Motion::Linear, Feed::None) => {
                    return Err(fail("a feed move without a feed".into()));
                }
            };
            if !(d.is_finite() && d >= 0.0) {
                return Err(fail(format!("block time {d} s is not finite")));
            }
            starts.push(t);
            rel_dt.push(rel);
            t += d;
            points.extend_from_slice(&b.target);
            kinds.push(b.kind);
            dwells.push(false);
            block_lines.push(lines[i]);
        }
        for d in pending_dwells {
            dwell_block(&mut points, w, &mut starts, &mut t, d.seconds);
            rel_dt.push(0.0);
            kinds.push(Motion::Linear);
            dwells.push(true);
            block_lines.push(d.line);
        }
        starts.push(t);
        Ok(Self {
            axes: program.axes.clone(),
            points,
            starts,
            kinds,
            dwells,
            lines: block_lines,
            rel_dt,
        })
    }

    /// How far block `i`'s duration may be off, relative, from the
    /// rounding of the written text: `F` (`60 / t` to 3 decimals; a
    /// per-minute feed to 1) and, for a per-minute block, its length from
    /// axis words each up to one written unit off. 0 past the end.
    pub fn time_uncertainty(&self, i: usize) -> f64 {
        self.rel_dt.get(i).copied().unwrap_or(0.0)
    }

    /// The program's axes, in the order of every value.
    pub fn axes(&self) -> &[AxisSpec] {
        &self.axes
    }

    /// The number of blocks.
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// Whether the program has no block.
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }

    /// The program's time, s.
    pub fn duration_s(&self) -> f64 {
        self.starts.last().copied().unwrap_or(0.0)
    }

    /// Block `i`, or `None` past the end.
    pub fn block(&self, i: usize) -> Option<BlockSpan<'_>> {
        let w = self.axes.len();
        let kind = *self.kinds.get(i)?;
        Some(BlockSpan {
            index: i,
            line: self.lines[i],
            kind,
            dwell: self.dwells[i],
            start_s: self.starts[i],
            duration_s: self.starts[i + 1] - self.starts[i],
            from: &self.points[i * w..(i + 1) * w],
            to: &self.points[(i + 1) * w..(i + 2) * w],
        })
    }

    /// Every block in order.
    pub fn blocks(&self) -> impl Iterator<Item = BlockSpan<'_>> {
        (0..self.len()).filter_map(|i| self.block(i))
    }

    /// The block running at `t` (s): the last block starting at or before
    /// `t` (times before 0 give the first block, past the end the last);
    /// `None` for an empty program.
    pub fn block_at(&self, t: f64) -> Option<usize> {
        let n = self.len();
        if n == 0 {
            return None;
        }
        let k = self.starts[..n].partition_point(|s| *s <= t);
        Some(k.saturating_sub(1))
    }

    /// The axis values at `t` (s), linear within each block; before 0 the
    /// start point, past the end the last block's end.
    pub fn sample(&self, t: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.axes.len()];
        self.sample_into(t, &mut out);
        out
    }

    /// [`Timeline::sample`] into `out` (one value per axis).
    pub fn sample_into(&self, t: f64, out: &mut [f64]) {
        let w = self.axes.len();
        let Some(i) = self.block_at(t) else {
            out.copy_from_slice(&self.points[..w]);
            return;
        };
        let (s, e) = (self.starts[i], self.starts[i + 1]);
        let f = if t <= s {
            0.0
        } else if t >= e {
            1.0
        } else {
            (t - s) / (e - s)
        };
        let from = &self.points[i * w..(i + 1) * w];
        let to = &self.points[(i + 1) * w..(i + 2) * w];
        for ((o, p), q) in out.iter_mut().zip(from).zip(to) {
            *o = p + f * (q - p);
        }
    }

    /// The machine at `t`: every link's pose and key point by forward
    /// kinematics of the axis values there (`machine`'s axes in the
    /// program's order, as [`crate::program_axes`] makes them).
    pub fn poses_at(&self, machine: &Machine, t: f64) -> Poses {
        let axes = self.sample(t);
        let q: Vec<f64> = machine
            .axes
            .iter()
            .zip(&axes)
            .map(|(a, v)| {
                if a.kind == JointKind::Revolute {
                    v.to_radians()
                } else {
                    *v
                }
            })
            .collect();
        let links = machine.poses(&q);
        let points = machine
            .points
            .iter()
            .map(|p| links[p.link] * p.position)
            .collect();
        Poses {
            time_s: t,
            block: self.block_at(t),
            axes,
            links,
            points,
        }
    }
}

/// Appends a dwell of `seconds` at time `t`: the axes stay where the last
/// block ended.
fn dwell_block(points: &mut Vec<f64>, w: usize, starts: &mut Vec<f64>, t: &mut f64, seconds: f64) {
    let at = points.len() - w;
    points.extend_from_within(at..at + w);
    starts.push(*t);
    *t += seconds;
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use formcam_nc::Block;

    #[test]
    fn sample_and_block_at_follow_the_blocks() {
        let mut p = Program::new("T", vec![AxisSpec::linear("X"), AxisSpec::rotary("A")]);
        p.blocks.push(Block::rapid(vec![10.0, 0.0]));
        p.blocks
            .push(Block::linear(vec![20.0, 90.0], Feed::InverseTime(2.0)));
        p.blocks
            .push(Block::linear(vec![20.0, 90.0], Feed::PerMinute(100.0)));
        p.blocks
            .push(Block::linear(vec![20.0, 180.0], Feed::PerMinute(900.0)));
        let tl = Timeline::from_start(&p, &[1, 2, 3, 4], FeedRule::Iso, &[0.0, 0.0], &[5.0, 1.0])
            .unwrap();
        // Rapid: 10 mm at 5 mm/s; 2 s; nothing moves; 90° at 900°/min.
        let d: Vec<f64> = tl.blocks().map(|b| b.duration_s).collect();
        assert_eq!(d, [2.0, 2.0, 0.0, 6.0]);
        assert_eq!(tl.duration_s(), 10.0);
        assert_eq!(tl.block_at(-1.0), Some(0));
        assert_eq!(tl.block_at(3.0), Some(1));
        // The empty block and the next start at 4 s: the later one runs.
        assert_eq!(tl.block_at(4.0), Some(3));
        assert_eq!(tl.block_at(99.0), Some(3));
        assert_eq!(tl.sample(1.0), [5.0, 0.0]);
        assert_eq!(tl.sample(3.0), [15.0, 45.0]);
        assert_eq!(tl.sample(7.0), [20.0, 135.0]);
        assert_eq!(tl.sample(12.0), [20.0, 180.0]);
        assert_eq!(tl.block(1).unwrap().from, [10.0, 0.0]);
    }
}
