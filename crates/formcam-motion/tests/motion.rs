//! Blocks within tolerance, and block times within every limit.

#![allow(clippy::unwrap_used)]

use formcam_motion::{
    AxisLimits, Tolerance, check_acceleration, check_timing, deltas, fit_blocks, global,
    global_by_cone, pairwise, preliminary_times, with_acceleration,
};
use proptest::prelude::*;

/// A smooth two-axis trajectory: a spindle turning on and a carriage going back
/// and forth (the carriage reverses twice per cycle).
fn trajectory(n: usize) -> (Vec<f64>, Vec<f64>) {
    let x: Vec<f64> = (0..n).map(|i| 1000.0 * i as f64 / (n - 1) as f64).collect();
    let mut v = Vec::with_capacity(2 * n);
    for &xi in &x {
        let t = xi / 1000.0 * std::f64::consts::TAU;
        v.push(6.0 * t + 0.3 * (3.0 * t).sin()); // rad
        v.push(400.0 * t.sin()); // mm
    }
    (x, v)
}

#[test]
fn blocks_stay_within_tolerance_by_dense_resampling() {
    let (x, v) = trajectory(20_001);
    let tol = Tolerance {
        axes: vec![1e-3, 0.01],
        position_mm: None,
    };
    let ends = fit_blocks(&x, &v, 2, &tol, None).unwrap();
    assert_eq!(ends[0], 0);
    assert_eq!(*ends.last().unwrap(), x.len() - 1);
    assert!(ends.len() < 2000, "{} blocks", ends.len());
    for w in ends.windows(2) {
        let (s, e) = (w[0], w[1]);
        for k in s..=e {
            let t = (x[k] - x[s]) / (x[e] - x[s]);
            for j in 0..2 {
                let q = v[2 * s + j] + t * (v[2 * e + j] - v[2 * s + j]);
                assert!(
                    (q - v[2 * k + j]).abs() <= tol.axes[j],
                    "block {s}..{e} at {k}"
                );
            }
        }
    }
    // Halving the tolerance needs more blocks; a straight line needs one.
    let finer = Tolerance {
        axes: vec![5e-4, 0.005],
        position_mm: None,
    };
    assert!(fit_blocks(&x, &v, 2, &finer, None).unwrap().len() > ends.len());
    let line: Vec<f64> = x.iter().flat_map(|&xi| [0.5 * xi, -2.0 * xi]).collect();
    assert_eq!(
        fit_blocks(&x, &line, 2, &tol, None).unwrap(),
        vec![0, x.len() - 1]
    );
}

#[test]
fn a_position_tolerance_is_kept_through_the_callback() {
    let (x, v) = trajectory(5001);
    // The "payout point": the carriage value and the spindle angle on a 100 mm arm.
    let p = |q: &[f64]| (q[1], 100.0 * q[0].cos(), 100.0 * q[0].sin());
    let dev = |q: &[f64], k: usize| {
        let (a, b) = (p(q), p(&v[2 * k..2 * k + 2]));
        ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2) + (a.2 - b.2).powi(2)).sqrt()
    };
    let tol = Tolerance {
        axes: vec![1.0, 1.0],
        position_mm: Some(0.05),
    };
    let ends = fit_blocks(&x, &v, 2, &tol, Some(&dev)).unwrap();
    for w in ends.windows(2) {
        for k in w[0]..=w[1] {
            let t = (x[k] - x[w[0]]) / (x[w[1]] - x[w[0]]);
            let q: Vec<f64> = (0..2)
                .map(|j| v[2 * w[0] + j] + t * (v[2 * w[1] + j] - v[2 * w[0] + j]))
                .collect();
            assert!(dev(&q, k) <= 0.05);
        }
    }
}

fn limits() -> Vec<AxisLimits> {
    vec![
        AxisLimits {
            v_max: 10.0,
            dv_max: 0.5,
        },
        AxisLimits {
            v_max: 500.0,
            dv_max: 40.0,
        },
    ]
}

/// The trajectory's blocks (within 1e-3 rad and 0.01 mm), their axis motions,
/// the limits and the preliminary times.
fn blocks_of_the_trajectory() -> (Vec<f64>, Vec<AxisLimits>, Vec<f64>) {
    let (x, v) = trajectory(20_001);
    let tol = Tolerance {
        axes: vec![1e-3, 0.01],
        position_mm: None,
    };
    let ends = fit_blocks(&x, &v, 2, &tol, None).unwrap();
    let d = deltas(&v, 2, &ends);
    let lim = limits();
    let t_star = preliminary_times(&d, &lim, 0.004).unwrap();
    (d, lim, t_star)
}

#[test]
fn times_keep_every_limit_and_pairwise_is_never_better_than_global() {
    let (d, lim, t_star) = blocks_of_the_trajectory();
    let pw = pairwise(&d, &t_star, &lim).unwrap();
    let gl = global(&d, &t_star, &lim).unwrap();
    assert!(check_timing(&d, &pw.times, &lim).is_empty());
    assert!(check_timing(&d, &gl.times, &lim).is_empty());
    let pre: f64 = t_star.iter().sum();
    assert!(pre <= gl.total + 1e-9);
    assert!(
        gl.total <= pw.total * (1.0 + 1e-9),
        "{} vs {}",
        gl.total,
        pw.total
    );
}

