//! Acceleration limits on top of the velocity and velocity-jump limits:
//! block times lengthened (never shortened, the path never moved) until the
//! velocity change between every pair of neighbouring blocks can ramp at
//! each axis's `a_max` within half of each block,
//!
//! ```text
//! | Delta_i^k / t_i  -  Delta_j^k / t_j |  <=  a_max^k (t_i + t_j) / 2
//! ```
//!
//! the rule `formcam check` judges a written program by. A circuit is timed
//! as a cycle (its last block meets its first); a whole program as a
//! sequence from rest to rest (the simulator checks acceleration between
//! feed blocks only, the jumps from and to rest by `dv_max`, which slowing
//! never breaks).

use std::collections::VecDeque;

use crate::{AxisLimits, MotionError, SolverFault, Timing};

/// How far inside a row a fix aims, so that rounding cannot leave it broken.
const INSIDE: f64 = 1.0 - 1e-12;

/// The relative tolerance of [`check_acceleration`] and
/// [`check_sequence_acceleration`].
const CHECK_TOLERANCE: f64 = 1e-9;

/// Per-axis acceleration limits on a circuit timed as a cycle (block `n`
/// meets block 1). See [`sequence_with_acceleration`] for the rule; the
/// result keeps every velocity-jump limit of `limits` too, and equals
/// `timing` where no row is broken.
pub fn with_acceleration(
    deltas: &[f64],
    timing: &Timing,
    limits: &[AxisLimits],
    a_max: &[f64],
) -> Result<Timing, MotionError> {
    settle(deltas, timing, limits, a_max, true)
}

/// Per-axis acceleration limits (`a_max`, units/s², `inf` where an axis
/// has none) on a sequence of blocks from rest to rest (a whole program):
/// the blocks of `timing` slowed where a pair of neighbours breaks
/// `|v_i - v_j| <= a_max (t_i + t_j) / 2` on some axis, or where that
/// breaks a velocity jump (`dv_max` of `limits`).
///
/// A broken row is mended by the least slow-down of one pair:
///
/// * an axis that keeps its direction: only the faster block slows, to the
///   time at which its velocity change to the other ramps exactly within
///   the two half blocks (`|Delta_i| / t - |v_j| = a_max (t + t_j) / 2`, a
///   quadratic in `t`);
/// * an axis that reverses: both blocks slow by the same factor `s`
///   (velocities times `s`, times over `s`: `s^2 = allowed / change`);
/// * a velocity jump: as the jump limits' own mend (the faster block to the
///   slower one's velocity plus the jump; across a reversal both).
///
/// Each mend puts the rows beside it back on a work list, so slowing
/// travels along a chain of binding rows (the ramp before a reversal)
/// without sweeping the whole sequence again. Velocities only fall: the
/// result keeps every velocity limit and every jump from or to rest that
/// `timing` kept. `mu` falls by the same factors.
pub fn sequence_with_acceleration(
    deltas: &[f64],
    timing: &Timing,
    limits: &[AxisLimits],
    a_max: &[f64],
) -> Result<Timing, MotionError> {
    settle(deltas, timing, limits, a_max, false)
}

/// The work list of [`with_acceleration`] and [`sequence_with_acceleration`].
fn settle(
    deltas: &[f64],
    timing: &Timing,
    limits: &[AxisLimits],
    a_max: &[f64],
    cyclic: bool,
) -> Result<Timing, MotionError> {
    let w = a_max.len().max(1);
    for (k, a) in a_max.iter().enumerate() {
        if a.is_nan() || *a <= 0.0 {
            return Err(MotionError::Field {
                field: format!("axis #{}: a_max", k + 1),
                reason: format!("must be > 0, got {a}"),
            });
        }
    }
    let n = timing.times.len();
    if deltas.len() != n * w || timing.mu.len() != n {
        return Err(MotionError::Field {
            field: "acceleration".into(),
            reason: format!(
                "{n} blocks of {w} axes need {} motions and {n} mu, got {} and {}",
                n * w,
                deltas.len(),
                timing.mu.len()
            ),
        });
    }
    let pairs = match (n, cyclic) {
        (0 | 1, _) => 0,
        (_, true) => n,
        (_, false) => n - 1,
    };
    if pairs == 0 {
        return Ok(timing.clone());
    }
    let rho: Vec<f64> = (0..w)
        .map(|k| limits.get(k).map_or(f64::INFINITY, |l| l.dv_max))
        .collect();
    let mut t = timing.times.clone();
    let mut mu = timing.mu.clone();
    let mut queued = vec![true; pairs];
    let mut work: VecDeque<usize> = (0..pairs).collect();
    // Every mend slows a block by a finite step; a sequence that needs more
    // than this many has lost its way (no shipped job comes near).
    let most = 1000 * pairs + 1_000_000;
    let mut mends = 0usize;
    while let Some(p) = work.pop_front() {
        queued[p] = false;
        let (i, j) = (p, (p + 1) % n);
        let (si, sj) = pair_scale(
            (&deltas[i * w..(i + 1) * w], t[i]),
            (&deltas[j * w..(j + 1) * w], t[j]),
            a_max,
            &rho,
        );
        if si >= 1.0 && sj >= 1.0 {
            continue;
        }
        mends += 1;
        if mends > most {
            return Err(SolverFault::AccelerationUnsettled.into());
        }
        let mut touched = |b: usize, s: f64, t: &mut [f64], mu: &mut [f64]| {
            if s < 1.0 {
                t[b] /= s;
                mu[b] *= s;
                // The rows on both sides of block b (the pair itself too:
                // one axis's mend may break another's row).
                let rows = if cyclic {
                    [Some((b + n - 1) % n), Some(b)]
                } else {
                    [b.checked_sub(1), (b < pairs).then_some(b)]
                };
                for q in rows.into_iter().flatten() {
                    if !queued[q] {
                        queued[q] = true;
                        work.push_back(q);
                    }
                }
            }
        };
        touched(i, si, &mut t, &mut mu);
        touched(j, sj, &mut t, &mut mu);
    }
    let total = t.iter().sum();
    Ok(Timing {
        mu,
        times: t,
        total,
    })
}

