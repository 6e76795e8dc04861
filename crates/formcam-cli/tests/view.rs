//! `formcam view OUT`: the address printed first, the built page served,
//! errors with exit code 2; and the page in a real browser (headless
//! Chromium driven by `viewer/tests/browser.mjs`): no console errors, the
//! canvas drawn and changed by a seek, and the payout point it shows equal
//! to `formcam machine fk` of the axes it shows; the eye trajectory and the
//! band laid drawn, the band growing; the follow camera keeping the payout
//! point centred; and a program that breaks a tightened limit with its
//! violations listed, marked on the timeline and red on the readouts, the
//! checks that ran (and why one did not) named above them.
//! Screenshots go to `target/screenshots/`.
//!
//! The browser test says it was skipped without `/usr/bin/chromium`,
//! `viewer/node_modules` or a page built into the binary, unless
//! `FORMCAM_REQUIRE_BROWSER=1` (set by `.ci/run`), when it fails. A page
//! that does not become ready fails it within a minute, naming the requests
//! that never finished.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::{Path, PathBuf};

use common::browser::{browser_present, driver};
use common::{Running, formcam, get, machines, repo, s, scratch, serving, stderr, wind_ok};

/// Starts `formcam view OUT --port 0` and reads the address it prints first.
fn view(out: &Path) -> Running {
    view_with(out, &[])
}

/// [`view`] with more arguments.
fn view_with(out: &Path, more: &[&str]) -> Running {
    let mut args = vec!["view", s(out), "--port", "0"];
    args.extend_from_slice(more);
    serving(&args)
}

/// A winding result on the 4-axis winder.
fn result(name: &str) -> PathBuf {
    let dir = scratch(name);
    let out = dir.join("out");
    wind_ok(&repo().join("examples/vessel-program-840d.toml"), &out);
    out
}

