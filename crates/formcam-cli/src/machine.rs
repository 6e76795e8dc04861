//! `formcam machine show|fk`: reading machine files (or shipped machines by name).

use std::fmt::Write as _;
use std::path::Path;

use formcam_machine::Machine;

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

/// A row of an axes file: `x` when given, the axes in the machine's order (rad, mm).
type AxesRow = (Option<f64>, Vec<f64>);

/// The rows of an axes CSV.
fn read_axes(m: &Machine, path: &Path) -> Result<Vec<AxesRow>, CliError> {
    let text = formcam_files::read_text(path).map_err(|e| CliError::ReadAxes {
        path: path.to_path_buf(),
        source: e.into(),
    })?;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let (_, header) = lines.next().ok_or_else(|| CliError::AxesEmpty {
        path: path.to_path_buf(),
    })?;
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let x_col = names.iter().position(|n| *n == "x");
    let cols: Vec<usize> = m
        .axes
        .iter()
        .map(|a| {
            names
                .iter()
                .position(|n| *n == a.name)
                .ok_or_else(|| CliError::AxesColumn {
                    path: path.to_path_buf(),
                    axis: a.name.clone(),
                    axes: m
                        .axes
                        .iter()
                        .map(|a| a.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                })
        })
        .collect::<Result<_, _>>()?;
    let mut rows = Vec::new();
    for (i, line) in lines {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |c: usize, name: &str| -> Result<f64, CliError> {
            cells
                .get(c)
                .and_then(|s| s.parse::<f64>().ok())
                .filter(|v| v.is_finite())
                .ok_or_else(|| CliError::AxesNumber {
                    path: path.to_path_buf(),
                    line: i + 1,
                    column: name.to_owned(),
                })
        };
        let x = x_col.map(|c| num(c, "x")).transpose()?;
        let q = m
            .axes
            .iter()
            .zip(&cols)
            .map(|(a, &c)| {
                let v = num(c, &a.name)?;
                Ok(if a.is_rotary() { v.to_radians() } else { v })
            })
            .collect::<Result<Vec<f64>, CliError>>()?;
        rows.push((x, q));
    }
    Ok(rows)
}

/// `formcam machine fk MACHINE --axes AXES -o POINTS`.
pub fn fk(machine: &Path, axes: &Path, out: &Path) -> Result<String, CliError> {
    let m = load(machine)?;
    let rows = read_axes(&m, axes)?;
    let with_x = rows.first().is_some_and(|r| r.0.is_some());
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
    for (x, q) in &rows {
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
