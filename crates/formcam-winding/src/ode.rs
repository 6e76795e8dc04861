//! Adaptive Dormand–Prince 5(4) integrator with error control, dense output
//! and event location, for small fixed-size systems.

#![allow(clippy::needless_range_loop)]

/// Tolerances and limits of one integration.
#[derive(Debug, Clone, Copy)]
pub struct Tolerance {
    /// Relative tolerance per step.
    pub rtol: f64,
    /// Absolute tolerance per step.
    pub atol: f64,
    /// Largest step.
    pub h_max: f64,
    /// Most steps before giving up.
    pub max_steps: usize,
}

impl Default for Tolerance {
    fn default() -> Self {
        Self {
            rtol: 1e-13,
            atol: 1e-13,
            h_max: f64::INFINITY,
            max_steps: 200_000,
        }
    }
}

const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// One accepted step with its continuous extension (4th order).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Step<const N: usize> {
    /// Start of the step.
    pub t0: f64,
    /// Length of the step.
    pub h: f64,
    /// State at the start.
    pub y0: [f64; N],
    /// State at the end.
    pub y1: [f64; N],
    rc: [[f64; N]; 3],
}

impl<const N: usize> Step<N> {
    /// State at `t` inside the step (dense output).
    pub fn at(&self, t: f64) -> [f64; N] {
        let th = ((t - self.t0) / self.h).clamp(0.0, 1.0);
        let th1 = 1.0 - th;
        let mut y = [0.0; N];
        for i in 0..N {
            let d = self.y1[i] - self.y0[i];
            y[i] = self.y0[i]
                + th * (d + th1 * (self.rc[0][i] + th * (self.rc[1][i] + th1 * self.rc[2][i])));
        }
        y
    }

    /// End of the step.
    pub fn t1(&self) -> f64 {
        self.t0 + self.h
    }
}

/// Result of one trial step.
struct Trial<const N: usize> {
    y1: [f64; N],
    f1: [f64; N],
    err: f64,
    step: Step<N>,
}

fn axpy<const N: usize>(y: &[f64; N], h: f64, terms: &[(f64, &[f64; N])]) -> [f64; N] {
    let mut out = *y;
    for (c, k) in terms {
        for i in 0..N {
            out[i] += h * c * k[i];
        }
    }
    out
}

fn trial<const N: usize, F: FnMut(f64, &[f64; N]) -> [f64; N]>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    k1: &[f64; N],
    h: f64,
    tol: &Tolerance,
) -> Trial<N> {
    let k2 = f(t + C2 * h, &axpy(y, h, &[(A21, k1)]));
    let k3 = f(t + C3 * h, &axpy(y, h, &[(A31, k1), (A32, &k2)]));
    let k4 = f(
        t + C4 * h,
        &axpy(y, h, &[(A41, k1), (A42, &k2), (A43, &k3)]),
    );
    let k5 = f(
        t + C5 * h,
        &axpy(y, h, &[(A51, k1), (A52, &k2), (A53, &k3), (A54, &k4)]),
    );
    let k6 = f(
        t + h,
        &axpy(
            y,
            h,
            &[(A61, k1), (A62, &k2), (A63, &k3), (A64, &k4), (A65, &k5)],
        ),
    );
    let y1 = axpy(
        y,
        h,
        &[(A71, k1), (A73, &k3), (A74, &k4), (A75, &k5), (A76, &k6)],
    );
    let k7 = f(t + h, &y1);
    let mut sum = 0.0;
    let mut rc = [[0.0; N]; 3];
    for i in 0..N {
        let e = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
        let sc = tol.atol + tol.rtol * y[i].abs().max(y1[i].abs());
        sum += (e / sc).powi(2);
        let d = y1[i] - y[i];
        let bspl = h * k1[i] - d;
        rc[0][i] = bspl;
        rc[1][i] = d - h * k7[i] - bspl;
        rc[2][i] =
            h * (D1 * k1[i] + D3 * k3[i] + D4 * k4[i] + D5 * k5[i] + D6 * k6[i] + D7 * k7[i]);
    }
    let err = (sum / N as f64).sqrt();
    let err = if err.is_finite() && y1.iter().all(|v| v.is_finite()) {
        err
    } else {
        f64::INFINITY
    };
    Trial {
        y1,
        f1: k7,
        err,
        step: Step {
            t0: t,
            h,
            y0: *y,
            y1,
            rc,
        },
    }
}

/// What the observer wants after each accepted step.
pub(crate) enum Control {
    /// Go on.
    Continue,
    /// Stop now; the last step stays the last.
    Stop,
    /// Stop at this `t` inside the last step: the integrator retakes the step to land on it.
    StopAt(f64),
}

/// Why an integration ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Outcome {
    /// The observer stopped it.
    Stopped,
    /// Reached `t_end`.
    Reached,
    /// The step size fell below what the tolerance can resolve.
    Failed,
    /// The step budget ran out.
    TooManySteps,
}

/// An adaptive integrator from `t0` towards `t_end`.
pub(crate) struct Integrator<const N: usize, F> {
    f: F,
    tol: Tolerance,
}

impl<const N: usize, F: FnMut(f64, &[f64; N]) -> [f64; N]> Integrator<N, F> {
    /// An integrator of `y' = f(t, y)`.
    pub fn new(f: F, tol: Tolerance) -> Self {
        Self { f, tol }
    }

