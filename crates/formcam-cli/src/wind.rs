//! `formcam wind ...` and the demo: arguments mapped to `formcam_run`'s
//! winding runs, their files written, their line printed.

use std::fs;
use std::path::{Path, PathBuf};

use clap::ValueEnum;
use formcam_program::{Check, Stage};
use formcam_run::RunOutput;

use crate::CliError;
use crate::output::write_run;

/// A check whose failure a `.wind` job accepts (`--allow`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AllowCheck {
    /// The eye's circuit closes.
    Cyclicity,
    /// The eye keeps its clearance.
    Clearance,
    /// The free band within `l_max`.
    #[value(name = "l_max")]
    LMax,
    /// The band never goes slack.
    Slack,
    /// The mandrel never turns backwards.
    ReverseRotation,
    /// Every axis within its limits.
    Limits,
    /// Every eye point reached.
    Unreachable,
    /// Block times within the velocity limits.
    Timing,
    /// Block times within the acceleration limits.
    Acceleration,
}

impl From<AllowCheck> for Check {
    fn from(c: AllowCheck) -> Self {
        match c {
            AllowCheck::Cyclicity => Check::Cyclicity,
            AllowCheck::Clearance => Check::Clearance,
            AllowCheck::LMax => Check::LMax,
            AllowCheck::Slack => Check::Slack,
            AllowCheck::ReverseRotation => Check::ReverseRotation,
            AllowCheck::Limits => Check::Limits,
            AllowCheck::Unreachable => Check::Unreachable,
            AllowCheck::Timing => Check::Timing,
            AllowCheck::Acceleration => Check::Acceleration,
        }
    }
}

/// Prints the run's warnings, writes its files into `out` and returns its line.
fn emit(out: &Path, run: Result<RunOutput, formcam_run::RunError>) -> Result<String, CliError> {
    let run = run.map_err(|e| CliError(e.to_string()))?;
    for w in &run.warnings {
        eprintln!("formcam: warning: {w}");
    }
    write_run(out, &run)?;
    Ok(run.line)
}

/// `formcam wind [path|eye|axes] JOB -o OUT`; returns the one-line summary.
pub fn run(job: &Path, out: &Path, stage: Stage) -> Result<String, CliError> {
    emit(out, formcam_run::wind(job, out, stage))
}

/// `formcam wind JOB.wind -o OUT [--eye-clearance MM] [--allow CHECKS]`.
pub fn run_wind_file(
    job: &Path,
    out: &Path,
    eye_clearance: f64,
    allow: &[AllowCheck],
) -> Result<String, CliError> {
    let allow: Vec<Check> = allow.iter().map(|&c| c.into()).collect();
    emit(out, formcam_run::wind_file(job, out, eye_clearance, &allow))
}

/// Runs every `*.toml` and `*.wind` job in `examples` into `out/<name>/`.
pub fn run_demo(examples: &Path, out: &Path) -> Result<(), CliError> {
    let mut jobs: Vec<PathBuf> = fs::read_dir(examples)
        .map_err(|e| {
            CliError(format!(
                "{}: cannot list the examples: {e}",
                examples.display()
            ))
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml" || x == "wind"))
        .collect();
    jobs.sort();
    if jobs.is_empty() {
        return Err(CliError(format!(
            "{}: no *.toml or *.wind jobs found",
            examples.display()
        )));
    }
    for job in &jobs {
        let name = job
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let dir = out.join(&name);
        if job.extension().is_some_and(|x| x == "wind") {
            println!(
                "{}",
                run_wind_file(job, &dir, formcam_program::EYE_CLEARANCE_MM, &[])?
            );
            continue;
        }
        let text = fs::read_to_string(job)
            .map_err(|e| CliError(format!("{}: cannot read the job file: {e}", job.display())))?;
        if let Ok(table) = text.parse::<toml::Table>() {
            if crate::correct::is_scenario(&table) {
                println!("{}", crate::correct::simulate_text(job, &text, &dir)?);
                continue;
            }
            if crate::correct::is_job(&table) {
                println!("{}", crate::correct::run_job_text(job, &text, &dir)?);
                continue;
            }
            if crate::dress::is_job(&table) {
                println!("{}", crate::dress::run_text(job, &text, &dir)?);
                continue;
            }
        }
        println!("{}", emit(&dir, formcam_run::wind_furthest(job, &dir))?);
    }
    println!("{} jobs written under {}", jobs.len(), out.display());
    Ok(())
}
