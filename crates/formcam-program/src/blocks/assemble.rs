//! The whole program: the layers laid one after another with the moves
//! between them, the joins ramped and re-timed from rest to rest, its timing
//! checked and its header written.

use formcam_machine::Machine;
use formcam_motion::{
    AxisLimits, Timing, check_sequence_acceleration, join_times, sequence_with_acceleration,
};
use formcam_nc::{AxisSpec, Block, Feed, Program};

use super::ramps::{program_deltas, ramps, timing_from_rest};
use super::{
    Assembled, LayerBlocks, TimedBlock, axis_limits, keeps_acceleration, planned_a_max, positive,
};
use crate::ProgramError;
use crate::checks::{Check, Violated, accepted};
use crate::job::MotionJob;

/// A block of the program before the joins are timed.
pub(super) struct Pending {
    pub(super) target: Vec<f64>,
    pub(super) t_star: f64,
    /// The block's `mu` as its layer timed it (1 for a move between layers).
    pub(super) cap: f64,
    pub(super) layer: usize,
    /// Blocks of one part (a layer, or one move between layers) share it.
    pub(super) part: usize,
    pub(super) comment: Option<String>,
    pub(super) rezero: bool,
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
    let tau = positive(
        "motion.tau_s",
        motion.tau_s.unwrap_or(formcam_motion::DEFAULT_TAU_S),
    )?;
    let total = layer_totals(layers);
    let mut program = Program::new(name, program_axes(m));
    let limits = axis_limits(m);
    let laid = Laying::lay(m, layers, &limits, tau, &mut program);
    // The layers' circuits keep their times; the blocks round each join (and
    // the program's start and end, from and to rest) are slowed until every
    // jump holds across it.
    let from = program.blocks.first().map(|b| b.target.clone());
    let pending_blocks = ramps(m, from.as_deref(), laid.blocks, &limits, tau)?;
    let (joined, program_violated) =
        time_joins(m, motion, from.as_deref(), &pending_blocks, &limits)?;
    let count = pending_blocks.len();
    let timed = push_blocks(&mut program, pending_blocks, &joined.times);
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
        time_preliminary_s: total[3] + laid.transitions,
        violated,
        accepted,
    })
}

/// The program's axes as the NC program names them.
fn program_axes(m: &Machine) -> Vec<AxisSpec> {
    m.axes
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
        .collect()
}

/// The layers' times summed: chosen, pairwise, global and preliminary, s.
fn layer_totals(layers: &[LayerBlocks]) -> [f64; 4] {
    layers.iter().fold([0.0; 4], |mut acc, l| {
        for (a, t) in acc.iter_mut().zip(l.times) {
            *a += t;
        }
        acc
    })
}

/// The layers laid one after another: the first from a rapid, each later one
/// on the turn nearest where the last ended, a move between them where they
/// do not meet.
struct Laying<'a> {
    /// The machine.
    m: &'a Machine,
    /// Its axis limits.
    limits: &'a [AxisLimits],
    /// The least block time, s.
    tau: f64,
    /// Where the last layer ended (NC units); `None` before the first.
    here_now: Option<Vec<f64>>,
    /// The blocks so far.
    blocks: Vec<Pending>,
    /// The moves' least times summed, s.
    transitions: f64,
    /// A layer's label waiting for its first block.
    pending: Option<String>,
    /// The skip layers' turns so far.
    carried: Vec<f64>,
}

