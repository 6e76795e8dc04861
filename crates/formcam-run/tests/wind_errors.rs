//! Winding jobs the library refuses: one line naming the job file and the
//! field (the CLI prints it as it is).

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

mod common;

use std::path::Path;

use common::{examples, machines, scratch};
use formcam_program::{EYE_CLEARANCE_MM, Stage};
use formcam_run::{wind, wind_file};

const VESSEL: &str = r#"
[mandrel]
kind = "vessel"
radius = 100.0
cylinder_length = 300.0
dome = "hemisphere"
polar_opening = 30.0
"#;

/// Runs `job` (with `extra` files beside it) up to `stage`; returns its error
/// after checking that it is one line naming the job file.
fn fails_in(stage: Stage, name: &str, job: &str, extra: &[(&str, &str)]) -> String {
    let dir = scratch(name);
    let path = dir.join("job.toml");
    std::fs::write(&path, job).unwrap();
    for (f, text) in extra {
        std::fs::write(dir.join(f), text).unwrap();
    }
    let err = match wind(&path, &dir.join("out"), stage) {
        Ok(_) => panic!("{name}: should fail"),
        Err(e) => e.to_string(),
    };
    assert_eq!(err.lines().count(), 1, "{name}: not one line: {err}");
    assert!(err.contains("job.toml"), "{name}: file not named: {err}");
    err
}

fn fails(name: &str, job: &str, extra: &[(&str, &str)]) -> String {
    fails_in(Stage::Path, name, job, extra)
}

#[test]
fn bad_jobs_fail_with_one_line_naming_the_field() {
    let w = "[winding]\nmu = 0.0\nband_width = 10.0\nband_thickness = 0.5\n";
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "unknown-kind",
            format!("[mandrel]\nkind = \"sphere\"\nradius = 1.0\n{w}"),
            "mandrel.kind",
        ),
        (
            "missing-field",
            format!("{VESSEL}[winding]\nmu = 0.0\nband_thickness = 0.5\n"),
            "winding.band_width",
        ),
        (
            "negative-width",
            format!("{VESSEL}[winding]\nmu = 0.0\nband_width = -10.0\nband_thickness = 0.5\n"),
            "winding.band_width",
        ),
        (
            "opening-too-big",
            format!(
                "{}{w}",
                VESSEL.replace("polar_opening = 30.0", "polar_opening = 120.0")
            ),
            "mandrel.polar_opening",
        ),
        (
            "nan-radius",
            format!("{}{w}", VESSEL.replace("radius = 100.0", "radius = nan")),
            "mandrel.radius",
        ),
        (
            "geodesic-unequal-openings",
            format!("{VESSEL}polar_opening_end = 45.0\n{w}").replace("[winding]", "\n[winding]"),
            "winding.mu",
        ),
        (
            "mu-beyond-limit",
            format!("{VESSEL}[winding]\nmu = 5.0\nband_width = 10.0\nband_thickness = 0.5\n"),
            "winding.mu",
        ),
        (
            "shooting-fails",
            format!(
                "{VESSEL}polar_opening_end = 45.0\n[winding]\nmu = \"auto\"\nmu_limit = 0.002\nband_width = 10.0\nband_thickness = 0.5\n"
            ),
            "winding.mu",
        ),
        (
            "unknown-word",
            format!("{VESSEL}[winding]\nmu = \"often\"\nband_width = 10.0\nband_thickness = 0.5\n"),
            "winding.mu",
        ),
        (
            "typo-field",
            format!("{VESSEL}[winding]\nmu = 0.0\nband_widht = 10.0\nband_thickness = 0.5\n"),
            "band_widht",
        ),
        (
            "tube-without-angle",
            format!("[mandrel]\nkind = \"cylinder\"\nradius = 50.0\nlength = 100.0\n{w}"),
            "winding.winding_angle_deg",
        ),
        ("syntax", "[mandrel\nkind = 1".to_string(), "job.toml:1"),
        ("missing-table", VESSEL.to_string(), "[winding]"),
    ];
    for (name, job, field) in cases {
        let err = fails(name, &job, &[]);
        assert!(
            err.contains(field),
            "{name}: field {field} not named in: {err}"
        );
    }
}

