//! The server on a port the system chooses, asked with raw HTTP requests:
//! the JSON the page draws agrees with the machine's forward kinematics at
//! the program's own block times, the result's files come back byte for
//! byte, and every request outside the rules is refused; the violations are
//! the simulator's checks (or the folder's `check.json`), the eye trajectory
//! the payout point by forward kinematics, the band laid the circuit tables
//! by the spindle angle.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::time::Duration;

use formcam_machine::Machine;
use formcam_nc::{Block, Dialect, Feed, Program, write};
use formcam_sim::{AxisLimits, FeedRule, Timeline, check_timeline, program_axes};
use formcam_view::{Page, ViewOptions, ViewServer};
use serde_json::Value;

/// Block times of the program, s.
const TIMES: [f64; 4] = [0.5, 1.25, 0.75, 2.0];

fn machine() -> Machine {
    let text = formcam_machine::shipped::shipped("winder-4axis")
        .unwrap()
        .text;
    Machine::from_toml(text).unwrap()
}

/// Block ends (A deg, X, Y mm, B deg) of the test program.
fn targets() -> Vec<[f64; 4]> {
    vec![
        [0.0, 0.0, 250.0, 0.0],
        [90.0, 100.0, 240.0, 10.0],
        [400.0, 250.0, 200.0, -30.0],
        [720.0, 300.0, 210.0, 45.0],
        [800.0, 20.0, 300.0, 0.0],
    ]
}

/// A result folder: a summary naming the shipped machine and the program,
/// the program (840D, inverse time) and a path table.
fn folder(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let m = machine();
    let mut p = Program::new("VIEW", program_axes(&m));
    let t = targets();
    p.blocks.push(Block::rapid(t[0].to_vec()));
    for (k, b) in t[1..].iter().enumerate() {
        p.blocks
            .push(Block::linear(b.to_vec(), Feed::InverseTime(TIMES[k])));
    }
    let mut text = String::new();
    write(&p, Dialect::Sinumerik840d, &mut text).unwrap();
    std::fs::write(dir.join("program.mpf"), text).unwrap();
    std::fs::write(
        dir.join("summary.json"),
        r#"{"job": "vessel.toml", "machine_shipped": "winder-4axis", "program_file": "program.mpf"}"#,
    )
    .unwrap();
    let mut path = String::from("s,z,r,v\n");
    for i in 0..=100 {
        let z = f64::from(i) * 3.0;
        path.push_str(&format!(
            "{i},{z},{},{}\n",
            50.0 + z / 10.0,
            f64::from(i) * 0.05
        ));
    }
    std::fs::write(dir.join("path.csv"), path).unwrap();
    dir
}

/// A server for `dir` answering on a background thread.
fn start(dir: &Path) -> Probe {
    serve(ViewServer::bind(dir, &ViewOptions::default(), Page::none()).unwrap())
}

fn serve(server: ViewServer) -> Probe {
    let probe = Probe {
        addr: server.addr(),
        url: server.url(),
    };
    let _ = server.spawn();
    probe
}

/// Where a server listens.
struct Probe {
    addr: std::net::SocketAddr,
    url: String,
}

impl Probe {
    fn json(&self, url: &str) -> Value {
        get_json(self, url)
    }
}

/// Sends `request` as it is and returns the status and the body.
fn raw(server: &Probe, request: &[u8]) -> (u16, Vec<u8>) {
    let a = formcam_testkit::send(server.addr, request, Duration::from_secs(10));
    (a.status, a.body)
}

/// A GET with its response's head.
fn get_with_head(server: &Probe, url: &str) -> (u16, String, Vec<u8>) {
    let a = formcam_testkit::get(server.addr, url);
    (a.status, a.head, a.body)
}

fn get(server: &Probe, url: &str) -> (u16, Vec<u8>) {
    let a = formcam_testkit::get(server.addr, url);
    (a.status, a.body)
}

