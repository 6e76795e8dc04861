//! Property: forward kinematics after inverse kinematics gives the target
//! back. For every shipped machine (`machines/*.toml`) and
//! every solver kind (the closed form where the machine has one, and the
//! numeric solver for all), random in-limit axis values are turned into a
//! reachable trajectory by the reference forward kinematics (`poses`): from
//! home to those values in even steps, the payout point in the mandrel frame
//! and a band and normal that satisfy the machine's orientation equations
//! there. The inverse kinematics of that trajectory, put through the
//! reference forward kinematics again, reaches every target to 1e-9 mm and
//! its orientation equations to 1e-9 (cosines), whatever axis values it
//! chose (the spindle by its own rule, another branch of an eye).
//!
//! The URDF arm (`machines/placement-arm.urdf`) is checked too. URDF has no
//! home values: every joint homes at 0, the arm stretched out on the edge of
//! its reach, where the targets of a trajectory from home are mostly out of
//! reach once the spindle's rule has turned the mandrel (the rule turns it by
//! the path point's direction, which the arm's motion changes; the stretched
//! arm cannot follow), so its trajectories start where the TOML file homes
//! the same arm; the solver still starts at the URDF home, every joint at 0,
//! far from the first target (where it used to settle with the head pressing
//! outward, along `+m`, which the equations then allowed).

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use formcam_machine::shipped::SHIPPED;
use formcam_machine::{IkMethod, Machine, MachineKind, Target, solve};
use nalgebra::{Point3, Unit, Vector3};
use proptest::prelude::*;

/// Steps from home to the random axis values.
const STEPS: usize = 12;

fn machines() -> Vec<(String, Machine, Vec<f64>)> {
    let mut out: Vec<(String, Machine, Vec<f64>)> = SHIPPED
        .iter()
        .map(|s| {
            let m = s.machine().unwrap();
            let start = m.home();
            (s.name.to_string(), m, start)
        })
        .collect();
    // The URDF arm homes every joint at 0, stretched out on the edge of its
    // reach: it starts where the TOML file homes the same arm.
    let urdf =
        Machine::from_urdf_document(include_str!("../../../machines/placement-arm.urdf")).unwrap();
    let start = out
        .iter()
        .find(|(name, _, _)| name == "placement-arm")
        .map(|(_, m, _)| m.home())
        .unwrap();
    out.push(("placement-arm.urdf".to_string(), urdf, start));
    out
}

/// Axis values from unit numbers: within the axis's limits, at most 0.6 rad
/// (a turn for the spindle, which has none) or 300 mm from home.
fn random_axes(m: &Machine, base: &[f64], u: &[f64]) -> Vec<f64> {
    m.axes
        .iter()
        .enumerate()
        .zip(base.iter().zip(u.iter().cycle()))
        .map(|((i, a), (&b, &u))| {
            let reach = match (a.is_rotary(), Some(i) == m.roles.spindle) {
                (true, true) => std::f64::consts::PI,
                (true, false) => 0.6,
                (false, _) => 300.0,
            };
            (b + reach * u).clamp(a.min, a.max)
        })
        .collect()
}

/// How many orientation equations a winder has (eq. 2): one per driven axis
/// beyond three, at most two.
fn winder_rows(m: &Machine) -> usize {
    m.axes.len().saturating_sub(3).min(2)
}

