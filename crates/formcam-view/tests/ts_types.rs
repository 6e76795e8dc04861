//! The page's types of the JSON the view sends are ts-rs's declarations of
//! the Rust types: `viewer/src/generated/` holds exactly the files
//! [`formcam_view::typescript`] makes (`FORMCAM_BLESS=1` writes them
//! again, and removes any other), and every type a file imports is one of
//! them. `npm run build` (tsc) checks the page against them.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use formcam_view::{TS_INDEX, typescript};

fn generated() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../viewer/src/generated")
}

/// The files in `dir` by name (none when it does not exist).
fn read(dir: &Path) -> BTreeMap<String, String> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return BTreeMap::new();
    };
    entries
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().into_string().unwrap();
            (name, std::fs::read_to_string(e.path()).unwrap())
        })
        .collect()
}

#[test]
fn the_page_has_the_generated_types() {
    let want: BTreeMap<String, String> = typescript()
        .unwrap()
        .into_iter()
        .map(|f| (f.name, f.text))
        .collect();
    let dir = generated();
    let have = read(&dir);
    if have == want {
        return;
    }
    if std::env::var_os("FORMCAM_BLESS").is_some() {
        std::fs::create_dir_all(&dir).unwrap();
        for name in have.keys().filter(|n| !want.contains_key(*n)) {
            std::fs::remove_file(dir.join(name)).unwrap();
        }
        for (name, text) in &want {
            if have.get(name) != Some(text) {
                std::fs::write(dir.join(name), text).unwrap();
            }
        }
    } else {
        let differ: BTreeSet<&str> = want
            .keys()
            .chain(have.keys())
            .filter(|n| have.get(*n) != want.get(*n))
            .map(String::as_str)
            .collect();
        panic!(
            "viewer/src/generated/: {} differ from formcam-view's types; regenerate them with \
             `FORMCAM_BLESS=1 cargo test -p formcam-view --test ts_types`",
            differ.into_iter().collect::<Vec<_>>().join(", ")
        );
    }
}

#[test]
fn every_imported_type_is_generated() {
    let files = typescript().unwrap();
    let names: Vec<&str> = files.iter().map(|f| f.name.as_str()).collect();
    assert!(names.contains(&TS_INDEX));
    for f in &files {
        for line in f.text.lines().filter(|l| l.starts_with("import ")) {
            let from = line
                .split(" from ")
                .nth(1)
                .and_then(|s| {
                    s.trim_end_matches(';')
                        .trim_matches(['"', '\''])
                        .strip_prefix("./")
                })
                .unwrap_or_else(|| panic!("{}: {line}", f.name));
            let file = format!("{from}.ts");
            assert!(names.contains(&file.as_str()), "{}: {line}", f.name);
        }
        // Numbers on the wire are JSON numbers: no `bigint`.
        assert!(!f.text.contains("bigint"), "{}", f.name);
    }
}
