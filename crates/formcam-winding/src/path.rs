//! A pass of the winding path integrated in path length `s`.
//!
//! State `(z, v, alpha)` with `s` as the independent variable:
//!
//! ```text
//! dz/ds     = cos(alpha) / q,              q = sqrt(1 + r'^2)
//! dv/ds     = sin(alpha) / r
//! dalpha/ds = [mu (sin^2 alpha - r r'' cos^2 alpha / q^2) - r' sin alpha] / (r q)
//! ```
//!
//! The last line is eq. 3 (docs/winding.md) (`k_g = mu k_n`) rewritten in `s`; it has no
//! singularity at a turn-around (`alpha = pi/2`), where `dv/dz` of eq. 1 is infinite,
//! so passes are integrated through their turn-arounds instead of stopping short.

use std::f64::consts::FRAC_PI_2;

use formcam_geom::Meridian;
use serde::Serialize;

use crate::ode::{Control, Integrator, Outcome, Step, Tolerance, find_root};
use crate::{MuLaw, WindingError};

/// One sample of a path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PathPoint {
    /// Path length from the pass's start, mm.
    pub s: f64,
    /// Axial position, mm.
    pub z: f64,
    /// Mandrel radius at `z`, mm.
    pub r: f64,
    /// Turn angle about the axis, rad.
    pub v: f64,
    /// Winding angle (to the meridian), rad.
    pub alpha: f64,
    /// Clairaut function `r sin(alpha)`, mm.
    pub c: f64,
    /// Slippage at this point.
    pub mu: f64,
}

/// How a pass ends (or starts).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum PassEnd {
    /// The path turns on the mandrel: `alpha = pi/2`, `C = r`.
    TurnAround {
        /// Where, mm.
        z: f64,
    },
    /// The path reaches the meridian's end with `alpha < pi/2` (tube ends, a polar boss).
    Exit {
        /// Where, mm.
        z: f64,
        /// Winding angle there, rad.
        alpha: f64,
    },
}

impl PassEnd {
    /// `z` of the end.
    pub fn z(&self) -> f64 {
        match self {
            PassEnd::TurnAround { z } | PassEnd::Exit { z, .. } => *z,
        }
    }
}

/// A pass integrated with its accepted steps (dense output available everywhere).
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    steps: Vec<Step<3>>,
    /// How the pass ends.
    pub end: PassEnd,
    /// Total path length, mm.
    pub length: f64,
    /// Final state `(z, v, alpha)`.
    pub last: [f64; 3],
}

/// Options of one integration.
#[derive(Debug, Clone, Copy)]
pub struct TraceOptions {
    /// Stop when `z` reaches the meridian's end with `alpha` clearly below `pi/2`.
    pub exit_at_end: bool,
    /// Give up when `z` passes the end by more than this (mm); only without `exit_at_end`.
    pub overrun: f64,
    /// Integration tolerances.
    pub tol: Tolerance,
}

impl Default for TraceOptions {
    fn default() -> Self {
        Self {
            exit_at_end: true,
            overrun: f64::INFINITY,
            tol: Tolerance::default(),
        }
    }
}

/// Right-hand side of the path ODE.
pub(crate) fn rhs<M: Meridian>(m: &M, law: &MuLaw, y: &[f64; 3]) -> [f64; 3] {
    let j = m.eval(y[0]);
    let q2 = 1.0 + j.dr * j.dr;
    let q = q2.sqrt();
    let (sa, ca) = y[2].sin_cos();
    let mu = law.at(y[0]);
    let kn = sa * sa - j.r * j.d2r * ca * ca / q2;
    [ca / q, sa / j.r, (mu * kn - j.dr * sa) / (j.r * q)]
}

/// Integrates one pass from `z_start` with winding angle `alpha0` until it turns
/// (`alpha = pi/2`) or leaves the meridian's end.
pub fn trace<M: Meridian>(
    m: &M,
    law: &MuLaw,
    alpha0: f64,
    opts: &TraceOptions,
) -> Result<Trace, WindingError> {
    let tracer = Tracer::new(m, law, opts);
    let y0 = [tracer.za, 0.0, alpha0];
    tracer.check_start(&y0)?;
    tracer.integrate(y0)
}

