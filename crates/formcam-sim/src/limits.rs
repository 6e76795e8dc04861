//! The axis checks of a timeline: position limits, velocity, velocity jump
//! between blocks and acceleration, against the machine's limits — the
//! rules the winding planner times its blocks by.

use formcam_machine::{JointKind, Machine};
use formcam_nc::Motion;
use serde::Serialize;

use crate::Timeline;

/// The written resolution of a linear axis word (formcam's writers print
/// 3 decimals of mm): each block end may lie half of it from the planned one.
pub const RESOLUTION_MM: f64 = 1e-3;

/// The written resolution of a rotary axis word (4 decimals of a degree).
pub const RESOLUTION_DEG: f64 = 1e-4;

/// How far below its margin a distance may be and still pass, mm: the
/// rounding of the distance queries (`4.999999999999995` against a margin
/// of 5 passes), a thousandth of the written resolution.
pub const DISTANCE_TOLERANCE_MM: f64 = 1e-6;

/// The relative tolerance of the arithmetic on every limit.
pub const RELATIVE_TOLERANCE: f64 = 1e-9;

/// The written resolution of an axis word.
pub(crate) fn resolution(rotary: bool) -> f64 {
    if rotary {
        RESOLUTION_DEG
    } else {
        RESOLUTION_MM
    }
}

/// One axis's limits in NC units (mm or degrees, per second).
#[derive(Debug, Clone, PartialEq)]
pub struct AxisLimits {
    /// The NC address.
    pub name: String,
    /// Rotary (degrees) or linear (mm).
    pub rotary: bool,
    /// Lower and upper position limit (`-inf`/`inf` when unlimited).
    pub min: f64,
    /// Upper position limit.
    pub max: f64,
    /// Velocity limit per second (`inf` when not given).
    pub v_max: f64,
    /// Velocity-jump limit between blocks, per second.
    pub dv_max: f64,
    /// Acceleration limit per second² (`inf` when not given).
    pub a_max: f64,
}

impl AxisLimits {
    /// The limits of every axis of `machine`, in its order, in NC units.
    pub fn of(machine: &Machine) -> Vec<Self> {
        machine
            .axes
            .iter()
            .map(|a| {
                let rotary = a.kind == JointKind::Revolute;
                let s = if rotary { 1f64.to_degrees() } else { 1.0 };
                Self {
                    name: a.name.clone(),
                    rotary,
                    min: a.min * s,
                    max: a.max * s,
                    v_max: a.v_max * s,
                    dv_max: a.dv_max * s,
                    a_max: a.a_max * s,
                }
            })
            .collect()
    }

    /// The written resolution of the axis's values.
    fn resolution(&self) -> f64 {
        resolution(self.rotary)
    }
}

/// What a violation breaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ViolationKind {
    /// An axis beyond its position limit (`min_*`, `max_*`).
    Position,
    /// An axis faster than its velocity limit (`v_max_*`).
    Velocity,
    /// An axis's velocity changing between neighbouring blocks (or from or
    /// to rest) by more than its jump limit (`dv_max_*`).
    VelocityJump,
    /// An axis's velocity changing between neighbouring blocks faster than
    /// its acceleration limit allows within half of each (`a_max_*`).
    Acceleration,
    /// Two solids closer than the machine's clearance margin (`[collision]
    /// margin_mm`), or overlapping.
    Collision,
    /// The free fibre, from the payout point to its contact point, cutting
    /// the mandrel or coming nearer a solid than the margin.
    Snag,
}

impl ViolationKind {
    /// The name in reports and messages.
    pub fn name(self) -> &'static str {
        match self {
            Self::Position => "position",
            Self::Velocity => "velocity",
            Self::VelocityJump => "velocity-jump",
            Self::Acceleration => "acceleration",
            Self::Collision => "collision",
            Self::Snag => "snag",
        }
    }
}

