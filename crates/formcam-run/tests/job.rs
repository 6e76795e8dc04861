//! `formcam_run::run_job_file` on the bundled examples: each job file told
//! by its kind and run by that kind's pipeline (the same files and line as
//! calling the pipeline itself), and the demo's list of examples.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use std::path::{Path, PathBuf};

use formcam_run::{
    JobKind, RunOutput, correct_job, correct_simulate, demo, demo_folder, dress, dressing_for,
    run_job_file, wind_file, wind_furthest,
};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn names(run: &RunOutput) -> Vec<&str> {
    run.files.iter().map(|f| f.name.as_str()).collect()
}

/// The files (names and bytes, except those that carry a run time) and
/// the line of two runs agree, up to the time a run reports.
fn same_run(a: &RunOutput, b: &RunOutput) {
    assert_eq!(names(a), names(b));
    for (x, y) in a.files.iter().zip(&b.files) {
        if !x.name.ends_with(".json") {
            assert_eq!(x.bytes, y.bytes, "{}", x.name);
        }
    }
    // The line's run time (`in 1.2 s`, `15.8 ms`) differs from run to run.
    let strip = |l: &str| {
        let head = l.split(" in ").next().unwrap_or(l);
        let words: Vec<&str> = head.split(' ').collect();
        words
            .iter()
            .enumerate()
            .map(|(i, w)| match words.get(i + 1) {
                Some(next) if next.starts_with("ms") => "#",
                _ => w,
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    assert_eq!(strip(&a.line), strip(&b.line));
}

#[test]
fn every_example_has_the_kind_its_tables_say() {
    let jobs = demo(&examples()).unwrap();
    assert!(jobs.len() >= 6);
    let mut sorted = jobs.clone();
    sorted.sort();
    assert_eq!(jobs, sorted);
    for job in &jobs {
        let text = std::fs::read_to_string(job).unwrap();
        let want = if job.extension().is_some_and(|x| x == "wind") {
            JobKind::WindFile
        } else if text.contains("\n[warp]") {
            JobKind::Scenario
        } else if text.contains("\n[correct]") || text.starts_with("[correct]") {
            JobKind::Correction
        } else if text.contains("\n[wheel]") {
            JobKind::Dressing
        } else {
            JobKind::Winding
        };
        assert_eq!(JobKind::of(job, &text), want, "{}", job.display());
    }
}

#[test]
fn each_kind_runs_by_its_own_pipeline() {
    let ex = examples();
    let out = Path::new("out");
    let dress_job = ex.join("dress-ballscrew-nut.toml");
    let by_kind = run_job_file(&dress_job, out).unwrap();
    same_run(
        &by_kind,
        &dressing_for(&dress_job, out, dress(&dress_job).unwrap()),
    );
    assert!(by_kind.line.ends_with(&format!(" -> {}", out.display())));
    assert!(by_kind.file("program.cls").is_some());

    let mould = ex.join("correct-mould.toml");
    let text = std::fs::read_to_string(&mould).unwrap();
    let by_kind = run_job_file(&mould, out).unwrap();
    same_run(&by_kind, &correct_job(&mould, &text, out).unwrap());
    assert!(by_kind.file("report.json").is_some());

    let wind = ex.join("tube-fiberpath.wind");
    same_run(
        &run_job_file(&wind, out).unwrap(),
        &wind_file(&wind, out, formcam_program::EYE_CLEARANCE_MM, &[]).unwrap(),
    );

    let tube = ex.join("tube-helical.toml");
    same_run(
        &run_job_file(&tube, out).unwrap(),
        &wind_furthest(&tube, out).unwrap(),
    );
}

#[test]
fn a_scenario_runs_its_closed_loop() {
    let job = examples().join("correct-panel-loop.toml");
    let text = std::fs::read_to_string(&job).unwrap();
    let out = Path::new("out");
    same_run(
        &run_job_file(&job, out).unwrap(),
        &correct_simulate(&job, &text, out).unwrap(),
    );
}

#[test]
fn the_demo_folder_is_the_job_stem() {
    assert_eq!(
        demo_folder(Path::new("out"), Path::new("examples/tube-helical.toml")),
        Path::new("out").join("tube-helical")
    );
}

#[test]
fn an_unreadable_job_names_its_file() {
    let missing = examples().join("no-such-job.toml");
    let err = run_job_file(&missing, Path::new("out")).unwrap_err();
    assert!(
        err.to_string().starts_with(&format!(
            "{}: cannot read the job file: ",
            missing.display()
        )),
        "{err}"
    );
}

/// Each run names every file it read, the job first, so that the writer
/// can refuse an output on any of them.
#[test]
fn each_run_names_the_files_it_read() {
    let ex = examples();
    let ends = |run: &RunOutput, want: &[&str]| {
        let got: Vec<String> = run
            .inputs
            .iter()
            .map(|p| p.to_string_lossy().replace('\\', "/"))
            .collect();
        assert_eq!(got.len(), want.len(), "{got:?}");
        for (g, w) in got.iter().zip(want) {
            assert!(g.ends_with(w), "{g} is not {w}");
        }
    };
    let run = run_job_file(&ex.join("vessel-program-840d.toml"), Path::new("o")).unwrap();
    ends(
        &run,
        &["vessel-program-840d.toml", "../machines/winder-4axis.toml"],
    );
    let run = run_job_file(&ex.join("profile-waist.toml"), Path::new("o")).unwrap();
    ends(&run, &["profile-waist.toml", "waist-meridian.csv"]);
    let run = run_job_file(&ex.join("vessel-eye-curve.toml"), Path::new("o")).unwrap();
    ends(&run, &["vessel-eye-curve.toml", "eye-curve.csv"]);
    let run = run_job_file(&ex.join("tube-fiberpath.wind"), Path::new("o")).unwrap();
    ends(&run, &["tube-fiberpath.wind"]);
    let run = run_job_file(&ex.join("correct-mould.toml"), Path::new("o")).unwrap();
    ends(
        &run,
        &["correct-mould.toml", "correct/cmm.csv", "correct/mould.nc"],
    );
    let run = run_job_file(&ex.join("correct-panel-loop.toml"), Path::new("o")).unwrap();
    ends(&run, &["correct-panel-loop.toml"]);
}
