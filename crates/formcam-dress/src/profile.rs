//! The wheel's profile: the gothic arch with fillets and tilted flanks,
//! built exactly from arcs and segments joined where they are tangent.
//!
//! Coordinates (docs/dressing.md): the ball's centre at the origin, `x` along the
//! wheel's axis, `y` radial and outward; the wheel's material lies below the
//! profile, which is symmetric about the `y` axis. The right half, from the
//! apex outward:
//!
//! * the flank arc AB, radius `R1`, centre `O1 = (Rs - R1) (cos a, sin a)`
//!   (docs/dressing.md, eq. 1), from the apex on the `y` axis down to the polar angle
//!   `arc_angle` about `O1` (B); it touches the ball at the contact angle `a`;
//! * the fillet BC, radius `R2`, centre `O2 = O1 + (R1 + R2) (cos a2, sin a2)`
//!   (eq. 2, `a2` the arc angle; the pieces: eqs. 3-5), outside the material (concave), tangent to
//!   AB at B and to the flank at C;
//! * the flank CD, falling outward at `flank_tilt` from C to the wheel's edge
//!   `x = B/2` (D).
//!
//! The two arcs AB meet at the apex in a corner (the gothic arch's point);
//! every other joint is tangent by construction.

use std::f64::consts::PI;

use crate::curve::{Piece, steps};
use crate::error::{deg, finite, mm};
use crate::{DressError, Point};

/// The wheel's profile as users give it (mm, rad), before it is checked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelSpec {
    /// The ball's radius `Rs`, mm.
    pub ball_radius: f64,
    /// The contact angle `a` of the ball on the flank arcs, from the wheel's
    /// axis direction, rad, in `(0, pi/2)`.
    pub contact_angle: f64,
    /// The flank arcs' radius `R1 > Rs`, mm.
    pub r1: f64,
    /// The fillets' radius `R2`, mm.
    pub r2: f64,
    /// The wheel's width `B`, mm.
    pub width: f64,
    /// The flanks' tilt from the wheel's axis, rad: positive where the flank
    /// falls towards the wheel's edges.
    pub flank_tilt: f64,
    /// The polar angle about `O1` where the flank arc ends and the fillet
    /// starts (the "arc angle", 0.2618 rad in the bundled example), rad, in `(0, a)`.
    pub arc_angle: f64,
}

/// A piece of the profile's right half.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Element {
    /// The flank arc AB (radius `R1`, convex).
    Arch,
    /// The fillet BC (radius `R2`, concave).
    Fillet,
    /// The straight flank CD.
    Flank,
}

impl Element {
    /// `arch`, `fillet`, `flank`.
    pub fn name(self) -> &'static str {
        match self {
            Element::Arch => "arch",
            Element::Fillet => "fillet",
            Element::Flank => "flank",
        }
    }
}

/// Where the ball touches one flank arc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// The contact point.
    pub point: Point,
    /// Its polar angle about the ball's centre, rad (`a` on the right,
    /// `pi - a` on the left).
    pub angle: f64,
    /// The distance from the ball's centre to the flank arc less `Rs`, mm
    /// (0: touching; negative: the ball would cut into the wheel).
    pub gap: f64,
}

/// How well the profile's pieces join.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joints {
    /// The largest distance between a piece's end and the next one's start, mm.
    pub gap: f64,
    /// The largest angle between a piece's end tangent and the next one's
    /// start tangent at the joints meant to be smooth (all but the apex), rad.
    pub angle: f64,
    /// The angle between the tangents of the two flank arcs at the apex, rad
    /// (the gothic arch's corner, by design).
    pub apex_angle: f64,
}

/// The wheel's profile, exact.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    spec: WheelSpec,
    /// Centre of the right flank arc AB.
    pub o1: Point,
    /// Centre of the right fillet BC.
    pub o2: Point,
    /// The apex (where the two flank arcs meet on the `y` axis).
    pub apex: Point,
    /// End of the right flank arc, start of the fillet.
    pub b: Point,
    /// End of the right fillet, start of the flank.
    pub c: Point,
    /// The right edge of the profile (`x = B/2`).
    pub d: Point,
    /// Polar angle of the apex about `O1`, rad.
    pub apex_angle: f64,
    right: [Piece; 3],
}

impl Profile {
    /// Checks `spec` and builds the profile. Errors name the job field
    /// (`wheel.r1`, `wheel.contact_angle_deg`, ...) and the allowed range.
    pub fn new(spec: &WheelSpec) -> Result<Profile, DressError> {
        let checked = finite_spec(spec)?;
        check_ranges(&checked, spec.contact_angle)?;
        Profile::build(checked)
    }

