//! Cutting a sampled axis trajectory into straight blocks.
//!
//! The fit is incremental: for a block start `s` the slopes that keep every
//! sample `s < k < e` within tolerance form an interval per axis, the
//! intersection of one interval per sample. Those running intersections are
//! kept from `s` on (one buffer for every block), so whether the block to `e`
//! fits is read off in `O(width)` instead of checking every sample again.
//! Each interval is kept for the tolerance less and plus a margin far above
//! the rounding: a slope between the two is decided by the direct check of
//! every sample, so the blocks are exactly those of that check.

use crate::{MotionError, TrajectoryFault};

/// A linear axis's tolerance when a job gives none, mm.
pub const DEFAULT_TOLERANCE_MM: f64 = 0.05;

/// A rotary axis's tolerance when a job gives none, degrees.
pub const DEFAULT_TOLERANCE_DEG: f64 = 0.05;

/// How far a block may leave the sampled trajectory.
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerance {
    /// Per axis, in its units (mm or rad): the largest distance between a sample
    /// and the block's straight interpolation at the same parameter.
    pub axes: Vec<f64>,
    /// The largest distance between the payout point where the block puts it and
    /// where the sample wants it, mm (checked through the `deviation` callback).
    pub position_mm: Option<f64>,
}

/// The payout point's deviation at interpolated axes `q` from sample `k`'s, mm.
pub type Deviation<'a> = &'a dyn Fn(&[f64], usize) -> f64;

/// Cuts the trajectory into blocks: returns the indices of the block ends, the
/// first `0` and the last `n - 1` (block `i` runs from `ends[i]` to `ends[i+1]`).
///
/// `x` is the parameter (increasing), `values` the axis values row by row
/// (`width` per row). Between two ends the axes move linearly in `x`. Each block
/// reaches as far as the tolerance allows (exponential then binary search).
/// `deviation(q, k)`: the distance between the payout point at the interpolated
/// axes `q` and sample `k`'s, mm.
pub fn fit_blocks(
    x: &[f64],
    values: &[f64],
    width: usize,
    tol: &Tolerance,
    deviation: Option<Deviation<'_>>,
) -> Result<Vec<usize>, MotionError> {
    check_input(x, values, width, tol)?;
    let n = x.len();
    if n < 2 {
        return Ok((0..n).collect());
    }
    let mut fit = Fit::new(x, values, width, tol, deviation);
    let mut ends = vec![0];
    let mut s = 0;
    while s + 1 < n {
        fit.start(s);
        let ok = farthest(n, s, |e| fit.fits(e));
        ends.push(ok);
        s = ok;
    }
    Ok(ends)
}

/// The sizes, tolerances and samples checked.
fn check_input(
    x: &[f64],
    values: &[f64],
    width: usize,
    tol: &Tolerance,
) -> Result<(), MotionError> {
    let n = x.len();
    if width == 0 || values.len() != n * width || tol.axes.len() != width {
        return Err(TrajectoryFault::Shape {
            samples: n,
            width,
            needed: n * width,
            values: values.len(),
            tolerances: tol.axes.len(),
        }
        .into());
    }
    for (i, t) in tol.axes.iter().enumerate() {
        if !(t.is_finite() && *t > 0.0) {
            return Err(MotionError::Field {
                field: format!("tolerance of axis #{}", i + 1),
                reason: format!("must be a finite number > 0, got {t}"),
            });
        }
    }
    if let Some(p) = tol.position_mm
        && !(p.is_finite() && p > 0.0)
    {
        return Err(MotionError::Field {
            field: "tolerance_mm".into(),
            reason: format!("must be a finite number > 0, got {p}"),
        });
    }
    if x.iter().chain(values).any(|v| !v.is_finite()) {
        return Err(TrajectoryFault::NotFinite.into());
    }
    if x.windows(2).any(|w| w[1] <= w[0]) {
        return Err(TrajectoryFault::NotIncreasing.into());
    }
    Ok(())
}

/// The block end reached from `s` (of `n` samples): an exponential probe,
/// then a binary search between the last fit and the first miss.
fn farthest(n: usize, s: usize, mut fits: impl FnMut(usize) -> bool) -> usize {
    let mut ok = s + 1;
    let mut step = 1;
    let mut bad = None;
    while ok < n - 1 {
        let e = (ok + step).min(n - 1);
        if fits(e) {
            ok = e;
            step *= 2;
        } else {
            bad = Some(e);
            break;
        }
    }
    if let Some(mut hi) = bad {
        while hi - ok > 1 {
            let mid = ok + (hi - ok) / 2;
            if fits(mid) {
                ok = mid;
            } else {
                hi = mid;
            }
        }
    }
    ok
}

