//! The winding pipeline of whole jobs: a single-layer tube on the shipped
//! 2-axis winder, and the same tube wound in four layers (hoop, helical,
//! hoop, helical), whose layers' eye, axes and blocks run in parallel; and
//! the speed case: a 3-layer vessel with 10^6 path points (planned with and
//! without the acceleration limits).

#![allow(clippy::expect_used, missing_docs)]

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_program::{WindJob, plan_program, write_program};

const TUBE: &str = r#"
[mandrel]
kind = "cylinder"
radius = 60.0
length = 800.0

[winding]
mu = 0.0
winding_angle_deg = 50.0
band_width = 8.0
band_thickness = 0.3
dwell_min_deg = 360.0

[eye]
mode = "axis-parallel"
radius = 250.0
clearance = 15.0
l_max = 1000.0

[machine]
name = "winder-2axis"

[post]
dialect = "marlin-xab"

[checks]
allow = ["slack", "clearance", "l_max", "cyclicity", "reverse-rotation", "limits", "unreachable", "timing"]
"#;

/// The speed case: the hemisphere vessel of `examples/vessel-layers-840d.toml`
/// (a hoop layer, two geodesic helical layers) with an equidistant eye on the
/// shipped 4-axis winder, for a Sinumerik 840D. Each layer's circuit holds
/// `eye.samples` = 333 334 path points, 1 000 002 in all. It makes 25 144
/// blocks and a program of 1 480 445 bytes (the bench prints the counts).
/// The eye keeps 10 mm: at the example's 20 mm an equidistant eye lets the
/// band go slack at the second layer's turn-arounds, and the program would be
/// refused.
/// (`vessel-1e6.toml`, shared with the `vessel_1e6` example that profilers run.)
const VESSEL: &str = include_str!("vessel-1e6.toml");

fn layers() -> String {
    let hoop = "[[layer]]\nkind = \"hoop\"\nband_width = 8.0\nband_thickness = 0.3\n";
    let helical = "[[layer]]\nmu = 0.0\nwinding_angle_deg = 50.0\nband_width = 8.0\n\
                   band_thickness = 0.3\ndwell_min_deg = 360.0\n";
    let base = TUBE.replace(
        "[winding]\nmu = 0.0\nwinding_angle_deg = 50.0\nband_width = 8.0\nband_thickness = 0.3\n\
         dwell_min_deg = 360.0\n",
        "",
    );
    format!("{base}{hoop}{helical}{hoop}{helical}")
}

fn benches(c: &mut Criterion) {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let single = WindJob::from_toml(TUBE, here).expect("job");
    let multi = WindJob::from_toml(&layers(), here).expect("job");
    let mut g = c.benchmark_group("wind");
    g.sample_size(10);
    g.bench_function("tube, one layer: plan and post", |b| {
        b.iter(|| {
            let p = plan_program(black_box(&single)).expect("plan");
            let mut text = Vec::new();
            write_program(&p, &mut text).expect("post");
            text.len()
        });
    });
    g.bench_function("tube, four layers: plan and post", |b| {
        b.iter(|| {
            let p = plan_program(black_box(&multi)).expect("plan");
            let mut text = Vec::new();
            write_program(&p, &mut text).expect("post");
            text.len()
        });
    });
    g.finish();
    vessel(c);
}

/// The speed case: planning alone, and planning and writing the program.
fn vessel(c: &mut Criterion) {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let job = WindJob::from_toml(VESSEL, here).expect("job");
    let p = plan_program(&job).expect("plan");
    let points: usize = p
        .layers
        .iter()
        .filter_map(|l| l.wound())
        .map(|w| w.targets.len())
        .sum();
    let blocks = p.program.as_ref().map_or(0, |a| a.blocks.len());
    let mut text = Vec::new();
    write_program(&p, &mut text).expect("post");
    eprintln!(
        "vessel, 3 layers: {points} path points, {blocks} blocks, {} bytes",
        text.len()
    );
    let mut g = c.benchmark_group("wind 1e6");
    g.sample_size(10);
    g.bench_function("vessel, 3 layers, 1e6 points: plan", |b| {
        b.iter(|| plan_program(black_box(&job)).expect("plan"));
    });
    g.bench_function("vessel, 3 layers, 1e6 points: plan and write", |b| {
        b.iter(|| {
            let p = plan_program(black_box(&job)).expect("plan");
            let mut text = Vec::new();
            write_program(&p, &mut text).expect("post");
            text.len()
        });
    });
    // The planner without the acceleration limits (`[motion] acceleration =
    // false`): its times before they became the default.
    let free = WindJob::from_toml(&format!("{VESSEL}\n[motion]\nacceleration = false\n"), here)
        .expect("job");
    g.bench_function(
        "vessel, 3 layers, 1e6 points: plan, acceleration off",
        |b| {
            b.iter(|| plan_program(black_box(&free)).expect("plan"));
        },
    );
    g.finish();
}

criterion_group!(wind, benches);
criterion_main!(wind);
