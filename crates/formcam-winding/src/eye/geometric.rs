//! The geometric modes: the free length of the axis-parallel (closed form),
//! equidistant (first exit from the clearance zone) and user-curve trajectories,
//! point after point along the circuit.

use super::band::Band;
use super::envelope::{FirstExit, Profile};
use super::spec::{EyeMode, EyeSpec};
use crate::WindingError;

/// What is wrong with a user curve's points (at least two, `Z` increasing,
/// finite, `R > 0`), if anything, counting the points from 1.
pub(crate) fn curve_fault(curve: &[(f64, f64)]) -> Option<String> {
    if curve.len() < 2 {
        return Some("needs at least 2 points (columns Z,R)".into());
    }
    for (i, w) in curve.windows(2).enumerate() {
        if w[1].0.is_nan() || w[1].0 <= w[0].0 {
            return Some(format!(
                "point {}: Z must increase (got {} after {})",
                i + 2,
                w[1].0,
                w[0].0
            ));
        }
    }
    curve
        .iter()
        .position(|p| !p.0.is_finite() || !p.1.is_finite() || p.1 <= 0.0)
        .map(|i| format!("point {}: Z and R must be finite, R > 0 mm", i + 1))
}

/// The user curve as a profile (fine resampling of the polyline).
pub(super) fn curve_profile(curve: &[(f64, f64)]) -> Result<Profile, WindingError> {
    if let Some(fault) = curve_fault(curve) {
        return Err(WindingError::field("eye.curve", fault));
    }
    let (z0, z1) = (curve[0].0, curve[curve.len() - 1].0);
    let cells = 8192usize;
    let dz = (z1 - z0) / cells as f64;
    let mut j = 0;
    let vals = (0..=cells)
        .map(|i| {
            let z = z0 + dz * i as f64;
            while j + 2 < curve.len() && curve[j + 1].0 < z {
                j += 1;
            }
            let (a, b) = (curve[j], curve[j + 1]);
            let t = ((z - a.0) / (b.0 - a.0)).clamp(0.0, 1.0);
            a.1 + t * (b.1 - a.1)
        })
        .collect();
    Ok(Profile {
        z0,
        inv_dz: 1.0 / dz,
        vals,
    })
}

/// The free length of a geometric mode, point after point along the circuit.
#[derive(Clone)]
pub(super) enum Geometric<'a> {
    AxisParallel(f64),
    Equidistant(FirstExit<'a>, f64),
    Curve {
        prof: &'a Profile,
        span: (f64, f64),
        guess: f64,
        l_hi: f64,
    },
}

impl<'a> Geometric<'a> {
    /// `curve`: the user curve's profile (curve mode).
    pub(super) fn new(
        mode: EyeMode,
        spec: &EyeSpec,
        env: &'a Profile,
        curve: Option<&'a Profile>,
    ) -> Result<Self, WindingError> {
        Ok(match (mode, curve) {
            (EyeMode::AxisParallel, _) => Geometric::AxisParallel(spec.radius.unwrap_or(0.0)),
            (EyeMode::Equidistant, _) => {
                Geometric::Equidistant(FirstExit::new(env, spec), spec.l_max)
            }
            (EyeMode::Curve, Some(prof)) => Geometric::Curve {
                prof,
                span: (
                    spec.curve.first().map_or(0.0, |p| p.0),
                    spec.curve.last().map_or(0.0, |p| p.0),
                ),
                guess: 0.0,
                l_hi: 4.0 * spec.l_max + 20.0 * prof.top().max(0.0),
            },
            (EyeMode::Curve, None) => {
                return Err(WindingError::field(
                    "eye.curve",
                    "missing: a file of Z,R points",
                ));
            }
            (EyeMode::PullSpeed, _) => {
                return Err(WindingError::field(
                    "eye.mode",
                    "pull-speed is not a geometric mode",
                ));
            }
        })
    }

    pub(super) fn at(&mut self, b: &Band) -> Result<f64, WindingError> {
        let p = &b.p;
        match self {
            Geometric::AxisParallel(radius) => b.length_to_radius(*radius).ok_or_else(|| {
                WindingError::infeasible(
                    "eye.radius",
                    format!(
                        "the free band at x = {:.3} mm never reaches R = {radius} mm",
                        p.x
                    ),
                )
            }),
            Geometric::Equidistant(exit, l_max) => {
                let l = exit.at(b)?;
                if l > *l_max {
                    return Err(WindingError::infeasible(
                        "eye.clearance",
                        format!(
                            "keeping {} mm from the mandrel needs a free length of {l:.3} mm at x = \
                             {:.3} mm (z = {:.3} mm), more than l_max = {l_max} mm",
                            exit.clearance, p.x, p.z
                        ),
                    ));
                }
                Ok(l)
            }
            Geometric::Curve {
                prof,
                span: (c0, c1),
                guess,
                l_hi,
            } => {
                if prof.at(p.z).0 <= p.r && p.z >= *c0 && p.z <= *c1 {
                    return Err(WindingError::field(
                        "eye.curve",
                        format!("lies inside the mandrel at Z = {:.3} mm", p.z),
                    ));
                }
                let l = b
                    .length_to_profile(prof, *guess, *guess, *l_hi)
                    .ok_or_else(|| {
                        WindingError::field(
                            "eye.curve",
                            format!("the free band at x = {:.3} mm never meets the curve", p.x),
                        )
                    })?;
                let ez = b.zr(l).0;
                if ez < *c0 - 1e-9 || ez > *c1 + 1e-9 {
                    return Err(WindingError::field(
                        "eye.curve",
                        format!(
                            "does not cover the winding zone: the eye needs Z = {ez:.3} mm, the \
                             curve spans [{c0:.3}, {c1:.3}] mm"
                        ),
                    ));
                }
                *guess = l;
                Ok(l)
            }
        }
    }
}
