//! The repository's own files, as tests find them.

use std::path::{Path, PathBuf};

/// The repository's root (the workspace's folder).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The bundled example `name` (`examples/<name>`).
pub fn example_path(name: &str) -> PathBuf {
    repo_root().join("examples").join(name)
}

/// The shipped machine file `name` (`machines/<name>`).
pub fn machine_path(name: &str) -> PathBuf {
    repo_root().join("machines").join(name)
}

/// The text of the shipped machine file `name`; a missing file panics with
/// its path (the tests' own fixture).
pub fn machine_text(name: &str) -> String {
    let p = machine_path(name);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}
