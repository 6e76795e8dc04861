//! The command line as users meet it: outputs of good jobs, one-line errors for bad ones.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn formcam() -> Command {
    Command::new(env!("CARGO_BIN_EXE_formcam"))
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("formcam-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// Runs `formcam ARGS -o OUT` (a trailing `*.toml` argument is an example job)
/// and checks that it succeeds; returns `OUT`.
fn succeeds(name: &str, args: &[&str]) -> PathBuf {
    let out = scratch(name).join("out");
    let mut cmd = formcam();
    for a in args {
        if a.ends_with(".toml") {
            cmd.arg(examples().join(a));
        } else {
            cmd.arg(a);
        }
    }
    let st = cmd.arg("-o").arg(&out).output().unwrap();
    assert!(
        st.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&st.stderr)
    );
    out
}

#[test]
fn wind_path_writes_csv_and_summary() {
    let out = succeeds("good", &["wind", "path", "vessel-geodesic.toml"]);
    let csv = std::fs::read_to_string(out.join("path.csv")).unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    assert!(header.starts_with("s,z,r,v,alpha,c,mu"));
    assert_eq!(lines.count(), 2001);
    let summary = summary_of(&out);
    for key in [
        "turn_angle_pass_rad",
        "turn_angle_circuit_rad",
        "mu",
        "alpha_equator_rad",
        "circuits",
        "fibre_length_mm",
    ] {
        assert!(summary.get(key).is_some(), "summary.json lacks {key}");
    }
    let alpha = 0.3f64.asin();
    let expect = 2.0 * std::f64::consts::PI + 2.0 * 300.0 * alpha.tan() / 100.0;
    let got = summary["turn_angle_circuit_rad"].as_f64().unwrap();
    assert!((got - expect).abs() < 1e-9, "{got} vs {expect}");
    assert!((summary["alpha_equator_rad"].as_f64().unwrap() - alpha).abs() < 1e-9);
    assert_eq!(summary["mu"].as_f64().unwrap(), 0.0);
    let circuits = summary["circuits"].as_u64().unwrap() as f64;
    assert_eq!(
        circuits,
        (std::f64::consts::TAU * 100.0 * alpha.cos() / 10.0).ceil()
    );
    // No temporary files are left behind.
    let names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into())
        .collect();
    assert!(names.iter().all(|n| !n.ends_with(".tmp")), "{names:?}");
}

const VESSEL: &str = r#"
[mandrel]
kind = "vessel"
radius = 100.0
cylinder_length = 300.0
dome = "hemisphere"
polar_opening = 30.0
"#;

/// Runs a bad job; returns its one-line error after checking the exit code and
/// that nothing was written.
fn fails(name: &str, job: &str, extra: &[(&str, &str)]) -> String {
    fails_in("path", name, job, extra)
}

/// As [`fails`] for `formcam wind <command>`.
fn fails_in(command: &str, name: &str, job: &str, extra: &[(&str, &str)]) -> String {
    let dir = scratch(name);
    let path = dir.join("job.toml");
    std::fs::write(&path, job).unwrap();
    for (f, text) in extra {
        std::fs::write(dir.join(f), text).unwrap();
    }
    let out = dir.join("out");
    let st = formcam()
        .args(["wind", command])
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(!st.status.success(), "{name}: should fail");
    assert!(!out.exists(), "{name}: a failed run wrote output");
    let err = String::from_utf8_lossy(&st.stderr).trim_end().to_string();
    assert_eq!(err.lines().count(), 1, "{name}: not one line: {err}");
    assert!(err.contains("job.toml"), "{name}: file not named: {err}");
    err
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
        err.contains("mandrel.file") && err.contains("row 4"),
        "{err}"
    );
    let err = fails("too-few", prof, &[("m.csv", "z,r\n0,10\n1,20\n2,10\n")]);
    assert!(err.contains("mandrel.file") && err.contains("4"), "{err}");
    let err = fails("missing-file", prof, &[]);
    assert!(err.contains("mandrel.file"), "{err}");
}

