//! `formcam wind ...` and the demo: arguments mapped to `formcam_run`'s
//! winding runs, their files written, their line printed.

use std::path::Path;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use formcam_program::{Check, Stage};
use formcam_run::ProgramCheck;

use crate::CliError;
use crate::output::emit;
use crate::progress::with_bar;

/// `--allow`'s words: every check by the name users write, with what it
/// holds (a `.wind` job's checks whose failure is accepted).
pub fn allow_parser() -> impl TypedValueParser<Value = Check> {
    let words = Check::ALL.map(|c| PossibleValue::new(c.name()).help(c.meaning()));
    PossibleValuesParser::new(words).try_map(|s| s.parse::<Check>())
}

/// What a winding command printed and whether the program it wrote
/// passed its check (true when none was checked).
pub struct Wound {
    /// The one-line summary.
    pub line: String,
    /// No check found a violation.
    pub clean: bool,
}

impl Wound {
    fn of(out: &Path, run: formcam_run::RunOutput) -> Result<Self, CliError> {
        let clean = run.violations.is_none_or(|n| n == 0);
        Ok(Self {
            line: emit(out, run)?,
            clean,
        })
    }
}

/// Whether `--no-check` was given.
fn program_check(no_check: bool) -> ProgramCheck {
    if no_check {
        ProgramCheck::Off
    } else {
        ProgramCheck::On
    }
}

/// `formcam wind [path|eye|axes] JOB -o OUT [--no-check]`.
pub fn run(job: &Path, out: &Path, stage: Stage, no_check: bool) -> Result<Wound, CliError> {
    let check = program_check(no_check);
    let run = with_bar(|p| formcam_run::wind_checked_with(job, out, stage, check, p))?;
    Wound::of(out, run)
}

/// `formcam wind JOB.wind -o OUT [--eye-clearance MM] [--allow CHECKS] [--no-check]`.
pub fn run_wind_file(
    job: &Path,
    out: &Path,
    eye_clearance: f64,
    allow: &[Check],
    no_check: bool,
) -> Result<Wound, CliError> {
    let check = program_check(no_check);
    let run = with_bar(|p| {
        formcam_run::wind_file_checked_with(job, out, eye_clearance, allow, check, p)
    })?;
    Wound::of(out, run)
}

/// Runs every `*.toml` and `*.wind` job in `examples` into `out/<name>/`,
/// each by its kind; prints each job's line, then the count. `Ok(false)`
/// when the check of a program the demo wrote found a violation.
pub fn run_demo(examples: &Path, out: &Path) -> Result<bool, CliError> {
    let jobs = formcam_run::demo(examples)?;
    let mut clean = true;
    for job in &jobs {
        let dir = formcam_run::demo_folder(out, job);
        let text = crate::correct::read_text(job)?;
        let kind = formcam_run::JobKind::of(job, &text);
        let run = with_bar(|p| formcam_run::run_job_text_with(job, &text, kind, &dir, p))?;
        if kind == formcam_run::JobKind::Correction {
            crate::correct::guard_job(job, &text, &dir, &run)?;
        }
        let wound = Wound::of(&dir, run)?;
        clean &= wound.clean;
        println!("{}", wound.line);
    }
    println!("{} jobs written under {}", jobs.len(), out.display());
    Ok(clean)
}
