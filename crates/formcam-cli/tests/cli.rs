//! The command line as users meet it: the files `formcam wind` and `formcam
//! demo` write, `formcam machine show|fk`, one-line errors with nothing
//! written. What the runs compute is tested in formcam-run.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{
    example, examples, formcam, machines, names_in, ok, one_line_error, run, run_job, s, scratch,
    summary,
};

#[test]
fn wind_path_writes_its_files_and_no_temporaries() {
    let (o, out) = run_job("good", &["wind", "path"], &example("vessel-geodesic.toml"));
    ok("good", &o);
    let names = names_in(&out);
    for f in ["path.csv", "path.svg", "summary.json"] {
        assert!(names.iter().any(|n| n == f), "{f} not written: {names:?}");
    }
    assert!(summary(&out)["circuits"].as_u64().unwrap() > 0);
    // The one line printed names the output folder.
    let line = String::from_utf8_lossy(&o.stdout);
    assert_eq!(line.trim_end().lines().count(), 1, "{line}");
    // No temporary files are left behind.
    assert!(names.iter().all(|n| !n.ends_with(".tmp")), "{names:?}");
}

#[test]
fn bad_jobs_fail_with_one_line_naming_the_file_and_write_nothing() {
    let vessel = example("vessel-geodesic.toml");
    for (name, command, job, want) in [
        (
            "syntax",
            "path",
            "[mandrel\nkind = 1".to_string(),
            "job.toml:1",
        ),
        (
            "unknown-kind",
            "path",
            vessel.replace("kind = \"vessel\"", "kind = \"sphere\""),
            "mandrel.kind",
        ),
        (
            "eye-mode",
            "eye",
            example("vessel-eye-pull-speed.toml").replace("\"pull-speed\"", "\"wobble\""),
            "eye.mode",
        ),
    ] {
        let (o, out) = run_job(name, &["wind", command], &job);
        let err = one_line_error(name, &o, &out);
        assert!(err.starts_with("formcam: error: "), "{name}: {err}");
        assert!(
            err.contains("job.toml") && err.contains(want),
            "{name}: {err}"
        );
    }
}

#[test]
fn demo_runs_every_example() {
    let examples_dir = examples().to_string_lossy().into_owned();
    let out = scratch("demo").join("out");
    ok(
        "demo",
        &run(&["demo", "--examples", &examples_dir, "-o", s(&out)]),
    );
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
fn wind_axes_writes_axes_that_forward_kinematics_takes_back_to_the_eye() {
    let (o, out) = run_job(
        "axes",
        &["wind", "axes"],
        &example("vessel-axes-4axis.toml"),
    );
    ok("axes", &o);
    let summary = summary(&out);
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
    ok("fk", &st);
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
    let m = scratch("bad-machine").join("bad.toml");
    std::fs::write(&m, text).unwrap();
    let st = run(&["machine", "show", s(&m)]);
    assert!(!st.status.success());
    let err = String::from_utf8_lossy(&st.stderr).trim_end().to_string();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("bad.toml") && err.contains("link \"cross\"") && err.contains("min_mm"),
        "{err}"
    );
}

#[test]
fn wind_writes_the_program_and_its_tables() {
    for (name, job, program) in [
        ("program", "vessel-program-840d.toml", "program.mpf"),
        ("layers", "tube-layers-4axis.toml", "program.ngc"),
    ] {
        let (o, out) = run_job(name, &["wind"], &example(job));
        ok(name, &o);
        let names = names_in(&out);
        for f in [program, "blocks.csv", "axes.csv", "summary.json"] {
            assert!(
                names.iter().any(|n| n == f),
                "{name}: {f} not written: {names:?}"
            );
        }
    }
    // A `.wind` document is told by its extension.
    let out = scratch("wind-file").join("out");
    common::wind_ok(&examples().join("tube-fiberpath.wind"), &out);
    assert!(out.join("program.gcode").exists());
    // Stages stop a multi-layer job with one line.
    let (o, out) = run_job(
        "layered-axes",
        &["wind", "axes"],
        &example("tube-layers-4axis.toml"),
    );
    assert!(one_line_error("layered-axes", &o, &out).contains("[[layer]]"));
}
