//! Big programs: a job estimated larger than the memory budget is refused
//! before any layer is planned, every layer's fields are checked before the
//! first is planned, and a run that goes ahead holds one batch of layers'
//! points at a time.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;
use std::sync::Mutex;

use formcam_program::{
    LAYER_BATCH, ProgramError, Stage, WindJob, WoundLayer, estimate, plan_each, plan_until_with,
};
use formcam_progress::{Hook, Step};

/// A helical tube on the shipped 2-axis lathe winder (fast).
const TUBE: &str = include_str!("jobs/tube.toml");

fn job(text: &str) -> WindJob {
    WindJob::from_toml(text, &PathBuf::from(env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// The tube job with `n` copies of its layer as `[[layer]]`s, `last` added
/// to the last one's fields, and `samples` points per pass and circuit.
fn layers(n: usize, last: &str, samples: usize) -> String {
    let head = TUBE.split("[winding]").next().unwrap();
    let layer = TUBE
        .split("[winding]")
        .nth(1)
        .unwrap()
        .split("[eye]")
        .next()
        .unwrap()
        .trim();
    let tail = TUBE
        .split("[eye]")
        .nth(1)
        .unwrap()
        .replace("samples = 2001", &format!("samples = {samples}"));
    let mut text = head.to_string();
    for i in 0..n {
        text.push_str("[[layer]]\n");
        let fields = if i + 1 == n && !last.is_empty() {
            last.to_string()
        } else {
            format!("{layer}\nsamples = {samples}\n")
        };
        text.push_str(&fields);
        text.push('\n');
    }
    format!("{text}[eye]{tail}")
}

/// Plans `job` recording every report.
fn planned(job: &WindJob) -> (Result<(), ProgramError>, Vec<Step>) {
    let seen = Mutex::new(Vec::new());
    let hook = Hook::new(|s| seen.lock().unwrap().push(s));
    let r = plan_until_with(job, Stage::Program, &hook).map(|_| ());
    (r, seen.into_inner().unwrap())
}

#[test]
fn a_thousand_helical_layers_are_refused_before_planning() {
    let j = job(&layers(1000, "", 2001));
    let (r, steps) = planned(&j);
    let e = r.unwrap_err();
    let ProgramError::TooLarge {
        layers,
        points,
        blocks,
        mib,
        budget_mib,
    } = e
    else {
        panic!("{e}");
    };
    assert_eq!(layers, 1000);
    assert_eq!(budget_mib, 2048);
    assert!(mib > budget_mib, "{mib}");
    // Each layer's pass and circuit, 2001 points each.
    assert_eq!(points, 1000 * 2 * 2001);
    assert!(blocks > 1000, "{blocks}");
    // Not one layer was planned: no phase reported at all.
    assert!(steps.is_empty(), "{steps:?}");
    let text = e.to_string();
    assert!(text.contains("1000 layers"), "{text}");
    assert!(text.contains("--max-memory-mb"), "{text}");
    assert!(text.contains("budget of 2048 MiB"), "{text}");
}

#[test]
fn the_estimate_counts_every_layer_and_grows_with_them() {
    let eye = |j: &WindJob| j.eye.as_ref().unwrap().spec(|_| Ok(String::new())).unwrap();
    let one = job(&layers(1, "", 2001));
    let ten = job(&layers(10, "", 2001));
    let s1 = estimate(&one, Stage::Program, Some(&eye(&one))).unwrap();
    let s10 = estimate(&ten, Stage::Program, Some(&eye(&ten))).unwrap();
    assert_eq!(s1.layers, 1);
    assert_eq!(s10.layers, 10);
    assert_eq!(s10.points, 10 * s1.points);
    // The mandrel grows, so later layers need more circuits.
    assert!(s10.circuits > 10 * s1.circuits, "{s10:?} {s1:?}");
    assert!(s10.bytes > 5 * s1.bytes, "{s10:?} {s1:?}");
    assert!(s10.within(s10.bytes).is_ok());
    assert!(matches!(
        s10.within(s10.bytes - 1),
        Err(ProgramError::TooLarge { .. })
    ));
}

#[test]
fn a_bad_last_layer_is_reported_before_the_first_is_planned() {
    // The last layer forgets its winding angle, which a tube needs.
    let j = job(&layers(
        40,
        "band_width = 8.0\nband_thickness = 0.3\nmu = 0.0\n",
        201,
    ));
    let (r, steps) = planned(&j);
    let e = r.unwrap_err().to_string();
    assert!(e.contains("layer[40].winding_angle_deg"), "{e}");
    assert!(steps.is_empty(), "{steps:?}");
}

/// The per-point records a layer holds.
fn points(l: &WoundLayer) -> usize {
    l.wound().map_or(0, |w| {
        w.layer.points.len() + w.eye.as_ref().map_or(0, |e| e.points.len()) + w.targets.len()
    })
}

#[test]
fn a_long_job_holds_one_batch_of_layers_at_a_time() {
    let n = 3 * LAYER_BATCH + 2;
    let j = job(&layers(n, "", 201));
    let whole = plan_until_with(&j, Stage::Program, &formcam_progress::Silent).unwrap();
    let per_layer: Vec<usize> = whole.layers.iter().map(points).collect();
    assert!(per_layer.iter().all(|&p| p > 0));
    assert_eq!(whole.peak_points, per_layer.iter().sum::<usize>());
    // Handed on in order, each whole; kept without its points.
    let mut seen = Vec::new();
    let streamed = plan_each(
        &j,
        Stage::Program,
        &formcam_progress::Silent,
        &mut |i, l: &WoundLayer| {
            seen.push((i, points(l)));
            Ok::<(), ProgramError>(())
        },
    )
    .unwrap();
    assert_eq!(
        seen,
        per_layer.iter().copied().enumerate().collect::<Vec<_>>()
    );
    assert!(streamed.layers.iter().all(|l| points(l) == 0));
    let batch_max = per_layer
        .chunks(LAYER_BATCH)
        .map(|c| c.iter().sum::<usize>())
        .max()
        .unwrap();
    assert_eq!(streamed.peak_points, batch_max);
    assert!(streamed.peak_points * 3 < whole.peak_points);
    // The same program, block for block.
    assert_eq!(streamed.program, whole.program);
    assert_eq!(streamed.blocks, whole.blocks);
    assert_eq!(streamed.fibre_length_mm(), whole.fibre_length_mm());
}
