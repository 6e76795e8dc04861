//! A winding result opens from any folder: a job given by a relative path,
//! its machine named relative to the job, run in one folder and viewed from
//! another. The summary records the job's absolute path, so the machine is
//! found; the result keeps the job's text as it ran (`job.toml`), so the
//! view's own check plans the job again for the mandrel even once the job
//! file has changed; a result without that copy (written before formcam
//! kept one) falls back to the job file the summary names.
//!
//! The test changes the process's current folder, so it is the only test
//! of this file (its own process).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_program::Stage;
use formcam_results::names;
use formcam_run::ProgramCheck;
use formcam_run::progress::Silent;
use formcam_view::{Page, View};
use serde_json::Value;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A fresh, empty folder.
fn fresh(path: &Path) -> PathBuf {
    let _ = std::fs::remove_dir_all(path);
    std::fs::create_dir_all(path).unwrap();
    path.canonicalize().unwrap()
}

/// `/api/violations` of the result `out`, opened from the current folder.
fn violations(out: &Path) -> Value {
    let view = View::open(out, None, Page::none()).unwrap();
    let (status, _, body) = view.answer("/api/violations");
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    serde_json::from_slice(&body).unwrap()
}

/// Whether the view's own check planned the job for the mandrel.
fn mandrel_checked(v: &Value) -> bool {
    v["source"] == "check"
        && v["checks"]
            .as_array()
            .unwrap()
            .iter()
            .any(|c| c == "mandrel")
}

#[test]
fn a_result_opens_with_its_machine_and_mandrel_check_from_another_folder() {
    let root = fresh(&Path::new(env!("CARGO_TARGET_TMPDIR")).join("view-anywhere"));
    // The job and its machine, laid out as in the repository: the job names
    // `../machines/winder-4axis.toml`, whose mesh is beside it.
    let here = root.join("here");
    for d in ["jobs", "machines/meshes"] {
        std::fs::create_dir_all(here.join(d)).unwrap();
    }
    let text = std::fs::read_to_string(repo().join("examples/vessel-program-840d.toml")).unwrap();
    assert!(text.contains("file = \"../machines/winder-4axis.toml\""));
    std::fs::write(here.join("jobs/vessel.toml"), &text).unwrap();
    for m in ["winder-4axis.toml", "meshes/chuck-flange.stl"] {
        std::fs::copy(
            repo().join("machines").join(m),
            here.join("machines").join(m),
        )
        .unwrap();
    }

    // `formcam wind jobs/vessel.toml -o out --no-check` in `here` (no
    // `check.json`: the view checks the program itself).
    std::env::set_current_dir(&here).unwrap();
    let job = Path::new("jobs/vessel.toml");
    let out = Path::new("out");
    let run = formcam_run::wind_checked_with(job, out, Stage::Program, ProgramCheck::Off, &Silent)
        .unwrap();
    assert!(run.file(names::CHECK).is_none());
    let files: Vec<(&str, &[u8])> = run
        .files
        .iter()
        .map(|f| (f.name.as_str(), f.bytes.as_slice()))
        .collect();
    formcam_files::write_folder(out, &files, &run.inputs).unwrap();
    let out = here.join("out");
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join(names::SUMMARY)).unwrap()).unwrap();
    assert_eq!(
        summary["job"].as_str().map(PathBuf::from),
        Some(here.join("jobs/vessel.toml")),
        "the job's absolute path"
    );
    assert_eq!(summary["machine_file"], "../machines/winder-4axis.toml");
    assert_eq!(
        std::fs::read_to_string(out.join(names::JOB)).unwrap(),
        text,
        "the job as it ran"
    );

    // Viewed from another folder: the machine is the job's, the job found.
    let elsewhere = fresh(&root.join("elsewhere"));
    std::env::set_current_dir(&elsewhere).unwrap();
    let v = violations(&out);
    assert!(mandrel_checked(&v), "{v:#}");
    assert!(v["unchecked"].is_null(), "{v:#}");

    // The job file changed since: the copy is the job that made the program.
    std::fs::write(here.join("jobs/vessel.toml"), "no job at all [").unwrap();
    let v = violations(&out);
    assert!(mandrel_checked(&v), "{v:#}");

    // A result without the copy reads the job file the summary names:
    // gone, it is named as not found.
    std::fs::remove_file(out.join(names::JOB)).unwrap();
    std::fs::remove_file(here.join("jobs/vessel.toml")).unwrap();
    let v = violations(&out);
    assert!(!mandrel_checked(&v), "{v:#}");
    let why = v["unchecked"].as_str().unwrap();
    assert!(
        why.contains("not found")
            && why.contains(&here.join("jobs/vessel.toml").display().to_string()),
        "{why}"
    );
}
