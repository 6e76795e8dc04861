//! Arc blocks (`G2`/`G3`) in their plane: the centre from a radius or from
//! `I J K`, the check that the end is on the circle, and the chords within
//! a tolerance (helical arcs move the normal axis in proportion).

use std::f64::consts::{FRAC_PI_2, TAU};

use crate::modal::ArcPlane;

/// How an arc block gives its centre (mm).
pub(super) enum Centre {
    /// `R` / `CR=`: the radius, negative for the major arc.
    Radius(f64),
    /// `I J K` (per axis, `None` where the word is missing), absolute
    /// (`G90.1`) or from the start.
    Offsets {
        /// The offsets of X, Y, Z.
        ijk: [Option<f64>; 3],
        /// `G90.1`.
        absolute: bool,
    },
}

/// An arc from `from` to `to`.
pub(super) struct Arc {
    from: [f64; 3],
    to: [f64; 3],
    /// The plane's axes (first, second, normal).
    axes: (usize, usize, usize),
    clockwise: bool,
    centre: (f64, f64),
    /// The radius at the start and at the end.
    radii: (f64, f64),
    /// The start angle and the swept angle (>= 0).
    start: f64,
    sweep: f64,
}

impl Arc {
    /// The arc of a block; an error (what is wrong) for an arc from an
    /// unknown position, a radius too short for the chord, or an end that is
    /// not on the circle.
    pub(super) fn new(
        from: [f64; 3],
        to: [f64; 3],
        plane: ArcPlane,
        clockwise: bool,
        centre: &Centre,
    ) -> Result<Self, String> {
        let (u, v, n) = plane.axes();
        if from[u].is_nan() || from[v].is_nan() || from[n].is_nan() && !to[n].is_nan() {
            return Err("an arc from an unknown position".into());
        }
        let (cu, cv) = match centre {
            Centre::Radius(r) => radius_centre(from, to, (u, v), clockwise, *r)?,
            Centre::Offsets { ijk, absolute } => {
                let off = |k: usize| ijk[k].unwrap_or(0.0);
                if *absolute {
                    // I, J, K belong to X, Y, Z; a missing one is the start's.
                    let abs = |k: usize| if ijk[k].is_some() { off(k) } else { from[k] };
                    (abs(u), abs(v))
                } else {
                    (from[u] + off(u), from[v] + off(v))
                }
            }
        };
        let rs = (from[u] - cu).hypot(from[v] - cv);
        let re = (to[u] - cu).hypot(to[v] - cv);
        if (rs - re).abs() > 0.002 + 1e-3 * rs || rs < 1e-9 {
            return Err(format!(
                "the arc's end is not on its circle (radius {rs:.4} at the start, {re:.4} at the end)"
            ));
        }
        let a0 = (from[v] - cv).atan2(from[u] - cu);
        let a1 = (to[v] - cv).atan2(to[u] - cu);
        let mut sweep = (if clockwise { a0 - a1 } else { a1 - a0 }).rem_euclid(TAU);
        let same = (to[u] - from[u]).hypot(to[v] - from[v]) < 1e-9;
        if same && matches!(centre, Centre::Offsets { .. }) {
            sweep = TAU;
        }
        Ok(Self {
            from,
            to,
            axes: (u, v, n),
            clockwise,
            centre: (cu, cv),
            radii: (rs, re),
            start: a0,
            sweep,
        })
    }

    /// The chords' ends within `tolerance` (mm) of the arc, the last the
    /// block's end; an error past a million chords.
    pub(super) fn chord_ends(&self, tolerance: f64) -> Result<Vec<[f64; 3]>, String> {
        let (rs, re) = self.radii;
        let r = rs.max(re);
        let step = if tolerance < r {
            (2.0 * (1.0 - tolerance / r).acos()).min(FRAC_PI_2)
        } else {
            FRAC_PI_2
        };
        let chords = (self.sweep / step).ceil();
        if chords > 1e6 {
            return Err(format!(
                "the arc (radius {r:.3}) would need {chords:.0} chords within {tolerance} mm; \
                 give a larger arc tolerance"
            ));
        }
        let count = (chords as usize).max(1);
        let dir = if self.clockwise { -1.0 } else { 1.0 };
        let (u, v, n) = self.axes;
        let (cu, cv) = self.centre;
        let (from, to) = (self.from, self.to);
        Ok((1..=count)
            .map(|k| {
                let f = k as f64 / count as f64;
                let mut p = to;
                if k < count {
                    let ang = self.start + dir * self.sweep * f;
                    let rad = rs + (re - rs) * f;
                    p[u] = cu + rad * ang.cos();
                    p[v] = cv + rad * ang.sin();
                    p[n] = if to[n].is_nan() {
                        f64::NAN
                    } else {
                        from[n] + (to[n] - from[n]) * f
                    };
                }
                p
            })
            .collect())
    }
}

/// The centre of a radius arc: left of the chord for a counter-clockwise
/// minor arc (`r > 0`).
fn radius_centre(
    from: [f64; 3],
    to: [f64; 3],
    (u, v): (usize, usize),
    clockwise: bool,
    r: f64,
) -> Result<(f64, f64), String> {
    let (du, dv) = (to[u] - from[u], to[v] - from[v]);
    let d = du.hypot(dv);
    if d < 1e-12 {
        return Err("a radius arc whose end is its start".into());
    }
    let h2 = r * r - d * d / 4.0;
    if h2 < -(1e-6 * r * r).max(1e-8) {
        return Err(format!(
            "radius {} is shorter than half the chord {}",
            r.abs(),
            d / 2.0
        ));
    }
    let h = h2.max(0.0).sqrt();
    let (pu, pv) = (-dv / d, du / d);
    let side = if clockwise { -1.0 } else { 1.0 } * r.signum();
    Ok((
        (from[u] + to[u]) / 2.0 + side * h * pu,
        (from[v] + to[v]) / 2.0 + side * h * pv,
    ))
}
