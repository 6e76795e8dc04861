//! What the machine must reach: targets in the mandrel frame, from an eye
//! trajectory (winders) or from the path itself (fibre placement).

use formcam_geom::Meridian;
use formcam_winding::eye::EyeTrajectory;
use nalgebra::{Point3, Unit, Vector3};
use rayon::prelude::*;

/// One point the machine must reach, in the mandrel frame (`z` the mandrel's
/// axis, `x` its `v = 0` direction).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    /// Circuit parameter (laid band length), mm.
    pub x: f64,
    /// Where the payout point must be: the eye (winder) or the compaction
    /// roller's centre `r + h m` (placement), mm.
    pub point: Point3<f64>,
    /// The path point on the mandrel, mm.
    pub path_point: Point3<f64>,
    /// Winder: the free band's direction from the path point towards the eye.
    /// Placement: the path's direction.
    pub band: Unit<Vector3<f64>>,
    /// The mandrel's outward surface normal at the path point.
    pub normal: Unit<Vector3<f64>>,
    /// Free length of band between the path point and the eye, mm (0 for placement).
    pub free_length: f64,
    /// The eye's margin over the clearance zone round the mandrel, mm (negative:
    /// closer than the clearance; infinite for placement).
    pub clearance_margin: f64,
}

/// The path point, its tangent `tau` (eqs. 8–9) and the outward normal, in the
/// mandrel frame.
fn frame(z: f64, r: f64, v: f64, alpha: f64, dr: f64) -> (Point3<f64>, Vector3<f64>, Vector3<f64>) {
    let (sv, cv) = v.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    let q = (1.0 + dr * dr).sqrt();
    let e_r = Vector3::new(cv, sv, 0.0);
    let e_v = Vector3::new(-sv, cv, 0.0);
    let e_z = Vector3::z();
    let tau = (e_z + e_r * dr) * (ca / q) + e_v * sa;
    let normal = (e_r - e_z * dr) / q;
    (Point3::new(r * cv, r * sv, z), tau, normal)
}

/// Targets of a winder: the eye points of `eye` (planned on `m`), each on
/// its own (in parallel on rayon's pool for long trajectories).
pub fn winder_targets<M: Meridian>(m: &M, eye: &EyeTrajectory) -> Vec<Target> {
    eye.points
        .par_iter()
        .with_min_len(4096)
        .map(|p| {
            let dr = m.eval(p.z).dr;
            let dr = if dr.is_finite() { dr } else { 0.0 };
            let (path_point, tau, normal) = frame(p.z, p.r, p.v, p.alpha, dr);
            let (se, ce) = p.eye_v.sin_cos();
            Target {
                x: p.x,
                point: Point3::new(p.eye_r * ce, p.eye_r * se, p.eye_z),
                path_point,
                band: Unit::new_normalize(tau),
                normal: Unit::new_normalize(normal),
                free_length: p.l,
                clearance_margin: p.margin,
            }
        })
        .collect()
}

/// Targets of a fibre-placement head with a compaction roller of radius `h`:
/// the path points `(x, z, r, v, alpha)` (`alpha` from the `+z` meridian) on `m`.
pub fn placement_targets<M: Meridian>(
    m: &M,
    path: &[(f64, f64, f64, f64, f64)],
    h: f64,
) -> Vec<Target> {
    path.iter()
        .map(|&(x, z, r, v, alpha)| {
            let dr = m.eval(z).dr;
            let dr = if dr.is_finite() { dr } else { 0.0 };
            let (path_point, tau, normal) = frame(z, r, v, alpha, dr);
            Target {
                x,
                point: path_point + normal * h,
                path_point,
                band: Unit::new_normalize(tau),
                normal: Unit::new_normalize(normal),
                free_length: 0.0,
                clearance_margin: f64::INFINITY,
            }
        })
        .collect()
}
