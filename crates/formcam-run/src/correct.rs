//! `formcam correct` (the options on the command line, or a `[correct]` job
//! file) and `formcam correct simulate` (the closed loop) to their files.
//!
//! One exception to "the result is the files": `--report` names a report
//! the command extends (its `history`). The caller reads that file and
//! passes its text ([`History`]); the new content comes back in
//! [`Corrected::report`] for the caller to write where it belongs.

use std::path::{Path, PathBuf};

use formcam_correct::simulate::LoopResult;
use formcam_correct::{
    CorrectError, Correction, CorrectionJob, Given, Grid, JobField, Measurements, MillingProgram,
    Rule, ScenarioError, ScenarioJob, correct_program_with,
};
use formcam_plot::{convergence_svg, deviations_svg, displacement_svg};
use formcam_progress::{Phase, Progress, Silent, Step};
use formcam_results::correction::{NODE_STATUS, PREDICTED, ROUND_CMM};
use formcam_results::names::{
    self, CONVERGENCE_SVG, DEVIATIONS_AFTER_SVG, DEVIATIONS_BEFORE_SVG, REPORT,
};
use serde_json::{Value, json};

use crate::files::recorded;
use crate::{ResultFile, RunError, RunOutput};

/// Why a correction or a closed loop failed: the file or the setting it
/// concerns.
#[derive(Debug, thiserror::Error)]
pub enum CorrectRunError {
    /// A file (CMM report, program, job, scenario) that cannot be used.
    #[error("{}: {source}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// Why.
        source: CorrectError,
    },
    /// An option of the command line out of range: the same rule as the
    /// job file's field (`--gain 0: allowed (0, 2]`).
    #[error("--{flag} {value}: {rule}")]
    Flag {
        /// The option's name (without `--`).
        flag: &'static str,
        /// Its value as given.
        value: Given,
        /// What it breaks.
        rule: Rule,
    },
    /// A measured deviation beyond the plausible limit.
    #[error(
        "{}: section `{section}`, point `{point}`: deviation {deviation_mm:.3} mm is beyond \
         {limit} mm (a typing error in the report? nothing written)",
        path.display()
    )]
    Deviation {
        /// The CMM report.
        path: PathBuf,
        /// The section's name.
        section: String,
        /// The point's name.
        point: String,
        /// Its deviation, mm.
        deviation_mm: f64,
        /// The limit as the user set it (`--max-deviation 5`).
        limit: String,
    },
    /// A node displacement beyond the plausible limit.
    #[error(
        "{}: line {line}: the node would move by {displacement_mm:.3} mm, beyond {limit} mm \
         (nothing written)",
        path.display()
    )]
    Displacement {
        /// The program.
        path: PathBuf,
        /// The node's program line.
        line: usize,
        /// Its displacement, mm.
        displacement_mm: f64,
        /// The limit as the user set it.
        limit: String,
    },
    /// A report to extend that is not one.
    #[error("{}: exists but is not {what}; give another --report", path.display())]
    History {
        /// The report.
        path: PathBuf,
        /// What it should be.
        what: String,
    },
    /// An output path without a file name.
    #[error("{}: not a file name", path.display())]
    OutputName {
        /// The path.
        path: PathBuf,
    },
    /// A report that could not be written as JSON.
    #[error("report: {0}")]
    Json(String),
    /// Any other failure of the correction.
    #[error("correct: {0}")]
    Other(CorrectError),
}

/// How a correction was asked for: errors name its settings as the user
/// wrote them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Form<'a> {
    /// Options on the command line (`--gain`).
    Flags,
    /// A job file (`correct.gain` in the file at this path).
    Job(&'a Path),
}

/// A report the run extends (`--report`): its path, as the report names it,
/// and its text when it exists.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct History {
    /// The report's path.
    pub path: PathBuf,
    /// Its text, or `None` when there is no report yet.
    pub previous: Option<String>,
}

/// The result of `formcam correct` with options.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Corrected {
    /// The corrected program, `<stem>.deviations.svg`,
    /// `<stem>.displacement.svg` and, without a [`History`],
    /// `<stem>.report.json`, named inside [`output_folder`]; the line.
    pub run: RunOutput,
    /// With a [`History`]: the extended report's new text.
    pub report: Option<Vec<u8>>,
}

