//! Timeline and axis checks of a 10^5-block program on the 4-axis winder.

#![allow(missing_docs, clippy::unwrap_used)]

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_machine::shipped::shipped;
use formcam_nc::{Block, Feed, Program};
use formcam_sim::{AxisLimits, FeedRule, Timeline, check_timeline, program_axes};

fn bench(c: &mut Criterion) {
    let m = shipped("winder-4axis").unwrap().machine().unwrap();
    let mut p = Program::new("BENCH", program_axes(&m));
    let n = 100_000;
    for i in 0..n {
        let s = i as f64 * 0.01;
        let target = vec![
            i as f64 * 3.6,
            500.0 + 400.0 * s.sin(),
            250.0 + 50.0 * s.cos(),
            30.0 * (0.5 * s).sin(),
        ];
        p.blocks
            .push(Block::linear(target, Feed::InverseTime(0.05)));
    }
    let lines: Vec<usize> = (1..=n).collect();
    let limits = AxisLimits::of(&m);
    c.bench_function("timeline + checks, 1e5 blocks", |b| {
        b.iter(|| {
            let tl = Timeline::new(&p, &lines, FeedRule::Iso, &m).unwrap();
            check_timeline(&tl, &limits)
        });
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
