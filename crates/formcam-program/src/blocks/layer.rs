//! One layer's blocks: its axes checked, one circuit cut within the
//! tolerances, timed and repeated; a skip layer's turn of the spindle.

use formcam_machine::{AxisTrack, Machine, Target};
use formcam_motion::{
    AxisLimits, Deviation, Timing, Tolerance, check_acceleration, check_timing, deltas, fit_blocks,
    global, pairwise, preliminary_times, with_acceleration,
};

use super::{axis_limits, keeps_acceleration, nc, planned_a_max, positive};
use crate::ProgramError;
use crate::checks::{Check, Violated};
use crate::job::{MotionJob, Times};

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
    let mut violated = ik_violations(label, track);
    let w = m.axes.len();
    let (tol, tau) = tolerance(m, motion)?;
    let ends = fit(m, targets, track, &tol)?;
    let limits = axis_limits(m);
    let d = deltas(&track.values, w, &ends);
    let times = LayerTimes::new(label, m, motion, &d, &limits, tau, &mut violated)?;
    let chosen = times.chosen();
    if let Some(&broken) = check_timing(&d, &chosen.times, &limits).first() {
        violated.push(limit_broken(
            label,
            m,
            Check::Timing,
            "velocity limits",
            broken,
        ));
    }
    let (start, blocks) = repeat_circuit(m, track, &ends, chosen, &times.t_star, circuits);
    let k = f64::from(circuits.max(1));
    Ok(LayerBlocks {
        label: label.to_string(),
        start,
        blocks,
        times: [
            k * chosen.total,
            k * times.pairwise.total,
            k * times.global.total,
            k * times.t_star.iter().sum::<f64>(),
        ],
        carry: vec![0.0; w],
        violated,
    })
}

/// The track's IK issues as the checks they fail: a program must not drive an
/// axis beyond its limits (unless the job accepts it).
fn ik_violations(label: &str, track: &AxisTrack) -> Vec<Violated> {
    track
        .issues
        .iter()
        .filter_map(|i| {
            let check = Check::of_issue(i.kind)?;
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
        .collect()
}

/// The job's tolerances per axis (and of the payout point) and its least
/// block time `tau`, s.
fn tolerance(m: &Machine, motion: &MotionJob) -> Result<(Tolerance, f64), ProgramError> {
    let tol_mm = positive(
        "motion.tolerance_mm",
        motion
            .tolerance_mm
            .unwrap_or(formcam_motion::DEFAULT_TOLERANCE_MM),
    )?;
    let tol_deg = positive(
        "motion.tolerance_deg",
        motion
            .tolerance_deg
            .unwrap_or(formcam_motion::DEFAULT_TOLERANCE_DEG),
    )?;
    let tau = positive(
        "motion.tau_s",
        motion.tau_s.unwrap_or(formcam_motion::DEFAULT_TAU_S),
    )?;
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
    Ok((tol, tau))
}

/// The track's rows that end the blocks, cut within `tol`: the payout point's
/// deviation where the axes move linearly too when `tol` bounds it.
fn fit(
    m: &Machine,
    targets: &[Target],
    track: &AxisTrack,
    tol: &Tolerance,
) -> Result<Vec<usize>, ProgramError> {
    let x: Vec<f64> = targets.iter().map(|t| t.x).collect();
    let payout = m.roles.payout;
    let wanted: Vec<_> = if tol.position_mm.is_some() {
        track.rows().map(|q| m.key_points(q)[payout]).collect()
    } else {
        Vec::new()
    };
    let deviation = |q: &[f64], k: usize| (m.key_points(q)[payout] - wanted[k]).norm();
    Ok(fit_blocks(
        &x,
        &track.values,
        m.axes.len(),
        tol,
        tol.position_mm.map(|_| &deviation as Deviation<'_>),
    )?)
}

/// A layer's block times: the least (eq. 17), pairwise and global ones, and
/// the job's choice ramped to the acceleration limits when it keeps them.
struct LayerTimes {
    /// The least times, s.
    t_star: Vec<f64>,
    /// The pairwise times.
    pairwise: Timing,
    /// The global times.
    global: Timing,
    /// The chosen times ramped to the acceleration limits, if kept.
    ramped: Option<Timing>,
    /// The times the job chose.
    times: Times,
}

impl LayerTimes {
    /// Times the blocks of motions `d`; a broken acceleration limit goes to
    /// `violated`.
    fn new(
        label: &str,
        m: &Machine,
        motion: &MotionJob,
        d: &[f64],
        limits: &[AxisLimits],
        tau: f64,
        violated: &mut Vec<Violated>,
    ) -> Result<LayerTimes, ProgramError> {
        let limit_err = ProgramError::AxisLimits;
        let t_star = preliminary_times(d, limits, tau).map_err(limit_err)?;
        let pw = pairwise(d, &t_star, limits).map_err(limit_err)?;
        let gl = global(d, &t_star, limits).map_err(limit_err)?;
        let mut times = LayerTimes {
            t_star,
            pairwise: pw,
            global: gl,
            ramped: None,
            times: motion.times,
        };
        if keeps_acceleration(motion) {
            let a_max = planned_a_max(m);
            let ramped = with_acceleration(d, times.chosen(), limits, &a_max).map_err(limit_err)?;
            if let Some(&broken) = check_acceleration(d, &ramped.times, &a_max).first() {
                violated.push(limit_broken(
                    label,
                    m,
                    Check::Acceleration,
                    "acceleration limit",
                    broken,
                ));
            }
            times.ramped = Some(ramped);
        }
        Ok(times)
    }

    /// The times the blocks get: the job's choice, ramped if kept.
    fn chosen(&self) -> &Timing {
        match (&self.ramped, self.times) {
            (Some(ramped), _) => ramped,
            (None, Times::Global) => &self.global,
            (None, Times::Pairwise) => &self.pairwise,
        }
    }
}

/// The check failed where the `limit` of axis `k` breaks in block `b`
/// (0-based) by `e`.
fn limit_broken(
    label: &str,
    m: &Machine,
    check: Check,
    limit: &str,
    (b, k, e): (usize, usize, f64),
) -> Violated {
    Violated {
        check,
        layer: label.to_string(),
        detail: format!(
            "break the {limit} of axis {} in block {} by {e:.3e}",
            m.axes[k].name,
            b + 1
        ),
    }
}

/// A block's end (NC units) and times: `(target, t, t_star, mu)`.
type Cut = (Vec<f64>, f64, f64, f64);

/// The layer's start (NC units) and its blocks: the circuit cut at `ends`
/// and timed by `chosen` and `t_star`, repeated `circuits` times, each circuit
/// starting where the last ended, turned on by the circuit's turn.
fn repeat_circuit(
    m: &Machine,
    track: &AxisTrack,
    ends: &[usize],
    chosen: &Timing,
    t_star: &[f64],
    circuits: u32,
) -> (Vec<f64>, Vec<Cut>) {
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
    (start, blocks)
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
