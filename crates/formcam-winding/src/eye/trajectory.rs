//! The trajectory assembled: a geometric mode's circuit cut into runs (one per
//! worker of rayon's pool) and each run into chunks (sample, solve, evaluate),
//! their checks joined in order; the pull-speed optimum on the nodes with the
//! geometric trajectories on the same nodes for comparison; the cycle closed.

use formcam_geom::Meridian;
use rayon::prelude::*;
use serde::Serialize;

use super::band::Band;
use super::checks::{Checks, PullStats, Violation, closure};
use super::envelope::{Profile, clearance_envelope, least_lengths};
use super::geometric::{Geometric, curve_profile};
use super::optimise::optimise;
use super::spec::{EyeMode, EyeSpec, check_spec};
use crate::{Circuit, CircuitPoint, Layer, WindingError};

/// One point of the eye trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EyePoint {
    /// Circuit parameter (laid band length), mm.
    pub x: f64,
    /// Path point `z`, mm.
    pub z: f64,
    /// Path point radius, mm.
    pub r: f64,
    /// Path point turn angle, rad.
    pub v: f64,
    /// Angle of the path to the `+z` meridian, rad (`pi - alpha` on the return pass).
    pub alpha: f64,
    /// Free length, mm.
    pub l: f64,
    /// Radial margin of the eye over the clearance zone, `R - R_zone(Z)`, mm
    /// (`>= 0`: the eye keeps the clearance).
    pub margin: f64,
    /// Eye `Z`, mm.
    pub eye_z: f64,
    /// Eye `R`, mm.
    pub eye_r: f64,
    /// Eye `V`, rad.
    pub eye_v: f64,
    /// Band length pulled through the bath, `l + s - k R`, mm.
    pub lambda: f64,
    /// Relative pull speed `d lambda / dx` on the interval that starts here.
    pub u: f64,
}

/// The pull speed of a geometric trajectory on the same nodes, for comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// The mode compared with.
    pub mode: EyeMode,
    /// Its statistics.
    pub stats: PullStats,
    /// Whether it keeps every constraint.
    pub constraints_ok: bool,
    /// How much higher the optimum's `u_min` is.
    pub gain_u_min: f64,
    /// How much lower the optimum's `u_max` is.
    pub gain_u_max: f64,
    /// How much lower the optimum's RMS of `u - U` is.
    pub gain_u_rms_dev: f64,
}

/// An eye trajectory over one circuit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EyeTrajectory {
    /// The mode.
    pub mode: EyeMode,
    /// The points, first and last at the circuit's start and end.
    #[serde(skip)]
    pub points: Vec<EyePoint>,
    /// Pull-speed statistics.
    pub stats: PullStats,
    /// Broken constraints.
    pub violations: Vec<Violation>,
    /// Whether every constraint holds.
    pub constraints_ok: bool,
    /// Mandrel turn over the circuit, rad.
    pub circuit_turn_rad: f64,
    /// Distance between the first eye point turned by the circuit's turn and the last, mm.
    pub closure_mm: f64,
    /// The geometric trajectories on the same nodes (pull-speed mode only).
    pub comparison: Vec<Comparison>,
    /// Least free length that keeps the clearance at each point (equidistant and
    /// pull-speed modes; empty otherwise).
    #[serde(skip)]
    pub l_min: Vec<f64>,
}

/// Points per run below which a geometric trajectory is built as one run.
const POINTS_PER_THREAD: usize = 20_000;

/// Eye points with the checks of their run.
type Run = (Vec<EyePoint>, Checks);

/// A geometric trajectory over the `n + 1` circuit samples. Long circuits are cut
/// into contiguous runs, one per worker of rayon's pool, each writing its own
/// part of one buffer of points; each run is built in chunks (sample, solve,
/// evaluate: each a loop of independent points), then checked, and the runs'
/// checks are joined in order.
fn geometric_points<M: Meridian>(
    circuit: &Circuit<'_, M>,
    n: usize,
    length: &Geometric<'_>,
    env: &Profile,
    spec: &EyeSpec,
    k: f64,
) -> Result<Run, WindingError> {
    let total = n + 1;
    let threads = rayon::current_num_threads()
        .min(total / POINTS_PER_THREAD)
        .clamp(1, 16);
    let per = total.div_ceil(threads);
    let mut points = vec![BLANK; total];
    let run = |(t, part): (usize, &mut [EyePoint])| {
        let from = t * per;
        geometric_run(
            circuit,
            n,
            from..from + part.len(),
            part,
            length,
            env,
            spec,
            k,
        )
    };
    let checks: Vec<Result<Checks, WindingError>> = if threads == 1 {
        vec![run((0, &mut points))]
    } else {
        points.par_chunks_mut(per).enumerate().map(run).collect()
    };
    let checks = join_runs(&mut points, per, checks)?;
    Ok((points, checks))
}