    /// Integrates from `(t0, y0)` to at most `t_end` (> t0). `observe` sees each accepted
    /// step and may stop the run; a `StopAt(t)` makes the integrator retake the last step
    /// with its end exactly at `t`, then observe that shortened step again (the observer
    /// must return `Stop` for it). Returns the last state and time.
    pub fn run(
        &mut self,
        t0: f64,
        y0: [f64; N],
        t_end: f64,
        h0: f64,
        mut observe: impl FnMut(&Step<N>) -> Control,
    ) -> (Outcome, f64, [f64; N]) {
        let tol = self.tol;
        let mut t = t0;
        let mut y = y0;
        let mut k1 = (self.f)(t, &y);
        let mut h = h0.min(tol.h_max).min(t_end - t0);
        let mut retake: Option<f64> = None;
        for _ in 0..tol.max_steps {
            if let Some(ts) = retake {
                h = ts - t;
            }
            if h <= 0.0 {
                return (Outcome::Stopped, t, y);
            }
            let tr = trial(&mut self.f, t, &y, &k1, h, &tol);
            if tr.err > 1.0 && retake.is_none() {
                let fac = if tr.err.is_finite() {
                    (0.9 * tr.err.powf(-0.2)).max(0.2)
                } else {
                    0.1
                };
                h *= fac;
                if h < 1e-14 * (t.abs() + 1.0) {
                    return (Outcome::Failed, t, y);
                }
                continue;
            }
            let was_retake = retake.take().is_some();
            let ctl = observe(&tr.step);
            let t_new = t + h;
            if was_retake {
                return (Outcome::Stopped, t_new, tr.y1);
            }
            match ctl {
                Control::Stop => return (Outcome::Stopped, t_new, tr.y1),
                Control::StopAt(ts) => {
                    retake = Some(ts.clamp(t, t_new));
                    continue;
                }
                Control::Continue => {}
            }
            t = t_new;
            y = tr.y1;
            k1 = tr.f1;
            if t >= t_end {
                return (Outcome::Reached, t, y);
            }
            let fac = if tr.err > 0.0 {
                (0.9 * tr.err.powf(-0.2)).clamp(0.2, 5.0)
            } else {
                5.0
            };
            h = (h * fac).min(tol.h_max).min(t_end - t);
        }
        (Outcome::TooManySteps, t, y)
    }
}

/// Bisection on a monotone test: from `lo`, where `fits` fails, and `hi`, where
/// it holds, at most `steps` halvings, until the bracket is within `rtol` of
/// `hi`; the last `hi`.
pub(crate) fn bisect(
    fits: impl Fn(f64) -> bool,
    mut lo: f64,
    mut hi: f64,
    steps: usize,
    rtol: f64,
) -> f64 {
    for _ in 0..steps {
        let mid = 0.5 * (lo + hi);
        if fits(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi - lo <= rtol * hi {
            break;
        }
    }
    hi
}

/// Finds `t` in `[a, b]` where `g` changes sign (`g(a)`, `g(b)` of opposite signs),
/// by the Illinois variant of regula falsi, until the bracket is narrower than
/// `xtol` or `|g| <= ftol`.
pub fn find_root(mut g: impl FnMut(f64) -> f64, a: f64, b: f64, xtol: f64, ftol: f64) -> f64 {
    let fa = g(a);
    let fb = g(b);
    find_root_known(g, (a, fa), (b, fb), xtol, ftol)
}

/// [`find_root`] with `g` already known at both ends of the bracket.
pub(crate) fn find_root_known(
    mut g: impl FnMut(f64) -> f64,
    (mut a, mut fa): (f64, f64),
    (mut b, mut fb): (f64, f64),
    xtol: f64,
    ftol: f64,
) -> f64 {
    if fa == 0.0 {
        return a;
    }
    if fb == 0.0 {
        return b;
    }
    let mut side = 0;
    for _ in 0..200 {
        let mut c = (a * fb - b * fa) / (fb - fa);
        if !c.is_finite() || c <= a.min(b) || c >= a.max(b) {
            c = 0.5 * (a + b);
        }
        let fc = g(c);
        if fc.abs() <= ftol || (b - a).abs() < xtol {
            return c;
        }
        if fc.signum() == fb.signum() {
            b = c;
            fb = fc;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            fa = fc;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        }
        if (b - a).abs() < xtol {
            return if fa.abs() < fb.abs() { a } else { b };
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_to_tolerance_and_dense_output() {
        let mut it = Integrator::new(|_t, y: &[f64; 1]| [y[0]], Tolerance::default());
        let mut worst: f64 = 0.0;
        let (out, t, y) = it.run(0.0, [1.0], 2.0, 0.1, |s| {
            for k in 1..10 {
                let tm = s.t0 + s.h * k as f64 / 10.0;
                worst = worst.max((s.at(tm)[0] - tm.exp()).abs());
            }
            Control::Continue
        });
        assert_eq!(out, Outcome::Reached);
        assert!((t - 2.0).abs() < 1e-15);
        assert!((y[0] - 2f64.exp()).abs() < 1e-10, "{}", y[0] - 2f64.exp());
        assert!(worst < 1e-9, "dense output error {worst}");
    }

    #[test]
    fn stop_at_lands_on_event() {
        let mut it = Integrator::new(|_t, y: &[f64; 2]| [y[1], -y[0]], Tolerance::default());
        // y = sin t; stop where y = 0.5 -> t = pi/6.
        let (_, t, y) = it.run(0.0, [0.0, 1.0], 10.0, 0.01, |s| {
            if s.y0[0] < 0.5 && s.y1[0] >= 0.5 {
                let ts = find_root(|t| s.at(t)[0] - 0.5, s.t0, s.t1(), 1e-15, 0.0);
                Control::StopAt(ts)
            } else if s.y1[0] >= 0.5 {
                Control::Stop
            } else {
                Control::Continue
            }
        });
        assert!((t - std::f64::consts::FRAC_PI_6).abs() < 1e-10);
        assert!((y[0] - 0.5).abs() < 1e-10);
    }
}