/// One pass being integrated: the meridian, the slippage law, the options and
/// what holds for the whole pass.
struct Tracer<'a, M> {
    m: &'a M,
    law: &'a MuLaw,
    opts: &'a TraceOptions,
    /// The options' tolerances, the largest step bounded by the mandrel's size.
    tol: Tolerance,
    /// The meridian's start, mm.
    za: f64,
    /// The meridian's end, mm.
    zb: f64,
    /// `zb - za`, mm.
    scale: f64,
    /// Where the integration stops and restarts: the meridian's and the law's
    /// breakpoints inside the meridian, in order.
    cuts: Vec<f64>,
}

impl<'a, M: Meridian> Tracer<'a, M> {
    fn new(m: &'a M, law: &'a MuLaw, opts: &'a TraceOptions) -> Self {
        let (za, zb) = m.z_range();
        let mut cuts: Vec<f64> = m.breakpoints();
        cuts.extend(law.breakpoints());
        cuts.retain(|z| *z > za && *z < zb);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let scale = zb - za;
        let mut tol = opts.tol;
        tol.h_max = tol.h_max.min(0.05 * scale + 0.05 * m.r(za).max(m.r(zb)));
        Self {
            m,
            law,
            opts,
            tol,
            za,
            zb,
            scale,
            cuts,
        }
    }

    /// A pass that starts at a turn-around must move into the mandrel: alpha has
    /// to fall below pi/2, i.e. the meridian must rise faster than the slippage
    /// lets it turn.
    fn check_start(&self, y0: &[f64; 3]) -> Result<(), WindingError> {
        let (m, law, za) = (self.m, self.law, self.za);
        if y0[2] >= FRAC_PI_2 && rhs(m, law, y0)[2] >= 0.0 {
            return Err(WindingError::infeasible(
                "winding.mu",
                format!(
                    "the pass cannot leave the start opening at z = {za:.3} mm: the meridian's slope \
                     r' = {:.4} there must exceed the slippage mu = {:.4}",
                    m.dr(za),
                    law.at(za)
                ),
            ));
        }
        Ok(())
    }

    /// Integrates from `y` event by event, restarting exactly on each cut,
    /// until an event ends the pass.
    fn integrate(&self, mut y: [f64; 3]) -> Result<Trace, WindingError> {
        let mut steps: Vec<Step<3>> = Vec::new();
        let mut t = 0.0;
        let mut h0 = 1e-3 * self.scale;
        loop {
            let (t1, y1, ev) = self.run_to_event(&mut steps, t, y, h0)?;
            t = t1;
            y = y1;
            h0 = steps.last().map_or(h0, |s| s.h.max(1e-6 * self.scale));
            let Event::Cut(zc) = ev else {
                return self.finish(ev, steps, t, y);
            };
            y[0] = zc;
            if let Some(last) = steps.last_mut() {
                last.y1[0] = zc;
            }
        }
    }

    /// One run of the integrator from `(t, y)` to the next event, the accepted
    /// steps pushed on `steps`; an error where the integration fails.
    fn run_to_event(
        &self,
        steps: &mut Vec<Step<3>>,
        t: f64,
        y: [f64; 3],
        h0: f64,
    ) -> Result<(f64, [f64; 3], Event), WindingError> {
        let (m, law) = (self.m, self.law);
        let next_cut = self.cuts.iter().copied().find(|c| *c > y[0] + 1e-12);
        let mut ev: Option<Event> = None;
        let mut integ = Integrator::new(|_s, y: &[f64; 3]| rhs(m, law, y), self.tol);
        let (outcome, t1, y1) = integ.run(t, y, f64::INFINITY, h0, |st| {
            self.observe(st, next_cut, steps, &mut ev)
        });
        if outcome == Outcome::TooManySteps {
            return Err(WindingError::Integration {
                z: y1[0],
                reason: format!(
                    "the pass needs more than {} integration steps: it is too long for its mandrel \
                     (a winding angle too close to 90 deg?)",
                    self.tol.max_steps
                ),
            });
        }
        match ev {
            Some(ev) if outcome != Outcome::Failed => Ok((t1, y1, ev)),
            _ => Err(WindingError::Integration {
                z: y1[0],
                reason:
                    "the step size collapsed: the meridian's slope is nearly infinite there or the \
                         slippage makes the path singular"
                        .into(),
            }),
        }
    }

