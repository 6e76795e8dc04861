//! Any job file run by its kind: a winding TOML, a `.wind` document, a
//! `[correct]` job, a closed-loop scenario or a dressing job, told apart by
//! the file's extension and top-level tables; and the bundled examples in
//! the order the demo runs them.

use std::fs;
use std::path::{Path, PathBuf};

use formcam_correct::{CORRECT_JOB, CorrectionJob, SCENARIO_JOB, ScenarioJob};
use formcam_dress::DRESS_JOB;
use formcam_program::WINDING_JOB;
use formcam_progress::{Progress, Silent};
use formcam_schema::JobSchema;
use serde::{Deserialize, Serialize};

use crate::{
    RunError, RunOutput, correct_job_with, correct_simulate_with, dress_text_with, is_dress_job,
};

/// What a job file holds, and so its description and the run it takes:
/// the one registry of job kinds (the command line, the demo and the
/// studio all tell a job's kind here). Its name is the word JSON and the
/// studio's page write (`winding`, `windfile`, `correction`, ...).
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    Serialize,
    Deserialize,
    strum::IntoStaticStr,
    strum::EnumString,
    strum::EnumIter,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
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
    /// The kinds written as TOML against a description, in the order the
    /// studio lists them.
    pub const EDITABLE: [JobKind; 4] = [
        JobKind::Winding,
        JobKind::Dressing,
        JobKind::Correction,
        JobKind::Scenario,
    ];

    /// The kind's name (`winding`, `windfile`, ...), as JSON writes it.
    pub fn name(self) -> &'static str {
        self.into()
    }

    /// The kind named `name` (as [`JobKind::name`] writes it).
    pub fn from_name(name: &str) -> Option<Self> {
        name.parse().ok()
    }

    /// The description of this kind's job file, the one its reader
    /// validates against and the studio's form is drawn from (`None` for a
    /// `.wind` document, which is JSON read by its own rules).
    pub fn schema(self) -> Option<&'static JobSchema> {
        match self {
            JobKind::Winding => Some(&WINDING_JOB),
            JobKind::WindFile => None,
            JobKind::Correction => Some(&CORRECT_JOB),
            JobKind::Scenario => Some(&SCENARIO_JOB),
            JobKind::Dressing => Some(&DRESS_JOB),
        }
    }

    /// The kind of the job at `path` whose text is `text`: `.wind` by its
    /// extension, the others by their tables ([`JobKind::of_tables`]); a
    /// winding job when no kind's tables are there, or when the text is no
    /// TOML: its run names the syntax error.
    pub fn of(path: &Path, text: &str) -> Self {
        if let Some(kind) = Self::of_extension(path) {
            return kind;
        }
        match text.parse::<toml::Table>() {
            Ok(t) => Self::of_tables(&t).unwrap_or(Self::Winding),
            Err(_) => Self::Winding,
        }
    }

    /// The kind a job file's extension alone tells: a `.wind` document.
    pub fn of_extension(path: &Path) -> Option<Self> {
        formcam_program::is_wind_file(path).then_some(Self::WindFile)
    }

    /// The kind of the TOML job `text` by its top-level tables
    /// ([`JobKind::of_tables`]); `None` for a text that is no TOML.
    pub fn of_text(text: &str) -> Option<Self> {
        Self::of_tables(&text.parse::<toml::Table>().ok()?)
    }

    /// The kind of a TOML job by its top-level tables: `[surface]` and
    /// `[warp]` a scenario, `[correct]`, `[wheel]`, else a winding job when
    /// it has a winding table; `None` when it has none of these, or is a
    /// machine file (its `[machine]` table is also a winding job's, its
    /// `[[link]]`s are no job's).
    pub fn of_tables(table: &toml::Table) -> Option<Self> {
        if ScenarioJob::is_scenario(table) {
            Some(Self::Scenario)
        } else if CorrectionJob::is_job(table) {
            Some(Self::Correction)
        } else if is_dress_job(table) {
            Some(Self::Dressing)
        } else if !table.contains_key("link")
            && WINDING_JOB
                .tables
                .iter()
                .any(|t| table.contains_key(t.name))
        {
            Some(Self::Winding)
        } else {
            None
        }
    }
}

impl std::fmt::Display for JobKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
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
        .filter(|p| {
            p.extension().is_some_and(|x| x == "toml") || JobKind::of_extension(p).is_some()
        })
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

    #[test]
    fn kinds_by_their_extension_and_tables() {
        let cases = [
            (
                "[surface]\nkind = \"panel\"\n[warp]\n",
                Some(JobKind::Scenario),
            ),
            ("[correct]\ngain = 1.0\n", Some(JobKind::Correction)),
            ("[wheel]\nr1 = 1.0\n", Some(JobKind::Dressing)),
            ("[mandrel]\nkind = \"vessel\"\n", Some(JobKind::Winding)),
            ("[[layer]]\nkind = \"hoop\"\n", Some(JobKind::Winding)),
            ("[machine]\nname = \"m\"\n[[link]]\nname = \"a\"\n", None),
            ("[other]\nx = 1\n", None),
            ("not = [toml", None),
        ];
        let toml = Path::new("job.toml");
        for (text, kind) in cases {
            assert_eq!(JobKind::of_text(text), kind, "{text}");
            // A run takes what is no other kind's as a winding job, whose
            // reader then names what is wrong.
            assert_eq!(JobKind::of(toml, text), kind.unwrap_or(JobKind::Winding));
            assert_eq!(JobKind::of(Path::new("job.wind"), text), JobKind::WindFile);
        }
    }

    #[test]
    fn names_are_the_json_words_and_editable_kinds_have_descriptions() {
        use strum::IntoEnumIterator;
        for k in JobKind::iter() {
            let json = serde_json::to_string(&k).unwrap_or_default();
            assert_eq!(json, format!("\"{}\"", k.name()));
            assert_eq!(JobKind::from_name(k.name()), Some(k));
            assert_eq!(k.schema().is_some(), JobKind::EDITABLE.contains(&k), "{k}");
        }
        assert_eq!(
            JobKind::Dressing.schema().map(|s| s.name),
            Some(DRESS_JOB.name)
        );
        assert_eq!(JobKind::WindFile.name(), "windfile");
        assert_eq!(JobKind::from_name("Winding"), None);
    }
}
