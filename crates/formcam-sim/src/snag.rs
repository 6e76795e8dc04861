//! The free-fibre snag check: the fibre from the payout point to its
//! contact point must not cut the mandrel nor come near a machine solid.
//!
//! * The mandrel: the surface of revolution each layer is laid on (the
//!   mandrel grown by the layers before), analytic: the clearance of a point
//!   is its radius outside the meridian `r(z)` over `sqrt(1 + r'²)`. The fibre
//!   leaves the surface tangentially at its contact point, so within
//!   [`SnagOptions::contact_exclusion_mm`] of it nothing is asked; beyond,
//!   while it rises from the surface towards the margin it must not cut the
//!   surface (clearance at least `-cut_tolerance_mm`), and once it has
//!   cleared [`SnagOptions::mandrel_margin_mm`] it must keep it (a fibre
//!   that comes back towards the surface, over a waist's far flank or a
//!   dome, snags). The fibre is checked at
//!   [`SnagOptions::points_per_fibre`] points evenly along it.
//! * The machine's solids (boxes, cylinders, spheres): the signed distance
//!   of the fibre segment to each, minimised exactly along the segment (the
//!   distance to a convex solid is convex along a line: golden-section
//!   search), at least [`SnagOptions::solid_margin_mm`]. Solids on the link
//!   of the payout point and on the links joined directly to it are exempt
//!   (the fibre leaves from them); mesh solids are not checked here. The
//!   distance is measured only where the segment comes within the margin
//!   of the solid's bounding sphere and of its box (in the solid's frame,
//!   the gap between the segment's box and the solid's): both are lower
//!   bounds, so nothing is missed.
//!
//! In time, every block that winds a layer is sampled at its start and its
//! end and bisected until, between neighbouring samples, neither end of the
//! fibre moves more than [`SnagOptions::sample_mm`] in the mandrel's frame,
//! in the world or in any solid's link frame. A clearance changes no more
//! than the fibre's points move, so a snag deeper than that step cannot
//! fall between two samples. The blocks are checked in runs of a fixed
//! length on rayon's threads and what the runs find taken in in order: the
//! first and worst occurrences are the same whatever the number of threads.

use formcam_machine::Shape;
use nalgebra::{Isometry3, Point3, Vector3};

use rayon::prelude::*;

use crate::fibre::{FibreSampler, FibreState, FibreTrack};
use crate::{
    BlockSpan, DISTANCE_TOLERANCE_MM, FreeFibre, SimError, Timeline, Violation, ViolationKind,
};

/// The margins and the sampling of the snag check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnagOptions {
    /// The clearance the fibre keeps from the mandrel once it has left it, mm.
    pub mandrel_margin_mm: f64,
    /// How far the fibre may dip into the surface while it leaves it, mm (the
    /// written program's rounding and the blocks' tolerance move the payout
    /// point by a fraction of a millimetre).
    pub cut_tolerance_mm: f64,
    /// The stretch next to the contact point that is not checked against the
    /// mandrel (the fibre is tangent there), mm.
    pub contact_exclusion_mm: f64,
    /// The clearance from every machine solid, mm.
    pub solid_margin_mm: f64,
    /// The most either end of the fibre moves between two samples, mm.
    pub sample_mm: f64,
    /// Points along the fibre checked against the mandrel.
    pub points_per_fibre: usize,
    /// The most halvings of a block.
    pub max_bisections: u32,
}

impl Default for SnagOptions {
    fn default() -> Self {
        Self {
            mandrel_margin_mm: 1.0,
            cut_tolerance_mm: 0.1,
            contact_exclusion_mm: 2.0,
            solid_margin_mm: 5.0,
            sample_mm: 1.0,
            points_per_fibre: 64,
            max_bisections: 20,
        }
    }
}

/// A machine solid the fibre is checked against.
struct Solid {
    /// Its name in reports: the link, and the solid's number when the link
    /// has several.
    name: String,
    link: usize,
    /// Its placement in the link's frame.
    origin: Isometry3<f64>,
    shape: Convex,
    /// A sphere about the solid's origin that holds it.
    bound: f64,
}

impl Convex {
    /// The half extents of the solid's box in its frame.
    fn half_extents(self) -> Vector3<f64> {
        match self {
            Convex::Box(h) => h,
            Convex::Cylinder { radius, half } => Vector3::new(radius, radius, half),
            Convex::Sphere(r) => Vector3::new(r, r, r),
        }
    }
}

