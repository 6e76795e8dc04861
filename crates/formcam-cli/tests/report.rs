//! `formcam report OUT -o report.html`: one self-contained file (the page's
//! script and style inlined, every answer the page asks for inlined; no
//! `src` or `href` to anything outside it), written alone, never inside the
//! result folder; a folder that is no result fails with exit 2 naming it.
//! The report opened in a browser from `file://`: `tests/view.rs`.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::{Path, PathBuf};

use common::{formcam, names_in, repo, s, scratch, stderr, wind_ok};

/// A winding result on the 4-axis winder, in `dir/out`.
fn result(dir: &Path) -> PathBuf {
    let out = dir.join("out");
    wind_ok(&repo().join("examples/vessel-program-840d.toml"), &out);
    out
}

/// The markup outside `<script>` and `<style>` elements.
fn markup(html: &str) -> String {
    let mut out = String::new();
    let mut rest = html;
    loop {
        let next = ["<script", "<style"]
            .iter()
            .filter_map(|t| rest.find(t).map(|i| (i, *t)))
            .min();
        let Some((at, tag)) = next else {
            out.push_str(rest);
            return out;
        };
        let open_end = at + rest[at..].find('>').unwrap() + 1;
        out.push_str(&rest[..open_end]);
        let close = if tag == "<script" {
            "</script>"
        } else {
            "</style>"
        };
        rest = &rest[open_end + rest[open_end..].find(close).unwrap()..];
    }
}

#[test]
fn report_writes_one_self_contained_file_of_a_winding_result() {
    if !formcam_view::Page::is_embedded() {
        let dir = scratch("report-unbuilt");
        let o = formcam()
            .args(["report", s(&dir), "-o", s(&dir.join("r.html"))])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2));
        assert!(
            stderr(&o).contains("npm ci && npm run build"),
            "{}",
            stderr(&o)
        );
        return;
    }
    let dir = scratch("report");
    let out = result(&dir);
    let before = names_in(&out);
    let shared = dir.join("shared");
    std::fs::create_dir_all(&shared).unwrap();
    let file = shared.join("report.html");
    let o = formcam()
        .args(["report", s(&out), "-o", s(&file)])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let line = String::from_utf8(o.stdout).unwrap();
    assert_eq!(line.lines().count(), 1, "{line}");
    assert!(
        line.starts_with(&format!("formcam report: {} (winding result, ", s(&file))),
        "{line}"
    );
    // One file written, the result untouched.
    assert_eq!(names_in(&shared), vec!["report.html".to_string()]);
    assert_eq!(names_in(&out), before);
    let html = std::fs::read_to_string(&file).unwrap();
    assert!(html.contains("<title>formcam report: "), "no report title");
    // No element names anything outside the file.
    let tags = markup(&html);
    assert!(!tags.contains("src="), "{tags}");
    for href in tags.split("href=\"").skip(1) {
        assert!(href.starts_with("data:"), "href to {href}");
    }
    assert!(
        !tags.contains("/assets/") && !tags.contains("http:"),
        "{tags}"
    );
    // The script and the style are in it, and every answer the page asks for.
    assert!(html.contains("<script type=\"module\">"));
    assert!(html.contains("<style>"));
    for url in [
        "/api/kind",
        "/api/result",
        "/api/machine",
        "/api/mandrel",
        "/api/blocks",
        "/api/program",
        "/api/violations",
        "/api/eye",
        "/api/band",
        "/api/plots",
        "/api/timeline?samples=2",
        "report:samples",
    ] {
        assert!(
            html.contains(&format!("data-formcam-url=\"{url}\"")),
            "{url} not inlined"
        );
    }
    // Written again over itself: still one file.
    let again = formcam()
        .args(["report", s(&out), "-o", s(&file)])
        .output()
        .unwrap();
    assert!(again.status.success(), "{}", stderr(&again));
    assert_eq!(names_in(&shared), vec!["report.html".to_string()]);
}

#[test]
fn report_refuses_a_folder_that_is_no_result_and_an_output_inside_the_result() {
    let dir = scratch("report-refused");
    let missing = dir.join("missing");
    let o = formcam()
        .args(["report", s(&missing), "-o", s(&dir.join("r.html"))])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(o.stdout.is_empty());
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    if !formcam_view::Page::is_embedded() {
        assert!(e.contains("npm ci && npm run build"), "{e}");
        return;
    }
    assert!(e.contains(s(&missing)), "{e}");
    assert!(!dir.join("r.html").exists());
    // A folder that holds no result.
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let o = formcam()
        .args(["report", s(&empty), "-o", s(&dir.join("r.html"))])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains(s(&empty)), "{}", stderr(&o));
    // Inside the result folder: over a file the result owns, or beside them.
    let out = result(&dir);
    let summary = std::fs::read(out.join("summary.json")).unwrap();
    let before = names_in(&out);
    for target in [out.join("summary.json"), out.join("report.html")] {
        let o = formcam()
            .args(["report", s(&out), "-o", s(&target)])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{}", s(&target));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(
            e.contains(s(&target)) && e.contains("inside the result folder"),
            "{e}"
        );
    }
    assert_eq!(std::fs::read(out.join("summary.json")).unwrap(), summary);
    assert_eq!(names_in(&out), before);
}
