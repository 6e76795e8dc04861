//! The residuals of a solved trajectory, every point checked by forward
//! kinematics.

use nalgebra::Vector3;
use rayon::prelude::*;

use super::equations::orientation_rows;
use crate::chain::{Chain, Frame};
use crate::file::MachineKind;
use crate::{Machine, Target};

/// The position residual (mm) and the orientation residual (the largest of the
/// equations' cosines) of every point of a solved trajectory (`values`, a row
/// of axis values per target), by forward kinematics.
///
/// Every point is checked, whichever solver produced it: the closed form is
/// exact only where the point is reachable (a cross feed's discriminant
/// clipped at zero, an eye turned as near as it goes), and a point checked at
/// a sample would let such a stretch between samples pass unseen. The check
/// is cheap instead: the forward kinematics is specialised to the payout
/// point's and the mandrel's chains ([`Chain`]: rotation matrices, whatever
/// does not depend on the axes folded in advance, one `sin_cos` per turning
/// joint), equal to the reference's poses to rounding. Long trajectories are
/// checked in runs, one per worker of rayon's pool, each writing its own
/// stretch of the two outputs.
pub(super) fn residuals(m: &Machine, targets: &[Target], values: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let width = m.axes.len().max(1);
    let n = targets.len().min(values.len() / width);
    let mut pos = vec![0.0; n];
    let mut ori = vec![0.0; n];
    let chain = Chain::new(m, &[m.points[m.roles.payout].link, m.roles.mandrel]);
    let rows = orientation_rows(m);
    let run = |ts: &[Target], values: &[f64], pos: &mut [f64], ori: &mut [f64]| {
        let mut frames = Vec::with_capacity(m.links.len());
        let rows_of = ts.iter().zip(values.chunks_exact(width));
        for ((t, q), (p, o)) in rows_of.zip(pos.iter_mut().zip(ori.iter_mut())) {
            chain.frames_into(q, &mut frames);
            (*p, *o) = point_residuals(m, rows, &frames, t);
        }
    };
    let threads = rayon::current_num_threads().min(n / 20_000).clamp(1, 16);
    if threads == 1 {
        run(targets, values, &mut pos, &mut ori);
    } else {
        let per = n.div_ceil(threads);
        targets[..n]
            .par_chunks(per)
            .zip(values.par_chunks(per * width))
            .zip(pos.par_chunks_mut(per).zip(ori.par_chunks_mut(per)))
            .for_each(|((ts, vs), (p, o))| run(ts, vs, p, o));
    }
    (pos, ori)
}