/// A lower bound of the distance between the segment `a`–`b` and a solid
/// within the box of `half` extents about the origin: the gap between the
/// segment's box and that box along the axis where it is widest.
fn box_gap(half: &Vector3<f64>, a: &Point3<f64>, b: &Point3<f64>) -> f64 {
    (0..3)
        .map(|k| (a[k].min(b[k]) - half[k]).max(-half[k] - a[k].max(b[k])))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The convex solids checked.
#[derive(Clone, Copy)]
enum Convex {
    Box(Vector3<f64>),
    Cylinder { radius: f64, half: f64 },
    Sphere(f64),
}

impl Convex {
    /// The signed distance of `p` (the solid's frame): negative inside.
    fn distance(self, p: &Point3<f64>) -> f64 {
        match self {
            Convex::Box(h) => {
                let q = p.coords.abs() - h;
                let outside = q.map(|v| v.max(0.0)).norm();
                outside + q.max().min(0.0)
            }
            Convex::Cylinder { radius, half } => {
                let d = (p.x.hypot(p.y) - radius, p.z.abs() - half);
                let outside = d.0.max(0.0).hypot(d.1.max(0.0));
                outside + d.0.max(d.1).min(0.0)
            }
            Convex::Sphere(r) => p.coords.norm() - r,
        }
    }
}

/// The least signed distance of the segment `a`–`b` to `shape` (convex along
/// the segment: golden-section search to 1e-9 of its length).
fn segment_distance(shape: Convex, a: &Point3<f64>, b: &Point3<f64>) -> f64 {
    let at = |u: f64| shape.distance(&(a + (b - a) * u));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut x1 = hi - g * (hi - lo);
    let mut x2 = lo + g * (hi - lo);
    let (mut f1, mut f2) = (at(x1), at(x2));
    while hi - lo > 1e-9 {
        if f1 <= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = at(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = at(x2);
        }
    }
    at(0.5 * (lo + hi)).min(at(0.0)).min(at(1.0))
}

/// The solids of the fibre's machine that can snag it.
fn solids(fibre: &FreeFibre) -> Vec<Solid> {
    let m = fibre.machine();
    let payout_link = m.points.get(m.roles.payout).map(|p| p.link);
    let exempt = |l: usize| {
        payout_link
            .is_some_and(|p| l == p || m.links[p].parent == Some(l) || m.links[l].parent == Some(p))
    };
    let mut out = Vec::new();
    for (l, link) in m.links.iter().enumerate() {
        if exempt(l) {
            continue;
        }
        let several = link.visuals.len() > 1;
        for (k, v) in link.visuals.iter().enumerate() {
            let (shape, bound) = match &v.shape {
                Shape::Box(s) => {
                    let h = Vector3::new(s[0], s[1], s[2]) * 0.5;
                    (Convex::Box(h), h.norm())
                }
                Shape::Cylinder { radius, length } => (
                    Convex::Cylinder {
                        radius: *radius,
                        half: 0.5 * length,
                    },
                    radius.hypot(0.5 * length),
                ),
                Shape::Sphere(r) => (Convex::Sphere(*r), *r),
                Shape::Mesh(_) => continue,
            };
            let name = if several {
                format!("{} solid {}", link.name, k + 1)
            } else {
                link.name.clone()
            };
            out.push(Solid {
                name,
                link: l,
                origin: v.origin,
                shape,
                bound,
            });
        }
    }
    out
}

/// One sample of the fibre: its state and its ends in every frame the
/// step is measured in.
struct Sample {
    t: f64,
    state: Option<FibreState>,
    /// The fibre's ends (payout, contact): mandrel frame, world, then each
    /// solid's frame.
    ends: Vec<[Point3<f64>; 2]>,
}

/// The first and worst occurrence of a snag on one obstacle.
struct Tally {
    /// (block, time, value, limit)
    first: Option<(usize, f64, f64, f64)>,
    worst: Option<(usize, f64, f64, f64)>,
    worst_slack: f64,
    blocks: usize,
    last_block: Option<usize>,
}

impl Tally {
    fn new() -> Self {
        Self {
            first: None,
            worst: None,
            worst_slack: f64::INFINITY,
            blocks: 0,
            last_block: None,
        }
    }

    /// Takes in the occurrences of the blocks after this tally's: the
    /// first stays the earliest, the worst the earliest of the smallest.
    fn merge(&mut self, later: Tally) {
        if self.first.is_none() {
            self.first = later.first;
        }
        if later.worst_slack < self.worst_slack {
            self.worst_slack = later.worst_slack;
            self.worst = later.worst;
        }
        self.blocks += later.blocks;
        self.last_block = later.last_block.or(self.last_block);
    }

    fn hit(&mut self, block: usize, t: f64, value: f64, limit: f64) {
        let h = (block, t, value, limit);
        self.first.get_or_insert(h);
        if value - limit < self.worst_slack {
            self.worst_slack = value - limit;
            self.worst = Some(h);
        }
        if self.last_block != Some(block) {
            self.blocks += 1;
            self.last_block = Some(block);
        }
    }

    fn violation(&self, tl: &Timeline, obstacle: &str) -> Option<Violation> {
        let (first, worst) = (self.first?, self.worst?);
        let line = |b: usize| tl.block(b).map_or(0, |s| s.line);
        Some(Violation {
            kind: ViolationKind::Snag,
            axis: obstacle.to_string(),
            links: Vec::new(),
            block: first.0 + 1,
            line: line(first.0),
            time_s: first.1,
            value: first.2,
            limit: first.3,
            unit: "mm",
            count: self.blocks,
            worst_block: worst.0 + 1,
            worst_line: line(worst.0),
            worst_time_s: worst.1,
            worst_value: worst.2,
        })
    }
}

/// Whether the solids are bounded before their exact distance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Solids {
    /// The bounding sphere and the boxes first; the exact distance only
    /// where they come within the margin.
    Bounded,
    /// The exact distance of every solid at every sample (the reference).
    Exact,
}

