//! A sequence of blocks timed in parts (the layers of a program, each timed as
//! its own cyclic circuit) joined by `join_times`: every jump holds across the
//! joins and at the ends (from and to rest), no block runs faster than its part
//! timed it, and the result is the optimum of the joined sequence; long blocks
//! at a join, cut by `ramp_pieces`, ramp in short pieces instead of slowing.

#![allow(clippy::unwrap_used)]

use formcam_motion::{
    AxisLimits, check_timing, global, global_by_cone, join_times, preliminary_times, ramp_pieces,
};
use proptest::prelude::*;

/// Two axes: a carriage (mm/s) and a spindle (rad/s).
fn limits() -> Vec<AxisLimits> {
    vec![
        AxisLimits {
            v_max: 1000.0,
            dv_max: 100.0,
        },
        AxisLimits {
            v_max: 10.0,
            dv_max: 1.0,
        },
    ]
}

const TAU: f64 = 0.004;

/// One part: a circuit of blocks (out and back, so the carriage reverses),
/// timed cyclically by `global` and repeated `circuits` times.
/// Returns `(deltas, t_star, mu)` of every block.
fn part(out: &[(f64, f64)], circuits: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut d: Vec<f64> = out.iter().flat_map(|&(x, a)| [x, a]).collect();
    d.extend(out.iter().flat_map(|&(x, a)| [-x, a]));
    let t_star = preliminary_times(&d, &limits(), TAU).unwrap();
    let timing = global(&d, &t_star, &limits()).unwrap();
    (
        d.repeat(circuits),
        t_star.repeat(circuits),
        timing.mu.repeat(circuits),
    )
}

/// Parts joined by one fast block each (as fast as the axes allow).
fn program(parts: &[(Vec<(f64, f64)>, usize)], join: (f64, f64)) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let (mut d, mut t, mut cap) = (Vec::new(), Vec::new(), Vec::new());
    for (k, (out, circuits)) in parts.iter().enumerate() {
        if k > 0 {
            let j = [join.0 * k as f64, join.1];
            d.extend(j);
            t.extend(preliminary_times(&j, &limits(), TAU).unwrap());
            cap.push(1.0);
        }
        let (pd, pt, pm) = part(out, *circuits);
        d.extend(pd);
        t.extend(pt);
        cap.extend(pm);
    }
    (d, t, cap)
}

/// The whole sequence's broken limits, standing before and after.
fn broken_from_rest(d: &[f64], times: &[f64]) -> Vec<(usize, usize, f64)> {
    let mut d = d.to_vec();
    d.extend([0.0, 0.0]);
    let mut t = times.to_vec();
    t.push(1.0);
    check_timing(&d, &t, &limits())
}

fn moves() -> impl Strategy<Value = Vec<(f64, f64)>> {
    prop::collection::vec((0.5f64..40.0, 0.0f64..0.5), 6..20)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn joined_parts_keep_every_jump_and_their_own_times(
        a in moves(),
        b in moves(),
        join in (-300.0f64..300.0, 0.0f64..3.0),
    ) {
        let (d, t_star, cap) = program(&[(a, 3), (b, 2)], join);
        let before: Vec<f64> = t_star.iter().zip(&cap).map(|(t, m)| t / m).collect();
        // As the parts were timed, the joins break the limits.
        let joined = join_times(&d, &t_star, &cap, &limits()).unwrap();
        prop_assert!(broken_from_rest(&d, &joined.times).is_empty());
        for (t, b) in joined.times.iter().zip(&before) {
            prop_assert!(*t >= b * (1.0 - 1e-12), "{t} faster than its part's {b}");
        }
        prop_assert!(joined.total >= before.iter().sum::<f64>() * (1.0 - 1e-12));
    }

    #[test]
    fn without_caps_the_windows_find_the_optimum_of_the_whole_sequence(
        a in moves(),
        b in moves(),
        join in (-300.0f64..300.0, 0.0f64..3.0),
    ) {
        let (d, t_star, _) = program(&[(a, 2), (b, 1)], join);
        let ones = vec![1.0; t_star.len()];
        let joined = join_times(&d, &t_star, &ones, &limits()).unwrap();
        prop_assert!(broken_from_rest(&d, &joined.times).is_empty());
        // The same problem as one cone program: the sequence and a standstill.
        let mut dr = d.clone();
        dr.extend([0.0, 0.0]);
        let mut tr = t_star.clone();
        tr.push(1.0);
        let whole = global_by_cone(&dr, &tr, &limits()).unwrap();
        let whole = whole.total - whole.times[t_star.len()];
        prop_assert!(
            (joined.total - whole).abs() <= 1e-5 * whole,
            "windows {} s, one cone program {} s",
            joined.total,
            whole
        );
    }
}