fn get_json(server: &Probe, url: &str) -> Value {
    let (status, body) = get(server, url);
    assert_eq!(status, 200, "{url}: {}", String::from_utf8_lossy(&body));
    serde_json::from_slice(&body).unwrap()
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The axes at `t` by the program's block times, in rad and mm.
fn axes_at(t: f64) -> Vec<f64> {
    let ends: Vec<f64> = TIMES
        .iter()
        .scan(0.0, |s, d| {
            *s += d;
            Some(*s)
        })
        .collect();
    let k = ends.iter().position(|&e| e >= t).unwrap_or(ends.len() - 1);
    let start = if k == 0 { 0.0 } else { ends[k - 1] };
    let f = (t - start) / TIMES[k];
    let (a, b) = (targets()[k], targets()[k + 1]);
    (0..4)
        .map(|i| {
            let v = a[i] + (b[i] - a[i]) * f;
            if i == 0 || i == 3 { v.to_radians() } else { v }
        })
        .collect()
}

#[test]
fn it_listens_on_the_loopback_only_at_the_port_chosen() {
    let server = start(&folder("loopback"));
    assert!(server.addr.ip().is_loopback());
    assert_ne!(server.addr.port(), 0);
    assert_eq!(
        server.url,
        format!("http://127.0.0.1:{}/", server.addr.port())
    );
    assert_eq!(get(&server, "/api/result").0, 200);
}

#[test]
fn the_timeline_is_the_program_at_its_block_times_through_forward_kinematics() {
    let dir = folder("timeline");
    let server = start(&dir);
    let tl = server.json("/api/timeline?samples=9");
    let duration: f64 = TIMES.iter().sum();
    assert!((tl["duration_s"].as_f64().unwrap() - duration).abs() < 1e-12);
    assert_eq!(tl["blocks"], 5);
    assert_eq!(tl["axes"][0]["name"], "A");
    assert_eq!(tl["axes"][0]["unit"], "deg");
    let samples = tl["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 9);
    let m = machine();
    let payout = tl["payout"].as_u64().unwrap() as usize;
    for (i, s) in samples.iter().enumerate() {
        let t = duration * i as f64 / 8.0;
        assert!((s["t"].as_f64().unwrap() - t).abs() < 1e-12);
        let q = axes_at(t);
        let shown = nums(&s["axes"]);
        for k in 0..4 {
            let want = if k == 0 || k == 3 {
                q[k].to_degrees()
            } else {
                q[k]
            };
            assert!(
                (shown[k] - want).abs() < 1e-9,
                "t {t} axis {k}: {} {want}",
                shown[k]
            );
        }
        let p = m.key_points(&q)[payout];
        let sent = nums(&s["points"][payout]);
        assert!(
            (sent[0] - p.x).abs() < 1e-9
                && (sent[1] - p.y).abs() < 1e-9
                && (sent[2] - p.z).abs() < 1e-9
        );
        // Every link's pose as FK gives it.
        let poses = m.poses(&q);
        for (l, pose) in poses.iter().enumerate() {
            let sent = nums(&s["poses"][l]);
            let v = pose.translation.vector;
            let r = pose.rotation.quaternion();
            for (a, b) in sent.iter().zip([v.x, v.y, v.z, r.i, r.j, r.k, r.w]) {
                assert!((a - b).abs() < 1e-9, "link {l}");
            }
        }
    }
    // An exact sample at a block's end: the block's target, its line.
    let s = server.json("/api/sample?t=1.75");
    assert_eq!(s["block"], 2);
    assert_eq!(nums(&s["axes"]), targets()[2].to_vec());
    let program = std::fs::read_to_string(dir.join("program.mpf")).unwrap();
    let line = program
        .lines()
        .nth(s["line"].as_u64().unwrap() as usize - 1)
        .unwrap();
    assert!(line.contains("X250") && line.contains("Y200"), "{line}");
    let blocks = server.json("/api/blocks");
    assert_eq!(nums(&blocks["ends"]).len(), 5);
    assert!((nums(&blocks["starts"])[3] - 1.75).abs() < 1e-12);
}

#[test]
fn the_scene_and_the_results_files_are_served() {
    let dir = folder("files");
    let server = start(&dir);
    let machine = get_json(&server, "/api/machine");
    assert_eq!(machine["name"], "4-axis winder");
    assert_eq!(machine["links"][0]["solids"][0]["shape"], "box");
    let mandrel = get_json(&server, "/api/mandrel");
    assert_eq!(mandrel["meridian"].as_array().unwrap().len(), 101);
    assert_eq!(
        get_json(&server, "/api/result")["program_file"],
        "program.mpf"
    );
    let (status, body) = get(&server, "/files/program.mpf");
    assert_eq!(status, 200);
    assert_eq!(body, std::fs::read(dir.join("program.mpf")).unwrap());
    let (status, body) = get(&server, "/api/program");
    assert_eq!(
        (status, body),
        (200, std::fs::read(dir.join("program.mpf")).unwrap())
    );
    assert_eq!(get(&server, "/files/nothing.csv").0, 404);
    assert_eq!(get(&server, "/api/nothing").0, 404);
    // No page built into this server: nothing at `/`.
    assert_eq!(get(&server, "/").0, 404);
}

#[test]
fn a_page_is_served_at_the_root() {
    let dir = folder("page");
    let page = Page::from_files(vec![("index.html".into(), b"<html>x</html>".to_vec())]);
    let server = serve(ViewServer::bind(&dir, &ViewOptions::default(), page).unwrap());
    let (status, head, body) = get_with_head(&server, "/");
    assert_eq!((status, body), (200, b"<html>x</html>".to_vec()));
    assert!(head.contains("Content-Type: text/html"), "{head}");
    assert_eq!(get(&server, "/favicon.ico").0, 200);
    assert_eq!(get(&server, "/index.html").0, 200);
}

#[test]
fn traversal_other_methods_and_oversized_requests_are_refused() {
    let dir = folder("refuse");
    let outside = dir.parent().unwrap().join("refuse-secret.txt");
    std::fs::write(&outside, "secret").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(&outside, dir.join("link.txt")).unwrap();
    let server = start(&dir);
    for url in [
        "/files/../refuse-secret.txt",
        "/files/%2e%2e/refuse-secret.txt",
        "/files/%2E%2E%2Frefuse-secret.txt",
        "/files/..%5crefuse-secret.txt",
        "/files//etc/passwd",
        "/files/.formcam-run",
        "/files/a%00b",
        "/../../etc/passwd",
    ] {
        let (status, body) = get(&server, url);
        assert_eq!(status, 400, "{url}: {}", String::from_utf8_lossy(&body));
    }
    // A symlink out of the folder, an absolute path: nothing there.
    #[cfg(unix)]
    assert_eq!(get(&server, "/files/link.txt").0, 404);
    assert_eq!(get(&server, "/etc/passwd").0, 404);
    for method in ["POST", "PUT", "DELETE", "HEAD", "OPTIONS"] {
        let (status, _) = raw(
            &server,
            format!(
                "{method} /api/result HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n"
            )
            .as_bytes(),
        );
        assert_eq!(status, 405, "{method}");
    }
    let long = format!("/files/{}", "a".repeat(4096));
    assert_eq!(get(&server, &long).0, 414);
    let (status, _) = raw(
        &server,
        b"GET /api/result HTTP/1.1\r\nHost: localhost\r\nContent-Length: 5\r\nConnection: close\r\n\r\nhello",
    );
    assert_eq!(status, 413);
    let big = format!(
        "GET /api/result HTTP/1.1\r\nHost: localhost\r\nX-Big: {}\r\nConnection: close\r\n\r\n",
        "b".repeat(20_000)
    );
    let (status, _) = raw(&server, big.as_bytes());
    assert!(status == 431 || status == 400, "{status}");
    assert_eq!(get(&server, "/api/timeline?samples=x").0, 400);
    assert_eq!(get(&server, "/api/sample?t=nan").0, 400);
    // A page of another site whose name points here (DNS rebinding).
    let (status, body) = raw(
        &server,
        b"GET /api/result HTTP/1.1\r\nHost: evil.example:80\r\nConnection: close\r\n\r\n",
    );
    assert_eq!(status, 403, "{}", String::from_utf8_lossy(&body));
}

#[test]
fn a_folder_without_a_summary_names_the_file() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("empty-result");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let e = ViewServer::bind(&dir, &ViewOptions::default(), Page::none())
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("summary.json"), "{e}");
}

