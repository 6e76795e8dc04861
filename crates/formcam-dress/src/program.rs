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
    let program = headed_program(name, profile, dresser, feed);
    let top = forming
        .initial
        .points()
        .iter()
        .map(|q| q.y)
        .fold(f64::NEG_INFINITY, f64::max);
    // Point A is on the periphery's line: this keeps the dresser clear.
    let safe = top + CLEARANCE;
    let mut blocks = Blocks {
        program,
        feed: &feed.feed,
        k: 0,
        step_block: Vec::with_capacity(feed.feed.len()),
        linear: 0,
    };
    for (pi, pass) in passes.iter().enumerate() {
        blocks.pass(pi, pass, dresser, safe);
    }
    blocks.program.validate()?;
    Ok((blocks.program, blocks.step_block))
}

/// The program without blocks: its axes, plane and header (the wheel, the
/// dresser, the axes, the feed's target and range).
fn headed_program(name: &str, profile: &Profile, dresser: &Dresser, feed: &FeedPlan) -> Program {
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
    p
}

/// The program as written so far: the feed of each step, the next step's
/// index `k`, for each step written the linear block that ends it, and the
/// count of linear blocks.
struct Blocks<'a> {
    program: Program,
    feed: &'a [f64],
    k: usize,
    step_block: Vec<usize>,
    linear: usize,
}

/// A pass being written: the time (min) and count of steps not yet written,
/// the last step's end, where the last written block starts, that block's
/// start and time, and where it prints.
struct PassSteps {
    pending: f64,
    waiting: usize,
    prev: Point,
    from: Point,
    block: Option<(Point, f64)>,
    last_printed: (i64, i64),
}

impl Blocks<'_> {
    /// Pass `pi`: a rapid move above its start and down to it, a block per
    /// step that moves, the steps left merged, a rapid move up.
    fn pass(&mut self, pi: usize, pass: &Pass, dresser: &Dresser, safe: f64) {
        let Some(first) = pass.points.first() else {
            return;
        };
        let a = first.reference;
        self.program
            .blocks
            .push(Block::rapid(vec![a.x, safe]).with_comment(format!(
                "pass {}: the {} half, corner radius {}",
                pi + 1,
                pass.side.name(),
                num(dresser.radius(pass.side))
            )));
        self.program.blocks.push(Block::rapid(vec![a.x, a.y]));
        let mut steps = PassSteps {
            pending: 0.0,
            waiting: 0,
            prev: a,
            from: a,
            block: None,
            last_printed: (printed(a.x), printed(a.y)),
        };
        for q in &pass.points[1..] {
            self.step(&mut steps, q.reference);
        }
        if steps.waiting > 0 {
            self.pass_end(&steps, a);
        }
        if let Some(last) = pass.points.last() {
            self.program
                .blocks
                .push(Block::rapid(vec![last.reference.x, safe]));
        }
    }

    /// The step to `r`: a linear block when it prints elsewhere than the
    /// last one, with the time of the steps it ends.
    fn step(&mut self, st: &mut PassSteps, r: Point) {
        st.pending += r.distance(st.prev) / self.feed[self.k];
        st.prev = r;
        self.k += 1;
        st.waiting += 1;
        let here = (printed(r.x), printed(r.y));
        if here == st.last_printed {
            return;
        }
        let length = r.distance(st.from);
        self.program.blocks.push(Block::linear(
            vec![r.x, r.y],
            Feed::PerMinute(length / st.pending),
        ));
        self.step_block
            .extend(std::iter::repeat_n(self.linear, st.waiting));
        st.block = Some((st.from, st.pending));
        self.linear += 1;
        (st.pending, st.waiting) = (0.0, 0);
        st.from = r;
        st.last_printed = here;
    }

    /// The steps left at the end of a pass that started at `a`.
    fn pass_end(&mut self, st: &PassSteps, a: Point) {
        let (pending, waiting, prev) = (st.pending, st.waiting, st.prev);
        // The pass ends where its last block prints: that block goes on
        // to the end, with the time of the steps after it.
        match (st.block, self.program.blocks.last_mut()) {
            (Some((start, time)), Some(b)) => {
                let time = time + pending;
                b.target = vec![prev.x, prev.y];
                b.feed = Feed::PerMinute(prev.distance(start) / time);
                self.step_block
                    .extend(std::iter::repeat_n(self.linear - 1, waiting));
            }
            _ => {
                // The whole pass prints at one place: one block anyway.
                let length = prev.distance(a);
                let f = if pending > 0.0 && length > 0.0 {
                    length / pending
                } else {
                    self.feed[self.k - 1]
                };
                self.program
                    .blocks
                    .push(Block::linear(vec![prev.x, prev.y], Feed::PerMinute(f)));
                self.step_block
                    .extend(std::iter::repeat_n(self.linear, waiting));
                self.linear += 1;
            }
        }
    }
}
