//! Property: the blocks keep the tolerance. For random smooth axis tracks
//! (sums of sines and a line per axis, one to five axes, unevenly spaced
//! samples) and random tolerances, `fit_blocks` returns block ends that are
//! original samples (strictly increasing indices from the first to the
//! last), and every original sample lies within its axis tolerance of the
//! straight block over it, interpolated at the sample's parameter, and
//! within the position tolerance through the deviation callback. (That the
//! cuts are those of a direct check is `fit_incremental.rs`.)

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::needless_range_loop,
    missing_docs
)]

use formcam_motion::{Deviation, Tolerance, fit_blocks};
use proptest::prelude::*;

/// Per axis: amplitude, frequency, phase of two sines and a slope.
type Wave = (f64, f64, f64, f64, f64, f64, f64);

fn wave() -> impl Strategy<Value = Wave> {
    (
        0.0f64..100.0,
        0.001f64..0.2,
        0.0f64..6.3,
        0.0f64..5.0,
        0.01f64..2.0,
        0.0f64..6.3,
        -3.0f64..3.0,
    )
}

fn value(w: &Wave, x: f64) -> f64 {
    let (a1, f1, p1, a2, f2, p2, slope) = *w;
    a1 * (f1 * x + p1).sin() + a2 * (f2 * x + p2).sin() + slope * x
}

/// The payout point of the axis values: a nonlinear mix of them.
fn point(q: &[f64]) -> [f64; 2] {
    let s: f64 = q.iter().sum();
    [
        100.0 * (0.01 * q[0]).cos() + s,
        50.0 * (0.02 * q[q.len() - 1]).sin(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn every_sample_lies_within_tolerance_of_its_block(
        waves in proptest::collection::vec(wave(), 1..6),
        gaps in proptest::collection::vec(0.01f64..2.0, 1..600),
        tols in proptest::collection::vec(1e-4f64..1.0, 5),
        position in proptest::option::of(1e-3f64..1.0),
    ) {
        let width = waves.len();
        let mut x = vec![0.0];
        for g in &gaps {
            x.push(x[x.len() - 1] + g);
        }
        let n = x.len();
        let values: Vec<f64> = x.iter().flat_map(|&xi| waves.iter().map(move |w| value(w, xi))).collect();
        let row = |k: usize| &values[k * width..(k + 1) * width];
        let tol = Tolerance { axes: tols[..width].to_vec(), position_mm: position };
        let wanted: Vec<[f64; 2]> = (0..n).map(|k| point(row(k))).collect();
        let dev = |q: &[f64], k: usize| {
            let p = point(q);
            (p[0] - wanted[k][0]).hypot(p[1] - wanted[k][1])
        };
        let ends = fit_blocks(&x, &values, width, &tol, Some(&dev as Deviation<'_>)).unwrap();
        prop_assert_eq!(ends.first(), Some(&0));
        prop_assert_eq!(ends.last(), Some(&(n - 1)));
        prop_assert!(ends.windows(2).all(|e| e[0] < e[1]), "{:?}", ends);
        let mut q = vec![0.0; width];
        for e in ends.windows(2) {
            let (s, t) = (e[0], e[1]);
            let (a, b) = (row(s), row(t));
            for k in s..=t {
                let f = (x[k] - x[s]) / (x[t] - x[s]);
                for j in 0..width {
                    q[j] = a[j] + f * (b[j] - a[j]);
                    prop_assert!(
                        (q[j] - row(k)[j]).abs() <= tol.axes[j],
                        "block {}..{}: sample {} axis {} off by {} > {}",
                        s, t, k, j, (q[j] - row(k)[j]).abs(), tol.axes[j]
                    );
                }
                if let Some(p) = position {
                    prop_assert!(dev(&q, k) <= p, "block {}..{}: sample {} payout off by {}", s, t, k, dev(&q, k));
                }
            }
        }
    }
}
