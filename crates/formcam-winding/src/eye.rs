//! The payout-eye trajectory (eqs. 7–11, docs/winding.md) and the pull-speed
//! optimisation (eqs. 12–15).
//!
//! For a path point with tangent `tau` (eq. 8–9) the eye lies at `P + l tau`;
//! its cylindrical coordinates are eq. 10. A trajectory is a free length `l(x)`
//! over the circuit's parameter `x` (the laid band length, see [`Circuit`]).
//!
//! * `axis-parallel`: `R(l) = R_eye`, solved in closed form;
//! * `equidistant`: the eye keeps `clearance` from the mandrel — on the upper
//!   envelope of the discs of that radius centred on the meridian (and on the
//!   shaft through the polar openings), which near a small opening is a circle
//!   round the opening's edge, not an offset dome;
//! * `curve`: a user polyline `R = f(Z)`;
//! * `pull-speed`: `l(x)` discretised and chosen lexicographically: max min `u`,
//!   then min max `u`, then min `∫ (u - U)^2 dx` (LP, LP, QP by Clarabel), with
//!   `lambda = l + s - k R`, `u = d lambda / dx`.
//!
//! The constraints (docs/winding.md) are checked for every mode: cyclicity, the
//! clearance (`l >= l_min(x)`, the equidistant length) and `l <= l_max`, no slack
//! (`d(l + s)/dx >= 0`) and no reverse rotation of the mandrel (`dV/dx >= 0`).

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
    SupportedConeT, ZeroConeT,
};
use formcam_geom::Meridian;
use serde::Serialize;

use crate::{Circuit, CircuitPoint, WindingError};

/// How the eye trajectory is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum EyeMode {
    /// On a line parallel to the axis at `radius`.
    AxisParallel,
    /// At `clearance` from the mandrel.
    Equidistant,
    /// On a user curve `R = f(Z)`.
    Curve,
    /// The pull-speed optimum.
    PullSpeed,
}

/// What the user asks of the eye.
#[derive(Debug, Clone, PartialEq)]
pub struct EyeSpec {
    /// The mode.
    pub mode: EyeMode,
    /// Axis-parallel: radius of the eye's line, mm.
    pub radius: Option<f64>,
    /// Least clearance between the eye and the mandrel in every mode, mm
    /// (and the clearance of `equidistant`).
    pub clearance: f64,
    /// Largest free length, mm.
    pub l_max: f64,
    /// `k = 0` (the bath moves with the eye) or `k = 1` (fixed bath).
    pub bath_moves_with_eye: bool,
    /// Curve mode: `(Z, R)` points with `Z` increasing.
    pub curve: Vec<(f64, f64)>,
    /// Points of the trajectory for the geometric modes.
    pub samples: usize,
    /// Intervals of the discretised `l(x)` of the optimisation.
    pub nodes: usize,
}

impl Default for EyeSpec {
    fn default() -> Self {
        Self {
            mode: EyeMode::PullSpeed,
            radius: None,
            clearance: 20.0,
            l_max: 400.0,
            bath_moves_with_eye: true,
            curve: Vec::new(),
            samples: 2001,
            nodes: 2000,
        }
    }
}

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

/// A broken constraint, summarised.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Violation {
    /// Which: `cyclicity`, `clearance`, `l_max`, `slack`, `reverse-rotation`.
    pub constraint: &'static str,
    /// The first `x` where it fails, mm.
    pub x: f64,
    /// How many points or intervals fail.
    pub count: usize,
    /// The worst excess (mm, or rad for the rotation), positive.
    pub worst: f64,
}

/// Statistics of the pull speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PullStats {
    /// Least `u`.
    pub u_min: f64,
    /// Largest `u`.
    pub u_max: f64,
    /// Mean `U` (weighted by `dx`).
    pub u_mean: f64,
    /// RMS of `u - U`.
    pub u_rms_dev: f64,
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

/// The free band leaving a circuit point: its unit direction split into the
/// axial (`ca`), radial (`ra`) and circumferential (`sa`) parts of the point's
/// frame (eqs. 8–9), computed once per point.
#[derive(Debug, Clone, Copy)]
struct Band {
    p: CircuitPoint,
    ca: f64,
    ra: f64,
    sa: f64,
}

impl Band {
    fn new(p: &CircuitPoint) -> Self {
        let q = (1.0 + p.dr * p.dr).sqrt();
        let (sa, cos) = p.alpha.sin_cos();
        let ca = cos / q;
        Self {
            p: *p,
            ca,
            ra: p.dr * ca,
            sa,
        }
    }

    /// The eye's radial (`d`) and circumferential (`w`) offsets from the axis
    /// in the path point's frame at free length `l`.
    fn dw(&self, l: f64) -> (f64, f64) {
        (self.p.r + l * self.ra, l * self.sa)
    }

    /// Eye `Z` and `R` at free length `l`.
    fn eye_zr(&self, l: f64) -> (f64, f64) {
        let (d, w) = self.dw(l);
        (self.p.z + l * self.ca, (d * d + w * w).sqrt())
    }

    /// Eye `Z`, `R` and `dR/dl` at free length `l`.
    fn zr(&self, l: f64) -> (f64, f64, f64) {
        let (d, w) = self.dw(l);
        let rr = (d * d + w * w).sqrt();
        let dr_dl = if rr > 0.0 {
            (d * self.ra + w * self.sa) / rr
        } else {
            0.0
        };
        (self.p.z + l * self.ca, rr, dr_dl)
    }

    /// Eye `V` at free length `l`.
    fn v(&self, l: f64) -> f64 {
        let (d, w) = self.dw(l);
        // w >= 0; the plain arctangent is cheaper where the quadrant is known.
        self.p.v + if d > 0.0 { (w / d).atan() } else { w.atan2(d) }
    }

    /// Free length that puts the eye at radius `radius`, if any.
    fn length_to_radius(&self, radius: f64) -> Option<f64> {
        let aa = self.ra * self.ra + self.sa * self.sa;
        let b = self.p.r * self.ra;
        let c = self.p.r * self.p.r - radius * radius;
        let disc = b * b - aa * c;
        if aa <= 1e-300 || disc < 0.0 {
            return None;
        }
        let l = (-b + disc.sqrt()) / aa;
        (l >= 0.0).then_some(l)
    }

