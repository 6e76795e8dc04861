//! Cutting a sampled axis trajectory into straight blocks.

use crate::MotionError;

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
    let n = x.len();
    if width == 0 || values.len() != n * width || tol.axes.len() != width {
        return Err(MotionError::Trajectory(format!(
            "{} samples of {width} axes need {} values and {width} tolerances (got {} and {})",
            n,
            n * width,
            values.len(),
            tol.axes.len()
        )));
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
        return Err(MotionError::Trajectory("a sample is not finite".into()));
    }
    if x.windows(2).any(|w| w[1] <= w[0]) {
        return Err(MotionError::Trajectory(
            "the parameter x must increase".into(),
        ));
    }
    if n < 2 {
        return Ok((0..n).collect());
    }
    let row = |k: usize| &values[k * width..(k + 1) * width];
    let mut q = vec![0.0; width];
    let mut fits = |s: usize, e: usize| -> bool {
        let (a, b) = (row(s), row(e));
        let span = x[e] - x[s];
        // A chord strays furthest near its middle: look there first, so that a
        // block that does not fit is rejected at once.
        let mid = (s + e) / 2;
        let order = (mid..=mid).filter(|&k| k > s && k < e).chain(s + 1..e);
        for k in order {
            let t = (x[k] - x[s]) / span;
            let r = row(k);
            for j in 0..width {
                q[j] = a[j] + t * (b[j] - a[j]);
                if (q[j] - r[j]).abs() > tol.axes[j] {
                    return false;
                }
            }
            if let (Some(p), Some(dev)) = (tol.position_mm, deviation)
                && dev(&q, k) > p
            {
                return false;
            }
        }
        true
    };
    let mut ends = vec![0];
    let mut s = 0;
    while s + 1 < n {
        // Exponential probe, then binary search between the last fit and the
        // first miss.
        let mut ok = s + 1;
        let mut step = 1;
        let mut bad = None;
        while ok < n - 1 {
            let e = (ok + step).min(n - 1);
            if fits(s, e) {
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
                if fits(s, mid) {
                    ok = mid;
                } else {
                    hi = mid;
                }
            }
        }
        ends.push(ok);
        s = ok;
    }
    Ok(ends)
}
