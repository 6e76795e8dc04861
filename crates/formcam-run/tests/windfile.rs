//! `.wind` documents run to their result files: a corpus of valid documents
//! that plan on the X/A/B winder (written from the format's specification),
//! warnings for unknown members, the eye over the mandrel, accepted checks.
//! (The reader's refusals are tested in formcam-program.)

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

mod common;

use std::path::Path;

use common::{machines, scratch, summary};
use formcam_program::{Check, EYE_CLEARANCE_MM};
use formcam_run::{RunOutput, wind_file};
use serde_json::{Value, json};

/// A valid 1.0 document: a cylinder 100 mm across, a hoop and a helical layer
/// whose 24 circuits (pi 100 cos 41 deg / 10, rounded up) three divide, with a
/// lockDegrees of a multiple of 60 deg stepping the circuits onto distinct slots.
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

/// Runs `doc` with the eye `clearance` mm over the mandrel, accepting `allow`.
fn run(name: &str, doc: &Value, clearance: f64, allow: &[Check]) -> RunOutput {
    let path = scratch(name).join("job.wind");
    std::fs::write(&path, serde_json::to_string_pretty(doc).unwrap()).unwrap();
    match wind_file(&path, Path::new("out"), clearance, allow) {
        Ok(run) => run,
        Err(e) => panic!("{name}: {e}"),
    }
}

/// Plans `doc` as `formcam wind` does by default; its summary.
fn plans(name: &str, doc: &Value) -> (Value, RunOutput) {
    let run = run(name, doc, EYE_CLEARANCE_MM, &[]);
    assert!(run.file("program.gcode").is_some(), "{name}");
    (summary(&run), run)
}

#[test]
fn valid_documents_plan() {
    let mut corpus: Vec<(&str, Value)> = vec![("base", base())];
    // An absent schemaVersion is 1.0.
    let mut d = base();
    d.as_object_mut().unwrap().remove("schemaVersion");
    corpus.push(("no-version", d));
    // A later minor of the same major is read.
    let mut d = base();
    d["schemaVersion"] = json!("1.12");
    corpus.push(("later-minor", d));
    // The first layer may be a skip: the mandrel turns before winding.
    let mut d = base();
    d["layers"] = json!([
        { "windType": "skip", "mandrelRotation": 90 },
        helical(41.0, 3, 180.0),
        { "windType": "skip", "mandrelRotation": -45.5 },
        { "windType": "hoop", "terminal": true }
    ]);
    corpus.push(("first-skip", d));
    // A reducing cone (1.1) with a helical layer that reaches its small end
    // (98 sin 30 deg = 49 <= 54), 45 circuits in patterns of three.
    let mut d = base();
    d["schemaVersion"] = json!("1.1");
    d["mandrelParameters"] = json!({ "diameter": 98, "windLength": 120, "endDiameter": 54 });
    d["towParameters"] = json!({ "width": 6, "thickness": 0.25 });
    d["layers"] = json!([helical(30.0, 3, 180.0)]);
    corpus.push(("cone", d));
    // An endDiameter equal to the diameter is a cylinder.
    let mut d = base();
    d["mandrelParameters"]["endDiameter"] = json!(100);
    corpus.push(("cone-of-no-taper", d));
    // frictionLambda 0 (1.3) is the geodesic; windAngle 90 is the hoop limit.
    let mut d = base();
    d["schemaVersion"] = json!("1.3");
    d["layers"][1]["frictionLambda"] = json!(0);
    d["layers"][1]["skipInitialNearLock"] = json!(true);
    d["layers"]
        .as_array_mut()
        .unwrap()
        .push(helical(90.0, 1, 180.0));
    corpus.push(("friction-zero-and-90", d));
    // No layers: a program without motion.
    let mut d = base();
    d["layers"] = json!([]);
    corpus.push(("no-layers", d));
    for (name, doc) in &corpus {
        let (s, _) = plans(name, doc);
        assert_eq!(s["machine"], "X/A/B winder", "{name}");
        assert!(s["checks_violated"].as_array().is_some(), "{name}");
    }
}

