//! The whole dressing: profile, dresser, path, forming, feed and program.

use formcam_nc::{Dialect, Program};
use formcam_progress::{Progress, Silent};

use crate::ContourFault;
use crate::error::{finite, mm, num};
use crate::forming::offset_contour;
use crate::program::dressing_program;
use crate::{
    Contour, DressError, Dresser, DresserSpec, FeedPlan, FeedSpec, Forming, Pass, Point, Profile,
    WheelSpec, dresser_path, plan_feed, simulate_with,
};

/// The wheel's contour before dressing.
#[derive(Debug, Clone, PartialEq)]
pub enum Allowance {
    /// The profile offset outward by this depth, mm.
    Depth(f64),
    /// A measured or worn contour (`x, y` in the profile's frame: the
    /// program's `z, x`; `x` non-decreasing, covering the wheel's width,
    /// nowhere below the profile), as [`crate::read_contour`] reads it.
    Contour(Vec<Point>),
}

/// Everything a dressing needs (mm, rad, mm/min).
#[derive(Debug, Clone, PartialEq)]
pub struct DressSpec {
    /// A name for the program (`PARTNO`, the 840D comment).
    pub name: String,
    /// The grinding wheel's profile.
    pub wheel: WheelSpec,
    /// The grinding wheel's diameter, mm, for volume rates (`pi D` times the
    /// section's rate); `None`: rates per the section only.
    pub wheel_diameter: Option<f64>,
    /// The dressing wheel.
    pub dresser: DresserSpec,
    /// The wheel before dressing.
    pub allowance: Allowance,
    /// The step along the path (and the profile's sampling step) `h`, mm.
    pub step: f64,
    /// Feed limits and target.
    pub feed: FeedSpec,
}

/// A dressing computed.
#[derive(Debug, Clone, PartialEq)]
pub struct Dressing {
    /// The grinding wheel's profile.
    pub profile: Profile,
    /// The dressing wheel.
    pub dresser: Dresser,
    /// The grinding wheel's diameter, mm, where given.
    pub wheel_diameter: Option<f64>,
    /// The step `h`, mm.
    pub step: f64,
    /// The two passes (right half, then left half).
    pub passes: Vec<Pass>,
    /// The simulation of forming.
    pub forming: Forming,
    /// The feed limits and target used.
    pub feed_spec: FeedSpec,
    /// The feed along the path.
    pub feed: FeedPlan,
    /// The NC program: axes Z (the wheel's axis) and X (radial), point A.
    pub program: Program,
    /// For each step, the linear block of the program that ends it: steps
    /// that would print as zero-length moves are merged into one block.
    pub step_block: Vec<usize>,
}

impl Dressing {
    /// The program as text in `dialect`.
    pub fn nc(&self, dialect: Dialect) -> Result<String, DressError> {
        let mut s = String::new();
        formcam_nc::write(&self.program, dialect, &mut s)?;
        Ok(s)
    }

    /// The time of the program's feed moves, s.
    pub fn dressing_time_s(&self) -> f64 {
        self.program.duration_s().unwrap_or(0.0)
    }

    /// The number of programmed points (every block's end point).
    pub fn points(&self) -> usize {
        self.program.blocks.len()
    }

    /// The factor from a rate of the section (mm²/min) to a volume rate
    /// (mm³/min): the wheel's circumference, where its diameter is given.
    pub fn volume_factor(&self) -> Option<f64> {
        self.wheel_diameter.map(|d| std::f64::consts::PI * d)
    }

