//! A program that breaks its own checks is not written unless the job accepts
//! the failed checks by name; fields that do not apply are errors; implausible
//! values warn; the summary and the outputs describe the whole program.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::Path;
use std::process::Output;

use common::{example, machines, ok, one_line_error, repo, run_job as run, scratch, summary};

fn refused(name: &str, st: &Output, out: &Path, want: &[&str]) {
    let err = one_line_error(name, st, out);
    for w in want {
        assert!(err.contains(w), "{name}: wants {w:?}: {err}");
    }
}

/// The bundled 2-axis example keeps its eye's constraints (a full turn of dwell
/// at each end); with half a turn, as it was, the band goes slack and the
/// program is refused unless the job accepts `slack`.
#[test]
fn a_slack_band_refuses_the_program_unless_accepted() {
    let good = example("tube-axes-2axis.toml");
    let (st, out) = run("2axis", &["wind"], &good);
    ok("checks", &st);
    let s = summary(&out);
    assert_eq!(s["constraints_ok"], true);
    assert_eq!(s["checks_accepted"], serde_json::json!([]));

    let slack = good.replace("dwell_min_deg = 360.0", "dwell_min_deg = 180.0");
    assert_ne!(slack, good);
    let (st, out) = run("2axis-slack", &["wind"], &slack);
    refused(
        "slack",
        &st,
        &out,
        &[
            "job.toml",
            "slack",
            "no program written",
            "allow = [\"slack\"]",
        ],
    );
    // Eye and axes stages only report.
    let (st, out) = run("2axis-slack-axes", &["wind", "axes"], &slack);
    assert!(st.status.success());
    assert_eq!(summary(&out)["constraints_ok"], false);

    let accepted = format!("{slack}\n[checks]\nallow = [\"slack\"]\n");
    let (st, out) = run("2axis-accepted", &["wind"], &accepted);
    ok("checks", &st);
    let s = summary(&out);
    assert_eq!(s["checks_accepted"], serde_json::json!(["slack"]));
    assert_eq!(s["checks_violated"][0]["check"], "slack");
    let program = std::fs::read_to_string(out.join("program.gcode")).unwrap();
    assert!(
        program
            .lines()
            .take(10)
            .any(|l| l.contains("checks accepted as violated") && l.contains("slack")),
        "{program:.400}"
    );
    // Accepting another check does not accept this one; unknown names are errors.
    let other = format!("{slack}\n[checks]\nallow = [\"timing\"]\n");
    let (st, out) = run("2axis-other", &["wind"], &other);
    refused("other", &st, &out, &["slack"]);
    // TOML jobs accept checks in the job, not on the command line.
    let (st, out) = run("2axis-flag", &["wind", "--allow", "slack"], &slack);
    refused("flag", &st, &out, &["--allow", "[checks]"]);
    let typo = format!("{slack}\n[checks]\nallow = [\"slak\"]\n");
    let (st, out) = run("2axis-typo", &["wind"], &typo);
    refused("typo", &st, &out, &["slak", "slack"]);
}

/// Beyond an axis limit: refused, or written when `limits` is accepted.
#[test]
fn a_limit_is_a_check_that_can_be_accepted() {
    let machine = std::fs::read_to_string(machines().join("winder-4axis.toml"))
        .unwrap()
        .replace("max_mm = 3000.0", "max_mm = 100.0");
    let dir = scratch("limits-machine");
    let m = dir.join("m.toml");
    std::fs::write(&m, machine).unwrap();
    let job = example("vessel-program-840d.toml").replace(
        &machines().join("winder-4axis.toml").display().to_string(),
        &m.display().to_string(),
    );
    let (st, out) = run("limits", &["wind"], &job);
    refused(
        "limits",
        &st,
        &out,
        &["axis X beyond its limit", "allow = [\"limits\"]"],
    );
    let (st, out) = run(
        "limits-accepted",
        &["wind"],
        &format!("{job}\n[checks]\nallow = [\"limits\"]\n"),
    );
    // Written, and its check on the machine says what the job accepted:
    // exit status 3, the position limit of X in `check.json`.
    assert_eq!(st.status.code(), Some(3), "{}", common::stderr(&st));
    let report = common::json(out.join("check.json"));
    assert!(
        report["violations"]
            .as_array()
            .unwrap()
            .iter()
            .any(|v| v["kind"] == "position" && v["axis"] == "X"),
        "{report}"
    );
    let s = summary(&out);
    assert_eq!(s["checks_accepted"], serde_json::json!(["limits"]));
    let x = s["axis_ranges"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["axis"] == "X")
        .unwrap()
        .clone();
    assert!(x["max"].as_f64().unwrap() > 100.0, "{x}");
}

