//! The payout-eye trajectory: closed forms, geometry, constraints and the optimum.

#![allow(clippy::unwrap_used)]

mod common;

use std::f64::consts::PI;

use common::vessel;
use formcam_geom::{Cylinder, Meridian};
use formcam_winding::eye::{
    Constraint, EyeMode, EyeSpec, axis_parallel_length, eye_at, eye_trajectory,
};
use formcam_winding::{Circuit, Ends, LayerSpec, Slippage, plan_layer};

fn tube_layer(m: &dyn Meridian, deg: f64) -> formcam_winding::Layer {
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Tube {
            winding_angle: deg.to_radians(),
        },
        dwell_min: PI,
        ..LayerSpec::default()
    };
    plan_layer(&m, &spec).unwrap()
}

fn vessel_layer(v: &formcam_geom::Vessel) -> formcam_winding::Layer {
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Poles {
            start: 30.0,
            end: 30.0,
        },
        ..LayerSpec::default()
    };
    plan_layer(v, &spec).unwrap()
}

#[test]
fn cylinder_axis_parallel_matches_the_closed_form() {
    let cyl = Cylinder::new(50.0, 400.0).unwrap();
    let layer = tube_layer(&cyl, 40.0);
    let spec = EyeSpec {
        mode: EyeMode::AxisParallel,
        radius: Some(90.0),
        clearance: 10.0,
        l_max: 2000.0,
        samples: 4001,
        ..EyeSpec::default()
    };
    let eye = eye_trajectory(&cyl, &layer, &spec).unwrap();
    let mut checked = 0;
    for p in &eye.points {
        // On the outgoing pass (alpha = 40 deg, z inside the tube).
        if (p.alpha - 40f64.to_radians()).abs() < 1e-12 && p.z < 399.0 {
            let l = (90.0f64 * 90.0 - 50.0 * 50.0).sqrt() / p.alpha.sin();
            assert!((p.l - l).abs() < 1e-9, "l {} vs {l}", p.l);
            assert!((p.eye_z - (p.z + l * p.alpha.cos())).abs() < 1e-9);
            assert!((p.eye_r - 90.0).abs() < 1e-9);
            checked += 1;
        }
    }
    assert!(checked > 1000, "{checked}");
}

#[test]
fn every_eye_point_lies_on_the_tangent_of_its_path_point() {
    let v = vessel(30.0, 30.0);
    let layer = vessel_layer(&v);
    let circuit = Circuit::new(&v, &layer);
    for mode in [
        EyeMode::AxisParallel,
        EyeMode::Equidistant,
        EyeMode::PullSpeed,
    ] {
        let spec = EyeSpec {
            mode,
            radius: Some(160.0),
            l_max: 600.0,
            nodes: 400,
            ..EyeSpec::default()
        };
        let eye = eye_trajectory(&v, &layer, &spec).unwrap();
        for e in &eye.points {
            let p = circuit.at(e.x);
            // Path point and tangent in Cartesian coordinates (eqs. 8-9).
            let (sv, cv) = p.v.sin_cos();
            let q = (1.0 + p.dr * p.dr).sqrt();
            let tau = [
                (p.dr * cv) * p.alpha.cos() / q - sv * p.alpha.sin(),
                (p.dr * sv) * p.alpha.cos() / q + cv * p.alpha.sin(),
                p.alpha.cos() / q,
            ];
            let base = [p.r * cv, p.r * sv, p.z];
            let eye_xyz = [e.eye_r * e.eye_v.cos(), e.eye_r * e.eye_v.sin(), e.eye_z];
            let d = [
                eye_xyz[0] - base[0],
                eye_xyz[1] - base[1],
                eye_xyz[2] - base[2],
            ];
            // Distance from the line base + t tau.
            let t = d[0] * tau[0] + d[1] * tau[1] + d[2] * tau[2];
            let off = ((d[0] - t * tau[0]).powi(2)
                + (d[1] - t * tau[1]).powi(2)
                + (d[2] - t * tau[2]).powi(2))
            .sqrt();
            assert!(
                off < 1e-9,
                "{mode:?}: {off} mm off the tangent at x = {}",
                e.x
            );
            assert!(
                (t - e.l).abs() < 1e-9,
                "{mode:?}: along the tangent {t} vs l {}",
                e.l
            );
        }
    }
}

