//! Correction of a mould's milling program from CMM measurements of the
//! moulded part (docs/correction.md).
//!
//! * [`Measurements`] — the CMM report: nominal and actual points per
//!   control section, from CSV or the point features of a DMIS file.
//! * [`Grid`] — the sections harmonised into corresponding points (resampled
//!   by arc length where needed): a grid of quadrilateral facets.
//! * [`Surface`] — patches over the facets, bilinear Coons (eq. 1) or bicubic
//!   Hermite ([`Interpolation`]), for the nominal surface and the deviation.
//! * [`smooth`] — separates measurement noise of a stated level from the
//!   deterministic warp (a penalised fit, its weight by the discrepancy
//!   principle).
//! * [`Corrector`] — for each node: the nearest facet by a k-d tree over
//!   facet centres and a walk to neighbours, the foot of the normal by
//!   Newton's method, the interpolated deviation, and the displacement
//!   `-gain * D(s, t)` ([`Tool`]: point or ball-end).
//! * [`simulate`] — the closed-loop check: mill, mould with a warp, measure,
//!   correct, again.
//! * [`predict_next`] — what the CMM would read of the next part, made on
//!   the corrected mould (the closed loop's model: the part follows the
//!   mould).
//! * [`NodeTable`] — a tool path given as a CSV of nodes.
//! * [`MillingProgram`] and [`Corrector::apply`] — a whole program
//!   corrected and written back; [`correct_program`] — the pipeline from a
//!   CMM report to the corrected program and its [`Report`].
//! * [`CorrectionJob`] — the `[correct]` job file; [`ScenarioJob`] — the
//!   closed-loop scenario file.

mod apply;
mod correct;
mod error;
mod grid;
mod job;
mod measure;
mod nodes;
mod patch;
mod pipeline;
mod predict;
mod program;
mod report;
mod scenario;
pub mod simulate;
mod smooth;
mod vec3;

pub use apply::{Applied, NODE_STATUS_FILE, line_ranges};
pub use correct::{
    Corrector, DEFAULT_GAIN, EDGE_TOLERANCE_MM, GAIN_RANGE, MARGIN_RANGE, NodeCorrection, Options,
    Placement, Tool, Totals, check_displacement,
};
pub use error::{
    CorrectError, Given, MeasureError, MeasureProblem, ProgramError, Rule, ScenarioError,
    SectionsError,
};
pub use grid::Grid;
pub use job::{
    CORRECT, CORRECT_JOB, CorrectionJob, DEFAULT_ARC_TOLERANCE_MM, DEFAULT_MAX_DEVIATION_MM,
    INTERPOLATIONS, JobField, MILLING_DIALECTS, Settings,
};
pub use measure::{MeasuredPoint, Measurements, Section};
pub use nodes::NodeTable;
pub use patch::{Interpolation, Surface};
pub use pipeline::{Correction, correct_program, correct_program_with};
pub use predict::{PREDICTED_FILE, predict_next};
pub use program::MillingProgram;
pub use report::Report;
pub use scenario::{CMM, LOOP, PROGRAM, SCENARIO_JOB, SURFACE, ScenarioField, ScenarioJob, WARP};
pub use smooth::{Smoothing, smooth};
