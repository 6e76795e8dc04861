//! Simulation of forming: the dresser stepped along its path, cutting the
//! wheel's contour exactly at every step (docs/dressing.md, eqs. 10-14).
//!
//! At each step the dresser (its whole section: periphery, both corners and
//! faces, the arcs as chords of at most `chord` with their vertices on the
//! arcs) moves by `v` from one path point to the next, and the wheel's
//! contour becomes `min(g, d)` ([`Contour`]). Only the part of the periphery
//! that leads (outward normal along `v`) can meet material the dresser has not
//! already passed through, so only the stretch of the contour under it, swept
//! by `v`, is cut; if a cut ever reached the stretch's end, the stretch is
//! widened and the cut redone.
//!
//! Per step: the removed area, where the periphery enters (A) and leaves (B)
//! the wheel (the cut arc) and the angle of A and B about the
//! dressing corner's centre (the cut-arc angle `epsilon`, eq. 12).

use std::convert::Infallible;
use std::f64::consts::PI;

use formcam_progress::{Cancelled, Phase, Progress, Step as Report};

use crate::contour::{ABOVE, Working, cut};
use crate::curve::{Piece, arc_polyline};
use crate::{Contour, Dresser, Pass, Point, Profile, Stage};

/// One step of the simulation: the move to a path point and what it cut.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The pass (0: right half, 1: left half).
    pub pass: usize,
    /// The stretch of the path.
    pub stage: Stage,
    /// The dressing corner's centre at the step's end.
    pub centre: Point,
    /// Point A (programmed) at the step's end.
    pub reference: Point,
    /// The profile's point formed at the step's end (`None` on the approach).
    pub contact: Option<Point>,
    /// The length of the move (of the corner's centre, and of point A), mm.
    pub length: f64,
    /// The area removed in the step, mm².
    pub area: f64,
    /// Where the dresser's periphery enters and leaves the wheel (the cut
    /// arc's ends, E and L of docs/dressing.md, eq. 12).
    pub cut: Option<(Point, Point)>,
    /// The angle from A to B about the dressing corner's centre, rad.
    pub cut_angle: f64,
    /// Cutting material that no earlier pass has touched, on a piece of the
    /// profile (not entering or leaving the allowance at a corner).
    pub steady: bool,
}

impl Step {
    /// The area removed per mm of path, mm²/mm.
    pub fn area_per_mm(&self) -> f64 {
        if self.length > 0.0 {
            self.area / self.length
        } else {
            0.0
        }
    }
}

/// The result of the simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct Forming {
    /// The wheel's contour before dressing.
    pub initial: Contour,
    /// The wheel's contour after each pass.
    pub after_pass: Vec<Contour>,
    /// Every step, pass after pass.
    pub steps: Vec<Step>,
    /// The chord the arcs were cut into, mm.
    pub chord: f64,
}

impl Forming {
    /// The contour after the last pass.
    pub fn final_contour(&self) -> &Contour {
        self.after_pass.last().unwrap_or(&self.initial)
    }

    /// The sum of the areas removed step by step, mm².
    pub fn removed(&self) -> f64 {
        self.steps.iter().map(|s| s.area).sum()
    }

    /// The area between the initial and the final contour, from the two
    /// contours alone, mm².
    pub fn area_between(&self) -> f64 {
        let base = self
            .final_contour()
            .points()
            .iter()
            .map(|p| p.y)
            .fold(f64::INFINITY, f64::min);
        self.initial.area(base) - self.final_contour().area(base)
    }

    /// How far the final contour lies from `profile`, mm: the smallest and
    /// the largest signed distance (positive outside the profile, along its
    /// normal) over the contour's vertices, the smallest also over the
    /// profile sampled at `h` (the contour's height above it there).
    pub fn deviation(&self, profile: &Profile, h: f64) -> (f64, f64) {
        let c = self.final_contour();
        let pieces = profile.pieces();
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for p in c.points() {
            let Some(y) = profile.y_at(p.x) else {
                continue;
            };
            let d = pieces
                .iter()
                .map(|piece| piece.nearest(*p).0.distance(*p))
                .fold(f64::INFINITY, f64::min);
            let signed = if p.y >= y { d } else { -d };
            lo = lo.min(signed);
            hi = hi.max(signed);
        }
        for q in profile.sample(h) {
            if let Some((l, r)) = c.y_at(q.x) {
                lo = lo.min(l - q.y).min(r - q.y);
            }
        }
        (lo, hi)
    }
}

