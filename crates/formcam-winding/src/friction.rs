//! Turn-arounds held by friction on a tube's own surface (`turnaround =
//! "friction"`), for winders with no room to turn the band beyond the ends.
//!
//! The pass is the geodesic `C = C0 = r(z_start) sin(alpha0)` in the middle
//! (the same geodesic as a pass that runs off the ends) and turns at each end
//! with the slippage `|mu|` of the job: at the start `C` falls from `r` (the
//! turn) to `C0` under `C' = -mu B`, at the end it rises from `C0` to `r` under
//! `C' = +mu B` (eq. 3, `B = C^2/r^2 - r r'' (1 - C^2/r^2) / (1 + r'^2)`). On a
//! cylinder `1/sin(alpha) = 1/sin(alpha0) - mu dz / R` towards the end, so each
//! zone is `R (1/sin(alpha0) - 1) / mu` long.
//!
//! The zones are found by integrating eq. 3 in `z` from each end until `C`
//! reaches `C0`; the pass itself is then traced in path length through both
//! turns ([`crate::trace`]) with the slippage `-mu`, `0`, `+mu` on the three parts.

use formcam_geom::Meridian;

use crate::minimax::b_factor;
use crate::ode::{Control, Integrator, Outcome, Tolerance, bisect, find_root};
use crate::{MuLaw, MuSegment, WindingError};

/// The friction turn-arounds of a tube's pass.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionTurns {
    /// Clairaut constant of the geodesic between the turns, mm.
    pub c0: f64,
    /// Length (in `z`) of the turn zone at the start, mm.
    pub start_zone: f64,
    /// Length (in `z`) of the turn zone at the end, mm.
    pub end_zone: f64,
    /// The slippage along the pass: `-mu` on the start zone, `0` between,
    /// `+mu` on the end zone (each zone's segment runs on beyond the tube's end,
    /// so that the tracer turns there).
    pub law: MuLaw,
}

/// The zones and the slippage law of friction turns with slippage `mu > 0` on a
/// tube whose middle geodesic has the winding angle `alpha0` at `z_start`.
///
/// Errors: `mu` too small to leave a turn where the tube widens towards its end
/// (`mu > |r'|` is needed there), a geodesic that would turn before the tube's
/// end, and zones longer together than the tube (on a cylinder, each longer
/// than half of it) — that error names the least `mu` that fits.
pub fn friction_turns<M: Meridian>(
    m: &M,
    mu: f64,
    alpha0: f64,
    mu_limit: f64,
) -> Result<FrictionTurns, WindingError> {
    let (za, zb) = m.z_range();
    let len = zb - za;
    let (ja, jb) = (m.eval(za), m.eval(zb));
    // At the turn (C = r) eq. 3 gives C' = mu B = mu: the path leaves r only if
    // the meridian does not widen towards the end faster than that.
    let need = (-ja.dr).max(jb.dr).max(0.0);
    if mu <= need {
        return Err(WindingError::infeasible(
            "winding.mu",
            format!(
                "the tube widens towards an end (|r'| = {need:.6}), so a turn held by friction there \
                 needs mu > {need:.6}, got {mu}"
            ),
        ));
    }
    let c0 = ja.r * alpha0.sin();
    if c0 >= jb.r {
        return Err(WindingError::infeasible(
            "winding.winding_angle_deg",
            format!(
                "the geodesic of {:.3} deg at z = {za:.3} mm turns before the tube's end, where \
                 r = {:.3} mm <= C = {c0:.3} mm; lower the winding angle",
                alpha0.to_degrees(),
                jb.r
            ),
        ));
    }
    let zones = |mu: f64| Some((zone(m, mu, c0, true)?, zone(m, mu, c0, false)?));
    let fits = |mu: f64| zones(mu).is_some_and(|(a, b)| a + b <= len);
    let Some((start_zone, end_zone)) = zones(mu).filter(|(a, b)| a + b <= len) else {
        let fit = least_fitting_mu(&fits, mu);
        let lengths = match zones(mu) {
            Some((a, b)) => format!("{a:.3} mm and {b:.3} mm"),
            None => "more than the tube's length each".to_string(),
        };
        let limit = if fit > mu_limit {
            format!(", above mu_limit = {mu_limit}")
        } else {
            String::new()
        };
        return Err(WindingError::infeasible(
            "winding.mu",
            format!(
                "the turns held by friction with mu = {mu} need {lengths} at the ends of the tube's \
                 {len:.3} mm (on a cylinder each zone must be at most half the tube); mu >= {fit:.6} \
                 would fit{limit}, or a smaller winding angle"
            ),
        ));
    };
    let beyond = len.max(1.0);
    let law = MuLaw::Segments(vec![
        MuSegment {
            z_from: za - beyond,
            z_to: za + start_zone,
            mu: -mu,
        },
        MuSegment {
            z_from: zb - end_zone,
            z_to: zb + beyond,
            mu,
        },
    ]);
    Ok(FrictionTurns {
        c0,
        start_zone,
        end_zone,
        law,
    })
}

/// Length in `z` over which `C` falls from `r` at one end (`start`: `z_start`,
/// else `z_end`) to `c0` with `|C'| = mu B` (it falls going inwards from either
/// end); `None` where it does not reach `c0` inside the tube, or touches `r`
/// again (the band would turn back).
fn zone<M: Meridian>(m: &M, mu: f64, c0: f64, start: bool) -> Option<f64> {
    let (za, zb) = m.z_range();
    let len = zb - za;
    let z_at = |u: f64| if start { za + u } else { zb - u };
    let r_end = m.r(z_at(0.0));
    let tol = Tolerance {
        rtol: 1e-13,
        atol: 1e-13 * r_end,
        h_max: 0.05 * len,
        max_steps: 100_000,
    };
    let mut reached: Option<f64> = None;
    let mut touched = false;
    let mut integ = Integrator::new(
        |u: f64, y: &[f64; 1]| [-mu * b_factor(&m.eval(z_at(u)), y[0])],
        tol,
    );
    let (outcome, u_stop, y_stop) = integ.run(0.0, [r_end], len, 1e-3 * len, |st| {
        if reached.is_some() {
            return Control::Stop;
        }
        if st.y1[0] <= c0 {
            let xtol = 1e-15 * (st.t1() + len);
            let u = find_root(|u| st.at(u)[0] - c0, st.t0, st.t1(), xtol, 0.0);
            reached = Some(u);
            return Control::StopAt(u);
        }
        // Past the first step the path must stay inside (C < r).
        if st.t0 > 0.0 && st.y1[0] >= m.r(z_at(st.t1())) {
            touched = true;
            return Control::Stop;
        }
        Control::Continue
    });
    if touched || matches!(outcome, Outcome::Failed | Outcome::TooManySteps) {
        return None;
    }
    // The retaken step lands on the crossing found in the dense output; one
    // Newton step on its (fifth-order) end state removes the interpolation error.
    reached?;
    let slope = mu * b_factor(&m.eval(z_at(u_stop)), y_stop[0]);
    Some(u_stop + (y_stop[0] - c0) / slope)
}

/// The least slippage above `mu` whose zones fit in the tube (bisection; the
/// zones shorten as `mu` grows).
fn least_fitting_mu(fits: &impl Fn(f64) -> bool, mu: f64) -> f64 {
    let mut lo = mu;
    let mut hi = 2.0 * mu;
    while !fits(hi) {
        lo = hi;
        hi *= 2.0;
        if hi > 1e6 {
            return f64::INFINITY;
        }
    }
    bisect(fits, lo, hi, 100, 1e-12)
}