#[test]
fn demo_runs_every_example() {
    let examples_dir = examples().to_string_lossy().into_owned();
    let out = succeeds("demo", &["demo", "--examples", &examples_dir]);
    let jobs = std::fs::read_dir(examples())
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "toml")
        })
        .count();
    assert!(jobs >= 6);
    for e in std::fs::read_dir(examples()).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "toml") {
            let name = p.file_stem().unwrap();
            let text = std::fs::read_to_string(&p).unwrap();
            if text.contains("[correct]") || text.contains("[warp]") {
                // Correction jobs and closed-loop scenarios write a report;
                // their outputs are checked in tests/correct.rs.
                assert!(out.join(name).join("report.json").exists(), "{name:?}");
                continue;
            }
            assert!(out.join(name).join("summary.json").exists(), "{name:?}");
            if std::fs::read_to_string(&p).unwrap().contains("[wheel]") {
                // Dressing jobs: their outputs are checked in tests/dress.rs.
                assert!(out.join(name).join("program.cls").exists(), "{name:?}");
                continue;
            }
            if std::fs::read_to_string(&p).unwrap().contains("[[layer]]") {
                // Multi-layer jobs write the program.
                assert!(out.join(name).join("blocks.csv").exists(), "{name:?}");
                continue;
            }
            assert!(out.join(name).join("path.csv").exists(), "{name:?}");
            let svg = std::fs::read_to_string(out.join(name).join("path.svg")).unwrap();
            assert!(
                svg.starts_with("<svg") && svg.contains("polyline"),
                "{name:?}"
            );
        }
    }
}

#[test]
fn wind_eye_writes_the_trajectory_and_its_summary() {
    let out = succeeds("eye", &["wind", "eye", "vessel-eye-pull-speed.toml"]);
    let csv = std::fs::read_to_string(out.join("eye.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.starts_with("x,z,r,v,alpha,l,eye_z,eye_r,eye_v,lambda,u"),
        "{header}"
    );
    assert_eq!(csv.lines().count(), 1 + 1001);
    let summary = summary_of(&out);
    assert_eq!(summary["eye_mode"], "pull-speed");
    assert_eq!(summary["constraints_ok"], true);
    assert!(summary["violations"].as_array().unwrap().is_empty());
    let (lo, hi) = (
        summary["u_min"].as_f64().unwrap(),
        summary["u_max"].as_f64().unwrap(),
    );
    assert!(lo > 0.0 && lo <= 1.0 && hi >= 1.0, "{lo} {hi}");
    assert!(summary["u_rms_dev"].as_f64().unwrap() >= 0.0);
    // The path outputs come along.
    assert!(out.join("path.csv").exists() && out.join("eye.svg").exists());
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
        let err = fails_in("eye", name, &text, &[]);
        assert!(err.contains(field), "{name}: {field} not named in {err}");
    }
    // A curve that does not cover the winding zone.
    let text = job("mode = \"curve\"\ncurve = \"c.csv\"\nl_max = 400.0\n");
    let err = fails_in(
        "eye",
        "eye-short-curve",
        &text,
        &[("c.csv", "Z,R\n100,200\n200,200\n")],
    );
    assert!(err.contains("eye.curve"), "{err}");
}

/// The summary.json of an output folder.
fn summary_of(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// Runs `formcam wind` on a job given as text (written to a scratch folder)
/// and checks that it succeeds; returns its summary.
fn winds(name: &str, job: &str) -> serde_json::Value {
    let dir = scratch(name);
    let path = dir.join("job.toml");
    std::fs::write(&path, job).unwrap();
    let out = dir.join("out");
    let st = formcam()
        .arg("wind")
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&st.stderr)
    );
    summary_of(&out)
}

fn machines() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../machines")
}

