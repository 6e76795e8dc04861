//! The documentation in `docs/` against what the binary writes: every CSV
//! column and every key of `summary.json` and the correction reports that
//! the winding and correction examples produce is named (in backticks) on
//! the matching page, and no file of the repository points outside it.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

use common::{demo, repo as root};

/// Which docs page documents a job's outputs; `None` for jobs another page
/// and its own test cover (dressing).
fn page_of(job: &Path) -> Option<&'static str> {
    if job.extension().is_some_and(|e| e == "wind") {
        return Some("winding.md");
    }
    let table: toml::Table = fs::read_to_string(job).unwrap().parse().unwrap();
    if table.contains_key("wheel") {
        None
    } else if table.contains_key("correct") || table.contains_key("warp") {
        Some("correction.md")
    } else {
        Some("winding.md")
    }
}

/// Every file under `dir`, recursively.
fn files_under(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files_under(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// Every object key in `v`, at any depth.
fn keys(v: &serde_json::Value, out: &mut BTreeSet<String>) {
    match v {
        serde_json::Value::Object(map) => {
            for (k, x) in map {
                out.insert(k.clone());
                keys(x, out);
            }
        }
        serde_json::Value::Array(items) => items.iter().for_each(|x| keys(x, out)),
        _ => {}
    }
}

/// The names a run wrote: CSV header columns and JSON keys, each with the
/// file it came from.
fn names_written(dir: &Path) -> Vec<(String, PathBuf)> {
    let mut files = Vec::new();
    files_under(dir, &mut files);
    let mut out = Vec::new();
    for f in files {
        match f.extension().and_then(|e| e.to_str()) {
            Some("csv") => {
                let text = fs::read_to_string(&f).unwrap();
                let header = text.lines().next().unwrap_or_default();
                for col in header.split(',') {
                    out.push((col.trim().to_string(), f.clone()));
                }
            }
            Some("json") => {
                let v: serde_json::Value =
                    serde_json::from_str(&fs::read_to_string(&f).unwrap()).unwrap();
                let mut ks = BTreeSet::new();
                keys(&v, &mut ks);
                out.extend(ks.into_iter().map(|k| (k, f.clone())));
            }
            _ => {}
        }
    }
    out
}

#[test]
fn every_column_and_key_the_examples_write_is_documented() {
    let out = std::env::temp_dir().join(format!("formcam-docs-{}", std::process::id()));
    let _ = fs::remove_dir_all(&out);
    let examples = root().join("examples");
    let st = demo(&examples, &out);
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let mut missing = Vec::new();
    let mut checked = 0;
    let mut pages_used = BTreeSet::new();
    for e in fs::read_dir(&examples).unwrap() {
        let job = e.unwrap().path();
        if !job.extension().is_some_and(|x| x == "toml" || x == "wind") {
            continue;
        }
        let Some(page) = page_of(&job) else { continue };
        pages_used.insert(page);
        let doc = fs::read_to_string(root().join("docs").join(page))
            .unwrap_or_else(|e| panic!("docs/{page}: {e}"));
        let dir = out.join(job.file_stem().unwrap());
        let written = names_written(&dir);
        assert!(
            !written.is_empty(),
            "{}: wrote no CSV or JSON",
            dir.display()
        );
        for (name, file) in written {
            checked += 1;
            if !doc.contains(&format!("`{name}`")) {
                missing.push(format!(
                    "docs/{page}: `{name}` (written in {})",
                    file.strip_prefix(&out).unwrap_or(&file).display()
                ));
            }
        }
    }
    let _ = fs::remove_dir_all(&out);
    missing.sort();
    missing.dedup();
    assert_eq!(
        pages_used.into_iter().collect::<Vec<_>>(),
        ["correction.md", "winding.md"]
    );
    assert!(checked > 200, "only {checked} names checked");
    assert!(
        missing.is_empty(),
        "not documented:\n{}",
        missing.join("\n")
    );
}

#[test]
fn no_file_points_outside_the_repository() {
    // Built from parts so that this file does not name them itself.
    let banned = [
        ["..", "/shared"].concat(),
        ["shared", "/spec"].concat(),
        ["seed", " 00"].concat(),
    ];
    let r = root();
    let mut files = vec![r.join("README.md")];
    for dir in ["docs", "crates", "examples", "machines"] {
        files_under(&r.join(dir), &mut files);
    }
    let mut found = Vec::new();
    for f in &files {
        let text = String::from_utf8_lossy(&fs::read(f).unwrap()).into_owned();
        for b in &banned {
            if text.contains(b.as_str()) {
                found.push(format!(
                    "{}: {b}",
                    f.strip_prefix(&r).unwrap_or(f).display()
                ));
            }
        }
    }
    assert!(files.len() > 50, "only {} files read", files.len());
    assert!(found.is_empty(), "{}", found.join("\n"));
}
