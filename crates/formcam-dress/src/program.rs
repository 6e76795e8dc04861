//! The dressing program: point A along the two passes, a feed per point.
//!
//! Axes `Z` (along the wheel's axis, the profile's `x`) and `X` (radial, the
//! profile's `y`), in that order, as CLDATA rows `Z, X, F` (docs/dressing.md,
//! section 5); the
//! origin at the ball's centre; plane G18. Each pass: a rapid move above its
//! start, down to it, then one linear block per path point with its own feed
//! (G01 throughout: the feed changes from point to point, so the arcs are not
//! written as G02/G03), then a rapid move up.
//!
//! Steps whose end point would print at the same place as the block before
//! (the programs carry 0.001 mm) are merged into the next block that moves
//! (the last ones of a pass into the block before): a zero-length block
//! takes no time on a machine, so its feed would mean nothing. A merged
//! block's feed gives it the time of all its steps (`F = length / sum of
//! len_i / f_i`, eq. 22), so the removal rate over the block is the steps' common
//! rate.

use formcam_nc::{AxisSpec, Block, Feed, Plane, Program};

use crate::error::num;
use crate::{DressError, Dresser, FeedPlan, Forming, Pass, Point, Profile};

/// How far above the wheel's highest point the dresser's periphery moves
/// between passes, mm.
pub const CLEARANCE: f64 = 1.0;

/// The resolution of the programs' coordinates, mm.
pub const RESOLUTION: f64 = 0.001;

/// `v` as the programs print it, in units of [`RESOLUTION`].
fn printed(v: f64) -> i64 {
    (v / RESOLUTION).round() as i64
}

/// The program for `passes` with the feeds of `feed` (one per step of
/// `forming`, pass after pass), and for each step the index of the linear
/// block that ends it (counting linear blocks only).
pub(crate) fn dressing_program(
    name: &str,
    profile: &Profile,
    dresser: &Dresser,
    passes: &[Pass],
    forming: &Forming,
    feed: &FeedPlan,
) -> Result<(Program, Vec<usize>), DressError> {
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
    let mut step_block = Vec::with_capacity(feed.feed.len());
    let mut linear = 0usize;
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
        // The time (min) and count of steps not yet written, where the last
        // written block starts, its time, and where it prints.
        let (mut pending, mut waiting) = (0.0, 0usize);
        let mut prev = a;
        let mut from = a;
        let mut block: Option<(Point, f64)> = None;
        let mut last_printed = (printed(a.x), printed(a.y));
        for q in &pass.points[1..] {
            let r = q.reference;
            pending += r.distance(prev) / feed.feed[k];
            prev = r;
            k += 1;
            waiting += 1;
            let here = (printed(r.x), printed(r.y));
            if here == last_printed {
                continue;
            }
            let length = r.distance(from);
            p.blocks.push(Block::linear(
                vec![r.x, r.y],
                Feed::PerMinute(length / pending),
            ));
            step_block.extend(std::iter::repeat_n(linear, waiting));
            block = Some((from, pending));
            linear += 1;
            (pending, waiting) = (0.0, 0);
            from = r;
            last_printed = here;
        }
        if waiting > 0 {
            // The pass ends where its last block prints: that block goes on
            // to the end, with the time of the steps after it.
            match (block, p.blocks.last_mut()) {
                (Some((start, time)), Some(b)) => {
                    let time = time + pending;
                    b.target = vec![prev.x, prev.y];
                    b.feed = Feed::PerMinute(prev.distance(start) / time);
                    step_block.extend(std::iter::repeat_n(linear - 1, waiting));
                }
                _ => {
                    // The whole pass prints at one place: one block anyway.
                    let length = prev.distance(a);
                    let f = if pending > 0.0 && length > 0.0 {
                        length / pending
                    } else {
                        feed.feed[k - 1]
                    };
                    p.blocks
                        .push(Block::linear(vec![prev.x, prev.y], Feed::PerMinute(f)));
                    step_block.extend(std::iter::repeat_n(linear, waiting));
                    linear += 1;
                }
            }
        }
        if let Some(last) = pass.points.last() {
            p.blocks.push(Block::rapid(vec![last.reference.x, safe]));
        }
    }
    p.validate()?;
    Ok((p, step_block))
}