/// The factors (`<= 1`, velocities times it, times over it) by which blocks
/// `i` and `j` (motions and times) slow so that every row between them
/// holds; `(1, 1)` when they all do.
fn pair_scale(
    (di, ti): (&[f64], f64),
    (dj, tj): (&[f64], f64),
    a_max: &[f64],
    rho: &[f64],
) -> (f64, f64) {
    let (mut si, mut sj) = (1.0f64, 1.0f64);
    for (k, (&a, &r)) in a_max.iter().zip(rho).enumerate() {
        let (vi, vj) = (di[k] / ti, dj[k] / tj);
        let change = (vi - vj).abs();
        if r.is_finite() && change > r * (1.0 + 1e-12) {
            if vi * vj < 0.0 {
                let s = r / change * INSIDE;
                si = si.min(s);
                sj = sj.min(s);
            } else if vi.abs() > vj.abs() {
                si = si.min((vj.abs() + r * INSIDE) / vi.abs());
            } else {
                sj = sj.min((vi.abs() + r * INSIDE) / vj.abs());
            }
        }
        let allowed = a * 0.5 * (ti + tj);
        if a.is_finite() && change > allowed * (1.0 + 1e-12) {
            if vi * vj < 0.0 {
                let s = (allowed / change).sqrt() * INSIDE;
                si = si.min(s);
                sj = sj.min(s);
            } else if vi.abs() > vj.abs() {
                si = si.min(ti / ramp_time(di[k].abs(), vj.abs(), tj, a) * INSIDE);
            } else {
                sj = sj.min(tj / ramp_time(dj[k].abs(), vi.abs(), ti, a) * INSIDE);
            }
        }
    }
    (si, sj)
}

/// The time `x` of a block moving `d` at which its velocity `d / x` exceeds
/// its neighbour's `v` (same direction, time `t`) by exactly what `a`
/// allows within the two half blocks: `d / x - v = a (x + t) / 2`, the
/// positive root of `(a / 2) x^2 + (v + a t / 2) x - d = 0` (written
/// without cancellation).
fn ramp_time(d: f64, v: f64, t: f64, a: f64) -> f64 {
    let b = v + 0.5 * a * t;
    2.0 * d / (b + (b * b + 2.0 * a * d).sqrt())
}

/// Broken acceleration limits of a circuit timed as a cycle: `(block, axis,
/// excess)` where the velocity change to the next block (the last block's
/// to the first) exceeds `a_max (t_i + t_j) / 2` (relative tolerance 1e-9).
pub fn check_acceleration(
    deltas: &[f64],
    times: &[f64],
    a_max: &[f64],
) -> Vec<(usize, usize, f64)> {
    broken(deltas, times, a_max, true)
}

/// [`check_acceleration`] of a sequence from rest to rest: no row between
/// the last block and the first.
pub fn check_sequence_acceleration(
    deltas: &[f64],
    times: &[f64],
    a_max: &[f64],
) -> Vec<(usize, usize, f64)> {
    broken(deltas, times, a_max, false)
}

