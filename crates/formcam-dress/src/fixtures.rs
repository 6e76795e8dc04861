//! The published wheel and dresser of the bundled example, for unit tests.

use crate::{Dresser, DresserSpec, Profile, WheelSpec};

/// The example's wheel.
pub(crate) fn wheel() -> WheelSpec {
    WheelSpec {
        ball_radius: 1.85,
        contact_angle: 45f64.to_radians(),
        r1: 1.937,
        r2: 0.296,
        width: 6.0,
        flank_tilt: 10f64.to_radians(),
        arc_angle: 0.2618,
    }
}

/// The example's dresser.
pub(crate) fn dresser_spec() -> DresserSpec {
    DresserSpec {
        width: 2.9,
        corner_radius_left: 0.258,
        corner_radius_right: 0.279,
        yo: None,
    }
}

/// The example's profile.
#[allow(clippy::unwrap_used)]
pub(crate) fn profile() -> Profile {
    Profile::new(&wheel()).unwrap()
}

/// The example's profile and dresser.
#[allow(clippy::unwrap_used)]
pub(crate) fn setup() -> (Profile, Dresser) {
    let p = profile();
    let d = Dresser::new(&dresser_spec(), &p).unwrap();
    (p, d)
}
