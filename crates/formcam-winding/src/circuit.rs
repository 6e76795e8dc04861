//! A circuit: pass out, turn-around, pass back, turn-around — the path as one
//! closed cycle, parametrised by the laid band length `x` (monotonic through
//! both passes and both turn-arounds).
//!
//! * At a polar turn-around (`alpha = pi/2` on the mandrel) the mandrel dwells
//!   and the band wraps the turn parallel: a hoop arc of radius `C`.
//! * At a tube's end the band turns on the tube's extension: `alpha` runs
//!   linearly in `x` from the arriving angle through `pi/2` to the leaving angle,
//!   so the direction stays continuous; its length is chosen so that the mandrel
//!   advances by the dwell (radius taken constant over the short excursion).
//! * Where a pass leaves a dome on its polar boss (isotensoid), the turn is the
//!   same sweep, the mandrel advancing by the boss part of the turn and the dwell.
//!
//! The return pass is the mirror image of the outgoing one: the same `z`
//! profile, `alpha -> pi - alpha`, `v` still increasing.

use std::f64::consts::{FRAC_PI_2, PI};

use formcam_geom::Meridian;

use crate::{Layer, PassEnd, PathPoint, Trace};

/// How the pass is stored for evaluation at any path length.
#[derive(Debug, Clone, PartialEq)]
pub enum PassPath {
    /// An integrated pass (dense output).
    Traced(Trace),
    /// A pass given at points (the minimax grid), interpolated linearly in `s`.
    Points(Vec<PathPoint>),
}

impl PassPath {
    /// `(z, v, alpha)` at path length `s` of the pass.
    pub fn state_at(&self, s: f64) -> [f64; 3] {
        match self {
            PassPath::Traced(t) => t.state_at(s),
            PassPath::Points(p) => {
                let i = p.partition_point(|q| q.s < s).clamp(1, p.len().max(2) - 1);
                let (Some(a), Some(b)) = (p.get(i - 1), p.get(i)) else {
                    return p.first().map_or([0.0; 3], |q| [q.z, q.v, q.alpha]);
                };
                let t = if b.s > a.s {
                    ((s - a.s) / (b.s - a.s)).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                [
                    a.z + t * (b.z - a.z),
                    a.v + t * (b.v - a.v),
                    a.alpha + t * (b.alpha - a.alpha),
                ]
            }
        }
    }

    /// State at `s` with a cursor for nearby successive calls.
    pub fn state_near(&self, s: f64, cursor: &mut usize) -> [f64; 3] {
        match self {
            PassPath::Traced(t) => t.state_near(s, cursor),
            PassPath::Points(_) => self.state_at(s),
        }
    }

    /// Length of the pass on the mandrel, mm.
    pub fn length(&self) -> f64 {
        match self {
            PassPath::Traced(t) => t.length(),
            PassPath::Points(p) => p.last().map_or(0.0, |q| q.s),
        }
    }
}

/// One point of a circuit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CircuitPoint {
    /// Laid band length from the circuit's start, mm.
    pub x: f64,
    /// Axial position, mm.
    pub z: f64,
    /// Mandrel radius (of the path point), mm.
    pub r: f64,
    /// Meridian slope `r'` at `z`.
    pub dr: f64,
    /// Turn angle, rad.
    pub v: f64,
    /// Angle between the path and the `+z` meridian direction, in `[0, pi]`.
    pub alpha: f64,
}

/// A turn-around at one end of the passes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Turnaround {
    /// A hoop arc of radius `radius` and angle `dv` at `z` (`alpha = pi/2`).
    Hoop {
        /// `z` of the arc, mm.
        z: f64,
        /// Radius, mm.
        radius: f64,
        /// Slope of the meridian there.
        dr: f64,
        /// Mandrel advance over the arc, rad.
        dv: f64,
    },
    /// A tube-end turn: `alpha` from `alpha_in` to `alpha_out` linearly in `x`.
    Sweep {
        /// `z` where the pass meets the tube's end, mm.
        z: f64,
        /// Radius there, mm.
        radius: f64,
        /// Slope of the meridian there.
        dr: f64,
        /// Arriving angle.
        alpha_in: f64,
        /// Leaving angle.
        alpha_out: f64,
        /// Length, mm.
        length: f64,
    },
}

