//! Forward kinematics prepared once for many evaluations (a trajectory's
//! residual check, the band past the key points): the rigid transforms
//! composed in advance, only the links asked for and their ancestors placed,
//! the poses written into one buffer that is reused.
//!
//! Every pose is the product [`Machine::poses`] computes, factor for factor
//! and in the same order (`parent * (pre * motion(q) * post)`, the motion's
//! rotation from one `sin_cos` of the half angle): a rigid joint's
//! `pre * post` and an undriven joint's transform at its value are the same
//! numbers computed once instead of at every call, so the poses are equal to
//! the reference's bit for bit and whatever is computed from them (residuals,
//! band lengths, the solver's iterates) does not change.

use nalgebra::Isometry3;

use crate::machine::{Joint, JointKind, Machine};

/// How a link's transform from its parent is obtained.
#[derive(Debug, Clone, PartialEq)]
enum Step {
    /// A rigid joint or an undriven one: its transform, computed once.
    Constant(Isometry3<f64>),
    /// A driven joint, at the value of an axis.
    Driven {
        /// The joint.
        joint: Joint,
        /// Its axis, an index into the axis values.
        axis: usize,
    },
}

/// One link to place.
#[derive(Debug, Clone, PartialEq)]
struct Placed {
    /// The link's index in [`Machine::links`].
    link: usize,
    /// Its parent's index, placed before it.
    parent: Option<usize>,
    /// Its transform from the parent.
    step: Step,
}

/// Forward kinematics of a machine prepared for repeated evaluation.
///
/// Built from a machine as it is; a machine changed afterwards needs a new one.
#[derive(Debug, Clone, PartialEq)]
pub struct Fk {
    /// The links to place, parents first.
    placed: Vec<Placed>,
    /// How many links the machine has (the length of the pose buffer).
    links: usize,
}

impl Fk {
    /// Every link of `m`.
    pub fn new(m: &Machine) -> Self {
        Self::build(m, &vec![true; m.links.len()])
    }

    /// Only `links` of `m` and their ancestors; the other poses are left as
    /// the identity.
    pub fn for_links(m: &Machine, links: &[usize]) -> Self {
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
        Self::build(m, &wanted)
    }

    fn build(m: &Machine, wanted: &[bool]) -> Self {
        let placed = m
            .links
            .iter()
            .enumerate()
            .filter(|&(i, _)| wanted[i])
            .map(|(i, l)| {
                let j = &l.joint;
                let step = match (j.kind, j.axis) {
                    (JointKind::Fixed, _) | (_, None) => Step::Constant(j.transform(j.value)),
                    (_, Some(axis)) => Step::Driven {
                        joint: j.clone(),
                        axis,
                    },
                };
                Placed {
                    link: i,
                    parent: l.parent,
                    step,
                }
            })
            .collect();
        Self {
            placed,
            links: m.links.len(),
        }
    }

    /// The world poses of the prepared links for the axis values `q` (rad or
    /// mm, in the order of the machine's axes; a missing value counts as 0),
    /// written into `out`, which is resized to the machine's links once and
    /// reused afterwards (the links not prepared keep what they held).
    pub fn poses_into(&self, q: &[f64], out: &mut Vec<Isometry3<f64>>) {
        if out.len() != self.links {
            out.clear();
            out.resize(self.links, Isometry3::identity());
        }
        for p in &self.placed {
            let t = match &p.step {
                Step::Constant(t) => *t,
                Step::Driven { joint, axis } => {
                    joint.transform(q.get(*axis).copied().unwrap_or(0.0))
                }
            };
            out[p.link] = match p.parent {
                Some(parent) => out[parent] * t,
                None => t,
            };
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use crate::shipped;

    /// The prepared poses are the reference's, bit for bit, for every link or
    /// a chosen few (their ancestors placed with them).
    #[test]
    fn prepared_poses_are_the_reference_ones() {
        for name in shipped::names() {
            let m = shipped::shipped(name).unwrap().machine().unwrap();
            let q: Vec<f64> = (0..m.axes.len()).map(|a| 0.3 + 0.7 * a as f64).collect();
            let reference = m.poses(&q);
            let mut out = Vec::new();
            Fk::new(&m).poses_into(&q, &mut out);
            assert_eq!(out, reference, "{name}");
            let payout = m.points[m.roles.payout].link;
            let mut few = Vec::new();
            Fk::for_links(&m, &[payout]).poses_into(&q, &mut few);
            let mut k = Some(payout);
            while let Some(i) = k {
                assert_eq!(few[i], reference[i], "{name}: link {i}");
                k = m.links[i].parent;
            }
        }
    }
}
