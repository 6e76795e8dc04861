//! The timeline the page draws: the program read back from its text, each
//! block's start and time from its own feeds, the axes interpolated within a
//! block, and every link's world pose and key point by forward kinematics.
//!
//! One module on purpose: the simulator's timeline replaces this builder
//! later; what the page receives ([`Sample`], [`TimelineHead`]) stays.

use formcam_machine::{JointKind, Machine};
use formcam_nc::{AxisSpec, Dialect, Program, read_cldata, read_gcode_in};
use nalgebra::Isometry3;
use serde::Serialize;

use crate::ViewError;

/// The program on the machine, block by block.
#[derive(Debug, Clone)]
pub struct Timeline {
    machine: Machine,
    /// Per block: start time, s.
    starts: Vec<f64>,
    /// Per block: end time, s.
    ends: Vec<f64>,
    /// Per block: the axes at its end as the program writes them (degrees,
    /// mm; the machine's order).
    targets: Vec<Vec<f64>>,
    /// Per block: its line in the program (1-based; 0 when unknown).
    lines: Vec<usize>,
}

/// The state at one time: what the page shows.
#[derive(Debug, Clone, PartialEq, Serialize)]
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
#[derive(Debug, Clone, PartialEq, Serialize)]
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
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisHead {
    /// NC address.
    pub name: String,
    /// `deg` or `mm`.
    pub unit: &'static str,
}