    /// The profile of the checked `spec`: the pieces' centres and ends, the
    /// fillet within the width.
    fn build(spec: WheelSpec) -> Result<Profile, DressError> {
        let WheelSpec {
            ball_radius: rs,
            contact_angle: a,
            r1,
            r2,
            width,
            flank_tilt: tilt,
            arc_angle: a2,
        } = spec;
        let u = Point::polar(a);
        let o1 = u * (rs - r1);
        // The apex: the flank arc crosses the y axis.
        let apex_angle = (-o1.x / r1).acos();
        let apex = o1 + Point::polar(apex_angle) * r1;
        let ub = Point::polar(a2);
        let b = o1 + ub * r1;
        let o2 = o1 + ub * (r1 + r2);
        // The fillet runs counter-clockwise about O2 from B (angle pi + a2) to
        // C, where its tangent is the flank's direction (cos t, -sin t).
        let fillet_end = 1.5 * PI - tilt;
        let c = o2 + Point::polar(fillet_end) * r2;
        let half = width / 2.0;
        if c.x >= half {
            return Err(DressError::field(
                "wheel.r2",
                mm(r2),
                format!(
                    "the fillet does not fit the width {}: it ends at x = {}, beyond the wheel's \
                     edge at {}; make r2 or the arc angle smaller, or the width larger",
                    mm(width),
                    mm(c.x),
                    mm(half)
                ),
            ));
        }
        let d = Point::new(half, c.y - (half - c.x) * tilt.tan());
        let right = [
            Piece::Arc {
                centre: o1,
                radius: r1,
                start: apex_angle,
                end: a2,
            },
            Piece::Arc {
                centre: o2,
                radius: r2,
                start: PI + a2,
                end: fillet_end,
            },
            Piece::Line { from: c, to: d },
        ];
        Ok(Profile {
            spec,
            o1,
            o2,
            apex,
            b,
            c,
            d,
            apex_angle,
            right,
        })
    }

    /// The checked parameters.
    pub fn spec(&self) -> &WheelSpec {
        &self.spec
    }

    /// The right half's pieces from the apex outward: arch, fillet, flank.
    pub fn right_half(&self) -> [(Element, Piece); 3] {
        [
            (Element::Arch, self.right[0]),
            (Element::Fillet, self.right[1]),
            (Element::Flank, self.right[2]),
        ]
    }

    /// The whole profile from the left edge to the right edge (x increasing):
    /// left flank, left fillet, left arch, right arch, right fillet, right flank.
    pub fn pieces(&self) -> Vec<Piece> {
        let mut all: Vec<Piece> = self
            .right
            .iter()
            .rev()
            .map(|p| p.mirrored().reversed())
            .collect();
        all.extend(self.right.iter().copied());
        all
    }

    /// The profile's height `y` at `x` (`|x| <= B/2`), exact; `None` outside.
    pub fn y_at(&self, x: f64) -> Option<f64> {
        let ax = x.abs();
        if ax > self.d.x || ax.is_nan() {
            return None;
        }
        let s = &self.spec;
        Some(if ax <= self.b.x {
            let dx = ax - self.o1.x;
            self.o1.y + (s.r1 * s.r1 - dx * dx).max(0.0).sqrt()
        } else if ax <= self.c.x {
            let dx = ax - self.o2.x;
            self.o2.y - (s.r2 * s.r2 - dx * dx).max(0.0).sqrt()
        } else {
            self.c.y + (ax - self.c.x) * (self.d.y - self.c.y) / (self.d.x - self.c.x)
        })
    }

    /// The profile sampled with steps of at most `h` along each piece, from the
    /// left edge to the right edge (docs/dressing.md, eqs. 3-5); the joints are sample points.
    pub fn sample(&self, h: f64) -> Vec<Point> {
        let mut out = Vec::new();
        for p in self.pieces() {
            if !out.is_empty() {
                out.pop();
            }
            p.sample(steps(p.length(), h), &mut out);
        }
        out
    }

    /// The length of the whole profile, mm.
    pub fn length(&self) -> f64 {
        2.0 * self.right.iter().map(Piece::length).sum::<f64>()
    }

    /// Where the ball (centre at the origin, radius `Rs`) touches the two
    /// flank arcs: the points of the arcs nearest to its centre.
    pub fn contacts(&self) -> [Contact; 2] {
        let rs = self.spec.ball_radius;
        let arch = self.right[0];
        [arch, arch.mirrored()].map(|p| {
            let (q, _) = p.nearest(Point::default());
            Contact {
                point: q,
                angle: q.atan2(),
                gap: q.hypot() - rs,
            }
        })
    }