#[test]
fn bad_profiles_and_concave_meridians_fail_cleanly() {
    let prof = "[mandrel]\nkind = \"profile\"\nfile = \"m.csv\"\n[winding]\nmu = \"minimax\"\nmu_limit = 0.02\nband_width = 10.0\nband_thickness = 0.5\n";
    let waist = std::fs::read_to_string(examples().join("waist-meridian.csv")).unwrap();
    let err = fails("no-band", prof, &[("m.csv", &waist)]);
    assert!(
        err.contains("winding.mu_limit") && err.contains("no band can lie"),
        "{err}"
    );
    let err = fails(
        "non-monotonic",
        prof,
        &[("m.csv", "z,r\n0,10\n1,20\n3,25\n2,24\n4,10\n")],
    );
    assert!(
        err.contains("mandrel.file") && err.contains("point 4"),
        "{err}"
    );
    let err = fails("too-few", prof, &[("m.csv", "z,r\n0,10\n1,20\n2,10\n")]);
    assert!(err.contains("mandrel.file") && err.contains("4"), "{err}");
    let err = fails("missing-file", prof, &[]);
    assert!(err.contains("mandrel.file"), "{err}");
}

#[test]
fn bad_eye_tables_fail_with_one_line_naming_the_field() {
    let w = "[winding]\nmu = 0.0\nband_width = 10.0\nband_thickness = 0.5\n";
    let job = |eye: &str| format!("{VESSEL}{w}[eye]\n{eye}");
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "eye-inside",
            job("mode = \"axis-parallel\"\nradius = 80.0\nl_max = 400.0\n"),
            "eye.radius",
        ),
        (
            "eye-no-radius",
            job("mode = \"axis-parallel\"\nl_max = 400.0\n"),
            "eye.radius",
        ),
        (
            "eye-mode",
            job("mode = \"wobble\"\nl_max = 400.0\n"),
            "eye.mode",
        ),
        ("eye-no-lmax", job("mode = \"equidistant\"\n"), "eye.l_max"),
        (
            "eye-clearance",
            job("mode = \"pull-speed\"\nclearance = 20.0\nl_max = 100.0\n"),
            "eye.l_max",
        ),
        (
            "eye-no-curve",
            job("mode = \"curve\"\nl_max = 400.0\n"),
            "eye.curve",
        ),
        (
            "eye-negative",
            job("mode = \"equidistant\"\nclearance = -5.0\nl_max = 400.0\n"),
            "eye.clearance",
        ),
    ];
    for (name, text, field) in cases {
        let err = fails_in(Stage::Eye, name, &text, &[]);
        assert!(err.contains(field), "{name}: {field} not named in {err}");
    }
    // A curve that does not cover the winding zone.
    let text = job("mode = \"curve\"\ncurve = \"c.csv\"\nl_max = 400.0\n");
    let err = fails_in(
        Stage::Eye,
        "eye-short-curve",
        &text,
        &[("c.csv", "Z,R\n100,200\n200,200\n")],
    );
    assert!(err.contains("eye.curve"), "{err}");
}

#[test]
fn a_machine_file_that_does_not_exist_is_named() {
    let job = std::fs::read_to_string(examples().join("vessel-axes-4axis.toml"))
        .unwrap()
        .replace("../machines/winder-4axis.toml", "no-such-machine.toml");
    let err = fails_in(Stage::Axes, "missing-machine", &job, &[]);
    assert!(err.contains("no-such-machine.toml"), "{err}");
}

#[test]
fn a_program_beyond_a_limit_is_refused() {
    let machine = std::fs::read_to_string(machines().join("winder-4axis.toml"))
        .unwrap()
        .replace("max_mm = 3000.0", "max_mm = 100.0");
    let job = std::fs::read_to_string(examples().join("vessel-program-840d.toml"))
        .unwrap()
        .replace("../machines/winder-4axis.toml", "m.toml");
    let err = fails_in(Stage::Program, "limit", &job, &[("m.toml", &machine)]);
    assert!(err.contains("axis X beyond its limit"), "{err}");
}

#[test]
fn bad_wind_files_fail_with_one_line() {
    let good = std::fs::read_to_string(examples().join("tube-fiberpath.wind")).unwrap();
    for (name, text, want) in [
        (
            "nan",
            good.replace("\"width\": 8", "\"width\": NaN"),
            "tube.wind",
        ),
        (
            "unknown",
            good.replace("\"width\": 8", "\"widht\": 8"),
            "widht",
        ),
        ("major", good.replace("\"1.0\"", "\"2.0\""), "schemaVersion"),
        (
            "negative",
            good.replace("\"thickness\": 0.4", "\"thickness\": -0.4"),
            "towParameters.thickness",
        ),
        (
            "angle",
            good.replace("\"windAngle\": 45", "\"windAngle\": 95"),
            "layers[1].windAngle",
        ),
    ] {
        let path = scratch(&format!("wind-{name}")).join("tube.wind");
        std::fs::write(&path, text).unwrap();
        let err = match wind_file(&path, Path::new("out"), EYE_CLEARANCE_MM, &[]) {
            Ok(_) => panic!("{name}: should fail"),
            Err(e) => e.to_string(),
        };
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        assert!(
            err.contains("tube.wind") && err.contains(want),
            "{name}: {err}"
        );
    }
}
