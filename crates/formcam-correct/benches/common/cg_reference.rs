//! The noise smoothing as it was before the multigrid solver: plain
//! conjugate gradients, matrix-free, to a relative residual of 1e-12 (at
//! most `4 n` steps), in the same bisection on `lambda`. Kept as the
//! reference the multigrid's surfaces must equal (the unit tests of
//! `smooth`) and as the "before" of the smoothing benchmark.

#![allow(dead_code)]

/// `y = (I + lambda L) x` on an `nu x nv` grid.
pub fn apply(x: &[f64], y: &mut [f64], nu: usize, nv: usize, lambda: f64) {
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
pub fn solve(d: &[f64], m: &mut [f64], nu: usize, nv: usize, lambda: f64) {
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
pub fn fit(fields: &[Vec<f64>], nu: usize, nv: usize, noise: f64) -> (Vec<Vec<f64>>, f64, bool) {
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
