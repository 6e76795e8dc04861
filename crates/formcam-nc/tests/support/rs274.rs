//! LinuxCNC's interpreter `rs274` (Debian's `linuxcnc-uspace`), which tests
//! of the LinuxCNC programs formcam writes run where it is installed. Shared
//! by the tests that run it (`formcam-sim`, `formcam-cli`), included by path
//! (`#[path = ".../formcam-nc/tests/support/rs274.rs"] mod rs274;`); no test
//! target of its own.

use std::path::Path;
use std::process::{Command, Output, Stdio};

/// Whether `rs274` runs here. Without it the caller's test is skipped (said
/// on stderr), unless `FORMCAM_REQUIRE_RS274=1` (set by `.ci/run`), when
/// this fails.
pub fn rs274_present() -> bool {
    let found = Command::new("rs274")
        .arg("-h")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok();
    if !found {
        assert!(
            std::env::var("FORMCAM_REQUIRE_RS274").as_deref() != Ok("1"),
            "rs274 (Debian package linuxcnc-uspace) is not on the PATH and \
             FORMCAM_REQUIRE_RS274=1"
        );
        eprintln!("skipped: rs274 (linuxcnc-uspace) is not installed");
    }
    found
}

/// One `rs274` at a time in a test binary: two started at once fail, often,
/// without a word (19 of 40 runs of formcam-sim's two rs274 tests).
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Runs `rs274 -g` in `dir` on the LinuxCNC program `text`, on a winder's
/// configuration (axes X, Y, Z, A, B; mm and degrees; A a wrapped rotary
/// axis): how it ended, and the canonical calls it printed (empty when it
/// printed none). Runs of one test binary take turns.
pub fn run_rs274(dir: &Path, text: &str) -> (Output, String) {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        dir.join("winder.ini"),
        "[RS274NGC]\nPARAMETER_FILE = winder.var\n\n[TRAJ]\nCOORDINATES = XYZAB\n\
         LINEAR_UNITS = mm\nANGULAR_UNITS = degree\n\n[AXIS_A]\nWRAPPED_ROTARY = 1\n",
    )
    .unwrap();
    std::fs::write(dir.join("winder.var"), "").unwrap();
    std::fs::write(dir.join("winder.tbl"), "T1 P1 D0 Z0 ;\n").unwrap();
    std::fs::write(dir.join("program.ngc"), text).unwrap();
    let run = Command::new("rs274")
        .current_dir(dir)
        .args([
            "-i",
            "winder.ini",
            "-t",
            "winder.tbl",
            "-v",
            "winder.var",
            "-g",
        ])
        .args(["program.ngc", "canon.txt"])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let printed = std::fs::read_to_string(dir.join("canon.txt")).unwrap_or_default();
    (run, printed)
}
