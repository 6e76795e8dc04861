//! Forward kinematics specialised to a prepared chain, in rotation matrices:
//! the check of a whole trajectory places the same few links at every point,
//! so whatever does not depend on the axes is computed once.
//!
//! A link's world pose is `parent * pre * motion(q) * post`. Where the
//! parent's rotation does not depend on the axes (the root, and links below
//! only fixed and prismatic joints), the products with it are folded in
//! advance: a fixed or prismatic joint then costs a vector sum (its rotation
//! is known, its translation the parent's plus `c + e q`), a revolute joint
//! one rotation matrix from one `sin_cos` and a matrix product. Other links
//! are composed as matrices. The poses equal [`Machine::poses`] to rounding
//! (the tests hold them within 1e-9 mm and 1e-12 rad), not bit for bit:
//! [`crate::Fk`] is the bit-for-bit form.

use nalgebra::{Isometry3, Matrix3, Point3, Unit, Vector3};

use crate::machine::{JointKind, Machine};

/// A rigid transform as a rotation matrix and a translation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    /// The rotation.
    pub(crate) rotation: Matrix3<f64>,
    /// The translation, mm.
    pub(crate) translation: Vector3<f64>,
}

impl Frame {
    const IDENTITY: Self = Self {
        rotation: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        translation: Vector3::new(0.0, 0.0, 0.0),
    };

    fn of(iso: &Isometry3<f64>) -> Self {
        Self {
            rotation: *iso.rotation.to_rotation_matrix().matrix(),
            translation: iso.translation.vector,
        }
    }

    /// `self * other`.
    fn then(&self, other: &Frame) -> Frame {
        Frame {
            rotation: self.rotation * other.rotation,
            translation: self.rotation * other.translation + self.translation,
        }
    }

    /// A point carried by the frame.
    pub(crate) fn point(&self, p: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.rotation * p.coords + self.translation)
    }
}

/// The rotation by `angle` about the unit axis `w` (Rodrigues).
fn turn(w: &Unit<Vector3<f64>>, angle: f64) -> Matrix3<f64> {
    let (s, c) = angle.sin_cos();
    let (x, y, z) = (w.x, w.y, w.z);
    let v = 1.0 - c;
    Matrix3::new(
        c + v * x * x,
        v * x * y - s * z,
        v * x * z + s * y,
        v * x * y + s * z,
        c + v * y * y,
        v * y * z - s * x,
        v * x * z - s * y,
        v * y * z + s * x,
        c + v * z * z,
    )
}

/// A joint's motion at its axis value.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Motion {
    /// Turning about a unit axis.
    Turn(Unit<Vector3<f64>>),
    /// Sliding along a unit direction.
    Slide(Vector3<f64>),
}

/// How a prepared link is placed.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Place {
    /// Its pose does not depend on the axes.
    Known(Frame),
    /// Its rotation does not: the rotation `rotation`, the translation the
    /// parent's plus `c + e q` (a fixed joint: `e = 0`).
    Shift {
        rotation: Matrix3<f64>,
        c: Vector3<f64>,
        e: Vector3<f64>,
        axis: Option<usize>,
    },
    /// A revolute joint under a parent of known rotation: the rotation
    /// `a * turn(q) * post`, the translation the parent's plus
    /// `c + a * turn(q) * post_t`.
    Turn {
        a: Matrix3<f64>,
        c: Vector3<f64>,
        w: Unit<Vector3<f64>>,
        post: Option<Frame>,
        axis: usize,
    },
    /// Any joint under a turning parent: `parent * pre * motion(q) * post`.
    General {
        pre: Frame,
        motion: Option<Motion>,
        post: Frame,
        axis: Option<usize>,
    },
}

/// One link to place: its index, its parent's, how.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Placed {
    link: usize,
    parent: Option<usize>,
    place: Place,
}

/// Forward kinematics of chosen links of a machine, in matrices, prepared
/// for many evaluations.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Chain {
    placed: Vec<Placed>,
    links: usize,
}

