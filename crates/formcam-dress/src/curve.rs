//! Exact plane curves: straight segments and circular arcs, their offsets,
//! nearest points and sampling.

use std::f64::consts::PI;

use crate::Point;

/// One piece of a profile or a path: a straight segment or a circular arc,
/// traversed from its start to its end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Piece {
    /// The segment from `from` to `to`.
    Line {
        /// Start point.
        from: Point,
        /// End point.
        to: Point,
    },
    /// The arc `centre + radius * (cos a, sin a)` for `a` running from `start`
    /// to `end` (rad; counter-clockwise when `end > start`).
    Arc {
        /// Centre.
        centre: Point,
        /// Radius, mm (0: a point; the arc then only turns the normal).
        radius: f64,
        /// Polar angle of the start point about the centre, rad.
        start: f64,
        /// Polar angle of the end point, rad.
        end: f64,
    },
}

impl Piece {
    /// The point at parameter `t` in `[0, 1]` (uniform in length).
    pub fn point(&self, t: f64) -> Point {
        match *self {
            Piece::Line { from, to } => from + (to - from) * t,
            Piece::Arc {
                centre,
                radius,
                start,
                end,
            } => centre + Point::polar(start + (end - start) * t) * radius,
        }
    }

    /// The start point.
    pub fn start(&self) -> Point {
        self.point(0.0)
    }

    /// The end point.
    pub fn end(&self) -> Point {
        self.point(1.0)
    }

    /// The unit tangent in the direction of travel at `t`. For an arc of zero
    /// radius it is the tangent the arc would have (its direction turns).
    pub fn tangent(&self, t: f64) -> Point {
        match *self {
            Piece::Line { from, to } => {
                let d = to - from;
                d * (1.0 / d.hypot())
            }
            Piece::Arc { start, end, .. } => {
                let a = start + (end - start) * t;
                if end >= start {
                    Point::polar(a + PI / 2.0)
                } else {
                    Point::polar(a - PI / 2.0)
                }
            }
        }
    }

    /// The unit normal on the left of the direction of travel at `t`.
    pub fn left_normal(&self, t: f64) -> Point {
        let d = self.tangent(t);
        Point::new(-d.y, d.x)
    }

    /// The length, mm.
    pub fn length(&self) -> f64 {
        match *self {
            Piece::Line { from, to } => from.distance(to),
            Piece::Arc {
                radius, start, end, ..
            } => radius * (end - start).abs(),
        }
    }

    /// The signed curvature (1/mm): positive where the piece turns left
    /// (counter-clockwise); 0 for a segment; infinite for an arc of radius 0.
    pub fn curvature(&self) -> f64 {
        match *self {
            Piece::Line { .. } => 0.0,
            Piece::Arc {
                radius, start, end, ..
            } => {
                let k = 1.0 / radius;
                if end >= start { k } else { -k }
            }
        }
    }

    /// The same piece traversed the other way.
    #[must_use]
    pub fn reversed(&self) -> Piece {
        match *self {
            Piece::Line { from, to } => Piece::Line { from: to, to: from },
            Piece::Arc {
                centre,
                radius,
                start,
                end,
            } => Piece::Arc {
                centre,
                radius,
                start: end,
                end: start,
            },
        }
    }

    /// The mirror image in the y axis (`x -> -x`), traversed from the image of
    /// the start to the image of the end.
    #[must_use]
    pub fn mirrored(&self) -> Piece {
        match *self {
            Piece::Line { from, to } => Piece::Line {
                from: from.mirrored(),
                to: to.mirrored(),
            },
            Piece::Arc {
                centre,
                radius,
                start,
                end,
            } => Piece::Arc {
                centre: centre.mirrored(),
                radius,
                start: PI - start,
                end: PI - end,
            },
        }
    }

    /// The offset by `d` to the left of the direction of travel (the exact
    /// equidistant: a parallel segment, a concentric arc), parametrised like
    /// the piece. `None` where an arc's radius would become negative.
    pub fn offset_left(&self, d: f64) -> Option<Piece> {
        match *self {
            Piece::Line { from, to } => {
                let n = self.left_normal(0.0) * d;
                Some(Piece::Line {
                    from: from + n,
                    to: to + n,
                })
            }
            Piece::Arc {
                centre,
                radius,
                start,
                end,
            } => {
                // Counter-clockwise: the left is the centre's side.
                let r = if end >= start { radius - d } else { radius + d };
                (r >= 0.0).then_some(Piece::Arc {
                    centre,
                    radius: r,
                    start,
                    end,
                })
            }
        }
    }

