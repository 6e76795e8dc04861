//! Where a joint or a solid sits: a plain origin or DH parameters as a
//! transform.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use crate::file::{DhSpec, OriginSpec};

pub(super) fn iso(o: &OriginSpec) -> Isometry3<f64> {
    let [r, p, y] = o.rpy_deg.map(f64::to_radians);
    Isometry3::from_parts(
        Translation3::new(o.xyz[0], o.xyz[1], o.xyz[2]),
        UnitQuaternion::from_euler_angles(r, p, y),
    )
}

pub(super) fn dh_post(dh: &DhSpec) -> Isometry3<f64> {
    let rz = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), dh.theta_deg.to_radians());
    let rx = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), dh.alpha_deg.to_radians());
    Isometry3::from_parts(Translation3::identity(), rz)
        * Isometry3::translation(dh.a, 0.0, dh.d)
        * Isometry3::from_parts(Translation3::identity(), rx)
}
