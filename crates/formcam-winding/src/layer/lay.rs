//! `lay_pass`: the pass of the chosen method laid, traced in path length (and
//! checked for bridging) or the minimax search's path, sampled densely for the
//! report and as the job asks.

use std::f64::consts::FRAC_PI_2;

use formcam_geom::Meridian;

use super::method::{Choice, Method, MinimaxFigures};
use super::spec::{LayerSpec, Slippage};
use crate::circuit::PassPath;
use crate::minimax::{bridging_limit, minimax};
use crate::path::{PassEnd, TraceOptions, trace};
use crate::{PathPoint, ShootingFault, WindingError};

/// Points of the dense sampling behind the report (equator, thickness, bridging).
const DENSE: usize = 4001;

/// The pass laid: the dense sampling behind the report, the points asked for,
/// the pass for evaluation anywhere and its ends.
pub(super) struct Laid {
    pub(super) dense: Vec<PathPoint>,
    pub(super) points: Vec<PathPoint>,
    pub(super) pass_path: PassPath,
    pub(super) start: PassEnd,
    pub(super) end: PassEnd,
}

/// Lays the pass of the chosen method: traced (and checked for bridging, where
/// `mu = "auto"` falls back to minimax) or the minimax search's path.
pub(super) fn lay_pass<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    friction: bool,
    choice: &mut Choice,
    warnings: &mut Vec<String>,
) -> Result<Laid, WindingError> {
    if choice.method != Method::Minimax {
        let laid = traced_pass(m, spec, friction, choice)?;
        let (_, bad) = bridging_margin(m, &laid.dense);
        let Some(zbad) = bad else {
            return Ok(laid);
        };
        if spec.slippage != Slippage::Auto {
            return Err(WindingError::infeasible(
                "winding.mu",
                format!(
                    "the band bridges (lifts off the concave surface) at z = {zbad:.3} mm; \
                     use mu = \"minimax\""
                ),
            ));
        }
        warnings.push(format!(
            "the constant-mu path bridges the concave meridian at z = {zbad:.3} mm; the minimax \
             search was used instead"
        ));
        choice.method = Method::Minimax;
    }
    minimax_pass(m, spec, choice)
}

/// The pass traced in path length (the shot pass of `auto` as it is), sampled
/// densely for the report and as the job asks.
fn traced_pass<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    friction: bool,
    choice: &Choice,
) -> Result<Laid, WindingError> {
    let (za, _) = m.z_range();
    let samples = spec.samples.max(2);
    let law = &choice.law;
    let tr = match &choice.shot {
        Some(s) => s.trace.clone(),
        None if friction => {
            // A tighter tolerance than a plain pass: the far turn must land on
            // the tube's end, which the error gathered over the pass would move.
            let mut opts = TraceOptions::default();
            opts.tol.rtol = 3e-15;
            opts.tol.atol = 3e-15;
            trace(m, law, choice.alpha0, &opts)?
        }
        None => trace(m, law, choice.alpha0, &TraceOptions::default())?,
    };
    let dense = tr.sample(m, law, samples.max(DENSE));
    let points = if samples >= DENSE {
        dense.clone()
    } else {
        tr.sample(m, law, samples)
    };
    let start = if choice.alpha0 < FRAC_PI_2 {
        PassEnd::Exit {
            z: za,
            alpha: choice.alpha0,
        }
    } else {
        PassEnd::TurnAround { z: za }
    };
    let end = tr.end;
    Ok(Laid {
        dense,
        points,
        pass_path: PassPath::Traced(tr),
        start,
        end,
    })
}

/// The minimax search's pass (eqs. 5–6), turning at both openings; notes its
/// slippage figures in `choice` and drops the shot pass.
fn minimax_pass<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    choice: &mut Choice,
) -> Result<Laid, WindingError> {
    let (za, zb) = m.z_range();
    let mm = minimax(m, spec.minimax_nodes, spec.mu_limit).map_err(|e| {
        if spec.slippage == Slippage::Auto && choice.shot.is_none() {
            WindingError::shooting(ShootingFault::NorMinimax {
                mu_limit: spec.mu_limit,
                minimax: Box::new(e),
            })
        } else {
            e
        }
    })?;
    let dense = mm.points(m);
    let points = resample(&dense, spec.samples.max(2));
    choice.minimax = Some(MinimaxFigures {
        mu_path: mm.mu_path,
        mu_max: mm.mu_max,
        bridging_active: mm.bridging_active,
    });
    choice.shot = None;
    Ok(Laid {
        pass_path: PassPath::Points(dense.clone()),
        dense,
        points,
        start: PassEnd::TurnAround { z: za },
        end: PassEnd::TurnAround { z: zb },
    })
}

/// `n` points evenly spaced in path length, interpolated linearly between the
/// points of a dense path (the minimax grid), ends kept exactly.
fn resample(pts: &[PathPoint], n: usize) -> Vec<PathPoint> {
    let (Some(first), Some(last)) = (pts.first(), pts.last()) else {
        return Vec::new();
    };
    let total = last.s;
    let mut out = Vec::with_capacity(n);
    let mut i = 0;
    for k in 0..n {
        let s = total * k as f64 / (n - 1).max(1) as f64;
        while i + 2 < pts.len() && pts[i + 1].s < s {
            i += 1;
        }
        let p = if k == 0 {
            *first
        } else if k + 1 == n {
            *last
        } else {
            let (a, b) = (pts[i], pts[(i + 1).min(pts.len() - 1)]);
            let t = if b.s > a.s {
                ((s - a.s) / (b.s - a.s)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let lerp = |x: f64, y: f64| x + t * (y - x);
            PathPoint {
                s,
                z: lerp(a.z, b.z),
                r: lerp(a.r, b.r),
                v: lerp(a.v, b.v),
                alpha: lerp(a.alpha, b.alpha),
                c: lerp(a.c, b.c),
                mu: if t < 0.5 { a.mu } else { b.mu },
            }
        };
        out.push(p);
    }
    out
}

/// Smallest `C - C_b` on concave parts and the first `z` where it is negative.
pub(super) fn bridging_margin(m: &impl Meridian, pts: &[PathPoint]) -> (Option<f64>, Option<f64>) {
    let mut margin: Option<f64> = None;
    let mut first_bad = None;
    for p in pts {
        let j = m.eval(p.z);
        if j.d2r > 0.0 {
            let d = p.c - bridging_limit(&j);
            margin = Some(margin.map_or(d, |m: f64| m.min(d)));
            if d < -1e-9 * j.r && first_bad.is_none() {
                first_bad = Some(p.z);
            }
        }
    }
    (margin, first_bad)
}
