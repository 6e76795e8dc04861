//! Timeline and axis checks of a 10^5-block program on the 4-axis winder;
//! a 10^5-block vessel program checked for collisions with its mandrel.

#![allow(missing_docs, clippy::unwrap_used)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::path::Path;

use formcam_machine::shipped::shipped;
use formcam_nc::{Block, Feed, Program};
use formcam_program::{Stage, WindJob, plan_until, write_program};
use formcam_sim::{
    AxisLimits, Collisions, FeedRule, Laminate, Timeline, check_timeline, program_axes,
    read_program,
};

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
    // The demo's 840D vessel program (its eye passes over the domes inside
    // the mandrel's box, so the exact distance runs there), repeated to 10^5
    // blocks, the spindle carried on; its mandrel from the job.
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let job_path = examples.join("vessel-program-840d.toml");
    let job = WindJob::from_toml(&std::fs::read_to_string(&job_path).unwrap(), &examples).unwrap();
    let m = job.machine.as_ref().unwrap().machine.clone();
    let planned = plan_until(&job, Stage::Program).unwrap();
    let mut text = Vec::new();
    write_program(&planned, &mut text).unwrap();
    let text = String::from_utf8(text).unwrap();
    let (one, _, _) = read_program(Path::new("program.mpf"), &text, &m).unwrap();
    let spindle = m.axis("A").unwrap();
    let turn = one.blocks.last().unwrap().target[spindle];
    let mut p = Program::new("VESSEL", program_axes(&m));
    let mut copy = 0.0;
    while p.blocks.len() < n {
        for b in one.blocks.iter().take(n - p.blocks.len()) {
            let mut b = b.clone();
            b.target[spindle] += copy * turn;
            p.blocks.push(b);
        }
        copy += 1.0;
    }
    let laminate = Laminate::of_job(&job).unwrap();
    let stages = laminate.stage_of_blocks(p.blocks.iter().map(|b| b.comment.as_deref()));
    let collisions = Collisions::with_mandrel(&m, None, &laminate, stages).unwrap();
    let tl = Timeline::new(&p, &lines, FeedRule::Sinumerik840d, &m).unwrap();
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
