//! Any job file run by its kind: a winding TOML, a `.wind` document, a
//! `[correct]` job, a closed-loop scenario or a dressing job, told apart by
//! the file's extension and top-level tables; and the bundled examples in
//! the order the demo runs them.

use std::fs;
use std::path::{Path, PathBuf};

use formcam_correct::{CorrectionJob, ScenarioJob};

use formcam_progress::{Progress, Silent};

use crate::{
    RunError, RunOutput, correct_job_with, correct_simulate_with, dress_text_with, is_dress_job,
};

/// What a job file holds, and so which run it takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JobKind {
    /// A winding job (TOML): run to its furthest stage.
    Winding,
    /// A Cyclone/FiberPath `.wind` document: the whole program.
    WindFile,
    /// A mould correction job (`[correct]`).
    Correction,
    /// A closed-loop correction scenario (`[surface]` and `[warp]`).
    Scenario,
    /// A wheel dressing job (`[wheel]`).
    Dressing,
}

impl JobKind {
    /// The kind of the job at `path` whose text is `text`: `.wind` by its
    /// extension, the others by their tables (a winding job when no other
    /// kind's table is there, or when the text is no TOML: its run names
    /// the syntax error).
    pub fn of(path: &Path, text: &str) -> Self {
        if path.extension().is_some_and(|x| x == "wind") {
            return Self::WindFile;
        }
        match text.parse::<toml::Table>() {
            Ok(t) if ScenarioJob::is_scenario(&t) => Self::Scenario,
            Ok(t) if CorrectionJob::is_job(&t) => Self::Correction,
            Ok(t) if is_dress_job(&t) => Self::Dressing,
            _ => Self::Winding,
        }
    }
}

/// Runs the job file at `path` by its [`JobKind`] to its result files;
/// `out` is the folder they are meant for, named in the line. A `.wind`
/// document keeps the eye at the default clearance and accepts no failed
/// check; a winding TOML runs as far as its tables go.
pub fn run_job_file(path: &Path, out: &Path) -> Result<RunOutput, RunError> {
    run_job_file_with(path, out, &Silent)
}

/// [`run_job_file`] reporting to `progress` (each kind's phases);
/// [`RunError::Cancelled`] when it asks to stop.
pub fn run_job_file_with(
    path: &Path,
    out: &Path,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let text = formcam_files::read_text(path).map_err(|e| RunError::ReadJob {
        path: path.to_path_buf(),
        source: e.into(),
    })?;
    run_job_text_with(path, &text, JobKind::of(path, &text), out, progress)
}

/// [`run_job_file`] for a job whose `text` and `kind` the caller has
/// already read.
pub fn run_job_text(
    path: &Path,
    text: &str,
    kind: JobKind,
    out: &Path,
) -> Result<RunOutput, RunError> {
    run_job_text_with(path, text, kind, out, &Silent)
}

/// [`run_job_text`] reporting to `progress`. A TOML job runs from `text`
/// alone (the files it names relative to `path`'s folder); a `.wind`
/// document is read from `path`.
pub fn run_job_text_with(
    path: &Path,
    text: &str,
    kind: JobKind,
    out: &Path,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    match kind {
        JobKind::WindFile => {
            crate::wind_file_with(path, out, formcam_program::EYE_CLEARANCE_MM, &[], progress)
        }
        JobKind::Winding => crate::wind_furthest_text_with(path, text, out, progress),
        JobKind::Correction => correct_job_with(path, text, out, progress),
        JobKind::Scenario => correct_simulate_with(path, text, out, progress),
        JobKind::Dressing => Ok(dressing_for(
            path,
            out,
            dress_text_with(path, text, progress)?,
        )),
    }
}

/// A dressing run as it is shown: each warning naming the job file, the
/// line naming the folder `out`.
pub fn dressing_for(path: &Path, out: &Path, run: RunOutput) -> RunOutput {
    RunOutput {
        warnings: run
            .warnings
            .iter()
            .map(|w| format!("{}: {w}", path.display()))
            .collect(),
        line: format!("{} -> {}", run.line, out.display()),
        files: run.files,
        inputs: run.inputs,
        violations: run.violations,
    }
}

/// The job files of the demo in `examples`: every `*.toml` and `*.wind`,
/// sorted by name. An empty list is an error naming the folder.
pub fn demo(examples: &Path) -> Result<Vec<PathBuf>, RunError> {
    let mut jobs: Vec<PathBuf> = fs::read_dir(examples)
        .map_err(|source| RunError::Examples {
            path: examples.to_path_buf(),
            source,
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml" || x == "wind"))
        .collect();
    jobs.sort();
    if jobs.is_empty() {
        return Err(RunError::NoExamples {
            path: examples.to_path_buf(),
        });
    }
    Ok(jobs)
}

/// The subfolder of `out` the demo writes the job at `path` into: its stem.
pub fn demo_folder(out: &Path, path: &Path) -> PathBuf {
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    out.join(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_by_extension_and_tables() {
        let p = Path::new("job.toml");
        assert_eq!(JobKind::of(Path::new("a.wind"), "{}"), JobKind::WindFile);
        assert_eq!(
            JobKind::of(p, "[surface]\nx = 1\n[warp]\ny = 2\n"),
            JobKind::Scenario
        );
        assert_eq!(
            JobKind::of(p, "[correct]\ngain = 1.0\n"),
            JobKind::Correction
        );
        assert_eq!(JobKind::of(p, "[wheel]\nr = 1.0\n"), JobKind::Dressing);
        assert_eq!(
            JobKind::of(p, "[mandrel]\nkind = \"x\"\n"),
            JobKind::Winding
        );
        assert_eq!(JobKind::of(p, "not = [toml"), JobKind::Winding);
    }

    #[test]
    fn dressing_warnings_name_the_job_and_the_line_the_folder() {
        let run = RunOutput {
            files: Vec::new(),
            line: "dressed".into(),
            warnings: vec!["wheel.r: small".into()],
            inputs: Vec::new(),
            violations: None,
        };
        let shown = dressing_for(Path::new("d.toml"), Path::new("out/d"), run);
        assert_eq!(
            shown.line,
            format!("dressed -> {}", Path::new("out/d").display())
        );
        assert_eq!(shown.warnings, vec!["d.toml: wheel.r: small".to_string()]);
    }

    #[test]
    fn an_empty_folder_has_no_demo() {
        let dir = std::env::temp_dir().join(format!("formcam-run-demo-{}", std::process::id()));
        let made = fs::create_dir_all(&dir);
        assert!(made.is_ok());
        let listed = demo(&dir);
        assert!(matches!(listed, Err(RunError::NoExamples { .. })));
        let _ = fs::remove_dir(&dir);
    }
}
