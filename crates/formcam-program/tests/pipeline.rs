//! The winding pipeline through the library: one path for single- and
//! multi-layer jobs, stages that stop it early, machines by shipped name or
//! file, the checks, the post to any writer.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_program::{
    Check, MachineSource, ProgramError, Stage, WindJob, WoundProgram, plan_program, plan_until,
    write_program,
};

/// A helical tube on the shipped 2-axis lathe winder, the eye parallel to
/// the axis (fast: closed-form axes, a geometric eye).
const TUBE: &str = include_str!("jobs/tube.toml");

fn here() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn job(text: &str) -> WindJob {
    WindJob::from_toml(text, &here()).unwrap()
}

/// The same job with its `[winding]` as the one table of `[[layer]]`.
fn as_one_layer(text: &str) -> String {
    text.replace("[winding]", "[[layer]]")
}

fn blocks(w: &WoundProgram) -> Vec<(Vec<f64>, f64, usize)> {
    w.program
        .as_ref()
        .unwrap()
        .blocks
        .iter()
        .map(|b| (b.target.clone(), b.t, b.layer))
        .collect()
}

#[test]
fn a_single_layer_job_is_a_one_layer_job() {
    let single = plan_program(&job(TUBE)).unwrap();
    let layered = plan_program(&job(&as_one_layer(TUBE))).unwrap();
    assert_eq!(single.layers.len(), 1);
    assert_eq!(layered.layers.len(), 1);
    assert_eq!(single.layers[0].label, "layer 1");
    assert_eq!(layered.layers[0].label, "layer 1 (helical)");
    // The same blocks, times and totals: the one path, only the labels differ.
    assert!(!blocks(&single).is_empty());
    assert_eq!(blocks(&single), blocks(&layered));
    let (s, l) = (
        single.program.as_ref().unwrap(),
        layered.program.as_ref().unwrap(),
    );
    assert_eq!(s.time_s, l.time_s);
    assert_eq!(s.time_pairwise_s, l.time_pairwise_s);
    assert_eq!(s.time_global_s, l.time_global_s);
    assert!(s.time_global_s <= s.time_pairwise_s * (1.0 + 1e-9));
}

#[test]
fn stages_stop_the_same_pipeline_early() {
    let j = job(TUBE);
    let path = plan_until(&j, Stage::Path).unwrap();
    let eye = plan_until(&j, Stage::Eye).unwrap();
    let axes = plan_until(&j, Stage::Axes).unwrap();
    let program = plan_until(&j, Stage::Program).unwrap();
    let wound = |w: &WoundProgram| w.layers[0].wound().unwrap().clone();
    assert!(wound(&path).eye.is_none() && wound(&path).track.is_none());
    assert!(path.machine.is_none() && path.program.is_none());
    assert!(wound(&eye).eye.is_some() && wound(&eye).track.is_none());
    assert!(wound(&axes).track.is_some() && axes.program.is_none());
    assert!(axes.machine.is_some());
    assert!(program.program.is_some());
    // Each stage extends the one before it: the same layer, eye and axes.
    assert_eq!(wound(&path).layer, wound(&program).layer);
    assert_eq!(wound(&eye).eye, wound(&program).eye);
    assert_eq!(wound(&axes).track, wound(&program).track);
    // A multi-layer job runs as a whole program only.
    let e = plan_until(&job(&as_one_layer(TUBE)), Stage::Axes).unwrap_err();
    assert!(matches!(e, ProgramError::LayeredStage), "{e}");
    // Stages that need a table name it.
    let eye_table = "[eye]\nmode = \"axis-parallel\"\nradius = 250.0\nclearance = 15.0\n\
                     l_max = 1000.0\nsamples = 2001\n";
    assert!(TUBE.contains(eye_table));
    let no_eye = TUBE.replace(eye_table, "");
    let e = plan_until(&job(&no_eye), Stage::Eye).unwrap_err();
    assert_eq!(e.to_string(), "[eye]: missing table");
    assert!(plan_until(&job(&no_eye), Stage::Path).is_ok());
}

