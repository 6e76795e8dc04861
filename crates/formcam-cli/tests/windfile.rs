//! `formcam wind DOC.wind` as users meet it: its options (`--eye-clearance`,
//! `--allow`), warnings on stderr, one-line errors with nothing written. The
//! documents' plans are tested in formcam-run, the reader's rules in
//! formcam-program.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::PathBuf;
use std::process::Output;

use common::{ok, one_line_error, run_file, stderr, summary};
use serde_json::{Value, json};

/// Runs `formcam wind DOC.wind -o OUT EXTRA...`; returns the output and `OUT`.
fn wind(name: &str, doc: &Value, extra: &[&str]) -> (Output, PathBuf) {
    let text = serde_json::to_string_pretty(doc).unwrap();
    run_file(name, &["wind"], "job.wind", &text, &[], extra)
}

/// A valid 1.0 document: a cylinder 100 mm across, a hoop and a helical layer
/// whose 24 circuits three divide.
fn base() -> Value {
    json!({
        "schemaVersion": "1.0",
        "mandrelParameters": { "diameter": 100, "windLength": 400 },
        "towParameters": { "width": 10, "thickness": 0.3 },
        "defaultFeedRate": 1500,
        "layers": [{ "windType": "hoop", "terminal": false }, helical(41.0, 3, 180.0)]
    })
}

fn helical(angle: f64, pattern: u32, lock: f64) -> Value {
    json!({
        "windType": "helical",
        "windAngle": angle,
        "patternNumber": pattern,
        "skipIndex": 1,
        "lockDegrees": lock,
        "leadInMM": 10,
        "leadOutDegrees": 10
    })
}

/// A small tube whose short lock lets the band go slack at the turn-arounds.
fn slack_tube() -> Value {
    json!({
        "mandrelParameters": { "diameter": 60, "windLength": 300 },
        "towParameters": { "width": 6, "thickness": 0.3 },
        "defaultFeedRate": 3000,
        "layers": [helical(20.0, 1, 180.0)]
    })
}

#[test]
fn unknown_members_are_warned_of_on_stderr() {
    let mut d = base();
    d["generator"] = json!("some CAD plug-in 4.2");
    d["layers"][1]["note"] = json!({ "text": "outer helical" });
    let (st, out) = wind("unknown-members", &d, &[]);
    ok("unknown-members", &st);
    assert!(out.join("program.gcode").exists());
    let err = stderr(&st);
    for member in ["generator", "layers[1].note"] {
        assert!(err.contains(member), "{member}: {err}");
    }
}

#[test]
fn invalid_documents_fail_with_one_line_and_write_nothing() {
    // The reader's rules are tested in formcam-program; here the contract of
    // the command: exit status, one line naming the file and the member.
    type Edit = Box<dyn Fn(&mut Value)>;
    let cases: Vec<(&str, Edit, &[&str])> = vec![
        (
            "major-2",
            Box::new(|d| d["schemaVersion"] = json!("2.0")),
            &["schemaVersion", "not supported"],
        ),
        (
            "not-coprime",
            Box::new(|d| {
                d["layers"][1]["patternNumber"] = json!(4);
                d["layers"][1]["skipIndex"] = json!(2);
            }),
            &["layers[1].skipIndex", "coprime"],
        ),
        (
            "misspelt-member",
            Box::new(|d| {
                d["towParameters"] = json!({ "widht": 10, "thickness": 0.3 });
            }),
            &["towParameters.width", "missing", "towParameters.widht"],
        ),
    ];
    for (name, edit, want) in cases {
        let mut d = base();
        edit(&mut d);
        let (st, out) = wind(name, &d, &[]);
        let err = one_line_error(name, &st, &out);
        assert!(err.contains("job.wind"), "{name}: {err}");
        for w in want {
            assert!(err.contains(w), "{name}: wants {w:?}: {err}");
        }
    }
}

#[test]
fn the_eye_clearance_is_an_option() {
    let doc = json!({
        "mandrelParameters": { "diameter": 60, "windLength": 300 },
        "towParameters": { "width": 6, "thickness": 0.3 },
        "defaultFeedRate": 3000,
        "layers": [helical(25.0, 1, 720.0)]
    });
    let (st, out) = wind("clearance-40", &doc, &["--eye-clearance", "40"]);
    ok("clearance-40", &st);
    assert_eq!(summary(&out)["eye_radius_mm"].as_f64().unwrap(), 70.0);
    let (st, out) = wind("clearance-0", &doc, &["--eye-clearance", "0"]);
    assert!(one_line_error("clearance-0", &st, &out).contains("--eye-clearance"));
}

/// `--allow` takes check names; a typo is refused, other names accepted, and
/// the slack a `.wind` job always accepts is said in the summary.
#[test]
fn allow_takes_check_names() {
    let doc = slack_tube();
    let (st, out) = wind("allow-typo", &doc, &["--allow", "timing,slak"]);
    assert!(!st.status.success() && !out.exists());
    assert!(stderr(&st).contains("slak"));
    let (st, out) = wind("allow-more", &doc, &["--allow", "timing,limits"]);
    ok("allow-more", &st);
    let accepted = summary(&out)["checks_accepted"].clone();
    assert!(
        accepted.as_array().unwrap().contains(&json!("slack")),
        "{accepted}"
    );
}