/// The folder the files of a correction with output `output` go to.
pub fn output_folder(output: &Path) -> PathBuf {
    output
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf()
}

/// Corrects `job.program` from `job.measurements` (both read here) into
/// the program `output`; its plots and report beside it, or the report
/// extending `history`.
pub fn correct(
    job: &CorrectionJob,
    output: &Path,
    history: Option<&History>,
) -> Result<Corrected, RunError> {
    correct_with(job, output, history, &Silent)
}

/// [`correct`] reporting to `progress` (the grid, the nodes, the files);
/// [`RunError::Cancelled`] when it asks to stop.
pub fn correct_with(
    job: &CorrectionJob,
    output: &Path,
    history: Option<&History>,
    progress: &dyn Progress,
) -> Result<Corrected, RunError> {
    let name = file_name(output)?;
    let stem = output
        .file_stem()
        .map_or_else(|| "corrected".into(), |f| f.to_string_lossy().into_owned());
    let (mut run, report, _) =
        correct_to(job, Form::Flags, (output, &name, &stem), history, progress)?;
    match history {
        Some(_) => Ok(Corrected {
            run,
            report: Some(report),
        }),
        None => {
            run.files
                .push(ResultFile::new(format!("{stem}.report.json"), report));
            Ok(Corrected { run, report: None })
        }
    }
}

/// Runs a `[correct]` job file (`path`, its `text`) into `out_dir`:
/// `corrected.<ext>` (the program's extension), its plots, what happened
/// to each node (`node-status.csv`), the next part's predicted CMM report
/// (`predicted-cmm.csv`), a fresh `report.json` and the job's text
/// (`job.toml`).
pub fn correct_job(path: &Path, text: &str, out_dir: &Path) -> Result<RunOutput, RunError> {
    correct_job_with(path, text, out_dir, &Silent)
}

/// [`correct_job`] reporting to `progress`.
pub fn correct_job_with(
    path: &Path,
    text: &str,
    out_dir: &Path,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let base = path.parent().unwrap_or(Path::new("."));
    let job = CorrectionJob::from_toml(text, base).map_err(|source| CorrectRunError::File {
        path: path.to_path_buf(),
        source,
    })?;
    let ext = job
        .program
        .extension()
        .map_or_else(|| "nc".into(), |e| e.to_string_lossy().into_owned());
    let name = format!("corrected.{ext}");
    let output = out_dir.join(&name);
    let (mut run, report, c) = correct_to(
        &job,
        Form::Job(path),
        (&output, &name, "corrected"),
        None,
        progress,
    )?;
    run.files
        .push(ResultFile::new(NODE_STATUS.file, c.applied.status_csv()));
    run.files
        .push(ResultFile::new(PREDICTED.file, c.predicted.to_csv()));
    run.files.push(ResultFile::new(REPORT, report));
    run.files.push(ResultFile::new(names::JOB, text));
    run.inputs.insert(0, path.to_path_buf());
    Ok(run)
}

