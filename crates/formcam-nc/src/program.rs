//! The NC program model: named axes and blocks of absolute axis values.

use std::collections::HashSet;

use crate::{NcError, ProgramFault};

/// One NC axis of a program.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct AxisSpec {
    /// The NC address: `"X"`, `"A"`, `"J1"`.
    pub name: String,
    /// Rotary axis (values in degrees) rather than linear (values in mm).
    pub rotary: bool,
    /// A rotary axis the controller holds within a turn (a winder's spindle):
    /// the program re-zeroes it or writes it modulo 360° with a direction,
    /// per dialect (see [`ModuloStyle`](crate::ModuloStyle)). Block targets still hold its
    /// unwound angle.
    pub modulo: bool,
}

impl AxisSpec {
    /// A linear axis (mm).
    pub fn linear(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            rotary: false,
            modulo: false,
        }
    }

    /// A rotary axis (degrees).
    pub fn rotary(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            rotary: true,
            modulo: false,
        }
    }

    /// A modulo rotary axis (degrees; see [`AxisSpec::modulo`]).
    pub fn rotary_modulo(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            rotary: true,
            modulo: true,
        }
    }
}

/// The kind of motion of a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Motion {
    /// Positioning at the machine's rapid rate (G0).
    Rapid,
    /// Linear interpolation of all axes at the block's feed (G1).
    Linear,
}

/// The feed of a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Feed {
    /// No feed: rapid moves.
    None,
    /// mm/min (deg/min for moves of rotary axes only), as G94.
    PerMinute(f64),
    /// The block's time in seconds, written as G93 `F = 60 / t` (1/min).
    InverseTime(f64),
}

/// One motion block.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Rapid or linear.
    pub kind: Motion,
    /// The end point: one absolute value per program axis, in NC units (mm, degrees).
    pub target: Vec<f64>,
    /// The feed.
    pub feed: Feed,
    /// A comment written with the block.
    pub comment: Option<String>,
    /// The program re-zeroes its modulo axes before this block (a new layer,
    /// or where an angle would pass the bound): the re-zeroing dialects write
    /// it (`G92`, CLDATA `ORIGIN`), the modulo ones need none.
    pub rezero: bool,
}

impl Block {
    /// A rapid move to `target`.
    pub fn rapid(target: Vec<f64>) -> Self {
        Self {
            kind: Motion::Rapid,
            target,
            feed: Feed::None,
            comment: None,
            rezero: false,
        }
    }

    /// A linear move to `target` at `feed`.
    pub fn linear(target: Vec<f64>, feed: Feed) -> Self {
        Self {
            kind: Motion::Linear,
            target,
            feed,
            comment: None,
            rezero: false,
        }
    }

    /// The same block with a comment.
    #[must_use]
    pub fn with_comment(mut self, comment: impl Into<String>) -> Self {
        self.comment = Some(comment.into());
        self
    }
}

/// A dwell (`G4`): the axes stand still for a time between two motion
/// blocks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dwell {
    /// How many motion blocks come before it: it follows
    /// `blocks[blocks_before - 1]` (0: before the first).
    pub blocks_before: usize,
    /// How long the axes stand, s.
    pub seconds: f64,
    /// Its line in the program text (1-based).
    pub line: usize,
}

/// The working plane (of circular interpolation and tool compensation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Plane {
    /// X-Y (`G17`).
    Xy,
    /// Z-X (`G18`): lathes and grinders with the Z and X axes.
    Zx,
    /// Y-Z (`G19`).
    Yz,
}

impl Plane {
    /// The G code that selects the plane.
    pub fn code(self) -> &'static str {
        match self {
            Plane::Xy => "G17",
            Plane::Zx => "G18",
            Plane::Yz => "G19",
        }
    }
}

/// An NC program: axes, header comments and motion blocks.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Program {
    /// The program's name (`PARTNO`, `O0001 (NAME)`, `; PROGRAM NAME`).
    pub name: String,
    /// The axes, in the order of every block's `target`.
    pub axes: Vec<AxisSpec>,
    /// Comments written at the top of the program.
    pub header_comments: Vec<String>,
    /// The motion blocks.
    pub blocks: Vec<Block>,
    /// Dwells (`G4`) read back, in order: the axes stand still between
    /// motion blocks. formcam's writers write none.
    pub dwells: Vec<Dwell>,
    /// The working plane, selected in the heading of the G-code dialects
    /// (`G17`/`G18`/`G19`); `None`: not written.
    pub plane: Option<Plane>,
}

impl Program {
    /// An empty program on `axes`.
    pub fn new(name: impl Into<String>, axes: Vec<AxisSpec>) -> Self {
        Self {
            name: name.into(),
            axes,
            header_comments: Vec::new(),
            blocks: Vec::new(),
            dwells: Vec::new(),
            plane: None,
        }
    }

