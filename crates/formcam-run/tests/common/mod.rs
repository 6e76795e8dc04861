//! What formcam-run's test files share: the bundled examples and machines,
//! scratch folders, the files of a run. Each test file is its own process,
//! so scratch folders named by the process id do not meet.

#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

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
