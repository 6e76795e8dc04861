//! Separating measurement noise from the warp: a penalised least-squares fit
//! of the grid deviations,
//!
//! ```text
//! minimise  sum |m - d|^2 + lambda * sum (|m_uu|^2 + 2 |m_uv|^2 + |m_vv|^2)
//! ```
//!
//! (second differences over the grid, a discrete thin plate), with `lambda`
//! chosen by the discrepancy principle: the mean squared residual equals the
//! stated noise variance. Solved by conjugate gradients, matrix-free.
//! Where the report gives normals, the scalar normal deviation is smoothed;
//! otherwise each component.

use crate::Grid;
use crate::vec3::{V3, dot, scale};

/// What the smoothing did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Smoothing {
    /// The stated noise level (standard deviation, mm).
    pub noise_mm: f64,
    /// The chosen weight of the roughness penalty.
    pub lambda: f64,
    /// RMS of the removed part (the estimated noise), mm.
    pub removed_rms_mm: f64,
    /// The data were smoother than the noise level says: the smoothest
    /// (bilinear-plane) fit was taken.
    pub saturated: bool,
}

/// `y = (I + lambda L) x` on an `nu x nv` grid.
fn apply(x: &[f64], y: &mut [f64], nu: usize, nv: usize, lambda: f64) {
    y.copy_from_slice(x);
    let k = |i: usize, j: usize| j * nu + i;
    for j in 0..nv {
        for i in 1..nu.saturating_sub(1) {
            let c = lambda * (x[k(i - 1, j)] - 2.0 * x[k(i, j)] + x[k(i + 1, j)]);
            y[k(i - 1, j)] += c;
            y[k(i, j)] -= 2.0 * c;
            y[k(i + 1, j)] += c;
        }
    }
    for j in 1..nv.saturating_sub(1) {
        for i in 0..nu {
            let c = lambda * (x[k(i, j - 1)] - 2.0 * x[k(i, j)] + x[k(i, j + 1)]);
            y[k(i, j - 1)] += c;
            y[k(i, j)] -= 2.0 * c;
            y[k(i, j + 1)] += c;
        }
    }
    for j in 0..nv - 1 {
        for i in 0..nu - 1 {
            let c =
                2.0 * lambda * (x[k(i, j)] - x[k(i + 1, j)] - x[k(i, j + 1)] + x[k(i + 1, j + 1)]);
            y[k(i, j)] += c;
            y[k(i + 1, j)] -= c;
            y[k(i, j + 1)] -= c;
            y[k(i + 1, j + 1)] += c;
        }
    }
}

/// Solves `(I + lambda L) m = d` by conjugate gradients from `m`.
fn solve(d: &[f64], m: &mut [f64], nu: usize, nv: usize, lambda: f64) {
    let n = d.len();
    let mut r = vec![0.0; n];
    let mut ap = vec![0.0; n];
    apply(m, &mut r, nu, nv, lambda);
    for (r, d) in r.iter_mut().zip(d) {
        *r = d - *r;
    }
    let mut p = r.clone();
    let mut rr: f64 = r.iter().map(|v| v * v).sum();
    let stop = 1e-24 * d.iter().map(|v| v * v).sum::<f64>().max(1e-300);
    for _ in 0..(4 * n).max(100) {
        if rr <= stop {
            break;
        }
        apply(&p, &mut ap, nu, nv, lambda);
        let pap: f64 = p.iter().zip(&ap).map(|(a, b)| a * b).sum();
        if pap <= 0.0 {
            break;
        }
        let alpha = rr / pap;
        for k in 0..n {
            m[k] += alpha * p[k];
            r[k] -= alpha * ap[k];
        }
        let rr_new: f64 = r.iter().map(|v| v * v).sum();
        let beta = rr_new / rr;
        rr = rr_new;
        for k in 0..n {
            p[k] = r[k] + beta * p[k];
        }
    }
}