/// A broken limit of one axis: where it first happens, how often, and where
/// it is worst.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Violation {
    /// What is broken.
    pub kind: ViolationKind,
    /// The axis (NC address); for a snag, what the fibre meets (`mandrel`,
    /// or a solid's link); empty for a collision.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub axis: String,
    /// A collision's two solids: their links' names (`bed` for the bed).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub links: Vec<String>,
    /// The first block that breaks it (1-based).
    pub block: usize,
    /// That block's program line (1-based).
    pub line: usize,
    /// When it happens, s: the block's end for a position, its start for
    /// a velocity, the join for a jump or an acceleration.
    pub time_s: f64,
    /// The value there (the unit in `unit`).
    pub value: f64,
    /// The limit broken (the unit in `unit`).
    pub limit: f64,
    /// `mm`, `deg`, `mm/min`, `deg/min`, `mm/s2`, `deg/s2`.
    pub unit: &'static str,
    /// How many blocks (or joins) break it.
    pub count: usize,
    /// The block where it is worst (1-based).
    pub worst_block: usize,
    /// Its line.
    pub worst_line: usize,
    /// Its time, s.
    pub worst_time_s: f64,
    /// The worst value.
    pub worst_value: f64,
}

impl Violation {
    /// Whether the worst value is on the same side of the limit as the
    /// first (a position can break `min` first and `max` worst; then the
    /// limit the violation carries is the first's).
    fn worst_against_limit(&self) -> bool {
        self.kind != ViolationKind::Position
            || (self.worst_value < self.limit) == (self.value < self.limit)
    }
}

/// The verdict of one violation: where it is worst, and its value there
/// against the limit; then, when it happens more than once, how often and
/// where it starts: `collision at block 9 (line 10, 1.250 s): eye and
/// mandrel overlap by 0.3 mm (margin 5 mm); broken 4 times from block 7
/// (line 8)`.
impl std::fmt::Display for Violation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let worst = self.worst_against_limit();
        let (block, line, t, value) = if worst {
            (
                self.worst_block,
                self.worst_line,
                self.worst_time_s,
                self.worst_value,
            )
        } else {
            (self.block, self.line, self.time_s, self.value)
        };
        write!(
            f,
            "{} at block {block} (line {line}, {t:.3} s): ",
            self.kind.name()
        )?;
        if self.kind == ViolationKind::Collision {
            let [a, b] = [0, 1].map(|k| self.links.get(k).map_or("", String::as_str));
            if value < 0.0 {
                write!(f, "{a} and {b} overlap by {} mm", short(-value))?;
            } else {
                write!(f, "{a} and {b} {} mm apart", short(value))?;
            }
            write!(f, " (margin {} mm)", short(self.limit))?;
        } else {
            let below = matches!(self.kind, ViolationKind::Position | ViolationKind::Snag);
            let rel = if below && value < self.limit {
                "<"
            } else {
                ">"
            };
            let what = if self.kind == ViolationKind::Snag {
                "fibre to"
            } else {
                "axis"
            };
            write!(
                f,
                "{what} {} {} {} {rel} {} {}",
                self.axis,
                short(value),
                self.unit,
                short(self.limit),
                self.unit
            )?;
        }
        if self.count > 1 {
            write!(
                f,
                "; broken {} times from block {} (line {})",
                self.count, self.block, self.line
            )?;
        }
        Ok(())
    }
}

/// A number in at most 6 significant digits.
fn short(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    let digits = s
        .trim_start_matches('-')
        .split('.')
        .next()
        .map_or(0, str::len);
    if digits >= 6 {
        format!("{v:.0}")
    } else {
        format!("{:.*}", 6 - digits, v)
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    }
}

/// One occurrence: (block index, time, value, limit).
type Hit = (usize, f64, f64, f64);

/// Gathers the occurrences of one (kind, axis).
struct Tally {
    kind: ViolationKind,
    axis: usize,
    first: Option<Hit>,
    worst: Option<Hit>,
    /// How far past the limit the worst is, relative to the limit.
    worst_excess: f64,
    count: usize,
}

