//! What formcam-run's test files share: the bundled examples and machines,
//! scratch folders, the files of a run. Each test file is its own process,
//! so scratch folders named by the process id do not meet.

#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_correct::{CorrectionJob, Settings};
use formcam_run::RunOutput;

/// The bundled example jobs.
pub fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// The shipped machine files.
pub fn machines() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../machines")
}

/// A fresh, empty folder for one test.
pub fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("formcam-run-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A result file of a run as text.
pub fn text(run: &RunOutput, name: &str) -> String {
    let f = run.file(name).unwrap_or_else(|| panic!("no {name}"));
    String::from_utf8(f.bytes.clone()).unwrap()
}

/// JSON bytes.
pub fn json(bytes: &[u8]) -> serde_json::Value {
    serde_json::from_slice(bytes).unwrap()
}

/// A run's `summary.json`.
pub fn summary(run: &RunOutput) -> serde_json::Value {
    json(&run.file("summary.json").unwrap().bytes)
}

/// A CMM report of a flat plate z = 0 in 3 sections x `xs`, `dz(x)` high.
pub fn plate(dir: &Path, xs: &[f64], dz: impl Fn(f64) -> f64) -> PathBuf {
    let mut cmm = String::from("section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act\n");
    for (j, y) in [0.0, 50.0, 100.0].iter().enumerate() {
        for (i, x) in xs.iter().enumerate() {
            cmm.push_str(&format!("S{j},{i},{x},{y},0,{x},{y},{}\n", dz(*x)));
        }
    }
    let m = dir.join("cmm.csv");
    std::fs::write(&m, cmm).unwrap();
    m
}

/// A correction job of `measurements` and `program`.
pub fn job(measurements: PathBuf, program: PathBuf, settings: Settings) -> CorrectionJob {
    CorrectionJob {
        measurements,
        program,
        settings,
    }
}

/// An ISO program over the plate with comments, modal words, an arc and a
/// rapid move.
pub fn plate_program(dir: &Path) -> PathBuf {
    let prog = "%\nO100 (PLATE)\nN10 G21 G90 G17\nN20 T1 M6 (TOOL)\nN30 G0 X10. Y10. Z20.\n\
                N40 G1 Z0. F800.\nN50 X100.\nN60 G3 X100. Y30. I0. J10.\nN70 G1 X10. ; back\n\
                N80 G0 Z20.\nM30\n%\n";
    let p = dir.join("plate.nc");
    std::fs::write(&p, prog).unwrap();
    p
}