/// The check's state over a run of blocks of one timeline.
struct Checker<'a> {
    fibre: &'a FreeFibre,
    opts: &'a SnagOptions,
    solids: &'a [Solid],
    how: Solids,
    sampler: FibreSampler<'a>,
    mandrel: Tally,
    solid_tallies: Vec<Tally>,
}

impl<'a> Checker<'a> {
    fn new(
        fibre: &'a FreeFibre,
        opts: &'a SnagOptions,
        solids: &'a [Solid],
        how: Solids,
        tl: &'a Timeline,
        track: &'a FibreTrack,
    ) -> Self {
        Self {
            fibre,
            opts,
            solids,
            how,
            sampler: fibre.sampler(tl, track),
            mandrel: Tally::new(),
            solid_tallies: solids.iter().map(|_| Tally::new()).collect(),
        }
    }

    /// Samples block `b` (one that winds a layer) and checks every sample.
    fn block(&mut self, b: &BlockSpan<'_>) {
        let start = self.sample(b.index, b.start_s);
        let end = self.sample(b.index, b.start_s + b.duration_s);
        self.check(b.index, &start);
        self.refine(b.index, &start, &end, 0);
        self.check(b.index, &end);
    }

    /// Takes in what `later` (the checker of the blocks after this one's)
    /// found.
    fn merge(&mut self, later: Checker<'_>) {
        self.mandrel.merge(later.mandrel);
        for (t, l) in self.solid_tallies.iter_mut().zip(later.solid_tallies) {
            t.merge(l);
        }
    }

    fn sample(&mut self, block: usize, t: f64) -> Sample {
        let state = self.sampler.at(block, t);
        let mut ends = Vec::with_capacity(2 + self.solids.len());
        if let Some(s) = &state {
            ends.push([s.payout_mandrel, s.contact_mandrel]);
            ends.push([s.payout, s.contact]);
            let poses = self.sampler.link_poses();
            for solid in self.solids {
                let frame = poses
                    .get(solid.link)
                    .map_or(solid.origin, |p| p * solid.origin);
                ends.push([
                    frame.inverse_transform_point(&s.payout),
                    frame.inverse_transform_point(&s.contact),
                ]);
            }
        }
        Sample { t, state, ends }
    }

