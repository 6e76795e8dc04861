//! `pass_summary`: what the pass is ([`PassSummary`]).

use formcam_geom::Meridian;
use serde::Serialize;

use super::lay::{Laid, bridging_margin};
use super::method::{Choice, Method};
use super::turn::PassTurn;
use crate::path::PassEnd;
use crate::{MuLaw, PathPoint};

/// What one pass is.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassSummary {
    /// Method used.
    pub method: Method,
    /// The constant slippage (geodesic, given or shot), or `None` for variable `mu`.
    pub mu: Option<f64>,
    /// Worst `|mu|` along the pass.
    pub mu_max_abs: f64,
    /// Minimax: the least worst-case `|mu|` of any path between the openings (the
    /// pass is laid at it, or a hair above where only a path grazing a
    /// turn-around would reach it).
    pub mu_optimal: Option<f64>,
    /// Where the pass starts.
    pub start: PassEnd,
    /// Where the pass ends.
    pub end: PassEnd,
    /// Path length on the mandrel, mm.
    pub length_mm: f64,
    /// Turn angle on the mandrel, rad.
    pub turn_angle_surface_rad: f64,
    /// Turn angle added where the path leaves the meridian with `alpha < pi/2` at a
    /// polar boss (a straight geodesic on the boss face up to the turn), rad.
    pub turn_angle_boss_rad: f64,
    /// Shooting: residual of the far boundary condition, mm.
    pub boundary_residual_mm: Option<f64>,
    /// Shooting: passes integrated.
    pub shooting_evaluations: Option<usize>,
    /// Minimax: `z` intervals (mm) where the bridging limit is active.
    pub bridging_active: Vec<(f64, f64)>,
    /// Smallest margin `C - C_b` to the bridging limit on concave parts, mm (None if convex).
    pub bridging_margin_mm: Option<f64>,
}

/// What the pass is: method, slippage, ends, length, turn angles, the shooting
/// and minimax figures, the margin to the bridging limit.
pub(super) fn pass_summary<M: Meridian>(
    m: &M,
    choice: &Choice,
    laid: &Laid,
    last: &PathPoint,
    turn: &PassTurn,
) -> PassSummary {
    let (mu, mu_max_abs) = match (choice.method, &choice.law) {
        (Method::Minimax, _) => (None, choice.minimax.as_ref().map_or(0.0, |x| x.mu_path)),
        (_, MuLaw::Constant(mu)) => (Some(*mu), mu.abs()),
        (_, l) => (None, l.max_abs()),
    };
    let (bridging_margin_mm, _) = bridging_margin(m, &laid.dense);
    let shot = choice.shot.as_ref();
    PassSummary {
        method: choice.method,
        mu,
        mu_max_abs,
        mu_optimal: choice.minimax.as_ref().map(|x| x.mu_max),
        start: laid.start,
        end: laid.end,
        length_mm: last.s,
        turn_angle_surface_rad: turn.surface,
        turn_angle_boss_rad: turn.boss,
        boundary_residual_mm: shot.map(|s| s.residual_mm),
        shooting_evaluations: shot.map(|s| s.evaluations),
        bridging_active: choice
            .minimax
            .as_ref()
            .map(|x| x.bridging_active.clone())
            .unwrap_or_default(),
        bridging_margin_mm,
    }
}
