//! The virtual machine of formcam: any program formcam writes, read back as
//! text and played on a machine model.
//!
//! * [`FeedRule`] — how each controller turns a per-minute `F` into a block
//!   time when linear and rotary axes move together (LinuxCNC, Sinumerik
//!   840D, ISO, Marlin, CLDATA).
//! * [`Timeline`] — per block its program line, start time, duration and
//!   axis values at both ends, from the program's own feeds (inverse time
//!   `60 / F`, per minute by the dialect's rule, rapids at the machine's
//!   velocity limits); [`Timeline::sample`], [`Timeline::block_at`] and
//!   [`Timeline::poses_at`] (every link and key point by forward kinematics)
//!   at any time. Later checks (collisions, the free band) and the viewer
//!   sample the same timeline.
//! * [`check_timeline`] — the axis checks: position limits, velocity,
//!   velocity jump and acceleration per axis, each a [`Violation`] with the
//!   block, line and time where it first happens and where it is worst.
//! * [`Collisions`] — every pair of solids that can meet (the links'
//!   solids, the bed, the mandrel grown by the laminate laid so far) kept
//!   the machine's clearance margin apart: a broad phase, then the exact
//!   distance with parry3d; each pair too close a [`Violation`] of kind
//!   [`ViolationKind::Collision`] naming both links.
//! * [`FreeFibre`] — where the free fibre is at each time of a winding
//!   program: the payout point by forward kinematics, the contact point on
//!   the mandrel from the planned circuits the planner hands on
//!   ([`WoundCircuit`]), by the spindle's angle; [`check_snag`] — the fibre
//!   must not cut the mandrel nor come near a machine solid
//!   ([`SnagOptions`]).
//! * [`MandrelCheck`] — what a winding job adds to a check: its
//!   [`Laminate`] and its [`FreeFibre`], made by the planner (the simulator
//!   never plans a job; it depends on no crate above it).
//! * [`check_file`] — a program file checked on a [`CheckMachine`] (a
//!   machine file or a shipped name) to a [`Report`] and its one line;
//!   [`check_text_with`] the same check of a program text in memory.

mod collision;
mod error;
mod feed;
mod fibre;
mod limits;
mod mandrel_check;
mod pipeline;
mod report;
mod snag;
mod timeline;

pub use collision::{
    Body, CHORD_TOLERANCE_MM, Collisions, Laminate, Mount, Pair, SIDES, exempt, machine_bodies,
    revolution_solid, visual_shape,
};
pub use error::SimError;
pub use feed::FeedRule;
pub use fibre::{FibreLayer, FibreSampler, FibreState, FibreTrack, FreeFibre, WoundCircuit};
pub use limits::{
    AxisLimits, DISTANCE_TOLERANCE_MM, RELATIVE_TOLERANCE, RESOLUTION_DEG, RESOLUTION_MM,
    Violation, ViolationKind, check_timeline,
};
pub use mandrel_check::MandrelCheck;
pub use pipeline::{
    CheckMachine, CheckRun, check_file, check_files, check_text, check_text_in, check_text_with,
    program_axes, read_program,
};
pub use report::Report;
pub use snag::{SnagOptions, check_snag, check_snag_exhaustive};
pub use timeline::{BlockSpan, Poses, Timeline};
