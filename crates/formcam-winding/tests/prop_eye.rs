//! Property: every eye point lies on the tangent line of the path at its
//! contact point, ahead of it by the free length, and where its mode puts
//! it. Random vessels (hemispherical domes, equal openings, cylinder lengths) and
//! tubes (winding angles), every eye mode:
//!
//! * the eye's distance from the line `path point + t tau` (eqs. 8-9 at the
//!   circuit point of the same `x`) is below 1e-9 of the mandrel's size, and
//!   `t` is the free length `l >= 0` (the eye lies ahead along the band);
//! * axis-parallel: the eye's radius is the line's, to 1e-9 relative;
//! * user curve (a straight line `R = a + b Z`, `|b| <= 0.02`): the eye lies on it, to
//!   1e-9 relative;
//! * equidistant: the eye lies on the clearance zone's edge (`margin` within
//!   the zone's tabulation, 1e-3 of the clearance below and 1e-2 above, as
//!   `tests/eye.rs` measures it against the meridian);
//! * pull-speed optimum: the eye keeps the clearance (`margin >= -1e-6 mm`)
//!   and the largest free length.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use std::f64::consts::PI;

use formcam_geom::{Cylinder, DomeShape, Meridian, Vessel};
use formcam_winding::eye::{EyeMode, EyeSpec, EyeTrajectory, eye_trajectory};
use formcam_winding::{Circuit, Ends, Layer, LayerSpec, Slippage, plan_layer};
use proptest::prelude::*;

/// A random mandrel and its layer: a hemisphere vessel with polar openings,
/// or a tube wound at a constant angle.
#[derive(Debug, Clone)]
enum Mandrel {
    Vessel {
        radius: f64,
        length: f64,
        openings: (f64, f64),
    },
    Tube {
        radius: f64,
        length: f64,
        angle_deg: f64,
    },
}

fn mandrel() -> impl Strategy<Value = Mandrel> {
    prop_oneof![
        // A geodesic needs equal openings.
        (60.0f64..150.0, 50.0f64..400.0, 0.2f64..0.45).prop_map(|(radius, length, a)| {
            Mandrel::Vessel {
                radius,
                length,
                openings: (a * radius, a * radius),
            }
        }),
        (30.0f64..150.0, 100.0f64..500.0, 20.0f64..70.0).prop_map(|(radius, length, angle_deg)| {
            Mandrel::Tube {
                radius,
                length,
                angle_deg,
            }
        }),
    ]
}

/// The mandrel as a meridian, its largest radius and its layer.
fn plan(m: &Mandrel) -> (Box<dyn Meridian>, f64, Layer) {
    match *m {
        Mandrel::Vessel {
            radius,
            length,
            openings,
        } => {
            let v = Vessel::new(
                radius,
                length,
                (DomeShape::Hemisphere, openings.0),
                (DomeShape::Hemisphere, openings.1),
            )
            .unwrap();
            let spec = LayerSpec {
                slippage: Slippage::Geodesic,
                ends: Ends::Poles {
                    start: openings.0,
                    end: openings.1,
                },
                ..LayerSpec::default()
            };
            let layer = plan_layer(&v, &spec).expect("a geodesic layer");
            (Box::new(v), radius, layer)
        }
        Mandrel::Tube {
            radius,
            length,
            angle_deg,
        } => {
            let c = Cylinder::new(radius, length).unwrap();
            let spec = LayerSpec {
                slippage: Slippage::Geodesic,
                ends: Ends::Tube {
                    winding_angle: angle_deg.to_radians(),
                },
                dwell_min: PI,
                ..LayerSpec::default()
            };
            let layer = plan_layer(&c, &spec).unwrap();
            (Box::new(c), radius, layer)
        }
    }
}