    /// The first free length at which the eye reaches the curve `R = f(Z)` (from
    /// inside), searched near `guess` (the root of the previous point). `None`
    /// when it is not reached before `l_hi`.
    /// `start`: where Newton starts (the guess, or a prediction from the roots
    /// of the previous points).
    fn length_to_profile(&self, f: &Profile, guess: f64, start: f64, l_hi: f64) -> Option<f64> {
        // g(l) = R(l) - f(Z(l)) and its slope.
        let g = |l: f64| {
            let (z, r, dr) = self.zr(l);
            let (fz, slope) = f.at(z);
            (r - fz, dr - slope * self.ca)
        };
        // Neighbouring points have nearly the same root: Newton from the guess,
        // kept when it settles close by on a crossing outwards with the band still
        // inside the zone a little before it (as the bracketing below demands).
        let near = (0.02 * guess).max(0.05);
        if guess > near {
            let mut l = start;
            for _ in 0..6 {
                let (gv, dg) = g(l);
                if dg.is_nan() || dg <= 0.0 {
                    break;
                }
                let step = gv / dg;
                l -= step;
                if l.is_nan() || (l - guess).abs() >= near {
                    break;
                }
                if step.abs() <= 1e-8 * (1.0 + l) {
                    let (z, r) = self.eye_zr(l - near);
                    if r < f.at(z).0 {
                        return Some(l);
                    }
                    break;
                }
            }
        }
        // Bracket the first sign change. Neighbouring points have nearly the same
        // root: start just below the guess with a small step when the curve is
        // still ahead there; otherwise march from 0 with a coarse step.
        let mut below = None;
        let mut step = (0.25 * guess).max(1.0);
        if guess > 0.0 {
            let gl = guess - near;
            if gl > 0.0 {
                let fg = g(gl).0;
                if fg < 0.0 {
                    below = Some(gl);
                    step = near;
                }
            }
        }
        let mut a = match below {
            Some(a) => a,
            None if g(0.0).0 >= 0.0 => return Some(0.0),
            None => 0.0,
        };
        let (mut l, (mut gv, mut dg)) = loop {
            if a >= l_hi {
                return None;
            }
            let b = (a + step).min(l_hi);
            let gb = g(b);
            if gb.0 >= 0.0 {
                break (b, gb);
            }
            a = b;
        };
        // Safeguarded Newton in [a, b]: f is linear between the profile's nodes, so
        // Newton lands on the root of the local piece; bisection when a step
        // leaves the bracket.
        let mut b = l;
        for _ in 0..100 {
            if gv == 0.0 {
                return Some(l);
            }
            if gv < 0.0 {
                a = l;
            } else {
                b = l;
            }
            let newton = l - gv / dg;
            let next = if dg.is_finite() && dg != 0.0 && newton > a && newton < b {
                newton
            } else {
                0.5 * (a + b)
            };
            if (next - l).abs() <= 1e-13 * (1.0 + l) || b - a <= 1e-13 * (1.0 + b) {
                return Some(next);
            }
            l = next;
            (gv, dg) = g(l);
        }
        Some(b)
    }
}

/// Eye position for free length `l`: `(Z, R, V, dZ/dl, dR/dl)` (eq. 10).
pub fn eye_at(p: &CircuitPoint, l: f64) -> (f64, f64, f64, f64, f64) {
    let b = Band::new(p);
    let (z, r, dr_dl) = b.zr(l);
    (z, r, b.v(l), b.ca, dr_dl)
}

/// Free length that puts the eye at radius `radius` (axis-parallel), if any.
pub fn axis_parallel_length(p: &CircuitPoint, radius: f64) -> Option<f64> {
    Band::new(p).length_to_radius(radius)
}

/// A curve `R = f(Z)` sampled on a uniform grid, linear between nodes, constant beyond.
#[derive(Debug, Clone)]
struct Profile {
    z0: f64,
    inv_dz: f64,
    vals: Vec<f64>,
}

impl Profile {
    /// `f(z)` and its slope.
    fn at(&self, z: f64) -> (f64, f64) {
        let n = self.vals.len();
        let t = (z - self.z0) * self.inv_dz;
        if t.is_nan() || t <= 0.0 {
            return (self.vals[0], 0.0);
        }
        let i = t as usize;
        if i + 1 >= n {
            return (self.vals[n - 1], 0.0);
        }
        let f = t - i as f64;
        let (a, b) = (self.vals[i], self.vals[i + 1]);
        (a + f * (b - a), (b - a) * self.inv_dz)
    }

    fn top(&self) -> f64 {
        self.vals.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }
}

