//! The NC blocks of a winding program: each layer's axes cut into blocks
//! within the tolerances and timed, skip layers' turns, and the whole
//! program joined from rest to rest with its joins ramped and re-timed.

use formcam_machine::AxisTrack;
use formcam_machine::Machine;
use formcam_machine::Target;
use formcam_motion::{
    AxisLimits, Deviation, Timing, Tolerance, check_acceleration, check_sequence_acceleration,
    check_timing, deltas, fit_blocks, global, join_times, pairwise, preliminary_times, ramp_pieces,
    sequence_with_acceleration, with_acceleration,
};
use formcam_nc::{AxisSpec, Block, Feed, Program};

use crate::ProgramError;
use crate::checks::{Check, Violated, accepted};
use crate::job::{MotionJob, Times};

/// The whole program, timed: the NC program (before the post), its blocks
/// as `blocks.csv` lists them, its times and the checks it failed.
#[derive(Debug, Clone, PartialEq)]
pub struct Assembled {
    /// The NC program (blocks with inverse-time feeds, header comments).
    pub program: Program,
    /// Every block after the first rapid, with its time.
    pub blocks: Vec<TimedBlock>,
    /// How many layers the program holds.
    pub layers: usize,
    /// The program's time with the chosen block times, s.
    pub time_s: f64,
    /// ... with the pairwise block times (the joins alike), s.
    pub time_pairwise_s: f64,
    /// ... with the global block times (the joins alike), s.
    pub time_global_s: f64,
    /// ... with the preliminary block times (eq. 17) and the moves between
    /// layers, s.
    pub time_preliminary_s: f64,
    /// The checks the whole program failed, its layers' and its own (the
    /// joins' timing): the program is written only when the job accepts them.
    pub violated: Vec<Violated>,
    /// The failed checks, each once, in [`Check`] order.
    pub accepted: Vec<Check>,
}

/// A block of the program as `blocks.csv` lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct TimedBlock {
    /// The axes at the block's end, NC units.
    pub target: Vec<f64>,
    /// The block's time, s.
    pub t: f64,
    /// The layer the block belongs to (or leads into), 1-based.
    pub layer: usize,
    /// The block's least time (eq. 17), s.
    pub t_star: f64,
}

/// A block of the program before the joins are timed.
struct Pending {
    target: Vec<f64>,
    t_star: f64,
    /// The block's `mu` as its layer timed it (1 for a move between layers).
    cap: f64,
    layer: usize,
    /// Blocks of one part (a layer, or one move between layers) share it.
    part: usize,
    comment: Option<String>,
    rezero: bool,
}

fn positive(field: &'static str, value: f64) -> Result<f64, ProgramError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ProgramError::NotPositive { field, value })
    }
}

/// Axis values in NC units: mm, and degrees for rotary axes.
pub fn nc(m: &Machine, a: usize, v: f64) -> f64 {
    if m.axes[a].is_rotary() {
        v.to_degrees()
    } else {
        v
    }
}

/// The blocks of one layer: its circuits, each cut and timed alike.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerBlocks {
    /// A label for comments and `blocks.csv`.
    pub label: String,
    /// Where the layer starts (NC units).
    pub start: Vec<f64>,
    /// Block ends (NC units) and times: `(target, t, t_star, mu)`.
    pub blocks: Vec<(Vec<f64>, f64, f64, f64)>,
    /// Time of the layer with the chosen, pairwise, global and preliminary times, s.
    pub times: [f64; 4],
    /// An offset the layer leaves to every later one (a skip layer's turn).
    pub carry: Vec<f64>,
    /// The checks that failed in this layer (the program is written only when
    /// the job accepts them).
    pub violated: Vec<Violated>,
}