/// The profile offset outward by `depth` (the wheel with its dressing
/// allowance): arcs and segments offset exactly, an arc of radius `depth`
/// round the apex, cut into chords of at most `chord` and clipped to the
/// wheel's width. `depth` must be below the fillet radius.
pub fn offset_contour(profile: &Profile, depth: f64, chord: f64) -> Contour {
    let pieces = profile.pieces();
    let apex_at = pieces.len() / 2;
    let mut pts: Vec<Point> = Vec::new();
    let push = |piece: Piece, pts: &mut Vec<Point>| {
        let mut seg = Vec::new();
        match piece {
            Piece::Line { from, to } => seg.extend([from, to]),
            Piece::Arc {
                centre,
                radius,
                start,
                end,
            } => arc_polyline(centre, radius, start, end, chord, &mut seg),
        }
        // A joint is the end of the piece before.
        let skip = usize::from(!pts.is_empty());
        for p in seg.into_iter().skip(skip) {
            let x = pts.last().map_or(p.x, |q: &Point| q.x.max(p.x));
            pts.push(Point::new(x, p.y));
        }
    };
    for (i, piece) in pieces.iter().enumerate() {
        if i == apex_at {
            let a = profile.apex_angle;
            push(
                Piece::Arc {
                    centre: profile.apex,
                    radius: depth,
                    start: PI - a,
                    end: a,
                },
                &mut pts,
            );
        }
        if let Some(off) = piece.offset_left(depth) {
            push(off, &mut pts);
        }
    }
    let half = profile.d.x;
    let c = Contour::from_sorted(pts);
    c.clipped(-half, half).unwrap_or(c)
}

/// Steps between two progress reports of the simulation.
const CHUNK: u64 = 4096;

/// Steps the dresser along `passes` from the contour `initial`.
pub fn simulate(dresser: &Dresser, passes: &[Pass], initial: &Contour, chord: f64) -> Forming {
    let Ok(forming) = step_through(dresser, passes, initial, chord, |_, _| {
        Ok::<(), Infallible>(())
    });
    forming
}

/// [`simulate`] reporting the steps done to `progress` (every 4096 steps);
/// [`Cancelled`] when it asks to stop.
pub fn simulate_with(
    dresser: &Dresser,
    passes: &[Pass],
    initial: &Contour,
    chord: f64,
    progress: &dyn Progress,
) -> Result<Forming, Cancelled> {
    step_through(dresser, passes, initial, chord, |done, total| {
        progress.checkpoint(Report::new(Phase::Forming, done, total))
    })
}

/// The simulation, `tick(done, total)` called at its start, every
/// [`CHUNK`] steps and at its end.
fn step_through<E>(
    dresser: &Dresser,
    passes: &[Pass],
    initial: &Contour,
    chord: f64,
    mut tick: impl FnMut(u64, u64) -> Result<(), E>,
) -> Result<Forming, E> {
    let total: u64 = passes
        .iter()
        .map(|p| p.points.len().saturating_sub(1) as u64)
        .sum();
    let mut done = 0;
    tick(done, total)?;
    let mut work = Working::new(initial);
    let mut steps = Vec::new();
    let mut after_pass = Vec::new();
    let mut g = Vec::new();
    let mut out = Vec::new();
    let mut tool = Vec::new();
    for (pi, pass) in passes.iter().enumerate() {
        let outline = dresser.outline(pass.side, chord);
        let tpl = &outline.points;
        for w in pass.points.windows(2) {
            let (c0, c1) = (w[0].centre, w[1].centre);
            let v = c1 - c0;
            let mut step = Step {
                pass: pi,
                stage: w[1].stage,
                centre: c1,
                reference: w[1].reference,
                contact: w[1].contact,
                length: v.hypot(),
                area: 0.0,
                cut: None,
                cut_angle: 0.0,
                steady: false,
            };
            if let Some((lo, hi)) = outline.leading_range(v) {
                let (dom_lo, dom_hi) = work.span();
                let margin = 1e-9;
                let mut xa = c1.x + lo - v.x.max(0.0) - margin;
                let mut xb = c1.x + hi + (-v.x).max(0.0) + margin;
                loop {
                    let (has_l, has_r) = work.take(xa, xb, &mut g);
                    let inner = usize::from(has_l)..g.len() - usize::from(has_r);
                    // Only where the periphery dips below the highest vertex
                    // of the stretch can it cut: narrow the range to there.
                    let top = g.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
                    let (na, nb) = match outline.below(top - c1.y) {
                        Some((l, r)) => (xa.max(c1.x + l - margin), xb.min(c1.x + r + margin)),
                        None => (xb, xa),
                    };
                    out.clear();
                    let r = if na <= nb {
                        let i0 = inner.start + g[inner.clone()].partition_point(|p| p.x < na);
                        let i1 = inner.start + g[inner.clone()].partition_point(|p| p.x <= nb);
                        out.extend_from_slice(&g[inner.start..i0]);
                        let sub = &g[i0.saturating_sub(1)..(i1 + 1).min(g.len())];
                        tool_slice(tpl, c1, na, nb, &mut tool);
                        let r = cut(sub, i0 > 0, i1 < g.len(), &tool, na, nb, &mut out);
                        out.extend_from_slice(&g[i1..inner.end]);
                        r
                    } else {
                        out.extend_from_slice(&g[inner.clone()]);
                        Default::default()
                    };
                    if r.spills && (xa > dom_lo || xb < dom_hi) {
                        work.put(&g[inner], false);
                        let wide = dresser.width;
                        xa -= wide;
                        xb += wide;
                        continue;
                    }
                    work.put(&out, v.x < 0.0);
                    step.area = r.area;
                    if let (Some(a), Some(b)) = (r.enter, r.leave) {
                        step.cut = Some((a, b));
                        step.cut_angle = ((b - c1).atan2() - (a - c1).atan2()).rem_euclid(2.0 * PI);
                    }
                    break;
                }
            }
            steps.push(step);
            done += 1;
            if done % CHUNK == 0 {
                tick(done, total)?;
            }
        }
        after_pass.push(work.contour());
    }
    mark_steady(&mut steps, passes.len());
    tick(total, total)?;
    Ok(Forming {
        initial: initial.clone(),
        after_pass,
        steps,
        chord,
    })
}