/// The clearance zone's outer boundary: the upper envelope of discs of radius
/// `c` centred on the meridian and on the shaft beyond its ends (radius of the end).
///
/// The envelope of the discs along a smooth stretch is traced by their offset
/// points `P + c n` (the upper normal `n`), folds included (where the meridian is
/// concave tighter than `c` the offset curve crosses itself and the maximum keeps
/// the outer branches); whole discs are laid at the ends and at breakpoints. The
/// offset curve is sampled every `c/50` of its own length, so its chords sag by
/// at most `c/20000`.
fn clearance_envelope<M: Meridian>(m: &M, c: f64, reach: f64) -> Profile {
    let (za, zb) = m.z_range();
    let (ra, rb) = (m.r(za), m.r(zb));
    let lo = za - reach - c;
    let hi = zb + reach + c;
    // Cells of c/400: where a disc meets the shaft's plateau the envelope has a
    // corner, and linear interpolation across it errs by about slope * cell / 2.
    let cells = (((hi - lo) / (c / 400.0)).ceil() as usize).clamp(2048, 1 << 18);
    let dz = (hi - lo) / cells as f64;
    let cell_z = |i: usize| lo + dz * i as f64;
    let mut vals: Vec<f64> = (0..=cells)
        .map(|i| {
            let z = cell_z(i);
            if z <= za {
                ra + c
            } else if z >= zb {
                rb + c
            } else {
                f64::NEG_INFINITY
            }
        })
        .collect();
    // Cells with z in [z0, z1].
    let span = |z0: f64, z1: f64| {
        let i0 = ((z0 - lo) / dz).ceil().max(0.0) as usize;
        let i1 = (((z1 - lo) / dz).floor().max(0.0) as usize).min(cells);
        i0..i1 + 1
    };
    let disc = |vals: &mut [f64], zc: f64, rc: f64| {
        for i in span(zc - c, zc + c) {
            let d = cell_z(i) - zc;
            vals[i] = vals[i].max(rc + (c * c - d * d).max(0.0).sqrt());
        }
    };
    disc(&mut vals, za, ra);
    disc(&mut vals, zb, rb);
    for z in m.breakpoints() {
        if z > za && z < zb {
            disc(&mut vals, z, m.r(z));
        }
    }
    // The offset curve, stretch by stretch between breakpoints.
    let h = c / 50.0;
    let min_step = (zb - za) / f64::from(1u32 << 20);
    let mut stops: Vec<f64> = m
        .breakpoints()
        .into_iter()
        .filter(|&z| z > za && z < zb)
        .collect();
    stops.push(zb);
    let offset = |z: f64| {
        let j = m.eval(z);
        let q = (1.0 + j.dr * j.dr).sqrt();
        let kappa = j.d2r.abs() / (q * q * q);
        ((z - c * j.dr / q, j.r + c / q), q, kappa)
    };
    let mut z = za;
    for stop in stops {
        let (mut p, mut q, mut kappa) = offset(z);
        while z < stop {
            // The offset curve is (1 + c kappa) times longer than the meridian.
            let step = (h / (q * (1.0 + c * kappa))).max(min_step);
            z = (z + step).min(stop);
            let (pn, qn, kn) = offset(z);
            let ((z0, r0), (z1, r1)) = if pn.0 >= p.0 { (p, pn) } else { (pn, p) };
            for i in span(z0, z1) {
                let t = if z1 > z0 {
                    (cell_z(i) - z0) / (z1 - z0)
                } else {
                    0.0
                };
                vals[i] = vals[i].max(r0 + t * (r1 - r0));
            }
            (p, q, kappa) = (pn, qn, kn);
        }
    }
    Profile {
        z0: lo,
        inv_dz: 1.0 / dz,
        vals,
    }
}

/// The user curve as a profile (fine resampling of the polyline).
fn curve_profile(curve: &[(f64, f64)]) -> Result<Profile, WindingError> {
    if curve.len() < 2 {
        return Err(WindingError::field(
            "eye.curve",
            "needs at least 2 points (columns Z,R)",
        ));
    }
    for (i, w) in curve.windows(2).enumerate() {
        if w[1].0.is_nan() || w[1].0 <= w[0].0 {
            return Err(WindingError::field(
                "eye.curve",
                format!(
                    "row {}: Z must increase (got {} after {})",
                    i + 2,
                    w[1].0,
                    w[0].0
                ),
            ));
        }
    }
    if curve
        .iter()
        .any(|p| !p.0.is_finite() || !p.1.is_finite() || p.1 <= 0.0)
    {
        return Err(WindingError::field(
            "eye.curve",
            "every point needs finite Z and R > 0",
        ));
    }
    let (z0, z1) = (curve[0].0, curve[curve.len() - 1].0);
    let cells = 8192usize;
    let dz = (z1 - z0) / cells as f64;
    let mut j = 0;
    let vals = (0..=cells)
        .map(|i| {
            let z = z0 + dz * i as f64;
            while j + 2 < curve.len() && curve[j + 1].0 < z {
                j += 1;
            }
            let (a, b) = (curve[j], curve[j + 1]);
            let t = ((z - a.0) / (b.0 - a.0)).clamp(0.0, 1.0);
            a.1 + t * (b.1 - a.1)
        })
        .collect();
    Ok(Profile {
        z0,
        inv_dz: 1.0 / dz,
        vals,
    })
}

/// Where the free band first leaves the clearance zone, point after point (each
/// search starts from the previous point's root).
#[derive(Clone)]
struct FirstExit<'a> {
    env: &'a Profile,
    clearance: f64,
    l_hi: f64,
    /// The roots at the two previous points.
    last: (f64, f64),
}

impl<'a> FirstExit<'a> {
    fn new(env: &'a Profile, spec: &EyeSpec) -> Self {
        Self {
            env,
            clearance: spec.clearance,
            l_hi: 4.0 * spec.l_max + 20.0 * env.top(),
            last: (0.0, 0.0),
        }
    }

    fn at(&mut self, b: &Band) -> Result<f64, WindingError> {
        // Points are evenly spaced: the next root is about the linear extrapolation.
        let (l1, l2) = self.last;
        let start = if l1 > 0.0 && l2 > 0.0 {
            2.0 * l1 - l2
        } else {
            l1
        };
        let l = b.length_to_profile(self.env, l1, start, self.l_hi).ok_or_else(|| {
            WindingError::infeasible(
                "eye.clearance",
                format!(
                    "no eye position on the free band keeps {} mm from the mandrel at x = {:.3} mm \
                     (z = {:.3} mm)",
                    self.clearance, b.p.x, b.p.z
                ),
            )
        })?;
        self.last = (l, l1);
        Ok(l)
    }
}

/// Least free lengths that keep the clearance at the given circuit points.
///
/// `first`: the first exit of the eye from the clearance zone along the free band
/// (the equidistant trajectory). Otherwise the last exit: the free band can dip
/// back into the zone beyond a dome's end (towards the shaft), so the free lengths
/// that keep the clearance from there on form one interval — what a convex
/// optimisation needs.
fn least_lengths(
    env: &Profile,
    pts: &[CircuitPoint],
    spec: &EyeSpec,
    first: bool,
) -> Result<Vec<f64>, WindingError> {
    let mut exit = FirstExit::new(env, spec);
    let top = env.top();
    pts.iter()
        .map(|p| {
            let b = Band::new(p);
            let l = exit.at(&b)?;
            if first {
                return Ok(l);
            }
            last_exit(&b, env, l, exit.l_hi, top, spec.clearance).ok_or_else(|| {
                WindingError::infeasible(
                    "eye.clearance",
                    format!(
                        "the free band at x = {:.3} mm (z = {:.3} mm) stays within {} mm of the \
                         mandrel",
                        p.x, p.z, spec.clearance
                    ),
                )
            })
        })
        .collect()
}