/// The fit of blocks from one start: the running slope intervals of the
/// samples after it, grown as far as the search looks.
struct Fit<'a> {
    x: &'a [f64],
    values: &'a [f64],
    width: usize,
    tol: &'a Tolerance,
    deviation: Option<Deviation<'a>>,
    /// Per axis, the margin (in its units) within which a sample's slack
    /// is left to the direct check: far above the rounding of either way.
    margin: Vec<f64>,
    /// The block's start.
    s: usize,
    /// Per sample `k = s + 1 + i`, per axis: the least and greatest slope
    /// that keep samples `s + 1 ..= k` within the tolerance less the margin
    /// (every sample surely fits), and within it plus the margin (no sample
    /// surely misses): `4 width` each.
    bounds: Vec<f64>,
    /// The interpolated axes of the direct check.
    q: Vec<f64>,
}

impl<'a> Fit<'a> {
    fn new(
        x: &'a [f64],
        values: &'a [f64],
        width: usize,
        tol: &'a Tolerance,
        deviation: Option<Deviation<'a>>,
    ) -> Self {
        let margin = (0..width)
            .map(|j| {
                let scale = values
                    .iter()
                    .skip(j)
                    .step_by(width)
                    .fold(0.0_f64, |m, v| m.max(v.abs()));
                1e-9 * (scale + tol.axes[j])
            })
            .collect();
        Self {
            x,
            values,
            width,
            tol,
            deviation,
            margin,
            s: 0,
            bounds: Vec::new(),
            q: vec![0.0; width],
        }
    }

    fn row(&self, k: usize) -> &'a [f64] {
        &self.values[k * self.width..(k + 1) * self.width]
    }

    /// Blocks from `s` on.
    fn start(&mut self, s: usize) {
        self.s = s;
        self.bounds.clear();
    }

    /// The slope intervals grown to cover samples up to `k`.
    fn grow_to(&mut self, k: usize) {
        let (s, w) = (self.s, self.width);
        let a = self.row(s);
        while s + self.bounds.len() / (4 * w) < k {
            let i = s + 1 + self.bounds.len() / (4 * w);
            let lever = self.x[i] - self.x[s];
            let r = self.row(i);
            let from = self.bounds.len();
            for j in 0..w {
                let (t, e) = (self.tol.axes[j], self.margin[j]);
                let mut b = [
                    (r[j] - (t - e) - a[j]) / lever,
                    (r[j] + (t - e) - a[j]) / lever,
                    (r[j] - (t + e) - a[j]) / lever,
                    (r[j] + (t + e) - a[j]) / lever,
                ];
                if from > 0 {
                    let p = &self.bounds[from - 4 * w + 4 * j..from - 4 * w + 4 * j + 4];
                    b = [
                        b[0].max(p[0]),
                        b[1].min(p[1]),
                        b[2].max(p[2]),
                        b[3].min(p[3]),
                    ];
                }
                self.bounds.extend_from_slice(&b);
            }
        }
    }

    /// Whether the block from the start to `e` keeps every sample between
    /// within tolerance.
    fn fits(&mut self, e: usize) -> bool {
        let s = self.s;
        if e <= s + 1 {
            return true;
        }
        self.grow_to(e - 1);
        let w = self.width;
        let (a, b) = (self.row(s), self.row(e));
        let span = self.x[e] - self.x[s];
        let at = (e - 1 - (s + 1)) * 4 * w;
        let mut sure = true;
        for j in 0..w {
            let m = (b[j] - a[j]) / span;
            let c = &self.bounds[at + 4 * j..at + 4 * j + 4];
            if m < c[2] || m > c[3] {
                return false;
            }
            sure &= m >= c[0] && m <= c[1];
        }
        if sure && (self.deviation.is_none() || self.tol.position_mm.is_none()) {
            return true;
        }
        self.direct(e)
    }

    /// Every sample between the start and `e` checked on the block's line.
    fn direct(&mut self, e: usize) -> bool {
        let s = self.s;
        let (a, b) = (self.row(s), self.row(e));
        let span = self.x[e] - self.x[s];
        // A chord strays furthest near its middle: look there first, so that a
        // block that does not fit is rejected at once.
        let mid = (s + e) / 2;
        let order = (mid..=mid).filter(|&k| k > s && k < e).chain(s + 1..e);
        for k in order {
            let t = (self.x[k] - self.x[s]) / span;
            let r = self.row(k);
            for j in 0..self.width {
                self.q[j] = a[j] + t * (b[j] - a[j]);
                if (self.q[j] - r[j]).abs() > self.tol.axes[j] {
                    return false;
                }
            }
            if let (Some(p), Some(dev)) = (self.tol.position_mm, self.deviation)
                && dev(&self.q, k) > p
            {
                return false;
            }
        }
        true
    }
}