/// The dresser's periphery at `centre` over `[xa, xb]`: the template's
/// vertices there with one more on each side, its faces as vertical rises to
/// [`ABOVE`] and [`ABOVE`] beyond.
fn tool_slice(tpl: &[Point], centre: Point, xa: f64, xb: f64, out: &mut Vec<Point>) {
    out.clear();
    let n = tpl.len();
    let (ra, rb) = (xa - centre.x, xb - centre.x);
    let i0 = tpl.partition_point(|p| p.x < ra);
    let i1 = tpl.partition_point(|p| p.x <= rb);
    let first = if i0 == 0 {
        let x = tpl[0].x + centre.x;
        out.push(Point::new(x.min(xa) - 1.0, ABOVE));
        out.push(Point::new(x, ABOVE));
        0
    } else {
        i0 - 1
    };
    let last = if i1 >= n { n - 1 } else { i1 };
    out.extend(tpl[first..=last].iter().map(|p| *p + centre));
    if i1 >= n {
        let x = tpl[n - 1].x + centre.x;
        out.push(Point::new(x, ABOVE));
        out.push(Point::new(x.max(xb) + 1.0, ABOVE));
    }
}

/// Marks the steps that cut, on a piece of the profile, material no earlier
/// pass has touched.
fn mark_steady(steps: &mut [Step], passes: usize) {
    let mut touched: Vec<(f64, f64)> = Vec::with_capacity(passes);
    for p in 0..passes {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for s in steps.iter_mut().filter(|s| s.pass == p) {
            if let Some((a, b)) = s.cut.filter(|_| s.area > 0.0) {
                let (x0, x1) = (a.x.min(b.x), a.x.max(b.x));
                lo = lo.min(x0);
                hi = hi.max(x1);
                s.steady =
                    s.stage.on_profile() && touched.iter().all(|&(t0, t1)| x1 < t0 || x0 > t1);
            }
        }
        touched.push((lo, hi));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dresser_path;
    use crate::fixtures::setup;

    #[test]
    fn the_allowance_is_the_offset() {
        let (p, _) = setup();
        let c = offset_contour(&p, 0.05, 0.005);
        let pts = c.points();
        assert!((pts[0].x + 3.0).abs() < 1e-12 && (pts[pts.len() - 1].x - 3.0).abs() < 1e-12);
        // Every vertex 0.05 from the profile (on the offset), chords inside.
        for q in pts {
            let d = p
                .pieces()
                .iter()
                .map(|piece| piece.nearest(*q).0.distance(*q))
                .fold(f64::INFINITY, f64::min);
            assert!((d - 0.05).abs() < 1e-9, "{q:?} {d}");
        }
    }

    #[test]
    fn areas_add_up_and_the_profile_is_formed() {
        let (p, d) = setup();
        let h = 0.01;
        let chord = h / 2.0;
        let passes = dresser_path(&p, &d, h);
        let start = offset_contour(&p, 0.05, chord);
        let f = simulate(&d, &passes, &start, chord);
        let (removed, between) = (f.removed(), f.area_between());
        assert!(
            ((removed - between) / between).abs() < 1e-9,
            "{removed} {between}"
        );
        // Roughly the allowance times the profile's length.
        assert!(
            (between / (0.05 * p.length()) - 1.0).abs() < 0.1,
            "{between}"
        );
        let (lo, hi) = f.deviation(&p, h);
        assert!(lo > -1e-9, "{lo}");
        assert!(hi < 1e-4, "{hi}");
        assert!(f.steps.iter().any(|s| s.steady));
    }
}