    /// The smallest distance from the ball's centre to the whole profile less
    /// `Rs`, mm: 0 when the ball touches and nowhere cuts into the wheel.
    pub fn ball_gap(&self) -> f64 {
        self.pieces()
            .iter()
            .map(|p| p.nearest(Point::default()).0.hypot())
            .fold(f64::INFINITY, f64::min)
            - self.spec.ball_radius
    }

    /// The clearance between the ball and the groove's bottom (the apex), mm.
    pub fn clearance(&self) -> f64 {
        self.apex.y - self.spec.ball_radius
    }

    /// The lowest point of the profile's height, mm.
    pub fn y_min(&self) -> f64 {
        // The fillet's lowest point is inside it where the flank rises outward.
        let fillet_low = if self.spec.flank_tilt < 0.0 {
            self.o2.y - self.spec.r2
        } else {
            f64::INFINITY
        };
        self.d.y.min(self.c.y).min(fillet_low)
    }

    /// The profile's height from its lowest point to the apex, mm.
    pub fn height(&self) -> f64 {
        self.apex.y - self.y_min()
    }

    /// The smallest radius of the profile's concave pieces (the fillets), mm.
    pub fn min_concave_radius(&self) -> f64 {
        self.spec.r2
    }

    /// How well the pieces join (see [`Joints`]), measured from the pieces'
    /// own end points and tangents.
    pub fn joints(&self) -> Joints {
        let all = self.pieces();
        let apex_joint = all.len() / 2 - 1;
        let mut gap = 0.0f64;
        let mut angle = 0.0f64;
        let mut apex_angle = 0.0;
        for (i, w) in all.windows(2).enumerate() {
            gap = gap.max(w[0].end().distance(w[1].start()));
            let (t0, t1) = (w[0].tangent(1.0), w[1].tangent(0.0));
            let turn = t0.cross(t1).atan2(t0.dot(t1)).abs();
            if i == apex_joint {
                apex_angle = turn;
            } else {
                angle = angle.max(turn);
            }
        }
        Joints {
            gap,
            angle,
            apex_angle,
        }
    }
}

/// `spec` with every value finite (the angles through degrees, as the job
/// gives them).
fn finite_spec(s: &WheelSpec) -> Result<WheelSpec, DressError> {
    let ball_radius = finite("wheel.ball_radius", s.ball_radius, " mm")?;
    let contact_angle =
        finite("wheel.contact_angle_deg", s.contact_angle.to_degrees(), "°")?.to_radians();
    let r1 = finite("wheel.r1", s.r1, " mm")?;
    let r2 = finite("wheel.r2", s.r2, " mm")?;
    let width = finite("wheel.width", s.width, " mm")?;
    let flank_tilt = finite("wheel.flank_tilt_deg", s.flank_tilt.to_degrees(), "°")?.to_radians();
    let arc_angle = finite("wheel.arc_angle_deg", s.arc_angle.to_degrees(), "°")?.to_radians();
    Ok(WheelSpec {
        ball_radius,
        contact_angle,
        r1,
        r2,
        width,
        flank_tilt,
        arc_angle,
    })
}

