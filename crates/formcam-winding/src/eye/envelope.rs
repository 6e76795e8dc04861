//! The clearance zone round the mandrel (equidistant mode's upper envelope of
//! discs of the clearance radius on the meridian and on the shaft) and where the
//! free band leaves it: the least free lengths that keep the clearance.

use formcam_geom::Meridian;

use super::band::Band;
use super::spec::EyeSpec;
use crate::{CircuitPoint, WindingError};

/// A curve `R = f(Z)` sampled on a uniform grid, linear between nodes, constant beyond.
#[derive(Debug, Clone)]
pub(super) struct Profile {
    pub(super) z0: f64,
    pub(super) inv_dz: f64,
    pub(super) vals: Vec<f64>,
}

impl Profile {
    /// `f(z)` and its slope.
    #[inline]
    pub(super) fn at(&self, z: f64) -> (f64, f64) {
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

    pub(super) fn top(&self) -> f64 {
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
pub(super) fn clearance_envelope<M: Meridian>(m: &M, c: f64, reach: f64) -> Profile {
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

/// Where the free band first leaves the clearance zone, point after point (each
/// search starts from the previous point's root).
#[derive(Clone)]
pub(super) struct FirstExit<'a> {
    env: &'a Profile,
    pub(super) clearance: f64,
    l_hi: f64,
    /// The roots at the two previous points.
    last: (f64, f64),
}

impl<'a> FirstExit<'a> {
    pub(super) fn new(env: &'a Profile, spec: &EyeSpec) -> Self {
        Self {
            env,
            clearance: spec.clearance,
            l_hi: 4.0 * spec.l_max + 20.0 * env.top(),
            last: (0.0, 0.0),
        }
    }

    pub(super) fn at(&mut self, b: &Band) -> Result<f64, WindingError> {
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
pub(super) fn least_lengths(
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
