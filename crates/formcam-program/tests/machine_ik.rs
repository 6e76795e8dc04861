//! Forward and inverse kinematics of the shipped machines.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;

use formcam_geom::{Cylinder, DomeShape, Meridian, Vessel};
use formcam_machine::{IkMethod, IssueKind, Machine, Target, solve};
use formcam_program::{placement_targets, winder_targets};
use formcam_winding::eye::{EyeMode, EyeSpec, eye_trajectory};
use formcam_winding::{Circuit, Ends, LayerSpec, Slippage, plan_layer};

fn machine(name: &str) -> Machine {
    Machine::from_toml(&formcam_testkit::machine_text(name))
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn vessel() -> Vessel {
    Vessel::new(
        100.0,
        300.0,
        (DomeShape::Hemisphere, 30.0),
        (DomeShape::Hemisphere, 30.0),
    )
    .unwrap()
}

fn eye_targets(m: &dyn Meridian, layer_ends: Ends, eye: EyeSpec) -> Vec<Target> {
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: layer_ends,
        dwell_min: std::f64::consts::PI,
        ..LayerSpec::default()
    };
    let layer = plan_layer(&m, &spec).unwrap();
    let t = eye_trajectory(&m, &layer, &eye).unwrap();
    winder_targets(&m, &t)
}

fn vessel_targets(mode: EyeMode, radius: f64, samples: usize) -> Vec<Target> {
    let v = vessel();
    eye_targets(
        &v,
        Ends::Poles {
            start: 30.0,
            end: 30.0,
        },
        EyeSpec {
            mode,
            radius: Some(radius),
            clearance: 20.0,
            l_max: 600.0,
            samples,
            nodes: 400,
            ..EyeSpec::default()
        },
    )
}

/// The payout point by forward kinematics, in the mandrel frame.
fn payout_in_mandrel(m: &Machine, q: &[f64]) -> nalgebra::Point3<f64> {
    let poses = m.poses(q);
    let p = m.key_points(q)[m.roles.payout];
    poses[m.roles.mandrel].inverse_transform_point(&p)
}

fn round_trip(m: &Machine, targets: &[Target], method: IkMethod) -> f64 {
    let track = solve(m, targets, method).unwrap();
    let mut worst: f64 = 0.0;
    for (q, t) in track.rows().zip(targets) {
        worst = worst.max((payout_in_mandrel(m, q) - t.point).norm());
    }
    worst
}

#[test]
fn round_trip_on_the_winders() {
    let two = machine("winder-2axis.toml");
    let targets = vessel_targets(EyeMode::AxisParallel, 250.0, 2001);
    for method in [IkMethod::ClosedForm, IkMethod::Solver] {
        let e = round_trip(&two, &targets, method);
        assert!(e < 1e-9, "2-axis {method:?}: {e}");
    }
    let targets = vessel_targets(EyeMode::PullSpeed, 160.0, 2001);
    for name in ["winder-4axis.toml", "winder-6axis.toml"] {
        let m = machine(name);
        for method in [IkMethod::Auto, IkMethod::Solver] {
            let track = solve(&m, &targets, method).unwrap();
            let e = round_trip(&m, &targets, method);
            assert!(e < 1e-9, "{name} {method:?}: {e}");
            // The eye roller lies across the free band (and along the band's width
            // on the 6-axis machine).
            let ori = track
                .residual_orientation
                .iter()
                .copied()
                .fold(0.0, f64::max);
            assert!(ori < 1e-9, "{name} {method:?}: orientation {ori}");
            assert!(track.issues.is_empty(), "{name}: {:?}", track.issues);
        }
    }
}

