//! The check over a timeline: per sample every solid placed by forward
//! kinematics, the broad phase (the gap between the solids' boxes, then the
//! radial bound beside the mandrel), then the exact distance (parry's
//! `contact`, negative when the solids overlap) only for the pairs the
//! bounds leave within the margin; pairs a bound shows clear are skipped
//! until their travel could bring them within it.

use std::path::Path;

use formcam_machine::{JointKind, Machine};
use nalgebra::Isometry3;
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::query;
use parry3d_f64::shape::SharedShape;

use super::mandrel::Laminate;
use super::pairs::{Pair, pairs};
use super::radial::Radial;
use super::solids::{Body, Mount, machine_bodies, reach};
use super::sweep::Sweep;
use crate::{BlockSpan, DISTANCE_TOLERANCE_MM, SimError, Timeline, Violation, ViolationKind};

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
    /// Per solid of revolution, its radial bound per stage.
    radial: Vec<Option<Vec<Radial>>>,
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
        let radial = bodies
            .iter()
            .map(|b| {
                b.revolution
                    .then(|| b.shapes.iter().map(Radial::of).collect())
            })
            .collect();
        Self {
            radial,
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
    ///
    /// What is found is what the exact distance of every pair at every
    /// sample finds; the work is spared where a bound shows a pair clear:
    /// per pair a lower bound of its distance less the margin, lowered by
    /// the pair's travel bound as the samples go on, skips the pair while it
    /// stays positive — a whole block at once when the block's travel cannot
    /// use it up, and the forward kinematics of a sample where no pair is
    /// left to look at. A pair looked at is bounded by the gap between the
    /// solids' boxes, then, beside the mandrel, by the radial bound (the
    /// `radial` module), and only then measured exactly.
    pub fn check(&self, tl: &Timeline, machine: &Machine) -> Vec<Violation> {
        let grid = Grid::new(machine, tl);
        let mut tallies: Vec<Tally> = vec![Tally::default(); self.pairs.len()];
        let mut place = Placement::new(machine, self.bodies.len());
        let mut g = grid.block_buffers(self.bodies.len());
        // Per pair, a lower bound of its distance less the margin at the
        // last sample looked at, lowered by the pair's travel at every
        // sample since: while it stays positive the pair is skipped.
        let mut slack = vec![f64::NEG_INFINITY; self.pairs.len()];
        let mut active: Vec<usize> = Vec::with_capacity(self.pairs.len());
        let mut last_stage = None;
        for b in tl.blocks() {
            self.plan_block(&grid, &b, &mut g);
            if last_stage != Some(g.stage) {
                slack.fill(f64::NEG_INFINITY);
                last_stage = Some(g.stage);
            }
            // The pairs this block may bring within the margin.
            let samples = (g.n + 1 - g.first) as f64;
            active.clear();
            for (k, pair) in self.pairs.iter().enumerate() {
                if pair.rigid {
                    if g.first == 0 {
                        active.push(k);
                    }
                    continue;
                }
                let drift = (g.travel[pair.a] + g.travel[pair.b]) / g.n as f64 * samples;
                if slack[k] > drift {
                    slack[k] -= drift;
                } else {
                    active.push(k);
                }
            }
            if active.is_empty() {
                continue;
            }
            for s in g.first..=g.n {
                let f = s as f64 / g.n as f64;
                let at_start = b.index == 0 && s == 0;
                place.clear();
                for &k in &active {
                    let pair = &self.pairs[k];
                    if pair.rigid && !at_start {
                        continue;
                    }
                    let (i, j) = (pair.a, pair.b);
                    slack[k] -= (g.travel[i] + g.travel[j]) / g.n as f64;
                    if slack[k] > 0.0 {
                        continue;
                    }
                    place.at(machine, &self.bodies, &g, f);
                    // The broad phase: the boxes' gap bounds the distance.
                    let (bi, bj) = (
                        place.aabb(&self.bodies, i, g.stage),
                        place.aabb(&self.bodies, j, g.stage),
                    );
                    let gap = box_gap(&bi, &bj);
                    if gap >= self.margin {
                        slack[k] = gap - self.margin;
                        continue;
                    }
                    if let Some(bound) = self.radial_bound(i, j, g.stage, &place.poses)
                        && bound >= self.margin
                    {
                        slack[k] = bound - self.margin;
                        continue;
                    }
                    let (si, sj) = (self.bodies[i].shape(g.stage), self.bodies[j].shape(g.stage));
                    // Looked for up to a few steps beyond the margin, so that
                    // a pair found clear is skipped for a few samples.
                    let ahead = LOOK_AHEAD * self.step();
                    let (pi, pj) = (&place.poses[i], &place.poses[j]);
                    match distance(pi, si, pj, sj, self.margin + ahead) {
                        None => slack[k] = ahead,
                        Some(d) => {
                            slack[k] = d - self.margin;
                            if d < self.margin - DISTANCE_TOLERANCE_MM {
                                tallies[k].hit(b.index, b.start_s + f * b.duration_s, d);
                            }
                        }
                    }
                }
            }
        }
        self.violations(tl, &tallies)
    }

    /// [`Collisions::check`] the straightforward way, for tests: every pair
    /// measured exactly at every sample of the same samples, no bound used.
    #[doc(hidden)]
    pub fn check_exhaustive(&self, tl: &Timeline, machine: &Machine) -> Vec<Violation> {
        let grid = Grid::new(machine, tl);
        let mut tallies: Vec<Tally> = vec![Tally::default(); self.pairs.len()];
        let mut place = Placement::new(machine, self.bodies.len());
        let mut g = grid.block_buffers(self.bodies.len());
        let ahead = LOOK_AHEAD * self.step();
        for b in tl.blocks() {
            self.plan_block(&grid, &b, &mut g);
            for s in g.first..=g.n {
                let f = s as f64 / g.n as f64;
                let at_start = b.index == 0 && s == 0;
                place.clear();
                place.at(machine, &self.bodies, &g, f);
                for (pair, tally) in self.pairs.iter().zip(&mut tallies) {
                    if pair.rigid && !at_start {
                        continue;
                    }
                    let (i, j) = (pair.a, pair.b);
                    let (si, sj) = (self.bodies[i].shape(g.stage), self.bodies[j].shape(g.stage));
                    let (pi, pj) = (&place.poses[i], &place.poses[j]);
                    if let Some(d) = distance(pi, si, pj, sj, self.margin + ahead)
                        && d < self.margin - DISTANCE_TOLERANCE_MM
                    {
                        tally.hit(b.index, b.start_s + f * b.duration_s, d);
                    }
                }
            }
        }
        self.violations(tl, &tallies)
    }

    /// Block `b`'s axis values at its ends (rad, mm), its stage, every
    /// solid's travel bound and the number of steps it is sampled in.
    fn plan_block(&self, grid: &Grid, b: &BlockSpan<'_>, g: &mut BlockGrid) {
        for (k, s) in grid.scale.iter().enumerate().take(grid.width) {
            g.from[k] = b.from[k] * s;
            g.to[k] = b.to[k] * s;
        }
        g.stage = self.stages.get(b.index).copied().unwrap_or(usize::MAX);
        for (i, t) in g.travel.iter_mut().enumerate() {
            *t = self.sweep.travel(i, &g.from, &g.to);
        }
        let most = g.travel.iter().copied().fold(0.0, f64::max);
        g.n = if b.duration_s > 0.0 || most > 0.0 {
            (most / self.step()).ceil().max(1.0) as usize
        } else {
            1
        };
        g.first = if b.index == 0 { 0 } else { 1 };
    }

    /// The radial bound of the distance between solids `i` and `j` where
    /// one of them is a solid of revolution and the other is not the bed's
    /// plane.
    fn radial_bound(
        &self,
        i: usize,
        j: usize,
        stage: usize,
        poses: &[Isometry3<f64>],
    ) -> Option<f64> {
        let of = |r: usize, o: usize| -> Option<f64> {
            let radial = self.radial[r].as_ref()?;
            let body = &self.bodies[o];
            if body.plane {
                return None;
            }
            let profile = &radial[stage.min(radial.len() - 1)];
            let rel = poses[r].inv_mul(&poses[o]);
            Some(profile.bound_to(body.shape(stage), &rel))
        };
        of(i, j).or_else(|| of(j, i))
    }

    /// The violations of the pairs' tallies, in the order they happen.
    fn violations(&self, tl: &Timeline, tallies: &[Tally]) -> Vec<Violation> {
        let mut out: Vec<Violation> = self
            .pairs
            .iter()
            .zip(tallies)
            .filter_map(|(p, t)| t.violation(tl, p, &self.bodies, self.margin))
            .collect();
        out.sort_by(|a, b| a.time_s.total_cmp(&b.time_s).then(a.block.cmp(&b.block)));
        out
    }
}

