//! The check over a timeline: per sample every solid placed by forward
//! kinematics, the broad phase (the gap between the solids' boxes), then the
//! exact distance (parry's `contact`, negative when the solids overlap)
//! only for the pairs whose boxes come within the margin.

use std::path::Path;

use formcam_machine::{JointKind, Machine};
use nalgebra::Isometry3;
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::query;
use parry3d_f64::shape::SharedShape;

use super::mandrel::Laminate;
use super::pairs::{Pair, pairs};
use super::solids::{Body, Mount, machine_bodies, reach};
use super::sweep::Sweep;
use crate::{SimError, Timeline, Violation, ViolationKind};

/// How many sampling steps beyond the margin the exact query looks.
const LOOK_AHEAD: f64 = 8.0;

/// The smallest sampling step, mm (half of it when the margin is 0).
const MIN_STEP_MM: f64 = 0.1;

/// The solids of a machine (and the mandrel, when a job gives it) ready to
/// be checked along a timeline.
#[derive(Debug, Clone)]
pub struct Collisions {
    bodies: Vec<Body>,
    pairs: Vec<Pair>,
    sweep: Sweep,
    /// The stage (layer) of each block, for the mandrel's solid.
    stages: Vec<usize>,
    margin: f64,
}

impl Collisions {
    /// The solids of `machine` (meshes read relative to `mesh_dir`, the
    /// machine file's folder; as written when `None`).
    pub fn new(machine: &Machine, mesh_dir: Option<&Path>) -> Result<Self, SimError> {
        Ok(Self::build(
            machine,
            machine_bodies(machine, mesh_dir)?,
            Vec::new(),
        ))
    }

    /// The solids of `machine` and the mandrel on its mandrel link, a solid
    /// per layer of `laminate`; `stages` gives each block's layer.
    pub fn with_mandrel(
        machine: &Machine,
        mesh_dir: Option<&Path>,
        laminate: &Laminate,
        stages: Vec<usize>,
    ) -> Result<Self, SimError> {
        let mut bodies = machine_bodies(machine, mesh_dir)?;
        if let Some(first) = laminate.solids.first() {
            let link = machine.roles.mandrel;
            let mut b = Body::new(
                machine,
                Mount::Link(link),
                first.clone(),
                Isometry3::identity(),
            );
            b.shapes.clone_from(&laminate.solids);
            b.reach = reach(&b.shapes, &b.origin);
            b.revolution = true;
            bodies.push(b);
        }
        Ok(Self::build(machine, bodies, stages))
    }

    fn build(machine: &Machine, bodies: Vec<Body>, stages: Vec<usize>) -> Self {
        let changes: Vec<bool> = bodies.iter().map(|b| b.shapes.len() > 1).collect();
        let symmetric: Vec<bool> = bodies.iter().map(|b| b.revolution).collect();
        Self {
            pairs: pairs(machine, &bodies, &changes),
            sweep: Sweep::new(machine, &bodies, &symmetric),
            bodies,
            stages,
            margin: machine.collision.margin,
        }
    }

    /// The solids checked.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The pairs of solids checked.
    pub fn pairs(&self) -> &[Pair] {
        &self.pairs
    }

    /// The clearance kept, mm.
    pub fn margin(&self) -> f64 {
        self.margin
    }

    /// The sampling step: the most any point of a solid travels between two
    /// samples, mm (half the margin).
    pub fn step(&self) -> f64 {
        0.5 * self.margin.max(MIN_STEP_MM)
    }