    /// The integrator's look at an accepted step: the step kept, and the run
    /// stopped at the first event in it (or after it, where the path overruns
    /// the end, turns back past the start or its Clairaut function turns
    /// negative).
    fn observe(
        &self,
        st: &Step<3>,
        next_cut: Option<f64>,
        steps: &mut Vec<Step<3>>,
        ev: &mut Option<Event>,
    ) -> Control {
        if ev.is_some() {
            steps.push(*st);
            return Control::Stop;
        }
        let found = first_event(st, next_cut, self.zb, self.opts);
        match found {
            Some((ts, e)) => {
                *ev = Some(e);
                Control::StopAt(ts)
            }
            None => {
                steps.push(*st);
                if !self.opts.exit_at_end && st.y1[0] > self.zb + self.opts.overrun {
                    *ev = Some(Event::Overrun);
                    return Control::Stop;
                }
                if st.y1[0] < self.za - 1e-9 * self.scale {
                    *ev = Some(Event::Backwards);
                    return Control::Stop;
                }
                if st.y1[2] < 0.0 {
                    *ev = Some(Event::NegativeClairaut(st.y1[0]));
                    return Control::Stop;
                }
                Control::Continue
            }
        }
    }

    /// The pass ended by `ev` at `(t, y)`: a turn-around, an exit at the end,
    /// or the error that the path cannot be wound.
    fn finish(
        &self,
        ev: Event,
        steps: Vec<Step<3>>,
        t: f64,
        mut y: [f64; 3],
    ) -> Result<Trace, WindingError> {
        let (za, zb) = (self.za, self.zb);
        match ev {
            Event::Turn => {
                y[2] = FRAC_PI_2;
                Ok(Trace {
                    steps,
                    end: PassEnd::TurnAround { z: y[0] },
                    length: t,
                    last: y,
                })
            }
            Event::Exit => {
                y[0] = zb;
                Ok(Trace {
                    steps,
                    end: PassEnd::Exit { z: zb, alpha: y[2] },
                    length: t,
                    last: y,
                })
            }
            Event::NegativeClairaut(z) => Err(WindingError::infeasible(
                "winding.mu",
                format!(
                    "the Clairaut function r sin(alpha) becomes negative near z = {z:.3} mm: the \
                     path would reverse its turn about the axis (eq. 6 needs C >= 0); reduce |mu|"
                ),
            )),
            Event::Backwards => Err(WindingError::infeasible(
                "winding.mu",
                format!(
                    "the path turns back and leaves the mandrel through its start (z = {za:.3} mm); \
                     the slippage is too large for this meridian"
                ),
            )),
            // An overrun ends the pass where it stands; a cut never ends it
            // (`integrate` restarts there).
            Event::Overrun | Event::Cut(_) => Ok(Trace {
                steps,
                end: PassEnd::Exit {
                    z: y[0],
                    alpha: y[2],
                },
                length: t,
                last: y,
            }),
        }
    }
}

/// A path that reaches the meridian's end with `alpha` this close to `pi/2` (rad)
/// is tangent there: it turns within a hair (`r - C < 5e-9 r`), not exits. Near a
/// turn-around `pi/2 - alpha` grows as the square root of the distance, so a
/// converged shot meets the end with `pi/2 - alpha` about 1e-5.
pub(crate) const TANGENT_ALPHA_TOL: f64 = 1e-4;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Event {
    Cut(f64),
    Turn,
    Exit,
    Overrun,
    Backwards,
    NegativeClairaut(f64),
}