/// The simulator's timeline of the test program, as `formcam check` plays it.
fn sim_timeline(dir: &Path) -> Timeline {
    let m = machine();
    let text = std::fs::read_to_string(dir.join("program.mpf")).unwrap();
    let (p, lines, d) = formcam_sim::read_program(&dir.join("program.mpf"), &text, &m).unwrap();
    Timeline::new(&p, &lines, FeedRule::of(d), &m).unwrap()
}

#[test]
fn the_violations_are_the_simulators_checks_with_their_blocks_times() {
    let dir = folder("violations");
    let server = start(&dir);
    let v = server.json("/api/violations");
    assert_eq!(v["source"], "check");
    let tl = sim_timeline(&dir);
    let want = check_timeline(&tl, &AxisLimits::of(&machine()));
    // From rest to 180 deg/s on A in the first feed block: a jump at least.
    assert!(!want.is_empty());
    assert_eq!(v["clean"], false);
    let got = v["violations"].as_array().unwrap();
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(&want) {
        assert_eq!(g["kind"], w.kind.name());
        assert_eq!(g["axis"], w.axis.as_str());
        assert_eq!(g["block"], w.block);
        assert_eq!(g["time_s"].as_f64().unwrap(), w.time_s);
        let b = tl.block(w.block - 1).unwrap();
        assert_eq!(
            nums(&g["spans"][0]),
            vec![b.start_s, b.start_s + b.duration_s]
        );
    }
    let limits = v["limits"].as_array().unwrap();
    assert_eq!(limits[2]["axis"], "Y");
    assert_eq!(
        (limits[2]["min"].as_f64(), limits[2]["max"].as_f64()),
        (Some(40.0), Some(800.0))
    );
    // Unlimited: null.
    assert!(limits[0]["min"].is_null());
}