/// The correction's program `output` and plots (named `name`,
/// `<stem>.*.svg`), the line, the report's text and the correction.
fn correct_to(
    job: &CorrectionJob,
    form: Form<'_>,
    (output, name, stem): (&Path, &str, &str),
    history: Option<&History>,
    progress: &dyn Progress,
) -> Result<(RunOutput, Vec<u8>, Correction), RunError> {
    let fail = |e: CorrectError| failure(e, job, form);
    job.settings.check().map_err(fail)?;
    let measurements =
        read_measurements(&job.measurements).map_err(|e| named(e, form, "correct.measurements"))?;
    let text = read(&job.program).map_err(|e| named(e, form, "correct.program"))?;
    let ext = job
        .program
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_default();
    let program = MillingProgram::read(&text, &ext, &job.settings).map_err(|source| {
        CorrectRunError::File {
            path: job.program.clone(),
            source,
        }
    })?;
    let c = correct_program_with(&measurements, &program, &job.settings, progress).map_err(fail)?;
    progress.checkpoint(Step::new(Phase::Files, 0, 1))?;
    let report = report_json(job, output, &c, history)?;
    let files = vec![
        ResultFile::new(name, c.applied.text.clone()),
        ResultFile::new(
            format!("{stem}.deviations.svg"),
            deviations_svg(&measurements, &c.grid)?,
        ),
        ResultFile::new(
            format!("{stem}.displacement.svg"),
            displacement_svg(&c.applied.nodes, &c.applied.corrections, &c.grid)?,
        ),
    ];
    let r = &c.report;
    let line = format!(
        "{}: {} nodes, {} corrected, {} outside, max deviation {:.4} mm, max displacement {:.4} mm",
        output.display(),
        r.nodes,
        r.nodes_corrected,
        r.nodes_outside,
        r.max_deviation_mm,
        r.max_displacement_mm
    );
    progress.checkpoint(Step::new(Phase::Files, 1, 1))?;
    Ok((
        RunOutput {
            files,
            line,
            warnings: Vec::new(),
            inputs: vec![job.measurements.clone(), job.program.clone()],
            violations: None,
        },
        report,
        c,
    ))
}

/// A failure of the pipeline, naming the file or the setting it concerns.
fn failure(e: CorrectError, job: &CorrectionJob, form: Form<'_>) -> CorrectRunError {
    let limit = |v: f64| match form {
        Form::Flags => format!("--max-deviation {v}"),
        Form::Job(_) => format!("{} = {v}", JobField::MaxDeviation),
    };
    match (e, form) {
        (CorrectError::Field { field, value, rule }, Form::Flags) => CorrectRunError::Flag {
            flag: flag(field),
            value,
            rule,
        },
        (e @ CorrectError::Field { .. }, Form::Job(path)) => CorrectRunError::File {
            path: path.to_path_buf(),
            source: e,
        },
        (
            CorrectError::Deviation {
                section,
                point,
                deviation_mm,
                limit_mm,
            },
            _,
        ) => CorrectRunError::Deviation {
            path: job.measurements.clone(),
            section,
            point,
            deviation_mm,
            limit: limit(limit_mm),
        },
        (
            CorrectError::NodeDisplacement {
                line,
                displacement_mm,
                limit_mm,
            },
            _,
        ) => CorrectRunError::Displacement {
            path: job.program.clone(),
            line,
            displacement_mm,
            limit: limit(limit_mm),
        },
        (e @ (CorrectError::Measurements(_) | CorrectError::Sections(_)), _) => {
            CorrectRunError::File {
                path: job.measurements.clone(),
                source: e,
            }
        }
        (e @ (CorrectError::Program(_) | CorrectError::Nc(_)), _) => CorrectRunError::File {
            path: job.program.clone(),
            source: e,
        },
        (e, _) => CorrectRunError::Other(e),
    }
}

/// The command-line option of a setting.
fn flag(field: JobField) -> &'static str {
    match field {
        JobField::Measurements => "measurements",
        JobField::Program => "program",
        JobField::Tool => "tool",
        JobField::Interpolation => "interpolation",
        JobField::Gain => "gain",
        JobField::Margin => "margin",
        JobField::Noise => "noise",
        JobField::ArcTolerance => "arc-tolerance",
        JobField::Dialect => "dialect",
        JobField::PointsPerSection => "points-per-section",
        JobField::MaxSegment => "max-segment",
        JobField::MaxDeviation => "max-deviation",
    }
}

