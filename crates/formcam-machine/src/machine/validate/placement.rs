//! Where a joint or a solid sits: a plain origin or DH parameters as a
//! transform.

use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

use super::numbers::{finite, unit};
use crate::MachineError;
use crate::file::{DhSpec, LinkSpec, OriginSpec};

/// The transform of a plain origin.
pub(super) fn iso(o: &OriginSpec) -> Isometry3<f64> {
    let [r, p, y] = o.rpy_deg.map(f64::to_radians);
    Isometry3::from_parts(
        Translation3::new(o.xyz[0], o.xyz[1], o.xyz[2]),
        UnitQuaternion::from_euler_angles(r, p, y),
    )
}

/// The transform of DH parameters: `Rz(theta) Tx(a) Tz(d) Rx(alpha)`.
fn dh_post(dh: &DhSpec) -> Isometry3<f64> {
    let rz = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), dh.theta_deg.to_radians());
    let rx = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), dh.alpha_deg.to_radians());
    Isometry3::from_parts(Translation3::identity(), rz)
        * Isometry3::translation(dh.a, 0.0, dh.d)
        * Isometry3::from_parts(Translation3::identity(), rx)
}

/// Where a joint sits and moves: `pre * motion(q) * post`.
pub(super) struct Placement {
    /// Before the motion.
    pub(super) pre: Isometry3<f64>,
    /// The direction of the motion.
    pub(super) direction: Unit<Vector3<f64>>,
    /// After the motion.
    pub(super) post: Isometry3<f64>,
}

/// Where the joint of `l` sits and moves: `pre`, the direction of its
/// motion, `post` (DH parameters: `post`, about or along `z`; a plain
/// origin: `pre`, along `direction`).
pub(super) fn placement(l: &LinkSpec, place: &str) -> Result<Placement, MachineError> {
    match (&l.dh, &l.origin) {
        (Some(_), Some(_)) => Err(MachineError::field(
            place,
            "dh",
            "give either dh or origin, not both",
        )),
        (Some(_), None) if l.direction.is_some() => Err(MachineError::field(
            place,
            "direction",
            "a DH joint moves about/along z; direction goes with origin",
        )),
        (Some(dh), None) => {
            for (f, v) in [
                ("dh.a", dh.a),
                ("dh.alpha_deg", dh.alpha_deg),
                ("dh.d", dh.d),
                ("dh.theta_deg", dh.theta_deg),
            ] {
                finite(v, place, f)?;
            }
            Ok(Placement {
                pre: Isometry3::identity(),
                direction: Vector3::z_axis(),
                post: dh_post(dh),
            })
        }
        (None, o) => {
            let o = o.unwrap_or_default();
            for (i, v) in o.xyz.iter().chain(&o.rpy_deg).enumerate() {
                finite(
                    *v,
                    place,
                    if i < 3 {
                        "origin.xyz"
                    } else {
                        "origin.rpy_deg"
                    },
                )?;
            }
            let dir = match l.direction {
                Some(d) => unit(d, place, "direction")?,
                None => Vector3::z_axis(),
            };
            Ok(Placement {
                pre: iso(&o),
                direction: dir,
                post: Isometry3::identity(),
            })
        }
    }
}
