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
    // One buffer of link poses and one of run lengths for every point: only
    // the band path's key points are placed.
    let mut poses = Vec::with_capacity(m.links.len());
    let mut out = vec![0.0; path.len()];
    let mut run = |q: &[f64], t: &Target, out: &mut [f64]| {
        m.poses_into(q, &mut poses);
        let at = |k: usize| {
            let p = &m.points[path[k]];
            poses[p.link] * p.position
        };
        // Distance from each band-path point to the payout point along the path.
        out.fill(0.0);
        for i in (0..path.len().saturating_sub(1)).rev() {
            out[i] = out[i + 1] + (at(i + 1) - at(i)).norm();
        }
        for d in out.iter_mut() {
            *d = *d + t.free_length + t.x;
        }
    };
    let Some((q0, t0)) = track.rows().next().zip(targets.first()) else {
        return Vec::new();
    };
    let mut start = vec![0.0; path.len()];
    run(q0, t0, &mut start);
    track
        .rows()
        .zip(targets)
        .map(|(q, t)| {
            run(q, t, &mut out);
            out.iter().zip(&start).map(|(a, b)| a - b).collect()
        })
        .collect()
}
