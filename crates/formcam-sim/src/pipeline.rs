//! `formcam check` as one call: a program file and a machine to a report.

use std::path::{Path, PathBuf};

use formcam_machine::{JointKind, Machine};
use formcam_nc::{AxisSpec, Dialect, Program, read_cldata_lines, read_gcode_lines_in};

use crate::{
    AxisLimits, Collisions, FeedRule, FreeFibre, Laminate, MandrelCheck, Report, SimError,
    SnagOptions, Timeline, check_snag, check_timeline,
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
/// the extension) on `machine` (its name for the report): the timeline,
/// every axis check and the collisions of the machine's solids (mesh files
/// as written, relative to the current folder).
pub fn check_text(
    program: &Path,
    text: &str,
    machine: &Machine,
    machine_name: &str,
) -> Result<Report, SimError> {
    check_text_in(program, text, machine, machine_name, None, None)
}

/// [`check_text`] with the machine's mesh files relative to `mesh_dir`
/// and, when given, the mandrel of a winding job's `laminate` checked
/// against the machine's solids (no free fibre: [`check_text_with`] checks
/// that too).
pub fn check_text_in(
    program: &Path,
    text: &str,
    machine: &Machine,
    machine_name: &str,
    mesh_dir: Option<&Path>,
    laminate: Option<&Laminate>,
) -> Result<Report, SimError> {
    check_read(
        program,
        text,
        machine,
        machine_name,
        mesh_dir,
        laminate,
        None,
    )
}

/// The whole check, as `formcam check --mandrel JOB` runs it: [`check_text`]
/// with the machine's mesh files relative to `mesh_dir` and, when given, a
/// winding job's `mandrel`: its laminate's solid against the machine's
/// solids and its free fibre ([`check_snag`] with [`SnagOptions::default`])
/// against the mandrel and the solids, the fibre on `machine` (which must
/// have the axes, links and key points of the job's machine).
pub fn check_text_with(
    program: &Path,
    text: &str,
    machine: &Machine,
    machine_name: &str,
    mesh_dir: Option<&Path>,
    mandrel: Option<&MandrelCheck>,
) -> Result<Report, SimError> {
    check_read(
        program,
        text,
        machine,
        machine_name,
        mesh_dir,
        mandrel.map(MandrelCheck::laminate),
        mandrel.and_then(MandrelCheck::fibre),
    )
}

/// The program read once, its timeline, then every check asked: the axes,
/// the collisions (with the laminate's mandrel when given), the free fibre
/// (when given, moved onto `machine`); the violations in the order they
/// first happen.
fn check_read(
    program: &Path,
    text: &str,
    machine: &Machine,
    machine_name: &str,
    mesh_dir: Option<&Path>,
    laminate: Option<&Laminate>,
    fibre: Option<&FreeFibre>,
) -> Result<Report, SimError> {
    let (p, lines, dialect) = read_program(program, text, machine)?;
    let rule = FeedRule::of(dialect);
    let tl = Timeline::new(&p, &lines, rule, machine)?;
    let mut violations = check_timeline(&tl, &AxisLimits::of(machine));
    let collisions = match laminate {
        None => Collisions::new(machine, mesh_dir)?,
        Some(l) => {
            let stages = l.stage_of_blocks(dialect, p.blocks.iter().map(|b| b.comment.as_deref()));
            Collisions::with_mandrel(machine, mesh_dir, l, stages)?
        }
    };
    violations.extend(collisions.check(&tl, machine));
    if let Some(f) = fibre {
        let fibre = f.clone().with_machine(machine.clone())?;
        violations.extend(check_snag(&tl, &fibre, &SnagOptions::default())?);
    }
    violations.sort_by(|a, b| {
        a.time_s
            .total_cmp(&b.time_s)
            .then(a.block.cmp(&b.block))
            .then(a.kind.cmp(&b.kind))
    });
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

/// A machine a check runs on, as `formcam check --machine` names it: a
/// machine file (TOML or URDF) or a shipped machine's name.
#[derive(Debug, Clone)]
pub struct CheckMachine {
    /// The machine.
    pub machine: Machine,
    /// What names it in the report (the argument as given).
    pub name: String,
    /// The folder its mesh files are relative to (a machine file's).
    pub mesh_dir: Option<PathBuf>,
    /// The machine file read, if any (no output may overwrite it).
    pub file: Option<PathBuf>,
}

impl CheckMachine {
    /// The machine file `machine` (TOML or URDF), or a shipped machine's
    /// name when no such file exists.
    pub fn read(machine: &Path) -> Result<Self, SimError> {
        let name = machine.to_string_lossy().into_owned();
        let (m, mesh_dir, file) = match formcam_machine::shipped::shipped(&name) {
            Some(s) if !machine.exists() => (s.machine(), None, None),
            _ => {
                let text = formcam_files::read_text(machine)?;
                let m = Machine::from_file_text(machine, &text);
                (m, machine.parent(), Some(machine.to_path_buf()))
            }
        };
        let machine_error = |source| SimError::Machine {
            path: machine.to_path_buf(),
            source,
        };
        Ok(Self {
            machine: m.map_err(machine_error)?,
            name,
            mesh_dir: mesh_dir.map(Path::to_path_buf),
            file,
        })
    }
}

/// `formcam check PROGRAM --machine MACHINE`: reads the program file and the
/// machine (a TOML or URDF file, or a shipped machine's name when no such
/// file exists) and checks the program.
pub fn check_files(program: &Path, machine: &Path) -> Result<CheckRun, SimError> {
    check_file(program, &CheckMachine::read(machine)?, None)
}

/// Reads the program file `program` and checks it on `machine` (mesh files
/// relative to the machine file), with a winding job's `mandrel` when given
/// (its laminate against the machine's solids, its free fibre against the
/// mandrel and the solids). The inputs named are the program and the
/// machine file; the caller adds the job's.
pub fn check_file(
    program: &Path,
    machine: &CheckMachine,
    mandrel: Option<&MandrelCheck>,
) -> Result<CheckRun, SimError> {
    let mut inputs = vec![program.to_path_buf()];
    inputs.extend(machine.file.clone());
    let text = formcam_files::read_text(program)?;
    let report = check_text_with(
        program,
        &text,
        &machine.machine,
        &machine.name,
        machine.mesh_dir.as_deref(),
        mandrel,
    )?;
    Ok(CheckRun {
        line: report.line(),
        report,
        inputs,
    })
}
