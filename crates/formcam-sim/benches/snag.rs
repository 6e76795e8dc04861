//! The free-fibre snag check of a program of about 10^5 blocks: the
//! 4-axis vessel job of the examples with helical layers repeated and tight
//! block tolerances, planned once, written, read back; the check (following
//! the layers, sampling, the mandrel and the solids) is what is timed.

#![allow(missing_docs, clippy::unwrap_used)]

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_program::{Stage, WindJob, plan_until, write_program};
use formcam_sim::{FeedRule, FreeFibre, SnagOptions, Timeline, check_snag, read_program};

/// The job: `layers` geodesic helical layers on the example vessel.
fn job(layers: usize) -> WindJob {
    let mut text = String::from(
        "[mandrel]\nkind = \"vessel\"\nradius = 100.0\ncylinder_length = 300.0\n\
         dome = \"hemisphere\"\npolar_opening = 30.0\n\n",
    );
    for _ in 0..layers {
        text.push_str("[[layer]]\nband_width = 10.0\nband_thickness = 0.5\n\n");
    }
    text.push_str(
        "[eye]\nmode = \"axis-parallel\"\nradius = 160.0\nclearance = 20.0\nl_max = 600.0\n\n\
         [machine]\nname = \"winder-4axis\"\n\n\
         [motion]\ntolerance_mm = 0.002\ntolerance_deg = 0.002\n\n\
         [checks]\nallow = [\"slack\", \"clearance\", \"l_max\", \"reverse-rotation\"]\n\n\
         [post]\ndialect = \"sinumerik-840d\"\n",
    );
    WindJob::from_toml(&text, Path::new(".")).unwrap()
}

fn bench(c: &mut Criterion) {
    // Enough layers for 10^5 blocks.
    let one = plan_until(&job(1), Stage::Program).unwrap();
    let per_layer = one.program.as_ref().unwrap().program.blocks.len();
    let layers = 100_000usize.div_ceil(per_layer).max(1);
    let wound = plan_until(&job(layers), Stage::Program).unwrap();
    let mut bytes = Vec::new();
    write_program(&wound, &mut bytes).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    let m = wound.machine.clone().unwrap();
    let (p, lines, d) = read_program(Path::new("program.mpf"), &text, &m).unwrap();
    let tl = Timeline::new(&p, &lines, FeedRule::of(d), &m).unwrap();
    let fibre = FreeFibre::from_wound(&wound).unwrap();
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
