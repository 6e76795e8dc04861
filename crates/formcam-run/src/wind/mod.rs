//! Winding runs: a job's result files — the program, `blocks.csv`,
//! `axes.csv`, the band, eye and path CSVs, each layer's `layer-NN/`
//! outputs, `summary.json` and the plots — and the line that says what was
//! done. A single-layer job writes its layer's outputs as its own; a
//! multi-layer job (and a `.wind` document) writes them per layer.
//!
//! The summary's `job` is the job file's absolute path (the files the job
//! names are found from its folder), and the result keeps the job's text
//! as it ran: `job.toml` (`job.wind` for a `.wind` document).
//!
//! A run that writes a program then checks it on its machine as `formcam
//! check --mandrel JOB` would, from the written text (the program read
//! back, each block timed by its own feed), with the job's mandrel, laminate
//! and free fibre taken from the planning already done: `check.json` is the
//! report, the line says `checked: clean` or the violations, and
//! [`RunOutput::violations`] their count. [`ProgramCheck::Off`] skips it.

mod check;
mod csv;
mod layers;
mod line;
mod program;
mod single;
mod summary;
mod windfile;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use formcam_program::{
    Assembled, MachineSource, MandrelCheckBuilder, Post, ProgramError, Stage, WindJob, WoundLayer,
    WoundProgram, plan_each, plan_until_with, write_program,
};
use formcam_progress::{Phase, Progress, Silent, Step};
use formcam_results::names::{self, CHECK};

use self::check::{Checked, check_error, check_program};
use self::layers::{LayerFiles, layered};
use self::single::single;
use crate::{ResultFile, RunError, RunOutput};

pub use windfile::{wind_file, wind_file_checked_with, wind_file_with};

/// Whether a winding run checks the program it wrote (`formcam check` on
/// its text, on the job's machine) before it reports.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum ProgramCheck {
    /// The written program read back and checked: `check.json`, the line's
    /// verdict, [`RunOutput::violations`].
    #[default]
    On,
    /// No check (`formcam wind --no-check`).
    Off,
}

/// `formcam wind [path|eye|axes] JOB -o OUT`: the job at `job` run up to
/// `stage`; `out` is only named in the line (and in the check's report).
pub fn wind(job: &Path, out: &Path, stage: Stage) -> Result<RunOutput, RunError> {
    wind_with(job, out, stage, &Silent)
}

/// [`wind`] reporting to `progress` (the pipeline's phases, the post, the
/// files); [`RunError::Cancelled`] when it asks to stop.
pub fn wind_with(
    job: &Path,
    out: &Path,
    stage: Stage,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    wind_checked_with(job, out, stage, ProgramCheck::On, progress)
}

/// [`wind_with`], checking the written program or not (`check`).
pub fn wind_checked_with(
    job: &Path,
    out: &Path,
    stage: Stage,
    check: ProgramCheck,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let t0 = Instant::now();
    let text = read_job_text(job)?;
    let wj = parse_job(job, &text)?;
    let mut output = run(job, out, &wj, stage, check, t0, progress)?;
    output.inputs = job_inputs(job, &wj);
    output.files.push(ResultFile::new(names::JOB, text));
    Ok(output)
}

/// The job at `job` run as far as its tables reach (the demo's rule, see
/// [`WindJob::furthest_stage`]).
pub fn wind_furthest(job: &Path, out: &Path) -> Result<RunOutput, RunError> {
    wind_furthest_with(job, out, &Silent)
}

/// [`wind_furthest`] reporting to `progress`.
pub fn wind_furthest_with(
    job: &Path,
    out: &Path,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let t0 = Instant::now();
    let text = read_job_text(job)?;
    furthest(job, &text, out, t0, progress)
}

/// [`wind_furthest_with`] for the job `text` the caller holds (an edited
/// job not yet saved): read as if it were the file at `job`, so the files
/// it names are found relative to `job`'s folder and the summary names
/// `job` (its absolute path); the file itself is not read, and `text` is
/// the copy the result keeps.
pub fn wind_furthest_text_with(
    job: &Path,
    text: &str,
    out: &Path,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    furthest(job, text, out, Instant::now(), progress)
}

