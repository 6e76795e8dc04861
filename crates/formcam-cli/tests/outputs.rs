//! No input is ever overwritten, and an output folder holds one whole run:
//! the reproducers of the command line (every output checked against every
//! file the run read, after `..` and symlinks), stale files gone, foreign
//! files refused. The writer's failure points, concurrent runs and planted
//! symlinks are tested in formcam-files.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use common::{example, examples, formcam, machines, names_in, ok, s, scratch, stderr};

/// `formcam ARGS` run in `dir`.
fn run_in(dir: &Path, args: &[&str]) -> Output {
    formcam().current_dir(dir).args(args).output().unwrap()
}

/// The run failed with one line naming the clash between `output` and
/// `input`; returns the line.
fn refused(name: &str, o: &Output, output: &str, input: &str) -> String {
    let err = stderr(o).trim_end().to_string();
    assert_eq!(o.status.code(), Some(2), "{name}: {err}");
    assert_eq!(err.lines().count(), 1, "{name}: {err}");
    assert!(
        err.contains("overwrite the input") || err.contains("holds the input"),
        "{name}: {err}"
    );
    assert!(err.contains(output) && err.contains(input), "{name}: {err}");
    err
}

fn read(p: impl AsRef<Path>) -> String {
    std::fs::read_to_string(p).unwrap()
}

#[test]
fn machine_fk_never_overwrites_its_machine_or_axes() {
    let dir = scratch("fk");
    let machine = read(machines().join("winder-4axis.toml"));
    std::fs::write(dir.join("m.toml"), &machine).unwrap();
    let axes = "A,X,Y,B\n0,0,100,0\n90,10,120,5\n";
    std::fs::write(dir.join("a.csv"), axes).unwrap();
    for out in ["a.csv", "m.toml", "./x/../a.csv"] {
        let o = run_in(
            &dir,
            &["machine", "fk", "m.toml", "--axes", "a.csv", "-o", out],
        );
        let input = if out.ends_with("m.toml") {
            "m.toml"
        } else {
            "a.csv"
        };
        refused(out, &o, out, input);
    }
    assert_eq!(read(dir.join("a.csv")), axes);
    assert_eq!(read(dir.join("m.toml")), machine);
    assert!(!dir.join("x").exists());
    let o = run_in(
        &dir,
        &["machine", "fk", "m.toml", "--axes", "a.csv", "-o", "p.csv"],
    );
    ok("fk", &o);
    assert_eq!(names_in(&dir), vec!["a.csv", "m.toml", "p.csv"]);
}

/// A plate measured 0.1 mm high (`c.csv`-like CMM text) and its program.
fn plate() -> (String, String) {
    let mut cmm = String::from("section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act\n");
    for (j, y) in [0.0, 50.0, 100.0].iter().enumerate() {
        for (i, x) in [0.0, 40.0, 80.0, 120.0].iter().enumerate() {
            cmm.push_str(&format!("S{j},{i},{x},{y},0,{x},{y},0.1\n"));
        }
    }
    let prog = "%\nO100\nG21 G90\nG0 X10. Y10. Z20.\nG1 Z0. F800.\nX100.\nY90.\nG0 Z20.\nM30\n%\n";
    (cmm, prog.to_string())
}