#[test]
fn a_check_json_in_the_folder_is_served_unknown_kinds_included() {
    let dir = folder("check-json");
    std::fs::write(
        dir.join("check.json"),
        r#"{"clean": false, "violations": [{"kind": "collision", "links": ["eye", "mandrel"], "block": 3, "line": 9, "time_s": 1.0}]}"#,
    )
    .unwrap();
    let server = start(&dir);
    let v = server.json("/api/violations");
    assert_eq!(v["source"], "check.json");
    let c = &v["violations"][0];
    assert_eq!(c["kind"], "collision");
    assert_eq!(c["links"][1], "mandrel");
    // Block 3 (1-based) runs from 0.5 s to 1.75 s.
    assert_eq!(nums(&c["spans"][0]), vec![0.5, 1.75]);
    std::fs::write(dir.join("check.json"), "{}").unwrap();
    let e = ViewServer::bind(&dir, &ViewOptions::default(), Page::none())
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("check.json") && e.contains("violations"), "{e}");
}

#[test]
fn the_eye_trajectory_is_the_payout_point_at_every_block_end() {
    let dir = folder("eye");
    let server = start(&dir);
    let eye = server.json("/api/eye");
    let points = eye["points"].as_array().unwrap();
    // The start and five block ends.
    assert_eq!(points.len(), 6);
    assert_eq!(eye["ends"], 6);
    let m = machine();
    let payout = m.roles.payout;
    let mut q = vec![0.0, 0.0, 250.0, 0.0];
    for (k, p) in points.iter().enumerate() {
        if k > 0 {
            let t = targets()[k - 1];
            q = vec![t[0].to_radians(), t[1], t[2], t[3].to_radians()];
        }
        let want = m.key_points(&q)[payout];
        let got = nums(p);
        for (a, b) in got.iter().zip([want.x, want.y, want.z]) {
            assert!((a - b).abs() < 1e-9, "point {k}: {got:?} {want}");
        }
    }
}

/// Writes one circuit's tables (the spindle turning 400 deg over `x` in
/// 0..100 mm, the path turning 3 rad) and `blocks.csv` ending the layer at
/// the program's last A (800 deg): two circuits from A = 0.
fn band_tables(dir: &Path) {
    let mut eye = String::from("x,z,r,v,alpha,l,eye_z,eye_r,eye_v,lambda,u,margin\n");
    let mut axes = String::from("x,A,X,Y,B\n");
    for i in 0..=100 {
        let x = f64::from(i);
        eye.push_str(&format!(
            "{x},{},{},{},0,0,0,0,0,0,0,0\n",
            2.0 * x,
            50.0 + x / 10.0,
            0.03 * x
        ));
        axes.push_str(&format!("{x},{},0,250,0\n", 4.0 * x));
    }
    std::fs::write(dir.join("eye.csv"), eye).unwrap();
    std::fs::write(dir.join("axes.csv"), axes).unwrap();
    std::fs::write(
        dir.join("blocks.csv"),
        "block,t,A,X,Y,B,layer,t_star,mu\n1,1.75,400,0,250,0,1,1,1\n2,2.75,800,20,300,0,1,1,1\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("summary.json"),
        r#"{"job": "vessel.toml", "machine_shipped": "winder-4axis", "program_file": "program.mpf", "circuits": 2}"#,
    )
    .unwrap();
}

