//! The correction of tool-path nodes: locate each node on the measured
//! surface, interpolate the deviation there, move the node against it.

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use rayon::prelude::*;

use crate::patch::Foot;
use crate::vec3::{V3, axpy, cross, dot, norm, scale, sub, unit};
use formcam_schema::{Range, Unit};

use crate::{CorrectError, Given, Grid, Interpolation, JobField, Rule, Surface};

/// The milling tool, as the program's nodes describe it: `point` or
/// `ball:R` (R in mm) in job files and on the command line.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Tool {
    /// The nodes are the tool's contact points on the surface: a node moves
    /// by the whole deviation vector (docs/correction.md).
    Point,
    /// A ball-end tool of this radius (mm): the nodes are the ball's centre.
    /// The centre moves along the surface normal at the contact point by the
    /// deviation's normal component, so the contact point moves by it.
    Ball {
        /// The ball's radius, mm.
        #[serde(rename = "radius_mm")]
        radius: f64,
    },
}

impl std::str::FromStr for Tool {
    type Err = Rule;

    /// `point` or `ball:R` (R in mm, > 0).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s == "point" {
            return Ok(Self::Point);
        }
        let Some(r) = s.strip_prefix("ball:") else {
            return Err(Rule::ToolName);
        };
        let Ok(radius) = r.trim().parse::<f64>() else {
            return Err(Rule::BallRadiusText { written: r.into() });
        };
        if !(radius.is_finite() && radius > 0.0) {
            return Err(Rule::BallRadius);
        }
        Ok(Self::Ball { radius })
    }
}

/// The gain's default: the deviation cancelled.
pub const DEFAULT_GAIN: f64 = 1.0;

/// The gains allowed, (0, 2].
pub const GAIN_RANGE: Range = Range::open_closed(0.0, 2.0);

/// The margins allowed, mm: >= 0.
pub const MARGIN_RANGE: Range = Range::at_least(0.0);

/// Correction options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Displacement = −gain × interpolated deviation (the mould moves
    /// against the part's error); 1.0 cancels it.
    pub gain: f64,
    /// The tool.
    pub tool: Tool,
    /// Bilinear (eq. 1, docs/correction.md) or bicubic patches.
    pub interpolation: Interpolation,
    /// Nodes beyond the measured area by at most this much (mm) are corrected
    /// with the deviation extrapolated linearly from the edge; farther ones
    /// are left unchanged. 0 leaves every node outside unchanged.
    pub margin_mm: f64,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            gain: DEFAULT_GAIN,
            tool: Tool::Point,
            interpolation: Interpolation::Bilinear,
            margin_mm: 0.0,
        }
    }
}

impl Options {
    /// Checks the gain against [`GAIN_RANGE`], a ball's radius and the
    /// margin against [`MARGIN_RANGE`]; the messages name the job's field
    /// ([`CorrectError::Field`]).
    pub fn validate(&self) -> Result<(), CorrectError> {
        let within = |field, v: f64, range: Range, unit| {
            if range.contains(v) {
                Ok(())
            } else {
                Err(CorrectError::Field {
                    field,
                    value: Given::Number(v),
                    rule: Rule::Range { range, unit },
                })
            }
        };
        within(JobField::Gain, self.gain, GAIN_RANGE, Unit::None)?;
        if let Tool::Ball { radius } = self.tool
            && !(radius.is_finite() && radius > 0.0)
        {
            return Err(CorrectError::Field {
                field: JobField::Tool,
                value: Given::Tool(self.tool),
                rule: Rule::BallRadius,
            });
        }
        within(JobField::Margin, self.margin_mm, MARGIN_RANGE, Unit::Mm)
    }
}

/// A node whose foot lies beyond the measured area's edge by at most this
/// (mm) counts as inside: the patches only approximate the surface, so the
/// foot of a node over the edge can land a few micrometres beyond it.
pub const EDGE_TOLERANCE_MM: f64 = 0.01;