/// The job `text` (of the file at `job`) run as far as its tables reach.
fn furthest(
    job: &Path,
    text: &str,
    out: &Path,
    t0: Instant,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let wj = parse_job(job, text)?;
    let stage = wj.furthest_stage();
    let mut output = run(job, out, &wj, stage, ProgramCheck::On, t0, progress)?;
    output.inputs = job_inputs(job, &wj);
    output.files.push(ResultFile::new(names::JOB, text));
    Ok(output)
}

/// The files a winding job at `path` reads: itself, its machine file, the
/// mandrel's meridian table, the eye's curve and the post's template.
fn job_inputs(path: &Path, job: &WindJob) -> Vec<PathBuf> {
    let machine = job.machine.as_ref().and_then(|m| match &m.source {
        MachineSource::File(f) => Some(f.as_str()),
        MachineSource::Shipped(_) => None,
    });
    let template = match &job.post {
        Some(Post::Template { file, .. }) => Some(file.as_str()),
        _ => None,
    };
    let named = [
        machine,
        job.mandrel.file.as_deref(),
        job.eye.as_ref().and_then(|e| e.curve.as_deref()),
        template,
    ];
    std::iter::once(path.to_path_buf())
        .chain(named.into_iter().flatten().map(|f| job.base_dir.join(f)))
        .collect()
}

/// The text of the job file at `path`.
fn read_job_text(path: &Path) -> Result<String, RunError> {
    formcam_files::read_text(path).map_err(|e| RunError::Read {
        path: path.to_path_buf(),
        source: e.into(),
    })
}

/// The job `text` of the file at `path`: the files it names relative to
/// `path`'s folder, named by `path`.
fn parse_job(path: &Path, text: &str) -> Result<WindJob, RunError> {
    let base = path.parent().unwrap_or(Path::new(""));
    Ok(WindJob::from_toml(text, base)
        .map_err(|e| RunError::wind(path, e))?
        .named(path))
}

/// Plans `job` up to `stage`, lays out its files and checks the program
/// written (unless `check` is off).
fn run(
    path: &Path,
    out: &Path,
    job: &WindJob,
    stage: Stage,
    check: ProgramCheck,
    t0: Instant,
    progress: &dyn Progress,
) -> Result<RunOutput, RunError> {
    let mut mandrel = mandrel_check(path, job, stage, check)?;
    let (wound, each) = plan(path, job, stage, progress, &mut mandrel)?;
    let program = post(path, &wound, progress)?;
    let checked = match (&program, mandrel) {
        (Some((_, text)), Some(mandrel)) => check_program(path, out, job, &wound, text, mandrel)?,
        _ => None,
    };
    progress.checkpoint(Step::new(Phase::Files, 0, 1))?;
    let mut output = if job.is_layered() {
        layered(path, job, &wound, program, each)?
    } else {
        single(path, job, &wound, program)?
    };
    progress.checkpoint(Step::new(Phase::Files, 1, 1))?;
    end_line(out, &wound, check, checked, t0, &mut output)?;
    warn(path, job, &wound, &mut output);
    Ok(output)
}

/// The check's free fibre and laminate, gathered as `job` is planned, when
/// its program is to be checked (a user template's program is not read
/// back).
fn mandrel_check(
    path: &Path,
    job: &WindJob,
    stage: Stage,
    check: ProgramCheck,
) -> Result<Option<MandrelCheckBuilder>, RunError> {
    Ok(match (check, stage, job.post()) {
        (ProgramCheck::On, Stage::Program, Post::Dialect(_)) => {
            Some(MandrelCheckBuilder::new(job).map_err(|e| check_error(path, e))?)
        }
        _ => None,
    })
}