    /// Every pair of solids closer than the margin along `tl` (the
    /// timeline of a program on `machine`), one [`Violation`] per pair in
    /// the order they first happen: the first block, line and time where
    /// the pair is closer than the margin and the distance there (mm,
    /// negative: how deep they overlap), the number of blocks where it is,
    /// and the smallest distance.
    ///
    /// Each block is sampled at its end and at `n - 1` evenly spaced times
    /// within it (the first block at its start too), `n` the smallest count
    /// for which no point of any solid travels more than [`Collisions::step`]
    /// between samples (see the `sweep` module). A pair found at least the
    /// margin apart at two samples is at least half the margin apart
    /// between them: no solid passes through another unseen. Pairs with no
    /// driven joint between them are checked once, at the start.
    pub fn check(&self, tl: &Timeline, machine: &Machine) -> Vec<Violation> {
        let scale: Vec<f64> = machine
            .axes
            .iter()
            .map(|a| {
                if a.kind == JointKind::Revolute {
                    1f64.to_radians()
                } else {
                    1.0
                }
            })
            .collect();
        let w = scale.len().min(tl.axes().len());
        let mut tallies: Vec<Tally> = vec![Tally::default(); self.pairs.len()];
        let mut q = vec![0.0; machine.axes.len()];
        let (mut from, mut to) = (q.clone(), q.clone());
        let mut links: Vec<Isometry3<f64>> = Vec::with_capacity(machine.links.len());
        let mut poses = vec![Isometry3::identity(); self.bodies.len()];
        let mut boxes = Vec::with_capacity(self.bodies.len());
        let step = self.step();
        // Per pair, a lower bound of its distance less the margin at the
        // last sample looked at, lowered by the pair's travel at every
        // sample since: while it stays positive the pair is skipped.
        let mut slack = vec![f64::NEG_INFINITY; self.pairs.len()];
        let mut travel = vec![0.0; self.bodies.len()];
        let mut last_stage = None;
        for b in tl.blocks() {
            for (k, s) in scale.iter().enumerate().take(w) {
                from[k] = b.from[k] * s;
                to[k] = b.to[k] * s;
            }
            let stage = self.stages.get(b.index).copied().unwrap_or(usize::MAX);
            if last_stage != Some(stage) {
                slack.fill(f64::NEG_INFINITY);
                last_stage = Some(stage);
            }
            for (i, t) in travel.iter_mut().enumerate() {
                *t = self.sweep.travel(i, &from, &to);
            }
            let most = travel.iter().copied().fold(0.0, f64::max);
            let n = if b.duration_s > 0.0 || most > 0.0 {
                (most / step).ceil().max(1.0) as usize
            } else {
                1
            };
            let first = if b.index == 0 { 0 } else { 1 };
            for s in first..=n {
                let f = s as f64 / n as f64;
                for ((qk, start), end) in q.iter_mut().zip(&from).zip(&to).take(w) {
                    *qk = start + f * (end - start);
                }
                machine.poses_into(&q, &mut links);
                boxes.clear();
                for (body, pose) in self.bodies.iter().zip(poses.iter_mut()) {
                    *pose = match body.mount {
                        Mount::Link(l) => links[l] * body.origin,
                        Mount::World => body.origin,
                    };
                    boxes.push(body.aabb(pose, stage));
                }
                let t = b.start_s + f * b.duration_s;
                let at_start = b.index == 0 && s == 0;
                for ((pair, tally), slack) in self.pairs.iter().zip(&mut tallies).zip(&mut slack) {
                    if pair.rigid && !at_start {
                        continue;
                    }
                    let (i, j) = (pair.a, pair.b);
                    *slack -= (travel[i] + travel[j]) / n as f64;
                    if *slack > 0.0 {
                        continue;
                    }
                    // The broad phase: the boxes' gap bounds the distance.
                    let gap = box_gap(&boxes[i], &boxes[j]);
                    if gap >= self.margin {
                        *slack = gap - self.margin;
                        continue;
                    }
                    let (si, sj) = (self.bodies[i].shape(stage), self.bodies[j].shape(stage));
                    // Looked for up to a few steps beyond the margin, so that
                    // a pair found clear is skipped for a few samples.
                    let ahead = LOOK_AHEAD * step;
                    match distance(&poses[i], si, &poses[j], sj, self.margin + ahead) {
                        None => *slack = ahead,
                        Some(d) => {
                            *slack = d - self.margin;
                            if d < self.margin {
                                tally.hit(b.index, t, d);
                            }
                        }
                    }
                }
            }
        }
        let mut out: Vec<Violation> = self
            .pairs
            .iter()
            .zip(&tallies)
            .filter_map(|(p, t)| t.violation(tl, p, &self.bodies, self.margin))
            .collect();
        out.sort_by(|a, b| a.time_s.total_cmp(&b.time_s).then(a.block.cmp(&b.block)));
        out
    }
}

/// The distance between two placed solids where it is at most `reach`
/// (negative: the depth they overlap), from parry's contact query; `None`
/// when they are further apart.
fn distance(
    p1: &Isometry3<f64>,
    s1: &SharedShape,
    p2: &Isometry3<f64>,
    s2: &SharedShape,
    reach: f64,
) -> Option<f64> {
    // Every pair of our shapes has a contact query (a plane, convex
    // solids, the mandrel's compound of convex frustums); none is
    // unsupported.
    query::contact(p1, s1.as_ref(), p2, s2.as_ref(), reach)
        .ok()
        .flatten()
        .map(|c| c.dist)
}

/// A lower bound of the distance between the solids in two boxes: their
/// largest separation along an axis (negative where they overlap).
fn box_gap(a: &Aabb, b: &Aabb) -> f64 {
    (0..3)
        .map(|k| (b.mins[k] - a.maxs[k]).max(a.mins[k] - b.maxs[k]))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// One occurrence: (block index, time, distance).
type Hit = (usize, f64, f64);

/// What one pair met along the timeline.
#[derive(Debug, Clone, Default)]
struct Tally {
    first: Option<Hit>,
    worst: Option<Hit>,
    /// The blocks where the pair is too close.
    count: usize,
    last_block: Option<usize>,
}

impl Tally {
    fn hit(&mut self, block: usize, t: f64, d: f64) {
        let h = (block, t, d);
        self.first.get_or_insert(h);
        if self.worst.is_none_or(|w| d < w.2) {
            self.worst = Some(h);
        }
        if self.last_block != Some(block) {
            self.count += 1;
            self.last_block = Some(block);
        }
    }

    fn violation(
        &self,
        tl: &Timeline,
        p: &Pair,
        bodies: &[Body],
        margin: f64,
    ) -> Option<Violation> {
        let (first, worst) = (self.first?, self.worst?);
        let line = |b: usize| tl.block(b).map_or(0, |s| s.line);
        Some(Violation {
            kind: ViolationKind::Collision,
            axis: String::new(),
            links: vec![bodies[p.a].name.clone(), bodies[p.b].name.clone()],
            block: first.0 + 1,
            line: line(first.0),
            time_s: first.1,
            value: first.2,
            limit: margin,
            unit: "mm",
            count: self.count,
            worst_block: worst.0 + 1,
            worst_line: line(worst.0),
            worst_time_s: worst.1,
            worst_value: worst.2,
        })
    }
}
