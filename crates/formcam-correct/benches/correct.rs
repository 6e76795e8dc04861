#![allow(clippy::expect_used, missing_docs)]
//! 10^6 raster nodes against a 200 x 200 grid of measured points.

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_correct::{Corrector, Interpolation, Options};

mod common;
use common::{grid, nodes};

fn bench(c: &mut Criterion) {
    let g = grid(200);
    let p = nodes(1000);
    let mut group = c.benchmark_group("correct_1e6_nodes_200x200");
    group.sample_size(10);
    for kind in [Interpolation::Bilinear, Interpolation::Bicubic] {
        let corr = Corrector::new(
            &g,
            Options {
                interpolation: kind,
                ..Options::default()
            },
        )
        .expect("corrector");
        group.bench_function(kind.name(), |b| b.iter(|| corr.correct(&p)));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