/// Each value of the finite `s` within its range; `given_contact_angle` is
/// the contact angle as given, named in its error.
fn check_ranges(s: &WheelSpec, given_contact_angle: f64) -> Result<(), DressError> {
    let (rs, a, a2, tilt) = (s.ball_radius, s.contact_angle, s.arc_angle, s.flank_tilt);
    let (r1, r2, width) = (s.r1, s.r2, s.width);
    if rs <= 0.0 {
        return Err(DressError::field(
            "wheel.ball_radius",
            mm(rs),
            "must be positive",
        ));
    }
    if !(a > 0.0 && a < PI / 2.0) {
        return Err(DressError::field(
            "wheel.contact_angle_deg",
            deg(given_contact_angle.to_degrees()),
            "must be in (0°, 90°)",
        ));
    }
    if r1 <= rs {
        return Err(DressError::field(
            "wheel.r1",
            mm(r1),
            format!(
                "the flank arc must be larger than the ball (wheel.ball_radius = {}); usually \
                 R1 = 1.03..1.05 Rs",
                mm(rs)
            ),
        ));
    }
    if r2 <= 0.0 {
        return Err(DressError::field("wheel.r2", mm(r2), "must be positive"));
    }
    if width <= 0.0 {
        return Err(DressError::field(
            "wheel.width",
            mm(width),
            "must be positive",
        ));
    }
    if !(a2 > 0.0 && a2 < a) {
        return Err(DressError::field(
            "wheel.arc_angle_deg",
            deg(a2.to_degrees()),
            format!(
                "the flank arc must end below the contact point: the arc angle must be in \
                 (0°, {}) (the contact angle)",
                deg(a.to_degrees())
            ),
        ));
    }
    if !(tilt > -PI / 2.0 && tilt < PI / 2.0 - a2) {
        return Err(DressError::field(
            "wheel.flank_tilt_deg",
            deg(tilt.to_degrees()),
            format!(
                "must be in (-90°, {}) (90° less the arc angle) for the fillet to turn from \
                 the flank arc to the flank",
                deg(90.0 - a2.to_degrees())
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::wheel as seed;

    #[test]
    fn joints_are_continuous_and_tangent() {
        let p = Profile::new(&seed()).unwrap();
        let j = p.joints();
        assert!(j.gap < 1e-9, "{j:?}");
        assert!(j.angle < 1e-9, "{j:?}");
        // The gothic arch's point: the two flank arcs meet at an angle.
        assert!(j.apex_angle > 0.01 && j.apex_angle < 0.2, "{j:?}");
        assert!(p.apex.x.abs() < 1e-12);
        // The flank falls at the tilt.
        let t = p.right_half()[2].1.tangent(0.5);
        assert!((t.y.atan2(t.x) + 10f64.to_radians()).abs() < 1e-12);
        assert!((p.d.x - 3.0).abs() < 1e-12);
    }

    #[test]
    fn the_ball_touches_at_the_contact_angle() {
        let p = Profile::new(&seed()).unwrap();
        let [r, l] = p.contacts();
        let a = 45f64.to_radians();
        assert!(r.gap.abs() < 1e-9 && l.gap.abs() < 1e-9, "{r:?} {l:?}");
        assert!((r.angle - a).abs() < 1e-9, "{r:?}");
        assert!((l.angle - (PI - a)).abs() < 1e-9, "{l:?}");
        // Nowhere closer than Rs: the ball does not cut the wheel.
        assert!(p.ball_gap().abs() < 1e-9);
        // Clearance at the bottom: the apex is above the ball.
        let expect = p.o1.y + (1.937f64.powi(2) - p.o1.x.powi(2)).sqrt() - 1.85;
        assert!((p.clearance() - expect).abs() < 1e-12);
        assert!(p.clearance() > 0.0);
    }

    #[test]
    fn samples_lie_on_the_profile() {
        let p = Profile::new(&seed()).unwrap();
        let pts = p.sample(0.01);
        assert!((pts[0].x + 3.0).abs() < 1e-12 && (pts[pts.len() - 1].x - 3.0).abs() < 1e-12);
        for w in pts.windows(2) {
            assert!(w[1].x > w[0].x);
            assert!(w[0].distance(w[1]) <= 0.01 + 1e-12);
        }
        for q in &pts {
            let y = p.y_at(q.x).unwrap();
            assert!((y - q.y).abs() < 1e-9, "{q:?} {y}");
        }
        assert!(p.y_at(3.1).is_none());
        assert!((p.y_at(-1.2).unwrap() - p.y_at(1.2).unwrap()).abs() < 1e-15);
    }

    #[test]
    fn bad_geometry_names_the_field() {
        let err = |f: fn(&mut WheelSpec)| {
            let mut s = seed();
            f(&mut s);
            Profile::new(&s).unwrap_err().to_string()
        };
        assert!(
            err(|s| s.r2 = 2.0)
                .starts_with("wheel.r2 = 2 mm: the fillet does not fit the width 6 mm")
        );
        assert!(err(|s| s.contact_angle = PI / 2.0).starts_with("wheel.contact_angle_deg = 90°"));
        assert!(err(|s| s.contact_angle = 0.0).starts_with("wheel.contact_angle_deg = 0°"));
        assert!(err(|s| s.r1 = 1.85).starts_with("wheel.r1 = 1.85 mm"));
        assert!(err(|s| s.ball_radius = f64::NAN).starts_with("wheel.ball_radius = NaN mm"));
        assert!(err(|s| s.arc_angle = 0.9).starts_with("wheel.arc_angle_deg"));
        assert!(err(|s| s.flank_tilt = 1.4).starts_with("wheel.flank_tilt_deg"));
        assert!(err(|s| s.width = 0.0).starts_with("wheel.width = 0 mm"));
    }

    #[test]
    fn a_rising_flank_keeps_the_joints() {
        let mut s = seed();
        s.flank_tilt = -20f64.to_radians();
        let p = Profile::new(&s).unwrap();
        let j = p.joints();
        assert!(j.gap < 1e-9 && j.angle < 1e-9);
        assert!((p.y_min() - (p.o2.y - s.r2)).abs() < 1e-15);
    }
}
