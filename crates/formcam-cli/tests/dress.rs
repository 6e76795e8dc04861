//! `formcam dress` as users meet it: the outputs of the seed's job, checked
//! against each other, and one-line errors with nothing written for bad jobs.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

mod common;

use std::ffi::OsStr;
use std::path::Path;
use std::process::Output;

use common::{formcam, ok, scratch};

const EXAMPLE: &str = include_str!("../../../examples/dress-ballscrew-nut.toml");

/// Writes `text` as a job in a fresh folder and runs `formcam dress` on it.
fn run_job(name: &str, text: &str) -> (Output, std::path::PathBuf) {
    common::run_job(name, &["dress"], text)
}

/// `formcam dress JOB -o OUT`.
fn dress(job: impl AsRef<OsStr>, out: impl AsRef<OsStr>) -> Output {
    formcam()
        .arg("dress")
        .arg(job)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap()
}

fn read(out: &Path, file: &str) -> String {
    std::fs::read_to_string(out.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// The rows of a CSV as numbers by column name.
fn csv(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (header, rows)
}

#[test]
fn the_seed_job_writes_its_files() {
    // The outputs' contents are checked in formcam-run's tests; here what
    // the command writes and prints.
    let (o, out) = run_job("good", EXAMPLE);
    ok("dress", &o);
    let line = String::from_utf8_lossy(&o.stdout);
    assert_eq!(line.lines().count(), 1, "{line}");
    assert!(
        line.contains("points") && line.contains("feed control") && line.contains(" -> "),
        "{line}"
    );
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            ".formcam-run",
            "contour_final.csv",
            "contour_initial.csv",
            "contour_passes.csv",
            "dresser.csv",
            "job.toml",
            "mrr.csv",
            "mrr.svg",
            "profile.csv",
            "profile.svg",
            "program.cls",
            "program.mpf",
            "summary.json"
        ]
    );
    // The job as it ran, kept with its result.
    assert_eq!(read(&out, "job.toml"), EXAMPLE);
    // Every table heads the wheel's axes as the programs do: z, x.
    for file in names.iter().filter(|n| n.ends_with(".csv")) {
        let (h, rows) = csv(&read(&out, file));
        assert_eq!(&h[..2], ["z", "x"], "{file}");
        assert!(!rows.is_empty(), "{file}");
    }
    let summary: serde_json::Value = serde_json::from_str(&read(&out, "summary.json")).unwrap();
    let gotos = read(&out, "program.cls")
        .lines()
        .filter(|l| l.starts_with("GOTO/"))
        .count();
    assert_eq!(gotos as u64, summary["points"].as_u64().unwrap());
}

#[test]
fn bad_jobs_stop_with_one_line_and_write_nothing() {
    let cases = [
        (
            "r2 = 0.296",
            "r2 = 2.0",
            "wheel.r2 = 2 mm: the fillet does not fit",
        ),
        (
            "contact_angle_deg = 45.0",
            "contact_angle_deg = 90.0",
            "wheel.contact_angle_deg = 90.0 at 5:21: out of range; allowed (0, 90) deg",
        ),
        (
            "contact_angle_deg = 45.0",
            "contact_angle_deg = -5.0",
            "wheel.contact_angle_deg = -5.0 at 5:21: out of range; allowed (0, 90) deg",
        ),
        ("r1 = 1.937", "r1 = 1.85", "wheel.r1 = 1.85 mm"),
        (
            "step = 0.01",
            "step = 0.0",
            "process.step = 0.0 at 19:8: out of range; allowed >= 0.0001 mm",
        ),
        (
            "depth = 0.05",
            "depth = 2.5",
            "process.depth = 2.5 mm: larger than the wheel",
        ),
        (
            "width = 6.0",
            "width = nan",
            "wheel.width = nan at 8:9: out of range; allowed > 0 mm",
        ),
        (
            "feed_max = 300.0",
            "feed_max = 300.0\nfeed_rate = 3",
            "unknown field `feed_rate`",
        ),
        (
            "corner_radius_left = 0.258",
            "corner_radius_left = 0.4",
            "dresser.corner_radius_left = 0.4 mm",
        ),
    ];
    for (from, to, expect) in cases {
        assert!(EXAMPLE.contains(from), "{from}");
        let (o, out) = run_job("bad", &EXAMPLE.replacen(from, to, 1));
        assert_eq!(o.status.code(), Some(2), "{to}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(expect), "{to}: {err}");
        assert!(err.contains("job.toml"), "{err}");
        assert!(!out.join("program.cls").exists() && !out.join("program.mpf").exists());
        assert!(!out.exists() || std::fs::read_dir(&out).unwrap().next().is_none());
    }
}

#[test]
fn an_unwritable_output_leaves_no_program() {
    let dir = scratch("unwritable");
    let job = dir.join("job.toml");
    std::fs::write(&job, EXAMPLE).unwrap();
    // The output folder's place is taken by a file.
    let out = dir.join("out");
    std::fs::write(&out, "not a folder").unwrap();
    let o = dress(&job, &out);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(String::from_utf8_lossy(&o.stderr).lines().count(), 1);
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "not a folder");
}

