//! Motion: axis trajectories cut into NC blocks, and the blocks' times.
//!
//! * [`fit_blocks`] — the fewest straight blocks (greedy farthest reach) that keep
//!   every axis, and optionally the payout point's position, within tolerance.
//! * [`preliminary_times`] — eq. 17: each block as fast as its slowest axis
//!   allows, but no shorter than the controller's least block time `tau`.
//! * [`pairwise`] — eq. 18 (docs/winding.md): neighbouring blocks slowed pair by
//!   pair (`t_i = t*_i / mu_i`) until every velocity jump is within its limit.
//! * [`global`] — the same problem over all blocks at once (convex): by monotone
//!   sweeps when no axis reverses between neighbours (the feasible set then has a
//!   greatest element), otherwise as a second-order-cone program (Clarabel).
//! * [`join_times`] — a sequence of blocks timed in parts (the layers of a
//!   program) re-timed across the joins, from rest to rest, each part's times
//!   kept as caps; [`ramp_pieces`] first cuts the long blocks at the joins so
//!   that the velocity can ramp there in short pieces.
//! * [`with_acceleration`] and [`sequence_with_acceleration`] — the axes'
//!   acceleration limits on top (a circuit as a cycle, a whole program from
//!   rest to rest): blocks slowed until every velocity change ramps within
//!   half of each neighbouring block.

mod acceleration;
mod blocks;
mod error;
mod ramps;
mod times;

pub use acceleration::{
    check_acceleration, check_sequence_acceleration, sequence_with_acceleration, with_acceleration,
};
pub use blocks::{DEFAULT_TOLERANCE_DEG, DEFAULT_TOLERANCE_MM, Deviation, Tolerance, fit_blocks};
pub use error::{MotionError, SetupStage, SolverFault, TrajectoryFault};
pub use ramps::ramp_pieces;
pub use times::{
    AxisLimits, DEFAULT_TAU_S, Timing, check_timing, deltas, global, global_by_cone, join_times,
    pairwise, preliminary_times,
};
