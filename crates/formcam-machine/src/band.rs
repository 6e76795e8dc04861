//! The length of band that has passed each key point of the band path.

use crate::ik::AxisTrack;
use crate::{Machine, Target};

/// For each point of `track` and each key point of the band path (creel side
/// first), the band length that has passed it since the first point, mm.
///
/// The band from a key point to the mandrel runs along the band path to the
/// payout point, then the free length `l` to the path point; what has passed a
/// key point is what has been laid (`x`) plus the growth of that run.
pub fn band_passed(m: &Machine, targets: &[Target], track: &AxisTrack) -> Vec<Vec<f64>> {
    let path = &m.roles.band_path;
    let run = |q: &[f64], t: &Target| -> Vec<f64> {
        let pts = m.key_points(q);
        // Distance from each band-path point to the payout point along the path.
        let mut out = vec![0.0; path.len()];
        for i in (0..path.len().saturating_sub(1)).rev() {
            out[i] = out[i + 1] + (pts[path[i + 1]] - pts[path[i]]).norm();
        }
        out.iter().map(|d| d + t.free_length + t.x).collect()
    };
    let Some((q0, t0)) = track.rows().next().zip(targets.first()) else {
        return Vec::new();
    };
    let start = run(q0, t0);
    track
        .rows()
        .zip(targets)
        .map(|(q, t)| run(q, t).iter().zip(&start).map(|(a, b)| a - b).collect())
        .collect()
}