/// The target the reference forward kinematics gives at `q`: the payout
/// point in the mandrel frame, with a band and a normal (`w`, `w2`: random
/// directions) that meet the orientation equations there.
fn target_at(m: &Machine, q: &[f64], x: f64, w: Vector3<f64>, w2: Vector3<f64>) -> Option<Target> {
    let poses = m.poses(q);
    let r = &m.roles;
    let head = poses[m.points[r.payout].link];
    let mandrel = poses[r.mandrel];
    let point = mandrel.inverse_transform_point(&(head * m.points[r.payout].position));
    let to_mandrel = |v: Vector3<f64>| mandrel.rotation.inverse() * (head.rotation * v);
    let roller = r.roller_axis.map(|a| to_mandrel(a.into_inner()));
    let unit = |v: Vector3<f64>| (v.norm() > 1e-3).then(|| Unit::new_normalize(v));
    let (band, normal, path_point) = match r.kind {
        MachineKind::Winder => {
            let band = match roller {
                Some(a) => unit(w - a * a.dot(&w))?,
                None => unit(w)?,
            };
            let normal = match roller {
                Some(a) if winder_rows(m) == 2 => unit(a.cross(&band))?,
                _ => unit(band.cross(&w2))?,
            };
            (band, normal, point)
        }
        MachineKind::Placement => {
            // The head presses along the inward normal, its roller across the path.
            let press = to_mandrel(r.head_normal?.into_inner());
            let normal = Unit::new_normalize(-press);
            let band = unit(roller?.cross(&press))?;
            (band, normal, point - normal.into_inner() * r.roller_radius)
        }
    };
    Some(Target {
        x,
        point,
        path_point,
        band,
        normal,
        free_length: 0.0,
        clearance_margin: f64::INFINITY,
    })
}

/// The payout point's distance from the target (mm) and the largest cosine
/// of the orientation equations, by the reference forward kinematics.
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
            if let Some(a) = roller {
                cosines.extend(
                    [a.dot(&band), a.dot(&normal)]
                        .into_iter()
                        .take(winder_rows(m)),
                );
            }
        }
        MachineKind::Placement => {
            let n = head.rotation * r.head_normal.unwrap().into_inner();
            cosines.push(1.0 + n.dot(&normal));
            cosines.push(n.dot(&band));
            cosines.extend(roller.map(|a| a.dot(&band)));
        }
    }
    (pos, cosines.iter().map(|c| c.abs()).fold(0.0, f64::max))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn fk_after_ik_gives_the_target_back(
        u in proptest::collection::vec(-1.0f64..1.0, 8),
        w in proptest::collection::vec(-1.0f64..1.0, 3),
        w2 in proptest::collection::vec(-1.0f64..1.0, 3),
    ) {
        let w = Vector3::new(w[0], w[1], w[2]);
        let w2 = Vector3::new(w2[0], w2[1], w2[2]);
        for (name, m, home) in machines() {
            let end = random_axes(&m, &home, &u);
            let mut targets = Vec::new();
            for k in 0..=STEPS {
                let f = k as f64 / STEPS as f64;
                let q: Vec<f64> = home.iter().zip(&end).map(|(h, e)| h + f * (e - h)).collect();
                match target_at(&m, &q, k as f64, w, w2) {
                    Some(t) => targets.push(t),
                    None => break,
                }
            }
            prop_assume!(targets.len() == STEPS + 1);
            for method in [IkMethod::Auto, IkMethod::Solver] {
                let track = solve(&m, &targets, method).unwrap();
                for (i, (q, t)) in track.rows().zip(&targets).enumerate() {
                    let (pos, ori) = reference_residual(&m, q, t);
                    prop_assert!(
                        pos <= 1e-9 && ori <= 1e-9,
                        "{} {:?} (closed form: {}): point {} of {:?}: {} mm, orientation {}; axes {:?}",
                        name, method, track.closed_form, i, end, pos, ori, q
                    );
                }
            }
        }
    }
}

/// The point-to-point property above relies on targets the orientation
/// equations can meet; these are the ones it builds: at home every shipped
/// machine meets its own target exactly.
#[test]
fn targets_at_home_are_met_at_home() {
    let w = Vector3::new(0.3, -0.5, 0.8);
    let w2 = Vector3::new(-0.7, 0.2, 0.1);
    for (name, m, q) in machines() {
        let t = target_at(&m, &q, 0.0, w, w2).unwrap();
        let (pos, ori) = reference_residual(&m, &q, &t);
        assert!(pos < 1e-9 && ori < 1e-12, "{name}: {pos} {ori}");
        assert!((t.point - Point3::origin()).norm() > 1.0, "{name}");
    }
}