/// Where a node lies relative to the measured area (`inside`,
/// `extrapolated`, `outside`, `unknown` in the node status file and the
/// view).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, strum::IntoStaticStr, ts_rs::TS,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
pub enum Placement {
    /// On the measured area: corrected by interpolation.
    Inside,
    /// Beyond it within the margin: corrected by extrapolation.
    Extrapolated,
    /// Beyond the margin: unchanged.
    Outside,
    /// A coordinate of the node is unknown (not set by the program): unchanged.
    Unknown,
}

impl Placement {
    /// Every placement, in the order the status file's legend lists them.
    pub const ALL: [Self; 4] = [
        Self::Inside,
        Self::Extrapolated,
        Self::Outside,
        Self::Unknown,
    ];

    /// The word written for it: `inside`, `extrapolated`, `outside`,
    /// `unknown`.
    pub fn name(self) -> &'static str {
        self.into()
    }

    /// The placement [`Self::name`] writes as `word`.
    pub fn from_name(word: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == word)
    }
}

/// The correction of one node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeCorrection {
    /// The displacement to add to the node, mm.
    pub displacement: V3,
    /// Where the node lies.
    pub placement: Placement,
    /// The facet `(i, j)` of the foot of the normal.
    pub facet: (u32, u32),
    /// The foot's parameters on the facet (clamped to `[0, 1]`).
    pub s: f64,
    /// See `s`.
    pub t: f64,
    /// The distance beyond the measured area, mm (0 inside).
    pub outside_mm: f64,
    /// The distance from the node to the nominal surface, mm.
    pub distance_mm: f64,
}

/// The previous node of a run, where the next node's walk starts.
#[derive(Debug, Clone, Copy)]
struct Hint {
    /// Its facet.
    i: usize,
    /// See `i`.
    j: usize,
    /// The node, mm.
    p: V3,
    /// The square of the distance (mm^2) within which the next node starts
    /// from it: half the facet's shorter edge, so the walk is a step or two.
    reach2: f64,
}

/// Corrects nodes against one set of measurements.
pub struct Corrector<'g> {
    surface: Surface<'g>,
    tree: ImmutableKdTree<f64, 3>,
    options: Options,
}

impl<'g> Corrector<'g> {
    /// Patches over `grid` and a k-d tree over the facet centres.
    pub fn new(grid: &'g Grid, options: Options) -> Result<Self, CorrectError> {
        options.validate()?;
        let mut centres = Vec::with_capacity(grid.facets());
        for j in 0..grid.nv - 1 {
            for i in 0..grid.nu - 1 {
                let c = [
                    grid.at(i, j),
                    grid.at(i + 1, j),
                    grid.at(i, j + 1),
                    grid.at(i + 1, j + 1),
                ]
                .into_iter()
                .fold([0.0; 3], |a, p| axpy(a, 0.25, p));
                centres.push(c);
            }
        }
        Ok(Self {
            surface: Surface::new(grid, options.interpolation),
            tree: ImmutableKdTree::new_from_slice(&centres),
            options,
        })
    }

    /// [`Self::new`] on the patches evaluated by the formulas as written:
    /// the straightforward correction the tests check the fast one against.
    #[cfg(test)]
    fn reference(grid: &'g Grid, options: Options) -> Result<Self, CorrectError> {
        let fast = Self::new(grid, options)?;
        Ok(Self {
            surface: Surface::reference(grid, options.interpolation),
            ..fast
        })
    }

