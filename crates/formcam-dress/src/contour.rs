//! The wheel's contour as a polyline graph, and the exact cut of a dresser
//! outline out of it.
//!
//! A contour is the upper boundary `y = g(x)` of the wheel's section over
//! `[-B/2, B/2]` (the wheel's faces below its ends): vertices with `x`
//! non-decreasing, where two vertices at one `x` are a vertical step. The
//! dresser is the region above its periphery (also a polyline graph, with
//! vertical faces at its ends). Removing the dresser from the wheel is the
//! pointwise minimum `min(g, d)`, itself a polyline graph whose vertices are
//! those of `g` where `g` is lower, those of `d` where `d` is lower, and the
//! crossings; the area removed is `integral of max(0, g - d)`, summed exactly
//! over the pieces between breakpoints, so the removed areas of all steps add
//! up to the area between the first and the last contour (to rounding).

use crate::{ContourFault, Point};

/// A value standing for "no dresser here" (above any wheel), mm.
pub(crate) const ABOVE: f64 = 1.0e9;

/// The wheel's contour: the upper boundary `y = g(x)` of its section, a
/// polyline with `x` non-decreasing (two vertices at one `x`: a vertical step).
#[derive(Debug, Clone, PartialEq)]
pub struct Contour {
    points: Vec<Point>,
}

impl Contour {
    /// A contour through `points`; `Err` names what is wrong (fewer than two
    /// points, a value that is not finite, `x` decreasing).
    pub fn new(points: Vec<Point>) -> Result<Contour, ContourFault> {
        if points.len() < 2 {
            return Err(ContourFault::TooFewPoints);
        }
        if let Some(i) = points.iter().position(|p| !p.is_finite()) {
            return Err(ContourFault::NotFinite { point: i + 1 });
        }
        if let Some(i) = points.windows(2).position(|w| w[1].x < w[0].x) {
            return Err(ContourFault::Decreasing {
                from: points[i].x,
                to: points[i + 1].x,
                point: i + 2,
            });
        }
        Ok(Contour { points })
    }

    /// Takes points known to be in order.
    pub(crate) fn from_sorted(points: Vec<Point>) -> Contour {
        Contour { points }
    }

    /// The vertices.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// The area between the contour and the level `base` over the contour's
    /// span, `integral of (g - base) dx`, mm².
    pub fn area(&self, base: f64) -> f64 {
        self.points
            .windows(2)
            .map(|w| (w[1].x - w[0].x) * ((w[0].y - base) + (w[1].y - base)) * 0.5)
            .sum()
    }

    /// The contour's height at `x` from the left and from the right (they
    /// differ at a vertical step); `None` outside the span.
    pub fn y_at(&self, x: f64) -> Option<(f64, f64)> {
        let p = &self.points;
        let n = p.len();
        if !(x >= p[0].x && x <= p[n - 1].x) {
            return None;
        }
        let i = p.partition_point(|q| q.x < x);
        if i < n && p[i].x == x {
            let j = i + p[i..].partition_point(|q| q.x == x) - 1;
            return Some((p[i].y, p[j].y));
        }
        let (a, b) = (p[i - 1], p[i]);
        let y = a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
        Some((y, y))
    }

    /// The part of the contour over `[x0, x1]` (cut by interpolation).
    pub fn clipped(&self, x0: f64, x1: f64) -> Option<Contour> {
        let (l, _) = self.y_at(x0)?;
        let (_, r) = self.y_at(x1)?;
        let mut pts = vec![Point::new(x0, l)];
        pts.extend(self.points.iter().filter(|p| p.x > x0 && p.x < x1));
        pts.push(Point::new(x1, r));
        Some(Contour { points: pts })
    }
}

/// What one cut did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct CutResult {
    /// The area removed, mm².
    pub area: f64,
    /// Where the dresser's periphery enters and leaves the wheel (first and
    /// last point of the cut along `x`).
    pub enter: Option<Point>,
    /// See `enter`.
    pub leave: Option<Point>,
    /// The cut reaches the left or right end of the range (not a domain end):
    /// the range was too narrow.
    pub spills: bool,
}