/// From a first exit `l0`, the last exit of the eye from the clearance zone: march
/// along the free band until the eye is above the zone's highest point and rising.
fn last_exit(b: &Band, env: &Profile, l0: f64, l_hi: f64, top: f64, clearance: f64) -> Option<f64> {
    // A dip into the zone is at least as long as the clearance is wide near its
    // deepest point; an eighth of it is a safe stride.
    let step = clearance / 8.0;
    let margin = |l: f64| {
        let (z, r, dr) = b.zr(l);
        (r - env.at(z).0, r, dr)
    };
    let mut last = l0;
    let mut l = l0;
    let mut inside = false;
    while l < l_hi {
        let (g, r, dr) = margin(l);
        if g >= -1e-9 {
            if inside {
                // Refine the exit between l - step and l.
                let (mut a, mut c) = (l - step, l);
                for _ in 0..60 {
                    let mid = 0.5 * (a + c);
                    if margin(mid).0 >= 0.0 {
                        c = mid
                    } else {
                        a = mid
                    }
                }
                last = c;
                inside = false;
            }
            if r >= top && dr >= 0.0 {
                break;
            }
        } else {
            inside = true;
        }
        l += step;
    }
    (!inside).then_some(last)
}

fn check_spec<M: Meridian>(m: &M, spec: &EyeSpec) -> Result<(), WindingError> {
    let pos = |field: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(WindingError::field(
                field,
                format!("must be a finite number > 0, got {v}"),
            ))
        }
    };
    pos("eye.clearance", spec.clearance)?;
    pos("eye.l_max", spec.l_max)?;
    if !(101..=10_000_000).contains(&spec.samples) {
        return Err(WindingError::field(
            "eye.samples",
            "must be in [101, 10000000]",
        ));
    }
    if !(100..=200_000).contains(&spec.nodes) {
        return Err(WindingError::field("eye.nodes", "must be in [100, 200000]"));
    }
    if spec.mode == EyeMode::AxisParallel {
        let radius = spec.radius.ok_or_else(|| {
            WindingError::field("eye.radius", "missing: the radius of the eye's line, mm")
        })?;
        pos("eye.radius", radius)?;
        let (za, zb) = m.z_range();
        let r_max = (0..=2000)
            .map(|i| m.r(za + (zb - za) * f64::from(i) / 2000.0))
            .fold(0.0, f64::max);
        if radius <= r_max {
            return Err(WindingError::field(
                "eye.radius",
                format!("{radius} mm is inside the mandrel (its largest radius is {r_max:.3} mm)"),
            ));
        }
    }
    Ok(())
}

/// The free length of a geometric mode, point after point along the circuit.
#[derive(Clone)]
enum Geometric<'a> {
    AxisParallel(f64),
    Equidistant(FirstExit<'a>, f64),
    Curve {
        prof: &'a Profile,
        span: (f64, f64),
        guess: f64,
        l_hi: f64,
    },
}

impl<'a> Geometric<'a> {
    /// `curve`: the user curve's profile (curve mode).
    fn new(
        mode: EyeMode,
        spec: &EyeSpec,
        env: &'a Profile,
        curve: Option<&'a Profile>,
    ) -> Result<Self, WindingError> {
        Ok(match (mode, curve) {
            (EyeMode::AxisParallel, _) => Geometric::AxisParallel(spec.radius.unwrap_or(0.0)),
            (EyeMode::Equidistant, _) => {
                Geometric::Equidistant(FirstExit::new(env, spec), spec.l_max)
            }
            (EyeMode::Curve, Some(prof)) => Geometric::Curve {
                prof,
                span: (
                    spec.curve.first().map_or(0.0, |p| p.0),
                    spec.curve.last().map_or(0.0, |p| p.0),
                ),
                guess: 0.0,
                l_hi: 4.0 * spec.l_max + 20.0 * prof.top().max(0.0),
            },
            (EyeMode::Curve, None) => {
                return Err(WindingError::field(
                    "eye.curve",
                    "missing: a file of Z,R points",
                ));
            }
            (EyeMode::PullSpeed, _) => {
                return Err(WindingError::field(
                    "eye.mode",
                    "pull-speed is not a geometric mode",
                ));
            }
        })
    }

    fn at(&mut self, b: &Band) -> Result<f64, WindingError> {
        let p = &b.p;
        match self {
            Geometric::AxisParallel(radius) => b.length_to_radius(*radius).ok_or_else(|| {
                WindingError::infeasible(
                    "eye.radius",
                    format!(
                        "the free band at x = {:.3} mm never reaches R = {radius} mm",
                        p.x
                    ),
                )
            }),
            Geometric::Equidistant(exit, l_max) => {
                let l = exit.at(b)?;
                if l > *l_max {
                    return Err(WindingError::infeasible(
                        "eye.clearance",
                        format!(
                            "keeping {} mm from the mandrel needs a free length of {l:.3} mm at x = \
                             {:.3} mm (z = {:.3} mm), more than l_max = {l_max} mm",
                            exit.clearance, p.x, p.z
                        ),
                    ));
                }
                Ok(l)
            }
            Geometric::Curve {
                prof,
                span: (c0, c1),
                guess,
                l_hi,
            } => {
                if prof.at(p.z).0 <= p.r && p.z >= *c0 && p.z <= *c1 {
                    return Err(WindingError::field(
                        "eye.curve",
                        format!("lies inside the mandrel at Z = {:.3} mm", p.z),
                    ));
                }
                let l = b
                    .length_to_profile(prof, *guess, *guess, *l_hi)
                    .ok_or_else(|| {
                        WindingError::field(
                            "eye.curve",
                            format!("the free band at x = {:.3} mm never meets the curve", p.x),
                        )
                    })?;
                let ez = b.zr(l).0;
                if ez < *c0 - 1e-9 || ez > *c1 + 1e-9 {
                    return Err(WindingError::field(
                        "eye.curve",
                        format!(
                            "does not cover the winding zone: the eye needs Z = {ez:.3} mm, the \
                             curve spans [{c0:.3}, {c1:.3}] mm"
                        ),
                    ));
                }
                *guess = l;
                Ok(l)
            }
        }
    }
}

/// Points per thread below which a geometric trajectory is built on one thread.
const POINTS_PER_THREAD: usize = 20_000;

