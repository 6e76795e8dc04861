//! `formcam check` as one call: a program file and a machine to a report.

use std::path::{Path, PathBuf};

use formcam_machine::{JointKind, Machine};
use formcam_nc::{AxisSpec, Dialect, Program, read_cldata_lines, read_gcode_lines_in};

use crate::{
    AxisLimits, FeedRule, FreeFibre, Report, SimError, SnagOptions, Timeline, check_snag,
    check_timeline,
};

/// The program axes of a machine, as formcam's programs for it name them:
/// every driven axis in the machine's order, revolute ones rotary (modulo
/// where the machine says so).
pub fn program_axes(machine: &Machine) -> Vec<AxisSpec> {
    machine
        .axes
        .iter()
        .map(|a| match (a.kind, a.modulo) {
            (JointKind::Revolute, true) => AxisSpec::rotary_modulo(a.name.clone()),
            (JointKind::Revolute, false) => AxisSpec::rotary(a.name.clone()),
            _ => AxisSpec::linear(a.name.clone()),
        })
        .collect()
}

/// Reads the text of the program file `path` in the dialect its extension
/// names, on `machine`'s axes: the program, each block's line, the dialect.
pub fn read_program(
    path: &Path,
    text: &str,
    machine: &Machine,
) -> Result<(Program, Vec<usize>, Dialect), SimError> {
    let dialect = path
        .extension()
        .and_then(|e| e.to_str())
        .and_then(Dialect::from_extension)
        .ok_or_else(|| SimError::Extension {
            path: path.to_path_buf(),
            allowed: ".mpf/.spf (Sinumerik 840D), .nc (ISO), .ngc (LinuxCNC), \
                      .gcode (Marlin X/A/B), .cls (CLDATA)",
        })?;
    let axes = program_axes(machine);
    let read = match dialect {
        Dialect::Cldata => read_cldata_lines(text, &axes),
        d => read_gcode_lines_in(text, &axes, d),
    };
    let (program, lines) = read.map_err(|source| SimError::Program {
        path: path.to_path_buf(),
        source,
    })?;
    Ok((program, lines, dialect))
}

/// A check's result: the report, its one line, and the files read.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckRun {
    /// The report (`report.json`).
    pub report: Report,
    /// The verdict in one line.
    pub line: String,
    /// The files read (no output may overwrite one).
    pub inputs: Vec<PathBuf>,
}

impl CheckRun {
    /// Whether every check passed.
    pub fn clean(&self) -> bool {
        self.report.clean
    }

    /// The report as JSON text (pretty, a newline at the end).
    pub fn report_json(&self) -> Result<String, SimError> {
        let mut s = serde_json::to_string_pretty(&self.report)?;
        s.push('\n');
        Ok(s)
    }
}

/// Checks the program text `text` (of the file `program`, its dialect from
/// the extension) on `machine` (its name for the report): the timeline and
/// every axis check.
pub fn check_text(
    program: &Path,
    text: &str,
    machine: &Machine,
    machine_name: &str,
) -> Result<Report, SimError> {
    let (p, lines, dialect) = read_program(program, text, machine)?;
    let rule = FeedRule::of(dialect);
    let tl = Timeline::new(&p, &lines, rule, machine)?;
    let violations = check_timeline(&tl, &AxisLimits::of(machine));
    Ok(Report {
        program: program.display().to_string(),
        machine: machine_name.to_string(),
        dialect: dialect.name(),
        feed_rule: rule.name(),
        blocks: tl.len(),
        duration_s: tl.duration_s(),
        clean: violations.is_empty(),
        violations,
    })
}

/// `formcam check PROGRAM --machine MACHINE`: reads the program file and the
/// machine (a TOML or URDF file, or a shipped machine's name when no such
/// file exists) and checks the program.
pub fn check_files(program: &Path, machine: &Path) -> Result<CheckRun, SimError> {
    check_files_with(program, machine, None)
}

/// [`check_files`], and with `snag_job` (the winding job the program was
/// written from, `--mandrel JOB`) the free-fibre snag check too
/// ([`check_snag`] with [`SnagOptions::default`], on the machine given).
pub fn check_files_with(
    program: &Path,
    machine: &Path,
    snag_job: Option<&Path>,
) -> Result<CheckRun, SimError> {
    let mut run = check_axes_files(program, machine)?;
    if let Some(job) = snag_job {
        let fibre = FreeFibre::from_job_file(job)?;
        run.inputs.push(job.to_path_buf());
        let m = machine_of(machine, &mut Vec::new())?;
        let fibre = fibre.with_machine(m)?;
        let text = formcam_files::read_text(program)?;
        let (p, lines, dialect) = read_program(program, &text, fibre.machine())?;
        let tl = Timeline::new(&p, &lines, FeedRule::of(dialect), fibre.machine())?;
        let snags = check_snag(&tl, &fibre, &SnagOptions::default())?;
        let r = &mut run.report;
        r.violations.extend(snags);
        r.violations.sort_by(|a, b| {
            a.time_s
                .total_cmp(&b.time_s)
                .then(a.block.cmp(&b.block))
                .then(a.kind.cmp(&b.kind))
        });
        r.clean = r.violations.is_empty();
        run.line = r.line();
    }
    Ok(run)
}

/// The machine of `--machine`: a file, or a shipped machine's name when no
/// such file exists; a file read is added to `inputs`.
fn machine_of(machine: &Path, inputs: &mut Vec<PathBuf>) -> Result<Machine, SimError> {
    let name = machine.to_string_lossy();
    match formcam_machine::shipped::shipped(&name) {
        Some(s) if !machine.exists() => s.machine(),
        _ => {
            let text = formcam_files::read_text(machine)?;
            inputs.push(machine.to_path_buf());
            Machine::from_file_text(machine, &text)
        }
    }
    .map_err(|source| SimError::Machine {
        path: machine.to_path_buf(),
        source,
    })
}

/// The axis checks of [`check_files`].
fn check_axes_files(program: &Path, machine: &Path) -> Result<CheckRun, SimError> {
    let mut inputs = vec![program.to_path_buf()];
    let name = machine.to_string_lossy();
    let m = machine_of(machine, &mut inputs)?;
    let text = formcam_files::read_text(program)?;
    let report = check_text(program, &text, &m, &name)?;
    Ok(CheckRun {
        line: report.line(),
        report,
        inputs,
    })
}
