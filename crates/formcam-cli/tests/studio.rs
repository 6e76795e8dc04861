//! `formcam studio [JOB_OR_FOLDER]`: the address printed first and the
//! studio answering there; a path that is neither a folder nor a job file
//! fails with exit code 2 and one line naming it. What the studio answers
//! is tested through the library in `formcam-studio/tests`.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Stdio};

use common::{formcam, repo, s, scratch, stderr};

/// `formcam studio` running, ended when dropped.
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

fn studio(path: &std::path::Path) -> Running {
    let mut child = formcam()
        .args(["studio", s(path), "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    Running {
        child,
        url: first.trim_end().to_string(),
    }
}

/// A GET of `path`: the status line and the body.
fn get(url: &str, path: &str) -> (String, String) {
    let addr = url.trim_start_matches("http://").trim_end_matches('/');
    let mut c = TcpStream::connect(addr).unwrap();
    c.write_all(
        format!("GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n").as_bytes(),
    )
    .unwrap();
    let mut out = Vec::new();
    c.read_to_end(&mut out).unwrap();
    let text = String::from_utf8_lossy(&out).into_owned();
    let (head, body) = text.split_once("\r\n\r\n").unwrap_or((&text, ""));
    (
        head.lines().next().unwrap_or("").to_string(),
        body.to_string(),
    )
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
    let v: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(v["job"], "nut.toml");
    assert_eq!(v["jobs"][0]["kind"], "dressing");
    let (status, html) = get(&st.url, "/");
    assert!(status.contains(" 200 "), "{status}");
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