/// A geometric trajectory over the `n + 1` circuit samples. Long circuits are cut
/// into contiguous runs, one per thread; each run is built in chunks (sample,
/// solve, evaluate: each a loop of independent points), then checked, and the
/// runs' checks are joined in order.
fn geometric_points<M: Meridian>(
    circuit: &Circuit<'_, M>,
    n: usize,
    length: &Geometric<'_>,
    env: &Profile,
    spec: &EyeSpec,
    k: f64,
) -> Result<(Vec<EyePoint>, Checks), WindingError> {
    let total = n + 1;
    let threads = std::thread::available_parallelism()
        .map_or(1, usize::from)
        .min(total / POINTS_PER_THREAD)
        .clamp(1, 16);
    let run = |range: std::ops::Range<usize>| -> Result<(Vec<EyePoint>, Checks), WindingError> {
        const CHUNK: usize = 1024;
        let mut out = Vec::with_capacity(range.len());
        let mut checks = Checks::new();
        let mut length = length.clone();
        let mut samples = circuit.samples(n, range);
        let mut bands = Vec::with_capacity(CHUNK);
        let mut ls = Vec::with_capacity(CHUNK);
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
            let from = out.len();
            out.extend(bands.iter().zip(&ls).map(|(b, &l)| eye_point(b, l, env, k)));
            checks.scan(&mut out, from, spec);
        }
        Ok((out, checks))
    };
    let per = total.div_ceil(threads);
    let runs: Vec<Result<(Vec<EyePoint>, Checks), WindingError>> = if threads == 1 {
        vec![run(0..total)]
    } else {
        std::thread::scope(|s| {
            let handles: Vec<_> = (0..threads)
                .map(|t| {
                    let run = &run;
                    s.spawn(move || run(t * per..((t + 1) * per).min(total)))
                })
                .collect();
            handles
                .into_iter()
                .map(|h| {
                    h.join().unwrap_or_else(|_| {
                        Err(WindingError::infeasible("eye", "a worker thread failed"))
                    })
                })
                .collect()
        })
    };
    let mut runs = runs.into_iter();
    let (mut points, mut checks) = match runs.next() {
        Some(r) => r?,
        None => (Vec::new(), Checks::new()),
    };
    for r in runs {
        let (next, c) = r?;
        if let (Some(last), Some(first)) = (points.last_mut(), next.first()) {
            checks.interval(last, first);
        }
        checks.join(c);
        points.extend(next);
    }
    Ok((points, checks))
}