#[test]
fn correct_never_overwrites_its_program_or_measurements() {
    let dir = scratch("correct");
    let (cmm, prog) = plate();
    std::fs::write(dir.join("cmm.csv"), &cmm).unwrap();
    std::fs::write(dir.join("mould.nc"), &prog).unwrap();
    // `..` over a folder that does not exist.
    let o = run_in(
        &dir,
        &[
            "correct",
            "--measurements",
            "cmm.csv",
            "--program",
            "mould.nc",
            "-o",
            "./x/../mould.nc",
        ],
    );
    refused("dotdot", &o, "mould.nc", "program");
    assert!(!dir.join("x").exists());
    // A side file of the run on the program.
    std::fs::write(dir.join("c.deviations.svg"), &prog).unwrap();
    let o = run_in(
        &dir,
        &[
            "correct",
            "--measurements",
            "cmm.csv",
            "--program",
            "c.deviations.svg",
            "--dialect",
            "iso",
            "-o",
            "c.nc",
        ],
    );
    refused("side program", &o, "c.deviations.svg", "c.deviations.svg");
    assert_eq!(read(dir.join("c.deviations.svg")), prog);
    // Its report on the measurements.
    std::fs::write(dir.join("c.report.json"), &cmm).unwrap();
    let o = run_in(
        &dir,
        &[
            "correct",
            "--measurements",
            "c.report.json",
            "--program",
            "mould.nc",
            "-o",
            "c.nc",
        ],
    );
    refused("side report", &o, "c.report.json", "c.report.json");
    assert_eq!(read(dir.join("c.report.json")), cmm);
    assert_eq!(read(dir.join("mould.nc")), prog);
    assert!(!dir.join("c.nc").exists());
    // A report that cannot be written stops the run before the program is
    // in place, and this run's side files go with it.
    std::fs::write(dir.join("blocker"), "a file").unwrap();
    let o = run_in(
        &dir,
        &[
            "correct",
            "--measurements",
            "cmm.csv",
            "--program",
            "mould.nc",
            "-o",
            "d.nc",
            "--report",
            "blocker/report.json",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("blocker"), "{}", stderr(&o));
    for f in ["d.nc", "d.deviations.svg", "d.displacement.svg"] {
        assert!(!dir.join(f).exists(), "{f}");
    }
    assert!(names_in(&dir).iter().all(|n| !n.starts_with('.')));
}

/// Runs `formcam ARGS JOB -o out` in `dir`.
fn into_out(dir: &Path, args: &[&str], job: &str) -> Output {
    let mut a = args.to_vec();
    a.extend([job, "-o", "out"]);
    run_in(dir, &a)
}

#[test]
fn fixed_names_inside_the_folder_never_land_on_inputs() {
    let dir = scratch("fixed");
    let out = dir.join("out");
    std::fs::create_dir(&out).unwrap();
    // A job named summary.json inside OUT.
    let job = example("vessel-geodesic.toml");
    std::fs::write(out.join("summary.json"), &job).unwrap();
    let o = into_out(&dir, &["wind", "path"], "out/summary.json");
    refused("job", &o, "summary.json", "summary.json");
    assert_eq!(read(out.join("summary.json")), job);
    std::fs::remove_file(out.join("summary.json")).unwrap();
    // A meridian out/path.csv.
    let meridian = read(examples().join("waist-meridian.csv"));
    std::fs::write(out.join("path.csv"), &meridian).unwrap();
    let waist = read(examples().join("profile-waist.toml"))
        .replace("\"waist-meridian.csv\"", "\"out/path.csv\"");
    std::fs::write(dir.join("waist.toml"), waist).unwrap();
    let o = into_out(&dir, &["wind", "path"], "waist.toml");
    refused("meridian", &o, "path.csv", "path.csv");
    assert_eq!(read(out.join("path.csv")), meridian);
    std::fs::remove_file(out.join("path.csv")).unwrap();
    // An eye curve out/eye.csv.
    let curve = read(examples().join("eye-curve.csv"));
    std::fs::write(out.join("eye.csv"), &curve).unwrap();
    let eye = example("vessel-eye-curve.toml").replace("\"eye-curve.csv\"", "\"out/eye.csv\"");
    std::fs::write(dir.join("eye.toml"), eye).unwrap();
    let o = into_out(&dir, &["wind", "eye"], "eye.toml");
    refused("eye curve", &o, "eye.csv", "eye.csv");
    assert_eq!(read(out.join("eye.csv")), curve);
    std::fs::remove_file(out.join("eye.csv")).unwrap();
    // A dressing job's initial contour out/profile.csv.
    let mut worn = String::from("z,x\n");
    for i in 0..=600 {
        let z = -3.0 + 0.01 * f64::from(i);
        worn.push_str(&format!("{z},{}\n", 1.95 + 0.02 * (3.0 * z).cos()));
    }
    std::fs::write(out.join("profile.csv"), &worn).unwrap();
    let dress = read(examples().join("dress-ballscrew-nut.toml"))
        .replace("depth = 0.05", "initial_contour = \"out/profile.csv\"");
    std::fs::write(dir.join("dress.toml"), dress).unwrap();
    let o = into_out(&dir, &["dress"], "dress.toml");
    refused("contour", &o, "profile.csv", "profile.csv");
    assert_eq!(read(out.join("profile.csv")), worn);
}

#[test]
fn a_folder_holds_one_whole_run_and_nothing_foreign_is_lost() {
    let dir = scratch("whole");
    std::fs::write(dir.join("job.toml"), example("vessel-program-840d.toml")).unwrap();
    let out: PathBuf = dir.join("out");
    ok("wind", &into_out(&dir, &["wind"], "job.toml"));
    let first = names_in(&out);
    for f in ["program.mpf", "blocks.csv", "axes.csv"] {
        assert!(first.iter().any(|n| n == f), "{f}: {first:?}");
    }
    ok("wind path", &into_out(&dir, &["wind", "path"], "job.toml"));
    assert_eq!(
        names_in(&out),
        vec![
            ".formcam-run",
            "job.toml",
            "path.csv",
            "path.svg",
            "summary.json"
        ]
    );
    // Nothing left beside the folder: no claim, no temporary folder.
    assert_eq!(names_in(&dir), vec!["job.toml", "out"]);
    // A file formcam did not write: refused, named, kept.
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let o = into_out(&dir, &["wind", "path"], "job.toml");
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        err.contains("notes.txt") && err.contains("formcam did not write"),
        "{err}"
    );
    assert_eq!(read(out.join("notes.txt")), "mine");
    assert!(out.join("summary.json").exists());
    // An output folder that is a file.
    let o = run_in(
        &dir,
        &["wind", "path", "job.toml", "-o", s(&dir.join("job.toml"))],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}