    /// How far above the profile the dressed contour may lie, mm: the
    /// highest cusp between the circles of the dressing corner at two
    /// neighbouring path points (their intersection on the profile's side,
    /// measured to the profile), plus what cutting the corners into chords
    /// leaves (`c^2 / (8 r)`, `c` the chord, `r` the smaller corner radius;
    /// docs/dressing.md, eq. 23).
    pub fn scallop_bound(&self) -> f64 {
        let pieces = self.profile.pieces();
        let mut cusp: f64 = 0.0;
        for pass in &self.passes {
            let r = pass.radius;
            for w in pass.points.windows(2) {
                let (Some(p0), Some(p1)) = (w[0].contact, w[1].contact) else {
                    continue;
                };
                let (c0, c1) = (w[0].centre, w[1].centre);
                let l = c0.distance(c1);
                if l <= 1e-15 || l >= 2.0 * r {
                    continue;
                }
                let u = (c1 - c0) * (1.0 / l);
                let n = Point::new(-u.y, u.x) * (r * r - 0.25 * l * l).sqrt();
                let m = (c0 + c1) * 0.5;
                let toward = (p0 + p1) * 0.5;
                let q = if (m + n).distance(toward) < (m - n).distance(toward) {
                    m + n
                } else {
                    m - n
                };
                let d = pieces
                    .iter()
                    .map(|piece| piece.nearest(q).0.distance(q))
                    .fold(f64::INFINITY, f64::min);
                cusp = cusp.max(d);
            }
        }
        let r = self.dresser.r_left.min(self.dresser.r_right);
        let c = self.forming.chord;
        cusp + c * c / (8.0 * r)
    }
}

/// The smallest step, mm.
pub const STEP_MIN: f64 = 1e-4;

/// Runs a dressing: checks `spec`, builds the profile, the dresser's path
/// (two passes), simulates forming from the allowance, plans the feed and
/// writes the program. Errors are one line naming the field.
pub fn dress(spec: &DressSpec) -> Result<Dressing, DressError> {
    dress_with(spec, &Silent)
}

/// [`dress`] reporting the simulation of forming to `progress`;
/// [`DressError::Cancelled`] when it asks to stop.
pub fn dress_with(spec: &DressSpec, progress: &dyn Progress) -> Result<Dressing, DressError> {
    let profile = Profile::new(&spec.wheel)?;
    check_tilt(&profile)?;
    check_diameter(spec.wheel_diameter)?;
    let dresser = Dresser::new(&spec.dresser, &profile)?;
    let h = checked_step(spec, &dresser)?;
    let feed_spec = spec.feed.check()?;
    let chord = h / 2.0;
    let initial = match &spec.allowance {
        Allowance::Depth(depth) => {
            let depth = checked_depth(&profile, *depth)?;
            offset_contour(&profile, depth, chord)
        }
        Allowance::Contour(points) => user_contour(&profile, points.clone(), h)?,
    };
    let passes = dresser_path(&profile, &dresser, h).to_vec();
    let forming = simulate_with(&dresser, &passes, &initial, chord, progress)?;
    check_gouge(&profile, &dresser, &forming)?;
    let feed = plan_feed(&forming.steps, &feed_spec);
    let (program, step_block) =
        dressing_program(&spec.name, &profile, &dresser, &passes, &forming, &feed)?;
    Ok(Dressing {
        profile,
        dresser,
        wheel_diameter: spec.wheel_diameter,
        step: h,
        passes,
        forming,
        feed_spec,
        feed,
        program,
        step_block,
    })
}

/// The flanks may not rise toward the wheel's edges.
fn check_tilt(profile: &Profile) -> Result<(), DressError> {
    let tilt = profile.spec().flank_tilt;
    if tilt < 0.0 {
        return Err(DressError::field(
            "wheel.flank_tilt_deg",
            crate::error::deg(tilt.to_degrees()),
            "flanks rising toward the wheel's edges face away from the corner that dresses them \
             (and the dresser's periphery would cut into them): dressing needs a tilt of 0° or more",
        ));
    }
    Ok(())
}

/// The wheel's diameter, where given, finite and positive.
fn check_diameter(diameter: Option<f64>) -> Result<(), DressError> {
    if let Some(d) = diameter {
        let d = finite("wheel.diameter", d, " mm")?;
        if d <= 0.0 {
            return Err(DressError::field(
                "wheel.diameter",
                mm(d),
                "must be positive",
            ));
        }
    }
    Ok(())
}

