//! The NC blocks of a winding program: each layer's axes cut into blocks
//! within the tolerances and timed, skip layers' turns, and the whole
//! program joined from rest to rest with its joins ramped and re-timed.
//!
//! `layer` cuts and times a layer ([`layer_blocks`], `skip_blocks`),
//! `assemble` lays the layers one after another into the program, `ramps`
//! cuts the blocks round each join and checks the program from rest to rest.

mod assemble;
mod layer;
mod ramps;

use formcam_machine::Machine;
use formcam_motion::AxisLimits;
use formcam_nc::Program;

use crate::ProgramError;
use crate::checks::{Check, Violated};
use crate::job::MotionJob;

pub use assemble::assemble;
pub use layer::{LayerBlocks, layer_blocks, skip_blocks};

/// The whole program, timed: the NC program (before the post), its blocks
/// as `blocks.csv` lists them, its times and the checks it failed.
#[derive(Debug, Clone, PartialEq)]
pub struct Assembled {
    /// The NC program (blocks with inverse-time feeds, header comments).
    pub program: Program,
    /// Every block after the first rapid, with its time.
    pub blocks: Vec<TimedBlock>,
    /// How many layers the program holds.
    pub layers: usize,
    /// The program's time with the chosen block times, s.
    pub time_s: f64,
    /// ... with the pairwise block times (the joins alike), s.
    pub time_pairwise_s: f64,
    /// ... with the global block times (the joins alike), s.
    pub time_global_s: f64,
    /// ... with the preliminary block times (eq. 17) and the moves between
    /// layers, s.
    pub time_preliminary_s: f64,
    /// The checks the whole program failed, its layers' and its own (the
    /// joins' timing): the program is written only when the job accepts them.
    pub violated: Vec<Violated>,
    /// The failed checks, each once, in [`Check`] order.
    pub accepted: Vec<Check>,
}

/// A block of the program as `blocks.csv` lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct TimedBlock {
    /// The axes at the block's end, NC units.
    pub target: Vec<f64>,
    /// The block's time, s.
    pub t: f64,
    /// The layer the block belongs to (or leads into), 1-based.
    pub layer: usize,
    /// The block's least time (eq. 17), s.
    pub t_star: f64,
}

/// `value` if finite and > 0, else the error naming `field`.
pub(super) fn positive(field: &'static str, value: f64) -> Result<f64, ProgramError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ProgramError::NotPositive { field, value })
    }
}

/// Axis values in NC units: mm, and degrees for rotary axes.
pub fn nc(m: &Machine, a: usize, v: f64) -> f64 {
    if m.axes[a].is_rotary() {
        v.to_degrees()
    } else {
        v
    }
}

/// How far below each axis's `a_max` the planner keeps its velocity changes
/// (relative): the written program's block times differ from the planned
/// ones by the rounding of `F` and of the axis words, which the check of
/// the written text (`formcam check`) allows in the velocities but not in
/// the time an acceleration has: 0.1 % covers a `G93` block of up to two
/// minutes (`F = 60 / t` to 3 decimals) and a per-minute block (Marlin,
/// CLDATA) whose travel is at least a millimetre.
pub const ACCELERATION_MARGIN: f64 = 1e-3;

/// Whether the job's block times keep the axes' acceleration limits: unless
/// `[motion] acceleration = false`.
pub fn keeps_acceleration(motion: &MotionJob) -> bool {
    motion.acceleration.unwrap_or(true)
}

/// Each axis's acceleration limit as the planner keeps it (internal units
/// per s², `inf` where the machine gives none): `a_max` less
/// [`ACCELERATION_MARGIN`].
pub fn planned_a_max(m: &Machine) -> Vec<f64> {
    m.axes
        .iter()
        .map(|a| a.a_max * (1.0 - ACCELERATION_MARGIN))
        .collect()
}

/// The machine's axis limits for the block times.
pub fn axis_limits(m: &Machine) -> Vec<AxisLimits> {
    m.axes
        .iter()
        .map(|a| AxisLimits {
            v_max: a.v_max,
            dv_max: a.dv_max,
        })
        .collect()
}
