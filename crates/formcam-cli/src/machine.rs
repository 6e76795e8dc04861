//! `formcam machine show|fk`: reading machine files (or shipped machines by name).

use std::fmt::Write as _;
use std::path::Path;

use formcam_machine::{AxesRow, Machine, read_axes_csv};

use crate::CliError;
use crate::output::write_files;

/// Reads a machine file; errors name the file, the link or point, and the field.
pub fn load(path: &Path) -> Result<Machine, CliError> {
    let text = formcam_files::read_text(path).map_err(|e| CliError::ReadMachine {
        path: path.to_path_buf(),
        source: e.into(),
    })?;
    parse(path, &text)
}

/// A machine from the text of its file (named `path` in errors; URDF or
/// TOML by its extension).
pub fn parse(path: &Path, text: &str) -> Result<Machine, CliError> {
    Machine::from_file_text(path, text).map_err(|source| CliError::Machine {
        path: path.to_path_buf(),
        source,
    })
}

/// `formcam machine show MACHINE`: a machine file, or a shipped machine by
/// name when no such file exists.
pub fn show(path: &Path) -> Result<String, CliError> {
    let name = path.to_string_lossy();
    match formcam_machine::shipped::shipped(&name) {
        Some(s) if !path.exists() => Ok(parse(path, s.text)?.table()),
        _ => Ok(load(path)?.table()),
    }
}

/// The rows of an axes CSV for `m`.
fn read_axes(m: &Machine, path: &Path) -> Result<Vec<AxesRow>, CliError> {
    let text = formcam_files::read_text(path).map_err(|e| CliError::ReadAxes {
        path: path.to_path_buf(),
        source: e.into(),
    })?;
    read_axes_csv(m, &text).map_err(|source| CliError::Axes {
        path: path.to_path_buf(),
        source,
    })
}

/// `formcam machine fk MACHINE --axes AXES -o POINTS`.
pub fn fk(machine: &Path, axes: &Path, out: &Path) -> Result<String, CliError> {
    let m = load(machine)?;
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
    write_files(
        &[(out.to_path_buf(), s.as_bytes())],
        &[machine.to_path_buf(), axes.to_path_buf()],
    )?;
    Ok(format!(
        "{}: {} rows, {} key points -> {}",
        m.name,
        rows.len(),
        m.points.len(),
        out.display()
    ))
}
