//! Layers on every mandrel shape: Clairaut's relation, polar bosses, tube
//! patterns, and properties over random vessels.

#![allow(clippy::unwrap_used)]

mod common;

use common::{Waist, vessel};

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use formcam_geom::{Cylinder, DomeShape, Meridian, Tabulated, Vessel};
use formcam_winding::{Ends, LayerSpec, Method, PassEnd, Slippage, plan_layer};
use proptest::prelude::*;

fn geodesic(start: f64, end: f64) -> LayerSpec {
    LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Poles { start, end },
        ..LayerSpec::default()
    }
}

#[test]
fn geodesics_keep_clairaut_constant_on_every_dome() {
    for shape in [
        DomeShape::Hemisphere,
        DomeShape::Ellipsoid { axis_ratio: 0.55 },
        DomeShape::Torispherical {
            crown_radius: 180.0,
            knuckle_radius: 20.0,
        },
        DomeShape::Isotensoid,
    ] {
        let v = Vessel::new(100.0, 250.0, (shape, 28.0), (shape, 28.0)).unwrap();
        let layer = plan_layer(&v, &geodesic(28.0, 28.0)).unwrap();
        for p in &layer.points {
            assert!(
                (p.c - 28.0).abs() < 1e-9,
                "{shape:?}: C = {} at z = {}",
                p.c,
                p.z
            );
            assert!(p.alpha >= 0.0 && p.alpha <= FRAC_PI_2 + 1e-12);
        }
        // The turn angle grows monotonically and the path length is consistent.
        for w in layer.points.windows(2) {
            assert!(w[1].v >= w[0].v - 1e-12 && w[1].s > w[0].s);
        }
        assert!(layer.warnings.is_empty(), "{shape:?}: {:?}", layer.warnings);
    }
}

#[test]
fn isotensoid_passes_finish_on_the_polar_boss() {
    let v = Vessel::new(
        120.0,
        400.0,
        (DomeShape::Isotensoid, 35.0),
        (DomeShape::Isotensoid, 35.0),
    )
    .unwrap();
    let r_end = v.start_dome().end_radius();
    assert!(r_end > 35.0 && r_end < 35.5);
    let layer = plan_layer(&v, &geodesic(35.0, 35.0)).unwrap();
    let alpha_end = (35.0 / r_end).asin();
    let PassEnd::Exit { alpha, .. } = layer.pass.end else {
        panic!(
            "the isotensoid meridian ends above the opening: {:?}",
            layer.pass.end
        )
    };
    assert!((alpha - alpha_end).abs() < 1e-9);
    // The boss adds the straight geodesic on its face: pi/2 - alpha at each end.
    assert!((layer.pass.turn_angle_boss_rad - 2.0 * (FRAC_PI_2 - alpha_end)).abs() < 1e-9);
    assert!(
        (layer.report.turn_angle_pass_rad
            - layer.pass.turn_angle_surface_rad
            - layer.pass.turn_angle_boss_rad)
            .abs()
            < 1e-12
    );
    // The isotensoid carries its geodesic without bridging.
    assert!(layer.pass.bridging_margin_mm.unwrap() > 0.0);
}

#[test]
fn tube_pattern_closes_with_the_dwell() {
    let cyl = Cylinder::new(50.0, 600.0).unwrap();
    let alpha = 55f64.to_radians();
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Tube {
            winding_angle: alpha,
        },
        band_width: 8.0,
        dwell_min: PI,
        ..LayerSpec::default()
    };
    let layer = plan_layer(&cyl, &spec).unwrap();
    let pass_turn = 600.0 * alpha.tan() / 50.0;
    assert!((layer.report.turn_angle_pass_rad - pass_turn).abs() < 1e-9);
    let pat = layer.pattern;
    assert_eq!(pat.circuits, (TAU * 50.0 * alpha.cos() / 8.0).ceil() as u32);
    assert!(
        pat.dwell_rad >= TAU - 1e-12,
        "two half-turn dwells at least"
    );
    let total = layer
        .report
        .turn_angle_circuit_with_dwell_rad
        .rem_euclid(TAU);
    let target = TAU * f64::from(pat.step) / f64::from(pat.circuits);
    let d = (total - target).rem_euclid(TAU);
    assert!(
        !(1e-9..=TAU - 1e-9).contains(&d),
        "circuit turn {total} vs band position {target}"
    );
    // Thickness: two plies of n bands over the circumference.
    let t = 2.0 * 0.5 * f64::from(pat.circuits) * 8.0 / (TAU * 50.0 * alpha.cos());
    assert!((layer.report.thickness_equator_mm - t).abs() < 1e-12);
    // A tube has no turn-around on the mandrel: the thickness is the same all along.
    assert!((layer.report.thickness_max_mm - t).abs() < 1e-9);
    assert!(layer.thickness.iter().all(|x| (x - t).abs() < 1e-9));
    // Fibre length: n circuits of two helices plus the two turn-arounds on the tube's
    // extension, where alpha sweeps through 90 deg while the mandrel turns the dwell.
    let helix = 600.0 / alpha.cos();
    let sweep = 0.5 * pat.dwell_rad * 50.0 * (PI - 2.0 * alpha) / (2.0 * alpha.cos());
    let expect = f64::from(pat.circuits) * (2.0 * helix + 2.0 * sweep);
    assert!((layer.report.fibre_length_mm - expect).abs() < 1e-6 * expect);
}

