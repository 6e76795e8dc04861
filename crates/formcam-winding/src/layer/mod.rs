//! One layer: the pass, the pattern of circuits and the layer report.
//!
//! [`plan_layer`] reads as its phases, one module each: `spec` (what the layer
//! asks, checked), `method` (`choose_method`), `lay` (`lay_pass`), `far_end`
//! (`check_far_end`), `turn` (`pass_turn`, `circuit_length`), `equator`, the
//! pattern (`choose_pattern`), `thickness`, `summary` (`pass_summary`),
//! `report` (`layer_report`).

mod equator;
mod far_end;
mod lay;
mod method;
mod report;
mod spec;
mod summary;
mod thickness;
mod turn;

use formcam_geom::Meridian;
use serde::Serialize;

use crate::circuit::PassPath;
use crate::pattern::{Pattern, PatternRequest, choose_pattern};
use crate::{PathPoint, WindingError};
use equator::equator;
use far_end::check_far_end;
use lay::lay_pass;
use method::choose_method;
use report::layer_report;
use spec::check_spec;
use summary::pass_summary;
use thickness::thickness;
use turn::{circuit_length, pass_turn};

pub use method::Method;
pub use report::LayerReport;
pub use spec::{Ends, LayerSpec, Slippage, TubeTurn};
pub use summary::PassSummary;

/// A planned layer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Layer {
    /// The pass, sampled.
    #[serde(skip)]
    pub points: Vec<PathPoint>,
    /// Band thickness of the layer at each sample, mm.
    #[serde(skip)]
    pub thickness: Vec<f64>,
    /// The pass.
    pub pass: PassSummary,
    /// The pattern.
    pub pattern: Pattern,
    /// The report.
    pub report: LayerReport,
    /// Things the user should know.
    pub warnings: Vec<String>,
    /// The pass, for evaluation anywhere (the circuit and the eye use it).
    #[serde(skip)]
    pub pass_path: PassPath,
    /// Whether the mandrel is a tube (turn-arounds off the winding zone).
    #[serde(skip)]
    pub tube: bool,
}

/// Plans one layer on mandrel `m`.
pub fn plan_layer<M: Meridian>(m: &M, spec: &LayerSpec) -> Result<Layer, WindingError> {
    check_spec(spec, m.z_range())?;
    let tube = matches!(spec.ends, Ends::Tube { .. });
    let friction = spec.turnaround == TubeTurn::Friction;
    let mut warnings = Vec::new();
    let mut choice = choose_method(m, spec, friction, &mut warnings)?;
    let laid = lay_pass(m, spec, friction, &mut choice, &mut warnings)?;
    let last = *laid
        .points
        .last()
        .ok_or_else(|| WindingError::field("winding.samples", "no points"))?;
    check_far_end(m, spec, friction, laid.end)?;
    let turn = pass_turn(m, spec, &laid, &last);
    let eq = equator(&laid.dense);
    let pattern = choose_pattern(&PatternRequest {
        band_width: spec.band_width,
        overlap: spec.overlap,
        radius: eq.r,
        alpha: eq.alpha,
        natural_turn: 2.0 * turn.total(),
        dwell_min: 2.0 * spec.dwell_min,
        pattern_number: spec.pattern_number,
        skip_index: spec.skip_index,
    })?;
    let circuit_len = circuit_length(m, &laid, &last, &pattern, tube);
    let n = f64::from(pattern.circuits);
    let (thickness, thickness_max) = thickness(m, spec, &laid, &eq, n, !tube || friction);
    let pass = pass_summary(m, &choice, &laid, &last, &turn);
    let report = layer_report(spec, &eq, &turn, &pattern, circuit_len, thickness_max);
    Ok(Layer {
        points: laid.points,
        thickness,
        pass,
        pattern,
        report,
        warnings,
        pass_path: laid.pass_path,
        tube,
    })
}