/// The position residual (mm) and the orientation residual (the largest of
/// the equations' cosines) at target `t`, from the world frames of the
/// payout point's and the mandrel's links: the residuals of [`Equations`],
/// the orientation ones unscaled.
fn point_residuals(m: &Machine, rows: usize, frames: &[Frame], t: &Target) -> (f64, f64) {
    let roles = &m.roles;
    let payout = &m.points[roles.payout];
    let head = &frames[payout.link];
    let mandrel = &frames[roles.mandrel];
    let d = head.point(&payout.position) - mandrel.point(&t.point);
    let pos = (d.x * d.x + d.y * d.y + d.z * d.z).sqrt();
    let band = mandrel.rotation * t.band.into_inner();
    let normal = mandrel.rotation * t.normal.into_inner();
    let roller = roles.roller_axis.map(|a| head.rotation * a.into_inner());
    let mut ori = 0.0_f64;
    let mut put = |v: f64| ori = ori.max(v.abs());
    match roles.kind {
        MachineKind::Winder => {
            if let Some(a) = roller {
                if rows >= 1 {
                    put(a.dot(&band));
                }
                if rows >= 2 {
                    put(a.dot(&normal));
                }
            }
        }
        MachineKind::Placement => {
            let n = roles
                .head_normal
                .map_or_else(Vector3::z, |a| head.rotation * a.into_inner());
            put(n.dot(&band));
            put(n.dot(&normal.cross(&band)));
            put(1.0 + n.dot(&normal));
            if let Some(a) = roller {
                put(a.dot(&band));
            }
        }
    }
    (pos, ori)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use nalgebra::{Point3, Unit};

    use super::*;
    use crate::Fk;
    use crate::ik::ORIENTATION_SCALE;
    use crate::ik::equations::{Equations, moves};

    proptest::proptest! {
        /// The check's residuals are the equations' (the reference forward
        /// kinematics) within 1e-9 mm and 1e-12 on random axis values and
        /// targets, for every shipped machine.
        #[test]
        fn residuals_are_the_equations_ones(
            u in proptest::collection::vec(-1.0..1.0_f64, 8),
            p in proptest::collection::vec(-500.0..500.0_f64, 3),
            b in proptest::collection::vec(-1.0..1.0_f64, 6),
        ) {
            for s in crate::shipped::SHIPPED {
                let m = s.machine().unwrap();
                let q: Vec<f64> = m
                    .axes
                    .iter()
                    .zip(&u)
                    .map(|(a, u)| if a.is_rotary() { 20.0 * u } else { 2000.0 * u })
                    .collect();
                let band = Vector3::new(b[0], b[1], b[2] + 2.0);
                let normal = Vector3::new(b[3] + 2.0, b[4], b[5]);
                let t = Target {
                    x: 0.0,
                    point: Point3::new(p[0], p[1], p[2]),
                    path_point: Point3::new(p[0], p[1], p[2]),
                    band: Unit::new_normalize(band),
                    normal: Unit::new_normalize(normal),
                    free_length: 0.0,
                    clearance_margin: 0.0,
                };
                let unknowns: Vec<usize> = (0..m.axes.len()).collect();
                let mv = moves(&m);
                let fk = Fk::new(&m);
                let e = Equations::new(&m, &t, &unknowns, &mv, &fk, &q).eval(false);
                let pos = (e.r[0] * e.r[0] + e.r[1] * e.r[1] + e.r[2] * e.r[2]).sqrt();
                let ori = e.r[3..]
                    .iter()
                    .map(|v| (v / ORIENTATION_SCALE).abs())
                    .fold(0.0, f64::max);
                let chain = Chain::new(&m, &[m.points[m.roles.payout].link, m.roles.mandrel]);
                let mut frames = Vec::new();
                chain.frames_into(&q, &mut frames);
                let (p2, o2) = point_residuals(&m, orientation_rows(&m), &frames, &t);
                proptest::prop_assert!((p2 - pos).abs() < 1e-9, "{}: {p2} vs {pos}", s.name);
                proptest::prop_assert!((o2 - ori).abs() < 1e-12, "{}: {o2} vs {ori}", s.name);
            }
        }
    }
    /// A placement head pressing along `+m` (outward) meets the two rows of
    /// pressing across the band, but is no solution: its residual is 2
    /// (pressing along `-m`: 0).
    #[test]
    fn a_head_pressing_outward_is_no_solution() {
        let m = crate::shipped::shipped("placement-arm")
            .unwrap()
            .machine()
            .unwrap();
        let q = m.home();
        let poses = m.poses(&q);
        let head = poses[m.points[m.roles.payout].link];
        let mandrel = poses[m.roles.mandrel];
        let to_mandrel = |v: Vector3<f64>| mandrel.rotation.inverse() * (head.rotation * v);
        let press = to_mandrel(m.roles.head_normal.unwrap().into_inner());
        let roller = to_mandrel(m.roles.roller_axis.unwrap().into_inner());
        let point = mandrel.inverse_transform_point(&(head * m.points[m.roles.payout].position));
        let chain = Chain::new(&m, &[m.points[m.roles.payout].link, m.roles.mandrel]);
        let mut frames = Vec::new();
        chain.frames_into(&q, &mut frames);
        for (sign, want) in [(-1.0, 0.0), (1.0, 2.0)] {
            let t = Target {
                x: 0.0,
                point,
                path_point: point,
                band: Unit::new_normalize(roller.cross(&press)),
                normal: Unit::new_normalize(sign * press),
                free_length: 0.0,
                clearance_margin: 0.0,
            };
            let (pos, ori) = point_residuals(&m, orientation_rows(&m), &frames, &t);
            assert!(
                pos < 1e-9 && (ori - want).abs() < 1e-9,
                "{sign}: {pos} {ori}"
            );
        }
    }
}
