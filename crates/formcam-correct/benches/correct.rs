#![allow(clippy::expect_used, missing_docs)]
//! 10^6 raster nodes against a 200 x 200 grid of measured points.

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_correct::{Corrector, Grid, Interpolation, Options};

/// The bench's surface: 400 x 300 mm, doubly curved.
fn height(x: f64, y: f64) -> f64 {
    (x - 200.0).powi(2) / 2400.0 + (y - 150.0).powi(2) / 1800.0
}

fn warp(x: f64, y: f64) -> f64 {
    0.4 * (std::f64::consts::PI * x / 400.0).sin() * (std::f64::consts::PI * y / 300.0).sin()
}

pub fn grid(n: usize) -> Grid {
    let mut nominal = Vec::with_capacity(n * n);
    let mut deviation = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (
                400.0 * j as f64 / (n - 1) as f64,
                300.0 * i as f64 / (n - 1) as f64,
            );
            nominal.push([x, y, height(x, y)]);
            deviation.push([0.0, 0.0, warp(x, y)]);
        }
    }
    Grid {
        nu: n,
        nv: n,
        nominal,
        deviation,
        normal: None,
        resampled: false,
    }
}

pub fn nodes(n: usize) -> Vec<[f64; 3]> {
    let mut out = Vec::with_capacity(n * n);
    for k in 0..n {
        let y = 300.0 * (k as f64 + 0.5) / n as f64;
        for i in 0..n {
            let i = if k % 2 == 0 { i } else { n - 1 - i };
            let x = 400.0 * (i as f64 + 0.5) / n as f64;
            out.push([x, y, height(x, y)]);
        }
    }
    out
}

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