#[test]
fn the_band_is_laid_circuit_by_circuit_as_the_spindle_turns() {
    let dir = folder("band");
    band_tables(&dir);
    let server = start(&dir);
    let band = server.json("/api/band");
    assert_eq!(band["link"], machine().roles.mandrel);
    let points = band["points"].as_array().unwrap();
    // Two circuits of 101 points sharing their join.
    assert_eq!(points.len(), 201);
    let on = |k: usize, x: f64, turn: f64| {
        let (z, r, v) = (2.0 * x, 50.0 + x / 10.0, 0.03 * x + turn);
        let p = nums(&points[k]);
        for (a, b) in p.iter().zip([r * v.cos(), r * v.sin(), z]) {
            assert!((a - b).abs() < 1e-9, "point {k}: {p:?}");
        }
    };
    on(0, 0.0, 0.0);
    on(100, 100.0, 0.0);
    // The second circuit starts where the first ends, turned on by 3 rad.
    on(150, 50.0, 3.0);
    on(200, 100.0, 3.0);
    // A = 0 at the start: the first point; A = 400 at 1.75 s: the first
    // circuit; A = 720 at 2.5 s: x = 80 of the second; A = 800: all.
    for (t, laid) in [(0.0, 1), (1.75, 101), (2.5, 181), (4.5, 201)] {
        let s = server.json(&format!("/api/sample?t={t}"));
        assert_eq!(s["laid"], laid, "t {t}");
    }
    let tl = server.json("/api/timeline?samples=3");
    assert_eq!(tl["samples"][2]["laid"], 201);
    // Without the tables: no band, and no `laid` in the samples.
    let plain = start(&folder("band-none"));
    assert_eq!(get(&plain, "/api/band").0, 404);
    assert!(plain.json("/api/sample?t=1").get("laid").is_none());
    // `/api/overlays` says which overlays exist: the page asks only for those.
    let has = |s: &Probe| {
        let o = s.json("/api/overlays");
        [&o["violations"], &o["eye"], &o["band"]].map(|v| v.as_bool().unwrap())
    };
    assert_eq!(has(&server), [true, true, true]);
    assert_eq!(has(&plain), [true, true, false]);
}

/// One answer read from a kept connection: status and body (by its
/// `Content-Length`), the connection left open.
fn read_answer(s: &mut TcpStream) -> std::io::Result<(u16, Vec<u8>)> {
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        s.read_exact(&mut byte)?;
        head.push(byte[0]);
    }
    let head = String::from_utf8(head).unwrap();
    let status = head.split_whitespace().nth(1).unwrap().parse().unwrap();
    let length: usize = head
        .lines()
        .find_map(|l| l.strip_prefix("Content-Length: "))
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    let mut body = vec![0; length];
    s.read_exact(&mut body)?;
    Ok((status, body))
}

#[test]
fn connections_kept_open_do_not_hold_back_new_ones() {
    let dir = folder("kept");
    let server = start(&dir);
    let ask = |s: &mut TcpStream, url: &str| {
        s.write_all(
            format!("GET {url} HTTP/1.1\r\nHost: localhost\r\nConnection: keep-alive\r\n\r\n")
                .as_bytes(),
        )
        .unwrap();
    };
    // A browser keeps its connections open between requests...
    let mut kept = Vec::new();
    for _ in 0..3 {
        let mut s = TcpStream::connect(server.addr).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
        ask(&mut s, "/api/result");
        assert_eq!(read_answer(&mut s).unwrap().0, 200);
        kept.push(s);
    }
    // ...and opens several more at once for a page's parallel fetches,
    // kept open too, after closing one (a thread of the server comes free):
    // every one is answered, round after round.
    for round in 0..5 {
        drop(kept.remove(0));
        std::thread::sleep(Duration::from_millis(50));
        let mut fresh: Vec<TcpStream> = (0..6)
            .map(|_| TcpStream::connect(server.addr).unwrap())
            .collect();
        for s in &mut fresh {
            s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
            ask(s, "/api/blocks");
        }
        for (i, s) in fresh.iter_mut().enumerate() {
            match read_answer(s) {
                Ok((status, _)) => assert_eq!(status, 200, "round {round}, connection {i}"),
                Err(e) => panic!(
                    "round {round}: connection {i} of 6 opened at once, {} kept open: \
                     no answer in 10 s ({e})",
                    kept.len()
                ),
            }
        }
        kept.extend(fresh);
    }
    // The kept ones still answer their next request.
    for s in &mut kept {
        ask(s, "/api/machine");
        let (status, body) = read_answer(s).unwrap();
        assert_eq!(status, 200);
        assert!(body.starts_with(b"{"));
    }
}