#[test]
fn without_reversals_pairwise_equals_global() {
    // Both axes move forwards only.
    let n = 4001;
    let x: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let v: Vec<f64> = x
        .iter()
        .flat_map(|&t| {
            [
                0.01 * t + 0.002 * (t / 50.0).sin(),
                2.0 * t + 30.0 * (t / 300.0).sin().powi(2),
            ]
        })
        .collect();
    let tol = Tolerance {
        axes: vec![1e-4, 0.01],
        position_mm: None,
    };
    let ends = fit_blocks(&x, &v, 2, &tol, None).unwrap();
    let d = deltas(&v, 2, &ends);
    assert!(d.iter().all(|&dv| dv >= 0.0));
    let lim = vec![
        AxisLimits {
            v_max: 0.05,
            dv_max: 0.001,
        },
        AxisLimits {
            v_max: 20.0,
            dv_max: 0.2,
        },
    ];
    let t_star = preliminary_times(&d, &lim, 0.004).unwrap();
    let pw = pairwise(&d, &t_star, &lim).unwrap();
    let gl = global(&d, &t_star, &lim).unwrap();
    assert!(
        pw.mu.iter().any(|&m| m < 0.999),
        "the jumps must bind somewhere"
    );
    assert!(
        (pw.total - gl.total).abs() <= 1e-9 * gl.total,
        "{} vs {}",
        pw.total,
        gl.total
    );
}

#[test]
fn bad_limits_are_errors() {
    let d = vec![1.0, 1.0];
    for (v, dv, tau) in [(0.0, 1.0, 0.01), (1.0, -1.0, 0.01), (1.0, 1.0, 0.0)] {
        let lim = vec![
            AxisLimits {
                v_max: v,
                dv_max: dv,
            };
            2
        ];
        assert!(preliminary_times(&d, &lim, tau).is_err());
    }
    let (x, v) = trajectory(11);
    let tol = Tolerance {
        axes: vec![0.0, 1.0],
        position_mm: None,
    };
    assert!(fit_blocks(&x, &v, 2, &tol, None).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_programs_keep_the_limits(
        d in proptest::collection::vec(-50.0f64..50.0, 6..60),
        rho in 0.5f64..20.0,
    ) {
        let lim = vec![AxisLimits { v_max: 100.0, dv_max: rho }, AxisLimits { v_max: 30.0, dv_max: rho / 3.0 }];
        let n = d.len() / 2;
        let d = &d[..2 * n];
        let t_star = preliminary_times(d, &lim, 0.01).unwrap();
        let pw = pairwise(d, &t_star, &lim).unwrap();
        let gl = global(d, &t_star, &lim).unwrap();
        prop_assert!(check_timing(d, &pw.times, &lim).is_empty());
        prop_assert!(check_timing(d, &gl.times, &lim).is_empty());
        prop_assert!(gl.total <= pw.total * (1.0 + 1e-6));
    }
}

#[test]
fn windows_round_the_reversals_give_the_cone_optimum() {
    // A long program whose carriage reverses a few times: the windowed optimum
    // equals the one cone program over all blocks.
    let n = 3000;
    let d: Vec<f64> = (0..n)
        .flat_map(|i| {
            let t = i as f64 / n as f64 * std::f64::consts::TAU * 3.0;
            [
                0.01 + 0.002 * (3.0 * t).sin(),
                5.0 * t.cos(),
                0.5 + 0.3 * t.sin(),
            ]
        })
        .collect();
    let lim = vec![
        AxisLimits {
            v_max: 10.0,
            dv_max: 0.5,
        },
        AxisLimits {
            v_max: 500.0,
            dv_max: 40.0,
        },
        AxisLimits {
            v_max: 200.0,
            dv_max: 20.0,
        },
    ];
    let t_star = preliminary_times(&d, &lim, 0.002).unwrap();
    let win = global(&d, &t_star, &lim).unwrap();
    let cone = global_by_cone(&d, &t_star, &lim).unwrap();
    let pw = pairwise(&d, &t_star, &lim).unwrap();
    assert!(check_timing(&d, &win.times, &lim).is_empty());
    assert!(
        (win.total - cone.total).abs() <= 1e-6 * cone.total,
        "{} vs {}",
        win.total,
        cone.total
    );
    assert!(
        win.total <= pw.total * (1.0 + 1e-9),
        "{} vs {}",
        win.total,
        pw.total
    );
}

#[test]
fn acceleration_limits_slow_the_blocks_and_keep_every_other_limit() {
    let (d, lim, t_star) = blocks_of_the_trajectory();
    let gl = global(&d, &t_star, &lim).unwrap();
    let a_max = [2.0, 200.0];
    assert!(
        !check_acceleration(&d, &gl.times, &a_max).is_empty(),
        "the limit must bind"
    );
    let acc = with_acceleration(&d, &gl, &lim, &a_max).unwrap();
    assert!(check_acceleration(&d, &acc.times, &a_max).is_empty());
    assert!(check_timing(&d, &acc.times, &lim).is_empty());
    assert!(acc.total > gl.total);
    assert!(with_acceleration(&d, &gl, &lim, &[0.0, 1.0]).is_err());
}
