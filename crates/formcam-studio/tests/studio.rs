//! The studio over HTTP on a port the system chooses, asked with raw
//! requests: its folder's jobs listed, a job run through the server into a
//! run folder whose view answers the same summary as `formcam wind` of the
//! saved job, a cancelled run and a run replaced by the next leaving no
//! folder, a bad value answered at its field, and nothing read or written
//! outside the folder.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use formcam_studio::{Studio, StudioServer};
use formcam_view::Page;
use serde_json::{Value, json};

/// The repository's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// An example job, its machine file beside it in `dir`.
fn add_job(dir: &Path, example: &str, name: &str) {
    let text = std::fs::read_to_string(root().join("examples").join(example)).unwrap();
    let text = text.replace("../machines/", "");
    std::fs::write(dir.join(name), text).unwrap();
}

/// A fresh folder `<name>/dir` holding the program example as `vessel.toml`
/// and the layered one as `slow.toml`, with their machine files; the
/// folder, and `<name>` around it (which must stay as it was).
fn folder(name: &str) -> (PathBuf, PathBuf) {
    let outer = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&outer);
    let dir = outer.join("dir");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(
        root().join("machines/winder-4axis.toml"),
        dir.join("winder-4axis.toml"),
    )
    .unwrap();
    add_job(&dir, "vessel-program-840d.toml", "vessel.toml");
    add_job(&dir, "vessel-layers-840d.toml", "slow.toml");
    (outer, dir)
}

/// The page the studios of these tests serve.
const PAGE: &str = "<!doctype html><title>studio</title>";

/// A studio on `dir` answering on a background thread.
fn start(dir: &Path) -> SocketAddr {
    let page = Page::from_files(vec![("index.html".into(), PAGE.as_bytes().to_vec())]);
    let server = StudioServer::bind(Studio::open(dir, page).unwrap(), 0).unwrap();
    let addr = server.addr();
    let _ = server.spawn();
    addr
}

/// Sends `request` as it is; the status and the body.
fn raw(addr: SocketAddr, request: &[u8]) -> (u16, Vec<u8>) {
    let a = formcam_testkit::send(addr, request, Duration::from_secs(120));
    (a.status, a.body)
}

fn get(addr: SocketAddr, url: &str) -> (u16, Value) {
    let a = formcam_testkit::get(addr, url);
    (a.status, a.json())
}

fn post(addr: SocketAddr, url: &str, body: &Value) -> (u16, Value) {
    let a = formcam_testkit::post_json(addr, url, &body.to_string());
    (a.status, a.json())
}

/// The job `file` as the page loads it, ready to post back.
fn edit(addr: SocketAddr, file: &str) -> Value {
    let (status, job) = get(addr, &format!("/api/studio/job?file={file}"));
    assert_eq!(status, 200, "{job}");
    json!({"file": file, "kind": job["kind"], "text": job["text"], "values": job["values"]})
}

