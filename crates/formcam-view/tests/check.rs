//! The view's own check of a result without `check.json`: formcam-sim's
//! whole check (the axes, the collisions of the machine's solids and, when
//! the job that made the result is found, the mandrel and the free fibre),
//! the same violations as `formcam wind` and `formcam check` report, and
//! the checks that ran named.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_machine::Machine;
use formcam_nc::{Block, Dialect, Feed, Program, write};
use formcam_sim::{ViolationKind, check_text_with, program_axes};
use formcam_view::{Page, View};
use serde_json::Value;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("view-check")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn violations(view: &View) -> Value {
    let (status, _, body) = view.answer("/api/violations");
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    serde_json::from_slice(&body).unwrap()
}

/// The violations as the report writes them (without the view's `spans`).
fn reported(v: &Value) -> Vec<Value> {
    v["violations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| {
            let mut x = x.clone();
            x.as_object_mut().unwrap().remove("spans");
            x
        })
        .collect()
}

/// The shipped 4-axis winder with a sphere of radius 400 mm on the mandrel
/// link: the eye's carrier, 200 to 300 mm from the spindle's axis, runs
/// inside it.
fn clashing_machine() -> String {
    let text = formcam_machine::shipped::shipped("winder-4axis")
        .unwrap()
        .text;
    let mandrel = "[[link]]\nname = \"mandrel\"\nparent = \"spindle\"\n";
    assert!(text.contains(mandrel));
    text.replace(
        mandrel,
        &format!("{mandrel}[[link.visual]]\nshape = \"sphere\"\nradius = 400.0\n"),
    )
}

#[test]
fn a_result_without_check_json_is_checked_for_collisions() {
    let dir = fresh("clash");
    std::fs::write(dir.join("machine.toml"), clashing_machine()).unwrap();
    let m = Machine::from_toml(&clashing_machine()).unwrap();
    let mut p = Program::new("CLASH", program_axes(&m));
    p.blocks.push(Block::rapid(vec![0.0, 0.0, 250.0, 0.0]));
    p.blocks.push(Block::linear(
        vec![90.0, 100.0, 240.0, 10.0],
        Feed::InverseTime(2.0),
    ));
    p.blocks.push(Block::linear(
        vec![180.0, 200.0, 260.0, 0.0],
        Feed::InverseTime(2.0),
    ));
    let mut text = String::new();
    write(&p, Dialect::Sinumerik840d, &mut text).unwrap();
    std::fs::write(dir.join("program.mpf"), &text).unwrap();
    // The job that made it is not there.
    std::fs::write(
        dir.join("summary.json"),
        format!(
            r#"{{"job": "{}", "machine_file": "machine.toml", "program_file": "program.mpf"}}"#,
            dir.join("gone.toml").display()
        ),
    )
    .unwrap();
    let view = View::open(&dir, None, Page::none()).unwrap();
    let v = violations(&view);
    assert_eq!(v["source"], "check");
    assert_eq!(v["checks"], serde_json::json!(["axes", "collisions"]));
    let why = v["unchecked"].as_str().unwrap();
    assert!(
        why.contains("gone.toml") && why.contains("not found"),
        "{why}"
    );
    assert_eq!(v["clean"], false);
    // formcam-sim's check of the same text, as `formcam check` runs it.
    let r = check_text_with(&dir.join("program.mpf"), &text, &m, "", Some(&dir), None).unwrap();
    let want: Vec<Value> = r
        .violations
        .iter()
        .map(|x| serde_json::to_value(x).unwrap())
        .collect();
    assert_eq!(reported(&v), want);
    let c = r
        .violations
        .iter()
        .find(|x| x.kind == ViolationKind::Collision && x.links.contains(&"mandrel".to_string()))
        .unwrap_or_else(|| panic!("no collision with the mandrel link: {v}"));
    assert_eq!(c.block, 1, "{c:?}");
    assert!(c.worst_value < 0.0, "{c:?}");
    // The same folder without the sphere: no collision.
    std::fs::write(
        dir.join("machine.toml"),
        formcam_machine::shipped::shipped("winder-4axis")
            .unwrap()
            .text,
    )
    .unwrap();
    let v = violations(&View::open(&dir, None, Page::none()).unwrap());
    assert!(reported(&v).iter().all(|x| x["kind"] != "collision"), "{v}");
}

#[test]
fn with_its_job_the_view_checks_the_mandrel_and_the_fibre_as_wind_does() {
    // The 4-axis tube's hoop layer with its eye 6 mm over the mandrel: the
    // eye's roller (radius 12) runs inside the mandrel's solid.
    let dir = fresh("hoop");
    let text = std::fs::read_to_string(repo().join("examples/tube-layers-4axis.toml"))
        .unwrap()
        .replace(
            "../machines/",
            &format!("{}/", repo().join("machines").display()),
        );
    let (head, _) = text.split_once("\n[[layer]]\nkind = \"helical\"").unwrap();
    let (_, tail) = text.split_once("\n[eye]").unwrap();
    let job = dir.join("job.toml");
    std::fs::write(
        &job,
        format!("{head}\n[eye]{tail}").replace("clearance = 20.0", "clearance = 6.0"),
    )
    .unwrap();
    let out = dir.join("out");
    let run = formcam_run::run_job_file(&job, &out).unwrap();
    for f in &run.files {
        let path = out.join(&f.name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, &f.bytes).unwrap();
    }
    let written: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("check.json")).unwrap()).unwrap();
    let by_wind = written["violations"].as_array().unwrap().clone();
    assert!(
        by_wind.iter().any(
            |x| x["kind"] == "collision" && x["links"] == serde_json::json!(["eye", "mandrel"])
        ),
        "{written}"
    );
    // With check.json: the report. Without: the view's own, the same.
    let v = violations(&View::open(&out, None, Page::none()).unwrap());
    assert_eq!(v["source"], "check.json");
    std::fs::remove_file(out.join("check.json")).unwrap();
    let v = violations(&View::open(&out, None, Page::none()).unwrap());
    assert_eq!(v["source"], "check");
    assert_eq!(
        v["checks"],
        serde_json::json!(["axes", "collisions", "mandrel", "snag"])
    );
    assert!(v["unchecked"].is_null(), "{v}");
    assert_eq!(reported(&v), by_wind);
}