#[test]
fn tables_and_fields_that_do_not_apply_are_errors() {
    let job = example("vessel-program-840d.toml");
    let (st, out) = run("motoin", &["wind"], &job.replace("[motion]", "[motoin]"));
    assert!(job.contains("[motion]"));
    refused("motoin", &st, &out, &["job.toml", "motoin"]);
    let vessel = example("vessel-geodesic.toml");
    assert!(vessel.contains("kind = \"vessel\""));
    let (st, out) = run(
        "angle-on-vessel",
        &["wind", "path"],
        &vessel.replace("[winding]", "[winding]\nwinding_angle_deg = 30.0"),
    );
    refused(
        "angle-on-vessel",
        &st,
        &out,
        &["winding.winding_angle_deg", "vessel"],
    );
}

#[test]
fn implausible_values_warn_on_stderr_and_in_the_summary() {
    let metres = "[mandrel]\nkind = \"vessel\"\nradius = 0.5\ncylinder_length = 0.3\n\
                  polar_opening = 0.15\n[winding]\nmu = 0.0\nband_width = 0.01\n\
                  band_thickness = 0.001\n";
    let wide = "[mandrel]\nkind = \"vessel\"\nradius = 100.0\ncylinder_length = 300.0\n\
                polar_opening = 5.0\n[winding]\nmu = 0.0\nband_width = 20.0\n\
                band_thickness = 0.5\n";
    for (name, text, field) in [
        ("metres", metres, "mandrel.radius"),
        ("wide-band", wide, "winding.band_width"),
    ] {
        let (st, out) = run(name, &["wind", "path"], text);
        assert!(st.status.success(), "{name}");
        let err = String::from_utf8_lossy(&st.stderr);
        assert!(
            err.contains("warning") && err.contains(field),
            "{name}: {err}"
        );
        let w = summary(&out)["warnings"].clone();
        assert!(
            w.as_array()
                .unwrap()
                .iter()
                .any(|w| w.as_str().unwrap().starts_with(field)),
            "{name}: {w}"
        );
    }
    // A plausible job says nothing.
    let (st, out) = run(
        "plausible",
        &["wind", "path"],
        &example("vessel-geodesic.toml"),
    );
    assert!(st.status.success() && !String::from_utf8_lossy(&st.stderr).contains("warning"));
    assert!(summary(&out)["warnings"].as_array().unwrap().is_empty());

    // Dressing feeds under 1 mm/min (mm/s?).
    let dress = std::fs::read_to_string(repo().join("examples/dress-ballscrew-nut.toml")).unwrap();
    let slow = dress.replacen("feed_min = ", "feed_min = 0.5 #", 1);
    assert_ne!(slow, dress);
    let (st, out) = run("dress-slow", &["dress"], &slow);
    ok("checks", &st);
    assert!(String::from_utf8_lossy(&st.stderr).contains("process.feed_min"));
    assert!(
        summary(&out)["warnings"][0]
            .as_str()
            .unwrap()
            .contains("mm/s?")
    );
}

#[test]
fn a_multi_layer_job_writes_each_wound_layer_in_its_folder() {
    // What the files hold is tested in formcam-run; here the folders.
    let (st, out) = run("layers", &["wind"], &example("tube-layers-4axis.toml"));
    ok("checks", &st);
    let s = summary(&out);
    let mut wound = 0;
    for l in s["per_layer"].as_array().unwrap() {
        let dir = out.join(format!("layer-{:02}", l["layer"].as_u64().unwrap()));
        if l["kind"] == "skip" {
            assert!(!dir.exists());
            continue;
        }
        wound += 1;
        for f in [
            "path.csv", "path.svg", "eye.csv", "eye.svg", "axes.csv", "band.csv",
        ] {
            assert!(dir.join(f).exists(), "{}: {f}", dir.display());
        }
    }
    assert!(wound >= 2);
}