/// The height of a graph polyline at `x` from the left and from the right,
/// `i` the first index with `p[i].x >= x` from an earlier call (advanced
/// here; calls come with `x` increasing), and whether a vertex lies at `x`.
#[inline]
fn value_at(p: &[Point], i: &mut usize, x: f64) -> (f64, f64, bool) {
    let n = p.len();
    while *i < n && p[*i].x < x {
        *i += 1;
    }
    if *i < n && p[*i].x == x {
        let mut j = *i;
        while j + 1 < n && p[j + 1].x == x {
            j += 1;
        }
        return (p[*i].y, p[j].y, true);
    }
    if *i == 0 || *i == n {
        // Outside: only the dresser's polyline is asked there, and it is
        // built with anchors beyond the range.
        return (ABOVE, ABOVE, false);
    }
    let (a, b) = (p[*i - 1], p[*i]);
    let y = a.y + (b.y - a.y) * ((x - a.x) / (b.x - a.x));
    (y, y, false)
}

/// Replaces the wheel contour `g` over `[xa, xb]` by `min(g, d)`, appending
/// the new vertices in `[xa, xb]` to `out`.
///
/// `g` holds the contour's vertices in the range, with the neighbours just
/// outside it first and last where there are any (where there are none, the
/// range ends at the contour's end). `d` is the dresser's periphery covering
/// the range, its faces and the parts beyond as vertices at [`ABOVE`].
pub(crate) fn cut(
    g: &[Point],
    has_left: bool,
    has_right: bool,
    d: &[Point],
    xa: f64,
    xb: f64,
    out: &mut Vec<Point>,
) -> CutResult {
    let mut res = CutResult::default();
    if g.len() < 2 {
        return res;
    }
    let xa = if has_left { xa } else { xa.max(g[0].x) };
    let xb = if has_right {
        xb
    } else {
        xb.min(g[g.len() - 1].x)
    };
    if xa > xb || xa.is_nan() || xb.is_nan() {
        return res;
    }
    // Breakpoints: the range's ends and every vertex of either polyline
    // inside it, in order.
    let inner_g = &g[usize::from(has_left)..g.len() - usize::from(has_right)];
    let d0 = d.partition_point(|p| p.x <= xa);
    let inner_d = &d[d0..d.partition_point(|p| p.x < xb).max(d0)];
    let (mut ig, mut id) = (0usize, 0usize);
    let (mut jg, mut jd) = (0usize, 0usize);
    let mut x = xa;
    let mut prev: Option<(f64, f64, f64)> = None; // (x, g right, d right)
    loop {
        let (gl, gr, g_at) = value_at(g, &mut ig, x);
        let (dl, dr, d_at) = value_at(d, &mut id, x);
        if let Some((x0, g0, t0)) = prev {
            // The open interval (x0, x), where both are linear.
            let (e0, e1) = (g0 - t0, gl - dl);
            let w = x - x0;
            if e0 >= 0.0 && e1 >= 0.0 {
                res.area += 0.5 * (e0 + e1) * w;
                // A cut from or to a point where the two touch.
                if e0 == 0.0 && e1 > 0.0 {
                    res.enter.get_or_insert(Point::new(x0, g0));
                }
                if e1 == 0.0 && e0 > 0.0 {
                    res.leave = Some(Point::new(x, gl));
                }
            } else if e0 > 0.0 || e1 > 0.0 {
                let t = e0 / (e0 - e1);
                let c = Point::new(x0 + t * w, g0 + t * (gl - g0));
                if t > 0.0 && t < 1.0 {
                    out.push(c);
                }
                if e0 > 0.0 {
                    res.area += 0.5 * e0 * t * w;
                    res.leave = Some(c);
                } else {
                    res.area += 0.5 * e1 * (1.0 - t) * w;
                    res.enter.get_or_insert(c);
                }
            }
        } else if has_left && gr - dr > 1e-12 {
            res.spills = true;
        }
        // The station at x: the new contour's vertices there, unless the
        // lower polyline runs straight through it on both sides.
        let (nl, nr) = (gl.min(dl), gr.min(dr));
        let g_below = gl < dl && gr < dr;
        let d_below = dl < gl && dr < gr;
        let domain_end = (x == xa && !has_left) || (x >= xb && !has_right);
        let skip = ((g_below && !g_at) || (d_below && !d_at)) && !domain_end;
        if nl != nr {
            out.push(Point::new(x, nl));
            out.push(Point::new(x, nr));
        } else if (g_at || d_at || domain_end) && !skip {
            out.push(Point::new(x, nl));
        }
        let (cut_l, cut_r) = (gl > dl, gr > dr);
        if cut_r && (!cut_l || prev.is_none()) && res.enter.is_none() {
            res.enter = Some(Point::new(x, if dl >= ABOVE { gr } else { dr }));
        }
        if cut_l && !cut_r {
            res.leave = Some(Point::new(x, if dr >= ABOVE { gl } else { dl }));
        }
        prev = Some((x, gr, dr));
        if x >= xb {
            if cut_l && cut_r {
                res.leave = Some(Point::new(x, dl));
                if has_right && gl - dl > 1e-12 {
                    res.spills = true;
                }
            }
            break;
        }
        // The next breakpoint: the nearest vertex of either polyline past x.
        while jg < inner_g.len() && inner_g[jg].x <= x {
            jg += 1;
        }
        while jd < inner_d.len() && inner_d[jd].x <= x {
            jd += 1;
        }
        let ng = inner_g.get(jg).map_or(xb, |p| p.x);
        let nd = inner_d.get(jd).map_or(xb, |p| p.x);
        x = ng.min(nd).min(xb);
    }
    res
}

