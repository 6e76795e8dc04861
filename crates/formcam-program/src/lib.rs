//! The wound program: a winding job planned layer by layer, moved to the
//! machine's axes, cut into timed NC blocks and written by a post-processor.
//!
//! [`WindJob`] is the whole job (read from TOML by [`WindJob::from_toml`] or
//! from a Cyclone/FiberPath `.wind` document by [`WindJob::from_wind`]);
//! [`plan_program`] (or [`plan_until`] a [`Stage`]) runs the one pipeline —
//! layers, payout eye, axes, blocks and times, the checks — into a
//! [`WoundProgram`], which [`write_program`] writes with the job's post.

mod blocks;
pub mod checks;
mod error;
mod job;
mod mandrel_check;
mod plan;
mod post;
mod size;
mod targets;
mod windfile;

pub use blocks::{
    ACCELERATION_MARGIN, Assembled, LayerBlocks, TimedBlock, axis_limits, keeps_acceleration, nc,
    planned_a_max,
};
pub use checks::{Check, ChecksJob, Violated};
pub use error::{JobFileError, ProgramError, WindFileError, in_layer};
pub use job::{
    Ik, JobMachine, Layers, MachineSource, MotionJob, Post, Times, WINDING_JOB, WindImport, WindJob,
};
pub use mandrel_check::{
    MandrelCheckBuilder, free_fibre, is_wind_file, laminate, laminate_of_job, mandrel_check,
    mandrel_check_of_file, read_job, read_job_from, wound_circuit,
};
pub use plan::{
    LayerBody, Stage, Wound, WoundLayer, WoundProgram, plan_each, plan_program, plan_until,
    plan_until_with,
};
pub use post::write_program;
pub use size::{LAYER_BATCH, ProgramSize, estimate};
pub use targets::{placement_targets, winder_targets};
pub use windfile::{EYE_CLEARANCE_MM, SPEC_VERSION};
