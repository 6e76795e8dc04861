//! `mu = "auto"`: the constant slippage that makes a pass start tangent to one
//! polar opening and end tangent to the other (eq. 4), found by shooting.

use std::f64::consts::FRAC_PI_2;

use formcam_geom::Meridian;

use crate::ode::find_root;
use crate::path::{PassEnd, TraceOptions, trace};
use crate::{MuLaw, WindingError};

/// The result of shooting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shot {
    /// The constant slippage found.
    pub mu: f64,
    /// Where the pass turns at the far end, mm (should be the meridian's end).
    pub z_turn: f64,
    /// Residual of the far boundary condition `|r(z_end) - C(z_end)|`, mm.
    pub residual_mm: f64,
    /// Number of passes integrated.
    pub evaluations: usize,
}

/// Miss distance of the far turn-around for slippage `mu`: `z_turn - z_end`
/// (negative when the path turns early), clamped to `+overrun` when it runs away.
fn miss<M: Meridian>(m: &M, mu: f64, overrun: f64) -> f64 {
    let opts = TraceOptions {
        exit_at_end: false,
        overrun,
        ..TraceOptions::default()
    };
    let z_end = m.z_end();
    match trace(m, &MuLaw::Constant(mu), FRAC_PI_2, &opts) {
        Ok(tr) => match tr.end {
            PassEnd::TurnAround { z } => (z - z_end).min(overrun),
            PassEnd::Exit { .. } => overrun,
        },
        Err(_) => overrun,
    }
}

/// Finds the constant `mu` such that the pass starting tangent to the opening at
/// `z_start` turns exactly at `z_end`. `mu_limit` bounds the search.
pub fn shoot<M: Meridian>(m: &M, mu_limit: f64) -> Result<Shot, WindingError> {
    let (za, zb) = m.z_range();
    let overrun = 0.25 * (zb - za);
    let mut evals = 0usize;
    let mut f = |mu: f64| {
        evals += 1;
        miss(m, mu, overrun)
    };
    let f0 = f(0.0);
    let mu = if f0 == 0.0 {
        0.0
    } else {
        // Scan outwards on both sides for a sign change; bracket it with the last
        // candidate on the same side that still had the sign of f(0).
        let mut last_same = [0.0f64, 0.0f64];
        let mut closest = (0.0, f0);
        let mut bracket = None;
        let mut step = 1e-3;
        'scan: while step <= mu_limit * 1.000_001 {
            for (side, cand) in [(0usize, step), (1usize, -step)] {
                let fc = f(cand);
                if fc.signum() != f0.signum() {
                    bracket = Some((last_same[side], cand));
                    break 'scan;
                }
                last_same[side] = cand;
                if fc.abs() < closest.1.abs() {
                    closest = (cand, fc);
                }
            }
            step *= 2.0;
        }
        let Some((a, b)) = bracket else {
            return Err(WindingError::Shooting(format!(
                "no constant slippage with |mu| <= {mu_limit} makes the path end tangent to the far \
                 polar opening (closest miss {:+.3} mm at mu = {}); try mu_segments or a larger mu_limit",
                closest.1, closest.0
            )));
        };
        find_root(&mut f, a, b, 1e-15 * a.abs().max(b.abs()), 1e-11)
    };
    let opts = TraceOptions {
        exit_at_end: false,
        overrun,
        ..TraceOptions::default()
    };
    let tr = trace(m, &MuLaw::Constant(mu), FRAC_PI_2, &opts)?;
    let z_turn = tr.z_last();
    let residual_mm = far_residual(m, &tr, zb);
    if (z_turn - zb).abs() > 1e-6 {
        return Err(WindingError::Shooting(format!(
            "shooting did not converge: the path turns at z = {z_turn:.6} mm instead of {zb:.6} mm"
        )));
    }
    Ok(Shot {
        mu,
        z_turn,
        residual_mm,
        evaluations: evals,
    })
}

/// `|r(z_end) - C(z_end)|` from a traced pass that turns at or near `z_end`.
fn far_residual<M: Meridian>(m: &M, tr: &crate::path::Trace, z_end: f64) -> f64 {
    // C at z_end: find s where z = z_end on the last part of the pass, or the
    // turn-around itself when the pass turns before z_end.
    let z_last = tr.z_last();
    if z_last <= z_end {
        // Turned before the end: C(z_turn) = r(z_turn); the condition misses by r(z_end)-C.
        let c = m.r(z_last);
        return (m.r(z_end) - c).abs();
    }
    let s = find_root(|s| tr.state_at(s)[0] - z_end, 0.0, tr.length(), 1e-14, 0.0);
    let y = tr.state_at(s);
    (m.r(z_end) - m.r(z_end) * y[2].sin()).abs()
}