/// The reproducer of the joins: a part at full speed next to a fast move the
/// other way breaks the jump limit as timed; joined, it holds, and blocks far
/// from the joins keep their part's times exactly.
#[test]
fn only_blocks_near_the_joins_are_slowed() {
    let out: Vec<(f64, f64)> = (0..30).map(|i| (20.0 + f64::from(i % 5), 0.2)).collect();
    let (d, t_star, cap) = program(&[(out.clone(), 3), (out, 3)], (-250.0, 1.0));
    let before: Vec<f64> = t_star.iter().zip(&cap).map(|(t, m)| t / m).collect();
    assert!(!broken_from_rest(&d, &before).is_empty());
    let joined = join_times(&d, &t_star, &cap, &limits()).unwrap();
    assert!(broken_from_rest(&d, &joined.times).is_empty());
    // The middle circuit of each part (blocks 60..120 of 180 per part).
    for part in [0usize, 181] {
        let middle = part + 60..part + 120;
        assert_eq!(joined.times[middle.clone()], before[middle]);
    }
    assert!(joined.total > before.iter().sum::<f64>());
}

/// A part of long blocks at full speed, from and to rest: slowing whole blocks
/// until the jumps hold makes it ten times slower; cut by `ramp_pieces`, the
/// velocity ramps in pieces of the least block time and the part keeps its
/// time but for the ramps.
#[test]
fn long_blocks_at_the_joins_ramp_in_short_pieces() {
    // Four blocks of 5 m on the carriage at its 1000 mm/s, the spindle along.
    let d: Vec<f64> = [5000.0, 20.0].repeat(4);
    let t_star = preliminary_times(&d, &limits(), TAU).unwrap();
    let cap = global(&d, &t_star, &limits()).unwrap().mu;
    let before: f64 = t_star.iter().zip(&cap).map(|(t, m)| t / m).sum();
    let whole = join_times(&d, &t_star, &cap, &limits()).unwrap();
    assert!(whole.total > 5.0 * before, "{} vs {before}", whole.total);
    // Joins at the start and the end only.
    let mut joins = vec![false; t_star.len() + 1];
    joins[0] = true;
    joins[t_star.len()] = true;
    let cuts = ramp_pieces(&d, &t_star, &cap, &joins, &limits(), TAU).unwrap();
    let (mut pd, mut pt, mut pc) = (Vec::new(), Vec::new(), Vec::new());
    for (i, ends) in cuts.iter().enumerate() {
        assert_eq!(ends.last().copied(), Some(1.0));
        assert!(ends.windows(2).all(|e| e[1] > e[0]));
        let t_block = t_star[i] / cap[i];
        let mut at = 0.0;
        for &e in ends {
            let piece: Vec<f64> = d[2 * i..2 * i + 2].iter().map(|v| v * (e - at)).collect();
            let ts = preliminary_times(&piece, &limits(), TAU).unwrap()[0];
            pd.extend(piece);
            pt.push(ts);
            pc.push((ts / ((e - at) * t_block)).min(1.0));
            at = e;
        }
    }
    // The first and last blocks are cut (10 steps of 100 mm/s), the others not.
    assert!(cuts[0].len() > 1 && cuts[3].len() > 1);
    assert!(cuts[1].len() == 1 && cuts[2].len() == 1);
    let ramped = join_times(&pd, &pt, &pc, &limits()).unwrap();
    assert!(broken_from_rest(&pd, &ramped.times).is_empty());
    let steps = 10.0;
    assert!(
        ramped.total <= before + 2.0 * steps * TAU,
        "{} vs {before}",
        ramped.total
    );
}