    /// The point of the piece nearest to `p`, and its parameter `t`.
    pub fn nearest(&self, p: Point) -> (Point, f64) {
        match *self {
            Piece::Line { from, to } => {
                let d = to - from;
                let t = ((p - from).dot(d) / d.dot(d)).clamp(0.0, 1.0);
                (self.point(t), t)
            }
            Piece::Arc {
                centre, start, end, ..
            } => {
                let ends = [(self.start(), 0.0), (self.end(), 1.0)];
                let mut best = if p.distance(ends[0].0) <= p.distance(ends[1].0) {
                    ends[0]
                } else {
                    ends[1]
                };
                let q = p - centre;
                if q.hypot() > 0.0 {
                    let a = q.atan2();
                    let (lo, hi) = (start.min(end), start.max(end));
                    // The polar angle of `p` taken into the arc's turn if it falls there.
                    let k = ((lo - a) / (2.0 * PI)).ceil();
                    let a = a + 2.0 * PI * k;
                    if a <= hi {
                        let t = (a - start) / (end - start);
                        let on = self.point(t);
                        if p.distance(on) < p.distance(best.0) {
                            best = (on, t);
                        }
                    }
                }
                best
            }
        }
    }

    /// `n + 1` points at equal steps of length along the piece, both ends included.
    pub fn sample(&self, n: usize, out: &mut Vec<Point>) {
        let n = n.max(1);
        for i in 0..=n {
            out.push(self.point(i as f64 / n as f64));
        }
    }
}

/// The number of equal steps of at most `h` that cover `length` (at least one).
pub(crate) fn steps(length: f64, h: f64) -> usize {
    ((length / h) - 1e-9).ceil().max(1.0) as usize
}

/// A polyline of the circular arc `centre + r (cos a, sin a)`, `a` from `a0`
/// to `a1`, with chords no longer than `chord` (vertices on the arc).
pub(crate) fn arc_polyline(
    centre: Point,
    r: f64,
    a0: f64,
    a1: f64,
    chord: f64,
    out: &mut Vec<Point>,
) {
    let n = if r > 0.0 {
        let da = 2.0 * (chord / (2.0 * r)).min(1.0).asin();
        (((a1 - a0).abs() / da) - 1e-9).ceil().max(1.0) as usize
    } else {
        1
    };
    for i in 0..=n {
        let a = a0 + (a1 - a0) * (i as f64 / n as f64);
        out.push(centre + Point::polar(a) * r);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Point, b: Point) -> bool {
        a.distance(b) < 1e-12
    }

    #[test]
    fn arc_offsets_keep_the_parametrisation() {
        let arc = Piece::Arc {
            centre: Point::new(1.0, 2.0),
            radius: 2.0,
            start: 0.3,
            end: 1.2,
        };
        // Counter-clockwise: the left is the centre's side.
        let off = arc.offset_left(0.5).unwrap_or(arc);
        for t in [0.0, 0.4, 1.0] {
            let p = arc.point(t) + arc.left_normal(t) * 0.5;
            assert!(close(off.point(t), p));
        }
        assert!(arc.offset_left(2.5).is_none());
        let cw = arc.reversed();
        let off = cw.offset_left(0.5).unwrap_or(cw);
        assert!(close(off.start(), cw.start() + cw.left_normal(0.0) * 0.5));
        assert!((off.length() - 2.5 * 0.9).abs() < 1e-12);
    }

    #[test]
    fn mirror_and_reverse() {
        let arc = Piece::Arc {
            centre: Point::new(1.0, 0.0),
            radius: 1.0,
            start: 0.0,
            end: 1.0,
        };
        let m = arc.mirrored();
        assert!(close(m.start(), arc.start().mirrored()));
        assert!(close(m.end(), arc.end().mirrored()));
        let t = arc.tangent(0.5);
        let tm = m.tangent(0.5);
        assert!((tm.x + t.x).abs() < 1e-12 && (tm.y - t.y).abs() < 1e-12);
        let r = arc.reversed();
        assert!(close(r.start(), arc.end()));
        assert!((r.curvature() + arc.curvature()).abs() < 1e-12);
    }

    #[test]
    fn nearest_points() {
        let line = Piece::Line {
            from: Point::new(0.0, 0.0),
            to: Point::new(2.0, 0.0),
        };
        let (q, t) = line.nearest(Point::new(1.5, 3.0));
        assert!(close(q, Point::new(1.5, 0.0)) && (t - 0.75).abs() < 1e-12);
        let arc = Piece::Arc {
            centre: Point::new(0.0, 0.0),
            radius: 1.0,
            start: 3.0,
            end: 3.5,
        };
        let (q, _) = arc.nearest(Point::new(-2.0, 0.0));
        assert!(close(q, Point::new(-1.0, 0.0)));
        // Outside the arc's turn: an end point.
        let (q, t) = arc.nearest(Point::new(2.0, 0.0));
        assert!(t == 0.0 || t == 1.0, "{q:?}");
    }

    #[test]
    fn arc_polylines_have_short_chords() {
        let mut pts = Vec::new();
        arc_polyline(Point::new(0.0, 0.0), 0.3, PI, 1.5 * PI, 0.005, &mut pts);
        for w in pts.windows(2) {
            assert!(w[0].distance(w[1]) <= 0.005 + 1e-12);
        }
        assert!(close(pts[0], Point::new(-0.3, 0.0)));
        assert_eq!(steps(1.0, 0.1), 10);
        assert_eq!(steps(1.0000001, 0.1), 11);
        assert_eq!(steps(0.0, 0.1), 1);
    }
}
