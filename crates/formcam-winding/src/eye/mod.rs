//! The payout-eye trajectory (eqs. 7–11, docs/winding.md) and the pull-speed
//! optimisation (eqs. 12–15).
//!
//! For a path point with tangent `tau` (eq. 8–9) the eye lies at `P + l tau`;
//! its cylindrical coordinates are eq. 10. A trajectory is a free length `l(x)`
//! over the circuit's parameter `x` (the laid band length, see
//! [`Circuit`](crate::Circuit)).
//!
//! * `axis-parallel`: `R(l) = R_eye`, solved in closed form;
//! * `equidistant`: the eye keeps `clearance` from the mandrel — on the upper
//!   envelope of the discs of that radius centred on the meridian (and on the
//!   shaft through the polar openings), which near a small opening is a circle
//!   round the opening's edge, not an offset dome;
//! * `curve`: a user polyline `R = f(Z)`;
//! * `pull-speed`: `l(x)` discretised and chosen lexicographically: max min `u`,
//!   then min max `u`, then min `∫ (u - U)^2 dx` (LP, LP, QP by Clarabel), with
//!   `lambda = l + s - k R`, `u = d lambda / dx`.
//!
//! The constraints (docs/winding.md) are checked for every mode: cyclicity, the
//! clearance (`l >= l_min(x)`, the equidistant length) and `l <= l_max`, no slack
//! (`d(l + s)/dx >= 0`) and no reverse rotation of the mandrel (`dV/dx >= 0`).
//!
//! One module per concept: `band` (eq. 10: the eye on the free band), `envelope`
//! (the clearance zone and where the band leaves it), `geometric` (the
//! axis-parallel, equidistant and curve modes), `checks` (the constraints and
//! the pull-speed statistics), `optimise` (the pull-speed optimum), `trajectory`
//! (the circuit cut into runs and chunks, the trajectory assembled), `spec`
//! (what the user asks).

mod band;
mod checks;
mod envelope;
mod geometric;
mod optimise;
mod spec;
mod trajectory;

pub use band::{axis_parallel_length, eye_at};
pub use checks::{Constraint, PullStats, Violation};
pub(crate) use geometric::curve_fault;
pub use spec::{
    DEFAULT_CLEARANCE_MM, DEFAULT_NODES, DEFAULT_SAMPLES, EyeMode, EyeSpec, NODE_COUNTS,
    SAMPLE_COUNTS,
};
pub use trajectory::{Comparison, EyePoint, EyeTrajectory, eye_trajectory};
