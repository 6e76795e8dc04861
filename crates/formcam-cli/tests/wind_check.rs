//! `formcam wind` checks the program it wrote on its machine: every bundled
//! winding program is clean (the planner keeps the machines' acceleration
//! limits by default), the report in `check.json` is the one `formcam
//! check --mandrel JOB` writes for the same file (the mandrel grown by the
//! laminate and the free fibre checked too), a job that switches the
//! acceleration limits off is told its violations and exits 3 with its
//! program written, an eye too close to the mandrel is found by both, and
//! `--no-check` skips the check.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::{Path, PathBuf};

use common::{example, examples, formcam, json, machines, run_file, s, scratch, stderr};

fn stdout(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The examples whose furthest stage is a program: `.wind` documents, and
/// winding jobs with a machine and a post or layers.
fn program_jobs() -> Vec<PathBuf> {
    let mut jobs: Vec<PathBuf> = std::fs::read_dir(examples())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
            let text = std::fs::read_to_string(p).unwrap_or_default();
            ext == "wind"
                || (ext == "toml"
                    && text.contains("\n[machine]")
                    && (text.contains("\n[post]") || text.contains("\n[[layer]]")))
        })
        .collect();
    jobs.sort();
    jobs
}

/// The `--machine` argument `check.json` names.
fn machine_of(report: &serde_json::Value) -> String {
    report["machine"].as_str().unwrap().to_string()
}

#[test]
fn every_bundled_winding_program_checks_clean() {
    let dir = scratch("examples");
    let jobs = program_jobs();
    let mut programs = Vec::new();
    for job in &jobs {
        let name = job.file_stem().unwrap().to_string_lossy().into_owned();
        let out = dir.join(&name);
        let o = formcam()
            .args(["wind", s(job), "-o", s(&out)])
            .output()
            .unwrap();
        let line = stdout(&o);
        assert_eq!(o.status.code(), Some(0), "{name}: {line}{}", stderr(&o));
        assert!(line.contains("; checked: clean ("), "{name}: {line}");
        let report = json(out.join("check.json"));
        assert_eq!(report["clean"], true, "{name}: {report}");
        assert_eq!(report["violations"], serde_json::json!([]), "{name}");
        // The same verdict as `formcam check --mandrel JOB` on the written
        // file.
        let program = PathBuf::from(report["program"].as_str().unwrap());
        assert!(program.starts_with(&out), "{}", program.display());
        let again = dir.join(format!("{name}.json"));
        let o = formcam()
            .args(["check", s(&program), "--machine", &machine_of(&report)])
            .args(["--mandrel", s(job), "-o", s(&again)])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stdout(&o));
        assert_eq!(
            std::fs::read_to_string(&again).unwrap(),
            std::fs::read_to_string(out.join("check.json")).unwrap(),
            "{name}"
        );
        programs.push(name);
    }
    // Marlin (2), LinuxCNC, CLDATA and Sinumerik 840D (2): one and many layers.
    assert!(programs.len() >= 6, "{programs:?}");
}

/// The 840D vessel example with `[motion] acceleration` set.
fn vessel(acceleration: bool) -> String {
    example("vessel-program-840d.toml").replace(
        "# acceleration = true",
        &format!("acceleration = {acceleration} #"),
    )
}

#[test]
fn a_job_without_acceleration_limits_is_told_its_violations() {
    let text = vessel(false);
    assert!(text.contains("acceleration = false"));
    let (o, out) = run_file("free", &["wind"], "job.toml", &text, &[], &[]);
    let line = stdout(&o);
    assert_eq!(o.status.code(), Some(3), "{line}{}", stderr(&o));
    assert_eq!(line.lines().count(), 1, "{line}");
    assert!(line.contains("; checked: "), "{line}");
    assert!(line.contains(" violation"), "{line}");
    assert!(line.contains("): acceleration at block "), "{line}");
    // Written all the same, with the report.
    assert!(out.join("program.mpf").exists());
    let report = json(out.join("check.json"));
    assert_eq!(report["clean"], false);
    let kinds: Vec<&str> = report["violations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["kind"].as_str().unwrap())
        .collect();
    assert!(
        !kinds.is_empty() && kinds.iter().all(|k| *k == "acceleration"),
        "{kinds:?}"
    );
    assert_eq!(
        report["machine"].as_str().unwrap(),
        machines().join("winder-4axis.toml").display().to_string()
    );

    // The same job with the limits kept (the default) is clean and slower.
    let (o, kept) = run_file("kept", &["wind"], "job.toml", &vessel(true), &[], &[]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert_eq!(json(kept.join("check.json"))["clean"], true);
    let time = |dir: &Path| common::summary(dir)["program_time_s"].as_f64().unwrap();
    assert!(
        time(&kept) > time(&out),
        "{} vs {}",
        time(&kept),
        time(&out)
    );
}

/// The 4-axis tube's hoop layer alone, its eye `clearance` mm over the
/// mandrel (the eye's roller has a radius of 12 mm).
fn hoop(clearance: &str) -> String {
    let text = example("tube-layers-4axis.toml");
    let (head, _) = text.split_once("\n[[layer]]\nkind = \"helical\"").unwrap();
    let (_, tail) = text.split_once("\n[eye]").unwrap();
    format!("{head}\n[eye]{tail}").replace("clearance = 20.0", &format!("clearance = {clearance}"))
}

#[test]
fn the_mandrel_and_the_fibre_are_checked_as_check_does() {
    // 6 mm: the roller runs inside the mandrel's solid (the bundled jobs,
    // clean, are compared above).
    let (o, out6) = run_file("hoop6", &["wind"], "job.toml", &hoop("6.0"), &[], &[]);
    let line = stdout(&o);
    assert_eq!(o.status.code(), Some(3), "{line}{}", stderr(&o));
    assert!(
        line.contains("; checked: ") && line.contains(" violation"),
        "{line}"
    );
    let report = json(out6.join("check.json"));
    let eye_in_mandrel =
        report["violations"].as_array().unwrap().iter().any(|v| {
            v["kind"] == "collision" && v["links"] == serde_json::json!(["eye", "mandrel"])
        });
    assert!(eye_in_mandrel, "{report}");
    // Byte for byte what `formcam check --mandrel JOB` writes: exit 3 too.
    let program = report["program"].as_str().unwrap();
    let job = out6.parent().unwrap().join("job.toml");
    let again = out6.parent().unwrap().join("again.json");
    let o = formcam()
        .args(["check", program, "--machine", &machine_of(&report)])
        .args(["--mandrel", s(&job), "-o", s(&again)])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(&again).unwrap(),
        std::fs::read_to_string(out6.join("check.json")).unwrap()
    );
}

#[test]
fn no_check_skips_the_check() {
    let (o, out) = run_file(
        "skip",
        &["wind"],
        "job.toml",
        &vessel(false),
        &[],
        &["--no-check"],
    );
    let line = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{line}{}", stderr(&o));
    assert!(!line.contains("checked"), "{line}");
    assert!(out.join("program.mpf").exists());
    assert!(!out.join("check.json").exists());
    // Stages without a program check nothing either.
    let (o, out) = run_file(
        "axes",
        &["wind", "axes"],
        "job.toml",
        &vessel(false),
        &[],
        &[],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!out.join("check.json").exists());
}
