//! The dresser's path: the equidistant of the profile at the corner radius
//! (docs/dressing.md, eqs. 7-8), pointing away from the wheel's material, in two passes.
//!
//! Each half is dressed from the wheel's edge up to the apex by the corner
//! named after it, which then leads (it faces the direction of travel and
//! does the cutting): the right half first, moving to `-x`, then the left
//! half, moving to `+x`. A pass of the corner's centre, for the right half
//! with the corner radius `r`:
//!
//! 1. the approach: a straight move in from `LEAD_IN` beyond the edge;
//! 2. a roll of the corner round the wheel's edge corner D (an arc of radius
//!    `r` about D) from the face's normal to the flank's;
//! 3. the flank's offset, 4. the fillet's (radius `R2 - r`), 5. the flank
//!    arc's (radius `R1 + r`);
//! 6. a roll round the apex up to the vertical, where the other pass will
//!    meet it.
//!
//! Each stretch is cut into equal steps of at most `h`, measured along the
//! path or along the profile under it, whichever is longer (the fillet's
//! offset is short: `R2 - r` is small), so every profile sample has a path
//! point. The left pass is the mirror image with the other
//! corner radius.

use std::f64::consts::PI;

use crate::curve::{Piece, steps};
use crate::{Dresser, Point, Profile, Side};

/// How far outside the wheel's edge the approach starts, mm.
pub const LEAD_IN: f64 = 0.5;

/// What the dresser does on a stretch of its path.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stage {
    /// The straight approach from beyond the wheel's edge.
    Approach,
    /// The corner rolls round the wheel's edge corner D.
    EdgeRoll,
    /// Along the straight flank CD.
    Flank,
    /// Along the fillet BC.
    Fillet,
    /// Along the flank arc AB.
    Arch,
    /// The corner rolls round the apex.
    ApexRoll,
}

impl Stage {
    /// `approach`, `edge`, `flank`, `fillet`, `arch`, `apex`.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Approach => "approach",
            Stage::EdgeRoll => "edge",
            Stage::Flank => "flank",
            Stage::Fillet => "fillet",
            Stage::Arch => "arch",
            Stage::ApexRoll => "apex",
        }
    }

    /// Along one of the profile's pieces (not an approach or a roll round a
    /// corner, where the dresser enters or leaves the allowance).
    pub fn on_profile(self) -> bool {
        matches!(self, Stage::Flank | Stage::Fillet | Stage::Arch)
    }
}

/// One stretch of a pass: the path of the dressing corner's centre and what
/// it dresses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stretch {
    /// What the dresser does here.
    pub stage: Stage,
    /// The corner centre's path.
    pub path: Piece,
    /// The profile piece dressed (parametrised like `path`), or the corner
    /// point rolled round (`Piece::Arc` of radius 0), or `None` (approach).
    pub profile: Option<Piece>,
    /// The number of steps.
    pub steps: usize,
}

/// A point of the path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// The stretch it ends a step of (the first point of a pass: its start).
    pub stage: Stage,
    /// The dressing corner's centre.
    pub centre: Point,
    /// The programmed point A.
    pub reference: Point,
    /// The profile's point the corner forms here (`None` on the approach).
    pub contact: Option<Point>,
}

/// One pass: a half of the profile dressed by its corner.
#[derive(Debug, Clone, PartialEq)]
pub struct Pass {
    /// The half dressed.
    pub side: Side,
    /// The dressing corner's radius, mm.
    pub radius: f64,
    /// The stretches in order.
    pub stretches: Vec<Stretch>,
    /// The path's points; the first is the start, each further one ends a step.
    pub points: Vec<PathPoint>,
}

/// The two passes, right half first, each cut into steps of at most `h`.
pub fn dresser_path(profile: &Profile, dresser: &Dresser, h: f64) -> [Pass; 2] {
    [Side::Right, Side::Left].map(|side| {
        let r = dresser.radius(side);
        let mut stretches = right_half(profile, r, h);
        if side == Side::Left {
            for s in &mut stretches {
                s.path = s.path.mirrored();
                s.profile = s.profile.map(|p| p.mirrored());
            }
        }
        let mut points = Vec::new();
        for s in &stretches {
            let first = points.is_empty();
            for i in usize::from(!first)..=s.steps {
                let t = i as f64 / s.steps as f64;
                let centre = s.path.point(t);
                points.push(PathPoint {
                    stage: s.stage,
                    centre,
                    reference: dresser.reference(side, centre),
                    contact: s.profile.map(|p| p.point(t)),
                });
            }
        }
        Pass {
            side,
            radius: r,
            stretches,
            points,
        }
    })
}

