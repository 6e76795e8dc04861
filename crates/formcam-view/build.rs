//! Embeds the built page (`viewer/dist/`, made by `npm ci && npm run build`
//! in `viewer/`) into the crate: a table of its files, each by
//! `include_bytes!`, written to `OUT_DIR/page.rs`. Without a build the table
//! is `None` and `formcam view` says how to make one.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::{env, fs, io};

fn main() -> io::Result<()> {
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default());
    let dist = manifest.join("../../viewer/dist");
    let mut files = Vec::new();
    let index = dist.join("index.html");
    // Each build of the page writes a new `index.html` (it names the hashed
    // scripts); while there is none, cargo looks again at every build.
    println!("cargo:rerun-if-changed={}", index.display());
    if index.is_file() {
        collect(&dist, &dist, &mut files)?;
        files.sort();
        println!("cargo:rerun-if-changed={}", dist.display());
    }
    let mut table = String::new();
    if files.is_empty() {
        table.push_str("/// The built page's files: none (not built).\npub static PAGE: Option<&[(&str, &[u8])]> = None;\n");
    } else {
        table.push_str("/// The built page's files: (path under `dist/`, bytes).\npub static PAGE: Option<&[(&str, &[u8])]> = Some(&[\n");
        for (name, path) in &files {
            let _ = writeln!(
                table,
                "    ({name:?}, include_bytes!({:?})),",
                path.display().to_string()
            );
        }
        table.push_str("]);\n");
    }
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap_or_default());
    fs::write(out.join("page.rs"), table)
}

/// Every regular file under `dir`, named by its path below `root` with `/`.
fn collect(root: &Path, dir: &Path, files: &mut Vec<(String, PathBuf)>) -> io::Result<()> {
    for entry in fs::read_dir(dir)? {
        let entry = entry?;
        let path = entry.path();
        let kind = entry.file_type()?;
        if kind.is_dir() {
            collect(root, &path, files)?;
        } else if kind.is_file() {
            let rel = path.strip_prefix(root).unwrap_or(&path);
            let name = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect::<Vec<_>>()
                .join("/");
            files.push((name, fs::canonicalize(&path)?));
        }
    }
    Ok(())
}
