//! `formcam demo` on folders of its own: the errors of a folder without
//! jobs, and a correction job whose result would land on its own input.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::process::Output;

use common::{demo, scratch};

/// The one line of stderr, checked to be one line.
fn error_line(o: &Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    err.trim_end().to_string()
}

#[test]
fn a_folder_without_jobs_or_no_folder_is_named() {
    let dir = scratch("empty");
    std::fs::write(dir.join("notes.txt"), "not a job").unwrap();
    let o = demo(&dir, &dir.join("out"));
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        error_line(&o),
        format!(
            "formcam: error: {}: no *.toml or *.wind jobs found",
            dir.display()
        )
    );
    let missing = dir.join("missing");
    let o = demo(&missing, &dir.join("out"));
    assert_eq!(o.status.code(), Some(2));
    let line = error_line(&o);
    assert!(
        line.starts_with(&format!(
            "formcam: error: {}: cannot list the examples: ",
            missing.display()
        )),
        "{line}"
    );
    assert!(!dir.join("out").exists());
}

#[test]
fn a_correction_job_never_overwrites_its_program() {
    let dir = scratch("guard");
    let examples = dir.join("examples");
    let inputs = dir.join("out/plate");
    std::fs::create_dir_all(&examples).unwrap();
    std::fs::create_dir_all(&inputs).unwrap();
    let mut cmm = String::from("section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act\n");
    for (j, y) in [0.0, 50.0, 100.0].iter().enumerate() {
        for (i, x) in [0.0, 40.0, 80.0, 120.0].iter().enumerate() {
            cmm.push_str(&format!("S{j},{i},{x},{y},0,{x},{y},0.1\n"));
        }
    }
    std::fs::write(inputs.join("cmm.csv"), cmm).unwrap();
    // The program is named as the demo's result would be: out/plate/corrected.nc.
    let prog = "%\nO100\nG21 G90\nG0 X10. Y10. Z20.\nG1 Z0. F800.\nX100.\nY90.\nG0 Z20.\nM30\n%\n";
    let program = inputs.join("corrected.nc");
    std::fs::write(&program, prog).unwrap();
    std::fs::write(
        examples.join("plate.toml"),
        "[correct]\nmeasurements = \"../out/plate/cmm.csv\"\nprogram = \"../out/plate/corrected.nc\"\n",
    )
    .unwrap();
    let o = demo(&examples, &dir.join("out"));
    assert_eq!(o.status.code(), Some(2));
    let line = error_line(&o);
    assert!(
        line.contains("-o would overwrite the input program of")
            && line.contains("plate.toml; give another -o"),
        "{line}"
    );
    assert_eq!(std::fs::read_to_string(&program).unwrap(), prog);
    assert!(!inputs.join("report.json").exists());
}