    /// The surface.
    pub fn surface(&self) -> &Surface<'g> {
        &self.surface
    }

    /// The facet and foot of the normal from `p`: from the facet whose
    /// centre is nearest, walking to a neighbour while the foot sits on a
    /// shared edge and the neighbour's foot is nearer.
    pub fn locate(&self, p: V3) -> (usize, usize, f64, f64, f64) {
        let (i, j, f) = self.walk(p, None);
        (i, j, f.s, f.t, f.d2.sqrt())
    }

    fn walk(&self, p: V3, hint: Option<(usize, usize)>) -> (usize, usize, Foot) {
        let g = self.surface.grid();
        let nf = g.nu - 1;
        let (mut i, mut j) = match hint {
            Some(h) => h,
            None => {
                let c = self.tree.nearest_one::<SquaredEuclidean>(&p).item as usize;
                (c % nf, c / nf)
            }
        };
        let mut foot = self.surface.foot(i, j, p, true);
        for _ in 0..(g.nu + g.nv) {
            let di: isize = if foot.s <= 0.0 && i > 0 {
                -1
            } else if foot.s >= 1.0 && i + 2 < g.nu {
                1
            } else {
                0
            };
            let dj: isize = if foot.t <= 0.0 && j > 0 {
                -1
            } else if foot.t >= 1.0 && j + 2 < g.nv {
                1
            } else {
                0
            };
            if di == 0 && dj == 0 {
                break;
            }
            let mut best: Option<(usize, usize, Foot)> = None;
            for (a, b) in [(di, 0), (0, dj), (di, dj)] {
                if a == 0 && b == 0 {
                    continue;
                }
                let (ni, nj) = (i.wrapping_add_signed(a), j.wrapping_add_signed(b));
                let f = self.surface.foot(ni, nj, p, true);
                let limit = best.map_or(foot.d2 * (1.0 - 1e-12) - 1e-18, |b| b.2.d2);
                if f.d2 < limit {
                    best = Some((ni, nj, f));
                }
            }
            match best {
                Some((ni, nj, f)) => (i, j, foot) = (ni, nj, f),
                None => break,
            }
        }
        (i, j, foot)
    }

    /// Whether the node at `p`, whose foot on the edge facet `(i, j)` is
    /// `(s, t)`, lies over the measured area in plan: its `(x, y)` (a ball's
    /// contact point, the centre less the radius along the grid's normal)
    /// within `EDGE_TOLERANCE_MM` of the plan view of the facet or one of its
    /// neighbours. The foot of the normal alone misses such nodes on curved
    /// surfaces: the facet's edge is the chord of the curved edge, and the
    /// foot of a node over the edge lands beyond the chord by the sag times
    /// the slope. Facets steeper than 84 degrees (normal within 0.1 of
    /// horizontal) have no useful plan view and are skipped.
    fn within_plan(&self, i: usize, j: usize, s: f64, t: f64, p: V3) -> bool {
        let g = self.surface.grid();
        let q = match self.options.tool {
            Tool::Point => p,
            Tool::Ball { radius } => {
                let corners = [
                    g.normal_at(i, j),
                    g.normal_at(i + 1, j),
                    g.normal_at(i, j + 1),
                    g.normal_at(i + 1, j + 1),
                ];
                let w = [(1.0 - s) * (1.0 - t), s * (1.0 - t), (1.0 - s) * t, s * t];
                let n = unit(
                    corners
                        .iter()
                        .zip(w)
                        .fold([0.0; 3], |a, (n, w)| axpy(a, w, *n)),
                );
                let toward = dot(n, sub(p, self.surface.point(i, j, s, t)));
                axpy(p, -radius * toward.signum(), n)
            }
        };
        let (i0, j0) = (i.saturating_sub(1), j.saturating_sub(1));
        let (i1, j1) = ((i + 1).min(g.nu - 2), (j + 1).min(g.nv - 2));
        (j0..=j1).any(|b| {
            (i0..=i1).any(|a| {
                let c = [
                    g.at(a, b),
                    g.at(a + 1, b),
                    g.at(a + 1, b + 1),
                    g.at(a, b + 1),
                ];
                let n = cross(sub(c[2], c[0]), sub(c[3], c[1]));
                n[2].abs() >= 0.1 * norm(n)
                    && plan_distance_outside(c.map(|v| [v[0], v[1]]), [q[0], q[1]])
                        <= EDGE_TOLERANCE_MM
            })
        })
    }

    /// The correction of one node at `p` (mm).
    pub fn correct_node(&self, p: V3) -> NodeCorrection {
        self.correct_near(p, &mut None)
    }

    /// [`Self::correct_node`], starting the walk at the facet of the previous
    /// node in `hint` when that node is within half the facet's shorter edge
    /// of `p` (nodes along a tool path, so the walk is a step or two), else
    /// at the facet the k-d tree finds. The result is the same (but where a
    /// node has two feet at equal distance, or two local ones, the start
    /// decides); it is found faster.
    fn correct_near(&self, p: V3, hint: &mut Option<Hint>) -> NodeCorrection {
        if p.iter().any(|v| !v.is_finite()) {
            return NodeCorrection {
                displacement: [0.0; 3],
                placement: Placement::Unknown,
                facet: (0, 0),
                s: 0.0,
                t: 0.0,
                outside_mm: 0.0,
                distance_mm: f64::NAN,
            };
        }
        let g = self.surface.grid();
        let start = match hint {
            Some(h) if dot(sub(p, h.p), sub(p, h.p)) < h.reach2 => Some((h.i, h.j)),
            _ => None,
        };
        let (i, j, foot) = self.walk(p, start);
        *hint = Some(Hint {
            i,
            j,
            p,
            reach2: 0.25 * self.surface.shorter_edge2(i, j),
        });
        let (s, t) = (foot.s, foot.t);
        let at_edge = (s <= 0.0 && i == 0)
            || (s >= 1.0 && i + 2 == g.nu)
            || (t <= 0.0 && j == 0)
            || (t >= 1.0 && j + 2 == g.nv);
        let mut outside_mm = 0.0;
        let mut ext = (s, t);
        if at_edge {
            let free = self.surface.foot(i, j, p, false);
            let a = self.surface.bilinear(i, j, free.s, free.t).f;
            let b = self
                .surface
                .bilinear(i, j, free.s.clamp(0.0, 1.0), free.t.clamp(0.0, 1.0))
                .f;
            let d = norm(sub(a, b));
            let size = norm(sub(g.at(i + 1, j + 1), g.at(i, j)));
            if d > EDGE_TOLERANCE_MM + 1e-9 * size && !self.within_plan(i, j, s, t, p) {
                outside_mm = d;
                ext = (free.s, free.t);
            }
        }
        let placement = if outside_mm == 0.0 {
            Placement::Inside
        } else if outside_mm <= self.options.margin_mm {
            Placement::Extrapolated
        } else {
            Placement::Outside
        };
        let displacement = match placement {
            Placement::Outside | Placement::Unknown => [0.0; 3],
            _ => {
                let d = if placement == Placement::Inside {
                    // At the foot itself: the slopes would be added times 0.
                    self.surface.deviation_value(i, j, s, t)
                } else {
                    let (d0, ds, dt) = self.surface.deviation(i, j, s, t);
                    axpy(axpy(d0, ext.0 - s, ds), ext.1 - t, dt)
                };
                let k = -self.options.gain;
                match self.options.tool {
                    Tool::Point => scale(d, k),
                    Tool::Ball { .. } => {
                        let n = self.surface.normal_toward(i, j, s, t, p);
                        scale(n, k * dot(d, n))
                    }
                }
            }
        };
        NodeCorrection {
            displacement,
            placement,
            facet: (i as u32, j as u32),
            s,
            t,
            outside_mm,
            distance_mm: foot.d2.sqrt(),
        }
    }

    /// The corrections of all `nodes`, computed on rayon's global pool in
    /// runs of 4096 consecutive nodes counted from the first, each run
    /// walking from one node's facet to the next. The runs are the same
    /// whatever the number of threads, and the same when the list is
    /// corrected in pieces whose lengths are multiples of 4096 (where a
    /// node has two feet at equal distance, the walk's start decides).
    pub fn correct(&self, nodes: &[V3]) -> Vec<NodeCorrection> {
        let mut out = Vec::with_capacity(nodes.len());
        nodes
            .par_iter()
            .enumerate()
            .with_min_len(RUN)
            .map_init(Walk::default, |walk, (i, &p)| walk.step(self, nodes, i, p))
            .collect_into_vec(&mut out);
        out
    }
}

