//! Runs with a progress hook: every kind of job stops with
//! `RunError::Cancelled` (and no files) when its hook cancels at the first
//! report, and a hook that only watches changes no file.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use formcam_run::progress::{Hook, Phase, Step};
use formcam_run::{RunError, RunOutput, run_job_file, run_job_file_with};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// Runs `name` with a hook that records every report and cancels at the
/// first one `stop` picks.
fn run(
    name: &str,
    stop: impl Fn(&Step) -> bool + Sync,
) -> (Vec<Step>, Result<RunOutput, RunError>) {
    let seen = Arc::new(Mutex::new(Vec::new()));
    let flag = Arc::new(AtomicBool::new(false));
    let (s, f) = (Arc::clone(&seen), Arc::clone(&flag));
    let hook = Hook::with_flag(flag, move |step| {
        s.lock().unwrap().push(step);
        if stop(&step) {
            f.store(true, Ordering::Relaxed);
        }
    });
    let out = run_job_file_with(&example(name), Path::new("out"), &hook);
    let seen = seen.lock().unwrap().clone();
    (seen, out)
}

#[test]
fn every_kind_of_job_stops_at_its_first_report() {
    for name in [
        "tube-helical.toml",
        "tube-fiberpath.wind",
        "correct-mould.toml",
        "correct-panel-loop.toml",
        "dress-ballscrew-nut.toml",
    ] {
        let (seen, out) = run(name, |_| true);
        assert_eq!(seen.len(), 1, "{name}: {seen:?}");
        match out {
            Err(e) => {
                assert!(e.is_cancelled(), "{name}: {e}");
                assert_eq!(e.to_string(), "cancelled");
            }
            Ok(_) => panic!("{name}: a cancelled run returns no files"),
        }
    }
}

#[test]
fn a_cancel_in_the_last_phase_still_returns_no_files() {
    let (seen, out) = run("tube-helical.toml", |s| s.phase == Phase::Files);
    assert_eq!(seen.last().map(|s| s.phase), Some(Phase::Files));
    assert!(matches!(out, Err(RunError::Cancelled(_))));
}

/// The files of two runs agree (not `summary.json`, which holds a run time).
fn same_files(a: &RunOutput, b: &RunOutput) {
    let names = |r: &RunOutput| r.files.iter().map(|f| f.name.clone()).collect::<Vec<_>>();
    assert_eq!(names(a), names(b));
    for (x, y) in a.files.iter().zip(&b.files) {
        if !x.name.ends_with(".json") {
            assert!(x.bytes == y.bytes, "{}", x.name);
        }
    }
}

#[test]
fn a_watching_hook_sees_every_phase_end_and_changes_no_file() {
    for (name, phases) in [
        (
            "tube-axes-2axis.toml",
            &[
                Phase::Path,
                Phase::Eye,
                Phase::Axes,
                Phase::Blocks,
                Phase::Assembly,
                Phase::Post,
                Phase::Files,
            ][..],
        ),
        (
            "correct-mould.toml",
            &[Phase::Grid, Phase::Nodes, Phase::Files],
        ),
        ("dress-ballscrew-nut.toml", &[Phase::Forming, Phase::Files]),
    ] {
        let (seen, out) = run(name, |_| false);
        let hooked = out.unwrap();
        same_files(
            &run_job_file(&example(name), Path::new("out")).unwrap(),
            &hooked,
        );
        let mut order: Vec<Phase> = Vec::new();
        for s in &seen {
            assert!(s.done <= s.total, "{name}: {s:?}");
            if order.last() != Some(&s.phase) {
                assert!(!order.contains(&s.phase), "{name}: {} again", s.phase);
                order.push(s.phase);
            }
        }
        assert_eq!(order, phases, "{name}");
        for p in phases {
            let last = seen.iter().rev().find(|s| s.phase == *p).unwrap();
            assert_eq!(last.done, last.total, "{name}: {p}");
        }
    }
}
