//! The prepared forward kinematics against the reference (`Machine::poses`),
//! the residuals the inverse kinematics reports against the reference forward
//! kinematics, and the band past the key points against the key points.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use formcam_geom::{Cylinder, DomeShape, Vessel};
use formcam_machine::shipped::{names, shipped};
use formcam_machine::{
    AxisTrack, Fk, IkMethod, Machine, MachineKind, ORIENTATION_SCALE, Target, band_passed, solve,
};
use formcam_program::{placement_targets, winder_targets};
use formcam_winding::eye::{EyeMode, EyeSpec, eye_trajectory};
use formcam_winding::{Circuit, Ends, LayerSpec, Slippage, plan_layer};
use nalgebra::Isometry3;
use proptest::prelude::*;

fn machines() -> Vec<(&'static str, Machine)> {
    names()
        .map(|n| (n, shipped(n).unwrap().machine().unwrap()))
        .collect()
}

/// The largest difference between two poses: translation (mm) and rotation
/// matrix entries.
fn difference(a: &Isometry3<f64>, b: &Isometry3<f64>) -> f64 {
    let t = (a.translation.vector - b.translation.vector).amax();
    let r = (a.rotation.to_rotation_matrix().into_inner()
        - b.rotation.to_rotation_matrix().into_inner())
    .amax();
    t.max(r)
}

/// Axis values from unit numbers: rotary axes over several turns either
/// way, prismatic ones over a few metres.
fn axes(m: &Machine, u: &[f64]) -> Vec<f64> {
    m.axes
        .iter()
        .zip(u.iter().cycle())
        .map(|(a, &u)| if a.is_rotary() { 20.0 * u } else { 2000.0 * u })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Every link of every shipped machine, and each key point's chain alone,
    /// placed by the prepared forward kinematics where the reference places it.
    #[test]
    fn prepared_fk_equals_the_reference(u in proptest::collection::vec(-1.0f64..1.0, 6)) {
        for (name, m) in machines() {
            let q = axes(&m, &u);
            let reference = m.poses(&q);
            let mut out = Vec::new();
            Fk::new(&m).poses_into(&q, &mut out);
            prop_assert_eq!(out.len(), reference.len());
            for (i, (a, b)) in out.iter().zip(&reference).enumerate() {
                prop_assert!(difference(a, b) <= 1e-9, "{}: link {}", name, i);
            }
            for p in &m.points {
                let fk = Fk::for_links(&m, &[p.link]);
                // The buffer reused from the full evaluation, as a caller would.
                fk.poses_into(&q, &mut out);
                let at = out[p.link] * p.position;
                let want = reference[p.link] * p.position;
                prop_assert!((at - want).amax() <= 1e-9, "{}: point {}", name, p.name);
            }
        }
    }
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

fn eye_targets(mode: EyeMode, radius: f64) -> Vec<Target> {
    let v = vessel();
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Poles {
            start: 30.0,
            end: 30.0,
        },
        dwell_min: std::f64::consts::PI,
        ..LayerSpec::default()
    };
    let layer = plan_layer(&v, &spec).unwrap();
    let eye = EyeSpec {
        mode,
        radius: Some(radius),
        clearance: 20.0,
        l_max: 600.0,
        samples: 801,
        nodes: 400,
        ..EyeSpec::default()
    };
    winder_targets(&v, &eye_trajectory(&v, &layer, &eye).unwrap())
}

fn placement(m: &Machine) -> Vec<Target> {
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
    let path: Vec<_> = Circuit::new(&cyl, &layer)
        .points(800)
        .iter()
        .map(|p| (p.x, p.z, p.r, p.v, p.alpha))
        .collect();
    placement_targets(&cyl, &path, m.roles.roller_radius)
}

/// The residuals of one point by the reference forward kinematics: the
/// payout point's distance from the target (mm) and the largest cosine of
/// the orientation equations (eq. 2, docs/machines.md).
fn reference_residual(m: &Machine, q: &[f64], t: &Target) -> (f64, f64) {
    let poses = m.poses(q);
    let r = &m.roles;
    let head = poses[m.points[r.payout].link];
    let mandrel = poses[r.mandrel];
    let p = head * m.points[r.payout].position;
    let pos = (p - mandrel * t.point).norm();
    let band = mandrel.rotation * t.band.into_inner();
    let normal = mandrel.rotation * t.normal.into_inner();
    let roller = r.roller_axis.map(|a| head.rotation * a.into_inner());
    let mut cosines = Vec::new();
    match r.kind {
        MachineKind::Winder => {
            let rows = m.axes.len().saturating_sub(3).min(2);
            if let Some(a) = roller {
                cosines.extend([a.dot(&band), a.dot(&normal)].into_iter().take(rows));
            }
        }
        MachineKind::Placement => {
            let n = head.rotation * r.head_normal.unwrap().into_inner();
            cosines.push(n.dot(&band));
            cosines.push(n.dot(&normal.cross(&band)));
            cosines.extend(roller.map(|a| a.dot(&band)));
        }
    }
    let ori = cosines.iter().map(|c| c.abs()).fold(0.0, f64::max);
    (pos, ori)
}