impl Turnaround {
    /// The turn-around at a pass end, with the dwell `dwell` (rad) spent there.
    /// `far` is true at the far end (`z_end`), false at the start.
    pub fn new<M: Meridian>(m: &M, end: &PassEnd, dwell: f64, tube: bool, far: bool) -> Self {
        let z = end.z();
        let j = m.eval(z);
        match *end {
            PassEnd::Exit { alpha, .. } if alpha < FRAC_PI_2 - 1e-9 => {
                // The mandrel advances by the dwell, and at a polar boss also by the
                // rest of the turn on the boss face (pi/2 - alpha on each side).
                let dv = dwell.max(0.0) + if tube { 0.0 } else { 2.0 * (FRAC_PI_2 - alpha) };
                let span = PI - 2.0 * alpha;
                let length = dv * j.r * span / (2.0 * alpha.cos());
                let (alpha_in, alpha_out) = if far {
                    (alpha, PI - alpha)
                } else {
                    (PI - alpha, alpha)
                };
                Turnaround::Sweep {
                    z,
                    radius: j.r,
                    dr: j.dr,
                    alpha_in,
                    alpha_out,
                    length,
                }
            }
            _ => Turnaround::Hoop {
                z,
                radius: j.r,
                dr: j.dr,
                dv: dwell,
            },
        }
    }

    /// Band length of the turn-around, mm.
    pub fn length(&self) -> f64 {
        match self {
            Turnaround::Hoop { radius, dv, .. } => radius * dv,
            Turnaround::Sweep { length, .. } => *length,
        }
    }

    /// Mandrel advance over the turn-around, rad.
    pub fn dv(&self) -> f64 {
        match self {
            Turnaround::Hoop { dv, .. } => *dv,
            Turnaround::Sweep {
                radius,
                alpha_in,
                alpha_out,
                length,
                ..
            } => {
                let span = alpha_out - alpha_in;
                if span.abs() < 1e-15 {
                    0.0
                } else {
                    length / (span * radius) * (alpha_in.cos() - alpha_out.cos())
                }
            }
        }
    }

    /// `(z, r, dr, dv, alpha)` at `sigma` in `[0, length]` from its start.
    /// On a sweep the point lies on the meridian's continuation beyond the end
    /// (`r`, `r'` from `m`), so that it joins the passes exactly; `z` and `v` follow
    /// from the end radius (the excursion is short).
    fn at<M: Meridian>(&self, m: &M, sigma: f64) -> (f64, f64, f64, f64, f64) {
        match *self {
            Turnaround::Hoop { z, radius, dr, .. } => (z, radius, dr, sigma / radius, FRAC_PI_2),
            Turnaround::Sweep {
                z,
                radius,
                dr,
                alpha_in,
                alpha_out,
                length,
            } => {
                let span = alpha_out - alpha_in;
                if length <= 0.0 || span.abs() < 1e-15 {
                    return (z, radius, dr, 0.0, alpha_in);
                }
                let a = alpha_in + span * (sigma / length).clamp(0.0, 1.0);
                let k = length / span;
                let q = (1.0 + dr * dr).sqrt();
                // dz = cos(a)/q dsigma, dv = sin(a)/r dsigma, with dsigma = k da.
                let zz = z + k * (a.sin() - alpha_in.sin()) / q;
                let dv = k * (alpha_in.cos() - a.cos()) / radius;
                let j = m.eval(zz);
                let (r, slope) = if j.r.is_finite() && j.r > 0.0 {
                    (j.r, j.dr)
                } else {
                    (radius, dr)
                };
                (zz, r, slope, dv, a)
            }
        }
    }
}

/// A closed circuit of a layer on its mandrel.
#[derive(Debug, Clone)]
pub struct Circuit<'a, M> {
    m: &'a M,
    pass: &'a PassPath,
    pass_len: f64,
    pass_turn: f64,
    far: Turnaround,
    near: Turnaround,
}

