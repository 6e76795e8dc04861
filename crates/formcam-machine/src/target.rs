//! What the machine must reach: targets in the mandrel frame, each made
//! from a path point on the mandrel and the payout point there (a winder's
//! eye, or a placement head's roller pressing on the path). The planner
//! makes them from its own trajectories (formcam-program's `targets`).

use nalgebra::{Point3, Unit, Vector3};

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

/// A point of the path on a surface of revolution: where it is (`z`, `r`,
/// the angle `v` about the axis), its angle `alpha` from the `+z` meridian
/// and the meridian's slope `dr = r'(z)` there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// Along the axis, mm.
    pub z: f64,
    /// Radius, mm.
    pub r: f64,
    /// Angle about the axis, rad.
    pub v: f64,
    /// Angle from the `+z` meridian, rad.
    pub alpha: f64,
    /// The meridian's slope `r'(z)` (a non-finite slope counts as 0).
    pub dr: f64,
}

impl Target {
    /// A winder's target at circuit parameter `x`: the path point `p`, the
    /// eye at `eye`, the free length `free_length` between them and the
    /// eye's margin over the clearance zone.
    pub fn winder(
        x: f64,
        p: &PathPoint,
        eye: Point3<f64>,
        free_length: f64,
        clearance_margin: f64,
    ) -> Self {
        let (path_point, tau, normal) = frame(p);
        Self {
            x,
            point: eye,
            path_point,
            band: Unit::new_normalize(tau),
            normal: Unit::new_normalize(normal),
            free_length,
            clearance_margin,
        }
    }

    /// A fibre-placement head's target at circuit parameter `x`: the path
    /// point `p`, the compaction roller of radius `h` pressing there.
    pub fn placement(x: f64, p: &PathPoint, h: f64) -> Self {
        let (path_point, tau, normal) = frame(p);
        Self {
            x,
            point: path_point + normal * h,
            path_point,
            band: Unit::new_normalize(tau),
            normal: Unit::new_normalize(normal),
            free_length: 0.0,
            clearance_margin: f64::INFINITY,
        }
    }
}

/// The path point, its tangent `tau` (eqs. 8–9) and the outward normal, in the
/// mandrel frame.
fn frame(p: &PathPoint) -> (Point3<f64>, Vector3<f64>, Vector3<f64>) {
    let PathPoint { z, r, v, alpha, dr } = *p;
    let dr = if dr.is_finite() { dr } else { 0.0 };
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
