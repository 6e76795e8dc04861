#![allow(clippy::expect_used, missing_docs)]
//! The noise smoothing of `n x n` measured points (a smooth warp with
//! 0.01 mm of noise): the multigrid-preconditioned solver for n = 100, 300,
//! 1000, and the plain conjugate gradients it replaced for n = 100.

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_correct::{Grid, smooth};

#[path = "common/cg_reference.rs"]
mod cg_reference;

/// `n x n` points 2 mm apart, the deviation along z (with normals): a
/// smooth warp and a deterministic noise of standard deviation `sigma`.
fn noisy(n: usize, sigma: f64) -> Grid {
    let mut state = 2024u64;
    let mut noise = move || {
        let mut s = 0.0;
        for _ in 0..12 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            s += (state >> 11) as f64 / (1u64 << 53) as f64;
        }
        (s - 6.0) * sigma
    };
    let size = 2.0 * (n - 1) as f64;
    let mut nominal = Vec::with_capacity(n * n);
    let mut deviation = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64 * 2.0, j as f64 * 2.0);
            nominal.push([x, y, 0.0]);
            let w = 0.3 * (3.0 * x / size).sin() * (2.0 * y / size).cos();
            deviation.push([0.0, 0.0, w + noise()]);
        }
    }
    Grid {
        nu: n,
        nv: n,
        nominal,
        deviation,
        normal: Some(vec![[0.0, 0.0, 1.0]; n * n]),
        resampled: false,
        reordered: false,
    }
}

fn bench(c: &mut Criterion) {
    let sigma = 0.01;
    let mut group = c.benchmark_group("smooth");
    group.sample_size(10);
    for n in [100, 300, 1000] {
        let g = noisy(n, sigma);
        group.bench_function(format!("multigrid_{n}x{n}"), |b| {
            b.iter(|| smooth(&mut g.clone(), sigma))
        });
    }
    let g = noisy(100, sigma);
    let d: Vec<f64> = g.deviation.iter().map(|d| d[2]).collect();
    group.bench_function("plain_cg_before_100x100", |b| {
        b.iter(|| cg_reference::fit(std::slice::from_ref(&d), 100, 100, sigma))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