#[test]
fn wind_axes_writes_axes_that_forward_kinematics_takes_back_to_the_eye() {
    let out = succeeds("axes", &["wind", "axes", "vessel-axes-4axis.toml"]);
    let summary = summary_of(&out);
    assert_eq!(summary["machine"], "4-axis winder");
    assert_eq!(summary["axes"], serde_json::json!(["A", "X", "Y", "B"]));
    assert_eq!(summary["limits_ok"], true);
    assert!(summary["max_ik_residual_mm"].as_f64().unwrap() < 1e-9);
    let axes = std::fs::read_to_string(out.join("axes.csv")).unwrap();
    assert!(axes.starts_with("x,A,X,Y,B\n"));
    // Forward kinematics of the axes file puts the payout point on the eye: the
    // spindle turns the eye's (Z, R, V) to the payout point's side, so compare
    // the axial position and the distance from the spindle axis.
    let points = out.join("points.csv");
    let st = formcam()
        .args(["machine", "fk"])
        .arg(machines().join("winder-4axis.toml"))
        .arg("--axes")
        .arg(out.join("axes.csv"))
        .arg("-o")
        .arg(&points)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let eye = std::fs::read_to_string(out.join("eye.csv")).unwrap();
    let fk = std::fs::read_to_string(&points).unwrap();
    assert!(fk.starts_with("x,payout_x,payout_y,payout_z"));
    let mut rows = 0;
    for (e, p) in eye.lines().skip(1).zip(fk.lines().skip(1)) {
        let e: Vec<f64> = e.split(',').map(|v| v.parse().unwrap()).collect();
        let p: Vec<f64> = p.split(',').map(|v| v.parse().unwrap()).collect();
        // eye.csv: x,z,r,v,alpha,l,eye_z,eye_r,... ; the spindle axis is world x
        // at y = 0, z = 1000 mm.
        let r = p[2].hypot(p[3] - 1000.0);
        assert!((p[0] - e[0]).abs() < 1e-9);
        assert!(
            (p[1] - e[6]).abs() < 1e-6 && (r - e[7]).abs() < 1e-6,
            "{p:?} {e:?}"
        );
        rows += 1;
    }
    assert_eq!(rows, 1001);
}

#[test]
fn machine_show_prints_the_chain() {
    let st = formcam()
        .args(["machine", "show"])
        .arg(machines().join("winder-6axis.toml"))
        .output()
        .unwrap();
    assert!(st.status.success());
    let text = String::from_utf8_lossy(&st.stdout);
    for word in [
        "6-axis winder",
        "carriage",
        "prismatic",
        "revolute",
        "payout",
    ] {
        assert!(text.contains(word), "{word} missing in {text}");
    }
    // The spindle is a modulo axis by default, the eye's yaw is not.
    let row = |link: &str| {
        text.lines()
            .find(|l| l.split_whitespace().next() == Some(link))
            .map(|l| l.split_whitespace().last().unwrap_or_default().to_string())
    };
    assert_eq!(row("spindle").as_deref(), Some("yes"), "{text}");
    assert_eq!(row("yaw").as_deref(), Some("no"), "{text}");
    assert_eq!(row("carriage").as_deref(), Some("-"), "{text}");
    // A shipped machine by name shows as its file does.
    let by_name = formcam()
        .args(["machine", "show", "winder-6axis"])
        .output()
        .unwrap();
    assert!(by_name.status.success());
    assert_eq!(String::from_utf8_lossy(&by_name.stdout), text);
}

#[test]
fn bad_machines_fail_with_one_line_naming_the_file_and_link() {
    let text = std::fs::read_to_string(machines().join("winder-4axis.toml"))
        .unwrap()
        .replace("min_mm = 40.0", "min_mm = 900.0");
    let dir = scratch("bad-machine");
    let m = dir.join("bad.toml");
    std::fs::write(&m, text).unwrap();
    let st = formcam()
        .args(["machine", "show"])
        .arg(&m)
        .output()
        .unwrap();
    assert!(!st.status.success());
    let err = String::from_utf8_lossy(&st.stderr).trim_end().to_string();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("bad.toml") && err.contains("link \"cross\"") && err.contains("min_mm"),
        "{err}"
    );
    // A job naming a machine file that does not exist.
    let job = std::fs::read_to_string(examples().join("vessel-axes-4axis.toml"))
        .unwrap()
        .replace("../machines/winder-4axis.toml", "no-such-machine.toml");
    let err = fails_in("axes", "missing-machine", &job, &[]);
    assert!(err.contains("no-such-machine.toml"), "{err}");
}

#[test]
fn wind_writes_the_whole_program() {
    let out = succeeds("program", &["wind", "vessel-program-840d.toml"]);
    let summary = summary_of(&out);
    for key in [
        "blocks",
        "program_time_s",
        "program_time_pairwise_s",
        "program_time_global_s",
        "layers",
        "fibre_length_mm",
    ] {
        assert!(summary.get(key).is_some(), "summary.json lacks {key}");
    }
    let global = summary["program_time_global_s"].as_f64().unwrap();
    let pairwise = summary["program_time_pairwise_s"].as_f64().unwrap();
    assert!(global <= pairwise * (1.0 + 1e-9));
    let blocks = summary["blocks"].as_u64().unwrap() as usize;
    let program = std::fs::read_to_string(out.join("program.mpf")).unwrap();
    assert!(program.contains("G90 G94 G71") && program.trim_end().ends_with("M30"));
    assert_eq!(
        program.lines().filter(|l| l.contains(" G1 ")).count(),
        blocks
    );
    let csv = std::fs::read_to_string(out.join("blocks.csv")).unwrap();
    assert!(csv.starts_with("block,t,A,X,Y,B,"));
    assert_eq!(csv.lines().count(), blocks + 1);
}

