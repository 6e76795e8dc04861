//! What a correction did, as its report states it (serialisable).

use serde::Serialize;

use crate::apply::line_ranges;
use crate::{
    Applied, Grid, Interpolation, Measurements, MillingProgram, Settings, Smoothing, Tool,
};

/// The report of a correction: the program's nodes and what happened to
/// them, the measurements, and the settings used. A correction whose
/// deviations or displacements break `Settings::max_deviation_mm` stops
/// with an error, so every report has passed that check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Nodes of the program (feed and rapid moves).
    pub nodes: usize,
    /// Feed nodes (the ones the correction looks at).
    pub nodes_feed: usize,
    /// Nodes moved.
    pub nodes_corrected: usize,
    /// Nodes beyond the margin, left unchanged.
    pub nodes_outside: usize,
    /// Nodes corrected by extrapolation beyond the measured area.
    pub nodes_extrapolated: usize,
    /// Rapid-move nodes, left unchanged.
    pub nodes_rapid_unchanged: usize,
    /// Nodes with an unknown coordinate, left unchanged.
    pub nodes_unknown: usize,
    /// The program lines of the nodes outside, as ranges (`1-3, 7`).
    pub outside_lines: String,
    /// The largest measured deviation, mm.
    pub max_deviation_mm: f64,
    /// The RMS measured deviation, mm.
    pub rms_deviation_mm: f64,
    /// The largest deviation predicted for the next part, made on the
    /// corrected mould ([`crate::predict_next`]), mm; `None` until
    /// [`Report::predict`].
    pub predicted_max_deviation_mm: Option<f64>,
    /// The RMS deviation predicted for the next part, mm.
    pub predicted_rms_deviation_mm: Option<f64>,
    /// The largest node displacement, mm.
    pub max_displacement_mm: f64,
    /// The RMS displacement over the moved nodes, mm.
    pub rms_displacement_mm: f64,
    /// The interpolation.
    pub interpolation: Interpolation,
    /// The gain.
    pub gain: f64,
    /// The tool.
    pub tool: Tool,
    /// The extrapolation margin, mm.
    pub margin_mm: f64,
    /// Sections of the grid.
    pub sections: usize,
    /// Points per section of the grid.
    pub points_per_section: usize,
    /// Points measured.
    pub measured_points: usize,
    /// Whether the sections were resampled.
    pub resampled: bool,
    /// Whether the sections were put in order.
    pub sections_reordered: bool,
    /// What the smoothing did (absent without a noise level).
    pub smoothing: Option<Smoothing>,
    /// `iso`, `sinumerik`, `linuxcnc` or `csv`.
    pub program_syntax: String,
    /// Arc blocks written back as chords.
    pub arcs_linearised: usize,
    /// Their chord tolerance, mm.
    pub arc_tolerance_mm: f64,
    /// Feed moves split.
    pub moves_split: usize,
    /// The longest piece of a split move, mm.
    pub max_segment_mm: Option<f64>,
}

impl Report {
    /// The report of `applied`, the correction of `program` from
    /// `measurements` over `grid` (after `smoothing`) with `settings`.
    pub fn new(
        measurements: &Measurements,
        grid: &Grid,
        smoothing: Option<Smoothing>,
        program: &MillingProgram,
        applied: &Applied,
        settings: &Settings,
    ) -> Self {
        let t = &applied.totals;
        let o = &settings.options;
        Self {
            nodes: applied.positions.len(),
            nodes_feed: t.nodes,
            nodes_corrected: t.corrected,
            nodes_outside: t.outside,
            nodes_extrapolated: t.extrapolated,
            nodes_rapid_unchanged: applied.positions.len() - applied.nodes.len(),
            nodes_unknown: t.unknown,
            outside_lines: line_ranges(&applied.outside_lines),
            max_deviation_mm: measurements.max_deviation(),
            rms_deviation_mm: measurements.rms_deviation(),
            predicted_max_deviation_mm: None,
            predicted_rms_deviation_mm: None,
            max_displacement_mm: t.max_displacement_mm,
            rms_displacement_mm: t.rms_displacement_mm,
            interpolation: o.interpolation,
            gain: o.gain,
            tool: o.tool,
            margin_mm: o.margin_mm,
            sections: grid.nv,
            points_per_section: grid.nu,
            measured_points: measurements.len(),
            resampled: grid.resampled,
            sections_reordered: grid.reordered,
            smoothing,
            program_syntax: program.syntax(),
            arcs_linearised: program.arcs_linearised(),
            arc_tolerance_mm: settings.arc_tolerance_mm,
            moves_split: program.moves_split(),
            max_segment_mm: settings.max_segment_mm,
        }
    }

    /// Adds the deviations of `predicted`, the next part's measurements
    /// [`crate::predict_next`] foresees.
    pub fn predict(&mut self, predicted: &Measurements) {
        self.predicted_max_deviation_mm = Some(predicted.max_deviation());
        self.predicted_rms_deviation_mm = Some(predicted.rms_deviation());
    }
}