#[test]
fn tabulated_waist_agrees_with_the_analytic_one() {
    let len = 300.0;
    let r =
        |z: f64| 40.0 + 60.0 * (PI * z / len).sin() - 15.0 * (-((z - 150.0) / 40.0).powi(2)).exp();
    let pts: Vec<(f64, f64)> = (0..=300).map(|i| (i as f64, r(i as f64))).collect();
    let t = Tabulated::new(&pts, 0.0).unwrap();
    let spec = LayerSpec {
        slippage: Slippage::Minimax,
        ends: Ends::Poles {
            start: t.r(0.0),
            end: t.r(len),
        },
        mu_limit: 3.0,
        ..LayerSpec::default()
    };
    let layer = plan_layer(&t, &spec).unwrap();
    assert_eq!(layer.pass.method, Method::Minimax);
    assert!(!layer.pass.bridging_active.is_empty());
    let (a, b) = layer.pass.bridging_active[0];
    assert!(
        a <= 150.5 && b >= 149.5,
        "bridging binds at the waist: {a}..{b}"
    );
    // The analytic waist of the same shape gives the same optimum.
    let analytic = formcam_winding::minimax(&Waist { len: 300.0 }, 4000, 3.0).unwrap();
    assert!(
        (layer.pass.mu_max_abs - analytic.mu_max).abs() < 1e-2 * analytic.mu_max,
        "{} vs {}",
        layer.pass.mu_max_abs,
        analytic.mu_max
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn hemisphere_vessels_turn_two_pi_plus_helix(
        radius in 40.0f64..300.0,
        len in 0.0f64..800.0,
        ratio in 0.1f64..0.8,
    ) {
        let rp = ratio * radius;
        let v = Vessel::new(radius, len, (DomeShape::Hemisphere, rp), (DomeShape::Hemisphere, rp)).unwrap();
        let layer = plan_layer(&v, &geodesic(rp, rp)).unwrap();
        let alpha = ratio.asin();
        let expect = TAU + 2.0 * len * alpha.tan() / radius;
        prop_assert!((layer.report.turn_angle_circuit_rad - expect).abs() < 1e-9);
        prop_assert!((layer.report.alpha_equator_rad - alpha).abs() < 1e-9);
    }

    #[test]
    fn nongeodesic_cylinders_follow_the_closed_form(
        radius in 20.0f64..200.0,
        alpha0 in 0.2f64..1.2,
        mu in -0.2f64..0.2,
    ) {
        let len = 100.0;
        // Keep the path on the tube: sin(alpha) must stay below 1.
        let inv_end = 1.0 / alpha0.sin() - mu * len / radius;
        prop_assume!(inv_end > 1.05);
        let cyl = Cylinder::new(radius, len).unwrap();
        let spec = LayerSpec {
            slippage: Slippage::Constant(mu),
            ends: Ends::Tube { winding_angle: alpha0 },
            dwell_min: 0.0,
            ..LayerSpec::default()
        };
        let layer = plan_layer(&cyl, &spec).unwrap();
        for p in layer.points.iter().step_by(50) {
            let inv = 1.0 / alpha0.sin() - mu * p.z / radius;
            prop_assert!((1.0 / p.alpha.sin() - inv).abs() < 1e-9);
        }
    }
}

/// A meridian that is flat where the pass should start: no band can leave it.
struct FlatStart;

impl Meridian for FlatStart {
    fn z_range(&self) -> (f64, f64) {
        (0.0, 100.0)
    }
    fn eval(&self, z: f64) -> formcam_geom::Jet {
        let u = z / 100.0;
        formcam_geom::Jet {
            r: 60.0 - 30.0 * u * u,
            dr: -0.6 * u,
            d2r: -0.006,
        }
    }
}

#[test]
fn a_pass_that_cannot_leave_its_start_is_refused() {
    let spec = LayerSpec {
        slippage: Slippage::Constant(0.05),
        ends: Ends::Poles {
            start: 60.0,
            end: 30.0,
        },
        ..LayerSpec::default()
    };
    let e = plan_layer(&FlatStart, &spec).unwrap_err();
    assert!(e.to_string().contains("winding.mu"), "{e}");
    assert!(e.to_string().contains("start opening"), "{e}");
}

fn poles(slippage: Slippage, start: f64, end: f64) -> LayerSpec {
    LayerSpec {
        slippage,
        ends: Ends::Poles { start, end },
        ..LayerSpec::default()
    }
}

#[test]
fn given_slippage_must_meet_the_far_opening() {
    // Turns early: the band never reaches the far opening.
    let e = plan_layer(
        &vessel(30.0, 30.0),
        &poles(Slippage::Constant(0.5), 30.0, 30.0),
    )
    .unwrap_err();
    assert!(
        e.to_string().contains("before the far polar opening"),
        "{e}"
    );
    // Reaches the far opening below 90 degrees: it would leave the mandrel.
    let e = plan_layer(
        &vessel(30.0, 45.0),
        &poles(Slippage::Constant(-0.05), 30.0, 45.0),
    )
    .unwrap_err();
    assert!(e.to_string().contains("winding.mu"), "{e}");
    let segs = vec![formcam_winding::MuSegment {
        z_from: 0.0,
        z_to: 30.0,
        mu: -0.02,
    }];
    let e = plan_layer(
        &vessel(30.0, 30.0),
        &poles(Slippage::Segments(segs), 30.0, 30.0),
    )
    .unwrap_err();
    assert!(e.to_string().contains("winding.mu_segments"), "{e}");
    // A negative Clairaut function (the turn would reverse) is refused.
    let e = plan_layer(
        &vessel(5.0, 5.0),
        &poles(Slippage::Constant(-0.05), 5.0, 5.0),
    )
    .unwrap_err();
    assert!(e.to_string().contains("negative"), "{e}");
}

#[test]
fn segments_must_lie_on_the_mandrel_and_not_overlap() {
    use formcam_winding::MuSegment;
    let v = vessel(30.0, 30.0);
    let outside = vec![MuSegment {
        z_from: 1000.0,
        z_to: 2000.0,
        mu: 0.1,
    }];
    let e = plan_layer(&v, &poles(Slippage::Segments(outside), 30.0, 30.0)).unwrap_err();
    assert!(e.to_string().contains("outside the mandrel"), "{e}");
    let overlap = vec![
        MuSegment {
            z_from: 0.0,
            z_to: 50.0,
            mu: 0.1,
        },
        MuSegment {
            z_from: 40.0,
            z_to: 60.0,
            mu: 0.1,
        },
    ];
    let e = plan_layer(&v, &poles(Slippage::Segments(overlap), 30.0, 30.0)).unwrap_err();
    assert!(e.to_string().contains("overlap"), "{e}");
}

#[test]
fn minimax_refuses_flat_ends_and_honours_tiny_limits() {
    // A cylinder given as a meridian between openings: no turn-around at its ends.
    let flat = Cylinder::new(50.0, 300.0).unwrap();
    let e = plan_layer(&flat, &poles(Slippage::Minimax, 50.0, 50.0)).unwrap_err();
    assert!(e.to_string().contains("narrow"), "{e}");
    // A limit below the first trial of the search is still a limit.
    let mut spec = poles(Slippage::Minimax, 30.0, 30.1);
    spec.mu_limit = 1e-5;
    let e = plan_layer(&vessel(30.0, 30.1), &spec).unwrap_err();
    assert!(e.to_string().contains("winding.mu_limit"), "{e}");
    // Nearly equal openings: the optimum matches shooting (no artefact at the ends).
    spec.mu_limit = 0.6;
    let layer = plan_layer(&vessel(30.0, 30.1), &spec).unwrap();
    let shot = formcam_winding::shoot(&vessel(30.0, 30.1), 0.6).unwrap();
    assert!(
        (layer.pass.mu_max_abs - shot.mu.abs()).abs() < 1e-2 * shot.mu.abs(),
        "{} vs {}",
        layer.pass.mu_max_abs,
        shot.mu
    );
}

#[test]
fn the_report_does_not_depend_on_the_number_of_samples() {
    let v = vessel(30.0, 30.0);
    let mut spec = geodesic(30.0, 30.0);
    let full = plan_layer(&v, &spec).unwrap();
    spec.samples = 2;
    let two = plan_layer(&v, &spec).unwrap();
    assert_eq!(two.points.len(), 2);
    assert_eq!(full.report, two.report);
    assert_eq!(full.pattern, two.pattern);
}