impl Chain {
    /// `links` of `m` and their ancestors; the other frames are left as the
    /// identity.
    pub(crate) fn new(m: &Machine, links: &[usize]) -> Self {
        let mut wanted = vec![false; m.links.len()];
        for &l in links {
            let mut k = (l < wanted.len()).then_some(l);
            while let Some(i) = k {
                if wanted[i] {
                    break;
                }
                wanted[i] = true;
                k = m.links[i].parent;
            }
        }
        // Per link: its pose where known, else its rotation where known.
        let mut known: Vec<Option<Frame>> = vec![None; m.links.len()];
        let mut rotation: Vec<Option<Matrix3<f64>>> = vec![None; m.links.len()];
        let mut placed = Vec::new();
        for (i, l) in m.links.iter().enumerate() {
            if !wanted[i] {
                continue;
            }
            let j = &l.joint;
            // A fixed or undriven joint is one constant transform.
            let (pre, motion, post, axis) = match (j.kind, j.axis) {
                (JointKind::Fixed, _) | (_, None) => (
                    Frame::of(&j.transform(j.value)),
                    None,
                    Frame::IDENTITY,
                    None,
                ),
                (JointKind::Revolute, Some(a)) => (
                    Frame::of(&j.pre),
                    Some(Motion::Turn(j.direction)),
                    Frame::of(&j.post),
                    Some(a),
                ),
                (JointKind::Prismatic, Some(a)) => (
                    Frame::of(&j.pre),
                    Some(Motion::Slide(j.direction.into_inner())),
                    Frame::of(&j.post),
                    Some(a),
                ),
            };
            let (parent_known, parent_rotation) = match l.parent {
                Some(p) => (known[p], rotation[p]),
                None => (Some(Frame::IDENTITY), Some(Matrix3::identity())),
            };
            let place = match (parent_known, parent_rotation, motion) {
                (Some(p), _, None) => Place::Known(p.then(&pre)),
                (_, Some(pr), None | Some(Motion::Slide(_))) => {
                    let d = match motion {
                        Some(Motion::Slide(d)) => d,
                        _ => Vector3::zeros(),
                    };
                    Place::Shift {
                        rotation: pr * pre.rotation * post.rotation,
                        c: pr * (pre.translation + pre.rotation * post.translation),
                        e: pr * pre.rotation * d,
                        axis,
                    }
                }
                (_, Some(pr), Some(Motion::Turn(w))) => Place::Turn {
                    a: pr * pre.rotation,
                    c: pr * pre.translation,
                    w,
                    post: (post != Frame::IDENTITY).then_some(post),
                    axis: axis.unwrap_or(0),
                },
                (_, None, motion) => Place::General {
                    pre,
                    motion,
                    post,
                    axis,
                },
            };
            match place {
                Place::Known(f) => {
                    known[i] = Some(f);
                    rotation[i] = Some(f.rotation);
                }
                Place::Shift { rotation: r, .. } => rotation[i] = Some(r),
                _ => {}
            }
            placed.push(Placed {
                link: i,
                parent: l.parent,
                place,
            });
        }
        Self {
            placed,
            links: m.links.len(),
        }
    }

    /// The world frames of the prepared links for the axis values `q` (a
    /// missing value counts as 0), written into `out`, resized to the
    /// machine's links once and reused afterwards.
    pub(crate) fn frames_into(&self, q: &[f64], out: &mut Vec<Frame>) {
        if out.len() != self.links {
            out.clear();
            out.resize(self.links, Frame::IDENTITY);
        }
        let value = |a: Option<usize>| a.and_then(|a| q.get(a).copied()).unwrap_or(0.0);
        for p in &self.placed {
            let parent = p.parent.map_or(Frame::IDENTITY, |i| out[i]);
            out[p.link] = match &p.place {
                Place::Known(f) => *f,
                Place::Shift {
                    rotation,
                    c,
                    e,
                    axis,
                } => Frame {
                    rotation: *rotation,
                    translation: parent.translation + c + e * value(*axis),
                },
                Place::Turn {
                    a,
                    c,
                    w,
                    post,
                    axis,
                } => {
                    let r = a * turn(w, value(Some(*axis)));
                    let translation = parent.translation + c;
                    match post {
                        None => Frame {
                            rotation: r,
                            translation,
                        },
                        Some(post) => Frame {
                            rotation: r * post.rotation,
                            translation: translation + r * post.translation,
                        },
                    }
                }
                Place::General {
                    pre,
                    motion,
                    post,
                    axis,
                } => {
                    let v = value(*axis);
                    let moved = match motion {
                        None => *pre,
                        Some(Motion::Turn(w)) => Frame {
                            rotation: pre.rotation * turn(w, v),
                            translation: pre.translation,
                        },
                        Some(Motion::Slide(d)) => Frame {
                            rotation: pre.rotation,
                            translation: pre.translation + pre.rotation * (d * v),
                        },
                    };
                    parent.then(&moved.then(post))
                }
            };
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use proptest::prelude::*;

    use super::*;
    use crate::shipped;

    /// The largest differences of translation (mm) and rotation (the
    /// matrices' entries) between the chain's frames and the reference poses
    /// of the links asked for and their ancestors.
    fn differences(m: &Machine, links: &[usize], q: &[f64]) -> (f64, f64) {
        let reference = m.poses(q);
        let mut frames = Vec::new();
        Chain::new(m, links).frames_into(q, &mut frames);
        let (mut dt, mut dr) = (0.0_f64, 0.0_f64);
        for &l in links {
            let mut k = Some(l);
            while let Some(i) = k {
                let want = Frame::of(&reference[i]);
                dt = dt.max((frames[i].translation - want.translation).amax());
                dr = dr.max((frames[i].rotation - want.rotation).amax());
                k = m.links[i].parent;
            }
        }
        (dt, dr)
    }

    proptest! {
        /// On random axis values (rotary axes over several turns, linear
        /// ones over metres) the frames of every shipped machine's links,
        /// all or the payout point's and the mandrel's chains, are the
        /// reference poses within 1e-9 mm and 1e-12.
        #[test]
        fn frames_are_the_reference_poses(u in prop::collection::vec(-1.0..1.0_f64, 8)) {
            for s in shipped::SHIPPED {
                let m = s.machine().unwrap();
                let q: Vec<f64> = m
                    .axes
                    .iter()
                    .zip(&u)
                    .map(|(a, u)| if a.is_rotary() { 20.0 * u } else { 2000.0 * u })
                    .collect();
                let all: Vec<usize> = (0..m.links.len()).collect();
                let few = [m.points[m.roles.payout].link, m.roles.mandrel];
                for links in [&all[..], &few[..]] {
                    let (dt, dr) = differences(&m, links, &q);
                    prop_assert!(dt < 1e-9, "{}: translation off by {dt:e} mm", s.name);
                    prop_assert!(dr < 1e-12, "{}: rotation off by {dr:e}", s.name);
                }
            }
        }
    }
}