/// How a timeline's axis values become joint values: per axis the factor
/// from NC units (degrees for rotary axes) to the machine's (rad).
struct Grid {
    scale: Vec<f64>,
    /// The axes both the machine and the program have.
    width: usize,
    axes: usize,
}

impl Grid {
    fn new(machine: &Machine, tl: &Timeline) -> Self {
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
        Self {
            width: scale.len().min(tl.axes().len()),
            axes: scale.len(),
            scale,
        }
    }

    fn block_buffers(&self, bodies: usize) -> BlockGrid {
        BlockGrid {
            from: vec![0.0; self.axes],
            to: vec![0.0; self.axes],
            travel: vec![0.0; bodies],
            n: 1,
            first: 1,
            stage: 0,
            width: self.width,
        }
    }
}

/// One block's samples: `n` steps from `from` to `to`, sample `first` to
/// `n` taken.
struct BlockGrid {
    from: Vec<f64>,
    to: Vec<f64>,
    /// Each solid's travel bound over the block, mm.
    travel: Vec<f64>,
    n: usize,
    first: usize,
    stage: usize,
    width: usize,
}

/// The solids placed at one sample: forward kinematics done once, when a
/// pair first needs it, and each box when first asked for.
struct Placement {
    q: Vec<f64>,
    links: Vec<Isometry3<f64>>,
    poses: Vec<Isometry3<f64>>,
    boxes: Vec<Option<Aabb>>,
    placed: bool,
}