/// The step `h`, checked: at least [`STEP_MIN`], at most half the smaller
/// corner radius, and not too much work.
fn checked_step(spec: &DressSpec, dresser: &Dresser) -> Result<f64, DressError> {
    let h = finite("process.step", spec.step, " mm")?;
    let h_max = 0.5 * dresser.r_left.min(dresser.r_right);
    if h_max < STEP_MIN {
        let (field, r) = if dresser.r_left <= dresser.r_right {
            ("dresser.corner_radius_left", dresser.r_left)
        } else {
            ("dresser.corner_radius_right", dresser.r_right)
        };
        return Err(DressError::field(
            field,
            mm(r),
            format!(
                "must be at least {} (twice the least step)",
                mm(2.0 * STEP_MIN)
            ),
        ));
    }
    if !(STEP_MIN..=h_max).contains(&h) {
        return Err(DressError::field(
            "process.step",
            mm(h),
            format!(
                "must be in [{}, {}] (half the smaller corner radius)",
                mm(STEP_MIN),
                mm(h_max)
            ),
        ));
    }
    // The work grows as 1/h^2: steps along a path of about twice the width,
    // each against a dresser outline of corner arcs cut at h / 2.
    let steps = 2.0 * spec.wheel.width / h;
    let work = steps * std::f64::consts::PI * dresser.r_left.max(dresser.r_right) / h;
    if steps > 5e6 || work > 2e9 {
        return Err(DressError::field(
            "process.step",
            mm(h),
            format!(
                "about {} steps against a dresser of {} chords is too much work; use a larger step",
                num(steps.round()),
                num((work / steps).round())
            ),
        ));
    }
    Ok(h)
}

/// The allowance's depth, checked: positive, less than the profile's height
/// and than its fillet radius.
fn checked_depth(profile: &Profile, depth: f64) -> Result<f64, DressError> {
    let depth = finite("process.depth", depth, " mm")?;
    if depth <= 0.0 {
        return Err(DressError::field(
            "process.depth",
            mm(depth),
            "must be positive",
        ));
    }
    let height = profile.height();
    if depth >= height {
        return Err(DressError::field(
            "process.depth",
            mm(depth),
            format!(
                "larger than the wheel's profile (its height from the edges to the apex \
                 is {})",
                mm(height)
            ),
        ));
    }
    let r2 = profile.min_concave_radius();
    if depth >= r2 {
        return Err(DressError::field(
            "process.depth",
            mm(depth),
            format!(
                "must be less than the fillet radius wheel.r2 = {}: the allowance's offset \
                 would lose the fillet",
                mm(r2)
            ),
        ));
    }
    Ok(depth)
}

/// A user's contour, checked and clipped to the wheel's width.
fn user_contour(profile: &Profile, points: Vec<Point>, h: f64) -> Result<Contour, DressError> {
    let c = Contour::new(points).map_err(DressError::Contour)?;
    let half = profile.d.x;
    let pts = c.points();
    let (x0, x1) = (pts[0].x, pts[pts.len() - 1].x);
    let clipped = c.clipped(-half, half).ok_or_else(|| {
        DressError::from(ContourFault::NotCovering {
            from: x0,
            to: x1,
            half_width: half,
        })
    })?;
    let mut worst = (0.0, 0.0);
    for q in profile.sample(h) {
        if let Some((l, r)) = clipped.y_at(q.x) {
            let below = q.y - l.min(r);
            if below > worst.0 {
                worst = (below, q.x);
            }
        }
    }
    for p in clipped.points() {
        if let Some(y) = profile.y_at(p.x)
            && y - p.y > worst.0
        {
            worst = (y - p.y, p.x);
        }
    }
    if worst.0 > 1e-9 {
        return Err(ContourFault::BelowProfile {
            depth: worst.0,
            z: worst.1,
        }
        .into());
    }
    Ok(clipped)
}

/// Refuses a dressing whose dresser cuts into the profile somewhere (its
/// periphery or other corner meeting a part of the profile that rises away
/// from the corner being used, such as flanks rising toward the edges).
fn check_gouge(profile: &Profile, dresser: &Dresser, forming: &Forming) -> Result<(), DressError> {
    let mut worst = (0.0, 0.0);
    for p in forming.final_contour().points() {
        if let Some(y) = profile.y_at(p.x)
            && y - p.y > worst.0
        {
            worst = (y - p.y, p.x);
        }
    }
    if worst.0 > 1e-9 {
        return Err(DressError::field(
            "dresser.width",
            mm(dresser.width),
            format!(
                "the dresser cuts into the profile, {} deep at Z = {}: its periphery meets the \
                 profile away from the corner that dresses it",
                mm(worst.0),
                mm(worst.1)
            ),
        ));
    }
    Ok(())
}
