//! How finely a block is sampled: a bound on how far any point of each
//! solid can travel while the axes move linearly through a block.
//!
//! A point `p` of a solid on link `l` moves at `|v| <= sum over the
//! revolute joints j above l of |dθj/dt| |p - oj| + sum over the prismatic
//! ones of |ddj/dt|`, where `oj` is a point of joint `j`'s axis. Below joint
//! `j` the chain is rigid but for the joints further down, so `|p - oj|` is
//! at most the lengths of the offsets down the chain (`pre`, `post`), the
//! travel of the prismatic joints below `j` (their larger end value within
//! the block) and the solid's reach about its link's origin. A revolute
//! joint whose axis is the axis of a solid of revolution (the spindle and
//! the mandrel) does not move that solid's space and is not counted.

use formcam_machine::{JointKind, Machine};
use nalgebra::{Isometry3, Vector3};

use super::solids::{Body, Mount};

/// One joint above a solid, for the bound.
#[derive(Debug, Clone)]
struct Lever {
    /// The joint's axis (index into the program's axes), if driven.
    axis: Option<usize>,
    /// Revolute or prismatic (fixed joints are not kept).
    kind: JointKind,
    /// The offsets' lengths from the joint down to the solid, plus the
    /// solid's reach, mm.
    length: f64,
    /// The prismatic joints below: their axes, or their fixed value.
    slides: Vec<Result<usize, f64>>,
}

/// The motion bound of every solid.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// Per solid, the joints above it.
    levers: Vec<Vec<Lever>>,
}

impl Sweep {
    /// The bound for `bodies` on `machine`; `symmetric[i]` marks a solid of
    /// revolution about its link's `z` axis.
    pub fn new(machine: &Machine, bodies: &[Body], symmetric: &[bool]) -> Self {
        let levers = bodies
            .iter()
            .zip(symmetric)
            .map(|(b, sym)| match b.mount {
                Mount::World => Vec::new(),
                Mount::Link(l) => levers(machine, l, b.reach, *sym),
            })
            .collect();
        Self { levers }
    }

    /// How far any point of solid `i` may travel while the axes move from
    /// `from` to `to` (in the machine's order: rad or mm), mm.
    pub fn travel(&self, i: usize, from: &[f64], to: &[f64]) -> f64 {
        let mut sum = 0.0;
        for lever in &self.levers[i] {
            let Some(a) = lever.axis else { continue };
            let change = (to[a] - from[a]).abs();
            if change == 0.0 {
                continue;
            }
            sum += match lever.kind {
                JointKind::Revolute => {
                    let slide: f64 = lever
                        .slides
                        .iter()
                        .map(|s| match s {
                            Ok(k) => from[*k].abs().max(to[*k].abs()),
                            Err(v) => v.abs(),
                        })
                        .sum();
                    change * (lever.length + slide)
                }
                _ => change,
            };
        }
        sum
    }
}

/// The length of an isometry's translation.
fn offset(i: &Isometry3<f64>) -> f64 {
    i.translation.vector.norm()
}

/// The joints above link `l`, from the link up, for a solid of `reach`.
fn levers(machine: &Machine, l: usize, reach: f64, symmetric: bool) -> Vec<Lever> {
    let mut out = Vec::new();
    let mut length = reach;
    let mut slides: Vec<Result<usize, f64>> = Vec::new();
    // Whether every joint so far (from the solid's link up) is fixed.
    let mut rigid_so_far = true;
    let mut k = Some(l);
    while let Some(i) = k {
        let j = &machine.links[i].joint;
        let on_axis = symmetric && rigid_so_far && spins_about(machine, i, l);
        if j.kind != JointKind::Fixed {
            length += offset(&j.post);
            if !on_axis {
                out.push(Lever {
                    axis: j.axis,
                    kind: j.kind,
                    length,
                    slides: slides.clone(),
                });
            }
            rigid_so_far = false;
        } else {
            length += offset(&j.post);
        }
        length += offset(&j.pre);
        if j.kind == JointKind::Prismatic {
            slides.push(j.axis.ok_or(j.value));
        }
        k = machine.links[i].parent;
    }
    out
}

/// Whether link `i`'s revolute joint turns about link `l`'s `z` axis (at
/// home; the links between are fixed, so at every pose).
fn spins_about(machine: &Machine, i: usize, l: usize) -> bool {
    let j = &machine.links[i].joint;
    if j.kind != JointKind::Revolute {
        return false;
    }
    let poses = machine.poses(&machine.home());
    let parent = machine.links[i]
        .parent
        .map_or_else(Isometry3::identity, |p| poses[p]);
    let frame = parent * j.pre;
    let dir = frame.rotation * j.direction.into_inner();
    let o = frame.translation.vector;
    let z = poses[l].rotation * Vector3::z();
    let c = poses[l].translation.vector;
    let scale = 1.0 + o.norm() + c.norm();
    dir.cross(&z).norm() < 1e-9 && (c - o).cross(&dir).norm() < 1e-9 * scale
}
