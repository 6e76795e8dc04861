//! Block times for 1e5 blocks: the global optimum (monotone sweeps without
//! reversals; the cone program with them) and the pairwise method; and 1e5
//! blocks of eight parts, each timed on its own, joined (`join_times`).

#![allow(clippy::expect_used, missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_motion::{AxisLimits, global, join_times, pairwise, preliminary_times};

fn program(n: usize, reversing: bool) -> Vec<f64> {
    (0..n)
        .flat_map(|i| {
            let t = i as f64 / n as f64 * std::f64::consts::TAU * 20.0;
            let carriage = if reversing {
                5.0 * t.cos()
            } else {
                5.0 + 2.0 * t.cos()
            };
            [
                0.01 + 0.002 * (3.0 * t).sin(),
                carriage,
                0.5 + 0.3 * t.sin(),
            ]
        })
        .collect()
}

fn benches(c: &mut Criterion) {
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
    for reversing in [false, true] {
        let d = program(100_000, reversing);
        let t_star = preliminary_times(&d, &lim, 0.002).expect("t*");
        let name = if reversing {
            "with carriage reversals"
        } else {
            "no reversals"
        };
        c.bench_function(&format!("global, 1e5 blocks, {name}"), |b| {
            b.iter(|| black_box(global(&d, &t_star, &lim).expect("global")))
        });
        c.bench_function(&format!("pairwise, 1e5 blocks, {name}"), |b| {
            b.iter(|| black_box(pairwise(&d, &t_star, &lim).expect("pairwise")))
        });
    }
    // Eight parts of 12 500 blocks with carriage reversals, each timed by
    // `global`, joined by one block of 300 mm on the carriage.
    let part = program(12_500, true);
    let pt = preliminary_times(&part, &lim, 0.002).expect("t*");
    let mu = global(&part, &pt, &lim).expect("global").mu;
    let (mut d, mut t_star, mut cap) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..8 {
        if k > 0 {
            let join = [0.0, 300.0, 0.0];
            t_star.extend(preliminary_times(&join, &lim, 0.002).expect("t*"));
            d.extend(join);
            cap.push(1.0);
        }
        d.extend(&part);
        t_star.extend(&pt);
        cap.extend(&mu);
    }
    c.bench_function("join_times, 8 parts of 12 500 blocks", |b| {
        b.iter(|| black_box(join_times(&d, &t_star, &cap, &lim).expect("join")))
    });
}

criterion_group!(name = g; config = Criterion::default().sample_size(10); targets = benches);
criterion_main!(g);
