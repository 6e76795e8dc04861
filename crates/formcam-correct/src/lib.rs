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
//! * [`NodeTable`] — a tool path given as a CSV of nodes.

mod correct;
mod error;
mod grid;
mod measure;
mod nodes;
mod patch;
pub mod simulate;
mod smooth;
mod vec3;

pub use correct::{
    Corrector, EDGE_TOLERANCE_MM, NodeCorrection, Options, Placement, Tool, Totals,
    check_displacement,
};
pub use error::CorrectError;
pub use grid::Grid;
pub use measure::{MeasuredPoint, Measurements, Section};
pub use nodes::NodeTable;
pub use patch::{Interpolation, Surface};
pub use smooth::{Smoothing, smooth};
