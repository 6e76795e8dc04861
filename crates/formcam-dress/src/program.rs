//! The dressing program: point A along the two passes, a feed per point.
//!
//! Axes `Z` (along the wheel's axis, the profile's `x`) and `X` (radial, the
//! profile's `y`), in that order, as the seed's CLDATA rows `Z, X, F`; the
//! origin at the ball's centre; plane G18. Each pass: a rapid move above its
//! start, down to it, then one linear block per path point with its own feed
//! (G01 throughout: the feed changes from point to point, so the arcs are not
//! written as G02/G03), then a rapid move up.

use formcam_nc::{AxisSpec, Block, Feed, Plane, Program};

use crate::error::num;
use crate::{DressError, Dresser, FeedPlan, Forming, Pass, Profile};

/// How far above the wheel's highest point the dresser's periphery moves
/// between passes, mm.
pub const CLEARANCE: f64 = 1.0;

/// The program for `passes` with the feeds of `feed` (one per step of
/// `forming`, pass after pass).
pub(crate) fn dressing_program(
    name: &str,
    profile: &Profile,
    dresser: &Dresser,
    passes: &[Pass],
    forming: &Forming,
    feed: &FeedPlan,
) -> Result<Program, DressError> {
    let mut p = Program::new(
        if name.is_empty() { "DRESS" } else { name },
        vec![AxisSpec::linear("Z"), AxisSpec::linear("X")],
    );
    p.plane = Some(Plane::Zx);
    let s = profile.spec();
    p.header_comments = vec![
        format!(
            "wheel: gothic arch Rs {} R1 {} R2 {} alpha {} deg, width {}",
            num(s.ball_radius),
            num(s.r1),
            num(s.r2),
            num(s.contact_angle.to_degrees()),
            num(s.width)
        ),
        format!(
            "dresser: width {}, corners {} (right half) {} (left half), point A {} from its left face",
            num(dresser.width),
            num(dresser.r_right),
            num(dresser.r_left),
            num(dresser.yo)
        ),
        "Z along the wheel's axis, X radial; origin at the ball's centre".into(),
        format!(
            "feed for a removal rate of {} mm2/min within {} .. {} mm/min",
            num(feed.target),
            num(feed.feed.iter().copied().fold(f64::INFINITY, f64::min)),
            num(feed.feed.iter().copied().fold(f64::NEG_INFINITY, f64::max))
        ),
    ];
    let top = forming
        .initial
        .points()
        .iter()
        .map(|q| q.y)
        .fold(f64::NEG_INFINITY, f64::max);
    // Point A is on the periphery's line: this keeps the dresser clear.
    let safe = top + CLEARANCE;
    let mut k = 0;
    for (pi, pass) in passes.iter().enumerate() {
        let Some(first) = pass.points.first() else {
            continue;
        };
        let a = first.reference;
        p.blocks
            .push(Block::rapid(vec![a.x, safe]).with_comment(format!(
                "pass {}: the {} half, corner radius {}",
                pi + 1,
                pass.side.name(),
                num(dresser.radius(pass.side))
            )));
        p.blocks.push(Block::rapid(vec![a.x, a.y]));
        for q in &pass.points[1..] {
            // One feed per step, in the order of the passes' points.
            p.blocks.push(Block::linear(
                vec![q.reference.x, q.reference.y],
                Feed::PerMinute(feed.feed[k]),
            ));
            k += 1;
        }
        if let Some(last) = pass.points.last() {
            p.blocks.push(Block::rapid(vec![last.reference.x, safe]));
        }
    }
    p.validate()?;
    Ok(p)
}
