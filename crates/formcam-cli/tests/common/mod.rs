//! What the CLI's test files share: running the built binary on a job.

#![allow(dead_code, clippy::unwrap_used)]

use std::path::Path;
use std::process::{Command, Output};

/// Runs `formcam wind JOB -o OUT` and checks that it succeeds (the failure
/// shows formcam's stderr).
pub fn wind_ok(job: &Path, out: &Path) -> Output {
    let st = Command::new(env!("CARGO_BIN_EXE_formcam"))
        .arg("wind")
        .arg(job)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}: {}",
        job.display(),
        String::from_utf8_lossy(&st.stderr)
    );
    st
}