/// The report: the correction's [`formcam_correct::Report`], the paths
/// (the measurements and the program it read absolute, the output as
/// given), and the history of the runs (the previous report's, this run
/// added).
fn report_json(
    job: &CorrectionJob,
    output: &Path,
    c: &Correction,
    history: Option<&History>,
) -> Result<Vec<u8>, CorrectRunError> {
    let mut runs = match history {
        Some(History {
            path,
            previous: Some(text),
        }) => previous_runs(path, text)?,
        _ => Vec::new(),
    };
    let (measurements, program) = (recorded(&job.measurements), recorded(&job.program));
    let output = output.display().to_string();
    let r = &c.report;
    runs.push(json!({
        "measurements": measurements,
        "program": program,
        "output": output,
        "max_deviation_mm": r.max_deviation_mm,
        "rms_deviation_mm": r.rms_deviation_mm,
        "max_displacement_mm": r.max_displacement_mm,
        "predicted_max_deviation_mm": r.predicted_max_deviation_mm,
        "nodes_corrected": r.nodes_corrected,
        "iteration": runs.len() + 1,
    }));
    let mut report = serde_json::to_value(r).map_err(|e| CorrectRunError::Json(e.to_string()))?;
    if let Value::Object(m) = &mut report {
        m.insert("measurements".into(), json!(measurements));
        m.insert("program".into(), json!(program));
        m.insert("output".into(), json!(output));
        m.insert("history".into(), Value::Array(runs));
    }
    pretty(&report)
}

/// The runs of an existing report's `history`.
fn previous_runs(path: &Path, text: &str) -> Result<Vec<Value>, CorrectRunError> {
    let bad = |what: String| CorrectRunError::History {
        path: path.to_path_buf(),
        what,
    };
    let old: Value = serde_json::from_str(text).map_err(|e| bad(format!("a JSON report ({e})")))?;
    match old.get("history").and_then(Value::as_array) {
        Some(h) => Ok(h.clone()),
        None => Err(bad("a formcam correct report (no `history`)".into())),
    }
}

/// Pretty JSON ending in a newline.
fn pretty(v: &Value) -> Result<Vec<u8>, CorrectRunError> {
    let mut s =
        serde_json::to_string_pretty(v).map_err(|e| CorrectRunError::Json(e.to_string()))?;
    s.push('\n');
    Ok(s.into_bytes())
}

/// Runs a closed-loop scenario (`path`, its `text`; the files go to
/// `out_dir`): `program-<k>.nc` and `cmm-<k>.csv` per round,
/// `deviations-before.svg`, `deviations-after.svg`, `convergence.svg` and
/// `report.json` (with the section-spacing study; `scenario` the file's
/// absolute path) and the scenario's text (`job.toml`).
pub fn correct_simulate(path: &Path, text: &str, out_dir: &Path) -> Result<RunOutput, RunError> {
    correct_simulate_with(path, text, out_dir, &Silent)
}

/// [`correct_simulate`] reporting to `progress` (the rounds, the
/// section-spacing study, the files).
pub fn correct_simulate_with(
    path: &Path,
    text: &str,
    out_dir: &Path,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let at = |source: CorrectError| CorrectRunError::File {
        path: path.to_path_buf(),
        source,
    };
    let ScenarioJob {
        scenario,
        section_study,
    } = ScenarioJob::from_toml(text).map_err(at)?;
    let result = scenario.run_with(progress).map_err(at)?;
    let rows = if section_study.is_empty() {
        Vec::new()
    } else {
        scenario
            .spacing_study_with(&section_study, progress)
            .map_err(at)?
    };
    progress.checkpoint(Step::new(Phase::Files, 0, 1))?;
    let (Some(first), Some(last)) = (result.rounds.first(), result.rounds.last()) else {
        return Err(at(ScenarioError::NoRound.into()).into());
    };
    let mut files = Vec::new();
    let mut rounds = Vec::new();
    for (k, r) in result.rounds.iter().enumerate() {
        files.push(ResultFile::new(names::round_program(k), r.program.clone()));
        files.push(ResultFile::new(
            names::round_cmm(k),
            cmm_csv(&r.measurements),
        ));
        rounds.push(json!({
            "iteration": k,
            "measured_max_mm": r.measured_max_mm,
            "measured_rms_mm": r.measured_rms_mm,
            "true_max_mm": r.true_max_mm,
            "true_rms_mm": r.true_rms_mm,
        }));
    }
    let grid_of = |m: &Measurements| Grid::from_measurements(m, None).map_err(at);
    files.push(ResultFile::new(
        DEVIATIONS_BEFORE_SVG,
        deviations_svg(&first.measurements, &grid_of(&first.measurements)?)?,
    ));
    files.push(ResultFile::new(
        DEVIATIONS_AFTER_SVG,
        deviations_svg(&last.measurements, &grid_of(&last.measurements)?)?,
    ));
    files.push(ResultFile::new(CONVERGENCE_SVG, convergence_svg(&result)?));
    let study: Vec<Value> = rows
        .iter()
        .map(|r| {
            json!({
                "sections": r.sections,
                "points_per_section": r.points,
                "section_spacing_mm": r.spacing_mm,
                "interpolation": r.interpolation.name(),
                "true_max_mm": r.true_max_mm,
                "true_rms_mm": r.true_rms_mm,
            })
        })
        .collect();
    let report = json!({
        "scenario": recorded(path),
        "iterations": scenario.iterations,
        "interpolation": scenario.options.interpolation.name(),
        "sections": scenario.sections,
        "points_per_section": scenario.points,
        "noise_mm": scenario.noise,
        "warp_amplitude_mm": scenario.warp_amplitude,
        "rounds": rounds,
        "max_deviation_before_mm": first.true_max_mm,
        "max_deviation_after_mm": last.true_max_mm,
        "rms_deviation_after_mm": last.true_rms_mm,
        "section_study": study,
    });
    files.push(ResultFile::new(REPORT, pretty(&report)?));
    files.push(ResultFile::new(names::JOB, text));
    progress.checkpoint(Step::new(Phase::Files, 1, 1))?;
    Ok(RunOutput {
        files,
        line: loop_line(out_dir, &result),
        warnings: Vec::new(),
        inputs: vec![path.to_path_buf()],
        violations: None,
    })
}

