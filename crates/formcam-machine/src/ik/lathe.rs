//! The closed form of a lathe-type winder (spindle, carriage along it,
//! radial cross feed, eye rotation about it), solved in phases.

use std::f64::consts::{PI, TAU};

use nalgebra::{Isometry3, Unit, Vector3};
use rayon::prelude::*;

use super::spindle::Spindle;
use super::{joint_axis, unwrap_near};
use crate::file::{MachineKind, SpindleFollows};
use crate::{JointKind, Machine, Target};

/// The closed form of a lathe-type winder.
#[derive(Debug, Clone)]
pub(super) struct Lathe {
    spindle: Spindle,
    /// Mandrel pose at home.
    mandrel0: Isometry3<f64>,
    /// Payout point at home, relative to the spindle axis: axial part and radial vector.
    p_axial: f64,
    p_perp: Vector3<f64>,
    carriage: (usize, f64),
    cross: Option<(usize, Vector3<f64>)>,
    /// Eye rotation: axis index, world direction, roller axis at home.
    eye: Option<(usize, Vector3<f64>, Vector3<f64>)>,
    /// Home axis values: every closed-form value is an offset from them.
    home: Vec<f64>,
}

impl Lathe {
    /// The closed form, if the machine is lathe-type.
    pub(super) fn detect(m: &Machine, spindle: Option<Spindle>) -> Option<Self> {
        let spindle = spindle?;
        if m.roles.kind != MachineKind::Winder || spindle.follows != SpindleFollows::Eye {
            return None;
        }
        let home = m.home();
        let poses = m.poses(&home);
        let payout = &m.points[m.roles.payout];
        let p0 = poses[payout.link] * payout.position;
        let d = p0 - spindle.origin;
        let k = spindle.k;
        let p_axial = d.dot(&k);
        let p_perp = d - k * p_axial;
        let (mut carriage, mut cross, mut eye) = (None, None, None);
        for (i, a) in m.axes.iter().enumerate() {
            if i == spindle.axis {
                continue;
            }
            if m.is_ancestor(a.link, m.roles.mandrel) || !m.is_ancestor(a.link, payout.link) {
                return None;
            }
            let (o, w) = joint_axis(m, &poses, a.link);
            match a.kind {
                JointKind::Prismatic
                    if (w.dot(&k).abs() - 1.0).abs() < 1e-9 && carriage.is_none() =>
                {
                    carriage = Some((i, w.dot(&k)));
                }
                JointKind::Prismatic
                    if w.dot(&k).abs() < 1e-9
                        && cross.is_none()
                        && w.cross(&p_perp).norm() < 1e-9 * p_perp.norm() =>
                {
                    cross = Some((i, w));
                }
                JointKind::Revolute if eye.is_none() => {
                    let off = p0 - o;
                    if (off - w * off.dot(&w)).norm() > 1e-9 {
                        return None;
                    }
                    let a0 = poses[payout.link].rotation * m.roles.roller_axis?.into_inner();
                    if a0.dot(&w).abs() > 1e-9 {
                        return None;
                    }
                    eye = Some((i, w, a0));
                }
                _ => return None,
            }
        }
        // Translations must not hang below the eye's rotation.
        if let Some((e, _, _)) = eye {
            for (ax, _) in carriage
                .iter()
                .map(|c| (c.0, ()))
                .chain(cross.iter().map(|c| (c.0, ())))
            {
                if m.is_ancestor(m.axes[e].link, m.axes[ax].link) {
                    return None;
                }
            }
            if let Some((_, w, _)) = eye
                && let Some((_, c)) = cross
                && w.cross(&c).norm() > 1e-9
            {
                return None;
            }
        }
        Some(Self {
            spindle,
            mandrel0: poses[m.roles.mandrel],
            p_axial,
            p_perp,
            carriage: carriage?,
            cross,
            eye,
            home,
        })
    }

    /// Axis values for `t`, near `prev`.
    #[cfg(test)]
    fn solve(&self, t: &Target, prev: &[f64], q: &mut [f64]) {
        let sp = self.spindle.axis;
        self.raw(t, q);
        q[sp] = unwrap_near(q[sp], prev[sp], TAU);
        if let Some((ei, _, _)) = self.eye {
            self.eye_raw(t, q);
            q[ei] = unwrap_near(q[ei], prev[ei], PI);
        }
    }

    /// The axis values of every target, each row near the one before (the
    /// first near home). The rows depend on each other only through the
    /// turns of the rotary axes, so the work is split in phases: the axes of
    /// every row in chunks on rayon's pool (the same chunks whatever the
    /// number of threads), the spindle's turns in order, the eye's angle
    /// (which reads the spindle's value) in chunks, its half turns in order.
    /// Each value is the same number as solving the rows one after another.
    pub(super) fn track(&self, targets: &[Target]) -> Vec<f64> {
        const CHUNK: usize = 4096;
        let w = self.home.len().max(1);
        let mut values = vec![0.0; targets.len() * w];
        let in_chunks = |values: &mut [f64], f: &(dyn Fn(&Target, &mut [f64]) + Sync)| {
            values
                .par_chunks_mut(CHUNK * w)
                .zip(targets.par_chunks(CHUNK))
                .for_each(|(rows, ts)| {
                    for (q, t) in rows.chunks_exact_mut(w).zip(ts) {
                        f(t, q);
                    }
                });
        };
        let in_order = |values: &mut [f64], axis: usize, period: f64| {
            let mut prev = self.home[axis];
            for q in values.chunks_exact_mut(w) {
                q[axis] = unwrap_near(q[axis], prev, period);
                prev = q[axis];
            }
        };
        in_chunks(&mut values, &|t, q| self.raw(t, q));
        in_order(&mut values, self.spindle.axis, TAU);
        if let Some((ei, _, _)) = self.eye {
            in_chunks(&mut values, &|t, q| self.eye_raw(t, q));
            in_order(&mut values, ei, PI);
        }
        values
    }

