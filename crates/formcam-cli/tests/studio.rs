//! `formcam studio [JOB_OR_FOLDER]`: the address printed first and the
//! studio answering there; a path that is neither a folder nor a job file
//! fails with exit code 2 and one line naming it. What the studio answers
//! is tested through the library in `formcam-studio/tests`.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{Running, formcam, get, repo, s, scratch, serving, stderr};

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