/// `job` planned up to `stage`, each layer handed to the check's `mandrel`;
/// a multi-layer job's layer files are made as each layer is planned, which
/// then drops its per-point data.
fn plan(
    path: &Path,
    job: &WindJob,
    stage: Stage,
    progress: &dyn Progress,
    mandrel: &mut Option<MandrelCheckBuilder>,
) -> Result<(WoundProgram, LayerFiles), RunError> {
    let at = |e: ProgramError| RunError::wind(path, e);
    let mut each = LayerFiles::default();
    let wound = if job.is_layered() {
        let m = job.machine.as_ref().map(|jm| &jm.machine);
        plan_each(job, stage, progress, &mut |i, l| {
            if let Some(b) = mandrel {
                b.add(l).map_err(|e| Halt::Run(check_error(path, e)))?;
            }
            match m {
                Some(m) => each.add(m, i, l).map_err(Halt::Run),
                None => Ok(()),
            }
        })
        .map_err(|h| match h {
            Halt::Program(e) => at(e),
            Halt::Run(e) => e,
        })?
    } else {
        let wound = plan_until_with(job, stage, progress).map_err(at)?;
        if let Some(b) = mandrel {
            for l in &wound.layers {
                b.add(l).map_err(|e| check_error(path, e))?;
            }
        }
        wound
    };
    Ok((wound, each))
}

/// The program of `wound` (if it has one) and its text, as the post writes
/// it.
fn post<'w>(
    path: &Path,
    wound: &'w WoundProgram,
    progress: &dyn Progress,
) -> Result<Option<(&'w Assembled, Vec<u8>)>, RunError> {
    let Some(p) = &wound.program else {
        return Ok(None);
    };
    progress.checkpoint(Step::new(Phase::Post, 0, 1))?;
    let mut text = Vec::new();
    write_program(wound, &mut text).map_err(|e| RunError::wind(path, e))?;
    progress.checkpoint(Step::new(Phase::Post, 1, 1))?;
    Ok(Some((p, text)))
}

/// The line's end (the run's time without the check's, the folder, the
/// check's verdict or why there is none) and `check.json`.
fn end_line(
    out: &Path,
    wound: &WoundProgram,
    check: ProgramCheck,
    checked: Option<Checked>,
    t0: Instant,
    output: &mut RunOutput,
) -> Result<(), RunError> {
    let check_time = checked.as_ref().map_or(Duration::ZERO, |c| c.time);
    let _ = write!(
        output.line,
        ", {:.1} ms -> {}",
        t0.elapsed().saturating_sub(check_time).as_secs_f64() * 1e3,
        out.display()
    );
    if let Some(c) = checked {
        output.line.push_str(&c.verdict());
        output.violations = Some(c.report.violations.len());
        output.files.push(ResultFile::new(CHECK, c.json()?));
    } else if check == ProgramCheck::On
        && program_written(output)
        && matches!(wound.post, Post::Template { .. })
    {
        output
            .line
            .push_str("; not checked: a user template's program cannot be read back");
    }
    Ok(())
}

/// A single-layer job's warnings on the line, every warning of the job (the
/// job file at `path`) for stderr.
fn warn(path: &Path, job: &WindJob, wound: &WoundProgram, output: &mut RunOutput) {
    if let Some(l) = wound.layers.first().and_then(WoundLayer::wound)
        && !job.is_layered()
    {
        for w in &l.layer.warnings {
            let _ = write!(output.line, "\n  warning: {w}");
        }
    }
    output.warnings = wound
        .warnings
        .iter()
        .map(|w| format!("{}: {w}", path.display()))
        .collect();
}

/// Whether a run's files hold a program.
fn program_written(output: &RunOutput) -> bool {
    output.files.iter().any(|f| names::is_program(&f.name))
}

/// Why planning a multi-layer job stopped: the plan, or a layer's files.
enum Halt {
    Program(ProgramError),
    Run(RunError),
}

impl From<ProgramError> for Halt {
    fn from(e: ProgramError) -> Self {
        Self::Program(e)
    }
}
