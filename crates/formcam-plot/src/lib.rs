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
#[error("{file}: {fault}")]
pub struct PlotError {
    /// The SVG file being drawn.
    pub file: String,
    /// What went wrong.
    pub fault: PlotFault,
}

/// Why plotters could not draw.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlotFault {
    /// The backend could not write (the SVG backend writes to a string).
    #[error("backend error: {0}")]
    Backend(std::io::ErrorKind),
    /// A text could not be laid out in its font.
    #[error("backend error: font error")]
    Font,
    /// The drawing area was in use by another drawing.
    #[error("Multiple backend operation in progress")]
    Sharing,
    /// A layout that does not fit.
    #[error("Bad layout")]
    Layout,
}

impl<E> From<plotters::drawing::DrawingAreaErrorKind<E>> for PlotFault
where
    E: std::error::Error + Send + Sync + 'static,
{
    fn from(e: plotters::drawing::DrawingAreaErrorKind<E>) -> Self {
        use plotters::drawing::DrawingAreaErrorKind as Area;
        use plotters_backend::DrawingErrorKind as Drawing;
        match e {
            Area::BackendError(Drawing::DrawingError(e)) => PlotFault::Backend(
                (&e as &dyn std::error::Error)
                    .downcast_ref::<std::io::Error>()
                    .map_or(std::io::ErrorKind::Other, std::io::Error::kind),
            ),
            Area::BackendError(Drawing::FontError(_)) => PlotFault::Font,
            Area::SharingError => PlotFault::Sharing,
            Area::LayoutError => PlotFault::Layout,
        }
    }
}
