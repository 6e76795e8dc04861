//! Ramps at the joins of a program timed in parts: a long block next to a join
//! whose velocity jump breaks a limit is cut, along its own straight line, into
//! short pieces on the join's side, so that the velocity can ramp there in
//! steps of the jump limit instead of the whole block being slowed.

use crate::MotionError;
use crate::times::AxisLimits;

/// Where to cut each block: the ends of its pieces as fractions of the block
/// (increasing, the last 1), for the blocks `deltas` (`limits.len()` axes per
/// block) with least times `t_star` and `mu` as timed in their parts `cap`.
///
/// `joins[i]` (`n + 1` entries): whether a join lies before block `i`
/// (`joins[0]`: the start, from rest; `joins[n]`: the end, to rest). A block
/// whose velocity jump across a join breaks a limit (against rest at the
/// ends) gets, on that side, pieces lasting the least block time `tau` at
/// `1/m, 2/m, ...` of its velocity (`m` steps of the jump limit reach it); at
/// most half of the block is cut so on each side. Other blocks stay whole.
pub fn ramp_pieces(
    deltas: &[f64],
    t_star: &[f64],
    cap: &[f64],
    joins: &[bool],
    limits: &[AxisLimits],
    tau: f64,
) -> Result<Vec<Vec<f64>>, MotionError> {
    let w = limits.len().max(1);
    let n = t_star.len();
    if deltas.len() != n * w || cap.len() != n || joins.len() != n + 1 {
        return Err(MotionError::Field {
            field: "ramp_pieces".into(),
            reason: format!(
                "{n} blocks need {} motions, {n} caps and {} joins, got {}, {} and {}",
                n * w,
                n + 1,
                deltas.len(),
                cap.len(),
                joins.len()
            ),
        });
    }
    if !(tau.is_finite() && tau > 0.0) {
        return Err(MotionError::Field {
            field: "tau".into(),
            reason: format!("the least block time must be a finite number > 0 s, got {tau}"),
        });
    }
    // Each block's velocity as timed in its part.
    let v = |i: usize, k: usize| deltas[i * w + k] * cap[i] / t_star[i];
    let breaks = |i: usize, other: Option<usize>| {
        limits.iter().enumerate().any(|(k, l)| {
            let u = other.map_or(0.0, |j| v(j, k));
            (v(i, k) - u).abs() > l.dv_max
        })
    };
    Ok((0..n)
        .map(|i| {
            let t = t_star[i] / cap[i];
            let steps = limits
                .iter()
                .enumerate()
                .map(|(k, l)| (v(i, k).abs() / l.dv_max).ceil())
                .fold(1.0f64, f64::max);
            let ramp = |side: bool| -> Vec<f64> {
                if !side {
                    return Vec::new();
                }
                // Piece j lasts tau at j/steps of the velocity: a fraction
                // j tau / (steps t) of the block; at most half of it in all.
                let mut out = Vec::new();
                let mut sum = 0.0;
                let mut j = 1.0;
                while j < steps {
                    let f = j * tau / (steps * t);
                    if sum + f >= 0.5 {
                        break;
                    }
                    sum += f;
                    out.push(f);
                    j += 1.0;
                }
                out
            };
            let up = ramp(joins[i] && breaks(i, i.checked_sub(1)));
            let down = ramp(joins[i + 1] && breaks(i, Some(i + 1).filter(|&j| j < n)));
            let mut ends = Vec::with_capacity(up.len() + down.len() + 1);
            let mut at = 0.0;
            for f in &up {
                at += f;
                ends.push(at);
            }
            let tail: f64 = down.iter().sum();
            if !down.is_empty() {
                at = 1.0 - tail;
                ends.push(at);
                for f in down.iter().rev().take(down.len() - 1) {
                    at += f;
                    ends.push(at);
                }
            }
            ends.push(1.0);
            ends
        })
        .collect())
}