impl Timeline {
    /// Reads `text` (written in `dialect` for `machine`) back into timed blocks.
    ///
    /// # Errors
    ///
    /// The reader's error (with the line), or a program without blocks,
    /// named `path` (the program file).
    pub fn from_program(
        machine: Machine,
        text: &str,
        dialect: Dialect,
        path: &std::path::Path,
    ) -> Result<Self, ViewError> {
        let specs = axis_specs(&machine);
        let program = match dialect {
            Dialect::Cldata => read_cldata(text, &specs),
            d => read_gcode_in(text, &specs, d),
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
        let (starts, ends) = block_times(&program);
        let targets = program.blocks.iter().map(|b| b.target.clone()).collect();
        let mut lines = block_lines(text, &specs, dialect);
        if lines.len() != program.blocks.len() {
            lines = vec![0; program.blocks.len()];
        }
        Ok(Self {
            machine,
            starts,
            ends,
            targets,
            lines,
        })
    }

    /// The program's time, s.
    pub fn duration_s(&self) -> f64 {
        self.ends.last().copied().unwrap_or(0.0)
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
            blocks: self.targets.len(),
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

    /// The state at `t` s (clamped to the program): the block running, the
    /// axes interpolated linearly within it, the poses and key points.
    pub fn sample(&self, t: f64) -> Sample {
        let t = if t.is_finite() {
            t.clamp(0.0, self.duration_s())
        } else {
            0.0
        };
        let block = self
            .ends
            .partition_point(|&e| e < t)
            .min(self.targets.len() - 1);
        let to = &self.targets[block];
        let from = &self.targets[block.saturating_sub(1)];
        let span = self.ends[block] - self.starts[block];
        let f = if span > 0.0 {
            ((t - self.starts[block]) / span).clamp(0.0, 1.0)
        } else {
            1.0
        };
        // Exactly the block's ends at f = 0 and f = 1.
        let nc: Vec<f64> = from
            .iter()
            .zip(to)
            .map(|(a, b)| a * (1.0 - f) + b * f)
            .collect();
        let q: Vec<f64> = nc
            .iter()
            .zip(&self.machine.axes)
            .map(|(v, a)| if a.is_rotary() { v.to_radians() } else { *v })
            .collect();
        let poses = self.machine.poses(&q);
        Sample {
            t,
            block,
            line: self.lines[block],
            axes: nc,
            poses: poses.iter().map(pose).collect(),
            points: self
                .machine
                .points
                .iter()
                .map(|p| {
                    let w = poses[p.link] * p.position;
                    [w.x, w.y, w.z]
                })
                .collect(),
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

    /// Per block: its line in the program text (1-based; 0 when unknown).
    pub fn lines(&self) -> &[usize] {
        &self.lines
    }

    /// Per block: start and end time, s.
    pub fn block_span(&self, block: usize) -> Option<(f64, f64)> {
        Some((*self.starts.get(block)?, *self.ends.get(block)?))
    }
}

/// The program axes of a machine: rotary in degrees (modulo where the
/// controller holds them within a turn), linear in mm.
pub fn axis_specs(machine: &Machine) -> Vec<AxisSpec> {
    machine
        .axes
        .iter()
        .map(|a| match (a.is_rotary(), a.modulo) {
            (true, true) => AxisSpec::rotary_modulo(a.name.clone()),
            (true, false) => AxisSpec::rotary(a.name.clone()),
            (false, _) => AxisSpec::linear(a.name.clone()),
        })
        .collect()
}

/// Each block's start and end from the program's feeds; a block whose time
/// is unknown (a rapid move, a first per-minute block) takes none.
fn block_times(program: &Program) -> (Vec<f64>, Vec<f64>) {
    let mut starts = Vec::with_capacity(program.blocks.len());
    let mut ends = Vec::with_capacity(program.blocks.len());
    let mut t = 0.0;
    for i in 0..program.blocks.len() {
        starts.push(t);
        t += program.block_time_s(i).unwrap_or(0.0);
        ends.push(t);
    }
    (starts, ends)
}

fn pose(p: &Isometry3<f64>) -> [f64; 7] {
    let v = p.translation.vector;
    let q = p.rotation.quaternion();
    [v.x, v.y, v.z, q.i, q.j, q.k, q.w]
}

/// The lines of the motion blocks (1-based): for CLDATA the `GOTO`
/// records; for G-code the lines with an axis word that are no `G92`
/// preset, comments left out — the reader's rule for a block.
pub fn block_lines(text: &str, axes: &[AxisSpec], dialect: Dialect) -> Vec<usize> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let is_block = if dialect == Dialect::Cldata {
            line.trim_start().to_ascii_uppercase().starts_with("GOTO")
        } else {
            gcode_block(&strip_comments(line).to_ascii_uppercase(), axes)
        };
        if is_block {
            out.push(i + 1);
        }
    }
    out
}

/// A G-code line without its `;` and `( )` comments.
fn strip_comments(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut depth = 0usize;
    for c in line.chars() {
        match c {
            ';' if depth == 0 => break,
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

/// A word of a G-code line.
enum Word<'a> {
    /// A letter and its number's text.
    Letter(char, &'a str),
    /// A Sinumerik assignment `NAME=value`: the name.
    Assign(&'a str),
}

/// Whether an upper-case G-code line (no comments) moves an axis.
fn gcode_block(line: &str, axes: &[AxisSpec]) -> bool {
    let words = words(line);
    let code =
        |w: &Word, n: &str| matches!(w, Word::Letter('G', v) if v.trim_start_matches('0') == n);
    if words.iter().any(|w| code(w, "92")) {
        return false;
    }
    // Arguments of a dwell, an M code or a T word are no axis words.
    let mut skipped = false;
    for w in &words {
        match w {
            Word::Letter('G', _) => skipped = code(w, "4"),
            Word::Letter('M' | 'T', _) => skipped = true,
            Word::Letter('N' | 'O' | 'F', _) => {}
            Word::Letter(letter, _) if !skipped => {
                if axes
                    .iter()
                    .any(|a| a.name.len() == 1 && a.name.eq_ignore_ascii_case(&letter.to_string()))
                {
                    return true;
                }
            }
            Word::Assign(name) => {
                if axes.iter().any(|a| a.name.eq_ignore_ascii_case(name)) {
                    return true;
                }
            }
            Word::Letter(..) => {}
        }
    }
    false
}

/// A line's words: whitespace-separated tokens, each an assignment
/// (`NAME=value`) or letters each followed by a number.
fn words(line: &str) -> Vec<Word<'_>> {
    let mut out = Vec::new();
    for token in line.split_whitespace() {
        if let Some((name, _)) = token.split_once('=') {
            out.push(Word::Assign(name));
            continue;
        }
        let mut rest = token;
        while let Some(c) = rest.chars().next() {
            let body = &rest[c.len_utf8()..];
            let end = body
                .find(|ch: char| ch.is_ascii_alphabetic())
                .unwrap_or(body.len());
            if c.is_ascii_alphabetic() {
                out.push(Word::Letter(c, &body[..end]));
            }
            rest = &body[end..];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use formcam_nc::{Block, Feed, write};

    fn program() -> Program {
        let axes = vec![
            AxisSpec::rotary_modulo("A"),
            AxisSpec::linear("X"),
            AxisSpec::linear("Y"),
            AxisSpec::rotary("B"),
        ];
        let mut p = Program::new("LINES", axes);
        p.header_comments.push("a header X1 Y2 comment".into());
        p.blocks.push(Block::rapid(vec![0.0, 0.0, 100.0, 0.0]));
        for i in 1..40 {
            let v = f64::from(i);
            // Past a turn: the modulo dialects write the spindle within one.
            p.blocks.push(
                Block::linear(
                    vec![v * 100.0, v, 100.0 + v, v / 10.0],
                    Feed::InverseTime(0.5),
                )
                .with_comment(format!("block X{i}")),
            );
        }
        p
    }

    #[test]
    fn every_dialect_has_one_line_per_block_read_back() {
        let p = program();
        for d in Dialect::ALL {
            let mut text = String::new();
            write(&p, d, &mut text).unwrap();
            let read = match d {
                Dialect::Cldata => read_cldata(&text, &p.axes),
                d => read_gcode_in(&text, &p.axes, d),
            }
            .unwrap();
            let lines = block_lines(&text, &p.axes, d);
            assert_eq!(lines.len(), read.blocks.len(), "{d:?}\n{text}");
            let all: Vec<&str> = text.lines().collect();
            for (k, &l) in lines.iter().enumerate() {
                let line = all[l - 1];
                // The block's X value stands on its line.
                let x = read.blocks[k].target[1];
                assert!(
                    line.contains(&format!("{x}")) || (x == 0.0 && line.contains('0')),
                    "{d:?} block {k}: {line}"
                );
            }
        }
    }
}