#[test]
fn the_circuit_trajectory_closes() {
    let v = vessel(30.0, 30.0);
    let layer = vessel_layer(&v);
    let cyl = Cylinder::new(50.0, 400.0).unwrap();
    let tube = tube_layer(&cyl, 55.0);
    // An isotensoid vessel: the passes leave the domes on their polar bosses.
    let iso = formcam_geom::Vessel::new(
        100.0,
        300.0,
        (formcam_geom::DomeShape::Isotensoid, 30.0),
        (formcam_geom::DomeShape::Isotensoid, 30.0),
    )
    .unwrap();
    let iso_layer = vessel_layer(&iso);
    for (m, layer) in [
        (&v as &dyn Meridian, &layer),
        (&cyl as &dyn Meridian, &tube),
        (&iso as &dyn Meridian, &iso_layer),
    ] {
        for mode in [
            EyeMode::AxisParallel,
            EyeMode::Equidistant,
            EyeMode::PullSpeed,
        ] {
            let spec = EyeSpec {
                mode,
                radius: Some(170.0),
                l_max: 800.0,
                nodes: 300,
                ..EyeSpec::default()
            };
            let eye = eye_trajectory(&m, layer, &spec).unwrap();
            assert!(
                eye.closure_mm < 1e-9,
                "{mode:?}: closure {}",
                eye.closure_mm
            );
            let (a, b) = (eye.points.first().unwrap(), eye.points.last().unwrap());
            assert!((b.eye_v - a.eye_v - eye.circuit_turn_rad).abs() < 1e-9);
            assert!(
                (eye.circuit_turn_rad - layer.report.turn_angle_circuit_with_dwell_rad).abs()
                    < 1e-9,
                "{} vs {}",
                eye.circuit_turn_rad,
                layer.report.turn_angle_circuit_with_dwell_rad
            );
        }
    }
}

#[test]
fn equidistant_keeps_the_clearance() {
    let v = vessel(30.0, 30.0);
    let layer = vessel_layer(&v);
    let spec = EyeSpec {
        mode: EyeMode::Equidistant,
        clearance: 25.0,
        l_max: 800.0,
        ..EyeSpec::default()
    };
    let eye = eye_trajectory(&v, &layer, &spec).unwrap();
    let (za, zb) = v.z_range();
    for e in &eye.points {
        // Distance from (Z, R) to the meridian and to the shaft beyond the ends.
        let mut best = f64::INFINITY;
        for i in 0..=20000 {
            let z = za + (zb - za) * f64::from(i) / 20000.0;
            best = best.min((e.eye_z - z).hypot(e.eye_r - v.r(z)));
        }
        if e.eye_z < za {
            best = best.min(e.eye_r - 30.0);
        }
        if e.eye_z > zb {
            best = best.min(e.eye_r - 30.0);
        }
        // The envelope is tabulated at clearance/400: never closer than 1 um less
        // than the clearance, and at most 10 um more where its corners are cut.
        assert!(
            best > 25.0 - 1e-3 && best < 25.0 + 1e-2,
            "clearance {best} at x = {}: {e:?}",
            e.x
        );
    }
}

#[test]
fn pull_speed_optimum_beats_the_geometric_trajectories() {
    let v = vessel(30.0, 30.0);
    let layer = vessel_layer(&v);
    let cyl = Cylinder::new(50.0, 400.0).unwrap();
    let tube = tube_layer(&cyl, 55.0);
    for (name, m, layer) in [
        ("vessel", &v as &dyn Meridian, &layer),
        ("tube", &cyl as &dyn Meridian, &tube),
    ] {
        for fixed_bath in [false, true] {
            let spec = EyeSpec {
                mode: EyeMode::PullSpeed,
                radius: Some(170.0),
                l_max: 900.0,
                bath_moves_with_eye: !fixed_bath,
                nodes: 400,
                ..EyeSpec::default()
            };
            let eye = eye_trajectory(&m, layer, &spec).unwrap();
            assert!(eye.constraints_ok, "{name}: {:?}", eye.violations);
            assert_eq!(eye.comparison.len(), 2);
            for c in &eye.comparison {
                assert!(
                    eye.stats.u_min >= c.stats.u_min - 1e-6,
                    "{name} fixed bath {fixed_bath}: u_min {} vs {:?} {}",
                    eye.stats.u_min,
                    c.mode,
                    c.stats.u_min
                );
                assert!(
                    eye.stats.u_max <= c.stats.u_max + 1e-6,
                    "{name} fixed bath {fixed_bath}: u_max {} vs {:?} {}",
                    eye.stats.u_max,
                    c.mode,
                    c.stats.u_max
                );
            }
            eprintln!(
                "{name} fixed bath {fixed_bath}: optimum u in [{:.4}, {:.4}] rms {:.4}; {:?}",
                eye.stats.u_min,
                eye.stats.u_max,
                eye.stats.u_rms_dev,
                eye.comparison
                    .iter()
                    .map(|c| (c.mode, c.stats.u_min, c.stats.u_max, c.stats.u_rms_dev))
                    .collect::<Vec<_>>()
            );
        }
    }
}