/// The earliest event inside an accepted step, if any.
fn first_event(
    st: &Step<3>,
    next_cut: Option<f64>,
    z_end: f64,
    opts: &TraceOptions,
) -> Option<(f64, Event)> {
    let mut best: Option<(f64, Event)> = None;
    let mut consider = |ts: f64, e: Event| {
        if best.is_none_or(|(b, _)| ts < b) {
            best = Some((ts, e));
        }
    };
    let xtol = 1e-14 * (st.t1().abs() + 1.0);
    if st.y0[2] < FRAC_PI_2 && st.y1[2] >= FRAC_PI_2 {
        consider(
            find_root(|t| st.at(t)[2] - FRAC_PI_2, st.t0, st.t1(), xtol, 0.0),
            Event::Turn,
        );
    }
    if let Some(zc) = next_cut
        && st.y0[0] < zc
        && st.y1[0] >= zc
    {
        {
            consider(
                find_root(|t| st.at(t)[0] - zc, st.t0, st.t1(), xtol, 0.0),
                Event::Cut(zc),
            );
        }
    }
    if opts.exit_at_end && st.y0[0] < z_end && st.y1[0] >= z_end {
        let ts = find_root(|t| st.at(t)[0] - z_end, st.t0, st.t1(), xtol, 0.0);
        // A path that would turn within a hair of the end is a turn-around, not an exit.
        if st.at(ts)[2] < FRAC_PI_2 - TANGENT_ALPHA_TOL {
            consider(ts, Event::Exit);
        }
    }
    best
}

impl Trace {
    /// Path length of the pass, mm.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Turn angle of the pass on the mandrel, rad.
    pub fn turn_angle(&self) -> f64 {
        self.last[1]
    }

    /// Final `z`, mm.
    pub fn z_last(&self) -> f64 {
        self.last[0]
    }

    /// State `(z, v, alpha)` at path length `s` (dense output; clamped to the pass).
    pub fn state_at(&self, s: f64) -> [f64; 3] {
        let i = self.steps.partition_point(|st| st.t1() < s);
        match self.steps.get(i) {
            Some(st) => st.at(s),
            None => self.last,
        }
    }

    /// State at `s` with a cursor `i` into the steps, for nearby successive calls
    /// (forwards or backwards) without a search each time.
    pub fn state_near(&self, s: f64, i: &mut usize) -> [f64; 3] {
        let n = self.steps.len();
        if n == 0 {
            return self.last;
        }
        let mut k = (*i).min(n - 1);
        while k + 1 < n && self.steps[k].t1() < s {
            k += 1;
        }
        while k > 0 && self.steps[k].t0 > s {
            k -= 1;
        }
        *i = k;
        let st = &self.steps[k];
        if s > st.t1() { self.last } else { st.at(s) }
    }

    /// `n >= 2` samples evenly spaced in path length, ends included.
    pub fn sample<M: Meridian>(&self, m: &M, law: &MuLaw, n: usize) -> Vec<PathPoint> {
        let n = n.max(2);
        let mut out = Vec::with_capacity(n);
        let mut i = 0;
        for k in 0..n {
            let s = if k + 1 == n {
                self.length
            } else {
                self.length * k as f64 / (n - 1) as f64
            };
            while i + 1 < self.steps.len() && self.steps[i].t1() < s {
                i += 1;
            }
            let y = if k + 1 == n {
                self.last
            } else if k == 0 {
                self.steps.first().map_or(self.last, |st| st.y0)
            } else {
                self.steps.get(i).map_or(self.last, |st| st.at(s))
            };
            let r = m.r(y[0]);
            out.push(PathPoint {
                s,
                z: y[0],
                r,
                v: y[1],
                alpha: y[2],
                c: r * y[2].sin(),
                mu: law.at(y[0]),
            });
        }
        out
    }
}
