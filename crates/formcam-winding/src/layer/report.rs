//! `layer_report`: the layer report ([`LayerReport`]).

use serde::Serialize;

use super::spec::LayerSpec;
use super::thickness::ply_thickness;
use super::turn::PassTurn;
use crate::PathPoint;
use crate::pattern::Pattern;

/// The layer report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LayerReport {
    /// Winding angle at the equator (the widest parallel), rad.
    pub alpha_equator_rad: f64,
    /// `z` of that parallel, mm.
    pub z_equator: f64,
    /// Turn angle of one pass, boss included, dwell excluded, rad.
    pub turn_angle_pass_rad: f64,
    /// Turn angle of one circuit (two passes), dwell excluded, rad.
    pub turn_angle_circuit_rad: f64,
    /// Turn angle of one circuit with the pattern's dwell, rad.
    pub turn_angle_circuit_with_dwell_rad: f64,
    /// Dwell per circuit, degrees.
    pub dwell_deg: f64,
    /// Dwell at each turn-around, degrees.
    pub dwell_per_turnaround_deg: f64,
    /// Fibre length of one pass, mm.
    pub pass_length_mm: f64,
    /// Fibre (band) length of one circuit, dwell arcs included, mm.
    pub circuit_length_mm: f64,
    /// Band length of the whole layer, mm.
    pub fibre_length_mm: f64,
    /// Layer thickness at the equator (two plies, +alpha and -alpha), mm.
    pub thickness_equator_mm: f64,
    /// Largest layer thickness along the meridian (capped one band width from the turn), mm.
    pub thickness_max_mm: f64,
}

/// The layer report: equator, turn angles with and without dwell, lengths,
/// thickness.
pub(super) fn layer_report(
    spec: &LayerSpec,
    eq: &PathPoint,
    turn: &PassTurn,
    pattern: &Pattern,
    circuit_len: f64,
    thickness_max: f64,
) -> LayerReport {
    let n = f64::from(pattern.circuits);
    let turn_circuit = 2.0 * turn.total();
    LayerReport {
        alpha_equator_rad: eq.alpha,
        z_equator: eq.z,
        turn_angle_pass_rad: turn.total(),
        turn_angle_circuit_rad: turn_circuit,
        turn_angle_circuit_with_dwell_rad: turn_circuit + pattern.dwell_rad,
        dwell_deg: pattern.dwell_rad.to_degrees(),
        dwell_per_turnaround_deg: 0.5 * pattern.dwell_rad.to_degrees(),
        pass_length_mm: turn.length,
        circuit_length_mm: circuit_len,
        fibre_length_mm: n * circuit_len,
        thickness_equator_mm: ply_thickness(spec, n, eq.r, eq.alpha),
        thickness_max_mm: thickness_max,
    }
}
