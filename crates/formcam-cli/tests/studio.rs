//! `formcam studio [JOB_OR_FOLDER]`: the address printed first and the
//! studio answering there; a path that is neither a folder nor a job file
//! fails with exit code 2 and one line naming it. What the studio answers
//! is tested through the library in `formcam-studio/tests`.
//!
//! And the job editor in a real browser (headless Chromium driven by
//! `viewer/tests/studio.mjs`) on a folder holding one winding job. A field
//! edited and run twice: the run ends done and the result shown changes
//! (its summary, its plots, its picture); a value out of range: the error
//! at that field in the words `formcam wind` prints for the same file,
//! nothing run and the previous result left shown; Save: the file written
//! (the previous one as `.bak`) and `formcam wind` on it gives the summary
//! the studio's run gave; two runs ticked and compared side by side;
//! Reset back to the saved file; Pause stops the
//! result's animation and, again, plays it on; a run cancelled.
//! Screenshots go to `target/screenshots/studio-*.png`. The browser test
//! is skipped without `/usr/bin/chromium`, `viewer/node_modules` or a page
//! built into the binary, unless `FORMCAM_REQUIRE_BROWSER=1`, when it fails.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::browser::{browser_present, driver};
use common::{Running, formcam, get, repo, s, scratch, serving, stderr, wind_ok};
use serde_json::Value;

fn studio(path: &std::path::Path) -> Running {
    serving(&["studio", s(path), "--port", "0"])
}

#[test]
fn studio_prints_its_address_first_and_answers_there() {
    let dir = scratch("studio-serve");
    std::fs::copy(
        repo().join("examples/dress-ballscrew-nut.toml"),
        dir.join("nut.toml"),
    )
    .unwrap();
    if !formcam_view::Page::is_embedded() {
        let o = formcam().args(["studio", s(&dir)]).output().unwrap();
        assert_eq!(o.status.code(), Some(2));
        assert!(
            stderr(&o).contains("npm ci && npm run build"),
            "{}",
            stderr(&o)
        );
        return;
    }
    let st = studio(&dir.join("nut.toml"));
    assert!(st.url.starts_with("http://127.0.0.1:"), "{}", st.url);
    let (status, body) = get(&st.url, "/api/studio");
    assert!(status.contains(" 200 "), "{status}");
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(v["job"], "nut.toml");
    assert_eq!(v["jobs"][0]["kind"], "dressing");
    let (status, html) = get(&st.url, "/");
    assert!(status.contains(" 200 "), "{status}");
    let html = String::from_utf8(html).unwrap();
    assert!(html.contains("<script"), "{html}");
}

#[test]
fn a_path_that_is_no_folder_nor_job_fails_with_exit_2_naming_it() {
    let dir = scratch("studio-refused");
    let notes = dir.join("notes.txt");
    std::fs::write(&notes, "no job").unwrap();
    for bad in [dir.join("missing"), notes] {
        let o = formcam().args(["studio", s(&bad)]).output().unwrap();
        assert_eq!(o.status.code(), Some(2));
        assert!(o.stdout.is_empty());
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        if formcam_view::Page::is_embedded() {
            assert!(e.contains(s(&bad)), "{e}");
        }
    }
}

/// The job the studio edits: a tube wound helically on the 4-axis winder,
/// the whole program (small: one layer).
const JOB: &str = "\
# A tube on the 4-axis winder: the studio's test job.
[mandrel]
kind = \"cylinder\"
radius = 50.0
length = 300.0

[winding]
mu = 0.0
winding_angle_deg = 55.0 # the angle the studio edits
band_width = 8.0
band_thickness = 0.3
dwell_min_deg = 180.0

[eye]
mode = \"axis-parallel\"
radius = 100.0
clearance = 20.0
l_max = 300.0

[machine]
name = \"winder-4axis\"

[post]
dialect = \"sinumerik-840d\"
";

/// The field edited, two values run in turn and one out of its range.
const FIELD: &str = "winding.winding_angle_deg";
const FIRST: &str = "50";
const SECOND: &str = "65";
const BAD: &str = "95.0";
/// The fields set for the run cancelled: one that takes seconds.
const SLOW: &str = "winding.band_width=0.5;mandrel.length=1000";