impl<'a> Laying<'a> {
    /// Lays `layers` (the first rapid goes to `program`).
    fn lay(
        m: &'a Machine,
        layers: &[LayerBlocks],
        limits: &'a [AxisLimits],
        tau: f64,
        program: &mut Program,
    ) -> Laying<'a> {
        let count: usize = layers.iter().map(|l| l.blocks.len()).sum();
        let mut laying = Laying {
            m,
            limits,
            tau,
            here_now: None,
            blocks: Vec::with_capacity(count + layers.len()),
            transitions: 0.0,
            pending: None,
            carried: vec![0.0; m.axes.len()],
        };
        for (li, l) in layers.iter().enumerate() {
            laying.layer(li, l, program);
        }
        laying
    }

    /// Lays layer `li`, `l`.
    fn layer(&mut self, li: usize, l: &LayerBlocks, program: &mut Program) {
        let turn = self.turn(l);
        for (c, v) in self.carried.iter_mut().zip(&l.carry) {
            *c += v;
        }
        let shifted = |v: &[f64]| -> Vec<f64> { v.iter().zip(&turn).map(|(x, t)| x + t).collect() };
        self.start(li, l, shifted(&l.start), program);
        for (target, _, t_star, mu) in &l.blocks {
            let label = self.pending.take();
            self.blocks.push(Pending {
                target: shifted(target),
                t_star: *t_star,
                cap: *mu,
                layer: li + 1,
                part: 2 * li + 1,
                rezero: label.is_some(),
                comment: label,
            });
        }
        self.here_now = self
            .blocks
            .last()
            .map(|b| b.target.clone())
            .or_else(|| program.blocks.last().map(|b| b.target.clone()));
    }

    /// The turn of each axis that layer `l` is laid on: a continuous rotary
    /// axis (no limits) starts the layer on the turn nearest where it stands;
    /// skip layers before this one turn it on by their carry.
    fn turn(&self, l: &LayerBlocks) -> Vec<f64> {
        self.m
            .axes
            .iter()
            .enumerate()
            .map(|(a, ax)| {
                let c = if l.carry.iter().any(|v| *v != 0.0) {
                    0.0
                } else {
                    self.carried[a]
                };
                match &self.here_now {
                    Some(prev)
                        if ax.is_rotary() && ax.min.is_infinite() && ax.max.is_infinite() =>
                    {
                        c + 360.0 * ((prev[a] - l.start[a] - c) / 360.0).round()
                    }
                    _ => c,
                }
            })
            .collect()
    }

    /// The way to layer `li`, `l`, starting at `start`: a rapid to the first,
    /// nothing where the last ended there, else one move.
    fn start(&mut self, li: usize, l: &LayerBlocks, start: Vec<f64>, program: &mut Program) {
        match &self.here_now {
            None => program
                .blocks
                .push(Block::rapid(start.clone()).with_comment(l.label.clone())),
            Some(prev) if prev.iter().zip(&start).all(|(p, s)| (p - s).abs() < 1e-9) => {
                // The layer starts where the last ended: its label goes on its
                // first block.
                self.pending = Some(l.label.clone());
            }
            Some(prev) => {
                let t = self.move_time(prev, &start);
                self.transitions += t;
                // Modulo axes are re-zeroed between layers.
                self.blocks.push(Pending {
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
    }

    /// The least time of one block from the end of the last layer, `prev`, to
    /// the start of the next, `start`: as fast as the axes allow.
    fn move_time(&self, prev: &[f64], start: &[f64]) -> f64 {
        prev.iter()
            .zip(start)
            .zip(self.m.axes.iter().zip(self.limits))
            .map(|((p, s), (a, lim))| {
                let d = if a.is_rotary() {
                    (s - p).to_radians()
                } else {
                    s - p
                };
                d.abs() / lim.v_max
            })
            .fold(self.tau, f64::max)
    }
}

/// The program's blocks, from `from`, timed across their joins (ramped to the
/// acceleration limits when the job keeps them), and the checks the timing
/// fails.
fn time_joins(
    m: &Machine,
    motion: &MotionJob,
    from: Option<&[f64]>,
    pending_blocks: &[Pending],
    limits: &[AxisLimits],
) -> Result<(Timing, Vec<Violated>), ProgramError> {
    let d = program_deltas(m, from, pending_blocks);
    let t_star: Vec<f64> = pending_blocks.iter().map(|b| b.t_star).collect();
    let cap: Vec<f64> = pending_blocks.iter().map(|b| b.cap).collect();
    let mut joined = join_times(&d, &t_star, &cap, limits)?;
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
        joined = sequence_with_acceleration(&d, &joined, limits, &a_max)?;
        if let Some(&first) = check_sequence_acceleration(&d, &joined.times, &a_max).first() {
            program_violated.push(violated(Check::Acceleration, "acceleration limit", first));
        }
    }
    if let Some(first) = timing_from_rest(&d, &joined.times, limits) {
        program_violated.push(violated(Check::Timing, "velocity limits", first));
    }
    Ok((joined, program_violated))
}

/// Writes the blocks with their `times` into `program`; the blocks as
/// `blocks.csv` lists them.
fn push_blocks(
    program: &mut Program,
    pending_blocks: Vec<Pending>,
    times: &[f64],
) -> Vec<TimedBlock> {
    let mut timed = Vec::with_capacity(pending_blocks.len());
    for (p, t) in pending_blocks.into_iter().zip(times) {
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
    timed
}
