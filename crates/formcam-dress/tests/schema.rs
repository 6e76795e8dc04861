//! The dressing job's description against its reader, its example and its
//! docs: a field's default written out reads as the field left out, every
//! key the reader takes is described, the example validates, and
//! `docs/dressing.md` lists the fields the description writes.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_dress::{DRESS_JOB, DressJob, DresserJob, ProcessJob, WheelJob};
use formcam_schema::{Default, replace_marked, validate};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The example job without the fields it gives at their defaults.
fn base() -> String {
    std::fs::read_to_string(root().join("examples/dress-ballscrew-nut.toml"))
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with("arc_angle_deg"))
        .collect::<Vec<_>>()
        .join("\n")
        + "\n"
}

/// What a job asks for: its dressing specification, in full.
fn spec(text: &str) -> String {
    format!(
        "{:?}",
        DressJob::from_toml(text).unwrap().spec(None).unwrap()
    )
}

#[test]
fn a_default_written_out_reads_as_the_field_left_out() {
    let base = base();
    let want = spec(&base);
    let mut checked = Vec::new();
    for table in DRESS_JOB.tables {
        let header = format!("[{}]\n", table.name);
        for f in table.fields {
            let Default::Value(v) = f.default else {
                continue;
            };
            assert!(!base.contains(&format!("\n{} =", f.name)), "{}", f.name);
            let job = base.replace(&header, &format!("{header}{} = {}\n", f.name, v.toml()));
            validate(&DRESS_JOB, &job).unwrap();
            assert_eq!(spec(&job), want, "{}.{}", table.name, f.name);
            checked.push(format!("{}.{}", table.name, f.name));
        }
    }
    assert_eq!(checked, ["wheel.arc_angle_deg", "process.name"]);
}

#[test]
fn every_key_the_reader_takes_is_described() {
    let [wheel, dresser, process] = DRESS_JOB.tables else {
        panic!("three tables")
    };
    assert_eq!(
        formcam_schema::reader_keys::<WheelJob>(),
        wheel.field_names()
    );
    assert_eq!(
        formcam_schema::reader_keys::<DresserJob>(),
        dresser.field_names()
    );
    assert_eq!(
        formcam_schema::reader_keys::<ProcessJob>(),
        process.field_names()
    );
    let mut tables: Vec<String> = DRESS_JOB.tables.iter().map(|t| t.name.into()).collect();
    tables.sort();
    assert_eq!(formcam_schema::reader_keys::<DressJob>(), tables);
}

#[test]
fn the_example_validates_and_bad_values_name_the_field() {
    let text = std::fs::read_to_string(root().join("examples/dress-ballscrew-nut.toml")).unwrap();
    validate(&DRESS_JOB, &text).unwrap();
    let e = DressJob::from_toml(&text.replace("feed_min = 50.0", "feed_min = 0.05"))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("process.feed_min = 0.05 at ") && e.ends_with("allowed >= 0.1 mm/min"),
        "{e}"
    );
    let e = DressJob::from_toml(&text.replace("[dresser]", "[dreser]"))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("[dreser] at ") && e.ends_with("allowed: [wheel], [dresser], [process]"),
        "{e}"
    );
}

#[test]
fn the_docs_list_the_described_fields() {
    let path = root().join("docs/dressing.md");
    let page = std::fs::read_to_string(&path).unwrap();
    let want = replace_marked(&page, &DRESS_JOB).unwrap();
    if want != page {
        if std::env::var_os("FORMCAM_BLESS").is_some() {
            std::fs::write(&path, want).unwrap();
        } else {
            panic!(
                "docs/dressing.md: the field tables differ from the dressing job's description \
                 (formcam_dress::DRESS_JOB); regenerate them with \
                 `FORMCAM_BLESS=1 cargo test -p formcam-dress --test schema`"
            );
        }
    }
}
