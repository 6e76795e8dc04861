//! The dressing wheel: its section (width and two corner radii), the outline
//! the forming simulation cuts with, and its programmed point A.
//!
//! The section is drawn with the grinding wheel below: the dresser's periphery
//! is its lower side, a straight line between two rounded corners, and its
//! faces are vertical. The corners are named after the half of the grinding
//! wheel's profile they dress (docs/dressing.md, eqs. 7-8: the right half
//! with `rR`): `corner_radius_right` dresses the right half (`x > 0`, whose normals
//! point up and to the right), so in this section it is the dresser's
//! lower-**left** corner; `corner_radius_left` is its lower-right corner.
//!
//! Point A, the point the NC program moves, lies on the periphery's line at
//! the distance `yo` from the dresser's left face.

use std::f64::consts::PI;

use crate::curve::arc_polyline;
use crate::error::{finite, mm};
use crate::{DressError, Point, Profile};

/// Which half of the wheel's profile a pass dresses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// `x > 0`, dressed with `corner_radius_right` (the dresser's lower-left corner).
    Right,
    /// `x < 0`, dressed with `corner_radius_left` (its lower-right corner).
    Left,
}

impl Side {
    /// `right`, `left`.
    pub fn name(self) -> &'static str {
        match self {
            Side::Right => "right",
            Side::Left => "left",
        }
    }
}

/// The dressing wheel as users give it, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DresserSpec {
    /// The width `b`.
    pub width: f64,
    /// The corner that dresses the left half of the profile (`rL` of docs/dressing.md, eq. 8).
    pub corner_radius_left: f64,
    /// The corner that dresses the right half (`rR` of docs/dressing.md, eq. 7).
    pub corner_radius_right: f64,
    /// Point A's distance from the dresser's left face (`Yo`); `None`: `b / 2`.
    pub yo: Option<f64>,
}

/// The dressing wheel, checked against the profile it dresses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dresser {
    /// The width `b`, mm.
    pub width: f64,
    /// Radius of the corner dressing the left half, mm.
    pub r_left: f64,
    /// Radius of the corner dressing the right half, mm.
    pub r_right: f64,
    /// Point A's distance from the left face, mm.
    pub yo: f64,
}

/// The dresser's periphery seen from the wheel: the lower boundary of its
/// section as a polyline (x non-decreasing, corner arcs as chords with their
/// vertices on the arcs), relative to the centre of the corner that dresses,
/// with the faces rising from its two ends.
#[derive(Debug, Clone, PartialEq)]
pub struct Outline {
    /// The vertices, left to right.
    pub points: Vec<Point>,
    /// The outward unit normal of each edge `points[j] -> points[j + 1]`;
    /// its angle runs over `[pi, 2 pi]`, non-decreasing (the periphery is convex).
    pub normals: Vec<Point>,
    /// The index of the lowest vertex.
    pub bottom: usize,
}

impl Dresser {
    /// Checks `spec` against `profile`: positive sizes, corners that fit the
    /// width, `yo` on the periphery, and corner radii no larger than the
    /// smallest concave radius of the profile (the dresser could not form it).
    pub fn new(spec: &DresserSpec, profile: &Profile) -> Result<Dresser, DressError> {
        let b = finite("dresser.width", spec.width, " mm")?;
        let rl = finite("dresser.corner_radius_left", spec.corner_radius_left, " mm")?;
        let rr = finite(
            "dresser.corner_radius_right",
            spec.corner_radius_right,
            " mm",
        )?;
        let concave = profile.min_concave_radius();
        for (field, r) in [
            ("dresser.corner_radius_left", rl),
            ("dresser.corner_radius_right", rr),
        ] {
            if r <= 0.0 {
                return Err(DressError::field(field, mm(r), "must be positive"));
            }
            if r > concave {
                return Err(DressError::field(
                    field,
                    mm(r),
                    format!(
                        "larger than the profile's smallest concave radius (the fillet \
                         wheel.r2 = {}): the dresser cannot form it",
                        mm(concave)
                    ),
                ));
            }
        }
        if b < rl + rr {
            return Err(DressError::field(
                "dresser.width",
                mm(b),
                format!(
                    "must be at least the two corner radii together ({})",
                    mm(rl + rr)
                ),
            ));
        }
        let yo = match spec.yo {
            Some(v) => finite("dresser.yo", v, " mm")?,
            None => b / 2.0,
        };
        if !(0.0..=b).contains(&yo) {
            return Err(DressError::field(
                "dresser.yo",
                mm(yo),
                format!("point A must lie on the periphery: yo in [0, {}]", mm(b)),
            ));
        }
        Ok(Dresser {
            width: b,
            r_left: rl,
            r_right: rr,
            yo,
        })
    }