/// Smooths the fields `d` (each of `nu * nv` values) with one `lambda` chosen
/// so the mean squared residual over all fields is `noise^2` (per value).
fn fit(fields: &[Vec<f64>], nu: usize, nv: usize, noise: f64) -> (Vec<Vec<f64>>, f64, bool) {
    let count = (fields.len() * nu * nv) as f64;
    let run = |lambda: f64, start: &[Vec<f64>]| {
        let out: Vec<Vec<f64>> = fields
            .iter()
            .zip(start)
            .map(|(d, s)| {
                let mut m = s.clone();
                solve(d, &mut m, nu, nv, lambda);
                m
            })
            .collect();
        let ms: f64 = fields
            .iter()
            .zip(&out)
            .map(|(d, m)| d.iter().zip(m).map(|(a, b)| (a - b) * (a - b)).sum::<f64>())
            .sum::<f64>()
            / count;
        (out, ms)
    };
    let target = noise * noise;
    let (mut lo, mut hi) = (-8.0f64, 10.0f64);
    let (hi_fit, hi_ms) = run(10f64.powf(hi), fields);
    if hi_ms <= target {
        return (hi_fit, 10f64.powf(hi), true);
    }
    let mut best = hi_fit;
    let mut warm = fields.to_vec();
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        let (m, ms) = run(10f64.powf(mid), &warm);
        if ms > target {
            hi = mid;
        } else {
            lo = mid;
        }
        warm = m.clone();
        best = m;
        if hi - lo < 1e-3 {
            break;
        }
    }
    (best, 10f64.powf(0.5 * (lo + hi)), false)
}

/// Replaces the grid's deviations by their smoothed values, for measurement
/// noise of standard deviation `noise_mm` (along the normal where the grid
/// has normals, else per component). `noise_mm = 0` leaves them as they are.
pub fn smooth(grid: &mut Grid, noise_mm: f64) -> Smoothing {
    let (nu, nv) = (grid.nu, grid.nv);
    if noise_mm <= 0.0 || nu < 2 || nv < 2 {
        return Smoothing {
            noise_mm,
            lambda: 0.0,
            removed_rms_mm: 0.0,
            saturated: false,
        };
    }
    let before = grid.deviation.clone();
    let (fits, lambda, saturated) = match &grid.normal {
        Some(normals) => {
            let d: Vec<f64> = grid
                .deviation
                .iter()
                .zip(normals)
                .map(|(d, n)| dot(*d, *n))
                .collect();
            let (f, l, s) = fit(&[d], nu, nv, noise_mm);
            for ((dev, n), v) in grid.deviation.iter_mut().zip(normals).zip(&f[0]) {
                *dev = scale(*n, *v);
            }
            (f, l, s)
        }
        None => {
            let comps: Vec<Vec<f64>> = (0..3)
                .map(|c| grid.deviation.iter().map(|d| d[c]).collect())
                .collect();
            let (f, l, s) = fit(&comps, nu, nv, noise_mm);
            for (k, dev) in grid.deviation.iter_mut().enumerate() {
                *dev = [f[0][k], f[1][k], f[2][k]];
            }
            (f, l, s)
        }
    };
    let _ = fits;
    let removed: f64 = before
        .iter()
        .zip(&grid.deviation)
        .map(|(a, b): (&V3, &V3)| {
            let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            dot(d, d)
        })
        .sum::<f64>()
        / before.len() as f64;
    Smoothing {
        noise_mm,
        lambda,
        removed_rms_mm: removed.sqrt(),
        saturated,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smoothing_recovers_a_smooth_field_under_noise() {
        let (nu, nv) = (40, 30);
        let mut nominal = Vec::new();
        let mut truth = Vec::new();
        let mut dev = Vec::new();
        // A deterministic pseudo-random noise of standard deviation ~0.02.
        let mut state = 12345u64;
        let mut noise = || {
            let mut s = 0.0;
            for _ in 0..12 {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                s += (state >> 11) as f64 / (1u64 << 53) as f64;
            }
            (s - 6.0) * 0.02
        };
        for j in 0..nv {
            for i in 0..nu {
                let (x, y) = (i as f64 * 5.0, j as f64 * 5.0);
                nominal.push([x, y, 0.0]);
                let w = 0.4 * (x / 60.0).sin() * (y / 45.0).cos();
                truth.push(w);
                dev.push([0.0, 0.0, w + noise()]);
            }
        }
        let mut g = Grid {
            nu,
            nv,
            nominal,
            deviation: dev,
            normal: Some(vec![[0.0, 0.0, 1.0]; nu * nv]),
            resampled: false,
            reordered: false,
        };
        let err = |g: &Grid| {
            (g.deviation
                .iter()
                .zip(&truth)
                .map(|(d, t)| (d[2] - t).powi(2))
                .sum::<f64>()
                / truth.len() as f64)
                .sqrt()
        };
        let raw = err(&g);
        let s = smooth(&mut g, 0.02);
        let smoothed = err(&g);
        assert!(!s.saturated);
        assert!((s.removed_rms_mm - 0.02).abs() < 2e-4, "{s:?}");
        assert!(smoothed < 0.5 * raw, "raw {raw}, smoothed {smoothed}");
    }
}
