//! `check_far_end`: the pass ends where the mandrel asks.

use formcam_geom::Meridian;

use super::spec::{Ends, LayerSpec, Slippage};
use crate::WindingError;
use crate::path::PassEnd;

/// How far before the far opening a turn still counts as at the opening, mm.
const FAR_TOL_MM: f64 = 1e-3;

/// Checks that the pass ends where the mandrel asks: at a tube's end, at the far
/// polar opening (not before it, not leaving the mandrel there).
pub(super) fn check_far_end<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    friction: bool,
    end: PassEnd,
) -> Result<(), WindingError> {
    let (_, zb) = m.z_range();
    match (spec.ends, end) {
        (Ends::Tube { .. }, PassEnd::TurnAround { z })
            if friction && (z - zb).abs() <= FAR_TOL_MM => {}
        (Ends::Tube { .. }, PassEnd::TurnAround { z }) if friction => {
            return Err(WindingError::infeasible(
                "winding.mu",
                format!(
                    "the pass with friction turn-arounds turns at z = {z:.6} mm instead of the tube's \
                     end ({zb:.6} mm)"
                ),
            ));
        }
        (Ends::Tube { .. }, PassEnd::TurnAround { z }) => {
            return Err(WindingError::infeasible(
                "winding.winding_angle_deg",
                format!(
                    "the path turns at z = {z:.3} mm before the tube's end ({zb:.3} mm); lower the \
                     winding angle or the slippage"
                ),
            ));
        }
        (Ends::Poles { .. }, PassEnd::TurnAround { z }) if z < zb - FAR_TOL_MM => {
            return Err(WindingError::infeasible(
                slippage_field(&spec.slippage),
                format!(
                    "the pass turns at z = {z:.3} mm, before the far polar opening at {zb:.3} mm; \
                     use mu = \"auto\" to meet both openings"
                ),
            ));
        }
        (Ends::Poles { end: opening, .. }, PassEnd::Exit { alpha, .. })
            if m.r(zb) - opening <= 1e-6 * m.r(zb) =>
        {
            return Err(WindingError::infeasible(
                slippage_field(&spec.slippage),
                format!(
                    "the band reaches the far polar opening at a winding angle of {:.2} deg and would \
                     leave the mandrel there; use mu = \"auto\" to meet both openings",
                    alpha.to_degrees()
                ),
            ));
        }
        _ => {}
    }
    Ok(())
}

/// The job field that sets the slippage.
fn slippage_field(s: &Slippage) -> &'static str {
    match s {
        Slippage::Segments(_) => "winding.mu_segments",
        _ => "winding.mu",
    }
}