#[test]
fn unknown_members_are_ignored_with_a_warning() {
    let mut d = base();
    d["generator"] = json!("some CAD plug-in 4.2");
    d["mandrelParameters"]["material"] = json!("aluminium");
    d["layers"][1]["note"] = json!({ "text": "outer helical" });
    let (s, run) = plans("unknown-members", &d);
    let warnings: Vec<String> = s["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_str().unwrap().to_string())
        .collect();
    for member in ["generator", "mandrelParameters.material", "layers[1].note"] {
        assert!(
            warnings.iter().any(|w| w.starts_with(member)),
            "{member}: {warnings:?}"
        );
        // The warnings a caller prints on stderr.
        assert!(
            run.warnings.iter().any(|w| w.contains(member)),
            "{member}: {:?}",
            run.warnings
        );
    }
}

/// Shallow helical layers on a small mandrel: the eye rides over the mandrel
/// (its radius plus the clearance), so the carriage stays near the band and
/// within its travel.
#[test]
fn shallow_helicals_on_small_mandrels_are_wound_with_the_eye_over_the_mandrel() {
    let machine = std::fs::read_to_string(machines().join("winder-xab.toml")).unwrap();
    assert!(machine.contains("min_mm = -600.0") && machine.contains("max_mm = 3000.0"));
    for angle in [20.0, 25.0, 30.0] {
        let doc = json!({
            "mandrelParameters": { "diameter": 60, "windLength": 300 },
            "towParameters": { "width": 6, "thickness": 0.3 },
            "defaultFeedRate": 3000,
            "layers": [helical(angle, 1, 720.0)]
        });
        let name = format!("shallow-{angle}");
        let (s, _) = plans(&name, &doc);
        assert_eq!(s["eye_radius_mm"].as_f64().unwrap(), 30.0 + 25.0);
        assert_eq!(s["eye_clearance_mm"].as_f64().unwrap(), 25.0);
        let x = s["axis_ranges"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["axis"] == "X")
            .unwrap();
        let (lo, hi) = (x["min"].as_f64().unwrap(), x["max"].as_f64().unwrap());
        // The carriage stays within its travel: the eye leads the band by its
        // axial lead sqrt(R^2 - r^2) / tan(angle) (plus the turn-around on the
        // tube's extension), 127 mm at 20 deg, where an eye 250 mm out would
        // lead by 682 mm, beyond the carriage's -600 mm.
        let lead = |r_eye: f64| (r_eye * r_eye - 30.0f64.powi(2)).sqrt() / angle.to_radians().tan();
        let overrun = (-lo).max(hi - 300.0);
        assert!(lo > -600.0 && hi < 3000.0, "{name}: X in [{lo}, {hi}]");
        assert!(
            overrun > lead(55.0) && overrun < lead(55.0) + 60.0,
            "{name}: X in [{lo}, {hi}], lead {}",
            lead(55.0)
        );
        assert!(lead(250.0) > 4.0 * lead(55.0));
        // Only the eye's slack may be accepted for a .wind job, and it is said.
        for v in s["checks_violated"].as_array().unwrap() {
            assert_eq!(v["check"], "slack", "{name}: {v}");
        }
    }
    let doc = json!({
        "mandrelParameters": { "diameter": 60, "windLength": 300 },
        "towParameters": { "width": 6, "thickness": 0.3 },
        "defaultFeedRate": 3000,
        "layers": [helical(25.0, 1, 720.0)]
    });
    let run = run("clearance-40", &doc, 40.0, &[]);
    let s = summary(&run);
    assert_eq!(s["eye_radius_mm"].as_f64().unwrap(), 70.0);
    let path = scratch("clearance-0").join("job.wind");
    std::fs::write(&path, doc.to_string()).unwrap();
    let e = match wind_file(&path, Path::new("out"), 0.0, &[]) {
        Ok(_) => panic!("a clearance of 0 accepted"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("--eye-clearance"), "{e}");
}

/// An accepted failed check is named in the summary and in the program's
/// header; accepting others does not hide it.
#[test]
fn accepted_slack_is_reported_in_the_summary_and_the_header() {
    // A short lock lets the band go slack at the turn-arounds.
    let doc = json!({
        "mandrelParameters": { "diameter": 60, "windLength": 300 },
        "towParameters": { "width": 6, "thickness": 0.3 },
        "defaultFeedRate": 3000,
        "layers": [helical(20.0, 1, 180.0)]
    });
    run(
        "allow-more",
        &doc,
        EYE_CLEARANCE_MM,
        &[Check::Timing, Check::Limits],
    );
    let (s, run) = plans("slack", &doc);
    assert_eq!(s["checks_accepted"], json!(["slack"]));
    let program = common::text(&run, "program.gcode");
    let header: Vec<&str> = program.lines().take(10).collect();
    assert!(
        header
            .iter()
            .any(|l| l.contains("checks accepted as violated") && l.contains("slack")),
        "{header:?}"
    );
}

#[test]
fn the_result_keeps_the_document_and_names_it_by_its_absolute_path() {
    let dir = scratch("kept");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let text = serde_json::to_string_pretty(&base()).unwrap();
    std::fs::write(dir.join("job.wind"), &text).unwrap();
    // Given through `..`: the summary names the file resolved.
    let run = wind_file(
        &dir.join("sub/../job.wind"),
        Path::new("out"),
        EYE_CLEARANCE_MM,
        &[],
    )
    .unwrap();
    let named = dir.join("job.wind").canonicalize().unwrap();
    assert_eq!(
        summary(&run)["job"].as_str().map(Path::new),
        Some(named.as_path())
    );
    assert_eq!(
        run.file("job.wind").map(|f| f.bytes.clone()),
        Some(text.into_bytes())
    );
    assert!(run.file("job.toml").is_none());
}