#[test]
fn a_program_beyond_a_limit_is_refused() {
    let machine = std::fs::read_to_string(machines().join("winder-4axis.toml"))
        .unwrap()
        .replace("max_mm = 3000.0", "max_mm = 100.0");
    let job = std::fs::read_to_string(examples().join("vessel-program-840d.toml"))
        .unwrap()
        .replace("../machines/winder-4axis.toml", "m.toml");
    let dir = scratch("limit");
    std::fs::write(dir.join("m.toml"), machine).unwrap();
    let path = dir.join("job.toml");
    std::fs::write(&path, job).unwrap();
    let out = dir.join("out");
    let st = formcam()
        .arg("wind")
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(!st.status.success());
    assert!(!out.exists(), "a refused program wrote output");
    let err = String::from_utf8_lossy(&st.stderr).trim_end().to_string();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("job.toml") && err.contains("axis X beyond its limit"),
        "{err}"
    );
}

#[test]
fn a_multi_layer_job_grows_the_mandrel_and_writes_one_program() {
    let out = succeeds("layers", &["wind", "tube-layers-4axis.toml"]);
    let summary = summary_of(&out);
    assert_eq!(summary["layers"], 4);
    let layers = summary["per_layer"].as_array().unwrap();
    let kinds: Vec<&str> = layers.iter().map(|l| l["kind"].as_str().unwrap()).collect();
    assert_eq!(kinds, ["hoop", "helical", "skip", "helical"]);
    // Each winding layer is planned on the mandrel grown by the ones before it.
    let t0 = layers[0]["thickness_mm"].as_f64().unwrap();
    let g1 = layers[1]["mandrel_growth_mm"].as_f64().unwrap();
    let t1 = layers[1]["thickness_mm"].as_f64().unwrap();
    let g3 = layers[3]["mandrel_growth_mm"].as_f64().unwrap();
    assert!((g1 - t0).abs() < 1e-12 && (g3 - (t0 + t1)).abs() < 1e-12);
    // A hoop layer lays one band width per turn.
    let hoop = layers[0]["alpha_equator_deg"].as_f64().unwrap();
    let expect = (std::f64::consts::TAU * 75.0 / 6.0).atan().to_degrees();
    assert!((hoop - expect).abs() < 1e-9, "{hoop} vs {expect}");
    let sum: f64 = layers.iter().map(|l| l["time_s"].as_f64().unwrap()).sum();
    let total = summary["program_time_s"].as_f64().unwrap();
    assert!(total >= sum - 1e-6, "{total} vs {sum}");
    let program = std::fs::read_to_string(out.join("program.ngc")).unwrap();
    for label in [
        "layer 1 [hoop]",
        "layer 2 [helical]",
        "layer 3 [skip]",
        "layer 4 [helical]",
    ] {
        assert!(program.contains(label), "{label}");
    }
    let csv = std::fs::read_to_string(out.join("blocks.csv")).unwrap();
    assert_eq!(
        csv.lines().count() - 1,
        summary["blocks"].as_u64().unwrap() as usize
    );
    // Path, eye and axes take one [winding].
    let st = formcam()
        .args(["wind", "axes"])
        .arg(examples().join("tube-layers-4axis.toml"))
        .args(["-o", "/nonexistent/never"])
        .output()
        .unwrap();
    assert!(!st.status.success());
    assert!(String::from_utf8_lossy(&st.stderr).contains("[[layer]]"));
}

