//! The eye on the free band (eqs. 8–10): for a path point with tangent `tau`
//! the eye lies at `P + l tau`; its cylindrical coordinates `Z, R, V` as
//! functions of the free length `l`, and the free lengths that reach a radius or
//! a curve `R = f(Z)`.

use super::envelope::Profile;
use crate::CircuitPoint;

/// The free band leaving a circuit point: its unit direction split into the
/// axial (`ca`), radial (`ra`) and circumferential (`sa`) parts of the point's
/// frame (eqs. 8–9), computed once per point.
#[derive(Debug, Clone, Copy)]
pub(super) struct Band {
    pub(super) p: CircuitPoint,
    pub(super) ca: f64,
    ra: f64,
    sa: f64,
}

impl Band {
    #[inline]
    pub(super) fn new(p: &CircuitPoint) -> Self {
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
    #[inline]
    fn dw(&self, l: f64) -> (f64, f64) {
        (self.p.r + l * self.ra, l * self.sa)
    }

    /// Eye `Z` and `R` at free length `l`.
    #[inline]
    pub(super) fn eye_zr(&self, l: f64) -> (f64, f64) {
        let (d, w) = self.dw(l);
        (self.p.z + l * self.ca, (d * d + w * w).sqrt())
    }

    /// Eye `Z`, `R` and `dR/dl` at free length `l`.
    #[inline]
    pub(super) fn zr(&self, l: f64) -> (f64, f64, f64) {
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
    #[inline]
    pub(super) fn v(&self, l: f64) -> f64 {
        let (d, w) = self.dw(l);
        // w >= 0; the plain arctangent is cheaper where the quadrant is known.
        self.p.v + if d > 0.0 { (w / d).atan() } else { w.atan2(d) }
    }

    /// Free length that puts the eye at radius `radius`, if any.
    pub(super) fn length_to_radius(&self, radius: f64) -> Option<f64> {
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
    pub(super) fn length_to_profile(
        &self,
        f: &Profile,
        guess: f64,
        start: f64,
        l_hi: f64,
    ) -> Option<f64> {
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
#[inline]
pub fn eye_at(p: &CircuitPoint, l: f64) -> (f64, f64, f64, f64, f64) {
    let b = Band::new(p);
    let (z, r, dr_dl) = b.zr(l);
    (z, r, b.v(l), b.ca, dr_dl)
}

/// Free length that puts the eye at radius `radius` (axis-parallel), if any.
pub fn axis_parallel_length(p: &CircuitPoint, radius: f64) -> Option<f64> {
    Band::new(p).length_to_radius(radius)
}