/// A summary without what differs between two runs of the same job: the
/// job's path (nothing measured goes into a summary); numbers as floats.
fn comparable(v: &Value) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.iter()
                .filter(|(k, _)| k.as_str() != "job")
                .map(|(k, v)| (k.clone(), comparable(v)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.iter().map(comparable).collect()),
        // Passed through the page, `0.0` comes back as `0`.
        Value::Number(n) => serde_json::json!(n.as_f64()),
        other => other.clone(),
    }
}

#[test]
fn the_studio_edits_runs_refuses_saves_and_cancels_a_winding_job() {
    if !browser_present() {
        return;
    }
    let dir = scratch("studio");
    let jobs = dir.join("jobs");
    std::fs::create_dir_all(&jobs).unwrap();
    let job = jobs.join("tube.toml");
    std::fs::write(&job, JOB).unwrap();
    let st = studio(&jobs);
    let report = dir.join("studio.json");
    let shots = repo().join("target/screenshots");
    let node = driver(
        "studio.mjs",
        &[
            &st.url,
            s(&shots),
            s(&report),
            FIELD,
            FIRST,
            SECOND,
            BAD,
            SLOW,
        ],
        &report,
    );
    drop(st);
    let r: Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap_or_default())
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&node.stderr)));
    assert_eq!(r["errors"], serde_json::json!([]), "{r:#}");
    assert!(node.status.success(), "{}", stderr(&node));

    // Opened on the folder's job, its fields in the form.
    assert_eq!(r["opened"]["job"], "tube.toml", "{:#}", r["opened"]);
    assert_eq!(r["opened"]["kind"], "winding");
    assert_eq!(r["opened"]["fields"][FIELD], 55.0, "{:#}", r["opened"]);
    assert_eq!(r["opened"]["saved"], true);
    assert!(r["form_rows"].as_u64().unwrap() >= 10, "{}", r["form_rows"]);

    // Two runs, each done and shown; the second result differs.
    assert_eq!(r["set_first"], true);
    let (first, second) = (&r["first"], &r["second"]);
    for (name, after, shown) in [
        (&r["first_run"], &r["after_first"], first),
        (&r["second_run"], &r["after_second"], second),
    ] {
        let name = name.as_str().unwrap();
        assert!(name.ends_with("-tube"), "{name}");
        assert_eq!(after["run"], name, "{after:#}");
        assert_eq!(after["runState"], "done", "{after:#}");
        assert_eq!(after["shown"], name, "{after:#}");
        assert_eq!(after["progress"], 1.0, "{after:#}");
        assert!(after["runs"].as_array().unwrap().iter().any(|n| n == name));
        assert_eq!(shown["src"], format!("runs/{name}/"));
        assert!(jobs.join("runs").join(name).join("summary.json").is_file());
    }
    assert_ne!(r["first_run"], r["second_run"]);
    assert_eq!(
        r["after_second"]["runs"][0], r["second_run"],
        "newest first"
    );
    assert_ne!(
        comparable(&first["result"]),
        comparable(&second["result"]),
        "the result did not change"
    );
    let hashes = |v: &Value| -> Vec<Value> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|c| c["hash"].clone())
            .collect()
    };
    assert!(!hashes(&first["plots"]).is_empty(), "{first:#}");
    assert_ne!(hashes(&first["plots"]), hashes(&second["plots"]));
    assert!(first["scene"][0]["colours"].as_u64().unwrap() > 10);
    assert_ne!(hashes(&first["scene"]), hashes(&second["scene"]));

    // The two runs ticked and compared in place of the result, then back.
    let c = &r["compare"];
    assert_eq!(
        c["selected"],
        serde_json::json!([r["first_run"], r["second_run"]]),
        "{c}"
    );
    assert_eq!(c["shown"], true, "{c}");
    assert_eq!(c["frame_hidden"], true, "{c}");
    assert_eq!(c["back"], true, "{c}");

    // The value out of range: refused at its field in the CLI's words, those
    // `formcam wind` prints for the text the studio checked (the file named
    // as given there: in the studio's folder, here beside it).
    let bad_dir = dir.join("bad");
    std::fs::create_dir_all(&bad_dir).unwrap();
    let bad_text = r["bad_state"]["text"].as_str().unwrap();
    assert!(
        bad_text.contains(&format!("winding_angle_deg = {BAD}")),
        "{bad_text}"
    );
    std::fs::write(bad_dir.join("tube.toml"), bad_text).unwrap();
    let cli = formcam()
        .current_dir(&bad_dir)
        .args(["wind", "tube.toml", "-o", "out"])
        .output()
        .unwrap();
    assert_eq!(cli.status.code(), Some(2), "{}", stderr(&cli));
    let message = r["bad_state"]["errors"][FIELD].as_str().unwrap();
    let words = message
        .strip_prefix(&format!("{}/", jobs.display()))
        .unwrap_or(message);
    assert!(words.starts_with("tube.toml: "), "{message}");
    assert!(
        stderr(&cli).contains(words),
        "the studio says {message:?}, formcam wind says {:?}",
        stderr(&cli)
    );
    let field = &r["bad_field"];
    assert_eq!(field["invalid"], true, "{field:#}");
    assert_eq!(field["message_shown"], true, "{field:#}");
    assert_eq!(field["message"], message, "{field:#}");
    assert_eq!(field["border"], "rgb(217, 48, 37)", "{field:#}");
    assert_eq!(r["bad_run"], Value::Null, "a refused job ran");
    let after_bad = &r["after_bad"];
    assert_eq!(after_bad["shown"], r["second_run"], "{after_bad:#}");
    assert_eq!(after_bad["run"], r["second_run"], "{after_bad:#}");
    assert_eq!(after_bad["runs"], r["after_second"]["runs"]);
    assert_eq!(
        r["after_bad_src"],
        format!("runs/{}/", r["second_run"].as_str().unwrap())
    );
    assert_eq!(r["after_bad_result"], second["result"]);

    // Saved: the file holds the second value, its comment kept, the
    // previous version beside it; `formcam wind` on it gives the same summary.
    assert_eq!(r["applied"], true);
    assert_eq!(r["cleared_field"]["invalid"], false);
    assert_eq!(r["before_save"]["saved"], false);
    assert_eq!(r["saved"], true);
    assert_eq!(r["after_save"]["saved"], true);
    let saved = std::fs::read_to_string(&job).unwrap();
    assert!(saved.contains("# the angle the studio edits"), "{saved}");
    assert!(saved.contains("# A tube on the 4-axis winder"), "{saved}");
    let angle: f64 = saved
        .lines()
        .find_map(|l| l.strip_prefix("winding_angle_deg = "))
        .and_then(|v| v.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(angle, SECOND.parse::<f64>().unwrap(), "{saved}");
    assert_eq!(
        std::fs::read_to_string(jobs.join("tube.toml.bak")).unwrap(),
        JOB
    );
    let cli_out = dir.join("cli-out");
    wind_ok(&job, &cli_out);
    let cli_summary: Value =
        serde_json::from_str(&std::fs::read_to_string(cli_out.join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(
        comparable(&cli_summary),
        comparable(&second["result"]),
        "formcam wind on the saved file and the studio's run differ"
    );

    // Reset: an applied edit undone back to the saved file.
    assert_eq!(r["edited"]["saved"], false);
    assert_eq!(r["reset"]["saved"], true);
    assert_eq!(
        r["reset"]["fields"][FIELD],
        SECOND.parse::<f64>().unwrap(),
        "{:#}",
        r["reset"]
    );

    // Pause: the animation stopped where it was.
    let (paused, later) = (
        r["pause"]["paused"].as_f64().unwrap(),
        r["pause"]["later"].as_f64().unwrap(),
    );
    assert!(paused > 0.0, "{}", r["pause"]);
    assert_eq!(r["pause"]["pausedState"], true, "{}", r["pause"]);
    assert_eq!(paused, later, "the animation went on after Pause");
    assert!(
        r["pause"]["resumed"].as_f64().unwrap() > later,
        "Resume did not play on: {}",
        r["pause"]
    );
    assert_eq!(r["pause"]["label"], "Pause", "{}", r["pause"]);

    // Cancel: the run stopped, listed as cancelled, the result before it shown.
    let c = &r["after_cancel"];
    assert_eq!(c["run"], r["cancel_run"], "{c:#}");
    assert_eq!(c["runState"], "cancelled", "{c:#}");
    assert_eq!(c["shown"], r["second_run"], "{c:#}");
}