fn assert_residuals_are_the_reference(name: &str, m: &Machine, targets: &[Target], t: &AxisTrack) {
    assert_eq!(t.residual_mm.len(), targets.len(), "{name}");
    assert_eq!(t.residual_orientation.len(), targets.len(), "{name}");
    for (i, (q, tg)) in t.rows().zip(targets).enumerate() {
        let (pos, ori) = reference_residual(m, q, tg);
        assert!(
            (t.residual_mm[i] - pos).abs() <= 1e-9,
            "{name}: point {i}: {} reported, {pos} by FK",
            t.residual_mm[i]
        );
        // The solver weighs the cosines by ORIENTATION_SCALE; the report does not.
        assert!(
            (t.residual_orientation[i] - ori).abs() <= 1e-9 / ORIENTATION_SCALE,
            "{name}: point {i}: {} reported, {ori} by FK",
            t.residual_orientation[i]
        );
    }
}

/// The residuals reported are what the reference forward kinematics gives, on
/// reachable trajectories and on one out of reach (the 2-axis winder's eye
/// runs at 250 mm, the eye line at 200 mm: 50 mm at every point), by the
/// closed form and by the solver.
#[test]
fn reported_residuals_are_what_fk_gives() {
    let reachable = eye_targets(EyeMode::PullSpeed, 160.0);
    let out_of_reach = eye_targets(EyeMode::AxisParallel, 200.0);
    for (name, m) in machines() {
        let cases: Vec<(Vec<Target>, IkMethod)> = match m.roles.kind {
            MachineKind::Placement => vec![(placement(&m), IkMethod::Auto)],
            MachineKind::Winder => [&reachable, &out_of_reach]
                .into_iter()
                .flat_map(|t| {
                    [IkMethod::Auto, IkMethod::Solver]
                        .into_iter()
                        .map(|k| (t.clone(), k))
                })
                .collect(),
        };
        for (targets, method) in cases {
            let track = solve(&m, &targets, method).unwrap();
            assert_residuals_are_the_reference(&format!("{name} {method:?}"), &m, &targets, &track);
        }
    }
    let two = shipped("winder-2axis").unwrap().machine().unwrap();
    let track = solve(&two, &out_of_reach, IkMethod::Auto).unwrap();
    assert!((track.max_residual_mm() - 50.0).abs() < 1e-9);
}

/// The band past each key point, read from its flat rows, is the growth of
/// the band path's length (by the key points) plus the band laid and the
/// growth of the free length.
#[test]
fn band_passed_follows_the_key_points() {
    let targets = eye_targets(EyeMode::PullSpeed, 160.0);
    for (name, m) in machines() {
        if m.roles.kind != MachineKind::Winder {
            continue;
        }
        let track = solve(&m, &targets, IkMethod::Auto).unwrap();
        let passed = band_passed(&m, &targets, &track);
        let path = &m.roles.band_path;
        assert_eq!(passed.len(), targets.len(), "{name}");
        assert_eq!(passed.width, path.len(), "{name}");
        let along = |q: &[f64], t: &Target| -> Vec<f64> {
            let k = m.key_points(q);
            (0..path.len())
                .map(|i| {
                    let run: f64 = path[i..]
                        .windows(2)
                        .map(|w| (k[w[1]] - k[w[0]]).norm())
                        .sum();
                    run + t.free_length + t.x
                })
                .collect()
        };
        let start = along(track.row(0), &targets[0]);
        for (i, row) in passed.rows().enumerate() {
            let want = along(track.row(i), &targets[i]);
            for (c, v) in row.iter().enumerate() {
                let w = want[c] - start[c];
                assert!((v - w).abs() <= 1e-9 * (1.0 + w.abs()), "{name}: row {i}");
            }
        }
        assert_eq!(passed.last(), passed.rows().last(), "{name}");
    }
}