/// Builds the eye trajectory of `layer` (planned on `m`) as `spec` asks.
pub fn eye_trajectory<M: Meridian>(
    m: &M,
    layer: &crate::Layer,
    spec: &EyeSpec,
) -> Result<EyeTrajectory, WindingError> {
    check_spec(m, spec)?;
    let circuit = Circuit::new(m, layer);
    let k = if spec.bath_moves_with_eye { 0.0 } else { 1.0 };
    let env = clearance_envelope(m, spec.clearance, spec.l_max);
    let curve = match spec.mode {
        EyeMode::Curve => Some(curve_profile(&spec.curve)?),
        _ => None,
    };
    let (mut points, checks, comparison, l_min) = if spec.mode == EyeMode::PullSpeed {
        let pts: Vec<CircuitPoint> = circuit.points(spec.nodes);
        let l_min = least_lengths(&env, &pts, spec, false)?;
        let l = optimise(&pts, &l_min, spec, k)?;
        // The geometric trajectories on the same nodes.
        let mut comparison = Vec::new();
        for mode in [EyeMode::AxisParallel, EyeMode::Equidistant] {
            if mode == EyeMode::AxisParallel && spec.radius.is_none() {
                continue;
            }
            let mut g = Geometric::new(mode, spec, &env, None)?;
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
            let (_, c) = eye_points(&pts, &lg, &env, spec, k);
            comparison.push(Comparison {
                mode,
                stats: c.stats(),
                constraints_ok: c.broken.iter().all(Option::is_none),
                gain_u_min: 0.0,
                gain_u_max: 0.0,
                gain_u_rms_dev: 0.0,
            });
        }
        let (points, checks) = eye_points(&pts, &l, &env, spec, k);
        (points, checks, comparison, l_min)
    } else {
        let length = Geometric::new(spec.mode, spec, &env, curve.as_ref())?;
        let (points, checks) =
            geometric_points(&circuit, spec.samples - 1, &length, &env, spec, k)?;
        (points, checks, Vec::new(), Vec::new())
    };
    let turn = circuit.turn_angle();
    let closure_mm = closure(&points, turn);
    let (stats, violations) = checks.close(&mut points, closure_mm);
    let comparison: Vec<Comparison> = comparison
        .into_iter()
        .map(|mut c| {
            c.gain_u_min = stats.u_min - c.stats.u_min;
            c.gain_u_max = c.stats.u_max - stats.u_max;
            c.gain_u_rms_dev = c.stats.u_rms_dev - stats.u_rms_dev;
            c
        })
        .collect();
    Ok(EyeTrajectory {
        mode: spec.mode,
        constraints_ok: violations.is_empty(),
        points,
        stats,
        violations,
        circuit_turn_rad: turn,
        closure_mm,
        comparison,
        l_min,
    })
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

/// The constraints, in the order of [`Checks`]' slots.
const CONSTRAINTS: [&str; 5] = [
    "cyclicity",
    "clearance",
    "l_max",
    "slack",
    "reverse-rotation",
];
const CLEARANCE: usize = 1;
const L_MAX: usize = 2;
const SLACK: usize = 3;
const REVERSE: usize = 4;

/// The pull speed and the constraints over a run of consecutive eye points:
/// what can be summed run by run and joined.
#[derive(Debug, Clone)]
struct Checks {
    u_min: f64,
    u_max: f64,
    /// Sums over the intervals: length, `(u - 1) dx`, `(u - 1)^2 dx` (the mean
    /// pull speed of a closed cycle is 1).
    sums: (f64, f64, f64),
    /// Per constraint: the first `x` where it fails, how often, the worst excess.
    broken: [Option<(f64, usize, f64)>; 5],
}

impl Checks {
    /// Sets `u` on every interval of `e` and checks its points and intervals.
    fn of_run(e: &mut [EyePoint], spec: &EyeSpec) -> Self {
        let mut c = Self::new();
        c.scan(e, 0, spec);
        c
    }

    fn new() -> Self {
        Self {
            u_min: f64::INFINITY,
            u_max: f64::NEG_INFINITY,
            sums: (0.0, 0.0, 0.0),
            broken: [None; 5],
        }
    }

    /// Checks the points of `e` from `from` on, and the intervals that end there.
    fn scan(&mut self, e: &mut [EyePoint], from: usize, spec: &EyeSpec) {
        for i in from..e.len() {
            self.point(&e[i], spec);
            if i > 0 {
                let next = e[i];
                self.interval(&mut e[i - 1], &next);
            }
        }
    }

    fn note(&mut self, kind: usize, x: f64, count: usize, excess: f64) {
        let slot = &mut self.broken[kind];
        *slot = Some(match *slot {
            Some((x0, n, worst)) => (x0.min(x), n + count, worst.max(excess)),
            None => (x, count, excess),
        });
    }

    fn point(&mut self, e: &EyePoint, spec: &EyeSpec) {
        if e.margin < -1e-6 * (1.0 + spec.clearance) {
            self.note(CLEARANCE, e.x, 1, -e.margin);
        }
        if e.l > spec.l_max + 1e-6 {
            self.note(L_MAX, e.x, 1, e.l - spec.l_max);
        }
    }

    /// The interval from `a` to the next point `b`: sets `a.u`.
    fn interval(&mut self, a: &mut EyePoint, b: &EyePoint) {
        let dx = b.x - a.x;
        a.u = if dx > 0.0 {
            (b.lambda - a.lambda) / dx
        } else {
            1.0
        };
        self.u_min = self.u_min.min(a.u);
        self.u_max = self.u_max.max(a.u);
        let d = a.u - 1.0;
        self.sums.0 += dx;
        self.sums.1 += d * dx;
        self.sums.2 += d * d * dx;
        let slack = (b.l - a.l) + dx;
        if slack < -1e-6 {
            self.note(SLACK, a.x, 1, -slack);
        }
        let dv = b.eye_v - a.eye_v;
        if dv < -1e-9 {
            self.note(REVERSE, a.x, 1, -dv);
        }
    }

    /// Adds the checks of the run that follows this one.
    fn join(&mut self, next: Checks) {
        self.u_min = self.u_min.min(next.u_min);
        self.u_max = self.u_max.max(next.u_max);
        self.sums.0 += next.sums.0;
        self.sums.1 += next.sums.1;
        self.sums.2 += next.sums.2;
        for (kind, b) in next.broken.into_iter().enumerate() {
            if let Some((x, count, worst)) = b {
                self.note(kind, x, count, worst);
            }
        }
    }

    fn stats(&self) -> PullStats {
        let (total, s1, s2) = self.sums;
        let (mean, dev) = if total > 0.0 {
            let shift = s1 / total;
            (1.0 + shift, (s2 / total - shift * shift).max(0.0).sqrt())
        } else {
            (1.0, 0.0)
        };
        let (u_min, u_max) = if self.u_min <= self.u_max {
            (self.u_min, self.u_max)
        } else {
            (0.0, 0.0)
        };
        PullStats {
            u_min,
            u_max,
            u_mean: mean,
            u_rms_dev: dev,
        }
    }

    /// Closes the cycle: the last point takes the first one's pull speed; the
    /// free length and the eye's position (`closure_mm` apart after the circuit's
    /// turn) are checked for cyclicity.
    fn close(mut self, e: &mut [EyePoint], closure_mm: f64) -> (PullStats, Vec<Violation>) {
        let u0 = e.first().map_or(0.0, |p| p.u);
        if e.len() >= 2
            && let Some(last) = e.last_mut()
        {
            last.u = u0;
        }
        if let (Some(a), Some(b)) = (e.first(), e.last())
            && (a.l - b.l).abs() > 1e-6
        {
            self.note(0, b.x, 1, (a.l - b.l).abs());
        }
        if closure_mm > 1e-6 {
            let x = e.last().map_or(0.0, |p| p.x);
            self.note(0, x, 1, closure_mm);
        }
        (self.stats(), self.violations())
    }

    /// The broken constraints, in the order they first fail along `x`.
    fn violations(&self) -> Vec<Violation> {
        let mut v: Vec<Violation> = CONSTRAINTS
            .iter()
            .zip(&self.broken)
            .filter_map(|(&constraint, b)| {
                b.map(|(x, count, worst)| Violation {
                    constraint,
                    x,
                    count,
                    worst,
                })
            })
            .collect();
        v.sort_by(|a, b| a.x.total_cmp(&b.x));
        v
    }
}

/// Distance between the first eye point turned by the circuit's turn and the last.
fn closure(e: &[EyePoint], turn: f64) -> f64 {
    let (Some(a), Some(b)) = (e.first(), e.last()) else {
        return 0.0;
    };
    let pa = (
        a.eye_r * (a.eye_v + turn).cos(),
        a.eye_r * (a.eye_v + turn).sin(),
        a.eye_z,
    );
    let pb = (b.eye_r * b.eye_v.cos(), b.eye_r * b.eye_v.sin(), b.eye_z);
    ((pa.0 - pb.0).powi(2) + (pa.1 - pb.1).powi(2) + (pa.2 - pb.2).powi(2)).sqrt()
}

/// A sparse problem for Clarabel: `min 1/2 x'Px + q'x`, equality rows then `<=` rows.
struct Problem {
    n: usize,
    p_diag: Vec<(usize, f64)>,
    q: Vec<f64>,
    eq: Vec<(Vec<(usize, f64)>, f64)>,
    le: Vec<(Vec<(usize, f64)>, f64)>,
}

impl Problem {
    fn new(n: usize) -> Self {
        Self {
            n,
            p_diag: Vec::new(),
            q: vec![0.0; n],
            eq: Vec::new(),
            le: Vec::new(),
        }
    }

    fn solve(&self, stage: &str) -> Result<Vec<f64>, WindingError> {
        let m = self.eq.len() + self.le.len();
        let (mut ii, mut jj, mut vv) = (Vec::new(), Vec::new(), Vec::new());
        for (row, (coef, _)) in self.eq.iter().chain(&self.le).enumerate() {
            for &(j, v) in coef {
                ii.push(row);
                jj.push(j);
                vv.push(v);
            }
        }
        let a = CscMatrix::new_from_triplets(m, self.n, ii, jj, vv);
        let (pi, pv): (Vec<usize>, Vec<f64>) = self.p_diag.iter().copied().unzip();
        let p = CscMatrix::new_from_triplets(self.n, self.n, pi.clone(), pi, pv);
        let b: Vec<f64> = self.eq.iter().chain(&self.le).map(|r| r.1).collect();
        let mut cones: Vec<SupportedConeT<f64>> = Vec::new();
        if !self.eq.is_empty() {
            cones.push(ZeroConeT(self.eq.len()));
        }
        cones.push(NonnegativeConeT(self.le.len()));
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .max_iter(400)
            .build()
            .map_err(|e| WindingError::field("eye", format!("solver settings: {e:?}")))?;
        let mut solver = DefaultSolver::new(&p, &self.q, &a, &b, &cones, settings)
            .map_err(|e| WindingError::field("eye", format!("{stage}: solver setup: {e:?}")))?;
        solver.solve();
        match solver.solution.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => Ok(solver.solution.x.clone()),
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                Err(WindingError::infeasible(
                    "eye.l_max",
                    format!(
                        "{stage}: no free length l(x) keeps the clearance, stays under l_max, never \
                         slackens the band and never turns the mandrel back (the LP is infeasible)"
                    ),
                ))
            }
            other => Err(WindingError::infeasible(
                "eye",
                format!("{stage}: the solver stopped with {other:?}"),
            )),
        }
    }
}

