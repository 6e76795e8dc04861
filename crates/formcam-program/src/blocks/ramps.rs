//! The program's blocks round each join cut into ramps, their axis motions,
//! and the program's timing checked from rest to rest.

use formcam_machine::Machine;
use formcam_motion::{AxisLimits, check_timing, preliminary_times, ramp_pieces};

use super::assemble::Pending;

/// The blocks next to each join (and at the program's start and end), cut
/// along their lines where the jump across the join breaks a limit, so that
/// the velocity ramps in short pieces there (see [`ramp_pieces`]). A piece
/// runs no faster than its block did.
pub(super) fn ramps(
    m: &Machine,
    from: Option<&[f64]>,
    blocks: Vec<Pending>,
    limits: &[AxisLimits],
    tau: f64,
) -> Result<Vec<Pending>, formcam_motion::MotionError> {
    let n = blocks.len();
    let w = m.axes.len();
    let d = program_deltas(m, from, &blocks);
    let t_star: Vec<f64> = blocks.iter().map(|b| b.t_star).collect();
    let cap: Vec<f64> = blocks.iter().map(|b| b.cap).collect();
    let joins: Vec<bool> = (0..=n)
        .map(|i| i == 0 || i == n || blocks[i].part != blocks[i - 1].part)
        .collect();
    let cuts = ramp_pieces(&d, &t_star, &cap, &joins, limits, tau)?;
    let mut out = Vec::with_capacity(n + cuts.iter().map(Vec::len).sum::<usize>());
    let mut prev: Option<Vec<f64>> = from.map(<[f64]>::to_vec);
    for (i, (b, ends)) in blocks.into_iter().zip(cuts).enumerate() {
        let start = prev.take().unwrap_or_else(|| b.target.clone());
        if ends.len() < 2 {
            prev = Some(b.target.clone());
            out.push(b);
            continue;
        }
        let t_block = b.t_star / b.cap;
        let mut at = 0.0;
        let mut comment = b.comment;
        for (j, &e) in ends.iter().enumerate() {
            let target: Vec<f64> = if j + 1 == ends.len() {
                b.target.clone()
            } else {
                start
                    .iter()
                    .zip(&b.target)
                    .map(|(s, t)| s + e * (t - s))
                    .collect()
            };
            let piece: Vec<f64> = d[i * w..(i + 1) * w].iter().map(|v| v * (e - at)).collect();
            let t_star = preliminary_times(&piece, limits, tau)?
                .first()
                .copied()
                .unwrap_or(tau);
            out.push(Pending {
                target,
                t_star,
                cap: (t_star / ((e - at) * t_block)).min(1.0),
                layer: b.layer,
                part: b.part,
                rezero: j == 0 && b.rezero,
                comment: comment.take(),
            });
            at = e;
        }
        prev = Some(b.target);
    }
    Ok(out)
}

/// The axis motions (mm, rad) of the program's blocks from `from` (NC units,
/// where the first block starts), block after block.
pub(super) fn program_deltas(m: &Machine, from: Option<&[f64]>, blocks: &[Pending]) -> Vec<f64> {
    let w = m.axes.len();
    let internal = |a: usize, v: f64| {
        if m.axes[a].is_rotary() {
            v.to_radians()
        } else {
            v
        }
    };
    let mut out = Vec::with_capacity(blocks.len() * w);
    let mut prev: Option<&[f64]> = from;
    for b in blocks {
        let p = prev.unwrap_or(&b.target);
        for (a, (t, f)) in b.target.iter().zip(p).enumerate().take(w) {
            out.push(internal(a, *t) - internal(a, *f));
        }
        prev = Some(&b.target);
    }
    out
}

/// The first broken velocity or jump limit of the whole program (`(block,
/// axis, excess)`), which starts and ends at rest.
pub(super) fn timing_from_rest(
    deltas: &[f64],
    times: &[f64],
    limits: &[AxisLimits],
) -> Option<(usize, usize, f64)> {
    let mut d = deltas.to_vec();
    d.extend(std::iter::repeat_n(0.0, limits.len()));
    let mut t = times.to_vec();
    t.push(1.0);
    check_timing(&d, &t, limits).first().copied()
}