#[test]
fn a_wind_file_runs_on_the_xab_winder_and_writes_marlin() {
    let out = scratch("wind-file").join("out");
    common::wind_ok(&examples().join("tube-fiberpath.wind"), &out);
    let summary = summary_of(&out);
    assert_eq!(summary["layers"], 3);
    assert_eq!(summary["machine"], "X/A/B winder");
    let layers = summary["per_layer"].as_array().unwrap();
    assert_eq!(
        layers[1]["alpha_equator_deg"].as_f64().unwrap().round(),
        45.0
    );
    let program = std::fs::read_to_string(out.join("program.gcode")).unwrap();
    assert!(program.contains("G21") && program.contains("G90") && program.contains("G94"));
    assert!(
        program
            .lines()
            .any(|l| l.starts_with("G1 ") && l.contains('A') && l.contains('X'))
    );
    assert!(!program.contains('Y') && !program.contains("G93"));
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
        let dir = scratch(&format!("wind-{name}"));
        let path = dir.join("tube.wind");
        std::fs::write(&path, text).unwrap();
        let out = dir.join("out");
        let st = formcam()
            .arg("wind")
            .arg(&path)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        assert!(!st.status.success(), "{name}");
        assert!(!out.exists(), "{name}: wrote output");
        let err = String::from_utf8_lossy(&st.stderr).trim_end().to_string();
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        assert!(
            err.contains("tube.wind") && err.contains(want),
            "{name}: {err}"
        );
    }
}

#[test]
fn acceleration_limits_lengthen_the_program() {
    let job = std::fs::read_to_string(examples().join("vessel-program-840d.toml"))
        .unwrap()
        .replace("# acceleration = true", "acceleration = true #")
        .replace("../machines/", &format!("{}/", machines().display()));
    let summary = winds("acceleration", &job);
    let with = summary["program_time_s"].as_f64().unwrap();
    let global = summary["program_time_global_s"].as_f64().unwrap();
    assert!(with > global, "{with} vs {global}");
}

#[test]
fn a_one_way_hoop_lays_one_ply() {
    let both = std::fs::read_to_string(examples().join("tube-layers-4axis.toml"))
        .unwrap()
        .replace("../machines/", &format!("{}/", machines().display()));
    let one = both.replacen("kind = \"hoop\"\n", "kind = \"hoop\"\none_way = true\n", 1);
    let run = |name: &str, text: &str| winds(name, text)["per_layer"][0].clone();
    let (b, o) = (run("hoop-both", &both), run("hoop-one", &one));
    assert_eq!(o["one_way"], true);
    let (tb, to) = (
        b["thickness_mm"].as_f64().unwrap(),
        o["thickness_mm"].as_f64().unwrap(),
    );
    assert!((to - 0.5 * tb).abs() < 1e-12, "{to} vs {tb}");
    assert!(o["time_s"].as_f64().unwrap() < b["time_s"].as_f64().unwrap());
}

/// The largest |value| of the spindle's words (`A..`, `A=ACP(..)`, `A=ACN(..)`).
fn largest_spindle_angle(program: &str) -> f64 {
    program
        .lines()
        .filter(|l| !l.starts_with(';') && !l.starts_with('('))
        .flat_map(|l| l.split(' '))
        .filter_map(|w| {
            w.strip_prefix("A=ACP(")
                .or_else(|| w.strip_prefix("A=ACN("))
                .map(|v| v.trim_end_matches(')'))
                .or_else(|| w.strip_prefix('A'))
        })
        .map(|v| v.parse::<f64>().unwrap().abs())
        .fold(0.0, f64::max)
}

#[test]
fn the_spindle_stays_within_100_turns() {
    // FiberPath's tube wound the spindle to A-291582.1534 on Marlin: now
    // re-zeroed by G92 between layers and before it would pass 100 turns.
    let out = scratch("spindle-wind").join("out");
    common::wind_ok(&examples().join("tube-fiberpath.wind"), &out);
    let program = std::fs::read_to_string(out.join("program.gcode")).unwrap();
    let largest = largest_spindle_angle(&program);
    assert!(largest <= 36000.0, "largest |A| {largest}");
    assert!(program.lines().filter(|l| l.starts_with("G92 A")).count() >= 3);
    // The spindle's unwound angle still runs far beyond: blocks.csv keeps it.
    let csv = std::fs::read_to_string(out.join("blocks.csv")).unwrap();
    let unwound = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse::<f64>().unwrap().abs())
        .fold(0.0, f64::max);
    assert!(unwound > 100_000.0, "{unwound}");
    // Sinumerik 840D: a modulo axis, every angle within the turn.
    let out = succeeds("spindle-840d", &["wind", "vessel-layers-840d.toml"]);
    let program = std::fs::read_to_string(out.join("program.mpf")).unwrap();
    assert!(program.contains("A=ACP(") && program.contains("A=ACN("));
    assert!(largest_spindle_angle(&program) < 360.0);
}