    /// The carriage, the cross feed and the spindle for `t`, the spindle as
    /// home plus its turn within a turn.
    fn raw(&self, t: &Target, q: &mut [f64]) {
        let sp = &self.spindle;
        let k = sp.k;
        let d0 = self.mandrel0 * t.point - sp.origin;
        let a_e = d0.dot(&k);
        let d0_perp = d0 - k * a_e;
        let r_e = d0_perp.norm();
        let (ci, sign) = self.carriage;
        q[ci] = self.home[ci] + (a_e - self.p_axial) / sign;
        let p_perp = match self.cross {
            Some((xi, c)) => {
                let b = self.p_perp.dot(&c);
                let disc = b * b - self.p_perp.norm_squared() + r_e * r_e;
                let roots = [-b + disc.max(0.0).sqrt(), -b - disc.max(0.0).sqrt()];
                // The root on the payout point's home side of the axis.
                let u = roots
                    .into_iter()
                    .find(|u| (self.p_perp + c * *u).dot(&self.p_perp) > 0.0)
                    .unwrap_or(roots[0]);
                q[xi] = self.home[xi] + u;
                self.p_perp + c * u
            }
            None => self.p_perp,
        };
        let delta = k.dot(&d0_perp.cross(&p_perp)).atan2(d0_perp.dot(&p_perp));
        q[sp.axis] = self.home[sp.axis] + delta;
    }

    /// The eye's rotation for `t` at the spindle's value in `q`, as home plus
    /// its angle within a half turn.
    fn eye_raw(&self, t: &Target, q: &mut [f64]) {
        let Some((ei, w, a0)) = self.eye else {
            return;
        };
        let sp = &self.spindle;
        let turn = q[sp.axis] - self.home[sp.axis];
        let rot = nalgebra::UnitQuaternion::from_axis_angle(&Unit::new_unchecked(sp.k), turn);
        let band = rot * (self.mandrel0.rotation * t.band.into_inner());
        let theta = (-a0.dot(&band)).atan2(w.cross(&a0).dot(&band));
        q[ei] = self.home[ei] + theta;
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    proptest::proptest! {
        /// The closed form recovers random axis values of the lathe-type
        /// shipped winders from the target the reference forward kinematics
        /// gives there (the eye's point, a band across the roller), within
        /// 1e-9 mm and 1e-12 rad.
        #[test]
        fn closed_form_inverts_the_reference_kinematics(
            u in proptest::collection::vec(-1.0..1.0_f64, 4),
            d in proptest::collection::vec(-1.0..1.0_f64, 3),
        ) {
            for s in crate::shipped::SHIPPED {
                let m = s.machine().unwrap();
                let Some(lathe) = Lathe::detect(&m, Spindle::new(&m).unwrap()) else {
                    continue;
                };
                let q: Vec<f64> = m
                    .axes
                    .iter()
                    .zip(&u)
                    .map(|(a, u)| match a.kind {
                        JointKind::Revolute if Some(a.link) == m.roles.spindle.map(|s| m.axes[s].link) => 20.0 * u,
                        JointKind::Revolute => 1.5 * u,
                        _ => a.home + 0.5 * (a.max - a.min).min(1000.0) * (u + 1.0) / 2.0,
                    })
                    .collect();
                let poses = m.poses(&q);
                let mandrel = poses[m.roles.mandrel];
                let payout = &m.points[m.roles.payout];
                let p = poses[payout.link] * payout.position;
                // A band across the roller (any band where the machine has no eye axis).
                let across = m.roles.roller_axis.map_or(Vector3::new(d[0], d[1], d[2]), |a| {
                    (poses[payout.link].rotation * a.into_inner()).cross(&Vector3::new(d[0], d[1], d[2]))
                });
                proptest::prop_assume!(across.norm() > 1e-3);
                // A band along the eye's own rotation axis leaves the eye's
                // angle undetermined: no target the planner makes.
                if let Some((_, w, _)) = lathe.eye {
                    let off_axis = (across - w * w.dot(&across)).norm();
                    proptest::prop_assume!(off_axis > 1e-2 * across.norm());
                }
                let band = mandrel.rotation.inverse() * across;
                let point = mandrel.inverse_transform_point(&p);
                let t = Target {
                    x: 0.0,
                    point,
                    path_point: point,
                    band: Unit::new_normalize(band),
                    normal: Unit::new_normalize(band.cross(&Vector3::new(1.0, 2.0, 3.0))),
                    free_length: 0.0,
                    clearance_margin: 0.0,
                };
                let mut got = q.clone();
                lathe.solve(&t, &q, &mut got);
                for (a, (g, w)) in m.axes.iter().zip(got.iter().zip(&q)) {
                    let tol = if a.is_rotary() { 1e-12 } else { 1e-9 };
                    proptest::prop_assert!((g - w).abs() < tol, "{}: {got:?} vs {q:?}", s.name);
                }
            }
        }
    }
}