#[test]
fn a_shipped_machine_by_name_is_its_file() {
    let by_name = job(TUBE);
    let by_file = job(&TUBE.replace(
        "name = \"winder-2axis\"",
        "file = \"../../machines/winder-2axis.toml\"",
    ));
    let (a, b) = (
        by_name.machine.as_ref().unwrap(),
        by_file.machine.as_ref().unwrap(),
    );
    assert_eq!(a.source, MachineSource::Shipped("winder-2axis".into()));
    assert_eq!(
        b.source,
        MachineSource::File("../../machines/winder-2axis.toml".into())
    );
    assert_eq!(a.machine, b.machine);
    assert_eq!(a.machine.name, "2-axis lathe winder");
    assert_eq!(
        blocks(&plan_program(&by_name).unwrap()),
        blocks(&plan_program(&by_file).unwrap())
    );
}

#[test]
fn a_failed_check_refuses_the_program_unless_the_job_accepts_it() {
    // A carriage too short for the tube.
    let text = std::fs::read_to_string(here().join("../../machines/winder-2axis.toml"))
        .unwrap()
        .replace("max_mm = 3000.0", "max_mm = 300.0");
    let dir = std::env::temp_dir().join(format!("formcam-program-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("short.toml"), text).unwrap();
    let short = TUBE.replace("name = \"winder-2axis\"", "file = \"short.toml\"");
    let j = WindJob::from_toml(&short, &dir).unwrap();
    match plan_program(&j).unwrap_err() {
        ProgramError::Refused {
            check,
            layer,
            detail,
        } => {
            assert_eq!(check, Check::Limits);
            assert_eq!(layer, "layer 1");
            assert!(detail.contains("axis X beyond its limit"), "{detail}");
        }
        other => panic!("not refused: {other}"),
    }
    let accepted = format!("{short}\n[checks]\nallow = [\"limits\"]\n");
    let j = WindJob::from_toml(&accepted, &dir).unwrap();
    let p = plan_program(&j).unwrap();
    let program = p.program.as_ref().unwrap();
    assert_eq!(program.accepted, [Check::Limits]);
    assert!(program.violated.iter().all(|v| v.check == Check::Limits));
    let mut text = Vec::new();
    write_program(&p, &mut text).unwrap();
    assert!(
        String::from_utf8(text)
            .unwrap()
            .contains("checks accepted as violated ([checks] allow): limits")
    );
}

/// A writer that refuses every byte.
struct Full;

impl std::io::Write for Full {
    fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
        Err(std::io::Error::other("disk full"))
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn the_post_writes_the_program_to_any_writer() {
    let j = job(TUBE).named(Path::new("jobs/tube.toml"));
    let p = plan_program(&j).unwrap();
    let mut text = Vec::new();
    write_program(&p, &mut text).unwrap();
    let text = String::from_utf8(text).unwrap();
    assert!(text.contains("formcam: jobs/tube.toml on 2-axis lathe winder"));
    let moves = text.lines().filter(|l| l.starts_with("G1 ")).count();
    assert!(moves >= p.program.as_ref().unwrap().blocks.len(), "{moves}");
    assert_eq!(p.post.extension(), "gcode");
    let e = write_program(&p, &mut Full).unwrap_err();
    assert!(matches!(e, ProgramError::Write(_)), "{e}");
}

#[test]
fn errors_name_the_field_and_in_multi_layer_jobs_the_layer() {
    // As the job is read (the description's ranges) or as it is planned.
    let error = |text: &str| match WindJob::from_toml(text, &here()) {
        Err(e) => e.to_string(),
        Ok(j) => plan_program(&j).unwrap_err().to_string(),
    };
    let bad = TUBE.replace("band_width = 8.0", "band_width = -8.0");
    let e = error(&bad);
    assert!(e.starts_with("winding.band_width"), "{e}");
    let e = error(&as_one_layer(&bad));
    assert!(e.starts_with("layer[1].band_width"), "{e}");
    let two = format!(
        "{}\n[[layer]]\nmu = 0.0\nwinding_angle_deg = 50.0\nband_width = 8.0\nband_thickness = -0.3\n",
        as_one_layer(TUBE)
    );
    let e = error(&two);
    assert!(e.starts_with("layer[2].band_thickness"), "{e}");
    let skip = format!("{}\n[[layer]]\nkind = \"skip\"\n", as_one_layer(TUBE));
    let e = error(&skip);
    assert!(
        e.starts_with("layer[2].mandrel_rotation_deg: missing")
            && e.contains("(required when kind = skip): a finite number"),
        "{e}"
    );
}
