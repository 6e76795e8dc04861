//! Timeline and axis checks of a 10^5-block program on the 4-axis winder;
//! a 10^5-block vessel program checked for collisions with its mandrel.

#![allow(missing_docs, clippy::unwrap_used)]

use criterion::{Criterion, criterion_group, criterion_main};

use formcam_machine::shipped::shipped;
use formcam_nc::{Block, Feed, Program};
use formcam_sim::{AxisLimits, FeedRule, Timeline, check_timeline, program_axes};

// Each target uses part of the shared cases.
#[allow(dead_code)]
#[path = "support/cases.rs"]
mod cases;

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
    let cases::VesselCase {
        machine: m,
        program: p,
        lines,
        timeline: tl,
        collisions,
    } = cases::vessel(n);
    let found = collisions.check(&tl, &m);
    // The demo's one finding: the cross feed's bar near the spindle chuck.
    assert!(
        found.iter().all(|v| v.links == ["spindle", "cross"]),
        "{found:?}"
    );
    let limits = AxisLimits::of(&m);
    c.bench_function("collisions with the mandrel, 1e5 blocks", |b| {
        b.iter(|| collisions.check(&tl, &m));
    });
    c.bench_function("timeline + checks + collisions, 1e5 blocks", |b| {
        b.iter(|| {
            let tl = Timeline::new(&p, &lines, FeedRule::Sinumerik840d, &m).unwrap();
            let mut v = check_timeline(&tl, &limits);
            v.extend(collisions.check(&tl, &m));
            v
        });
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