    /// The radius of the corner that dresses `side`.
    pub fn radius(&self, side: Side) -> f64 {
        match side {
            Side::Right => self.r_right,
            Side::Left => self.r_left,
        }
    }

    /// Point A when the centre of the corner dressing `side` is at `centre`
    /// (docs/dressing.md, eq. 9).
    pub fn reference(&self, side: Side, centre: Point) -> Point {
        match side {
            // The lower-left corner: the left face at centre.x - r.
            Side::Right => Point::new(centre.x - self.r_right + self.yo, centre.y - self.r_right),
            // The lower-right corner: the right face at centre.x + r.
            Side::Left => Point::new(
                centre.x + self.r_left - self.width + self.yo,
                centre.y - self.r_left,
            ),
        }
    }

    /// The periphery relative to the centre of the corner dressing `side`,
    /// its arcs cut into chords of at most `chord` mm.
    pub fn outline(&self, side: Side, chord: f64) -> Outline {
        let flat = self.width - self.r_left - self.r_right;
        // Centres of the lower-left (r_right) and lower-right (r_left) corners.
        let (cl, cr) = match side {
            Side::Right => (
                Point::default(),
                Point::new(flat, self.r_left - self.r_right),
            ),
            Side::Left => (
                Point::new(-flat, self.r_right - self.r_left),
                Point::default(),
            ),
        };
        let mut points = Vec::new();
        arc_polyline(cl, self.r_right, PI, 1.5 * PI, chord, &mut points);
        let mut right = Vec::new();
        arc_polyline(cr, self.r_left, 1.5 * PI, 2.0 * PI, chord, &mut right);
        if flat <= 0.0 {
            // The two bottoms coincide.
            right.remove(0);
        }
        points.extend(right);
        let normals = points
            .windows(2)
            .map(|w| {
                let d = w[1] - w[0];
                // Outward (downward) normal of a left-to-right edge: (dy, -dx).
                Point::new(d.y, -d.x) * (1.0 / d.hypot())
            })
            .collect();
        let bottom = points
            .iter()
            .enumerate()
            .fold((0, f64::INFINITY), |(bi, by), (i, q)| {
                if q.y < by { (i, q.y) } else { (bi, by) }
            })
            .0;
        Outline {
            points,
            normals,
            bottom,
        }
    }
}

impl Outline {
    /// The x-range (relative) outside which the periphery lies above the
    /// height `level` (relative): from the last vertex above it on the way
    /// down to the first above it on the way up. `None` when the whole
    /// periphery is above `level`.
    pub fn below(&self, level: f64) -> Option<(f64, f64)> {
        let p = &self.points;
        let n = p.len();
        let bottom = self.bottom;
        if p[bottom].y > level {
            return None;
        }
        // Falling to the bottom, then rising.
        let i = p[..bottom].partition_point(|q| q.y > level);
        let j = bottom + p[bottom..].partition_point(|q| q.y <= level);
        let lo = p[i.saturating_sub(1)].x;
        let hi = p[j.min(n - 1)].x;
        Some((lo, hi))
    }