/// Lexicographic pull-speed optimum on the nodes `pts` (`pts[n]` closes the cycle).
fn optimise(
    pts: &[CircuitPoint],
    l_min: &[f64],
    spec: &EyeSpec,
    k: f64,
) -> Result<Vec<f64>, WindingError> {
    let n = pts.len() - 1;
    if let Some(i) = (0..=n).find(|&i| l_min[i] > spec.l_max) {
        return Err(WindingError::infeasible(
            "eye.l_max",
            format!(
                "keeping the clearance of {} mm needs a free length of {:.3} mm at x = {:.3} mm \
                 (z = {:.3} mm), more than l_max = {} mm",
                spec.clearance, l_min[i], pts[i].x, pts[i].z, spec.l_max
            ),
        ));
    }
    let lo: Vec<f64> = (0..n)
        .map(|i| l_min[i].max(l_min[if i == 0 { n } else { i }]))
        .collect();
    // Start: a constant length when one fits, else the least lengths. A fixed bath
    // needs a start that keeps every constraint (each trust region around it then
    // holds a feasible point): the constant length if the mandrel never turns back
    // with it, else the optimum of a moving bath.
    let top = lo.iter().copied().fold(0.0, f64::max);
    let constant = (top <= spec.l_max).then(|| vec![top; n]);
    let mut l0: Vec<f64> = match constant {
        Some(c) if k == 0.0 || turns_forward(pts, &c) => c,
        _ if k != 0.0 => {
            let mut start = optimise(pts, l_min, spec, 0.0)?;
            start.truncate(n);
            start
        }
        Some(c) => c,
        None => lo.clone(),
    };
    // k = 1 linearises R(l); both linearise the turn V(l) of the no-reverse rows.
    let iterations = 8;
    let mut trust = 0.25 * spec.l_max;
    let mut best = l0.clone();
    let mut best_min = f64::NEG_INFINITY;
    for _ in 0..iterations {
        let (_, l) = Stages::new(pts, &lo, spec, &l0, trust, k).min()?;
        let exact = exact_u_min(pts, &l, k);
        let forward = turns_forward(pts, &l);
        if exact > best_min + 1e-12 || (k == 0.0 && forward) {
            let gain = exact - best_min;
            best_min = best_min.max(exact);
            best = l.clone();
            l0 = l;
            // Converged: the linearisations no longer move the optimum.
            if forward && (k == 0.0 || gain < 1e-4) {
                break;
            }
        } else if k == 0.0 {
            // Only the turn is linearised: relinearise at the new solution.
            l0 = l;
        } else {
            trust *= 0.5;
        }
    }
    // Stages 2 and 3 around the stage-1 optimum; the turn rows are relinearised
    // at their solution until the exact check holds, else the stage-1 optimum
    // (which keeps every constraint) stands.
    let mut at = best.clone();
    let mut out = None;
    for _ in 0..4 {
        let stages = Stages::new(pts, &lo, spec, &at, trust, k);
        let (t_star, _) = stages.min()?;
        let (w_star, _) = stages.max(t_star)?;
        let l = stages.rms(t_star, w_star)?;
        if turns_forward(pts, &l) {
            out = Some(l);
            break;
        }
        at = l;
    }
    let mut l = out.unwrap_or(best);
    l.push(l[0]);
    Ok(l)
}

/// `lambda`'s dependence on `l` at each node, linear: `lambda_i = c1_i l_i + c0_i + s_i`
/// (exact for `k = 0`; linearised `R` for `k = 1`).
struct Linear {
    c1: Vec<f64>,
    c0: Vec<f64>,
}

impl Linear {
    fn new(pts: &[CircuitPoint], l0: &[f64], k: f64) -> Self {
        let n = pts.len() - 1;
        let mut c1 = vec![1.0; n];
        let mut c0 = vec![0.0; n];
        if k != 0.0 {
            for i in 0..n {
                let (_, r, _, _, g) = eye_at(&pts[i], l0[i]);
                c1[i] = 1.0 - k * g;
                c0[i] = -k * (r - g * l0[i]);
            }
        }
        Self { c1, c0 }
    }
}

fn exact_u_min(pts: &[CircuitPoint], l: &[f64], k: f64) -> f64 {
    let n = pts.len() - 1;
    let lam = |i: usize| {
        let li = l[i % n];
        let (_, r, _, _, _) = eye_at(&pts[i], li);
        li + pts[i].x - k * r
    };
    (0..n)
        .map(|i| (lam(i + 1) - lam(i)) / (pts[i + 1].x - pts[i].x))
        .fold(f64::INFINITY, f64::min)
}

/// The eye's turn `V` at free length `l` and its slope `dV/dl`.
fn turn_and_slope(p: &CircuitPoint, l: f64) -> (f64, f64) {
    let (_, r, v, _, _) = eye_at(p, l);
    (
        v,
        if r > 0.0 {
            p.r * p.alpha.sin() / (r * r)
        } else {
            0.0
        },
    )
}

