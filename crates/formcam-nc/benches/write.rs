//! Writing 10^6 blocks as Sinumerik 840D and Marlin X/A/B.

#![allow(clippy::expect_used, missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_nc::{AxisSpec, Block, Dialect, Feed, Program, write};

/// A winding-like program: X travels back and forth, A turns on, Y and B
/// follow; inverse-time blocks of 10 ms.
fn program(n: usize, axes: &[(&str, bool)]) -> Program {
    let axes = axes
        .iter()
        .map(|(name, rotary)| AxisSpec {
            modulo: false,
            name: (*name).to_string(),
            rotary: *rotary,
        })
        .collect::<Vec<_>>();
    let mut p = Program::new("BENCH", axes);
    p.blocks.reserve(n);
    p.blocks.push(Block::rapid(vec![0.0; p.axes.len()]));
    for i in 1..n {
        let s = i as f64 * 1e-3;
        let target = p
            .axes
            .iter()
            .enumerate()
            .map(|(k, a)| {
                if a.rotary {
                    s * 360.0 / (k as f64 + 1.0)
                } else {
                    200.0 * (s * 0.7 + k as f64).sin()
                }
            })
            .collect();
        p.blocks
            .push(Block::linear(target, Feed::InverseTime(0.01)));
    }
    p
}

fn benches(c: &mut Criterion) {
    let n = 1_000_000;
    let cases = [
        (
            Dialect::Sinumerik840d,
            program(n, &[("X", false), ("A", true), ("Y", false), ("B", true)]),
        ),
        (
            Dialect::MarlinXab,
            program(n, &[("X", false), ("A", true), ("B", true)]),
        ),
    ];
    let mut g = c.benchmark_group("write_1e6_blocks");
    g.sample_size(10);
    for (dialect, p) in &cases {
        let mut out = String::new();
        g.bench_function(dialect.name(), |b| {
            b.iter(|| {
                out.clear();
                write(black_box(p), *dialect, &mut out).expect("write");
                black_box(out.len())
            })
        });
    }
    g.finish();
}

criterion_group!(write_benches, benches);
criterion_main!(write_benches);