impl<'a, M: Meridian> Circuit<'a, M> {
    /// The circuit of `layer` on `m` (the mandrel it was planned on).
    pub fn new(m: &'a M, layer: &'a Layer) -> Self {
        let dwell_end = 0.5 * layer.pattern.dwell_rad;
        let far = Turnaround::new(m, &layer.pass.end, dwell_end, layer.tube, true);
        let near = Turnaround::new(m, &layer.pass.start, dwell_end, layer.tube, false);
        let pass_len = layer.pass_path.length();
        let pass_turn = layer.pass_path.state_at(pass_len)[1];
        Self {
            m,
            pass: &layer.pass_path,
            pass_len,
            pass_turn,
            far,
            near,
        }
    }

    /// Band length of the circuit, mm.
    pub fn length(&self) -> f64 {
        2.0 * self.pass_len + self.far.length() + self.near.length()
    }

    /// Mandrel turn over the circuit (dwell included), rad.
    pub fn turn_angle(&self) -> f64 {
        2.0 * self.pass_turn + self.far.dv() + self.near.dv()
    }

    /// `n + 1` points evenly spaced in `x`, ends included: [`Circuit::at`] at each,
    /// evaluated with a cursor over the pass (forwards on the outgoing pass,
    /// backwards on the return pass).
    pub fn points(&self, n: usize) -> Vec<CircuitPoint> {
        self.samples(n, 0..n.max(1) + 1).collect()
    }

    /// The points `range` of [`Circuit::points`]`(n)`, one at a time.
    pub fn samples(
        &self,
        n: usize,
        range: std::ops::Range<usize>,
    ) -> impl Iterator<Item = CircuitPoint> + '_ {
        let n = n.max(1);
        let total = self.length();
        let s1 = self.pass_len;
        let t1 = s1 + self.far.length();
        let s2 = t1 + s1;
        let v_back = 2.0 * self.pass_turn + self.far.dv();
        let mut cursor = 0usize;
        range.map(move |i| {
            let x = total * i as f64 / n as f64;
            let on_pass = |state: [f64; 3], back: bool| {
                let [z, v, a] = state;
                let j = self.m.eval(z);
                CircuitPoint {
                    x,
                    z,
                    r: j.r,
                    dr: j.dr,
                    v: if back { v_back - v } else { v },
                    alpha: if back { PI - a } else { a },
                }
            };
            if x <= s1 {
                on_pass(self.pass.state_near(x, &mut cursor), false)
            } else if x > t1 && x <= s2 {
                on_pass(self.pass.state_near(s1 - (x - t1), &mut cursor), true)
            } else {
                self.at(x)
            }
        })
    }

    /// The point at laid length `x` (clamped to the circuit).
    pub fn at(&self, x: f64) -> CircuitPoint {
        let x = x.clamp(0.0, self.length());
        let s1 = self.pass_len;
        let t1 = s1 + self.far.length();
        let s2 = t1 + s1;
        let point = |z: f64, v: f64, alpha: f64| {
            let j = self.m.eval(z);
            CircuitPoint {
                x,
                z,
                r: j.r,
                dr: j.dr,
                v,
                alpha,
            }
        };
        if x <= s1 {
            let [z, v, a] = self.pass.state_at(x);
            point(z, v, a)
        } else if x <= t1 {
            let (z, r, dr, dv, a) = self.far.at(self.m, x - s1);
            CircuitPoint {
                x,
                z,
                r,
                dr,
                v: self.pass_turn + dv,
                alpha: a,
            }
        } else if x <= s2 {
            let sigma = s1 - (x - t1);
            let [z, v, a] = self.pass.state_at(sigma);
            point(z, 2.0 * self.pass_turn + self.far.dv() - v, PI - a)
        } else {
            let (z, r, dr, dv, a) = self.near.at(self.m, x - s2);
            let v0 = 2.0 * self.pass_turn + self.far.dv();
            CircuitPoint {
                x,
                z,
                r,
                dr,
                v: v0 + dv,
                alpha: a,
            }
        }
    }
}