    /// The x-range of the periphery's part that leads when the dresser moves
    /// by `v` (edges and faces whose outward normal has a non-negative
    /// component along `v`), relative to the corner centre; `None` when no
    /// part leads (the dresser moves up).
    pub fn leading_range(&self, v: Point) -> Option<(f64, f64)> {
        let n = self.points.len();
        let (first, last) = (self.points[0].x, self.points[n - 1].x);
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        if v.x < 0.0 {
            lo = lo.min(first);
            hi = hi.max(first);
        }
        if v.x > 0.0 {
            lo = lo.min(last);
            hi = hi.max(last);
        }
        let len = v.hypot();
        if len > 0.0 {
            // Leading edges: normal within 90° of v. The normals turn one way
            // over half a turn, so the leading ones make one run (every run
            // is taken all the same).
            let tol = -1e-12 * len;
            let m = self.normals.len();
            let mut j = 0;
            while j < m {
                if self.normals[j].dot(v) >= tol {
                    let start = j;
                    while j < m && self.normals[j].dot(v) >= tol {
                        j += 1;
                    }
                    lo = lo.min(self.points[start].x);
                    hi = hi.max(self.points[j].x);
                } else {
                    j += 1;
                }
            }
        }
        (lo <= hi).then_some((lo, hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{dresser_spec as seed, profile};

    #[test]
    fn outline_is_the_rounded_periphery() {
        let d = Dresser::new(&seed(), &profile()).unwrap();
        for side in [Side::Right, Side::Left] {
            let o = d.outline(side, 0.005);
            let p = &o.points;
            assert!((p[p.len() - 1].x - p[0].x - 2.9).abs() < 1e-12);
            for w in p.windows(2) {
                assert!(w[1].x >= w[0].x);
            }
            for w in o.normals.windows(2) {
                // Turning counter-clockwise.
                assert!(w[0].cross(w[1]) >= -1e-12);
            }
            // The bottom is flat at one height.
            let bottom = p.iter().map(|q| q.y).fold(f64::INFINITY, f64::min);
            let r = d.radius(side);
            assert!((bottom + r).abs() < 1e-12);
            // Point A on the periphery's line, yo from the left face.
            let a = d.reference(side, Point::default());
            assert!((a.y + r).abs() < 1e-12);
            assert!((a.x - p[0].x - 1.45).abs() < 1e-12);
        }
    }

    #[test]
    fn leading_part_follows_the_motion() {
        let d = Dresser::new(&seed(), &profile()).unwrap();
        let o = d.outline(Side::Right, 0.005);
        // Moving left and up (climbing the right half): the lower-left corner leads.
        let (lo, hi) = o.leading_range(Point::new(-1.0, 0.2)).unwrap();
        assert!(
            (lo + 0.279).abs() < 1e-12 && hi < 0.0 && hi > -0.279,
            "{lo} {hi}"
        );
        // Moving straight up: nothing leads.
        assert!(o.leading_range(Point::new(0.0, 1.0)).is_none());
        // Moving down: the whole periphery leads.
        let (lo, hi) = o.leading_range(Point::new(0.0, -1.0)).unwrap();
        assert!((hi - lo - 2.9).abs() < 1e-12);
    }

    #[test]
    fn corner_larger_than_the_fillet_is_refused() {
        let mut s = seed();
        s.corner_radius_right = 0.3;
        let e = Dresser::new(&s, &profile()).unwrap_err().to_string();
        assert!(
            e.starts_with("dresser.corner_radius_right = 0.3 mm: larger than"),
            "{e}"
        );
        let mut s = seed();
        s.width = 0.5;
        assert!(
            Dresser::new(&s, &profile())
                .unwrap_err()
                .to_string()
                .starts_with("dresser.width")
        );
        let mut s = seed();
        s.yo = Some(3.0);
        assert!(
            Dresser::new(&s, &profile())
                .unwrap_err()
                .to_string()
                .starts_with("dresser.yo")
        );
    }
}
