//! Two runs of `formcam studio` compared in a real browser (headless
//! Chromium driven by `viewer/tests/compare.mjs`): a winding job run through
//! the studio's HTTP API as it is and with its motion tolerance doubled, and
//! a dressing job. The comparison of the two winding runs lists every
//! summary value once, marks those that differ (the block count and the
//! program's time among them, the path's values not), and overlays their
//! plots, every series of run A solid and of run B dashed in the same
//! colour, both drawn (their pixels, run B's broken by its dashes); the
//! winding run against the dressing run shows the table only and says so;
//! two dressing runs, the feed's limit lowered, their removal rate and feed
//! overlaid; two corrections, the gain halved, their deviation per section
//! and per run overlaid.
//! Screenshots go to `target/screenshots/compare-*.png`.
//!
//! Skipped as `view.rs`'s browser tests are without Chromium, unless
//! `FORMCAM_REQUIRE_BROWSER=1`.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::browser::{browser_present, driver};
use common::{repo, s, scratch, serving};

/// The winding job, on the shipped 4-axis winder (the studio reads only in
/// its folder).
fn winding_job() -> String {
    let text = std::fs::read_to_string(repo().join("examples/vessel-program-840d.toml")).unwrap();
    assert!(text.contains("file = \"../machines/winder-4axis.toml\""));
    text.replace(
        "file = \"../machines/winder-4axis.toml\"",
        "name = \"winder-4axis\"",
    )
}