/// A point before it is computed.
const BLANK: EyePoint = EyePoint {
    x: 0.0,
    z: 0.0,
    r: 0.0,
    v: 0.0,
    alpha: 0.0,
    l: 0.0,
    margin: 0.0,
    eye_z: 0.0,
    eye_r: 0.0,
    eye_v: 0.0,
    lambda: 0.0,
    u: 0.0,
};

/// One run of a geometric trajectory: the circuit samples `range` of `n`
/// written to `out` (as long as the range), in chunks (sample, solve,
/// evaluate), checked as they come.
#[allow(clippy::too_many_arguments)]
fn geometric_run<M: Meridian>(
    circuit: &Circuit<'_, M>,
    n: usize,
    range: std::ops::Range<usize>,
    out: &mut [EyePoint],
    length: &Geometric<'_>,
    env: &Profile,
    spec: &EyeSpec,
    k: f64,
) -> Result<Checks, WindingError> {
    const CHUNK: usize = 1024;
    let mut checks = Checks::new();
    let mut length = length.clone();
    let mut samples = circuit.samples(n, range);
    let mut bands = Vec::with_capacity(CHUNK);
    let mut ls = Vec::with_capacity(CHUNK);
    let mut from = 0;
    loop {
        bands.clear();
        bands.extend(samples.by_ref().take(CHUNK).map(|p| Band::new(&p)));
        if bands.is_empty() {
            break;
        }
        ls.clear();
        for b in &bands {
            ls.push(length.at(b)?);
        }
        let to = from + bands.len();
        for ((e, b), &l) in out[from..to].iter_mut().zip(&bands).zip(&ls) {
            *e = eye_point(b, l, env, k);
        }
        checks.scan(&mut out[..to], from, spec);
        from = to;
    }
    Ok(checks)
}

/// The runs' checks joined in order (run `i` holds `points[i * per..]`): the
/// interval across each seam checked, the checks summed; the first run's
/// error, if any.
fn join_runs(
    points: &mut [EyePoint],
    per: usize,
    runs: Vec<Result<Checks, WindingError>>,
) -> Result<Checks, WindingError> {
    let mut runs = runs.into_iter();
    let mut checks = match runs.next() {
        Some(r) => r?,
        None => Checks::new(),
    };
    for (i, r) in runs.enumerate() {
        let c = r?;
        let seam = (i + 1) * per;
        if seam > 0 && seam < points.len() {
            let first = points[seam];
            checks.interval(&mut points[seam - 1], &first);
        }
        checks.join(c);
    }
    Ok(checks)
}

/// Builds the eye trajectory of `layer` (planned on `m`) as `spec` asks.
pub fn eye_trajectory<M: Meridian>(
    m: &M,
    layer: &Layer,
    spec: &EyeSpec,
) -> Result<EyeTrajectory, WindingError> {
    check_spec(m, spec)?;
    let circuit = Circuit::new(m, layer);
    let k = if spec.bath_moves_with_eye { 0.0 } else { 1.0 };
    let env = clearance_envelope(m, spec.clearance, spec.l_max);
    let ((mut points, checks), comparison, l_min) = if spec.mode == EyeMode::PullSpeed {
        pull_speed(&circuit, &env, spec, k)?
    } else {
        let curve = match spec.mode {
            EyeMode::Curve => Some(curve_profile(&spec.curve)?),
            _ => None,
        };
        let length = Geometric::new(spec.mode, spec, &env, curve.as_ref())?;
        let run = geometric_points(&circuit, spec.samples - 1, &length, &env, spec, k)?;
        (run, Vec::new(), Vec::new())
    };
    let turn = circuit.turn_angle();
    let closure_mm = closure(&points, turn);
    let (stats, violations) = checks.close(&mut points, closure_mm);
    Ok(EyeTrajectory {
        mode: spec.mode,
        constraints_ok: violations.is_empty(),
        points,
        stats,
        violations,
        circuit_turn_rad: turn,
        closure_mm,
        comparison: with_gains(comparison, &stats),
        l_min,
    })
}