#[test]
fn a_clearance_that_no_trajectory_keeps_is_an_error() {
    let v = vessel(30.0, 30.0);
    let layer = vessel_layer(&v);
    for mode in [EyeMode::Equidistant, EyeMode::PullSpeed] {
        let spec = EyeSpec {
            mode,
            clearance: 20.0,
            l_max: 60.0,
            nodes: 200,
            samples: 201,
            ..EyeSpec::default()
        };
        let e = eye_trajectory(&v, &layer, &spec).unwrap_err().to_string();
        assert!(e.contains("l_max"), "{mode:?}: {e}");
    }
}

#[test]
fn the_optimum_keeps_the_clearance_near_a_small_opening() {
    // A small opening: the free band beyond the dome's end dips towards the shaft.
    let v = vessel(3.0, 3.0);
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Poles {
            start: 3.0,
            end: 3.0,
        },
        ..LayerSpec::default()
    };
    let layer = plan_layer(&v, &spec).unwrap();
    for fixed in [false, true] {
        let eye = EyeSpec {
            mode: EyeMode::PullSpeed,
            clearance: 20.0,
            l_max: 2000.0,
            bath_moves_with_eye: !fixed,
            nodes: 400,
            ..EyeSpec::default()
        };
        let t = eye_trajectory(&v, &layer, &eye).unwrap();
        assert!(t.constraints_ok, "fixed bath {fixed}: {:?}", t.violations);
        assert!(
            t.points.iter().all(|p| p.margin >= -1e-6),
            "fixed bath {fixed}"
        );
    }
}

#[test]
fn circuit_points_match_pointwise_evaluation() {
    let v = vessel(30.0, 45.0);
    let spec = LayerSpec {
        slippage: Slippage::Auto,
        ends: Ends::Poles {
            start: 30.0,
            end: 45.0,
        },
        ..LayerSpec::default()
    };
    let layer = plan_layer(&v, &spec).unwrap();
    let c = Circuit::new(&v, &layer);
    let pts = c.points(997);
    assert_eq!(pts.len(), 998);
    for p in &pts {
        let q = c.at(p.x);
        assert!(
            (p.z - q.z).abs() < 1e-12
                && (p.v - q.v).abs() < 1e-12
                && (p.alpha - q.alpha).abs() < 1e-12
        );
    }
}

#[test]
fn the_optimum_never_turns_the_mandrel_back_and_closes_on_a_cone() {
    // A shallow helix: keeping the pull speed even would turn the mandrel back
    // unless the no-reverse-rotation rows hold it.
    let cyl = Cylinder::new(50.0, 400.0).unwrap();
    let layer = tube_layer(&cyl, 10.0);
    let cone = formcam_geom::Cone::new(40.0, 70.0, 300.0).unwrap();
    let cone_layer = tube_layer(&cone, 30.0);
    for (m, layer) in [
        (&cyl as &dyn Meridian, &layer),
        (&cone as &dyn Meridian, &cone_layer),
    ] {
        for fixed in [false, true] {
            let spec = EyeSpec {
                mode: EyeMode::PullSpeed,
                clearance: 15.0,
                l_max: 900.0,
                bath_moves_with_eye: !fixed,
                nodes: 300,
                ..EyeSpec::default()
            };
            let t = eye_trajectory(&m, layer, &spec).unwrap();
            assert!(t.constraints_ok, "fixed bath {fixed}: {:?}", t.violations);
            assert!(t.closure_mm < 1e-9, "closure {}", t.closure_mm);
            for w in t.points.windows(2) {
                assert!(w[1].eye_v >= w[0].eye_v - 1e-9);
            }
        }
    }
}

