//! A job saved in the studio's folder: a plain `*.toml` name in the folder
//! (no folders, no `..`, so never under `runs/`), the previous version
//! copied to `NAME.bak` first, then the new text placed atomically (a new
//! file beside it renamed over it), so that a failed write leaves the job
//! as it was.

use std::path::{Component, Path, PathBuf};

use formcam_files::Writer;

use crate::StudioError;
use crate::error::NameProblem;

/// The path of the job file `name` in the folder `dir`, if `name` is a
/// plain job file name: `*.toml` with a name before it, no folder part,
/// no `..`, not hidden, no control characters.
pub fn job_path(dir: &Path, name: &str) -> Result<PathBuf, StudioError> {
    let refuse = |reason| {
        Err(StudioError::JobName {
            name: name.to_string(),
            reason,
        })
    };
    if name.chars().any(char::is_control) {
        return refuse(NameProblem::Control);
    }
    if name.contains(['/', '\\']) {
        return refuse(NameProblem::NotPlain);
    }
    let mut parts = Path::new(name).components();
    let plain = matches!(
        (parts.next(), parts.next()),
        (Some(Component::Normal(part)), None) if part == name
    );
    if name.is_empty() || name == ".toml" {
        return refuse(NameProblem::Empty);
    }
    if !plain {
        return refuse(NameProblem::NotPlain);
    }
    if name.starts_with('.') {
        return refuse(NameProblem::Hidden);
    }
    if !name.ends_with(".toml") {
        return refuse(NameProblem::NotToml);
    }
    Ok(dir.join(name))
}

/// The `.bak` beside a job file: `NAME.bak` (`vessel.toml.bak`).
pub fn backup_path(job: &Path) -> PathBuf {
    let mut name = job.as_os_str().to_owned();
    name.push(".bak");
    PathBuf::from(name)
}

/// Saves `text` as the job `file_name` in `dir` (see [`job_path`]): the
/// file there before copied to `NAME.bak`, then the text placed atomically;
/// returns the job's path.
pub fn save_job(dir: &Path, file_name: &str, text: &str) -> Result<PathBuf, StudioError> {
    save_job_with(&Writer::default(), dir, file_name, text)
}

/// [`save_job`] through `writer` (tests: a writer whose temporary names are
/// known in advance).
pub fn save_job_with(
    writer: &Writer,
    dir: &Path,
    file_name: &str,
    text: &str,
) -> Result<PathBuf, StudioError> {
    let path = job_path(dir, file_name)?;
    if path.exists() {
        let old = formcam_files::read_bytes(&path).map_err(|source| StudioError::ReadJob {
            path: path.clone(),
            source,
        })?;
        writer.write_files(&[(backup_path(&path), old)], &[])?;
    }
    writer.write_files(&[(&path, text.as_bytes())], &[])?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_toml_names_only() {
        let dir = Path::new("studio");
        assert_eq!(
            job_path(dir, "vessel.toml").ok(),
            Some(dir.join("vessel.toml"))
        );
        let refused = [
            ("", NameProblem::Empty),
            (".toml", NameProblem::Empty),
            ("runs/a.toml", NameProblem::NotPlain),
            ("../a.toml", NameProblem::NotPlain),
            ("..", NameProblem::NotPlain),
            ("a\\b.toml", NameProblem::NotPlain),
            ("/etc/a.toml", NameProblem::NotPlain),
            (".hidden.toml", NameProblem::Hidden),
            ("a.txt", NameProblem::NotToml),
            ("a.toml.bak", NameProblem::NotToml),
            ("a\n.toml", NameProblem::Control),
        ];
        for (name, why) in refused {
            match job_path(dir, name) {
                Err(StudioError::JobName { reason, .. }) => assert_eq!(reason, why, "{name:?}"),
                other => panic!("{name:?}: {other:?}"),
            }
        }
        assert_eq!(
            job_path(dir, "runs/a.toml")
                .map_err(|e| e.to_string())
                .err()
                .as_deref(),
            Some(
                "runs/a.toml: not a job file name: give a plain file name in the studio's folder (no folders, no `..`)"
            )
        );
    }

    #[test]
    fn backups_sit_beside_the_job() {
        assert_eq!(
            backup_path(Path::new("d/vessel.toml")),
            PathBuf::from("d/vessel.toml.bak")
        );
    }
}