/// One worker's walk along the nodes: the hint the node before `next` left.
#[derive(Debug, Default)]
struct Walk {
    /// The node the hint is for.
    next: usize,
    /// Where that node's walk starts.
    hint: Option<Hint>,
}

impl Walk {
    /// Corrects node `i` (at `p`) as a walk from the start of its run would.
    /// A worker's share that begins inside a run first walks the run's
    /// nodes before `i` (at most one run per share), so the result never
    /// depends on how the pool splits the list.
    fn step(&mut self, c: &Corrector, nodes: &[V3], i: usize, p: V3) -> NodeCorrection {
        if i.is_multiple_of(RUN) {
            self.hint = None;
        } else if self.next != i {
            self.hint = None;
            for &q in &nodes[i - i % RUN..i] {
                c.correct_near(q, &mut self.hint);
            }
        }
        self.next = i + 1;
        c.correct_near(p, &mut self.hint)
    }
}

/// The length of the runs [`Corrector::correct`] walks node to node.
pub(crate) const RUN: usize = 4096;

/// Checks every displacement against `limit_mm`: the first node beyond it
/// is the error ([`CorrectError::Displacement`], its index in
/// `corrections`).
pub fn check_displacement(
    corrections: &[NodeCorrection],
    limit_mm: f64,
) -> Result<(), CorrectError> {
    for (node, c) in corrections.iter().enumerate() {
        let d = norm(c.displacement);
        if d.is_nan() || d > limit_mm {
            return Err(CorrectError::Displacement {
                node,
                displacement_mm: d,
                limit_mm,
            });
        }
    }
    Ok(())
}