#[test]
fn the_browser_compares_two_studio_runs_value_by_value_and_plot_over_plot() {
    if !browser_present() {
        return;
    }
    let dir = scratch("compare");
    std::fs::write(dir.join("vessel.toml"), winding_job()).unwrap();
    std::fs::copy(
        repo().join("examples/dress-ballscrew-nut.toml"),
        dir.join("nut.toml"),
    )
    .unwrap();
    std::fs::copy(
        repo().join("examples/correct-mould.toml"),
        dir.join("mould.toml"),
    )
    .unwrap();
    std::fs::create_dir_all(dir.join("correct")).unwrap();
    for input in ["cmm.csv", "mould.nc"] {
        std::fs::copy(
            repo().join("examples/correct").join(input),
            dir.join("correct").join(input),
        )
        .unwrap();
    }
    let studio = serving(&["studio", s(&dir), "--port", "0"]);
    let report = dir.join("compare.json");
    let shots = repo().join("target/screenshots");
    let node = driver(
        "compare.mjs",
        &[
            &studio.url,
            s(&shots),
            s(&report),
            "vessel.toml",
            "motion.tolerance_mm=0.1",
            "nut.toml",
            "process.feed_max=250",
            "mould.toml",
            "correct.gain=0.5",
        ],
        &report,
    );
    drop(studio);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap_or_default())
            .unwrap_or_default();
    assert!(
        node.status.success(),
        "{}\n{r:#}",
        String::from_utf8_lossy(&node.stderr)
    );
    assert_eq!(r["errors"], serde_json::json!([]), "{r:#}");
    // Six runs, each a folder of its own under DIR/runs/.
    let runs: Vec<&str> = r["runs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    assert_eq!(runs.len(), 6, "{r:#}");
    for run in &runs {
        let folder = dir.join("runs").join(run);
        assert!(
            folder.join("summary.json").is_file() || folder.join("report.json").is_file(),
            "{run}"
        );
    }
    assert_eq!(r["changed"]["from"], 0.05, "{r:#}");

    // The table: every summary value a row, the differing ones marked.
    let st = &r["state"];
    assert_eq!(st["runs"], serde_json::json!(runs[..2]), "{st:#}");
    assert_eq!(st["same_kind"], true, "{st:#}");
    let rows = st["rows"].as_u64().unwrap();
    let differing: Vec<&str> = st["differing_keys"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_str().unwrap())
        .collect();
    assert_eq!(r["dom"]["rows"].as_u64().unwrap(), rows, "{r:#}");
    assert_eq!(
        r["dom"]["differ"].as_array().unwrap().len(),
        differing.len(),
        "{r:#}"
    );
    // Ticking "differences only" leaves those rows alone shown.
    assert_eq!(
        r["dom"]["visible_rows"].as_u64().unwrap() as usize,
        differing.len(),
        "{r:#}"
    );
    // A coarser tolerance: fewer blocks, another time; the same path.
    let summary = |run: &str| -> serde_json::Value {
        serde_json::from_str(
            &std::fs::read_to_string(dir.join("runs").join(run).join("summary.json")).unwrap(),
        )
        .unwrap()
    };
    let (a, b) = (summary(runs[0]), summary(runs[1]));
    assert!(b["blocks"].as_u64().unwrap() < a["blocks"].as_u64().unwrap());
    for key in ["blocks", "program_time_s"] {
        assert!(differing.contains(&key), "{key} not marked: {differing:?}");
    }
    assert_eq!(a["fibre_length_mm"], b["fibre_length_mm"]);
    assert!(!differing.contains(&"fibre_length_mm"), "{differing:?}");
    assert!(
        (differing.len() as u64) < rows && rows > 20,
        "{rows} rows, {differing:?}"
    );
    // The block count's row: both values and the change with its relative size.
    let blocks_row = r["dom"]["differ"]
        .as_array()
        .unwrap()
        .iter()
        .find(|row| row[0] == "blocks")
        .unwrap();
    let (na, nb) = (a["blocks"].as_i64().unwrap(), b["blocks"].as_i64().unwrap());
    assert_eq!(blocks_row[1], na.to_string(), "{blocks_row}");
    assert_eq!(blocks_row[2], nb.to_string(), "{blocks_row}");
    let change = blocks_row[3].as_str().unwrap();
    assert!(
        change.starts_with(&format!("{} (", nb - na)) && change.ends_with(" %)"),
        "{change}"
    );

    // The plots: angle, thickness, pull speed, each axis.
    let plots = st["plots"].as_array().unwrap();
    assert!(plots.len() >= 4, "{st:#}");
    let series = overlaid(plots, [runs[0], runs[1]]);
    assert_eq!(st["series"].as_u64().unwrap(), series as u64);
    assert_eq!(
        r["dom"]["canvases"].as_u64().unwrap(),
        plots.len() as u64,
        "{r:#}"
    );
    // The winding angle of the same path drawn twice: run A's line solid,
    // run B's dashed over it, fewer pixels for its gaps; both together
    // about run A's.
    let px = &r["pixels"];
    let (pa, pb, both) = (
        px["a"].as_u64().unwrap(),
        px["b"].as_u64().unwrap(),
        px["both"].as_u64().unwrap(),
    );
    assert!(pa > 100 && pb > 50, "{px}");
    assert!(pb < pa * 9 / 10, "the dashed line is not broken: {px}");
    assert!(20 * both >= 19 * pa, "{px}");

    // Another kind: the table only, saying so.
    let o = &r["other"];
    assert_eq!(o["same_kind"], false, "{o:#}");
    assert_eq!(
        o["kinds"],
        serde_json::json!(["winding", "dressing"]),
        "{o:#}"
    );
    assert_eq!(o["series"], 0, "{o:#}");
    assert!(o["rows"].as_u64().unwrap() > 0, "{o:#}");
    assert_eq!(r["other_dom"]["canvases"], 0, "{r:#}");
    let note = r["other_dom"]["note"].as_str().unwrap();
    assert!(note.contains("only their summaries are compared"), "{note}");

    // Two dressing runs, the feed's upper limit lowered: the removal rate
    // and the feed per pass of both, overlaid.
    let d = &r["dressing"];
    assert_eq!(
        d["kinds"],
        serde_json::json!(["dressing", "dressing"]),
        "{d:#}"
    );
    let keys: Vec<&str> = d["differing_keys"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_str().unwrap())
        .collect();
    assert!(keys.contains(&"feed_limits_mm_min"), "{keys:?}");
    let plots = d["plots"].as_array().unwrap();
    assert_eq!(plots.len(), 2, "{d:#}");
    assert_eq!(
        d["series"].as_u64().unwrap() as usize,
        overlaid(plots, [runs[2], runs[3]])
    );
    assert_eq!(r["dressing_canvases"], 2, "{r:#}");

    // Two corrections, the gain halved: the deviation per section (the
    // same measurements) and per run of the report's history, overlaid.
    let c = &r["third"];
    assert_eq!(
        c["kinds"],
        serde_json::json!(["correction", "correction"]),
        "{c:#}"
    );
    let keys: Vec<&str> = c["differing_keys"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_str().unwrap())
        .collect();
    assert!(
        keys.contains(&"gain") && keys.contains(&"max_displacement_mm"),
        "{keys:?}"
    );
    assert!(!keys.contains(&"max_deviation_mm"), "{keys:?}");
    let plots = c["plots"].as_array().unwrap();
    assert_eq!(plots[0]["title"], "Deviation per section", "{c:#}");
    assert_eq!(
        c["series"].as_u64().unwrap() as usize,
        overlaid(plots, [runs[4], runs[5]])
    );
    assert_eq!(r["third_canvases"], plots.len(), "{r:#}");
    eprintln!("compare: screenshots in {}", shots.display());
}

/// Checks the plots of a comparison of `runs`: each series of run A solid,
/// run B's dashed in the same colour, each named after its run, each with
/// point drawn. The number of series.
fn overlaid(plots: &[serde_json::Value], runs: [&str; 2]) -> usize {
    let mut series = 0;
    for p in plots {
        let labels = p["labels"].as_array().unwrap();
        let dashed = p["dashed"].as_array().unwrap();
        let colours = p["colours"].as_array().unwrap();
        let points = p["points"].as_array().unwrap();
        let n = labels.len();
        assert!(n >= 2 && n % 2 == 0, "{p}");
        let (la, lb) = (format!("A {}: ", runs[0]), format!("B {}: ", runs[1]));
        for k in 0..n / 2 {
            assert_eq!(dashed[k], false, "{p}");
            assert_eq!(dashed[n / 2 + k], true, "{p}");
            assert_eq!(colours[k], colours[n / 2 + k], "{p}");
            assert!(labels[k].as_str().unwrap().starts_with(&la), "{p}");
            assert!(labels[n / 2 + k].as_str().unwrap().starts_with(&lb), "{p}");
            assert!(points[k].as_u64().unwrap() >= 1, "{p}");
            assert!(points[n / 2 + k].as_u64().unwrap() >= 1, "{p}");
        }
        series += n;
    }
    series
}