fn broken(deltas: &[f64], times: &[f64], a_max: &[f64], cyclic: bool) -> Vec<(usize, usize, f64)> {
    let w = a_max.len().max(1);
    let n = times.len();
    let mut out = Vec::new();
    if n < 2 || deltas.len() < n * w {
        return out;
    }
    let pairs = if cyclic { n } else { n - 1 };
    for i in 0..pairs {
        let j = (i + 1) % n;
        for (k, a) in a_max.iter().enumerate() {
            let jump = (deltas[i * w + k] / times[i] - deltas[j * w + k] / times[j]).abs();
            let allowed = a * 0.5 * (times[i] + times[j]);
            if jump > allowed * (1.0 + CHECK_TOLERANCE) {
                out.push((i, k, jump - allowed));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn timing(times: &[f64]) -> Timing {
        Timing {
            mu: vec![1.0; times.len()],
            times: times.to_vec(),
            total: times.iter().sum(),
        }
    }

    fn free() -> Vec<AxisLimits> {
        vec![AxisLimits {
            v_max: f64::INFINITY,
            dv_max: f64::INFINITY,
        }]
    }

    #[test]
    fn the_faster_block_slows_to_the_ramp_exactly() {
        // 1 mm/s for 1 s, then 10 mm in 1 s: a change of 9 mm/s against
        // a_max 2 mm/s² over (1 + t) / 2.
        let d = [1.0, 10.0];
        let r = sequence_with_acceleration(&d, &timing(&[1.0, 1.0]), &free(), &[2.0]).unwrap();
        assert_eq!(r.times[0], 1.0);
        let t = r.times[1];
        // 10 / t - 1 = 2 (1 + t) / 2: t^2 + 2 t - 10 = 0.
        let exact = -1.0 + 11f64.sqrt();
        assert!((t - exact).abs() < 1e-9 * exact, "{t} vs {exact}");
        assert!(check_sequence_acceleration(&d, &r.times, &[2.0]).is_empty());
        assert!((r.mu[1] - 1.0 / exact).abs() < 1e-9);
    }

    #[test]
    fn a_reversal_slows_both_blocks_alike() {
        // +4 and -4 mm/s for 1 s each: a change of 8 against 2 (1 + 1) / 2.
        let d = [4.0, -4.0];
        let r = sequence_with_acceleration(&d, &timing(&[1.0, 1.0]), &free(), &[2.0]).unwrap();
        assert_eq!(r.times[0], r.times[1]);
        // 8 / t = 2 t: t = 2.
        assert!((r.times[0] - 2.0).abs() < 1e-9, "{:?}", r.times);
    }

    #[test]
    fn a_feasible_timing_is_returned_unchanged() {
        let d = [1.0, 2.0, 3.0, 2.0];
        let tm = timing(&[1.0, 1.0, 1.0, 1.0]);
        assert_eq!(
            sequence_with_acceleration(&d, &tm, &free(), &[1.0]).unwrap(),
            tm
        );
        assert_eq!(with_acceleration(&d, &tm, &free(), &[2.0]).unwrap(), tm);
        // The cycle also meets 2 -> 1: within 2 but not within 0.5.
        assert!(with_acceleration(&d, &tm, &free(), &[0.5]).unwrap().total > tm.total);
    }

    #[test]
    fn a_ramp_travels_back_along_a_chain() {
        // Ten blocks of 10 mm at 10 mm/s, then a stop (a block that does not
        // move): the slow-down reaches back block after block.
        let mut d = vec![10.0; 10];
        d.push(0.0);
        let tm = timing(&[1.0; 11]);
        let a = [5.0];
        let r = sequence_with_acceleration(&d, &tm, &free(), &a).unwrap();
        assert!(check_sequence_acceleration(&d, &r.times, &a).is_empty());
        let v: Vec<f64> = d.iter().zip(&r.times).map(|(d, t)| d / t).collect();
        assert!(v.windows(2).take(9).all(|p| p[0] >= p[1]), "{v:?}");
        assert!(r.times[0] < r.times[9]);
        // The jump limit holds too.
        let lim = vec![AxisLimits {
            v_max: 10.0,
            dv_max: 1.5,
        }];
        let r = sequence_with_acceleration(&d, &tm, &lim, &a).unwrap();
        let v: Vec<f64> = d.iter().zip(&r.times).map(|(d, t)| d / t).collect();
        assert!(
            v.windows(2)
                .all(|p| (p[0] - p[1]).abs() <= 1.5 * (1.0 + 1e-9))
        );
    }

    #[test]
    fn bad_limits_are_refused() {
        let tm = timing(&[1.0, 1.0]);
        assert!(sequence_with_acceleration(&[1.0, 2.0], &tm, &free(), &[0.0]).is_err());
        assert!(sequence_with_acceleration(&[1.0], &tm, &free(), &[1.0]).is_err());
    }
}
