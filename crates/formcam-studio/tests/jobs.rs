//! The studio's job library on real job files: the bundled examples started
//! into a folder and checked, a bad value at its field in the words
//! `formcam` prints, saving with its `.bak`, an edited example keeping its
//! comments.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::fs;
use std::path::{Path, PathBuf};

use formcam_studio::{
    FieldError, JobKind, NameProblem, StudioError, apply_values, backup_path, check_job, examples,
    save_job, save_job_with, start_example, values_of,
};
use serde_json::{Value, json};

/// A fresh folder for one test.
fn fresh(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("formcam-studio-{tag}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).expect("temp folder");
    dir
}

fn read(path: &Path) -> String {
    fs::read_to_string(path).expect("readable")
}

#[test]
fn every_example_started_into_a_folder_checks_clean() {
    let dir = fresh("examples");
    for ex in examples() {
        let file = start_example(&dir, ex.name).expect("started");
        assert_eq!(file, format!("{}.toml", ex.name));
        let text = read(&dir.join(&file));
        assert_eq!(JobKind::of_text(&text), Some(ex.kind), "{}", ex.name);
        assert_eq!(
            check_job(ex.kind, &dir, &file, &text),
            Vec::<FieldError>::new(),
            "{}",
            ex.name
        );
        for (input, _) in ex.inputs {
            assert!(dir.join(input).is_file(), "{}: {input}", ex.name);
        }
    }
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn the_list_holds_every_example_job_of_the_four_kinds() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut on_disk: Vec<String> = fs::read_dir(&folder)
        .expect("examples folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .collect();
    on_disk.sort();
    let listed: Vec<String> = examples().iter().map(|e| e.name.to_string()).collect();
    assert_eq!(
        listed, on_disk,
        "add every examples/*.toml to formcam-studio's examples.rs"
    );
    for ex in examples() {
        let bundled = fs::read_to_string(folder.join(format!("{}.toml", ex.name))).expect("job");
        assert_eq!(ex.text, bundled, "{}", ex.name);
    }
}

#[test]
fn an_example_never_replaces_a_different_file() {
    let dir = fresh("clash");
    let file = start_example(&dir, "correct-mould").expect("started");
    // Started again: the same files are left as they are.
    assert_eq!(start_example(&dir, "correct-mould").expect("again"), file);
    let cmm = dir.join("correct/cmm.csv");
    fs::write(&cmm, "section,point\n").expect("edited");
    fs::remove_file(dir.join(&file)).expect("job removed");
    match start_example(&dir, "correct-mould") {
        Err(e @ StudioError::ExampleClash { .. }) => {
            let message = e.to_string();
            assert!(message.starts_with(&cmm.display().to_string()), "{message}");
        }
        other => panic!("expected a clash, got {other:?}"),
    }
    assert_eq!(read(&cmm), "section,point\n");
    assert!(!dir.join(&file).exists(), "nothing written on a clash");
    let _ = fs::remove_dir_all(&dir);
}

/// The example `name` started into `dir`, its values edited by `edit`, the
/// new text.
fn edited(dir: &Path, name: &str, edit: impl FnOnce(&mut Value)) -> (String, String) {
    let file = start_example(dir, name).expect("started");
    let base = read(&dir.join(&file));
    let mut values = values_of(&base).expect("values");
    edit(&mut values);
    (file, apply_values(&base, &values).expect("applied"))
}

/// What `formcam` prints for `text` as the file `file` in `dir` (after
/// `formcam: error: `), through the command line's library path.
fn formcam_says(dir: &Path, file: &str, text: &str) -> String {
    let path = dir.join(file);
    fs::write(&path, text).expect("written");
    formcam_run::run_job_file(&path, &dir.join("out"))
        .expect_err("refused")
        .to_string()
}

/// One bad value of an example: the field the studio places it at, and
/// the message is what `formcam` prints.
fn bad_value(tag: &str, name: &str, field: &str, edit: impl FnOnce(&mut Value)) -> FieldError {
    let dir = fresh(tag);
    let kind = examples()
        .iter()
        .find(|e| e.name == name)
        .expect("bundled")
        .kind;
    let (file, text) = edited(&dir, name, edit);
    let found = check_job(kind, &dir, &file, &text);
    assert_eq!(found.len(), 1, "{found:?}");
    let e = found.into_iter().next().expect("one");
    assert_eq!(e.field.as_deref(), Some(field), "{e:?}");
    assert_eq!(e.message, formcam_says(&dir, &file, &text));
    assert!(
        e.message
            .starts_with(&dir.join(&file).display().to_string())
    );
    if let Some(line) = e.line {
        assert!(line >= 1 && line <= text.lines().count(), "{e:?}");
    }
    let _ = fs::remove_dir_all(&dir);
    e
}

#[test]
fn winding_a_value_out_of_range_at_its_field() {
    let e = bad_value("w-range", "vessel-geodesic", "winding.band_width", |v| {
        v["winding"]["band_width"] = json!(-10)
    });
    assert!(
        e.message.contains("winding.band_width = -10.0 at ")
            && e.message.ends_with("out of range; allowed > 0 mm"),
        "{}",
        e.message
    );
    assert!(e.line.is_some());
}

#[test]
fn winding_a_layer_named_from_one_in_the_file_and_from_zero_in_the_form() {
    let e = bad_value("w-layer", "vessel-layers-840d", "layer[1].overlap", |v| {
        v["layer"][1]["overlap"] = json!(1.5)
    });
    assert!(
        e.message.contains("layer[2].overlap = 1.5"),
        "{}",
        e.message
    );
}

#[test]
fn winding_a_mandrel_the_reader_refuses_after_its_description() {
    let e = bad_value("w-geom", "vessel-geodesic", "mandrel.polar_opening", |v| {
        v["mandrel"]["polar_opening"] = json!(500)
    });
    assert!(e.message.contains("mandrel.polar_opening"), "{}", e.message);
}

#[test]
fn winding_a_word_not_in_the_list() {
    let e = bad_value("w-word", "vessel-program-840d", "post.dialect", |v| {
        v["post"]["dialect"] = json!("heidenhain")
    });
    assert!(e.message.contains("not allowed; allowed:"), "{}", e.message);
}

#[test]
fn dressing_a_value_out_of_range_at_its_field() {
    let e = bad_value(
        "d-range",
        "dress-ballscrew-nut",
        "wheel.contact_angle_deg",
        |v| v["wheel"]["contact_angle_deg"] = json!(95),
    );
    assert!(
        e.message.ends_with("out of range; allowed (0, 90) deg"),
        "{}",
        e.message
    );
}

#[test]
fn dressing_a_wheel_its_profile_refuses() {
    let e = bad_value("d-profile", "dress-ballscrew-nut", "wheel.r1", |v| {
        v["wheel"]["r1"] = json!(1.5)
    });
    assert!(e.message.contains("wheel.r1 = 1.5 mm"), "{}", e.message);
}

#[test]
fn correction_a_setting_out_of_range_at_its_field() {
    let e = bad_value("c-gain", "correct-mould", "correct.gain", |v| {
        v["correct"]["gain"] = json!(0)
    });
    assert!(
        e.message.ends_with("correct.gain = 0: allowed (0, 2]"),
        "{}",
        e.message
    );
}

#[test]
fn correction_a_missing_measurement_file_at_its_field() {
    let e = bad_value("c-file", "correct-mould", "correct.measurements", |v| {
        v["correct"]["measurements"] = json!("correct/cmm-2.csv")
    });
    assert!(
        e.message.contains("correct.measurements: cannot read"),
        "{}",
        e.message
    );
}

#[test]
fn scenario_a_value_out_of_range_at_its_field() {
    let e = bad_value("s-range", "correct-panel-loop", "surface.length", |v| {
        v["surface"]["length"] = json!(-400)
    });
    assert!(
        e.message.ends_with("surface.length = -400: must be > 0 mm"),
        "{}",
        e.message
    );
}

#[test]
fn a_text_that_is_no_toml_is_placed_at_its_line() {
    let dir = fresh("syntax");
    let text = "[mandrel]\nkind = \"vessel\"\nradius = \n";
    let found = check_job(JobKind::Winding, &dir, "a.toml", text);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].field, None);
    assert_eq!(found[0].line, Some(3));
    assert_eq!(found[0].message, formcam_says(&dir, "a.toml", text));
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn saving_keeps_the_previous_version_as_bak() {
    let dir = fresh("save");
    let path = save_job(&dir, "job.toml", "[mandrel]\nkind = \"vessel\"\n").expect("saved");
    assert_eq!(path, dir.join("job.toml"));
    assert!(
        !backup_path(&path).exists(),
        "nothing to back up the first time"
    );
    save_job(&dir, "job.toml", "[mandrel]\nkind = \"cone\"\n").expect("saved again");
    assert_eq!(read(&path), "[mandrel]\nkind = \"cone\"\n");
    assert_eq!(
        read(&dir.join("job.toml.bak")),
        "[mandrel]\nkind = \"vessel\"\n"
    );
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn a_failed_write_leaves_the_job_as_it_was() {
    let dir = fresh("failed");
    let path = save_job(&dir, "job.toml", "old = 1\n").expect("saved");
    // Every temporary name the stamped writer would try is taken.
    for k in 0..64 {
        fs::write(dir.join(format!(".job.toml.formcam-new-t-{k}")), "").expect("taken");
    }
    let writer = formcam_files::Writer::default().stamped("t");
    let e = save_job_with(&writer, &dir, "job.toml", "new = 2\n").expect_err("no free name");
    assert!(matches!(e, StudioError::Write(_)), "{e:?}");
    assert_eq!(read(&path), "old = 1\n");
    assert_eq!(read(&backup_path(&path)), "old = 1\n");
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn names_outside_the_folder_are_refused_and_nothing_written() {
    let dir = fresh("names");
    let inner = dir.join("inner");
    fs::create_dir_all(inner.join("runs")).expect("folders");
    for (name, why) in [
        ("../escape.toml", NameProblem::NotPlain),
        ("runs/job.toml", NameProblem::NotPlain),
        ("job.txt", NameProblem::NotToml),
        (".job.toml", NameProblem::Hidden),
    ] {
        match save_job(&inner, name, "x = 1\n") {
            Err(StudioError::JobName { reason, .. }) => assert_eq!(reason, why, "{name}"),
            other => panic!("{name}: {other:?}"),
        }
    }
    assert!(!dir.join("escape.toml").exists());
    assert!(!inner.join("runs/job.toml").exists());
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn an_edited_example_keeps_its_comments() {
    let dir = fresh("golden");
    let (_, text) = edited(&dir, "correct-mould", |v| {
        let c = &mut v["correct"];
        c["gain"] = json!(0.8);
        c["interpolation"] = json!("bilinear");
        c.as_object_mut().expect("table").remove("noise_mm");
        c["max_deviation_mm"] = json!(4);
    });
    insta::assert_snapshot!(text);
    let _ = fs::remove_dir_all(&dir);
}
