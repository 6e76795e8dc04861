//! Modulo rotary axes: the angle a program writes for a spindle kept within
//! [`BOUND_DEG`] (100 turns) everywhere.
//!
//! A program's blocks hold the unwound angle of a modulo axis
//! ([`AxisSpec::modulo`](crate::AxisSpec::modulo)), so that block times and
//! travels stay what they are. Controllers do not hold such angles: Marlin
//! keeps positions in 32-bit floats (0.03° steps at 3·10⁵°), others have
//! display and range limits. So the writers print a modulo axis in one of two
//! ways ([`ModuloStyle::of`] a dialect):
//!
//! * [`ModuloStyle::Rezero`] (ISO, Marlin X/A/B, CLDATA): before a block
//!   marked [`Block::rezero`] the axis is re-zeroed to its angle within the
//!   turn, `G92 A<v>` with `0 <= v < 360` (CLDATA: `ORIGIN/A,<o>`, the `GOTO`
//!   values after it measured from `o`, a whole number of turns); every value
//!   written is the unwound angle less the whole turns of the last re-zero.
//! * [`ModuloStyle::Modulo`] (Sinumerik 840D, LinuxCNC): the controller holds
//!   the axis modulo 360° and every block names the angle within the turn and
//!   the direction: 840D `A=ACP(v)` / `A=ACN(v)` (the axis configured as a
//!   modulo rotary axis, MD30310 `ROT_IS_MODULO`); LinuxCNC `A v` / `A-v`
//!   (the axis configured `WRAPPED_ROTARY = 1` in the INI file: the interpreter
//!   goes to `|v|` in the direction of the sign). A block must then turn the
//!   axis by less than one turn.
//!
//! [`keep_within_turns`] prepares a program for a style: it moves the whole
//! program by whole turns so that the first angle lies in `[0, 360)`, splits
//! blocks that turn a modulo axis too far for the style into equal pieces
//! (an inverse-time block's time shared among them, a per-minute feed kept:
//! every block's time is unchanged), and for re-zeroing marks the blocks
//! where an angle would pass the bound. The writers check that a program
//! keeps the bound and refuse it otherwise. The readers take the written
//! forms back to unwound angles (the first one within its first turn).

use crate::num::{self, DEG};
use crate::{Block, Dialect, Feed, NcError, Program, ProgramFault};

/// The largest angle a modulo axis is written with, degrees (100 turns).
pub const BOUND_DEG: f64 = 36_000.0;

/// One turn in printed units (degrees with [`DEG`] decimals).
pub(crate) const TURN: i64 = 360 * 10_000;
/// The bound in printed units.
const BOUND: i64 = 36_000 * 10_000;

/// Blocks a single block may be split into, at most.
const PIECES_MAX: f64 = 1e6;

/// How a dialect keeps a modulo axis within the bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModuloStyle {
    /// Re-zeroed (`G92`, CLDATA `ORIGIN`) between layers and where an angle
    /// would pass the bound.
    Rezero,
    /// Held modulo 360° by the controller; blocks carry a direction.
    Modulo,
}

impl ModuloStyle {
    /// The style of a dialect: modulo for Sinumerik 840D and LinuxCNC,
    /// re-zeroing for the others.
    pub fn of(dialect: Dialect) -> Self {
        match dialect {
            Dialect::Sinumerik840d | Dialect::LinuxCnc => ModuloStyle::Modulo,
            Dialect::Cldata | Dialect::Iso | Dialect::MarlinXab => ModuloStyle::Rezero,
        }
    }

    /// The most one block turns a modulo axis in this style, degrees: less
    /// than a turn for modulo axes, the bound less a turn for re-zeroing (a
    /// re-zeroed block starts within its first turn).
    pub fn max_block_turn_deg(self) -> f64 {
        match self {
            ModuloStyle::Modulo => 359.0,
            ModuloStyle::Rezero => BOUND_DEG - 360.0,
        }
    }
}

/// A value of a modulo axis in printed units; `None` beyond `i64`.
pub(crate) fn scaled(v: f64) -> Option<i64> {
    num::scaled(v, DEG)
}

/// The whole turns below `s` (printed units).
pub(crate) fn turns_below(s: i64) -> i64 {
    turns_below_in(s, TURN)
}