impl Tally {
    fn new(kind: ViolationKind, axis: usize) -> Self {
        Self {
            kind,
            axis,
            first: None,
            worst: None,
            worst_excess: f64::NEG_INFINITY,
            count: 0,
        }
    }

    fn hit(&mut self, h: Hit, excess: f64) {
        self.count += 1;
        self.first.get_or_insert(h);
        if excess > self.worst_excess {
            self.worst_excess = excess;
            self.worst = Some(h);
        }
    }

    fn violation(
        &self,
        tl: &Timeline,
        limits: &[AxisLimits],
        unit: &'static str,
        scale: f64,
    ) -> Option<Violation> {
        let (first, worst) = (self.first?, self.worst?);
        let line = |b: usize| tl.block(b).map_or(0, |s| s.line);
        Some(Violation {
            kind: self.kind,
            axis: limits[self.axis].name.clone(),
            links: Vec::new(),
            block: first.0 + 1,
            line: line(first.0),
            time_s: first.1,
            value: first.2 * scale,
            limit: first.3 * scale,
            unit,
            count: self.count,
            worst_block: worst.0 + 1,
            worst_line: line(worst.0),
            worst_time_s: worst.1,
            worst_value: worst.2 * scale,
        })
    }
}

/// Every broken limit of `tl` on axes with `limits` (in the timeline's axis
/// order), one [`Violation`] per kind and axis, in the order they first
/// happen.
///
/// * Position: each block's end against `[min, max]`, half a written unit
///   allowed (the axes move linearly, so the ends are the extremes).
/// * Velocity: `|Δ| / t` of each feed block against `v_max` (rapids run at
///   it by definition).
/// * Velocity jump: between neighbouring feed blocks, and from rest where a
///   feed block follows the start or a rapid, and to rest where it is the last
///   or precedes a rapid, against `dv_max`.
/// * Acceleration: between neighbouring feed blocks, `|v_i - v_j| <= a_max
///   (t_i + t_j) / 2` (the planner's rule), where the machine gives `a_max`.
///
/// Values within what the rounding of the written text allows pass: each
/// axis word one unit ([`RESOLUTION_MM`], [`RESOLUTION_DEG`]) off over the
/// block's time, and the block's time off by
/// [`Timeline::time_uncertainty`] (plus [`RELATIVE_TOLERANCE`]).
pub fn check_timeline(tl: &Timeline, limits: &[AxisLimits]) -> Vec<Violation> {
    let w = limits.len().min(tl.axes().len());
    let mut pos: Vec<Tally> = (0..w)
        .map(|k| Tally::new(ViolationKind::Position, k))
        .collect();
    let mut vel: Vec<Tally> = (0..w)
        .map(|k| Tally::new(ViolationKind::Velocity, k))
        .collect();
    let mut jump: Vec<Tally> = (0..w)
        .map(|k| Tally::new(ViolationKind::VelocityJump, k))
        .collect();
    let mut acc: Vec<Tally> = (0..w)
        .map(|k| Tally::new(ViolationKind::Acceleration, k))
        .collect();
    let tol = 1.0 + RELATIVE_TOLERANCE;
    // The previous feed block: (index, duration, velocities per axis,
    // their uncertainty).
    let mut prev: Option<(usize, f64, Vec<f64>, Vec<f64>)> = None;
    let mut dv = vec![0.0; w];
    let mut v = vec![0.0; w];
    for b in tl.blocks() {
        let i = b.index;
        let end = b.start_s + b.duration_s;
        for (k, l) in limits.iter().enumerate().take(w) {
            let q = b.to[k];
            let half = 0.5 * l.resolution();
            if q > l.max + half {
                pos[k].hit((i, end, q, l.max), (q - l.max) / l.max.abs().max(1.0));
            } else if q < l.min - half {
                pos[k].hit((i, end, q, l.min), (l.min - q) / l.min.abs().max(1.0));
            }
        }
        if b.kind == Motion::Rapid {
            if let Some((j, _, vj, uj)) = prev.take() {
                to_rest(&mut jump, limits, j, b.start_s, &vj, &uj);
            }
            continue;
        }
        let t = b.duration_s;
        let rel = tl.time_uncertainty(i);
        for (k, l) in limits.iter().enumerate().take(w) {
            let d = b.to[k] - b.from[k];
            v[k] = if d == 0.0 { 0.0 } else { d / t };
            dv[k] = l.resolution() / t + v[k].abs() * rel;
            let slack = dv[k];
            if v[k].abs() > l.v_max * tol + slack {
                vel[k].hit((i, b.start_s, v[k].abs(), l.v_max), v[k].abs() / l.v_max);
            }
        }
        match &prev {
            None => {
                // From rest.
                for (k, l) in limits.iter().enumerate().take(w) {
                    let slack = dv[k];
                    if v[k].abs() > l.dv_max * tol + slack {
                        jump[k].hit((i, b.start_s, v[k].abs(), l.dv_max), v[k].abs() / l.dv_max);
                    }
                }
            }
            Some((_, tj, vj, uj)) => {
                for (k, l) in limits.iter().enumerate().take(w) {
                    let change = (v[k] - vj[k]).abs();
                    let slack = dv[k] + uj[k];
                    if change > l.dv_max * tol + slack {
                        jump[k].hit((i, b.start_s, change, l.dv_max), change / l.dv_max);
                    }
                    let allowed = l.a_max * 0.5 * (t + tj);
                    if l.a_max.is_finite() && change > allowed * tol + slack {
                        let a = change / (0.5 * (t + tj));
                        acc[k].hit((i, b.start_s, a, l.a_max), a / l.a_max);
                    }
                }
            }
        }
        prev = Some((i, t, v.clone(), dv.clone()));
    }
    if let Some((j, _, vj, uj)) = prev {
        to_rest(&mut jump, limits, j, tl.duration_s(), &vj, &uj);
    }
    let mut out: Vec<Violation> = Vec::new();
    for (tallies, unit_lin, unit_rot, scale) in [
        (&pos, "mm", "deg", 1.0),
        (&vel, "mm/min", "deg/min", 60.0),
        (&jump, "mm/min", "deg/min", 60.0),
        (&acc, "mm/s2", "deg/s2", 1.0),
    ] {
        for t in tallies {
            let unit = if limits[t.axis].rotary {
                unit_rot
            } else {
                unit_lin
            };
            out.extend(t.violation(tl, limits, unit, scale));
        }
    }
    out.sort_by(|a, b| {
        a.time_s
            .total_cmp(&b.time_s)
            .then(a.block.cmp(&b.block))
            .then(a.kind.cmp(&b.kind))
    });
    out
}