/// The eye's distance from the tangent line of its circuit point and how
/// far along the line it lies.
fn off_tangent<M: Meridian>(
    circuit: &Circuit<'_, M>,
    e: &formcam_winding::eye::EyePoint,
) -> (f64, f64) {
    let p = circuit.at(e.x);
    let (sv, cv) = p.v.sin_cos();
    let (sa, ca) = p.alpha.sin_cos();
    let q = (1.0 + p.dr * p.dr).sqrt();
    let tau = [
        p.dr * cv * ca / q - sv * sa,
        p.dr * sv * ca / q + cv * sa,
        ca / q,
    ];
    let (se, ce) = e.eye_v.sin_cos();
    let d = [
        e.eye_r * ce - p.r * cv,
        e.eye_r * se - p.r * sv,
        e.eye_z - p.z,
    ];
    let t = d[0] * tau[0] + d[1] * tau[1] + d[2] * tau[2];
    let off = (0..3)
        .map(|k| (d[k] - t * tau[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    (off, t)
}

/// Checks every point of `eye` against its tangent line and returns the
/// number of points.
fn on_tangents<M: Meridian>(
    circuit: &Circuit<'_, M>,
    eye: &EyeTrajectory,
    size: f64,
    mode: EyeMode,
) -> Result<usize, TestCaseError> {
    for e in &eye.points {
        let (off, t) = off_tangent(circuit, e);
        prop_assert!(
            off <= 1e-9 * size,
            "{:?}: {} mm off the tangent at x = {}",
            mode,
            off,
            e.x
        );
        prop_assert!(
            (t - e.l).abs() <= 1e-9 * size && e.l >= 0.0,
            "{:?}: {} along the tangent, l = {} at x = {}",
            mode,
            t,
            e.l,
            e.x
        );
    }
    Ok(eye.points.len())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn eye_points_lie_on_their_tangent_lines(
        m in mandrel(),
        gap in 0.2f64..1.0,
        clearance in 5.0f64..30.0,
        slope in -0.02f64..0.02,
    ) {
        let (meridian, radius, layer) = plan(&m);
        let meridian = meridian.as_ref();
        let circuit = Circuit::new(&meridian, &layer);
        let size = radius.max(meridian.z_range().1 - meridian.z_range().0);
        let line = radius + clearance + gap * radius;
        let (za, zb) = meridian.z_range();
        let zm = 0.5 * (za + zb);
        let curve_r = |z: f64| line + slope * (z - zm);
        let base = EyeSpec {
            clearance,
            l_max: 20.0 * size,
            samples: 401,
            nodes: 120,
            ..EyeSpec::default()
        };
        // The curve spans where an eye at the line's radius goes (on a short,
        // wide tube wound shallow it leads the band far past the mandrel's
        // ends), with a mandrel's size to spare for the slope.
        let parallel = eye_trajectory(
            &meridian,
            &layer,
            &EyeSpec { mode: EyeMode::AxisParallel, radius: Some(line), ..base.clone() },
        )
        .map_err(|e| TestCaseError::fail(format!("axis-parallel: {e}")))?;
        let (zlo, zhi) = parallel
            .points
            .iter()
            .fold((za, zb), |(lo, hi), e| (lo.min(e.eye_z), hi.max(e.eye_z)));
        let (z0, z1) = ((za - 4.0 * size).min(zlo - size), (zb + 4.0 * size).max(zhi + size));
        let curve = vec![(z0, curve_r(z0)), (z1, curve_r(z1))];
        for mode in [EyeMode::AxisParallel, EyeMode::Curve, EyeMode::Equidistant, EyeMode::PullSpeed] {
            let spec = EyeSpec {
                mode,
                radius: Some(line),
                curve: if mode == EyeMode::Curve { curve.clone() } else { Vec::new() },
                ..base.clone()
            };
            let eye = eye_trajectory(&meridian, &layer, &spec)
                .map_err(|e| TestCaseError::fail(format!("{mode:?}: {e}")))?;
            prop_assert!(on_tangents(&circuit, &eye, size, mode)? > 100);
            for e in &eye.points {
                match mode {
                    EyeMode::AxisParallel => prop_assert!(
                        (e.eye_r - line).abs() <= 1e-9 * line,
                        "radius {} vs {}", e.eye_r, line
                    ),
                    EyeMode::Curve => {
                        let want = curve_r(e.eye_z);
                        prop_assert!(
                            (e.eye_r - want).abs() <= 1e-9 * line,
                            "curve: R {} vs {} at Z {}", e.eye_r, want, e.eye_z
                        );
                    }
                    EyeMode::Equidistant => prop_assert!(
                        e.margin >= -1e-3 * clearance && e.margin <= 1e-2 * clearance,
                        "equidistant: margin {} at x = {}", e.margin, e.x
                    ),
                    EyeMode::PullSpeed => prop_assert!(
                        e.margin >= -1e-6 && e.l <= spec.l_max * (1.0 + 1e-9),
                        "pull-speed: margin {}, l {} at x = {}", e.margin, e.l, e.x
                    ),
                }
            }
        }
    }
}