/// Whether the mandrel never turns back along `l` (cyclic, `l[n] = l[0]`).
fn turns_forward(pts: &[CircuitPoint], l: &[f64]) -> bool {
    let n = l.len();
    (0..n).all(|i| {
        let (vi, _) = turn_and_slope(&pts[i], l[i]);
        let (vj, _) = turn_and_slope(&pts[i + 1], l[(i + 1) % n]);
        vj - vi >= -1e-9
    })
}

/// The three stages on the discretised `l(x)`, linearised at `l0` (the turn `V`,
/// and `R` for a fixed bath), with what every stage shares.
struct Stages<'a> {
    pts: &'a [CircuitPoint],
    lo: &'a [f64],
    spec: &'a EyeSpec,
    l0: &'a [f64],
    lin: Linear,
    trust: f64,
    k: f64,
}

impl<'a> Stages<'a> {
    fn new(
        pts: &'a [CircuitPoint],
        lo: &'a [f64],
        spec: &'a EyeSpec,
        l0: &'a [f64],
        trust: f64,
        k: f64,
    ) -> Self {
        Self {
            pts,
            lo,
            spec,
            l0,
            lin: Linear::new(pts, l0, k),
            trust,
            k,
        }
    }

    fn n(&self) -> usize {
        self.lo.len()
    }

    /// Rows common to every stage: bounds, trust region, no slack, no reverse rotation.
    fn rows(&self, prob: &mut Problem) {
        let (pts, l0, n) = (self.pts, self.l0, self.n());
        for i in 0..n {
            let j = (i + 1) % n;
            let dx = pts[i + 1].x - pts[i].x;
            prob.le.push((vec![(i, -1.0)], -self.lo[i]));
            prob.le.push((vec![(i, 1.0)], self.spec.l_max));
            if self.k != 0.0 {
                prob.le.push((vec![(i, 1.0)], l0[i] + self.trust));
                prob.le.push((vec![(i, -1.0)], -(l0[i] - self.trust)));
            }
            // No slack: l_j - l_i + dx >= 0.
            prob.le.push((vec![(i, 1.0), (j, -1.0)], dx));
            // No reverse rotation, linearised at l0: V_j(l_j) >= V_i(l_i), with
            // dV/dl = r sin(alpha) / R^2 > 0.
            let (vi, gi) = turn_and_slope(&pts[i], l0[i]);
            let (vj, gj) = turn_and_slope(&pts[i + 1], l0[j]);
            prob.le
                .push((vec![(i, gi), (j, -gj)], vj - vi - gj * l0[j] + gi * l0[i]));
        }
    }

    /// `u_i = 1 + (D_i + e_i)/dx_i` with `D_i = c1_j l_j - c1_i l_i`: the
    /// coefficients of `D_i / dx_i` and the constant `1 + e_i / dx_i`.
    fn u_terms(&self, i: usize) -> (Vec<(usize, f64)>, f64) {
        let (c1, c0) = (&self.lin.c1, &self.lin.c0);
        let j = (i + 1) % c1.len();
        let dx = self.pts[i + 1].x - self.pts[i].x;
        (
            vec![(j, c1[j] / dx), (i, -c1[i] / dx)],
            1.0 + (c0[j] - c0[i]) / dx,
        )
    }

    /// Stage 1: the largest lower bound `t` of `u`, and its `l`.
    fn min(&self) -> Result<(f64, Vec<f64>), WindingError> {
        let n = self.n();
        let mut prob = Problem::new(n + 1);
        prob.q[n] = -1.0;
        self.rows(&mut prob);
        for i in 0..n {
            // t <= u_i  ->  t - D_i/dx <= const
            let (row, c) = self.u_terms(i);
            let mut row: Vec<(usize, f64)> = row.iter().map(|&(j, v)| (j, -v)).collect();
            row.push((n, 1.0));
            prob.le.push((row, c));
        }
        let x = prob.solve("stage 1 (max min u)")?;
        Ok((x[n], x[..n].to_vec()))
    }

    /// Stage 2: the smallest upper bound `w` of `u` keeping `u >= t*`, and its `l`.
    fn max(&self, t_star: f64) -> Result<(f64, Vec<f64>), WindingError> {
        let n = self.n();
        let mut prob = Problem::new(n + 1);
        prob.q[n] = 1.0;
        self.rows(&mut prob);
        let t_lo = t_star - 1e-7 * (1.0 + t_star.abs());
        for i in 0..n {
            let (row, c) = self.u_terms(i);
            // u_i <= w  ->  D_i/dx - w <= -c
            let mut up = row.clone();
            up.push((n, -1.0));
            prob.le.push((up, -c));
            // u_i >= t*  ->  -D_i/dx <= c - t*
            let down: Vec<(usize, f64)> = row.iter().map(|&(j, v)| (j, -v)).collect();
            prob.le.push((down, c - t_lo));
        }
        let x = prob.solve("stage 2 (min max u)")?;
        Ok((x[n], x[..n].to_vec()))
    }

    /// Stage 3: the least RMS of `u - U` within `[t*, w*]`.
    fn rms(&self, t_star: f64, w_star: f64) -> Result<Vec<f64>, WindingError> {
        let (pts, n) = (self.pts, self.n());
        // Variables: l_0..l_{n-1}, u_0..u_{n-1}.
        let mut prob = Problem::new(2 * n);
        let total = pts[n].x - pts[0].x;
        let t_lo = t_star - 1e-7 * (1.0 + t_star.abs());
        let w_hi = w_star + 1e-7 * (1.0 + w_star.abs());
        for i in 0..n {
            let dx = pts[i + 1].x - pts[i].x;
            let (row, c) = self.u_terms(i);
            // u_i - D_i/dx = c
            let mut eq: Vec<(usize, f64)> = row.iter().map(|&(j, v)| (j, -v)).collect();
            eq.push((n + i, 1.0));
            prob.eq.push((eq, c));
            prob.le.push((vec![(n + i, 1.0)], w_hi));
            prob.le.push((vec![(n + i, -1.0)], -t_lo));
            // (u_i - U)^2 dx / X with U = 1 (the mean of u over a closed cycle).
            let w = dx / total;
            prob.p_diag.push((n + i, 2.0 * w));
            prob.q[n + i] = -2.0 * w;
            // Tie-break: among equally even pull speeds, the shortest free band.
            prob.q[i] = 1e-9 * w;
        }
        self.rows(&mut prob);
        let x = prob.solve("stage 3 (min rms of u - U)")?;
        Ok(x[..n].to_vec())
    }
}
