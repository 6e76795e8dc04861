//! `formcam machine show|fk`: a machine file (or a shipped machine by
//! name) shown as its table, and the key points of a machine at each row
//! of an axes CSV by forward kinematics.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use formcam_machine::{AxesRow, Machine, read_axes_csv};

use crate::RunError;

/// Reads a machine file; errors name the file, the link or point, and the field.
pub fn read_machine(path: &Path) -> Result<Machine, RunError> {
    let text = formcam_files::read_text(path).map_err(|e| RunError::ReadMachine {
        path: path.to_path_buf(),
        source: e.into(),
    })?;
    parse_machine(path, &text)
}

/// A machine from the text of its file (named `path` in errors; URDF or
/// TOML by its extension).
fn parse_machine(path: &Path, text: &str) -> Result<Machine, RunError> {
    Machine::from_file_text(path, text).map_err(|source| RunError::Machine {
        path: path.to_path_buf(),
        source,
    })
}

/// `formcam machine show MACHINE`: the table of a machine file, or of a
/// shipped machine by name when no such file exists.
pub fn machine_show(path: &Path) -> Result<String, RunError> {
    let name = path.to_string_lossy();
    match formcam_machine::shipped::shipped(&name) {
        Some(s) if !path.exists() => Ok(parse_machine(path, s.text)?.table()),
        _ => Ok(read_machine(path)?.table()),
    }
}

/// The rows of an axes CSV for `m`.
fn read_axes(m: &Machine, path: &Path) -> Result<Vec<AxesRow>, RunError> {
    let text = formcam_files::read_text(path).map_err(|e| RunError::ReadAxes {
        path: path.to_path_buf(),
        source: e.into(),
    })?;
    read_axes_csv(m, &text).map_err(|source| RunError::Axes {
        path: path.to_path_buf(),
        source,
    })
}

/// The key points of a machine at each row of an axes CSV.
#[derive(Debug, Clone, PartialEq)]
pub struct MachineFk {
    /// The CSV: `x` when the axes give it, then `<point>_x,_y,_z` per key point.
    pub csv: String,
    /// The line printed (`out` is only named in it).
    pub line: String,
    /// The files read (no output may overwrite one).
    pub inputs: Vec<PathBuf>,
}

/// `formcam machine fk MACHINE --axes AXES -o POINTS`: every key point of
/// the machine file `machine` at each row of `axes`.
pub fn machine_fk(machine: &Path, axes: &Path, out: &Path) -> Result<MachineFk, RunError> {
    let m = read_machine(machine)?;
    let rows = read_axes(&m, axes)?;
    let with_x = rows.first().is_some_and(|r| r.x.is_some());
    let mut s = String::with_capacity(rows.len() * 40 * (m.points.len() + 1));
    let mut head: Vec<String> = Vec::new();
    if with_x {
        head.push("x".into());
    }
    for p in &m.points {
        for c in ["x", "y", "z"] {
            head.push(format!("{}_{c}", p.name));
        }
    }
    s.push_str(&head.join(","));
    s.push('\n');
    for AxesRow { x, q } in &rows {
        let mut cells: Vec<String> = Vec::new();
        if let Some(x) = x {
            cells.push(x.to_string());
        }
        for p in m.key_points(q) {
            cells.extend([p.x, p.y, p.z].map(|v| v.to_string()));
        }
        let _ = writeln!(s, "{}", cells.join(","));
    }
    let line = format!(
        "{}: {} rows, {} key points -> {}",
        m.name,
        rows.len(),
        m.points.len(),
        out.display()
    );
    Ok(MachineFk {
        csv: s,
        line,
        inputs: vec![machine.to_path_buf(), axes.to_path_buf()],
    })
}
