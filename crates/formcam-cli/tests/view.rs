//! `formcam view OUT`: the address printed first, the built page served,
//! errors with exit code 2; and the page in a real browser (headless
//! Chromium driven by `viewer/tests/browser.mjs`): no console errors, the
//! canvas drawn and changed by a seek, and the payout point it shows equal
//! to `formcam machine fk` of the axes it shows. Screenshots go to
//! `target/screenshots/`.
//!
//! The browser test says it was skipped without `/usr/bin/chromium`,
//! `viewer/node_modules` or a page built into the binary, unless
//! `FORMCAM_REQUIRE_BROWSER=1` (set by `.ci/run`), when it fails. A page
//! that does not become ready fails it within a minute, naming the requests
//! that never finished.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{formcam, machines, repo, s, scratch, stderr, wind_ok};

/// `formcam view` running, ended when dropped.
struct Running {
    child: Child,
    url: String,
}

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts `formcam view OUT --port 0` and reads the address it prints first.
fn view(out: &Path) -> Running {
    let mut child = formcam()
        .args(["view", s(out), "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    let url = first.trim_end().to_string();
    Running { child, url }
}

/// A GET of `path` on the server at `url`: status line and body.
fn get(url: &str, path: &str) -> (String, Vec<u8>) {
    let addr = url.trim_start_matches("http://").trim_end_matches('/');
    let mut c = TcpStream::connect(addr).unwrap();
    c.write_all(
        format!("GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n").as_bytes(),
    )
    .unwrap();
    let mut out = Vec::new();
    c.read_to_end(&mut out).unwrap();
    let i = out.windows(4).position(|w| w == b"\r\n\r\n").unwrap();
    let head = String::from_utf8_lossy(&out[..i]).into_owned();
    (
        head.lines().next().unwrap_or("").to_string(),
        out[i + 4..].to_vec(),
    )
}

/// A winding result on the 4-axis winder.
fn result(name: &str) -> PathBuf {
    let dir = scratch(name);
    let out = dir.join("out");
    wind_ok(&repo().join("examples/vessel-program-840d.toml"), &out);
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
        // Every script and style the page names is served by formcam itself.
        for asset in html.split('"').filter(|p| p.starts_with("/assets/")) {
            assert!(get(&v.url, asset).0.contains(" 200 "), "{asset}");
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

/// Whether the browser test can run here; fails when it must.
fn browser_present() -> bool {
    let missing: Vec<&str> = [
        (!Path::new("/usr/bin/chromium").is_file())
            .then_some("/usr/bin/chromium (apt-get install chromium)"),
        (!repo().join("viewer/node_modules/playwright-core").is_dir())
            .then_some("viewer/node_modules (npm ci in viewer/)"),
        (!formcam_view::Page::is_embedded())
            .then_some("the built page (npm run build in viewer/, then cargo build)"),
    ]
    .into_iter()
    .flatten()
    .collect();
    if !missing.is_empty() {
        assert!(
            std::env::var("FORMCAM_REQUIRE_BROWSER").as_deref() != Ok("1"),
            "FORMCAM_REQUIRE_BROWSER=1 but missing: {}",
            missing.join(", ")
        );
        eprintln!("skipped: the browser test needs {}", missing.join(", "));
    }
    missing.is_empty()
}

/// The most the browser driver may take; it bounds itself (a page not
/// ready within 45 s, the whole run within 150 s), this is the last resort.
const DRIVER_LIMIT: Duration = Duration::from_secs(180);

/// Runs `viewer/tests/browser.mjs` on `url`, killed past [`DRIVER_LIMIT`].
fn driver(url: &str, shots: &Path, report: &Path) -> Output {
    let mut child = Command::new("node")
        .arg(repo().join("viewer/tests/browser.mjs"))
        .args([url, s(shots), s(report)])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > DRIVER_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "the browser driver did not end within {} s; its report so far: {}",
                DRIVER_LIMIT.as_secs(),
                std::fs::read_to_string(report).unwrap_or_default()
            );
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    child.wait_with_output().unwrap()
}

#[test]
fn the_browser_shows_the_payout_point_formcam_machine_fk_gives() {
    if !browser_present() {
        return;
    }
    let out = result("browser");
    let v = view(&out);
    let report = out.parent().unwrap().join("browser.json");
    let shots = repo().join("target/screenshots");
    let node = driver(&v.url, &shots, &report);
    assert!(
        node.status.success(),
        "{}",
        String::from_utf8_lossy(&node.stderr)
    );
    drop(v);
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
    eprintln!(
        "browser: time to interactive {:.2} s, {:.1} frames/s playing at {}x; screenshots in {}",
        r["tti_s"].as_f64().unwrap(),
        r["fps"].as_f64().unwrap(),
        r["speed"],
        shots.display()
    );
}