    /// The most either end moves between two samples, in any frame.
    fn step(a: &Sample, b: &Sample) -> f64 {
        match (&a.state, &b.state) {
            (Some(_), Some(_)) => a
                .ends
                .iter()
                .zip(&b.ends)
                .map(|(p, q)| (p[0] - q[0]).norm().max((p[1] - q[1]).norm()))
                .fold(0.0, f64::max),
            _ => 0.0,
        }
    }

    /// Samples between `a` and `b` (exclusive) in time order, each checked.
    fn refine(&mut self, block: usize, a: &Sample, b: &Sample, depth: u32) {
        if depth >= self.opts.max_bisections || Self::step(a, b) <= self.opts.sample_mm {
            return;
        }
        let mid = self.sample(block, 0.5 * (a.t + b.t));
        self.refine(block, a, &mid, depth + 1);
        self.check(block, &mid);
        self.refine(block, &mid, b, depth + 1);
    }

    /// Checks one sample against the mandrel and every solid.
    fn check(&mut self, block: usize, s: &Sample) {
        let Some(st) = &s.state else {
            return;
        };
        if let Some((value, limit)) = self.mandrel_clearance(st) {
            self.mandrel.hit(block, s.t, value, limit);
        }
        let margin = self.opts.solid_margin_mm;
        for (k, solid) in self.solids.iter().enumerate() {
            let [p, c] = s.ends[2 + k];
            if self.how == Solids::Bounded && clear_by_bounds(solid, &p, &c, margin) {
                continue;
            }
            let dist = segment_distance(solid.shape, &p, &c);
            if dist < margin - DISTANCE_TOLERANCE_MM {
                self.solid_tallies[k].hit(block, s.t, dist, margin);
            }
        }
    }

    /// The fibre's worst clearance from the mandrel and the clearance asked
    /// there, when it is short of it.
    fn mandrel_clearance(&self, st: &FibreState) -> Option<(f64, f64)> {
        let o = self.opts;
        let layer = self.fibre.layers().get(st.layer)?;
        let (c, p) = (st.contact_mandrel, st.payout_mandrel);
        let len = (p - c).norm();
        if len <= o.contact_exclusion_mm {
            return None;
        }
        let dir = (p - c) / len;
        let n = o.points_per_fibre.max(2);
        let mut cleared = false;
        let mut worst: Option<(f64, f64)> = None;
        for i in 0..n {
            let s =
                o.contact_exclusion_mm + (len - o.contact_exclusion_mm) * i as f64 / (n - 1) as f64;
            let Some(gap) = layer.gap(&(c + dir * s)) else {
                continue;
            };
            let asked = if cleared {
                o.mandrel_margin_mm
            } else {
                -o.cut_tolerance_mm
            };
            if gap < asked - DISTANCE_TOLERANCE_MM && worst.is_none_or(|(v, l)| gap - asked < v - l)
            {
                worst = Some((gap, asked));
            }
            cleared |= gap >= o.mandrel_margin_mm;
        }
        worst
    }
}

/// Every snag of the free fibre of `fibre` along `tl`: one [`Violation`]
/// (kind `snag`, `axis` naming the obstacle: `mandrel` or the solid's link)
/// per obstacle, with the first block, line and time, the clearance there
/// and the clearance asked (mm), and where it is worst, in the order they
/// first happen. The blocks that wind no layer (moves between layers,
/// skip layers) are not checked: where the fibre lies then is not planned.
pub fn check_snag(
    tl: &Timeline,
    fibre: &FreeFibre,
    opts: &SnagOptions,
) -> Result<Vec<Violation>, SimError> {
    run(tl, fibre, opts, Solids::Bounded)
}

/// [`check_snag`] the straightforward way, for tests: one pass over the
/// blocks, the exact distance of every solid at every sample.
#[doc(hidden)]
pub fn check_snag_exhaustive(
    tl: &Timeline,
    fibre: &FreeFibre,
    opts: &SnagOptions,
) -> Result<Vec<Violation>, SimError> {
    run(tl, fibre, opts, Solids::Exact)
}

/// Blocks per run checked on one thread: fixed, so that the runs and what
/// they find do not depend on the number of threads.
const RUN_BLOCKS: usize = 512;