#[test]
fn round_trip_on_the_placement_arm() {
    let m = machine("placement-arm.toml");
    let cyl = Cylinder::new(100.0, 400.0).unwrap();
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Tube {
            winding_angle: 45f64.to_radians(),
        },
        dwell_min: std::f64::consts::PI,
        ..LayerSpec::default()
    };
    let layer = plan_layer(&cyl, &spec).unwrap();
    let c = Circuit::new(&cyl, &layer);
    let path: Vec<_> = c
        .points(2000)
        .iter()
        .map(|p| (p.x, p.z, p.r, p.v, p.alpha))
        .collect();
    let targets = placement_targets(&cyl, &path, m.roles.roller_radius);
    let track = solve(&m, &targets, IkMethod::Auto).unwrap();
    assert!(track.issues.is_empty(), "{:?}", track.issues);
    let e = round_trip(&m, &targets, IkMethod::Auto);
    assert!(e < 1e-9, "placement: {e}");
    // The roller presses along the inward normal with its axis across the path.
    for (q, t) in track.rows().zip(&targets) {
        let poses = m.poses(q);
        let head = poses[m.points[m.roles.payout].link];
        let mandrel = poses[m.roles.mandrel];
        let press = head.rotation * m.roles.head_normal.unwrap().into_inner();
        let axis = head.rotation * m.roles.roller_axis.unwrap().into_inner();
        let normal = mandrel.rotation * t.normal.into_inner();
        let band = mandrel.rotation * t.band.into_inner();
        assert!(
            (press + normal).norm() < 1e-9,
            "press {press} normal {normal}"
        );
        assert!(axis.dot(&band).abs() < 1e-9);
    }
}
#[test]
fn closed_forms_equal_the_solver() {
    for (name, targets) in [
        (
            "winder-2axis.toml",
            vessel_targets(EyeMode::AxisParallel, 250.0, 1001),
        ),
        (
            "winder-4axis.toml",
            vessel_targets(EyeMode::PullSpeed, 160.0, 1001),
        ),
        (
            "winder-4axis.toml",
            vessel_targets(EyeMode::Equidistant, 0.0, 1001),
        ),
    ] {
        let m = machine(name);
        let closed = solve(&m, &targets, IkMethod::ClosedForm).unwrap();
        let solver = solve(&m, &targets, IkMethod::Solver).unwrap();
        assert!(closed.closed_form && !solver.closed_form);
        for (a, b) in closed.rows().zip(solver.rows()) {
            for (x, y) in a.iter().zip(b) {
                assert!((x - y).abs() < 1e-9, "{name}: {a:?} vs {b:?}");
            }
        }
    }
}

#[test]
fn machines_without_a_closed_form_say_so() {
    let targets = vessel_targets(EyeMode::PullSpeed, 160.0, 201);
    let m = machine("winder-6axis.toml");
    let e = solve(&m, &targets, IkMethod::ClosedForm).unwrap_err();
    assert!(e.to_string().contains("no closed form"), "{e}");
}

#[test]
fn a_limit_is_reported_at_the_first_point_beyond_it() {
    let text = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../machines/winder-4axis.toml"),
    )
    .unwrap()
    .replace("max_mm = 3000.0", "max_mm = 300.0");
    let m = Machine::from_toml(&text).unwrap();
    let targets = vessel_targets(EyeMode::PullSpeed, 160.0, 2001);
    let track = solve(&m, &targets, IkMethod::Auto).unwrap();
    let x = m.axis("X").unwrap();
    let first = track.rows().position(|q| q[x] > 300.0).unwrap();
    let count = track.rows().filter(|q| q[x] > 300.0 + 1e-9).count();
    let issue = track
        .issues
        .iter()
        .find(|i| i.kind == IssueKind::Limit && i.axis.as_deref() == Some("X"))
        .unwrap();
    assert_eq!(issue.x, targets[first].x);
    assert_eq!(issue.count, count);
    assert!(!track.limits_ok());
}

#[test]
fn an_unreachable_eye_is_reported() {
    // The 2-axis winder's eye runs at 250 mm: an eye line at 200 mm is out of reach.
    let m = machine("winder-2axis.toml");
    let targets = vessel_targets(EyeMode::AxisParallel, 200.0, 401);
    let track = solve(&m, &targets, IkMethod::Auto).unwrap();
    let issue = track
        .issues
        .iter()
        .find(|i| i.kind == IssueKind::Unreachable)
        .unwrap();
    assert_eq!(issue.count, targets.len());
    assert!((track.max_residual_mm() - 50.0).abs() < 1e-9);
}

#[test]
fn an_eye_too_close_to_the_mandrel_is_reported() {
    // An eye line at 125 mm keeps only 25 mm from the 100 mm cylinder: less than
    // the clearance of 30 mm asked for.
    let v = vessel();
    let targets = eye_targets(
        &v,
        Ends::Poles {
            start: 30.0,
            end: 30.0,
        },
        EyeSpec {
            mode: EyeMode::AxisParallel,
            radius: Some(125.0),
            clearance: 30.0,
            l_max: 2000.0,
            samples: 1001,
            ..EyeSpec::default()
        },
    );
    let m = machine("winder-4axis.toml");
    let track = solve(&m, &targets, IkMethod::Auto).unwrap();
    let close = targets
        .iter()
        .filter(|t| t.clearance_margin < -1e-6)
        .count();
    let issue = track
        .issues
        .iter()
        .find(|i| i.kind == IssueKind::Clearance)
        .unwrap();
    assert!(close > 0);
    assert_eq!(issue.count, close);
    let first = targets.iter().find(|t| t.clearance_margin < -1e-6).unwrap();
    assert_eq!(issue.x, first.x);
}
