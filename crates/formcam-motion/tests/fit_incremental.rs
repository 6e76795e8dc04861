//! The incremental block fit against the direct one: on random tracks (smooth
//! runs, kinks, steps, noise; one to four axes, optionally a position
//! tolerance through the deviation callback) `fit_blocks` cuts exactly where
//! checking every sample of every probed block cuts.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use formcam_motion::{Deviation, Tolerance, fit_blocks};
use proptest::prelude::*;

/// The direct fit: the same farthest-reaching search, every probed block
/// checked sample by sample (the middle one first).
fn direct(
    x: &[f64],
    values: &[f64],
    width: usize,
    tol: &Tolerance,
    deviation: Option<Deviation<'_>>,
) -> Vec<usize> {
    let n = x.len();
    if n < 2 {
        return (0..n).collect();
    }
    let row = |k: usize| &values[k * width..(k + 1) * width];
    let mut q = vec![0.0; width];
    let mut fits = |s: usize, e: usize| -> bool {
        let (a, b) = (row(s), row(e));
        let span = x[e] - x[s];
        let mid = (s + e) / 2;
        let order = (mid..=mid).filter(|&k| k > s && k < e).chain(s + 1..e);
        for k in order {
            let t = (x[k] - x[s]) / span;
            let r = row(k);
            for j in 0..width {
                q[j] = a[j] + t * (b[j] - a[j]);
                if (q[j] - r[j]).abs() > tol.axes[j] {
                    return false;
                }
            }
            if let (Some(p), Some(dev)) = (tol.position_mm, deviation)
                && dev(&q, k) > p
            {
                return false;
            }
        }
        true
    };
    let mut ends = vec![0];
    let mut s = 0;
    while s + 1 < n {
        let mut ok = s + 1;
        let mut step = 1;
        let mut bad = None;
        while ok < n - 1 {
            let e = (ok + step).min(n - 1);
            if fits(s, e) {
                ok = e;
                step *= 2;
            } else {
                bad = Some(e);
                break;
            }
        }
        if let Some(mut hi) = bad {
            while hi - ok > 1 {
                let mid = ok + (hi - ok) / 2;
                if fits(s, mid) {
                    ok = mid;
                } else {
                    hi = mid;
                }
            }
        }
        ends.push(ok);
        s = ok;
    }
    ends
}

/// A track of `n` samples and `width` axes: per axis a sum of a line, a
/// sine, kinks and steps at random places, and noise, on unevenly spaced `x`.
fn track(n: usize, width: usize, seed: &[f64], amp: f64, noise: f64) -> (Vec<f64>, Vec<f64>) {
    let at = |i: usize| seed[i % seed.len()];
    let mut x = Vec::with_capacity(n);
    let mut xi = 0.0;
    for i in 0..n {
        xi += 0.2 + at(i);
        x.push(xi);
    }
    let mut v = Vec::with_capacity(n * width);
    for (i, &xi) in x.iter().enumerate() {
        for j in 0..width {
            let f = 0.05 + at(3 * j + 1);
            let kink = xi - x[(n / (j + 2)).min(n - 1)];
            let step = if i > n / (j + 3) { amp * at(j) } else { 0.0 };
            let jitter = noise * (at(7 * i + 5 * j) - 0.5);
            v.push(amp * (f * xi).sin() + 0.3 * (j as f64) * xi + kink.abs() + step + jitter);
        }
    }
    (x, v)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn incremental_fit_cuts_as_the_direct_fit(
        n in 2usize..400,
        width in 1usize..5,
        seed in proptest::collection::vec(0.0f64..1.0, 1..64),
        amp in 0.01f64..50.0,
        noise in 0.0f64..0.2,
        tols in proptest::collection::vec(1e-4f64..1.0, 4),
        position in proptest::option::of(1e-3f64..1.0),
    ) {
        let (x, v) = track(n, width, &seed, amp, noise);
        let tol = Tolerance { axes: tols[..width].to_vec(), position_mm: position };
        // A payout point that mixes the axes nonlinearly.
        let point = |q: &[f64]| -> (f64, f64) {
            let s: f64 = q.iter().sum();
            (q[0].cos() * 10.0 + s, q[q.len() - 1].sin() * 10.0)
        };
        let wanted: Vec<(f64, f64)> = v.chunks(width).map(point).collect();
        let dev = |q: &[f64], k: usize| {
            let (a, b) = point(q);
            ((a - wanted[k].0).powi(2) + (b - wanted[k].1).powi(2)).sqrt()
        };
        let deviation = Some(&dev as Deviation<'_>);
        prop_assert_eq!(
            fit_blocks(&x, &v, width, &tol, deviation).unwrap(),
            direct(&x, &v, width, &tol, deviation)
        );
        prop_assert_eq!(
            fit_blocks(&x, &v, width, &tol, None).unwrap(),
            direct(&x, &v, width, &tol, None)
        );
    }
}

/// Samples that sit exactly on the tolerance's edge (a triangle wave whose
/// chords miss it by exactly the tolerance, in binary fractions): the
/// borderline decisions go to the direct check and agree with it.
#[test]
fn samples_on_the_tolerance_edge_cut_as_the_direct_fit() {
    let n = 257;
    let x: Vec<f64> = (0..n).map(|i| i as f64 * 0.25).collect();
    let v: Vec<f64> = (0..n)
        .map(|i| {
            if i % 8 < 4 {
                (i % 8) as f64 * 0.125
            } else {
                (8 - i % 8) as f64 * 0.125
            }
        })
        .collect();
    for tol in [0.25, 0.5, 0.125, 0.0625] {
        let tol = Tolerance {
            axes: vec![tol],
            position_mm: None,
        };
        let ends = fit_blocks(&x, &v, 1, &tol, None).unwrap();
        assert_eq!(ends, direct(&x, &v, 1, &tol, None));
        assert_eq!(ends.first(), Some(&0));
        assert_eq!(ends.last(), Some(&(n - 1)));
    }
}
