//! SVG plots of formcam results.
//!
//! `panels_svg` stacks panels of line series in one document with readable
//! tick labels; the process modules draw each process's plots with it
//! (`winding`: the layer and the eye; `correction`: deviations,
//! displacement, the closed loop's convergence).

mod correction;
mod dressing;
mod panels;
mod winding;

pub use correction::{convergence_svg, deviations_svg, displacement_svg};
pub use dressing::{mrr_svg, profile_svg};
pub use panels::{Panel, Series, panels_svg, range, svg_err, tick_label};
pub use winding::{eye_svg, layer_svg};

/// A plot that could not be drawn, naming the file it was for.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}: {message}")]
pub struct PlotError {
    /// The SVG file being drawn.
    pub file: String,
    /// What went wrong.
    pub message: String,
}
