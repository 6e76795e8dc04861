//! Property: the acceleration limits hold and cost only slowing. For random
//! blocks (one to four axes, motions of either sign, some standing still)
//! timed by the global optimum under their velocity and jump limits, and
//! random acceleration limits, `sequence_with_acceleration` (a program from
//! rest to rest) and `with_acceleration` (a circuit) return times that keep
//! every acceleration row, still keep every velocity and jump limit, are
//! nowhere shorter than the times given, and are those times unchanged
//! when no row was broken.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use formcam_motion::{
    AxisLimits, check_acceleration, check_sequence_acceleration, check_timing, global,
    preliminary_times, sequence_with_acceleration, with_acceleration,
};
use proptest::prelude::*;

/// Blocks: their number, axes, motions and limits (`v_max`, `dv_max`,
/// `a_max` per axis).
type Case = (usize, Vec<f64>, Vec<(f64, f64, f64)>);

fn case() -> impl Strategy<Value = Case> {
    (1usize..=4, 2usize..40).prop_flat_map(|(w, n)| {
        (
            Just(w),
            prop::collection::vec(prop_oneof![4 => -50.0f64..50.0, 1 => Just(0.0)], n * w),
            prop::collection::vec((5.0f64..100.0, 0.5f64..20.0, 0.5f64..200.0), w),
        )
    })
}

fn limits(l: &[(f64, f64, f64)]) -> (Vec<AxisLimits>, Vec<f64>) {
    (
        l.iter()
            .map(|&(v_max, dv_max, _)| AxisLimits { v_max, dv_max })
            .collect(),
        l.iter().map(|l| l.2).collect(),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn every_row_holds_and_blocks_only_slow((w, d, l) in case()) {
        let (lim, a_max) = limits(&l);
        let t_star = preliminary_times(&d, &lim, 0.004).unwrap();
        let gl = global(&d, &t_star, &lim).unwrap();
        prop_assume!(check_timing(&d, &gl.times, &lim).is_empty());
        for cyclic in [false, true] {
            let (r, broken_before, broken_after) = if cyclic {
                let r = with_acceleration(&d, &gl, &lim, &a_max).unwrap();
                let after = check_acceleration(&d, &r.times, &a_max);
                (r, check_acceleration(&d, &gl.times, &a_max), after)
            } else {
                let r = sequence_with_acceleration(&d, &gl, &lim, &a_max).unwrap();
                let after = check_sequence_acceleration(&d, &r.times, &a_max);
                (r, check_sequence_acceleration(&d, &gl.times, &a_max), after)
            };
            prop_assert!(broken_after.is_empty(), "{broken_after:?}");
            // The circuit's jumps are cyclic as `check_timing` checks them;
            // a sequence's last-to-first row is no row.
            if cyclic {
                prop_assert!(check_timing(&d, &r.times, &lim).is_empty());
            } else {
                let n = r.times.len();
                for i in 0..n.saturating_sub(1) {
                    for (k, lk) in lim.iter().enumerate() {
                        let vi = d[i * w + k] / r.times[i];
                        let vj = d[(i + 1) * w + k] / r.times[i + 1];
                        prop_assert!(vi.abs() <= lk.v_max * (1.0 + 1e-9));
                        prop_assert!((vi - vj).abs() <= lk.dv_max * (1.0 + 1e-9), "{i} {k}");
                    }
                }
            }
            for (a, b) in r.times.iter().zip(&gl.times) {
                prop_assert!(a >= b, "{a} < {b}");
            }
            for ((m, t), ts) in r.mu.iter().zip(&r.times).zip(&t_star) {
                prop_assert!((m * t - ts).abs() <= 1e-9 * ts, "mu {m} t {t} t* {ts}");
            }
            if broken_before.is_empty() {
                prop_assert_eq!(&r, &gl);
            }
        }
    }
}
