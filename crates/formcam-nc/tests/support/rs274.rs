//! LinuxCNC's interpreter `rs274` (Debian's `linuxcnc-uspace`), which tests
//! of the LinuxCNC programs formcam writes run where it is installed. Shared
//! by the tests that run it (`formcam-sim`, `formcam-cli`), included by path
//! (`#[path = ".../formcam-nc/tests/support/rs274.rs"] mod rs274;`); no test
//! target of its own.

use std::process::{Command, Stdio};

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
