//! `mu = "auto"`: the constant slippage that makes a pass start tangent to one
//! polar opening and end tangent to the other (eq. 4), found by shooting.

use std::f64::consts::FRAC_PI_2;

use formcam_geom::Meridian;

use crate::ode::Tolerance;
use crate::ode::{find_root, find_root_known};
use crate::path::{PassEnd, Trace, TraceOptions, trace};
use crate::{MuLaw, ShootingFault, WindingError};

/// The result of shooting.
#[derive(Debug, Clone)]
pub struct Shot {
    /// The constant slippage found.
    pub mu: f64,
    /// Where the pass turns at the far end, mm (should be the meridian's end).
    pub z_turn: f64,
    /// Residual of the far boundary condition `|r(z_end) - C(z_end)|`, mm.
    pub residual_mm: f64,
    /// Number of passes integrated.
    pub evaluations: usize,
    /// The final pass, integrated at the fine tolerance.
    pub trace: Trace,
}

/// Tolerance while bracketing and narrowing the root.
const COARSE: Tolerance = Tolerance {
    rtol: 1e-9,
    atol: 1e-9,
    h_max: f64::INFINITY,
    max_steps: 200_000,
};
/// Tolerance of the polishing steps and of the final pass.
const FINE: Tolerance = Tolerance {
    rtol: 1e-13,
    atol: 1e-13,
    h_max: f64::INFINITY,
    max_steps: 400_000,
};

fn opts(overrun: f64, tol: Tolerance) -> TraceOptions {
    TraceOptions {
        exit_at_end: false,
        overrun,
        tol,
    }
}

/// Miss distance of the far turn-around for slippage `mu`: `z_turn - z_end`
/// (negative when the path turns early), clamped to `+overrun` when it runs away.
fn miss<M: Meridian>(m: &M, mu: f64, overrun: f64, tol: Tolerance) -> f64 {
    let z_end = m.z_end();
    match trace(m, &MuLaw::Constant(mu), FRAC_PI_2, &opts(overrun, tol)) {
        Ok(tr) => match tr.end {
            PassEnd::TurnAround { z } => (z - z_end).min(overrun),
            PassEnd::Exit { .. } => overrun,
        },
        Err(_) => overrun,
    }
}

/// Finds the constant `mu` such that the pass starting tangent to the opening at
/// `z_start` turns exactly at `z_end`. `mu_limit` bounds the search.
///
/// Three phases: a secant-guided search for a sign change of the miss distance
/// (falling back to a doubling scan on both sides), Illinois regula falsi on
/// that bracket at a coarse integration tolerance, then secant polishing at a
/// fine tolerance until the far turn-around is within 1e-11 mm of the end.
pub fn shoot<M: Meridian>(m: &M, mu_limit: f64) -> Result<Shot, WindingError> {
    let (za, zb) = m.z_range();
    let overrun = 0.25 * (zb - za);
    let mut evals = 0usize;
    let mut f = |mu: f64, tol: Tolerance| {
        evals += 1;
        miss(m, mu, overrun, tol)
    };
    let f0 = f(0.0, COARSE);
    let mut mu = 0.0;
    if f0 != 0.0 {
        let ((a, fa), (b, fb)) = bracket(&mut |x| f(x, COARSE), f0, mu_limit)?;
        // The coarse tolerance resolves the miss to about 1e-6 mm: stop there.
        mu = find_root_known(
            |x| f(x, COARSE),
            (a, fa),
            (b, fb),
            1e-13 * a.abs().max(b.abs()),
            1e-6,
        );
    }
    // Polish with the fine tolerance (secant from a small step).
    let mut x0 = mu;
    let mut g0 = f(x0, FINE);
    let mut x1 = mu + 1e-6 * mu.abs().max(1e-3);
    let mut g1 = f(x1, FINE);
    // The fine tolerance resolves the miss to about 1e-10 mm.
    for _ in 0..4 {
        if g0.abs() <= 2e-10 || g1 == g0 {
            break;
        }
        let x2 = x1 - g1 * (x1 - x0) / (g1 - g0);
        if !x2.is_finite() || (x2 - x1).abs() > 1e-3 * mu_limit {
            break;
        }
        (x0, g0) = (x1, g1);
        x1 = x2;
        g1 = f(x1, FINE);
        if g1.abs() < g0.abs() {
            std::mem::swap(&mut x0, &mut x1);
            std::mem::swap(&mut g0, &mut g1);
        }
    }
    let mu = x0;
    let tr = trace(m, &MuLaw::Constant(mu), FRAC_PI_2, &opts(overrun, FINE))?;
    let z_turn = tr.z_last();
    let residual_mm = far_residual(m, &tr, zb);
    if (z_turn - zb).abs() > 1e-6 {
        return Err(WindingError::shooting(ShootingFault::NotConverged {
            z_turn,
            z_far: zb,
        }));
    }
    Ok(Shot {
        mu,
        z_turn,
        residual_mm,
        evaluations: evals,
        trace: tr,
    })
}

/// A point `(mu, miss)` of the miss function.
type Sample = (f64, f64);

/// A bracket `[a, b]` of the sign change of `f` (with `f(0) = f0`), within `±mu_limit`.
fn bracket(
    f: &mut impl FnMut(f64) -> f64,
    f0: f64,
    mu_limit: f64,
) -> Result<(Sample, Sample), WindingError> {
    // Secant-guided first.
    let (mut x0, mut g0) = (0.0, f0);
    let mut x1 = 0.01f64.min(mu_limit);
    let mut g1 = f(x1);
    if g1.signum() != f0.signum() {
        return Ok(((0.0, f0), (x1, g1)));
    }
    let mut closest = if g1.abs() < f0.abs() {
        (x1, g1)
    } else {
        (0.0, f0)
    };
    for _ in 0..8 {
        if g1 == g0 {
            break;
        }
        let step = -g1 * (x1 - x0) / (g1 - g0);
        let x2 = (x1 + step * 1.2).clamp(-mu_limit, mu_limit);
        if x2 == x1 {
            break;
        }
        let g2 = f(x2);
        if g2.signum() != f0.signum() {
            return Ok(((x1, g1), (x2, g2)));
        }
        if g2.abs() < closest.1.abs() {
            closest = (x2, g2);
        }
        (x0, g0, x1, g1) = (x1, g1, x2, g2);
    }
    // Doubling scan on both sides.
    let mut last_same = [(0.0f64, f0), (0.0f64, f0)];
    let mut step = 1e-3;
    while step <= mu_limit * 1.000_001 {
        for (side, cand) in [(0usize, step), (1usize, -step)] {
            let fc = f(cand);
            if fc.signum() != f0.signum() {
                return Ok((last_same[side], (cand, fc)));
            }
            last_same[side] = (cand, fc);
            if fc.abs() < closest.1.abs() {
                closest = (cand, fc);
            }
        }
        step *= 2.0;
    }
    Err(WindingError::shooting(ShootingFault::NoSlippage {
        mu_limit,
        miss_mm: closest.1,
        mu: closest.0,
    }))
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
