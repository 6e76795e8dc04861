//! The free-fibre snag check of a program of about 10^5 blocks: the
//! 4-axis vessel job of the examples with helical layers repeated and tight
//! block tolerances, planned once, written, read back; the check (following
//! the layers, sampling, the mandrel and the solids) is what is timed.

#![allow(missing_docs, clippy::unwrap_used)]

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_sim::{SnagOptions, check_snag};

// Each target uses part of the shared cases.
#[allow(dead_code)]
#[path = "support/cases.rs"]
mod cases;

fn bench(c: &mut Criterion) {
    let (tl, fibre, layers) = cases::helical(100_000);
    let opts = SnagOptions::default();
    eprintln!(
        "{} blocks, {} layers, {:.0} s of program",
        tl.len(),
        layers,
        tl.duration_s()
    );
    for v in check_snag(&tl, &fibre, &opts).unwrap() {
        eprintln!(
            "{v} (worst {} mm at block {})",
            v.worst_value, v.worst_block
        );
    }
    c.bench_function("snag check, 1e5 blocks", |b| {
        b.iter(|| check_snag(&tl, &fibre, &opts).unwrap());
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