/// How far the plan point `q` lies outside the quadrilateral `c` (corners
/// in order round it): 0 inside, else the distance to its nearest side.
fn plan_distance_outside(c: [[f64; 2]; 4], q: [f64; 2]) -> f64 {
    let mut inside = false;
    let mut nearest = f64::INFINITY;
    for k in 0..4 {
        let (a, b) = (c[k], c[(k + 1) % 4]);
        if (a[1] > q[1]) != (b[1] > q[1])
            && q[0] < a[0] + (q[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1])
        {
            inside = !inside;
        }
        let e = [b[0] - a[0], b[1] - a[1]];
        let len2 = e[0] * e[0] + e[1] * e[1];
        let f = if len2 > 0.0 {
            (((q[0] - a[0]) * e[0] + (q[1] - a[1]) * e[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d = [q[0] - a[0] - f * e[0], q[1] - a[1] - f * e[1]];
        nearest = nearest.min((d[0] * d[0] + d[1] * d[1]).sqrt());
    }
    if inside { 0.0 } else { nearest }
}

/// Totals of a correction.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Totals {
    /// Nodes looked at.
    pub nodes: usize,
    /// Nodes moved (inside or extrapolated, with a non-zero displacement).
    pub corrected: usize,
    /// Nodes corrected by extrapolation.
    pub extrapolated: usize,
    /// Nodes beyond the margin, left unchanged.
    pub outside: usize,
    /// Nodes with an unknown coordinate, left unchanged.
    pub unknown: usize,
    /// The largest displacement, mm.
    pub max_displacement_mm: f64,
    /// The root mean square displacement over the corrected nodes, mm.
    pub rms_displacement_mm: f64,
}

impl Totals {
    /// Totals of `corrections`.
    pub fn of(corrections: &[NodeCorrection]) -> Self {
        let mut t = Self {
            nodes: corrections.len(),
            ..Self::default()
        };
        let mut sum = 0.0;
        for c in corrections {
            match c.placement {
                Placement::Outside => t.outside += 1,
                Placement::Unknown => t.unknown += 1,
                Placement::Extrapolated => t.extrapolated += 1,
                Placement::Inside => {}
            }
            let d = norm(c.displacement);
            if d > 0.0 {
                t.corrected += 1;
                sum += d * d;
                t.max_displacement_mm = t.max_displacement_mm.max(d);
            }
        }
        if t.corrected > 0 {
            t.rms_displacement_mm = (sum / t.corrected as f64).sqrt();
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// A gently curved `nu x nv` grid (a random quadratic, every point
    /// jittered: in plan by up to 15 % of the spacing, in height by 1 %)
    /// with random deviations, and a tool path above and below it that
    /// wanders beyond its edges.
    fn case() -> impl Strategy<Value = (Grid, Vec<V3>)> {
        (
            2usize..9,
            2usize..9,
            2.0..15.0f64,
            2.0..15.0f64,
            prop::array::uniform3(-0.02..0.02f64),
        )
            .prop_flat_map(|(nu, nv, dx, dy, q)| {
                let n = nu * nv;
                let (w, h) = ((nu - 1) as f64 * dx, (nv - 1) as f64 * dy);
                (
                    prop::collection::vec((-0.15..0.15f64, -0.15..0.15f64, -0.01..0.01f64), n),
                    prop::collection::vec(prop::array::uniform3(-0.3..0.3f64), n),
                    (-0.2..1.2f64, -0.2..1.2f64),
                    prop::collection::vec((-0.06..0.06f64, -0.06..0.06f64, -3.0..3.0f64), 1..80),
                )
                    .prop_map(move |(jitter, deviation, (u0, v0), raw)| {
                        let z = |x: f64, y: f64| q[0] * x * x + q[1] * x * y + q[2] * y * y;
                        let nominal = (0..n)
                            .map(|k| {
                                let (i, j) = ((k % nu) as f64, (k / nu) as f64);
                                let (a, b, c) = jitter[k];
                                let (x, y) = ((i + a) * dx, (j + b) * dy);
                                [x, y, z(x, y) + c * dx.min(dy)]
                            })
                            .collect();
                        // A wandering tool path: steps of up to 6 % of
                        // the grid's size, at random heights.
                        let nodes = raw
                            .iter()
                            .scan((u0, v0), |(u, v), &(du, dv, above)| {
                                (*u, *v) = (*u + du, *v + dv);
                                let (x, y) = (*u * w, *v * h);
                                Some([x, y, z(x, y) + above])
                            })
                            .collect();
                        let grid = Grid {
                            nu,
                            nv,
                            nominal,
                            deviation,
                            normal: None,
                            resampled: false,
                            reordered: false,
                        };
                        (grid, nodes)
                    })
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// The fast path (per-facet patch records, the bilinear Newton
        /// without its zero terms, runs written in place on the pool) gives
        /// every node of a wandering tool path the displacement and
        /// placement of the formulas as written, node after node, to
        /// 1e-12 mm.
        #[test]
        fn the_fast_path_equals_the_straightforward_formula(
            (grid, nodes) in case(),
            ball in prop::option::of(0.5..4.0f64),
            margin_mm in 0.0..3.0f64,
        ) {
            let tool = ball.map_or(Tool::Point, |radius| Tool::Ball { radius });
            for interpolation in [Interpolation::Bilinear, Interpolation::Bicubic] {
                let options = Options { gain: 1.0, tool, interpolation, margin_mm };
                let fast = Corrector::new(&grid, options).map_err(|e| TestCaseError::fail(e.to_string()))?;
                let slow = Corrector::reference(&grid, options).map_err(|e| TestCaseError::fail(e.to_string()))?;
                let straight: Vec<NodeCorrection> = nodes
                    .iter()
                    .scan(None, |hint, &p| Some(slow.correct_near(p, hint)))
                    .collect();
                for (k, ((a, b), p)) in fast.correct(&nodes).iter().zip(&straight).zip(&nodes).enumerate() {
                    prop_assert_eq!(a.placement, b.placement, "{:?} node {}", interpolation, k);
                    prop_assert!(
                        norm(sub(a.displacement, b.displacement)) <= 1e-12,
                        "{:?} node {} at {:?}: {:?} vs {:?}", interpolation, k, p, a, b
                    );
                    prop_assert!(
                        (a.distance_mm - b.distance_mm).abs() <= 1e-9,
                        "{:?} node {} at {:?}: {:?} vs {:?}", interpolation, k, p, a, b
                    );
                }
            }
        }
    }
}