/// The jump from feed block `j` (velocities `vj`, their uncertainty `uj`)
/// to rest at `time`.
fn to_rest(jump: &mut [Tally], limits: &[AxisLimits], j: usize, time: f64, vj: &[f64], uj: &[f64]) {
    for (((tally, l), v), slack) in jump.iter_mut().zip(limits).zip(vj).zip(uj) {
        if v.abs() > l.dv_max * (1.0 + RELATIVE_TOLERANCE) + slack {
            tally.hit((j, time, v.abs(), l.dv_max), v.abs() / l.dv_max);
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::FeedRule;
    use formcam_nc::{AxisSpec, Block, Feed, Program};

    fn limits() -> Vec<AxisLimits> {
        vec![AxisLimits {
            name: "X".into(),
            rotary: false,
            min: 0.0,
            max: 100.0,
            v_max: 10.0,
            dv_max: 2.0,
            a_max: 4.0,
        }]
    }

    fn timeline(blocks: &[(f64, f64)]) -> Timeline {
        let mut p = Program::new("T", vec![AxisSpec::linear("X")]);
        for (x, t) in blocks {
            p.blocks
                .push(Block::linear(vec![*x], Feed::InverseTime(*t)));
        }
        let lines: Vec<usize> = (0..blocks.len()).map(|i| 10 + i).collect();
        Timeline::from_start(&p, &lines, FeedRule::Iso, &[0.0], &[10.0]).unwrap()
    }

    #[test]
    fn a_smooth_program_is_clean() {
        // 1, 2, 3, 2, 1 mm/s over 1 s each; jumps of 1 mm/s, accelerations of 1 mm/s².
        let tl = timeline(&[(1.0, 1.0), (3.0, 1.0), (6.0, 1.0), (8.0, 1.0), (9.0, 1.0)]);
        assert_eq!(check_timeline(&tl, &limits()), []);
    }

    #[test]
    fn each_limit_is_found_at_its_first_and_worst_block() {
        // Velocities 1, 12, 1, then beyond 100 mm.
        let tl = timeline(&[(1.0, 1.0), (13.0, 1.0), (14.0, 1.0), (120.0, 100.0)]);
        let v = check_timeline(&tl, &limits());
        let kinds: Vec<_> = v.iter().map(|x| (x.kind, x.block, x.line)).collect();
        assert_eq!(
            kinds,
            [
                (ViolationKind::Velocity, 2, 11),
                (ViolationKind::VelocityJump, 2, 11),
                (ViolationKind::Acceleration, 2, 11),
                (ViolationKind::Position, 4, 13),
            ]
        );
        let jump = &v[1];
        // 1 → 12 and 12 → 1 mm/s: two joins, 660 mm/min each.
        assert_eq!((jump.count, jump.value, jump.limit), (2, 660.0, 120.0));
        assert_eq!(v[0].value, 720.0);
        assert_eq!(v[3].value, 120.0);
        assert_eq!(v[3].time_s, 103.0);
    }

    #[test]
    fn the_verdict_leads_with_the_worst_and_says_how_often() {
        // Velocities 12, 11, 15 mm/s against 10 mm/s: first at block 1,
        // worst at block 3.
        let tl = timeline(&[(12.0, 1.0), (23.0, 1.0), (38.0, 1.0)]);
        let v = check_timeline(&tl, &limits());
        let velocity = v
            .iter()
            .find(|x| x.kind == ViolationKind::Velocity)
            .unwrap();
        assert_eq!(
            (velocity.block, velocity.worst_block, velocity.count),
            (1, 3, 3)
        );
        assert_eq!(
            velocity.to_string(),
            "velocity at block 3 (line 12, 2.000 s): axis X 900 mm/min > 600 mm/min; \
             broken 3 times from block 1 (line 10)"
        );
        // Once: no count.
        let tl = timeline(&[(1.0, 1.0), (13.0, 1.0), (14.0, 1.0)]);
        let v = check_timeline(&tl, &limits());
        assert_eq!(
            v[0].to_string(),
            "velocity at block 2 (line 11, 1.000 s): axis X 720 mm/min > 600 mm/min"
        );
    }

    #[test]
    fn a_position_broken_on_both_sides_is_told_where_it_first_breaks() {
        let v = Violation {
            kind: ViolationKind::Position,
            axis: "X".into(),
            links: Vec::new(),
            block: 2,
            line: 3,
            time_s: 1.0,
            value: -5.0,
            limit: 0.0,
            unit: "mm",
            count: 2,
            worst_block: 4,
            worst_line: 5,
            worst_time_s: 3.0,
            worst_value: 130.0,
        };
        assert_eq!(
            v.to_string(),
            "position at block 2 (line 3, 1.000 s): axis X -5 mm < 0 mm; \
             broken 2 times from block 2 (line 3)"
        );
    }
}
