//! The whole dressing simulation of the example's wheel at a fine step.

#![allow(clippy::expect_used, missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_dress::{DressJob, dress};

const JOB: &str = include_str!("../../../examples/dress-ballscrew-nut.toml");

fn bench(c: &mut Criterion) {
    let job = DressJob::from_toml(JOB).expect("the example job");
    let mut g = c.benchmark_group("dress");
    g.sample_size(10);
    for step in [0.01, 0.001] {
        let mut job = job.clone();
        job.process.step = step;
        let spec = job.spec(None).expect("spec");
        g.bench_function(format!("whole dressing, step {step} mm"), |b| {
            b.iter(|| dress(&spec).expect("dressing"))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