#[test]
fn long_trajectories_agree_point_by_point_with_the_closed_forms() {
    // 60 001 points: built in runs (one per thread where there are several) whose
    // pull speeds, statistics and checks are joined; each point must still match
    // its own evaluation, and each `u` its neighbours.
    let v = vessel(30.0, 30.0);
    let layer = vessel_layer(&v);
    let circuit = Circuit::new(&v, &layer);
    let spec = EyeSpec {
        mode: EyeMode::AxisParallel,
        radius: Some(160.0),
        l_max: 600.0,
        samples: 60_001,
        ..EyeSpec::default()
    };
    let eye = eye_trajectory(&v, &layer, &spec).unwrap();
    let pts = circuit.points(60_000);
    assert_eq!(eye.points.len(), pts.len());
    let n = pts.len() - 1;
    let (mut lo, mut hi, mut slack) = (f64::INFINITY, f64::NEG_INFINITY, 0);
    for (i, (e, p)) in eye.points.iter().zip(&pts).enumerate() {
        let l = axis_parallel_length(p, 160.0).unwrap();
        let (z, r, v, _, _) = eye_at(p, l);
        assert!((e.l - l).abs() < 1e-12 && (e.eye_z - z).abs() < 1e-12);
        assert!((e.eye_r - r).abs() < 1e-12 && (e.eye_v - v).abs() < 1e-12);
        if i < n {
            let f = &eye.points[i + 1];
            let u = (f.lambda - e.lambda) / (f.x - e.x);
            assert!((e.u - u).abs() < 1e-12, "u at {i}: {} vs {u}", e.u);
            lo = lo.min(u);
            hi = hi.max(u);
            if f.l - e.l + (f.x - e.x) < -1e-6 {
                slack += 1;
            }
        }
    }
    assert_eq!(eye.points[n].u, eye.points[0].u);
    assert!((eye.stats.u_min - lo).abs() < 1e-12 && (eye.stats.u_max - hi).abs() < 1e-12);
    let reported = eye
        .violations
        .iter()
        .find(|v| v.constraint == Constraint::Slack)
        .map_or(0, |v| v.count);
    // Axis-parallel slackens the band near the turn-arounds here.
    assert!(slack > 0);
    assert_eq!(reported, slack);
}

/// A long geometric trajectory is built in runs on rayon's pool: with four
/// workers (four runs) it is the trajectory of one worker (one run), point for
/// point to rounding, with the same statistics and constraints.
#[test]
fn runs_on_the_pool_build_the_trajectory_of_one_run() {
    let v = vessel(30.0, 30.0);
    let layer = vessel_layer(&v);
    let spec = EyeSpec {
        mode: EyeMode::Equidistant,
        clearance: 15.0,
        l_max: 600.0,
        samples: 80_001,
        ..EyeSpec::default()
    };
    let on = |workers: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(workers)
            .build()
            .unwrap();
        pool.install(|| eye_trajectory(&v, &layer, &spec)).unwrap()
    };
    let (one, four) = (on(1), on(4));
    assert_eq!(one.points.len(), four.points.len());
    for (a, b) in one.points.iter().zip(&four.points) {
        assert!((a.l - b.l).abs() < 1e-9, "x = {}: {} vs {}", a.x, a.l, b.l);
        assert!((a.u - b.u).abs() < 1e-6, "x = {}: {} vs {}", a.x, a.u, b.u);
    }
    assert_eq!(one.violations.len(), four.violations.len());
    for (a, b) in one.violations.iter().zip(&four.violations) {
        assert_eq!((a.constraint, a.count), (b.constraint, b.count));
    }
    assert_eq!(one.constraints_ok, four.constraints_ok);
    assert!((one.stats.u_min - four.stats.u_min).abs() < 1e-6);
    assert!((one.stats.u_max - four.stats.u_max).abs() < 1e-6);
    assert!((one.stats.u_rms_dev - four.stats.u_rms_dev).abs() < 1e-9);
}