/// Polls the status until the run `name` has ended; its status.
fn ended(addr: SocketAddr, name: &str) -> Value {
    let t0 = Instant::now();
    loop {
        let (_, s) = get(addr, "/api/studio/status");
        if s["run"] == name && s["state"] != "running" {
            return s;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(600),
            "the run never ended: {s}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// The folders under `dir/runs`, by name.
fn run_folders(dir: &Path) -> Vec<String> {
    let Ok(read) = std::fs::read_dir(dir.join("runs")) else {
        return Vec::new();
    };
    let mut names: Vec<String> = read
        .filter_map(Result::ok)
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Every path under `dir`, relative, sorted.
fn tree(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap().filter_map(Result::ok) {
            let p = e.path();
            out.push(p.strip_prefix(dir).unwrap().to_path_buf());
            if p.is_dir() {
                todo.push(p);
            }
        }
    }
    out.sort();
    out
}

/// A summary without what names the job's file or times the computer.
fn values(summary: &Value) -> Value {
    let mut s = summary.clone();
    if let Some(m) = s.as_object_mut() {
        m.remove("job");
    }
    s
}

#[test]
fn the_folder_s_jobs_and_kinds_are_listed() {
    let (_, dir) = folder("studio-list");
    let addr = start(&dir);
    let (status, kind) = get(addr, "/api/kind");
    assert_eq!((status, kind), (200, json!({"kind": "studio"})));
    let (status, studio) = get(addr, "/api/studio");
    assert_eq!(status, 200);
    assert_eq!(
        studio["jobs"],
        json!([
            {"file": "slow.toml", "kind": "winding"},
            {"file": "vessel.toml", "kind": "winding"},
        ]),
        "the machine file is no job"
    );
    let kinds: Vec<&str> = studio["kinds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["winding", "dressing", "correction", "scenario"]);
    assert!(studio["kinds"][0]["schema"].is_object());
    assert_eq!(studio["job"], Value::Null);
    let (status, job) = get(addr, "/api/studio/job?file=vessel.toml");
    assert_eq!(status, 200);
    assert_eq!(job["values"]["mandrel"]["radius"], json!(100.0));
}

#[test]
fn a_run_through_the_server_is_the_saved_job_s_wind() {
    let (outer, dir) = folder("studio-run");
    let before = tree(&outer);
    let addr = start(&dir);
    let mut body = edit(addr, "vessel.toml");
    // An edit: the run is of the text posted, not of the file.
    body["values"]["winding"]["band_width"] = json!(12.0);
    let (status, started) = post(addr, "/api/studio/run", &body);
    assert_eq!(status, 200, "{started}");
    let name = started["run"].as_str().unwrap().to_string();
    assert!(name.ends_with("-vessel"), "{name}");
    let status = ended(addr, &name);
    assert_eq!(status["state"], "done", "{status}");
    assert!(status["line"].as_str().unwrap().contains("checked"));
    assert_eq!(run_folders(&dir), std::slice::from_ref(&name));

    // The run's view answers its summary; the run folder keeps the text.
    let (code, summary) = get(addr, &format!("/runs/{name}/api/result"));
    assert_eq!(code, 200, "{summary}");
    // The page at `/` and at the run's folder, which its relative URLs need.
    for url in ["/".to_string(), format!("/runs/{name}/")] {
        let (code, page) = raw(
            addr,
            format!("GET {url} HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n")
                .as_bytes(),
        );
        assert_eq!((code, page.as_slice()), (200, PAGE.as_bytes()), "{url}");
    }
    let (code, _) = raw(
        addr,
        format!("GET /runs/{name} HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n")
            .as_bytes(),
    );
    assert_eq!(code, 308);
    let (code, kind) = get(addr, &format!("/runs/{name}/api/kind"));
    assert_eq!((code, kind["kind"].as_str()), (200, Some("winding")));
    let ran = std::fs::read_to_string(dir.join("runs").join(&name).join("job.toml")).unwrap();
    assert!(ran.contains("band_width = 12"), "{ran}");

    // The same text saved and wound as `formcam wind` does.
    let (code, saved) = post(addr, "/api/studio/save", &body);
    assert_eq!(code, 200, "{saved}");
    let job = dir.join("vessel.toml");
    assert_eq!(std::fs::read_to_string(&job).unwrap(), ran);
    let wound = formcam_run::wind(&job, &dir.join("out"), formcam_program::Stage::Program).unwrap();
    let wound: Value = serde_json::from_slice(&wound.file("summary.json").unwrap().bytes).unwrap();
    assert_eq!(values(&summary), values(&wound));
    assert!(summary["program_file"].is_string(), "{summary}");

    // The runs list has it, with its job and kind.
    let (_, runs) = get(addr, "/api/studio/runs");
    assert_eq!(runs[0]["name"], name.as_str());
    assert_eq!(runs[0]["job"], "vessel.toml");
    assert_eq!(runs[0]["kind"], "winding");
    assert_eq!(runs[0]["state"], "done");

    // Only the run folder, the saved job and its `.bak` are new, all in DIR.
    let new: Vec<PathBuf> = tree(&outer)
        .into_iter()
        .filter(|p| !before.contains(p))
        .collect();
    assert!(new.iter().all(|p| p.starts_with("dir")), "{new:?}");
    assert!(
        new.iter()
            .all(|p| p.starts_with(Path::new("dir").join("runs"))
                || p.to_string_lossy().ends_with(".bak")),
        "{new:?}"
    );
}

#[test]
fn a_cancelled_run_leaves_no_folder() {
    let (_, dir) = folder("studio-cancel");
    let addr = start(&dir);
    let body = edit(addr, "slow.toml");
    let (status, started) = post(addr, "/api/studio/run", &body);
    assert_eq!(status, 200, "{started}");
    let name = started["run"].as_str().unwrap().to_string();
    // Cancelled once it has reported a phase: stopped inside the run.
    let t0 = Instant::now();
    loop {
        let (_, s) = get(addr, "/api/studio/status");
        assert_eq!(s["state"], "running", "{s}");
        if s["phase"].is_string() {
            break;
        }
        assert!(t0.elapsed() < Duration::from_secs(60), "{s}");
        std::thread::sleep(Duration::from_millis(5));
    }
    let (status, cancelled) = post(addr, "/api/studio/cancel", &json!({}));
    assert_eq!(status, 200);
    assert_eq!(cancelled["run"], name.as_str());
    let status = ended(addr, &name);
    assert_eq!(status["state"], "cancelled", "{status}");
    assert!(run_folders(&dir).is_empty(), "{:?}", run_folders(&dir));
    let (code, _) = get(addr, &format!("/runs/{name}/api/result"));
    assert_eq!(code, 404);
}

#[test]
fn a_second_run_cancels_the_first() {
    let (_, dir) = folder("studio-second");
    let addr = start(&dir);
    let slow = edit(addr, "slow.toml");
    let (_, first) = post(addr, "/api/studio/run", &slow);
    let first = first["run"].as_str().unwrap().to_string();
    let fast = edit(addr, "vessel.toml");
    let (status, second) = post(addr, "/api/studio/run", &fast);
    assert_eq!(status, 200, "{second}");
    let second = second["run"].as_str().unwrap().to_string();
    assert_ne!(first, second);
    let status = ended(addr, &second);
    assert_eq!(status["state"], "done", "{status}");
    assert_eq!(run_folders(&dir), [second]);
}

#[test]
fn a_bad_value_is_answered_at_its_field_and_nothing_runs() {
    let (_, dir) = folder("studio-bad");
    let addr = start(&dir);
    let mut body = edit(addr, "vessel.toml");
    body["values"]["mandrel"]["radius"] = json!(-5.0);
    let (status, applied) = post(addr, "/api/studio/apply", &body);
    assert_eq!(status, 200);
    assert_eq!(applied["ok"], false);
    assert_eq!(applied["errors"][0]["field"], "mandrel.radius", "{applied}");
    let (status, refused) = post(addr, "/api/studio/run", &body);
    assert_eq!(status, 422);
    assert_eq!(refused["ok"], false);
    assert_eq!(refused["errors"][0]["field"], "mandrel.radius", "{refused}");
    let (_, s) = get(addr, "/api/studio/status");
    assert_eq!(s["state"], "idle");
    let before = std::fs::read(dir.join("vessel.toml")).unwrap();
    let (status, _) = post(addr, "/api/studio/save", &body);
    assert_eq!(status, 422);
    assert_eq!(std::fs::read(dir.join("vessel.toml")).unwrap(), before);
    assert!(run_folders(&dir).is_empty());
}

#[test]
fn paths_out_of_the_folder_and_bad_requests_are_refused() {
    let (outer, dir) = folder("studio-refuse");
    std::fs::write(outer.join("secret.toml"), "[mandrel]\n").unwrap();
    let before = tree(&outer);
    let addr = start(&dir);
    for url in [
        "/api/studio/job?file=../secret.toml",
        "/api/studio/job?file=..%2Fsecret.toml",
        "/api/studio/job?file=runs%2Fx.toml",
        "/api/studio/job?file=winder-4axis",
    ] {
        let (status, body) = get(addr, url);
        assert_eq!(status, 400, "{url}: {body}");
        assert!(body["error"].is_string(), "{url}: {body}");
    }
    for url in ["/runs/../secret.toml", "/runs/%2e%2e/x", "/files/../x"] {
        let (status, _) = get(addr, url);
        assert_eq!(status, 400, "{url}");
    }
    let (status, _) = get(addr, "/runs/20200101-000000-none/api/result");
    assert_eq!(status, 404);
    let mut body = edit(addr, "vessel.toml");
    body["file"] = json!("../evil.toml");
    for action in ["save", "run", "apply"] {
        let (status, answer) = post(addr, &format!("/api/studio/{action}"), &body);
        assert_eq!(status, 400, "{action}: {answer}");
    }
    // No JSON, a body too long, a method not served.
    let (status, _) = raw(
        addr,
        b"POST /api/studio/apply HTTP/1.1\r\nHost: localhost\r\nContent-Type: text/plain\r\nContent-Length: 2\r\n\r\n{}",
    );
    assert_eq!(status, 415);
    let (status, _) = raw(
        addr,
        format!(
            "POST /api/studio/apply HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
            2 * formcam_studio::MAX_BODY_BYTES
        )
        .as_bytes(),
    );
    assert_eq!(status, 413);
    let (status, _) = raw(
        addr,
        b"DELETE /api/studio HTTP/1.1\r\nHost: localhost\r\n\r\n",
    );
    assert_eq!(status, 405);
    // A page of another site whose name points here (DNS rebinding) saves nothing.
    let mut save = body.clone();
    save["file"] = json!("vessel.toml");
    let rebound = format!(
        "POST /api/studio/save HTTP/1.1\r\nHost: evil.example:80\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n{save}",
        save.to_string().len()
    );
    let (status, _) = raw(addr, rebound.as_bytes());
    assert_eq!(status, 403);
    let (status, _) = post(addr, "/api/studio/apply", &json!({"nonsense": 1}));
    assert_eq!(status, 400);
    assert_eq!(tree(&outer), before, "nothing written");
}

#[test]
fn a_job_file_opens_its_folder_with_the_job_chosen() {
    let (outer, dir) = folder("studio-file");
    let addr = start(&dir.join("vessel.toml"));
    let (_, studio) = get(addr, "/api/studio");
    assert_eq!(studio["job"], "vessel.toml");
    assert_eq!(studio["jobs"].as_array().map(Vec::len), Some(2));
    std::fs::write(outer.join("notes.txt"), "no job").unwrap();
    for bad in [
        outer.join("notes.txt"),
        outer.join("missing"),
        dir.join("winder-4axis.toml"),
    ] {
        let err = Studio::open(&bad, Page::none()).unwrap_err();
        assert!(
            err.to_string().contains(&bad.display().to_string()),
            "{err}"
        );
    }
}

#[test]
fn examples_started_from_the_page_run_and_open_as_their_kind_of_result() {
    let (outer, dir) = folder("studio-examples");
    let before = tree(&outer);
    let addr = start(&dir);
    for (example, kind) in [
        ("dress-ballscrew-nut", "dressing"),
        ("correct-mould", "correction"),
    ] {
        let (status, job) = post(addr, "/api/studio/example", &json!({"name": example}));
        assert_eq!(status, 200, "{job}");
        assert_eq!(job["kind"], kind);
        let file = job["file"].as_str().unwrap();
        let body =
            json!({"file": file, "kind": kind, "text": job["text"], "values": job["values"]});
        let (status, started) = post(addr, "/api/studio/run", &body);
        assert_eq!(status, 200, "{started}");
        let name = started["run"].as_str().unwrap().to_string();
        let status = ended(addr, &name);
        assert_eq!(status["state"], "done", "{status}");
        let (code, shown) = get(addr, &format!("/runs/{name}/api/kind"));
        assert_eq!((code, shown["kind"].as_str()), (200, Some(kind)), "{shown}");
        let (code, _) = get(addr, &format!("/runs/{name}/api/{kind}"));
        assert_eq!(code, 200, "{name}");
    }
    let (_, studio) = get(addr, "/api/studio");
    let jobs: Vec<&str> = studio["jobs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["file"].as_str().unwrap())
        .collect();
    assert!(jobs.contains(&"dress-ballscrew-nut.toml"), "{jobs:?}");
    assert!(jobs.contains(&"correct-mould.toml"), "{jobs:?}");
    let new: Vec<PathBuf> = tree(&outer)
        .into_iter()
        .filter(|p| !before.contains(p))
        .collect();
    assert!(new.iter().all(|p| p.starts_with("dir")), "{new:?}");
}