/// The wheel's contour during the simulation: a gap buffer round the place
/// being cut. `lo` holds the vertices left of it in order, `hi` those right
/// of it in reverse order, so moving the place along costs only the vertices
/// passed.
#[derive(Debug, Clone, Default)]
pub(crate) struct Working {
    lo: Vec<Point>,
    hi: Vec<Point>,
    from_lo: Vec<Point>,
    from_hi: Vec<Point>,
}

impl Working {
    pub(crate) fn new(c: &Contour) -> Working {
        Working {
            lo: c.points.clone(),
            hi: Vec::new(),
            from_lo: Vec::new(),
            from_hi: Vec::new(),
        }
    }

    /// The span of the contour.
    pub(crate) fn span(&self) -> (f64, f64) {
        let first = self.lo.first().or_else(|| self.hi.last());
        let last = self.hi.first().or_else(|| self.lo.last());
        match (first, last) {
            (Some(a), Some(b)) => (a.x, b.x),
            _ => (0.0, 0.0),
        }
    }

    /// Moves the vertices with `x` in `[xa, xb]` into `g`, after the left
    /// neighbour (if any), and appends the right neighbour; returns whether
    /// there are neighbours.
    pub(crate) fn take(&mut self, xa: f64, xb: f64, g: &mut Vec<Point>) -> (bool, bool) {
        // Vertices of `lo` in the range (last first), then of `hi` (in order).
        self.from_lo.clear();
        self.from_hi.clear();
        while let Some(&p) = self.lo.last() {
            if p.x < xa {
                break;
            }
            self.lo.pop();
            if p.x > xb {
                self.hi.push(p);
            } else {
                self.from_lo.push(p);
            }
        }
        while let Some(&p) = self.hi.last() {
            if p.x > xb {
                break;
            }
            self.hi.pop();
            if p.x < xa {
                // The range moved right past it (then `from_lo` is empty).
                self.lo.push(p);
            } else {
                self.from_hi.push(p);
            }
        }
        // g = left neighbour, lo's part, hi's part, right neighbour.
        let left = self.lo.last().copied();
        let right = self.hi.last().copied();
        g.clear();
        g.extend(left);
        g.extend(self.from_lo.iter().rev());
        g.extend_from_slice(&self.from_hi);
        g.extend(right);
        (left.is_some(), right.is_some())
    }

    /// Puts the vertices `mid` (in order, between `lo` and `hi`) back: on the
    /// right of the place (`to_hi`) or on its left.
    pub(crate) fn put(&mut self, mid: &[Point], to_hi: bool) {
        if to_hi {
            self.hi.extend(mid.iter().rev());
        } else {
            self.lo.extend_from_slice(mid);
        }
    }