/// Checks the axes of a layer, cuts one circuit into blocks, times them, and
/// repeats the circuit `circuits` times (each turned on by the circuit's turn).
pub fn layer_blocks(
    label: &str,
    m: &Machine,
    targets: &[Target],
    track: &AxisTrack,
    motion: &MotionJob,
    circuits: u32,
) -> Result<LayerBlocks, ProgramError> {
    // A program must not drive an axis beyond its limits (unless the job accepts it).
    let mut violated: Vec<Violated> = track
        .issues
        .iter()
        .filter_map(|i| {
            let check = Check::of_ik_issue(i.kind.name())?;
            let what = match (check, &i.axis) {
                (Check::Limits, Some(a)) => format!("drive axis {a} beyond its limit"),
                (Check::Clearance, _) => "bring the eye within its clearance".to_string(),
                _ => "miss the eye (unreachable)".to_string(),
            };
            Some(Violated {
                check,
                layer: label.to_string(),
                detail: format!(
                    "{what} at x = {:.3} mm ({} points, worst {:.4})",
                    i.x, i.count, i.worst
                ),
            })
        })
        .collect();
    let w = m.axes.len();
    let tol_mm = positive("motion.tolerance_mm", motion.tolerance_mm.unwrap_or(0.05))?;
    let tol_deg = positive("motion.tolerance_deg", motion.tolerance_deg.unwrap_or(0.05))?;
    let tau = positive("motion.tau_s", motion.tau_s.unwrap_or(0.004))?;
    let position = motion
        .position_tolerance_mm
        .map(|p| positive("motion.position_tolerance_mm", p))
        .transpose()?;
    let tol = Tolerance {
        axes: m
            .axes
            .iter()
            .map(|a| {
                if a.is_rotary() {
                    tol_deg.to_radians()
                } else {
                    tol_mm
                }
            })
            .collect(),
        position_mm: position,
    };
    let x: Vec<f64> = targets.iter().map(|t| t.x).collect();
    // The payout point's deviation where the axes move linearly.
    let payout = m.roles.payout;
    let wanted: Vec<_> = if position.is_some() {
        track.rows().map(|q| m.key_points(q)[payout]).collect()
    } else {
        Vec::new()
    };
    let deviation = |q: &[f64], k: usize| (m.key_points(q)[payout] - wanted[k]).norm();
    let ends = fit_blocks(
        &x,
        &track.values,
        w,
        &tol,
        position.map(|_| &deviation as Deviation<'_>),
    )?;
    let limits = axis_limits(m);
    let d = deltas(&track.values, w, &ends);
    let limit_err = ProgramError::AxisLimits;
    let t_star = preliminary_times(&d, &limits, tau).map_err(limit_err)?;
    let pw = pairwise(&d, &t_star, &limits).map_err(limit_err)?;
    let gl = global(&d, &t_star, &limits).map_err(limit_err)?;
    let chosen: &Timing = match motion.times {
        Times::Global => &gl,
        Times::Pairwise => &pw,
    };
    let ramped;
    let chosen: &Timing = if keeps_acceleration(motion) {
        let a_max = planned_a_max(m);
        ramped = with_acceleration(&d, chosen, &limits, &a_max).map_err(limit_err)?;
        if let Some(&(b, k, e)) = check_acceleration(&d, &ramped.times, &a_max).first() {
            violated.push(Violated {
                check: Check::Acceleration,
                layer: label.to_string(),
                detail: format!(
                    "break the acceleration limit of axis {} in block {} by {e:.3e}",
                    m.axes[k].name,
                    b + 1
                ),
            });
        }
        &ramped
    } else {
        chosen
    };
    if let Some(&(b, k, e)) = check_timing(&d, &chosen.times, &limits).first() {
        violated.push(Violated {
            check: Check::Timing,
            layer: label.to_string(),
            detail: format!(
                "break the velocity limits of axis {} in block {} by {e:.3e}",
                m.axes[k].name,
                b + 1
            ),
        });
    }
    let row = |i: usize| -> Vec<f64> {
        track
            .row(i)
            .iter()
            .enumerate()
            .map(|(a, v)| nc(m, a, *v))
            .collect()
    };
    let start = row(0);
    let last = row(ends.last().copied().unwrap_or(0));
    // Each circuit ends where the next begins, turned on by the circuit's turn.
    let shift: Vec<f64> = last.iter().zip(&start).map(|(e, s)| e - s).collect();
    let mut blocks = Vec::with_capacity((ends.len() - 1) * circuits.max(1) as usize);
    for c in 0..circuits.max(1) {
        for (b, e) in ends.iter().skip(1).enumerate() {
            let target = row(*e)
                .iter()
                .zip(&shift)
                .map(|(v, s)| v + f64::from(c) * s)
                .collect();
            blocks.push((target, chosen.times[b], t_star[b], chosen.mu[b]));
        }
    }
    let k = f64::from(circuits.max(1));
    Ok(LayerBlocks {
        label: label.to_string(),
        start,
        blocks,
        times: [
            k * chosen.total,
            k * pw.total,
            k * gl.total,
            k * t_star.iter().sum::<f64>(),
        ],
        carry: vec![0.0; w],
        violated,
    })
}

/// How far below each axis's `a_max` the planner keeps its velocity changes
/// (relative): the written program's block times differ from the planned
/// ones by the rounding of `F` and of the axis words, which the check of
/// the written text (`formcam check`) allows in the velocities but not in
/// the time an acceleration has: 0.1 % covers a `G93` block of up to two
/// minutes (`F = 60 / t` to 3 decimals) and a per-minute block (Marlin,
/// CLDATA) whose travel is at least a millimetre.
pub const ACCELERATION_MARGIN: f64 = 1e-3;

/// Whether the job's block times keep the axes' acceleration limits: unless
/// `[motion] acceleration = false`.
pub fn keeps_acceleration(motion: &MotionJob) -> bool {
    motion.acceleration.unwrap_or(true)
}

/// Each axis's acceleration limit as the planner keeps it (internal units
/// per s², `inf` where the machine gives none): `a_max` less
/// [`ACCELERATION_MARGIN`].
pub fn planned_a_max(m: &Machine) -> Vec<f64> {
    m.axes
        .iter()
        .map(|a| a.a_max * (1.0 - ACCELERATION_MARGIN))
        .collect()
}

/// The machine's axis limits for the block times.
pub fn axis_limits(m: &Machine) -> Vec<AxisLimits> {
    m.axes
        .iter()
        .map(|a| AxisLimits {
            v_max: a.v_max,
            dv_max: a.dv_max,
        })
        .collect()
}

/// A move of the spindle alone by `turn_deg` from `from` (a skip layer), timed
/// by the spindle's velocity limit.
pub fn skip_blocks(
    label: &str,
    m: &Machine,
    from: &[f64],
    turn_deg: f64,
    tau: f64,
) -> Result<LayerBlocks, ProgramError> {
    let s = m.roles.spindle.ok_or_else(|| ProgramError::NoSpindle {
        label: label.to_string(),
        machine: m.name.clone(),
    })?;
    if !turn_deg.is_finite() {
        return Err(ProgramError::SkipTurnNotFinite {
            label: label.to_string(),
        });
    }
    let mut target = from.to_vec();
    target[s] += turn_deg;
    let t = (turn_deg.to_radians().abs() / m.axes[s].v_max).max(tau);
    let mut carry = vec![0.0; from.len()];
    carry[s] = turn_deg;
    Ok(LayerBlocks {
        label: label.to_string(),
        start: from.to_vec(),
        blocks: vec![(target, t, t, 1.0)],
        times: [t; 4],
        carry,
        violated: Vec::new(),
    })
}

/// The whole program of `layers` (in order): the moves between layers, the
/// joins ramped and re-timed from rest to rest, its timing checked. `title`
/// names the job in the header, `name` the program.
pub fn assemble(
    title: &str,
    name: &str,
    m: &Machine,
    layers: &[LayerBlocks],
    motion: &MotionJob,
) -> Result<Assembled, ProgramError> {
    let tau = positive("motion.tau_s", motion.tau_s.unwrap_or(0.004))?;
    let axes: Vec<AxisSpec> = m
        .axes
        .iter()
        .map(|a| {
            if a.modulo {
                AxisSpec::rotary_modulo(a.name.clone())
            } else if a.is_rotary() {
                AxisSpec::rotary(a.name.clone())
            } else {
                AxisSpec::linear(a.name.clone())
            }
        })
        .collect();
    let total: [f64; 4] = layers.iter().fold([0.0; 4], |mut acc, l| {
        for (a, t) in acc.iter_mut().zip(l.times) {
            *a += t;
        }
        acc
    });
    let count: usize = layers.iter().map(|l| l.blocks.len()).sum();
    let mut program = Program::new(name, axes);
    let limits = axis_limits(m);
    let mut here_now: Option<Vec<f64>> = None;
    let mut pending_blocks: Vec<Pending> = Vec::with_capacity(count + layers.len());
    let mut transitions = 0.0;
    let mut pending: Option<String> = None;
    let mut carried = vec![0.0; m.axes.len()];
    for (li, l) in layers.iter().enumerate() {
        // A continuous rotary axis (no limits) starts the layer on the turn
        // nearest where it stands.
        // Skip layers before this one turn it on by their carry.
        let turn: Vec<f64> = m
            .axes
            .iter()
            .enumerate()
            .map(|(a, ax)| {
                let c = if l.carry.iter().any(|v| *v != 0.0) {
                    0.0
                } else {
                    carried[a]
                };
                match &here_now {
                    Some(prev)
                        if ax.is_rotary() && ax.min.is_infinite() && ax.max.is_infinite() =>
                    {
                        c + 360.0 * ((prev[a] - l.start[a] - c) / 360.0).round()
                    }
                    _ => c,
                }
            })
            .collect();
        for (c, v) in carried.iter_mut().zip(&l.carry) {
            *c += v;
        }
        let shifted = |v: &[f64]| -> Vec<f64> { v.iter().zip(&turn).map(|(x, t)| x + t).collect() };
        let start = shifted(&l.start);
        match &here_now {
            None => program
                .blocks
                .push(Block::rapid(start.clone()).with_comment(l.label.clone())),
            Some(prev) if prev.iter().zip(&start).all(|(p, s)| (p - s).abs() < 1e-9) => {
                // The layer starts where the last ended: its label goes on its
                // first block.
                pending = Some(l.label.clone());
            }
            Some(prev) => {
                // From the end of the last layer to the start of this one: one
                // block as fast as the axes allow.
                let t = prev
                    .iter()
                    .zip(&start)
                    .zip(m.axes.iter().zip(&limits))
                    .map(|((p, s), (a, lim))| {
                        let d = if a.is_rotary() {
                            (s - p).to_radians()
                        } else {
                            s - p
                        };
                        d.abs() / lim.v_max
                    })
                    .fold(tau, f64::max);
                transitions += t;
                // Modulo axes are re-zeroed between layers.
                pending_blocks.push(Pending {
                    target: start.clone(),
                    t_star: t,
                    cap: 1.0,
                    layer: li + 1,
                    part: 2 * li,
                    comment: Some(l.label.clone()),
                    rezero: true,
                });
            }
        }
        for (target, _, t_star, mu) in &l.blocks {
            let label = pending.take();
            pending_blocks.push(Pending {
                target: shifted(target),
                t_star: *t_star,
                cap: *mu,
                layer: li + 1,
                part: 2 * li + 1,
                rezero: label.is_some(),
                comment: label,
            });
        }
        here_now = pending_blocks
            .last()
            .map(|b| b.target.clone())
            .or_else(|| program.blocks.last().map(|b| b.target.clone()));
    }
    // The layers' circuits keep their times; the blocks round each join (and
    // the program's start and end, from and to rest) are slowed until every
    // jump holds across it.
    let from = program.blocks.first().map(|b| b.target.clone());
    let pending_blocks = ramps(m, from.as_deref(), pending_blocks, &limits, tau)?;
    let d = program_deltas(m, from.as_deref(), &pending_blocks);
    let t_star: Vec<f64> = pending_blocks.iter().map(|b| b.t_star).collect();
    let cap: Vec<f64> = pending_blocks.iter().map(|b| b.cap).collect();
    let mut joined = join_times(&d, &t_star, &cap, &limits)?;
    let mut program_violated = Vec::new();
    // A limit of axis `k` broken in block `b` (0-based) by `e`.
    let violated = |check: Check, limit: &str, (b, k, e): (usize, usize, f64)| Violated {
        check,
        layer: format!("layer {}", pending_blocks.get(b).map_or(0, |p| p.layer)),
        detail: format!(
            "break the {limit} of axis {} in block {} of the program by {e:.3e}",
            m.axes[k].name,
            b + 1
        ),
    };
    if keeps_acceleration(motion) {
        // The joins' ramps and the moves between layers, slowed where a
        // velocity change breaks an acceleration limit.
        let a_max = planned_a_max(m);
        joined = sequence_with_acceleration(&d, &joined, &limits, &a_max)?;
        if let Some(&first) = check_sequence_acceleration(&d, &joined.times, &a_max).first() {
            program_violated.push(violated(Check::Acceleration, "acceleration limit", first));
        }
    }
    if let Some(first) = timing_from_rest(&d, &joined.times, &limits) {
        program_violated.push(violated(Check::Timing, "velocity limits", first));
    }
    let count = pending_blocks.len();
    let mut timed = Vec::with_capacity(count);
    for (p, t) in pending_blocks.into_iter().zip(&joined.times) {
        timed.push(TimedBlock {
            target: p.target.clone(),
            t: *t,
            layer: p.layer,
            t_star: p.t_star,
        });
        let mut block = Block::linear(p.target, Feed::InverseTime(*t));
        if let Some(label) = p.comment {
            block = block.with_comment(label);
        }
        block.rezero = p.rezero;
        program.blocks.push(block);
    }
    // The joins' share of the program time, the same for every method.
    let joins = joined.total - total[0];
    program.header_comments = vec![
        format!("formcam: {} on {}", title, m.name),
        format!(
            "{} layers, {count} blocks, {:.3} s ({} block times; pairwise {:.3} s, global {:.3} s)",
            layers.len(),
            total[0] + joins,
            motion.times.name(),
            total[1] + joins,
            total[2] + joins
        ),
    ];
    let violated: Vec<Violated> = layers
        .iter()
        .flat_map(|l| l.violated.clone())
        .chain(program_violated)
        .collect();
    let accepted = accepted(&violated);
    if !accepted.is_empty() {
        program.header_comments.push(format!(
            "checks accepted as violated ([checks] allow): {}",
            accepted
                .iter()
                .map(|c| c.name())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    Ok(Assembled {
        program,
        blocks: timed,
        layers: layers.len(),
        time_s: total[0] + joins,
        time_pairwise_s: total[1] + joins,
        time_global_s: total[2] + joins,
        time_preliminary_s: total[3] + transitions,
        violated,
        accepted,
    })
}

/// The blocks next to each join (and at the program's start and end), cut
/// along their lines where the jump across the join breaks a limit, so that
/// the velocity ramps in short pieces there (see [`ramp_pieces`]). A piece
/// runs no faster than its block did.
fn ramps(
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
fn program_deltas(m: &Machine, from: Option<&[f64]>, blocks: &[Pending]) -> Vec<f64> {
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
fn timing_from_rest(
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
