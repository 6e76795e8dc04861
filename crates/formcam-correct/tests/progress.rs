#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]
//! The correction's progress hook: the grid, then the nodes chunk by chunk
//! (the same corrections as in one piece), the closed loop's rounds, and
//! `CorrectError::Cancelled` when the hook asks to stop.

use std::path::Path;
use std::sync::Mutex;

use formcam_correct::{
    CorrectError, Corrector, Measurements, MillingProgram, ScenarioJob, Settings,
    correct_program_with,
};
use formcam_progress::{Phase, Step};
use formcam_testkit::Recorder;

fn measurements() -> Measurements {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/correct/cmm.csv");
    Measurements::from_csv(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A node table of `nx * ny` nodes over the measured area (0..200 x 0..150).
fn table(nx: usize, ny: usize) -> MillingProgram {
    let mut text = String::from("x,y,z\n");
    for j in 0..ny {
        for i in 0..nx {
            let x = 200.0 * i as f64 / (nx - 1) as f64;
            let y = 150.0 * j as f64 / (ny - 1) as f64;
            text.push_str(&format!("{x:.4},{y:.4},5.0000\n"));
        }
    }
    MillingProgram::read(&text, "csv", &Settings::default()).unwrap()
}

/// A hook recording every report and cancelling at the first one `stop`
/// picks.
fn hook(stop: impl Fn(&Step) -> bool + Sync) -> Recorder<impl Fn(&Step) -> bool + Sync> {
    Recorder::new(stop)
}

#[test]
fn nodes_are_reported_chunk_by_chunk_with_the_same_corrections() {
    let program = table(300, 250);
    let h = hook(|_| false);
    let c = correct_program_with(&measurements(), &program, &Settings::default(), &h).unwrap();
    let seen = h.steps();
    let of = |p: Phase| -> Vec<(u64, u64)> {
        seen.iter()
            .filter(|s| s.phase == p)
            .map(|s| (s.done, s.total))
            .collect()
    };
    assert_eq!(of(Phase::Grid), [(0, 1), (1, 1)]);
    assert_eq!(
        of(Phase::Nodes),
        [(0, 75_000), (65_536, 75_000), (75_000, 75_000)]
    );
    assert_eq!(seen.len(), 5);
    // The chunks change nothing: the nodes corrected in one piece agree.
    let whole = Corrector::new(&c.grid, Settings::default().options)
        .unwrap()
        .correct(&c.applied.nodes);
    assert_eq!(whole, c.applied.corrections);
    assert!(c.applied.totals.corrected > 70_000);
}

#[test]
fn a_hook_that_cancels_stops_the_correction() {
    let program = table(300, 250);
    for (at, phase) in [(0usize, Phase::Grid), (1, Phase::Nodes)] {
        let count = Mutex::new(0usize);
        let h = hook(move |s| {
            let mut c = count.lock().unwrap();
            let stop = s.phase == phase && *c == at;
            if s.phase == phase {
                *c += 1;
            }
            stop
        });
        let e =
            correct_program_with(&measurements(), &program, &Settings::default(), &h).unwrap_err();
        assert_eq!(e, CorrectError::Cancelled(formcam_progress::Cancelled));
        assert_eq!(e.to_string(), "cancelled");
        // Nothing after the report that cancelled.
        let last = *h.steps().last().unwrap();
        assert_eq!(last.phase, phase);
    }
}

const LOOP: &str = r#"
[surface]
kind = "panel"
length = 200.0
width = 150.0
radius_x = 1200.0
radius_y = 900.0

[program]
tool = "ball:6"
step = 4.0
step_over = 5.0
feed = 3000.0

[warp]
amplitude = 0.4

[cmm]
sections = 9
points = 7
noise = 0.0
seed = 1

[loop]
iterations = 2
interpolation = "bicubic"
section_study = [3, 5]
"#;

#[test]
fn the_closed_loop_reports_its_rounds_and_stops_when_asked() {
    let job = ScenarioJob::from_toml(LOOP).unwrap();
    let h = hook(|_| false);
    let plain = job.scenario.run().unwrap();
    let hooked = job.scenario.run_with(&h).unwrap();
    assert_eq!(plain.rounds.len(), hooked.rounds.len());
    for (a, b) in plain.rounds.iter().zip(&hooked.rounds) {
        assert_eq!(a.program, b.program);
    }
    let rounds: Vec<(Phase, u64, u64)> = h
        .steps()
        .iter()
        .map(|s| (s.phase, s.done, s.total))
        .collect();
    // The inner corrections are muted: only the rounds are reported.
    assert_eq!(
        rounds,
        (0..=3).map(|k| (Phase::Round, k, 3)).collect::<Vec<_>>()
    );
    for at in 0..3 {
        let h = hook(move |s| s.done == at);
        let e = job.scenario.run_with(&h).unwrap_err();
        assert!(matches!(e, CorrectError::Cancelled(_)), "round {at}: {e}");
    }
}

#[test]
fn the_spacing_study_reports_each_correction() {
    let job = ScenarioJob::from_toml(LOOP).unwrap();
    let h = hook(|_| false);
    let rows = job
        .scenario
        .spacing_study_with(&job.section_study, &h)
        .unwrap();
    assert_eq!(
        rows,
        job.scenario.spacing_study(&job.section_study).unwrap()
    );
    let done: Vec<u64> = h.steps().iter().map(|s| s.done).collect();
    assert_eq!(done, [0, 1, 2, 3, 4]);
    let h = hook(|s| s.done == 1);
    let e = job
        .scenario
        .spacing_study_with(&job.section_study, &h)
        .unwrap_err();
    assert!(matches!(e, CorrectError::Cancelled(_)));
}