/// The pull-speed optimum on the circuit's nodes: its points and checks, the
/// geometric trajectories on the same nodes, the least free lengths.
fn pull_speed<M: Meridian>(
    circuit: &Circuit<'_, M>,
    env: &Profile,
    spec: &EyeSpec,
    k: f64,
) -> Result<(Run, Vec<Comparison>, Vec<f64>), WindingError> {
    let pts: Vec<CircuitPoint> = circuit.points(spec.nodes);
    let l_min = least_lengths(env, &pts, spec, false)?;
    let l = optimise(&pts, &l_min, spec, k)?;
    let comparison = comparisons(&pts, env, spec, k)?;
    Ok((eye_points(&pts, &l, env, spec, k), comparison, l_min))
}

/// The geometric trajectories (axis-parallel where a radius is given and its
/// line reaches every band, equidistant) on the nodes `pts`, gains still unset.
fn comparisons(
    pts: &[CircuitPoint],
    env: &Profile,
    spec: &EyeSpec,
    k: f64,
) -> Result<Vec<Comparison>, WindingError> {
    let mut comparison = Vec::new();
    for mode in [EyeMode::AxisParallel, EyeMode::Equidistant] {
        if mode == EyeMode::AxisParallel && spec.radius.is_none() {
            continue;
        }
        let mut g = Geometric::new(mode, spec, env, None)?;
        let lg = match (
            mode,
            pts.iter()
                .map(|p| g.at(&Band::new(p)))
                .collect::<Result<Vec<f64>, _>>(),
        ) {
            (_, Ok(lg)) => lg,
            // The eye's line may not reach every band: no comparison then.
            (EyeMode::AxisParallel, Err(_)) => continue,
            (_, Err(e)) => return Err(e),
        };
        let (_, c) = eye_points(pts, &lg, env, spec, k);
        comparison.push(Comparison {
            mode,
            stats: c.stats(),
            constraints_ok: c.broken.iter().all(Option::is_none),
            gain_u_min: 0.0,
            gain_u_max: 0.0,
            gain_u_rms_dev: 0.0,
        });
    }
    Ok(comparison)
}

/// The comparisons with the optimum's gains over each (`stats`: the optimum's).
fn with_gains(comparison: Vec<Comparison>, stats: &PullStats) -> Vec<Comparison> {
    comparison
        .into_iter()
        .map(|mut c| {
            c.gain_u_min = stats.u_min - c.stats.u_min;
            c.gain_u_max = c.stats.u_max - stats.u_max;
            c.gain_u_rms_dev = c.stats.u_rms_dev - stats.u_rms_dev;
            c
        })
        .collect()
}

impl EyePoint {
    /// The point of the path itself (free length 0, nothing computed yet).
    fn at(p: &CircuitPoint) -> Self {
        Self {
            x: p.x,
            z: p.z,
            r: p.r,
            v: p.v,
            alpha: p.alpha,
            l: 0.0,
            margin: 0.0,
            eye_z: p.z,
            eye_r: p.r,
            eye_v: p.v,
            lambda: p.x,
            u: 0.0,
        }
    }
}

/// The eye point of free length `l` on the band `b` (its `u` still unknown).
fn eye_point(b: &Band, l: f64, env: &Profile, k: f64) -> EyePoint {
    let (ez, er) = b.eye_zr(l);
    EyePoint {
        l,
        margin: er - env.at(ez).0,
        eye_z: ez,
        eye_r: er,
        eye_v: b.v(l),
        lambda: l + b.p.x - k * er,
        ..EyePoint::at(&b.p)
    }
}

/// Eye points of free lengths `l` at `pts`, with their checks.
fn eye_points(
    pts: &[CircuitPoint],
    l: &[f64],
    env: &Profile,
    spec: &EyeSpec,
    k: f64,
) -> (Vec<EyePoint>, Checks) {
    let mut e: Vec<EyePoint> = pts
        .iter()
        .zip(l)
        .map(|(p, &l)| eye_point(&Band::new(p), l, env, k))
        .collect();
    let c = Checks::of_run(&mut e, spec);
    (e, c)
}