/// The whole turns below `s`, a turn being `turn` printed units (a
/// template's own decimals).
pub(crate) fn turns_below_in(s: i64, turn: i64) -> i64 {
    s.div_euclid(turn) * turn
}

/// The indices of the program's modulo axes.
pub(crate) fn modulo_axes(p: &Program) -> Vec<usize> {
    p.axes
        .iter()
        .enumerate()
        .filter(|(_, a)| a.modulo)
        .map(|(k, _)| k)
        .collect()
}

/// `program` prepared for `style` (see the module documentation): the same
/// motion and block times, every modulo angle writable within the bound.
/// Fails only on angles beyond what the writers can print (about 9·10¹⁴°) or
/// a block that would need more than a million pieces.
pub fn keep_within_turns(program: &Program, style: ModuloStyle) -> Result<Program, NcError> {
    let mut p = program.clone();
    let axes = modulo_axes(&p);
    if axes.is_empty() || p.blocks.is_empty() {
        return Ok(p);
    }
    start_in_first_turn(&mut p, &axes);
    split_long_blocks(&mut p, &axes, style.max_block_turn_deg())?;
    if style == ModuloStyle::Rezero {
        mark_rezeros(&mut p, &axes)?;
    }
    Ok(p)
}

/// Moves every modulo axis by whole turns so that its first angle lies in
/// `[0, 360)`.
fn start_in_first_turn(p: &mut Program, axes: &[usize]) {
    for &k in axes {
        let shift = 360.0 * (p.blocks[0].target[k] / 360.0).floor();
        if shift != 0.0 {
            for b in &mut p.blocks {
                b.target[k] -= shift;
            }
        }
    }
}

/// Splits every block that turns a modulo axis by more than `max_deg` into
/// equal pieces.
fn split_long_blocks(p: &mut Program, axes: &[usize], max_deg: f64) -> Result<(), NcError> {
    let blocks = std::mem::take(&mut p.blocks);
    let mut out: Vec<Block> = Vec::with_capacity(blocks.len());
    for (i, b) in blocks.into_iter().enumerate() {
        let Some(prev) = out.last().map(|q| q.target.clone()) else {
            out.push(b);
            continue;
        };
        let need = axes
            .iter()
            .map(|&k| ((b.target[k] - prev[k]).abs() / max_deg).ceil())
            .fold(1.0, f64::max);
        if need <= 1.0 {
            out.push(b);
            continue;
        }
        if need > PIECES_MAX {
            return Err(ProgramFault::TurnsTooFar {
                block: i,
                turns: PIECES_MAX * max_deg / 360.0,
            }
            .into());
        }
        let n = need as usize;
        for j in 1..=n {
            let target = if j == n {
                b.target.clone()
            } else {
                let f = j as f64 / n as f64;
                prev.iter()
                    .zip(&b.target)
                    .map(|(a, e)| a + (e - a) * f)
                    .collect()
            };
            out.push(Block {
                kind: b.kind,
                target,
                feed: match b.feed {
                    Feed::InverseTime(t) => Feed::InverseTime(t / n as f64),
                    f => f,
                },
                comment: if j == 1 { b.comment.clone() } else { None },
                rezero: j == 1 && b.rezero,
            });
        }
    }
    p.blocks = out;
    Ok(())
}

/// Re-zeroing: marks each block whose angle would pass the bound.
fn mark_rezeros(p: &mut Program, axes: &[usize]) -> Result<(), NcError> {
    let mut off = vec![0i64; axes.len()];
    let mut before: Option<Vec<i64>> = None;
    for i in 0..p.blocks.len() {
        let now = writable(p, i, axes)?;
        if let Some(before) = &before {
            let passes = now.iter().zip(&off).any(|(s, o)| (s - o).abs() > BOUND);
            if p.blocks[i].rezero || passes {
                p.blocks[i].rezero = true;
                for (o, s) in off.iter_mut().zip(before) {
                    *o = turns_below(*s);
                }
            }
        }
        before = Some(now);
    }
    Ok(())
}

/// The modulo angles of block `i` in printed units.
fn writable(p: &Program, i: usize, axes: &[usize]) -> Result<Vec<i64>, NcError> {
    axes.iter()
        .map(|&k| {
            scaled(p.blocks[i].target[k]).ok_or_else(|| {
                NcError::from(ProgramFault::Unwritable {
                    block: i,
                    axis: p.axes[k].name.clone(),
                    angle_deg: p.blocks[i].target[k],
                })
            })
        })
        .collect()
}