    /// Checks what every writer relies on: non-empty unique axis names (a
    /// modulo axis rotary), one
    /// finite value per axis in every block, a positive finite feed on every
    /// linear block (per-minute or inverse time) and no feed on rapid blocks.
    pub fn validate(&self) -> Result<(), NcError> {
        check_axes(&self.axes)?;
        let n = self.axes.len();
        for (i, b) in self.blocks.iter().enumerate() {
            if b.target.len() != n {
                return Err(ProgramFault::AxisCount {
                    block: i,
                    values: b.target.len(),
                    axes: n,
                }
                .into());
            }
            if let Some(k) = b.target.iter().position(|v| !v.is_finite()) {
                return Err(ProgramFault::NotFinite {
                    block: i,
                    axis: self.axes[k].name.clone(),
                }
                .into());
            }
            match (b.kind, b.feed) {
                (Motion::Rapid, Feed::None) => {}
                (Motion::Rapid, _) => {
                    return Err(ProgramFault::RapidWithFeed { block: i }.into());
                }
                (Motion::Linear, Feed::None) => {
                    return Err(ProgramFault::LinearWithoutFeed { block: i }.into());
                }
                (Motion::Linear, Feed::PerMinute(f) | Feed::InverseTime(f)) => {
                    if !(f.is_finite() && f > 0.0) {
                        return Err(ProgramFault::FeedNotPositive { block: i, value: f }.into());
                    }
                }
            }
        }
        Ok(())
    }

    /// The time of block `index` in seconds, where it is known: the block time
    /// of an inverse-time block; for a per-minute block the path length over
    /// the feed, where the path length is the Euclidean travel of the linear
    /// axes, or of the rotary axes when no linear axis moves (the G94
    /// convention). Rapid blocks and the per-minute first block (whose start
    /// is unknown) have no known time.
    pub fn block_time_s(&self, index: usize) -> Option<f64> {
        let b = self.blocks.get(index)?;
        match b.feed {
            Feed::None => None,
            Feed::InverseTime(t) => Some(t),
            Feed::PerMinute(f) => {
                let prev = &self.blocks.get(index.checked_sub(1)?)?.target;
                let travel = feed_travel(&self.axes, prev, &b.target);
                (f > 0.0).then(|| travel / f * 60.0)
            }
        }
    }

    /// The sum of the block times that are known (see [`Program::block_time_s`]);
    /// rapid moves are not counted. `None` when no block time is known.
    pub fn duration_s(&self) -> Option<f64> {
        let mut sum = 0.0;
        let mut any = false;
        for i in 0..self.blocks.len() {
            if let Some(t) = self.block_time_s(i) {
                sum += t;
                any = true;
            }
        }
        any.then_some(sum)
    }
}

/// Axis names non-empty and unique.
pub(crate) fn check_axes(axes: &[AxisSpec]) -> Result<(), NcError> {
    let mut seen = HashSet::new();
    for a in axes {
        if a.name.is_empty() {
            return Err(ProgramFault::EmptyAxisName.into());
        }
        if !seen.insert(a.name.as_str()) {
            return Err(ProgramFault::AxisTwice {
                axis: a.name.clone(),
            }
            .into());
        }
        if a.modulo && !a.rotary {
            return Err(ProgramFault::ModuloNotRotary {
                axis: a.name.clone(),
            }
            .into());
        }
    }
    Ok(())
}

/// The G94 path length between two points: linear axes, or rotary axes when
/// no linear axis moves.
pub(crate) fn feed_travel(axes: &[AxisSpec], from: &[f64], to: &[f64]) -> f64 {
    let (mut lin, mut rot) = (0.0, 0.0);
    for ((a, p), q) in axes.iter().zip(from).zip(to) {
        let d = q - p;
        if a.rotary {
            rot += d * d;
        } else {
            lin += d * d;
        }
    }
    if lin > 0.0 { lin.sqrt() } else { rot.sqrt() }
}

/// The linear-axis travel only (0 when only rotary axes move).
pub(crate) fn linear_travel(axes: &[AxisSpec], from: &[f64], to: &[f64]) -> f64 {
    axes.iter()
        .zip(from)
        .zip(to)
        .filter(|((a, _), _)| !a.rotary)
        .map(|((_, p), q)| (q - p) * (q - p))
        .sum::<f64>()
        .sqrt()
}

/// The Euclidean norm of all axis deltas in NC units (mm and degrees mixed),
/// FiberPath's path length.
pub(crate) fn nc_travel(from: &[f64], to: &[f64]) -> f64 {
    from.iter()
        .zip(to)
        .map(|(p, q)| (q - p) * (q - p))
        .sum::<f64>()
        .sqrt()
}