impl Placement {
    fn new(machine: &Machine, bodies: usize) -> Self {
        Self {
            q: vec![0.0; machine.axes.len()],
            links: Vec::with_capacity(machine.links.len()),
            poses: vec![Isometry3::identity(); bodies],
            boxes: vec![None; bodies],
            placed: false,
        }
    }

    /// Forgets the last sample.
    fn clear(&mut self) {
        self.placed = false;
    }

    /// Places every solid at the fraction `f` of the block `g`, unless the
    /// sample is placed already.
    fn at(&mut self, machine: &Machine, bodies: &[Body], g: &BlockGrid, f: f64) {
        if self.placed {
            return;
        }
        for ((qk, start), end) in self.q.iter_mut().zip(&g.from).zip(&g.to).take(g.width) {
            *qk = start + f * (end - start);
        }
        machine.poses_into(&self.q, &mut self.links);
        for (body, pose) in bodies.iter().zip(self.poses.iter_mut()) {
            *pose = match body.mount {
                Mount::Link(l) => self.links[l] * body.origin,
                Mount::World => body.origin,
            };
        }
        self.boxes.fill(None);
        self.placed = true;
    }

    /// Solid `i`'s box at stage `stage`.
    fn aabb(&mut self, bodies: &[Body], i: usize, stage: usize) -> Aabb {
        *self.boxes[i].get_or_insert_with(|| bodies[i].aabb(&self.poses[i], stage))
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