/// Checks that `p` can be written in `style` within the bound: every modulo
/// angle printable, re-zeroing: every written angle within the bound;
/// modulo: every block turning less than a turn.
pub(crate) fn check(p: &Program, style: ModuloStyle) -> Result<(), NcError> {
    let axes = modulo_axes(p);
    if axes.is_empty() {
        return Ok(());
    }
    let mut off = vec![0i64; axes.len()];
    let mut before: Option<Vec<i64>> = None;
    for i in 0..p.blocks.len() {
        let now = writable(p, i, &axes)?;
        let name = |j: usize| &p.axes[axes[j]].name;
        match (style, &before) {
            (ModuloStyle::Rezero, prev) => {
                if let (true, Some(prev)) = (p.blocks[i].rezero, prev) {
                    for (o, s) in off.iter_mut().zip(prev) {
                        *o = turns_below(*s);
                    }
                }
                if let Some(j) = (0..axes.len()).find(|&j| (now[j] - off[j]).abs() > BOUND) {
                    return Err(ProgramFault::BeyondBound {
                        block: i,
                        axis: name(j).clone(),
                        bound_deg: BOUND_DEG,
                    }
                    .into());
                }
            }
            (ModuloStyle::Modulo, Some(prev)) => {
                if let Some(j) = (0..axes.len()).find(|&j| (now[j] - prev[j]).abs() >= TURN) {
                    return Err(ProgramFault::WholeTurn {
                        block: i,
                        axis: name(j).clone(),
                    }
                    .into());
                }
            }
            (ModuloStyle::Modulo, None) => {}
        }
        before = Some(now);
    }
    Ok(())
}

/// The re-zero offsets (printed units, per program axis; 0 for the others)
/// in force before block `start`.
pub(crate) fn offsets_before(p: &Program, start: usize) -> Vec<i64> {
    let mut off = vec![0i64; p.axes.len()];
    let axes = modulo_axes(p);
    if axes.is_empty() {
        return off;
    }
    if let Some(j) = (1..start.min(p.blocks.len()))
        .rev()
        .find(|&j| p.blocks[j].rezero)
    {
        for &k in &axes {
            off[k] = scaled(p.blocks[j - 1].target[k]).map_or(0, turns_below);
        }
    }
    off
}

/// The direction of a move of a modulo axis, as the modulo dialects write it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Direction {
    /// Towards larger angles (`ACP`, LinuxCNC: no sign).
    Positive,
    /// Towards smaller angles (`ACN`, LinuxCNC: a minus sign).
    Negative,
    /// The shorter way (`DC`).
    Shortest,
}

/// The unwound angle a modulo controller reaches from `current` when told to
/// go to `v` (taken modulo 360) in direction `dir`; LinuxCNC's rule for
/// wrapped rotary axes (staying put when `v` is where the axis stands).
pub(crate) fn unwrap(current: f64, v: f64, dir: Direction) -> f64 {
    let within = v.rem_euclid(360.0);
    let base = 360.0 * (current / 360.0).floor();
    let mut r = base + within;
    match dir {
        Direction::Positive => {
            if r < current {
                r += 360.0;
            }
        }
        Direction::Negative => {
            if r > current {
                r -= 360.0;
            }
        }
        Direction::Shortest => {
            if r - current > 180.0 {
                r -= 360.0;
            } else if current - r > 180.0 {
                r += 360.0;
            }
        }
    }
    r
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn unwrap_follows_the_direction() {
        assert_eq!(unwrap(350.0, 0.0, Direction::Negative), 0.0);
        assert_eq!(unwrap(0.0, 10.0, Direction::Negative), -350.0);
        assert_eq!(unwrap(-350.0, 0.0, Direction::Positive), 0.0);
        assert_eq!(unwrap(0.0, 0.0, Direction::Negative), 0.0);
        assert_eq!(unwrap(0.0, 350.0, Direction::Negative), -10.0);
        assert_eq!(unwrap(-10.0, 350.0, Direction::Negative), -10.0);
        assert_eq!(unwrap(725.0, 10.0, Direction::Positive), 730.0);
        assert_eq!(unwrap(725.0, 0.0, Direction::Positive), 1080.0);
        assert_eq!(unwrap(725.0, 350.0, Direction::Shortest), 710.0);
    }
}