/// The right half's stretches for a corner of radius `r`.
fn right_half(profile: &Profile, r: f64, h: f64) -> Vec<Stretch> {
    let tilt = profile.spec().flank_tilt;
    let d = profile.d;
    let corner = |p: Point, a0: f64, a1: f64| Piece::Arc {
        centre: p,
        radius: 0.0,
        start: a0,
        end: a1,
    };
    let roll = |p: Point, a0: f64, a1: f64| Piece::Arc {
        centre: p,
        radius: r,
        start: a0,
        end: a1,
    };
    let mut out = vec![
        Stretch {
            stage: Stage::Approach,
            path: Piece::Line {
                from: d + Point::new(r + LEAD_IN, 0.0),
                to: d + Point::new(r, 0.0),
            },
            profile: None,
            steps: 1,
        },
        Stretch {
            stage: Stage::EdgeRoll,
            path: roll(d, 0.0, PI / 2.0 - tilt),
            profile: Some(corner(d, 0.0, PI / 2.0 - tilt)),
            steps: 0,
        },
    ];
    // The profile's pieces from the edge inward; the material is then on the
    // left of travel, so the path is the offset to the right.
    for (element, piece) in profile.right_half().iter().rev() {
        let inward = piece.reversed();
        let Some(path) = inward.offset_left(-r) else {
            continue;
        };
        let stage = match element {
            crate::Element::Flank => Stage::Flank,
            crate::Element::Fillet => Stage::Fillet,
            crate::Element::Arch => Stage::Arch,
        };
        out.push(Stretch {
            stage,
            path,
            profile: Some(inward),
            steps: 0,
        });
    }
    out.push(Stretch {
        stage: Stage::ApexRoll,
        path: roll(profile.apex, profile.apex_angle, PI / 2.0),
        profile: Some(corner(profile.apex, profile.apex_angle, PI / 2.0)),
        steps: 0,
    });
    // A corner radius equal to the fillet's leaves the corner where it is on
    // the fillet: nothing to step through.
    out.retain(|s| s.path.length() > 1e-12);
    for s in &mut out {
        if s.stage != Stage::Approach {
            let under = s.profile.map_or(0.0, |p| p.length());
            s.steps = steps(s.path.length().max(under), h);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DresserSpec;
    use crate::fixtures::setup;

    #[test]
    fn the_path_is_the_equidistant() {
        let (p, d) = setup();
        let passes = dresser_path(&p, &d, 0.01);
        for pass in &passes {
            let r = pass.radius;
            // Continuous and tangent along each pass.
            for w in pass.stretches.windows(2) {
                assert!(w[0].path.end().distance(w[1].path.start()) < 1e-12);
                if w[0].stage != Stage::Approach {
                    let (a, b) = (w[0].path.tangent(1.0), w[1].path.tangent(0.0));
                    assert!(a.cross(b).abs() < 1e-9 && a.dot(b) > 0.0, "{w:?}");
                }
            }
            for q in &pass.points {
                // At distance r from the profile's point it forms, along the
                // normal, and no closer to the profile anywhere.
                if let Some(c) = q.contact {
                    assert!((q.centre.distance(c) - r).abs() < 1e-12);
                    let nearest = p
                        .pieces()
                        .iter()
                        .map(|piece| piece.nearest(q.centre).0.distance(q.centre))
                        .fold(f64::INFINITY, f64::min);
                    assert!(nearest > r - 1e-12, "{q:?} {nearest}");
                    // Away from the material: above the profile.
                    if let Some(y) = p.y_at(q.centre.x) {
                        assert!(q.centre.y > y);
                    }
                }
            }
            for w in pass.points[1..].windows(2) {
                assert!(w[0].centre.distance(w[1].centre) <= 0.01 + 1e-12);
            }
        }
        // The right pass climbs to -x, the left one to +x.
        let r = &passes[0].points;
        assert!(r[0].centre.x > 3.0 && r[r.len() - 1].centre.x.abs() < 1e-12);
        let l = &passes[1].points;
        assert!(l[0].centre.x < -3.0 && l[l.len() - 1].centre.x.abs() < 1e-12);
    }

    #[test]
    fn a_corner_as_large_as_the_fillet_skips_it() {
        let (p, _) = setup();
        let d = Dresser::new(
            &DresserSpec {
                width: 2.9,
                corner_radius_left: 0.296,
                corner_radius_right: 0.296,
                yo: None,
            },
            &p,
        )
        .unwrap();
        let passes = dresser_path(&p, &d, 0.01);
        assert!(passes[0].stretches.iter().all(|s| s.stage != Stage::Fillet));
    }
}