/// The closed loop's line: rounds, the true and the measured deviation
/// before and after.
fn loop_line(out_dir: &Path, result: &LoopResult) -> String {
    let (Some(first), Some(last)) = (result.rounds.first(), result.rounds.last()) else {
        return format!("{}: no round", out_dir.display());
    };
    format!(
        "{}: {} rounds, true max deviation {:.4} mm -> {:.4} mm (rms {:.4} mm), measured {:.4} mm -> {:.4} mm",
        out_dir.display(),
        result.rounds.len() - 1,
        first.true_max_mm,
        last.true_max_mm,
        last.true_rms_mm,
        first.measured_max_mm,
        last.measured_max_mm,
    )
}

/// The measurements as the CMM CSV report (with normals).
fn cmm_csv(m: &Measurements) -> String {
    let mut out = ROUND_CMM.header_with(&[], true);
    for s in &m.sections {
        for p in &s.points {
            let n = p.normal.unwrap_or([0.0, 0.0, 1.0]);
            out.push_str(&format!(
                "{},{},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.6},{:.6},{:.6}\n",
                s.name,
                p.point,
                p.nominal[0],
                p.nominal[1],
                p.nominal[2],
                p.actual[0],
                p.actual[1],
                p.actual[2],
                n[0],
                n[1],
                n[2]
            ));
        }
    }
    out
}

/// Reads a text file.
fn read(path: &Path) -> Result<String, RunError> {
    formcam_files::read_text(path).map_err(|e| RunError::Read {
        path: path.to_path_buf(),
        source: e.into(),
    })
}

/// Reads a CMM report, CSV or DMIS (`.dmi`, `.dmis`, `.dms`, `.dmo`) by its
/// extension.
pub fn read_measurements(path: &Path) -> Result<Measurements, RunError> {
    let text = read(path)?;
    Ok(
        Measurements::from_file_text(path, &text).map_err(|source| CorrectRunError::File {
            path: path.to_path_buf(),
            source,
        })?,
    )
}

/// A file a job names that cannot be read, naming the job and its `field`;
/// on the command line the file alone.
fn named(e: RunError, form: Form<'_>, field: &'static str) -> RunError {
    match (e, form) {
        (RunError::Read { path, source }, Form::Job(job)) => RunError::ReadNamed {
            job: job.to_path_buf(),
            field,
            path,
            source,
        },
        (e, _) => e,
    }
}

/// The file name of `path`.
fn file_name(path: &Path) -> Result<String, CorrectRunError> {
    path.file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .ok_or_else(|| CorrectRunError::OutputName {
            path: path.to_path_buf(),
        })
}
