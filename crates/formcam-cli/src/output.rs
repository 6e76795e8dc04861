//! Atomic output: every file is written to a temporary name in the output
//! folder and renamed into place, so a failed run leaves no half-written file.

use std::fs;
use std::io::Write;
use std::path::Path;

use crate::CliError;

/// Writes the files of a run into `dir` (see [`write_all`]).
pub fn write_run(dir: &Path, run: &formcam_run::RunOutput) -> Result<(), CliError> {
    let files: Vec<(&str, Vec<u8>)> = run
        .files
        .iter()
        .map(|f| (f.name.as_str(), f.bytes.clone()))
        .collect();
    write_all(dir, &files)
}

/// Prints the run's warnings, writes its files into `dir` and returns its line.
pub fn emit(dir: &Path, run: formcam_run::RunOutput) -> Result<String, CliError> {
    for w in &run.warnings {
        eprintln!("formcam: warning: {w}");
    }
    write_run(dir, &run)?;
    Ok(run.line)
}

/// The temporary name of the file `name` (which may lie in a subfolder,
/// `layer-01/path.csv`) inside `dir`, beside its target.
fn temp_name(dir: &Path, name: &str) -> std::path::PathBuf {
    let target = dir.join(name);
    let file = target
        .file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_default();
    target.with_file_name(format!(".{file}.tmp"))
}

/// Writes all `files` (name, contents) into `dir`, creating it (and the
/// subfolders the names give) if needed. Nothing is renamed into place until
/// every temporary file is complete.
pub fn write_all<S: AsRef<str>>(dir: &Path, files: &[(S, Vec<u8>)]) -> Result<(), CliError> {
    fs::create_dir_all(dir).map_err(|source| CliError::OutputFolder {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut temps = Vec::new();
    for (name, data) in files {
        let name = name.as_ref();
        let tmp = temp_name(dir, name);
        let res = tmp
            .parent()
            .map_or(Ok(()), fs::create_dir_all)
            .and_then(|()| fs::File::create(&tmp))
            .and_then(|mut f| {
                f.write_all(data)?;
                f.sync_all()
            });
        if let Err(source) = res {
            for t in &temps {
                let _ = fs::remove_file(t);
            }
            let _ = fs::remove_file(&tmp);
            return Err(CliError::Output {
                path: dir.join(name),
                source,
            });
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
            return Err(CliError::FolderInTheWay { path: target });
        }
    }
    for (k, ((name, _), tmp)) in files.iter().zip(&temps).enumerate() {
        let name = name.as_ref();
        if let Err(source) = fs::rename(tmp, dir.join(name)) {
            for t in &temps[k..] {
                let _ = fs::remove_file(t);
            }
            return Err(CliError::Output {
                path: dir.join(name),
                source,
            });
        }
    }
    Ok(())
}