    /// The contour as it stands.
    pub(crate) fn contour(&self) -> Contour {
        let mut pts = self.lo.clone();
        pts.extend(self.hi.iter().rev());
        Contour { points: pts }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dresser periphery from its vertices, with faces and anchors.
    fn tool(p: &[Point]) -> Vec<Point> {
        let mut d = vec![Point::new(p[0].x - 10.0, ABOVE), Point::new(p[0].x, ABOVE)];
        d.extend_from_slice(p);
        let l = p[p.len() - 1];
        d.push(Point::new(l.x, ABOVE));
        d.push(Point::new(l.x + 10.0, ABOVE));
        d
    }

    fn area_between(a: &Contour, b: &Contour) -> f64 {
        a.area(0.0) - b.area(0.0)
    }

    #[test]
    fn a_v_cut_out_of_a_flat_wheel() {
        let g = Contour::new(vec![Point::new(-2.0, 1.0), Point::new(2.0, 1.0)]).unwrap();
        let d = tool(&[
            Point::new(-1.0, 1.5),
            Point::new(0.0, 0.5),
            Point::new(1.0, 1.5),
        ]);
        let mut out = Vec::new();
        let r = cut(g.points(), false, false, &d, -2.0, 2.0, &mut out);
        // A triangle of base 1 and height 0.5.
        assert!((r.area - 0.25).abs() < 1e-15, "{r:?}");
        let after = Contour::new(out).unwrap();
        assert_eq!(after.points().len(), 5);
        assert!((area_between(&g, &after) - r.area).abs() < 1e-15);
        assert_eq!(r.enter, Some(Point::new(-0.5, 1.0)));
        assert_eq!(r.leave, Some(Point::new(0.5, 1.0)));
        assert!(!r.spills);
    }

    #[test]
    fn a_face_cuts_a_vertical_step() {
        let g = Contour::new(vec![Point::new(-2.0, 1.0), Point::new(2.0, 1.0)]).unwrap();
        // A flat-bottomed dresser from x = 0.5 on, bottom at 0.2.
        let d = tool(&[Point::new(0.5, 0.2), Point::new(5.0, 0.2)]);
        let mut out = Vec::new();
        let r = cut(g.points(), false, false, &d, -2.0, 2.0, &mut out);
        assert!((r.area - 1.5 * 0.8).abs() < 1e-15, "{r:?}");
        let after = Contour::new(out).unwrap();
        assert_eq!(
            after.points(),
            &[
                Point::new(-2.0, 1.0),
                Point::new(0.5, 1.0),
                Point::new(0.5, 0.2),
                Point::new(2.0, 0.2)
            ]
        );
        assert_eq!(after.y_at(0.5), Some((1.0, 0.2)));
        assert_eq!(r.enter, Some(Point::new(0.5, 1.0)));
        // A second dresser over the step: it cuts into the step's corner.
        let d2 = tool(&[Point::new(0.0, 0.5), Point::new(1.0, 0.5)]);
        let mut out2 = Vec::new();
        let r2 = cut(after.points(), false, false, &d2, -2.0, 2.0, &mut out2);
        assert!((r2.area - 0.5 * 0.5).abs() < 1e-15, "{r2:?}");
        let after2 = Contour::new(out2).unwrap();
        assert!((area_between(&after, &after2) - r2.area).abs() < 1e-15);
    }

    #[test]
    fn cuts_within_a_window_keep_the_area() {
        // A wavy contour, many round cutters along it through the gap buffer.
        let pts: Vec<Point> = (0..=400)
            .map(|i| {
                let x = -2.0 + 0.01 * i as f64;
                Point::new(x, 1.0 + 0.1 * (7.0 * x).sin())
            })
            .collect();
        let start = Contour::new(pts).unwrap();
        let mut w = Working::new(&start);
        let mut g = Vec::new();
        let mut out = Vec::new();
        let mut total = 0.0;
        for k in 0..300 {
            let cx = 1.8 - 0.012 * k as f64;
            let cy = 1.25 + 0.05 * (3.0 * cx).cos();
            let mut circle = Vec::new();
            crate::curve::arc_polyline(
                Point::new(cx, cy),
                0.3,
                std::f64::consts::PI,
                2.0 * std::f64::consts::PI,
                0.01,
                &mut circle,
            );
            let d = tool(&circle);
            let (xa, xb) = (cx - 0.31, cx + 0.31);
            let (hl, hr) = w.take(xa, xb, &mut g);
            out.clear();
            let r = cut(&g, hl, hr, &d, xa, xb, &mut out);
            assert!(!r.spills);
            w.put(&out, true);
            total += r.area;
        }
        let end = w.contour();
        assert!(Contour::new(end.points().to_vec()).is_ok());
        let between = area_between(&start, &end);
        assert!(total > 0.1);
        assert!(
            ((total - between) / between).abs() < 1e-12,
            "{total} {between}"
        );
    }
}
