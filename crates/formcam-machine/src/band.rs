//! The length of band that has passed each key point of the band path.

use crate::ik::AxisTrack;
use crate::{Fk, Machine, Target};

/// The band length that has passed each key point of the band path, per
/// point of a trajectory: one row per point, one column per key point
/// (creel side first), mm; held in one buffer.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BandPassed {
    /// The rows one after the other: see [`BandPassed::rows`].
    pub values: Vec<f64>,
    /// Key points per row (the band path's length; empty rows when 0).
    pub width: usize,
    /// How many rows (points).
    pub points: usize,
}

impl BandPassed {
    /// The rows, point after point.
    pub fn rows(&self) -> impl ExactSizeIterator<Item = &[f64]> + DoubleEndedIterator {
        (0..self.points).map(|i| self.row(i))
    }

    /// The row of point `i`.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.values[i * self.width..(i + 1) * self.width]
    }

    /// The last row (what has passed over the whole trajectory).
    pub fn last(&self) -> Option<&[f64]> {
        self.points.checked_sub(1).map(|i| self.row(i))
    }

    /// How many rows.
    pub fn len(&self) -> usize {
        self.points
    }

    /// Whether there are no rows.
    pub fn is_empty(&self) -> bool {
        self.points == 0
    }
}

/// For each point of `track` and each key point of the band path (creel side
/// first), the band length that has passed it since the first point, mm.
///
/// The band from a key point to the mandrel runs along the band path to the
/// payout point, then the free length `l` to the path point; what has passed a
/// key point is what has been laid (`x`) plus the growth of that run. Only the
/// band path's links are placed (their forward kinematics prepared once), and
/// the rows are written into one buffer (empty rows for a machine without a
/// band path).
pub fn band_passed(m: &Machine, targets: &[Target], track: &AxisTrack) -> BandPassed {
    let path = &m.roles.band_path;
    let width = path.len();
    let links: Vec<usize> = path.iter().map(|&k| m.points[k].link).collect();
    let fk = Fk::for_links(m, &links);
    let mut poses = Vec::with_capacity(m.links.len());
    // Distance from each band-path point to the payout point along the path,
    // plus the free length and what has been laid.
    let mut run = |q: &[f64], t: &Target, out: &mut [f64]| {
        fk.poses_into(q, &mut poses);
        let at = |k: usize| {
            let p = &m.points[path[k]];
            poses[p.link] * p.position
        };
        out.fill(0.0);
        for i in (0..width.saturating_sub(1)).rev() {
            out[i] = out[i + 1] + (at(i + 1) - at(i)).norm();
        }
        for d in out.iter_mut() {
            *d = *d + t.free_length + t.x;
        }
    };
    let Some((q0, t0)) = track.rows().next().zip(targets.first()) else {
        return BandPassed {
            values: Vec::new(),
            width,
            points: 0,
        };
    };
    let mut start = vec![0.0; width];
    run(q0, t0, &mut start);
    let n = track.rows().len().min(targets.len());
    let mut values = vec![0.0; n * width];
    for (i, (q, t)) in track.rows().zip(targets).enumerate() {
        let out = &mut values[i * width..(i + 1) * width];
        run(q, t, out);
        for (d, s) in out.iter_mut().zip(&start) {
            *d -= s;
        }
    }
    BandPassed {
        values,
        width,
        points: n,
    }
}