#[test]
fn a_worn_contour_from_a_file() {
    let dir = scratch("worn");
    // A wheel worn unevenly: 0.03 mm allowance above the profile's bounding
    // line plus a bump, read from CSV beside the job.
    let mut csv = String::from("z,x\n");
    for i in 0..=600 {
        let x = -3.0 + 0.01 * i as f64;
        // Above the whole profile (apex at 1.875 mm): a flat-topped wheel.
        let y = 1.95 + 0.02 * (3.0 * x).cos();
        csv.push_str(&format!("{x},{y}\n"));
    }
    std::fs::write(dir.join("worn.csv"), csv).unwrap();
    let job = EXAMPLE.replace("depth = 0.05", "initial_contour = \"worn.csv\"");
    std::fs::write(dir.join("job.toml"), job).unwrap();
    let out = dir.join("out");
    let o = dress(dir.join("job.toml"), &out);
    ok("dress", &o);
    let summary: serde_json::Value = serde_json::from_str(&read(&out, "summary.json")).unwrap();
    assert!(summary["area_identity_rel_error"].as_f64().unwrap().abs() < 1e-9);
    assert!(
        summary["final_deviation_max_mm"].as_f64().unwrap()
            <= summary["scallop_bound_mm"].as_f64().unwrap()
    );
    // A contour below the profile is refused.
    std::fs::write(dir.join("worn.csv"), "z,x\n-3,0\n3,0\n").unwrap();
    let o = dress(dir.join("job.toml"), dir.join("out2"));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2));
    assert!(err.contains("process.initial_contour: it lies"), "{err}");
    // A line that cannot be read: the file and the line.
    std::fs::write(dir.join("worn.csv"), "z,x\n-3,2\n0,two\n3,2\n").unwrap();
    let o = dress(dir.join("job.toml"), dir.join("out3"));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("worn.csv:3: process.initial_contour: "),
        "{err}"
    );
    assert!(!dir.join("out3").exists());
}

#[test]
fn the_demo_runs_the_dressing_example() {
    let dir = scratch("demo");
    let examples = dir.join("examples");
    std::fs::create_dir_all(&examples).unwrap();
    std::fs::write(examples.join("dress-ballscrew-nut.toml"), EXAMPLE).unwrap();
    let out = dir.join("out");
    let o = common::demo(&examples, &out);
    ok("dress", &o);
    assert!(out.join("dress-ballscrew-nut/program.cls").exists());
    assert!(out.join("dress-ballscrew-nut/summary.json").exists());
}

#[test]
fn a_folder_in_the_way_leaves_the_last_run_whole() {
    let (o, out) = run_job("in-the-way", EXAMPLE);
    ok("dress", &o);
    let profile = read(&out, "profile.csv");
    let summary = read(&out, "summary.json");
    std::fs::remove_file(out.join("mrr.csv")).unwrap();
    std::fs::create_dir(out.join("mrr.csv")).unwrap();
    let job = out.parent().unwrap().join("job.toml");
    std::fs::write(&job, EXAMPLE.replace("step = 0.01", "step = 0.02")).unwrap();
    let o = dress(&job, &out);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("a folder is in the way"));
    assert_eq!(read(&out, "profile.csv"), profile);
    assert_eq!(read(&out, "summary.json"), summary);
    let names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into())
        .collect();
    assert!(names.iter().all(|n| !n.ends_with(".tmp")), "{names:?}");
}