fn run(
    tl: &Timeline,
    fibre: &FreeFibre,
    opts: &SnagOptions,
    how: Solids,
) -> Result<Vec<Violation>, SimError> {
    let track = fibre.follow(tl)?;
    if !fibre.layers().is_empty() && track.blocks.iter().all(Option::is_none) {
        return Err(SimError::Fibre {
            what: "the program never starts the job's first layer: \
                   is it the job's program?"
                .into(),
        });
    }
    let solids = solids(fibre);
    let check_run = |first: usize, last: usize| {
        let mut ck = Checker::new(fibre, opts, &solids, how, tl, &track);
        for b in (first..last).filter_map(|i| tl.block(i)) {
            if track.blocks[b.index].is_some() {
                ck.block(&b);
            }
        }
        ck
    };
    let ck = match how {
        Solids::Exact => check_run(0, tl.len()),
        Solids::Bounded => {
            let starts: Vec<usize> = (0..tl.len()).step_by(RUN_BLOCKS).collect();
            let runs: Vec<Checker<'_>> = starts
                .par_iter()
                .map(|&s| check_run(s, (s + RUN_BLOCKS).min(tl.len())))
                .collect();
            let mut runs = runs.into_iter();
            let mut ck = runs
                .next()
                .unwrap_or_else(|| Checker::new(fibre, opts, &solids, how, tl, &track));
            for later in runs {
                ck.merge(later);
            }
            ck
        }
    };
    let mut out: Vec<Violation> = ck.mandrel.violation(tl, "mandrel").into_iter().collect();
    for (t, s) in ck.solid_tallies.iter().zip(&solids) {
        out.extend(t.violation(tl, &s.name));
    }
    out.sort_by(|a, b| a.time_s.total_cmp(&b.time_s).then(a.block.cmp(&b.block)));
    Ok(out)
}

/// Whether the segment `p`–`c` (the solid's frame) is provably at least
/// `margin` from `solid`: the segment's distance to the solid's bounding
/// sphere, or the gap between the segment's box and the solid's.
fn clear_by_bounds(solid: &Solid, p: &Point3<f64>, c: &Point3<f64>, margin: f64) -> bool {
    let d = c - p;
    let u = if d.norm_squared() > 0.0 {
        (-p.coords.dot(&d) / d.norm_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p + d * u).coords.norm() - solid.bound >= margin
        || box_gap(&solid.shape.half_extents(), p, c) >= margin
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_distances_of_the_solids_are_exact() {
        let b = Convex::Box(Vector3::new(1.0, 2.0, 3.0));
        assert_eq!(b.distance(&Point3::new(4.0, 0.0, 0.0)), 3.0);
        assert_eq!(b.distance(&Point3::new(0.0, 0.0, 0.0)), -1.0);
        assert_eq!(b.distance(&Point3::new(4.0, 6.0, 0.0)), 5.0);
        let c = Convex::Cylinder {
            radius: 2.0,
            half: 1.0,
        };
        assert_eq!(c.distance(&Point3::new(5.0, 0.0, 0.0)), 3.0);
        assert_eq!(c.distance(&Point3::new(0.0, 0.0, 4.0)), 3.0);
        assert_eq!(c.distance(&Point3::new(0.0, 0.0, 0.5)), -0.5);
        assert_eq!(
            Convex::Sphere(2.0).distance(&Point3::new(0.0, 3.0, 4.0)),
            3.0
        );
    }

    #[test]
    fn a_segment_passing_a_sphere_is_as_far_as_its_nearest_point() {
        // The segment x in [-10, 10] at y = 3, z = 4 passes 5 from the centre.
        let s = Convex::Sphere(2.0);
        let d = segment_distance(
            s,
            &Point3::new(-10.0, 3.0, 4.0),
            &Point3::new(10.0, 3.0, 4.0),
        );
        assert!((d - 3.0).abs() < 1e-9, "{d}");
        // Through a box's corner region: the nearest point is an end.
        let b = Convex::Box(Vector3::new(1.0, 1.0, 1.0));
        let d = segment_distance(b, &Point3::new(3.0, 0.0, 0.0), &Point3::new(9.0, 0.0, 0.0));
        assert!((d - 2.0).abs() < 1e-9, "{d}");
        // Through the solid: the depth of its middle (found within 1e-9 of
        // the segment's 10 mm, where the distance has slope 1).
        let d = segment_distance(b, &Point3::new(-5.0, 0.0, 0.0), &Point3::new(5.0, 0.0, 0.0));
        assert!((d + 1.0).abs() < 2e-8, "{d}");
    }
}
