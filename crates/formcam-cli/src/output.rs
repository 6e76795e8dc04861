//! Atomic output: every file is written to a temporary name in the output
//! folder and renamed into place, so a failed run leaves no half-written file.

use std::fs;
use std::io::Write;
use std::path::Path;

use crate::CliError;

/// Writes all `files` (name, contents) into `dir`, creating it if needed.
/// Nothing is renamed into place until every temporary file is complete.
pub fn write_all<S: AsRef<str>>(dir: &Path, files: &[(S, Vec<u8>)]) -> Result<(), CliError> {
    fs::create_dir_all(dir).map_err(|e| {
        CliError(format!(
            "{}: cannot create the output folder: {e}",
            dir.display()
        ))
    })?;
    let mut temps = Vec::new();
    for (name, data) in files {
        let name = name.as_ref();
        let tmp = dir.join(format!(".{name}.tmp"));
        let res = fs::File::create(&tmp).and_then(|mut f| {
            f.write_all(data)?;
            f.sync_all()
        });
        if let Err(e) = res {
            for t in &temps {
                let _ = fs::remove_file(t);
            }
            let _ = fs::remove_file(&tmp);
            return Err(CliError(format!(
                "{}: cannot write: {e}",
                dir.join(name).display()
            )));
        }
        temps.push(tmp);
    }
    // A target that cannot be replaced (a folder) stops the run before any
    // file is renamed, so the folder never mixes two runs.
    for (name, _) in files {
        let target = dir.join(name.as_ref());
        if target.is_dir() {
            for t in &temps {
                let _ = fs::remove_file(t);
            }
            return Err(CliError(format!(
                "{}: cannot write: a folder is in the way",
                target.display()
            )));
        }
    }
    for (k, ((name, _), tmp)) in files.iter().zip(&temps).enumerate() {
        let name = name.as_ref();
        if let Err(e) = fs::rename(tmp, dir.join(name)) {
            for t in &temps[k..] {
                let _ = fs::remove_file(t);
            }
            return Err(CliError(format!(
                "{}: cannot write: {e}",
                dir.join(name).display()
            )));
        }
    }
    Ok(())
}
