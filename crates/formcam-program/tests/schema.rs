//! The winding job's description against its reader, its examples and its
//! docs: a field's default written out reads as the field left out, every
//! example validates, and `docs/winding.md` lists the fields the description
//! writes.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_program::{WINDING_JOB, WindJob, plan_program, write_program};
use formcam_schema::{Default, Repeat, replace_marked, validate};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A small single-layer program: every table but `[[layer]]`.
const SINGLE: &str = "[mandrel]\nkind = \"cylinder\"\nradius = 60.0\nlength = 800.0\n\n\
[winding]\nwinding_angle_deg = 50.0\nband_width = 8.0\nband_thickness = 0.3\ndwell_min_deg = 360.0\n\n\
[eye]\nmode = \"axis-parallel\"\nradius = 250.0\nl_max = 1000.0\n\n\
[machine]\nname = \"winder-2axis\"\n\n[motion]\n\n[post]\n\n[checks]\n";

/// The same as a multi-layer job: a skip, then the helical layer.
const LAYERED: &str = "[mandrel]\nkind = \"cylinder\"\nradius = 60.0\nlength = 800.0\n\n\
[[layer]]\nkind = \"skip\"\nmandrel_rotation_deg = 90.0\n\n\
[[layer]]\nwinding_angle_deg = 50.0\nband_width = 8.0\nband_thickness = 0.3\ndwell_min_deg = 360.0\n\n\
[eye]\nmode = \"axis-parallel\"\nradius = 250.0\nl_max = 1000.0\n\n\
[machine]\nname = \"winder-2axis\"\n";

/// The program a job writes (the whole result of a winding job).
fn program(text: &str) -> String {
    let job = WindJob::from_toml(text, &root().join("examples")).unwrap();
    let wound = plan_program(&job).unwrap();
    let mut out = Vec::new();
    write_program(&wound, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

/// `text` with `line` added at the end of the last table headed `header`.
fn with_line(text: &str, header: &str, line: &str) -> String {
    let at = text.rfind(header).expect("the table is in the job");
    let end = text[at..].find("\n\n").map_or(text.len(), |e| at + e);
    format!("{}\n{line}{}", &text[..end], &text[end..])
}

#[test]
fn a_default_written_out_reads_as_the_field_left_out() {
    let mut checked = Vec::new();
    for (base, repeat) in [(SINGLE, Repeat::Single), (LAYERED, Repeat::Array)] {
        let want = program(base);
        for table in WINDING_JOB.tables.iter().filter(|t| t.repeat == repeat) {
            let header = format!("{}\n", table.header());
            if !base.contains(&header) {
                continue;
            }
            for f in table.fields {
                let Default::Value(v) = f.default else {
                    continue;
                };
                let at = base.rfind(&header).unwrap_or(0);
                let section = &base[at..base[at..].find("\n\n").map_or(base.len(), |e| at + e)];
                if section.contains(&format!("\n{} =", f.name)) {
                    continue;
                }
                let job = with_line(base, &header, &format!("{} = {}", f.name, v.toml()));
                validate(&WINDING_JOB, &job).unwrap();
                assert_eq!(
                    program(&job),
                    want,
                    "{}.{} = {} differs from leaving it out",
                    table.name,
                    f.name,
                    v.toml()
                );
                checked.push(format!("{}.{}", table.name, f.name));
            }
        }
    }
    for f in [
        "winding.samples",
        "eye.clearance",
        "motion.tau_s",
        "post.dialect",
        "layer.kind",
    ] {
        assert!(
            checked.iter().any(|c| c == f),
            "{f} not checked: {checked:?}"
        );
    }
}

#[test]
fn every_winding_example_validates() {
    let mut n = 0;
    for e in std::fs::read_dir(root().join("examples")).unwrap() {
        let path = e.unwrap().path();
        if path.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let table: toml::Table = text.parse().unwrap();
        if !table.contains_key("mandrel") {
            continue;
        }
        validate(&WINDING_JOB, &text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        n += 1;
    }
    assert!(n >= 10, "only {n} winding examples");
}

#[test]
fn the_docs_list_the_described_fields() {
    let path = root().join("docs/winding.md");
    let page = std::fs::read_to_string(&path).unwrap();
    let want = replace_marked(&page, &WINDING_JOB).unwrap();
    if want != page {
        if std::env::var_os("FORMCAM_BLESS").is_some() {
            std::fs::write(&path, want).unwrap();
        } else {
            panic!(
                "docs/winding.md: the field tables differ from the winding job's description \
                 (formcam_program::WINDING_JOB); regenerate them with \
                 `FORMCAM_BLESS=1 cargo test -p formcam-program --test schema`"
            );
        }
    }
}