/// The result folder of `formcam VERB.. examples/EXAMPLE -o OUT`, written in
/// the scratch folder `name`.
fn example_result(name: &str, verb: &[&str], example: &str) -> PathBuf {
    let out = scratch(name).join("out");
    let job = repo().join("examples").join(example);
    let mut args = verb.to_vec();
    args.extend([s(&job), "-o", s(&out)]);
    let o = formcam().args(&args).output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

#[test]
fn view_prints_its_address_first_and_serves_the_page_or_names_the_setup_command() {
    let out = result("serve");
    if formcam_view::Page::is_embedded() {
        let v = view(&out);
        let port = v
            .url
            .strip_prefix("http://127.0.0.1:")
            .and_then(|r| r.strip_suffix('/'));
        assert!(
            port.is_some_and(|p| p.parse::<u16>().is_ok_and(|p| p > 0)),
            "{}",
            v.url
        );
        let (status, body) = get(&v.url, "/");
        assert!(status.contains(" 200 "), "{status}");
        let html = String::from_utf8(body).unwrap();
        assert!(html.contains("id=\"stage\""), "{html}");
        // Every script and style the page names (relative: `./assets/`)
        // is served by formcam itself.
        let assets: Vec<&str> = html
            .split('"')
            .filter_map(|p| p.strip_prefix("./assets/"))
            .collect();
        assert!(assets.len() >= 2, "{html}");
        for asset in assets {
            let path = format!("/assets/{asset}");
            assert!(get(&v.url, &path).0.contains(" 200 "), "{path}");
        }
        assert!(get(&v.url, "/files/summary.json").0.contains(" 200 "));
    } else {
        let o = formcam().args(["view", s(&out)]).output().unwrap();
        assert_eq!(o.status.code(), Some(2));
        assert!(o.stdout.is_empty());
        assert!(
            stderr(&o).contains("npm ci && npm run build"),
            "{}",
            stderr(&o)
        );
    }
}

#[test]
fn a_folder_that_is_no_result_fails_with_exit_2_naming_it() {
    let dir = scratch("no-result");
    let missing = dir.join("missing");
    let o = formcam().args(["view", s(&missing)]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(o.stdout.is_empty());
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    if formcam_view::Page::is_embedded() {
        assert!(e.contains(s(&missing)), "{e}");
    } else {
        assert!(e.contains("npm ci && npm run build"), "{e}");
    }
}

#[test]
fn the_browser_shows_the_payout_point_formcam_machine_fk_gives() {
    if !browser_present() {
        return;
    }
    let out = result("browser");
    let v = view(&out);
    // The same program on a machine whose carriage stops at X = 100 mm.
    let tight = out.parent().unwrap().join("winder-tight.toml");
    let text = std::fs::read_to_string(machines().join("winder-4axis.toml")).unwrap();
    assert!(text.contains("max_mm = 3000.0"));
    std::fs::write(&tight, text.replace("max_mm = 3000.0", "max_mm = 100.0")).unwrap();
    let v_tight = view_with(&out, &["--machine", s(&tight)]);
    let report = out.parent().unwrap().join("browser.json");
    let shots = repo().join("target/screenshots");
    let node = driver(
        "browser.mjs",
        &[&v.url, s(&shots), s(&report), "10", &v_tight.url],
        &report,
    );
    assert!(
        node.status.success(),
        "{}",
        String::from_utf8_lossy(&node.stderr)
    );
    drop(v);
    drop(v_tight);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(r["errors"], serde_json::json!([]), "{r:#}");
    let (before, after) = (&r["before"], &r["after"]);
    assert!(
        before["colours"].as_u64().unwrap() > 10,
        "one flat colour: {before}"
    );
    assert_ne!(
        before["hash"], after["hash"],
        "the canvas did not change after a seek"
    );
    // The payout point shown against `formcam machine fk` of the axes shown.
    let states = r["states"].as_array().unwrap();
    assert_eq!(states.len(), 4);
    let names = ["A", "X", "Y", "B"];
    let mut csv = names.join(",") + "\n";
    for st in states {
        let row: Vec<String> = names
            .iter()
            .map(|n| st["axes"][n].as_f64().unwrap().to_string())
            .collect();
        csv += &(row.join(",") + "\n");
    }
    let axes = out.parent().unwrap().join("shown-axes.csv");
    std::fs::write(&axes, csv).unwrap();
    let points = out.parent().unwrap().join("shown-points.csv");
    let machine = machines().join("winder-4axis.toml");
    let o = formcam()
        .args([
            "machine",
            "fk",
            s(&machine),
            "--axes",
            s(&axes),
            "-o",
            s(&points),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&points).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| head.iter().position(|h| *h == n).unwrap();
    let (cx, cy, cz) = (col("payout_x"), col("payout_y"), col("payout_z"));
    let mut times = Vec::new();
    for (st, line) in states.iter().zip(lines) {
        let cells: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        let shown: Vec<f64> = st["payout"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        for (k, c) in [cx, cy, cz].into_iter().enumerate() {
            assert!(
                (shown[k] - cells[c]).abs() < 0.01,
                "t {}: {shown:?} vs {line}",
                st["time_s"]
            );
        }
        assert!(st["line"].as_u64().unwrap() > 0);
        times.push(st["time_s"].as_f64().unwrap());
    }
    assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
    // The eye trajectory and the band drawn; the band grows to the whole.
    let o = &r["overlays"];
    assert!(o["eye_points"].as_u64().unwrap() > 100, "{o}");
    let band: Vec<(u64, u64)> = o["band"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| {
            (
                b["band_points"].as_u64().unwrap(),
                b["band_total"].as_u64().unwrap(),
            )
        })
        .collect();
    assert!(band[0].1 > 100, "{o}");
    assert!(band[0].0 < band[1].0 && band[1].0 < band[2].0, "{o}");
    assert_eq!(band[2].0, band[2].1, "{o}");
    assert_eq!(o["band_pixels_differ"], true, "{o}");
    assert_eq!(o["eye_pixels_differ"], true, "{o}");
    // Following: the payout point at the centre (within a pixel) at two
    // times, the camera moved with it.
    let f = &r["follow"];
    for px in f["px"].as_array().unwrap() {
        let p: Vec<f64> = px
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert!(p[0].abs() < 1.0 && p[1].abs() < 1.0, "{f}");
    }
    // The camera moved by as much as the payout point, which moved.
    let v3 = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (c0, c1) = (v3(&f["camera"][0]), v3(&f["camera"][1]));
    let (p0, p1) = (v3(&f["payout"][0]), v3(&f["payout"][1]));
    let moved: f64 = (0..3).map(|k| (p1[k] - p0[k]).powi(2)).sum::<f64>().sqrt();
    assert!(moved > 1.0, "{f}");
    for k in 0..3 {
        assert!(((c1[k] - c0[k]) - (p1[k] - p0[k])).abs() < 1e-6, "{f}");
    }
    // The tightened carriage: the position violation listed and marked; at
    // its first time the X readout is red.
    let v = &r["violations"];
    let listed: Vec<&str> = v["listed"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap())
        .collect();
    assert!(
        listed.iter().any(|l| l.starts_with("position axis X")),
        "{listed:?}"
    );
    assert!(v["marks"].as_u64().unwrap() >= 1, "{v}");
    assert!(
        v["state"]["red_axes"]
            .as_array()
            .unwrap()
            .iter()
            .any(|a| a == v["first"]["axis"].as_str().unwrap()),
        "{v}"
    );
    assert!(v["red_cells"].as_u64().unwrap() >= 1, "{v}");
    // Above the list, the checks the view ran (its own: the machine was
    // replaced) and why one did not, as `/api/violations` says.
    let checks: Vec<&str> = v["checks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    assert!(
        checks.contains(&"axes") && checks.contains(&"collisions"),
        "{v}"
    );
    assert_eq!(
        v["ran"]["checks"],
        format!("checked: {}", checks.join(", ")),
        "{v}"
    );
    match v["unchecked"].as_str() {
        Some(why) => assert_eq!(v["ran"]["unchecked"], format!("not checked: {why}"), "{v}"),
        None => assert!(v["ran"]["unchecked"].is_null(), "{v}"),
    }
    eprintln!(
        "browser: time to interactive {:.2} s, {:.1} frames/s playing at {}x; screenshots in {}",
        r["tti_s"].as_f64().unwrap(),
        r["fps"].as_f64().unwrap(),
        r["speed"],
        shots.display()
    );
}

/// Runs `viewer/tests/results.mjs KIND` on `formcam view OUT`: its report.
fn drive(kind: &str, out: &Path) -> serde_json::Value {
    let v = view(out);
    let report = out.parent().unwrap().join(format!("{kind}.json"));
    let shots = repo().join("target/screenshots");
    let node = driver(
        "results.mjs",
        &[kind, &v.url, s(&shots), s(&report)],
        &report,
    );
    drop(v);
    assert!(
        node.status.success(),
        "{}",
        String::from_utf8_lossy(&node.stderr)
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(r["errors"], serde_json::json!([]), "{r:#}");
    r
}

/// No legend value of the plots is uPlot's `--` before the pointer comes.
fn no_dashes(r: &serde_json::Value) {
    let values = r["legends"].as_array().unwrap();
    assert!(!values.is_empty(), "{r:#}");
    assert!(values.iter().all(|v| v != "--"), "{:?}", r["legends"]);
}

/// A canvas drawn: more than a few colours.
fn drawn(c: &serde_json::Value) -> bool {
    // Background, grid and a series at least (one line on a plot samples
    // to four or five colours).
    c["colours"].as_u64().unwrap() >= 3
}

#[test]
fn the_browser_draws_the_winding_plots_with_every_point_the_server_sent() {
    if !browser_present() {
        return;
    }
    let r = drive("plots", &result("browser-plots"));
    assert_eq!(r["series"], r["expected"], "{r:#}");
    no_dashes(&r);
    // Angle, thickness, pull speed, four axes, block times.
    let canvases = r["canvases"].as_array().unwrap();
    assert_eq!(canvases.len(), 8, "{r:#}");
    assert!(canvases.iter().all(drawn), "a flat plot: {r:#}");
    // The violations of the check `formcam wind` wrote, said so above them.
    let c = &r["checks"];
    assert_eq!(c["api"]["source"], "check.json", "{c}");
    assert_eq!(
        c["shown"], "checked when the program was written (check.json)",
        "{c}"
    );
    assert!(c["unchecked"].is_null(), "{c}");
}

#[test]
fn the_browser_plays_the_dressing_at_the_points_the_server_computes() {
    if !browser_present() {
        return;
    }
    let out = example_result("browser-dress", &["dress"], "dress-ballscrew-nut.toml");
    let r = drive("dressing", &out);
    assert!(drawn(&r["first"][0]) && drawn(&r["mrr"][0]), "{r:#}");
    assert_ne!(
        r["first"][0]["hash"], r["after"][0]["hash"],
        "no change after a seek"
    );
    let point =
        |v: &serde_json::Value| -> [f64; 2] { [v[0].as_f64().unwrap(), v[1].as_f64().unwrap()] };
    let mut seen = Vec::new();
    for s in r["seeks"].as_array().unwrap() {
        let (shown, server) = (
            point(&s["shown"]["dresser"]),
            point(&s["server"]["dresser"]),
        );
        assert!(
            (shown[0] - server[0]).abs() < 1e-6 && (shown[1] - server[1]).abs() < 1e-6,
            "{s}"
        );
        seen.push(shown);
    }
    assert!(seen.windows(2).all(|w| w[0] != w[1]), "{seen:?}");
    // Playing moves the time and the dresser on.
    let (before, playing) = (&r["play"]["before"], &r["play"]["playing"]);
    assert!(
        playing["time_s"].as_f64().unwrap() > before["time_s"].as_f64().unwrap(),
        "{r:#}"
    );
    assert_ne!(before["dresser"], playing["dresser"], "{r:#}");
    no_dashes(&r);
    // The region removed so far grows with the dresser: none at the start.
    let mut removed = vec![r["start"]["removed_px"].as_u64().unwrap()];
    for s in r["seeks"].as_array().unwrap() {
        removed.push(s["removed_px"].as_u64().unwrap());
    }
    assert_eq!(removed[0], 0, "{removed:?}");
    assert!(removed.windows(2).all(|w| w[0] < w[1]), "{removed:?}");
}

/// A number of the driver's report.
fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[test]
fn the_browser_pauses_zooms_and_links_the_dressing_views() {
    if !browser_present() {
        return;
    }
    let out = example_result(
        "browser-dress-views",
        &["dress"],
        "dress-ballscrew-nut.toml",
    );
    let v = view(&out);
    let report = out.parent().unwrap().join("dressing-views.json");
    let shots = repo().join("target/screenshots");
    let node = driver("dressing.mjs", &[&v.url, s(&shots), s(&report)], &report);
    drop(v);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap_or_default())
            .unwrap_or_else(|_| panic!("{}", String::from_utf8_lossy(&node.stderr)));
    assert!(node.status.success(), "{r:#}");
    assert_eq!(r["errors"], serde_json::json!([]), "{r:#}");
    let sent = &r["sent"];

    // Paused, the time stands across 300 ms; resumed, it goes on from there.
    let p = &r["pause"];
    let t = |k: &str| num(&p[k]["time_s"]);
    assert!(t("running") > num(&p["started"]), "{p:#}");
    assert_eq!(p["paused"]["playing"], false, "{p:#}");
    assert_eq!(t("paused"), t("still"), "{p:#}");
    assert!(t("resumed") > t("still"), "{p:#}");
    assert_eq!(p["buttonPaused"]["playing"], false, "{p:#}");
    assert_eq!(t("buttonPaused"), t("buttonStill"), "{p:#}");
    assert!(t("buttonResumed") > t("buttonStill"), "{p:#}");

    // The contour as cut: nothing removed at the start, more and more as
    // the program runs, at the end the area between the contours the
    // simulation gives (to the page's grid of Z).
    let forming = r["forming"].as_array().unwrap();
    let removed: Vec<f64> = forming.iter().map(|f| num(&f["removed_mm2"])).collect();
    let pixels: Vec<u64> = forming
        .iter()
        .map(|f| f["removed_px"].as_u64().unwrap())
        .collect();
    assert_eq!(removed[0], 0.0, "{removed:?}");
    assert_eq!(pixels[0], 0, "{pixels:?}");
    assert!(
        removed.windows(2).all(|w| w[1] > w[0]),
        "the removed area does not grow: {removed:?}"
    );
    // (The dresser drawn over the region hides a few of its pixels.)
    let n = pixels.len();
    assert!(
        0 < pixels[1] && pixels[1] < pixels[n / 2] && pixels[n / 2] < pixels[n - 1],
        "{pixels:?}"
    );
    let between = num(&sent["area_between_mm2"]);
    let end = *removed.last().unwrap();
    assert!(
        (end - between).abs() < 0.01 * between,
        "removed {end} mm² at the end, the simulation {between} mm²"
    );
    assert_eq!(
        sent["contours"],
        sent["steps"].as_object().unwrap().len(),
        "{sent:#}"
    );
    // At each pass's end, what the simulation removed by then.
    let ends = r["pass_ends"].as_array().unwrap();
    assert_eq!(ends.len(), 2, "{r:#}");
    for e in ends {
        let (shown, simulated) = (num(&e["removed_mm2"]), num(&e["simulated_mm2"]));
        assert!(
            (shown - simulated).abs() < 0.01 * simulated,
            "pass {}: {shown} mm² shown, {simulated} mm² simulated",
            e["pass"]
        );
    }

    // The program line marked is the state's, within the text's box.
    for seen in r["program"].as_array().unwrap() {
        assert_eq!(seen["marked_line"], seen["line"], "{seen}");
        assert_eq!(seen["marked_in_sight"], true, "{seen}");
        assert!(seen["text"].as_str().unwrap().contains('G'), "{seen}");
    }
    let clicked = &r["clicked"];
    assert!(
        clicked["state"]["line"].as_u64().unwrap() >= clicked["picked"].as_u64().unwrap(),
        "{clicked:#}"
    );

    // Zoom narrows the view and changes pixels; a drag pans it; the
    // button fits it again.
    let z = &r["zoom"];
    let width = |v: &serde_json::Value| num(&v["view"]["x1"]) - num(&v["view"]["x0"]);
    assert!(width(&z["zoomed"]) < 0.8 * width(&z["fitted"]), "{z:#}");
    assert_ne!(z["zoomed"]["canvas"]["hash"], z["fitted"]["canvas"]["hash"]);
    let shift = num(&z["panned"]["view"]["x0"]) - num(&z["zoomed"]["view"]["x0"]);
    let per_px = width(&z["zoomed"]) / num(&z["width_px"]);
    assert!((shift + 120.0 * per_px).abs() < 2.0 * per_px, "{z:#}");
    for k in ["x0", "x1", "y0", "y1"] {
        let (a, b) = (num(&z["reset"]["view"][k]), num(&z["fitted"]["view"][k]));
        assert!((a - b).abs() < 1e-9 * a.abs().max(1.0), "{k}: {z:#}");
    }
    assert_eq!(z["reset"]["canvas"]["hash"], z["fitted"]["canvas"]["hash"]);

    // The dresser puts the plots' cursor at its Z; hovering a plot at a Z
    // puts the marker there on the profile (the nearest step's Z, within a
    // pixel of the plot), drawn at its column; off the plot, none.
    let c = &r["cursor"];
    assert_eq!(c["plot_cursor_z"], c["dresser"][1], "{c:#}");
    assert!(c["plot_row"].is_u64(), "{c:#}");
    let zs: Vec<f64> = sent["z"].as_array().unwrap().iter().map(num).collect();
    for h in r["hover"].as_array().unwrap() {
        let (lo, hi) = (num(&h["plot_z"][0]), num(&h["plot_z"][1]));
        let want = lo + num(&h["f"]) * (hi - lo);
        let px = (hi - lo) / num(&h["width_px"]);
        let nearest = zs
            .iter()
            .map(|z| (z - want).abs())
            .fold(f64::INFINITY, f64::min);
        let m = &h["marker"];
        assert!(m.is_object(), "no marker: {h:#}");
        let at = num(&m["z"]);
        assert!((at - want).abs() <= nearest + 2.0 * px, "{want} mm: {h:#}");
        assert_eq!(num(&m["point_a"][0]), at, "{h:#}");
        assert!(h["marker_px_column"].as_u64().unwrap() > 0, "{h:#}");
    }
    assert!(r["hover_off"].is_null(), "{r:#}");

    // Both series, with and without feed control, every step of each pass.
    let plots = &r["plots"];
    for (k, n) in sent["steps"].as_object().unwrap() {
        for label in [
            format!("with control, pass {k}"),
            format!("without control, pass {k}"),
        ] {
            assert_eq!(plots["mrr"][&label], *n, "{label}: {plots:#}");
        }
        assert_eq!(plots["feed"][format!("with control, pass {k}")], *n);
    }
    assert_eq!(plots["feed"]["without control"], sent["all_steps"]);
    let colours = &r["colours"];
    for k in [
        "controlled",
        "uncontrolled",
        "feed_controlled",
        "feed_uncontrolled",
    ] {
        assert!(colours[k].as_u64().unwrap() > 20, "{k}: {colours:#}");
    }
    no_dashes(&r);
    eprintln!(
        "dressing: screenshots dressing-open.png, dressing-resumed.png, dressing-forming.png, \
         dressing-zoom.png, dressing-linked.png, dressing-plots.png in {}",
        shots.display()
    );
}

#[test]
fn the_browser_maps_every_measured_point_of_a_correction() {
    if !browser_present() {
        return;
    }
    let out = example_result("browser-correct", &["correct"], "correct-mould.toml");
    let r = drive("correction", &out);
    let cmm = std::fs::read_to_string(repo().join("examples/correct/cmm.csv")).unwrap();
    let points = cmm.lines().skip(1).filter(|l| !l.trim().is_empty()).count();
    assert_eq!(
        r["state"]["points"].as_u64().unwrap() as usize,
        points,
        "{r:#}"
    );
    assert!(drawn(&r["map"][0]) && drawn(&r["sections"][0]), "{r:#}");
    no_dashes(&r);
    // The measurement file's path plain in the title (the job's path, and
    // so the report's, runs through `crates/formcam-cli/../..`).
    let title = r["title"].as_str().unwrap();
    assert!(
        title.ends_with("examples/correct/cmm.csv") && !title.contains("/../"),
        "{title}"
    );
    // The surface in 3-D: the report's grid of sections, drawn where its
    // centre is, with a colour bar.
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let (before, after) = (&r["before"], &r["after"]);
    let surface = &before["state"]["surface"];
    let (nu, nv) = (
        report["points_per_section"].as_u64().unwrap(),
        report["sections"].as_u64().unwrap(),
    );
    assert_eq!(surface["vertices"].as_u64().unwrap(), nu * nv, "{r:#}");
    assert_eq!(
        surface["triangles"].as_u64().unwrap(),
        2 * (nu - 1) * (nv - 1)
    );
    assert_eq!(surface["dots"].as_u64().unwrap() as usize, points);
    for seen in [before, after] {
        let centre: Vec<u64> = seen["centre"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_u64().unwrap())
            .collect();
        assert!(
            centre
                .iter()
                .zip(BACKGROUND)
                .any(|(c, b)| c.abs_diff(b) > 3),
            "the background at the surface's centre: {r:#}"
        );
        assert!(
            drawn(&seen["surface"][0]) && drawn(&seen["bar"][0]),
            "{r:#}"
        );
    }
    // Before and after on one colour scale: other colours, and a smaller
    // worst deviation after (the next part predicted, as the report says).
    assert_eq!(before["state"]["view"], "before");
    assert_eq!(after["state"]["view"], "after");
    assert_eq!(before["state"]["limit"], after["state"]["limit"]);
    assert_ne!(before["surface"][0]["hash"], after["surface"][0]["hash"]);
    assert_ne!(before["map"][0]["hash"], after["map"][0]["hash"]);
    let worst = |s: &serde_json::Value| s["state"]["max_abs_deviation"].as_f64().unwrap();
    assert!(worst(after) < worst(before), "{r:#}");
    assert!(
        (worst(after) - report["predicted_max_deviation_mm"].as_f64().unwrap()).abs() < 1e-9,
        "{r:#}"
    );
    assert!(
        (worst(before) - report["max_deviation_mm"].as_f64().unwrap()).abs() < 1e-9,
        "{r:#}"
    );
    // Back to before: the first picture again.
    assert_eq!(
        before["surface"][0]["hash"],
        r["back"]["surface"][0]["hash"]
    );
    // Every node marked by what happened to it, counted as the report does.
    let nodes = &before["state"]["nodes"];
    assert_eq!(nodes["every"], 1);
    let markers = &nodes["markers"];
    let marked = |k: &str| markers[k].as_u64().unwrap_or(0);
    assert_eq!(
        marked("inside") + marked("extrapolated") + marked("outside") + marked("unknown"),
        report["nodes_feed"].as_u64().unwrap()
    );
    assert_eq!(
        marked("extrapolated"),
        report["nodes_extrapolated"].as_u64().unwrap()
    );
    assert_eq!(marked("outside"), report["nodes_outside"].as_u64().unwrap());
    assert!(marked("inside") > 0, "{r:#}");
    eprintln!(
        "correction: screenshots correction-before.png, correction-after.png in {}",
        repo().join("target/screenshots").display()
    );
}

#[test]
fn the_browser_opens_a_closed_loop_with_the_map_of_each_round() {
    if !browser_present() {
        return;
    }
    let out = example_result(
        "browser-loop",
        &["correct", "simulate"],
        "correct-panel-loop.toml",
    );
    let r = drive("loop", &out);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let rounds = report["rounds"].as_array().unwrap().len();
    let state = &r["state"];
    assert_eq!(state["rounds"].as_u64().unwrap() as usize, rounds, "{r:#}");
    assert_eq!(state["round"].as_u64().unwrap() as usize, rounds - 1);
    let cmm = |k: usize| {
        std::fs::read_to_string(out.join(format!("cmm-{k}.csv")))
            .unwrap()
            .lines()
            .skip(1)
            .filter(|l| !l.trim().is_empty())
            .count() as u64
    };
    assert_eq!(state["points"].as_u64().unwrap(), cmm(rounds - 1), "{r:#}");
    // Every round in the history plot, every study row in its plot.
    let history = state["series"]["history"].as_array().unwrap();
    assert!(
        history
            .iter()
            .all(|n| n.as_u64().unwrap() as usize == rounds),
        "{r:#}"
    );
    let study = report["section_study"].as_array().unwrap();
    let drawn_study: u64 = state["series"]["study"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_u64().unwrap())
        .sum();
    // A maximum and an RMS per row.
    assert_eq!(drawn_study as usize, 2 * study.len(), "{r:#}");
    for plot in ["map", "sections", "history", "study"] {
        assert!(drawn(&r[plot][0]), "{plot}: {r:#}");
    }
    no_dashes(&r);
    // Round 0's map: other deviations, so other colours.
    assert_eq!(r["round0"]["state"]["round"], 0);
    assert_eq!(r["round0"]["state"]["points"].as_u64().unwrap(), cmm(0));
    assert_ne!(r["round0"]["map"][0]["hash"], r["map"][0]["hash"]);
    // The last round has no after; round 0's is round 1, on one scale.
    assert_eq!(state["after_available"], false, "{r:#}");
    assert_eq!(state["view"], "before");
    let (before, after) = (&r["round0"]["state"], &r["round0_after"]["state"]);
    assert_eq!(
        (&before["view"], &after["view"]),
        (&"before".into(), &"after".into())
    );
    assert_eq!(after["round"], 0);
    assert_eq!(before["limit"], after["limit"]);
    let worst = |s: &serde_json::Value| s["max_abs_deviation"].as_f64().unwrap();
    let measured = |k: usize| report["rounds"][k]["measured_max_mm"].as_f64().unwrap();
    assert!((worst(before) - measured(0)).abs() < 2e-4, "{r:#}");
    assert!((worst(after) - measured(1)).abs() < 2e-4, "{r:#}");
    assert!(worst(after) < worst(before), "{r:#}");
    assert!(drawn(&r["round0_after"]["surface"][0]), "{r:#}");
    assert!(
        r["title"]
            .as_str()
            .unwrap()
            .ends_with("examples/correct-panel-loop.toml")
    );
}

/// The tolerance of a report's payout point against the server's, mm
/// (the report interpolates poses within 0.001 mm of forward kinematics).
const REPORT_PAYOUT_MM: f64 = 0.01;

#[test]
fn the_report_opens_offline_from_a_file_and_draws_every_view() {
    if !browser_present() {
        return;
    }
    let dir = scratch("browser-report");
    let wind = result("browser-report-wind");
    let dress = dir.join("dress");
    let correct = dir.join("correct");
    for (verb, job, out) in [
        ("dress", "examples/dress-ballscrew-nut.toml", &dress),
        ("correct", "examples/correct-mould.toml", &correct),
    ] {
        let o = formcam()
            .args([verb, s(&repo().join(job)), "-o", s(out)])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let mut runs = Vec::new();
    let mut servers = Vec::new();
    for (kind, out) in [
        ("winding", &wind),
        ("dressing", &dress),
        ("correction", &correct),
    ] {
        let file = dir.join(format!("{kind}.html"));
        let o = formcam()
            .args(["report", s(out), "-o", s(&file)])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        eprintln!("{}", String::from_utf8_lossy(&o.stdout).trim_end());
        let v = view(out);
        runs.push(format!("{kind}={}={}", s(&file), v.url));
        servers.push(v);
    }
    let report = dir.join("report.json");
    let shots = repo().join("target/screenshots");
    let mut args = vec![s(&shots).to_string(), s(&report).to_string()];
    args.extend(runs);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let node = driver("report.mjs", &args, &report);
    drop(servers);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap_or_default())
            .unwrap_or_else(|_| panic!("{}", String::from_utf8_lossy(&node.stderr)));
    assert!(node.status.success(), "{r:#}");
    assert_eq!(r["errors"], serde_json::json!([]), "{r:#}");
    let results = &r["results"];
    for kind in ["winding", "dressing", "correction"] {
        let k = &results[kind];
        assert_eq!(
            k["blocked"],
            serde_json::json!([]),
            "{kind} asked the network"
        );
        assert!(
            k["title"].as_str().unwrap().starts_with("formcam report"),
            "{k:#}"
        );
        assert!(
            k["heading"].as_str().unwrap().starts_with("formcam report"),
            "{k:#}"
        );
        assert!(drawn(&k["first"][0]), "{kind}: a flat canvas: {k:#}");
    }
    // The winding: drawn, changed by a seek, the state the server's.
    let w = &results["winding"];
    assert_ne!(
        w["first"][0]["hash"], w["after"][0]["hash"],
        "no change after a seek"
    );
    assert!(w["plots"].as_array().unwrap().iter().all(drawn), "{w:#}");
    let names: Vec<&str> = w["axes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    let payout = w["payout"].as_u64().unwrap() as usize;
    for seek in w["seeks"].as_array().unwrap() {
        let (shown, server) = (&seek["shown"], &seek["server"]);
        assert_eq!(shown["time_s"], server["t"], "{seek}");
        assert_eq!(shown["block"], server["block"], "{seek}");
        assert_eq!(shown["line"], server["line"], "{seek}");
        // The band laid: the server's count, drawn.
        assert!(server["laid"].is_u64(), "no band: {seek}");
        assert_eq!(shown["band_points"], server["laid"], "{seek}");
        for (k, name) in names.iter().enumerate() {
            let a = shown["axes"][name].as_f64().unwrap();
            let b = server["axes"][k].as_f64().unwrap();
            assert!((a - b).abs() <= 1e-9 * b.abs().max(1.0), "{name}: {seek}");
        }
        for c in 0..3 {
            let a = shown["payout"][c].as_f64().unwrap();
            let b = server["points"][payout][c].as_f64().unwrap();
            assert!((a - b).abs() <= REPORT_PAYOUT_MM, "payout: {seek}");
        }
    }
    // The dressing: the dresser where the server puts it.
    let d = &results["dressing"];
    assert_ne!(
        d["first"][0]["hash"], d["after"][0]["hash"],
        "no change after a seek"
    );
    assert!(drawn(&d["mrr"][0]), "{d:#}");
    for seek in d["seeks"].as_array().unwrap() {
        assert_eq!(seek["shown"]["block"], seek["server"]["block"], "{seek}");
        for c in 0..2 {
            let a = seek["shown"]["dresser"][c].as_f64().unwrap();
            let b = seek["server"]["dresser"][c].as_f64().unwrap();
            assert!((a - b).abs() <= 1e-9, "{seek}");
        }
    }
    // The correction: every point of the map.
    let c = &results["correction"];
    assert_eq!(c["state"]["points"], c["server_points"], "{c:#}");
    assert!(drawn(&c["sections"][0]), "{c:#}");
    // The surface in 3-D, before and after, from the inlined answer.
    assert!(drawn(&c["surface"][0]), "{c:#}");
    assert_eq!(c["after_state"]["view"], "after", "{c:#}");
    assert_ne!(c["surface"][0]["hash"], c["after_surface"][0]["hash"]);
    eprintln!(
        "report: screenshots report-winding.png, report-plots.png, report-dressing.png, report-correction.png in {}",
        shots.display()
    );
}

/// The colour of the 3-D view's background (`scene.ts`).
const BACKGROUND: [u64; 3] = [0xdf, 0xe4, 0xea];

#[test]
fn the_browser_draws_the_machines_mesh_solids_and_names_a_missing_one() {
    if !browser_present() {
        return;
    }
    // The 4-axis winder's chuck flange is a mesh solid (machines/meshes/).
    let out = result("browser-mesh");
    let v = view(&out);
    let missing = out.parent().unwrap().join("winder-no-mesh.toml");
    let text = std::fs::read_to_string(machines().join("winder-4axis.toml")).unwrap();
    assert!(text.contains("meshes/chuck-flange.stl"));
    std::fs::write(
        &missing,
        text.replace("meshes/chuck-flange.stl", "meshes/no-such-flange.stl"),
    )
    .unwrap();
    let v_missing = view_with(&out, &["--machine", s(&missing)]);
    let report = out.parent().unwrap().join("mesh.json");
    let shots = repo().join("target/screenshots");
    let node = driver(
        "mesh.mjs",
        &[&v.url, s(&shots), s(&report), &v_missing.url],
        &report,
    );
    drop(v);
    drop(v_missing);
    assert!(
        node.status.success(),
        "{}",
        String::from_utf8_lossy(&node.stderr)
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(r["errors"], serde_json::json!([]), "{r:#}");
    // Every triangle of the file drawn, nothing said against it.
    let flange =
        formcam_machine::read_mesh(&machines().join("meshes/chuck-flange.stl"), [1.0; 3]).unwrap();
    let m = &r["mesh"];
    assert_eq!(m["triangles"], flange.triangles.len(), "{m}");
    assert_eq!(m["notes"], serde_json::json!([]), "{m}");
    assert_eq!(m["notes_shown"], serde_json::json!([]), "{m}");
    // Where the flange is drawn the picture is neither the background nor
    // what it is with the meshes hidden.
    let rgb = |v: &serde_json::Value| -> Vec<u64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_u64().unwrap())
            .collect()
    };
    let (shown, hidden) = (rgb(&m["shown"][0]), rgb(&m["hidden"][0]));
    let far = |a: &[u64], b: &[u64]| a.iter().zip(b).any(|(x, y)| x.abs_diff(*y) > 8);
    assert!(far(&shown, &BACKGROUND), "{m}");
    assert!(far(&shown, &hidden), "{m}");
    // A mesh file that is not there is said on the page, naming it.
    let miss = &r["missing"];
    assert_eq!(miss["triangles"], 0, "{miss}");
    for key in ["notes", "notes_shown"] {
        let notes = miss[key].as_array().unwrap();
        assert!(
            notes.len() == 1
                && notes[0]
                    .as_str()
                    .unwrap()
                    .contains("meshes/no-such-flange.stl"),
            "{miss}"
        );
    }
}

#[test]
fn the_browser_opens_a_winding_path_without_a_program() {
    if !browser_present() {
        return;
    }
    let out = example_result(
        "browser-path",
        &["wind", "eye"],
        "vessel-eye-pull-speed.toml",
    );
    assert!(!out.join("blocks.csv").exists());
    let r = drive("path", &out);
    let (state, expected) = (&r["state"], &r["expected"]);
    assert_eq!(state["kind"], "path", "{r:#}");
    // The whole path, band and eye the server sent are drawn.
    assert_eq!(state["path_points"], expected["path"], "{r:#}");
    assert_eq!(state["band_points"], expected["band"], "{r:#}");
    assert_eq!(state["band_total"], expected["band"], "{r:#}");
    assert_eq!(state["eye_points"], expected["eye"], "{r:#}");
    assert!(expected["eye"].as_u64().unwrap() > 0, "{r:#}");
    // Half the circuits: fewer band points, another picture.
    let half = &r["half"];
    assert_eq!(
        half["band_circuits"],
        expected["circuits"].as_u64().unwrap() / 2
    );
    assert!(half["band_points"].as_u64() < expected["band"].as_u64());
    let (scene, half_scene) = (&r["scene"][0], &r["half_scene"][0]);
    assert!(
        scene["colours"].as_u64().unwrap() > 8,
        "a flat picture: {r:#}"
    );
    assert_ne!(scene["hash"], half_scene["hash"], "{r:#}");
    // Winding angle, thickness, pull speed; no axes without a program.
    let canvases = r["canvases"].as_array().unwrap();
    assert_eq!(canvases.len(), 3, "{r:#}");
    assert!(canvases.iter().all(drawn), "a flat plot: {r:#}");
    let plots = state["plots"].as_object().unwrap();
    assert_eq!(plots.len(), 3, "{r:#}");
}
