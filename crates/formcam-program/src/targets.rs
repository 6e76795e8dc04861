//! What the machine must reach over a circuit, made from the planner's own
//! trajectories: the eye trajectory's points (winders) or the path with the
//! roller pressing on it (fibre placement), as formcam-machine's
//! [`Target`]s for the inverse kinematics.

use formcam_geom::Meridian;
use formcam_machine::{PathPoint, Target};
use formcam_winding::eye::EyeTrajectory;
use nalgebra::Point3;
use rayon::prelude::*;

/// The path point at `(z, r, v, alpha)` on `m`, with the meridian's slope.
fn path_point<M: Meridian>(m: &M, z: f64, r: f64, v: f64, alpha: f64) -> PathPoint {
    let dr = m.eval(z).dr;
    PathPoint { z, r, v, alpha, dr }
}

/// Targets of a winder: the eye points of `eye` (planned on `m`), each on
/// its own (in parallel on rayon's pool for long trajectories).
pub fn winder_targets<M: Meridian>(m: &M, eye: &EyeTrajectory) -> Vec<Target> {
    eye.points
        .par_iter()
        .with_min_len(4096)
        .map(|p| {
            let (se, ce) = p.eye_v.sin_cos();
            let at = Point3::new(p.eye_r * ce, p.eye_r * se, p.eye_z);
            let on = path_point(m, p.z, p.r, p.v, p.alpha);
            Target::winder(p.x, &on, at, p.l, p.margin)
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
        .map(|&(x, z, r, v, alpha)| Target::placement(x, &path_point(m, z, r, v, alpha), h))
        .collect()
}
