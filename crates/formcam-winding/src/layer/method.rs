//! `choose_method`: the method of a layer's pass, its slippage law and start
//! angle, from the slippage asked for and the pass's ends.

use std::f64::consts::FRAC_PI_2;

use formcam_geom::Meridian;
use serde::Serialize;

use super::spec::{Ends, LayerSpec, Slippage};
use crate::friction::friction_turns;
use crate::path::TANGENT_ALPHA_TOL;
use crate::shooting::{Shot, shoot};
use crate::{MuLaw, WindingError};

/// Which method produced the pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Clairaut's relation, integrated as a geodesic.
    Geodesic,
    /// A given constant or piecewise slippage.
    GivenSlippage,
    /// Shooting on a constant slippage.
    Shooting,
    /// The minimax direct search of eqs. 5–6.
    Minimax,
    /// A tube's geodesic with turn-arounds held by friction at both ends.
    FrictionTurn,
}

/// The method chosen for a layer, the slippage law and start angle of its pass.
pub(super) struct Choice {
    pub(super) method: Method,
    pub(super) law: MuLaw,
    /// Winding angle at `z_start`, rad.
    pub(super) alpha0: f64,
    /// The shot pass of `mu = "auto"`.
    pub(super) shot: Option<Shot>,
    /// The minimax search's figures.
    pub(super) minimax: Option<MinimaxFigures>,
}

/// What the minimax search reports besides its path.
pub(super) struct MinimaxFigures {
    /// The worst `|mu|` of the path laid.
    pub(super) mu_path: f64,
    /// The least worst-case `|mu|` of any path.
    pub(super) mu_max: f64,
    /// `z` intervals (mm) where the bridging limit is active.
    pub(super) bridging_active: Vec<(f64, f64)>,
}

/// Chooses the method from the slippage asked for and the pass's ends: the law
/// and the start angle, shooting `mu = "auto"` (minimax where no constant
/// slippage turns at both ends) and a tube's friction turns.
pub(super) fn choose_method<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    friction: bool,
    warnings: &mut Vec<String>,
) -> Result<Choice, WindingError> {
    let (za, _) = m.z_range();
    let mut shot = None;
    let (method, law, alpha0) = match (&spec.slippage, spec.ends) {
        (Slippage::Constant(mu), Ends::Tube { winding_angle }) if friction => {
            let turns = friction_turns(m, *mu, winding_angle, spec.mu_limit)?;
            (Method::FrictionTurn, turns.law, FRAC_PI_2)
        }
        (Slippage::Auto | Slippage::Minimax, Ends::Tube { .. }) => {
            return Err(WindingError::field(
                "winding.mu",
                "\"auto\" and \"minimax\" need a mandrel with polar openings; give a number for a tube",
            ));
        }
        (Slippage::Geodesic, Ends::Poles { start, end }) => {
            if (start - end).abs() > 1e-9 * start.max(end) {
                return Err(WindingError::infeasible(
                    "winding.mu",
                    format!(
                        "a geodesic (mu = 0) needs equal polar openings, these are {start} and {end} mm; \
                         use mu = \"auto\""
                    ),
                ));
            }
            // The path is tangent to the opening when the meridian starts at it; compare
            // with a tolerance, since asin near 1 turns a rounding error of 1e-16 into 1e-8.
            let a0 = (start / m.r(za)).clamp(-1.0, 1.0).asin();
            // Within a hair of tangent is tangent, as at the far end (see `trace`).
            let a0 = if a0 > FRAC_PI_2 - TANGENT_ALPHA_TOL {
                FRAC_PI_2
            } else {
                a0
            };
            (Method::Geodesic, MuLaw::Constant(0.0), a0)
        }
        (Slippage::Geodesic, Ends::Tube { winding_angle }) => {
            (Method::Geodesic, MuLaw::Constant(0.0), winding_angle)
        }
        (Slippage::Constant(mu), Ends::Poles { .. }) => {
            (Method::GivenSlippage, MuLaw::Constant(*mu), FRAC_PI_2)
        }
        (Slippage::Constant(mu), Ends::Tube { winding_angle }) => {
            (Method::GivenSlippage, MuLaw::Constant(*mu), winding_angle)
        }
        (Slippage::Segments(s), Ends::Poles { .. }) => {
            (Method::GivenSlippage, MuLaw::Segments(s.clone()), FRAC_PI_2)
        }
        (Slippage::Segments(s), Ends::Tube { winding_angle }) => (
            Method::GivenSlippage,
            MuLaw::Segments(s.clone()),
            winding_angle,
        ),
        (Slippage::Auto, Ends::Poles { .. }) => match shoot(m, spec.mu_limit) {
            Ok(s) => {
                let mu = s.mu;
                shot = Some(s);
                (Method::Shooting, MuLaw::Constant(mu), FRAC_PI_2)
            }
            Err(e) => {
                warnings.push(format!(
                    "no constant slippage turns this shell at both ends (shooting: {e}); \
                     the minimax search was used instead"
                ));
                (Method::Minimax, MuLaw::Constant(0.0), FRAC_PI_2)
            }
        },
        (Slippage::Minimax, Ends::Poles { .. }) => {
            (Method::Minimax, MuLaw::Constant(0.0), FRAC_PI_2)
        }
    };
    Ok(Choice {
        method,
        law,
        alpha0,
        shot,
        minimax: None,
    })
}
