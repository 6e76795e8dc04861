//! A winding result folder: its summary, the machine it names, the program
//! and the path table, read once when the view starts.

use std::path::{Path, PathBuf};

use formcam_machine::Machine;
use formcam_nc::Dialect;
use formcam_results::names::{self, REPORT, SUMMARY};
use formcam_results::winding::PATH;
use formcam_results::{Entry, Kind};
use serde_json::{Map, Value};

use crate::ViewError;

/// What a result folder holds, told apart by its files as
/// [`formcam_results::Kind::of`] tells it: a correction writes
/// `report.json` naming its measurements (a closed-loop simulation, one
/// listing its `rounds`) and no `summary.json`; a dressing's `summary.json`
/// has `dressing_time_s`; any other `summary.json` is a winding result's, a
/// [`ResultKind::Path`] one without `program_file`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, ts_rs::TS)]
#[serde(rename_all = "lowercase")]
pub enum ResultKind {
    /// `formcam wind`: the machine, the program, the path.
    Winding,
    /// `formcam dress`: the profile, the dresser's path, the program.
    Dressing,
    /// `formcam correct`: the measurements' deviations, the report; or
    /// `formcam correct simulate`: those of every round.
    Correction,
    /// A winding result without a program (its summary names no
    /// `program_file`): the path, its tables and plots.
    Path,
}

impl From<Kind> for ResultKind {
    fn from(kind: Kind) -> Self {
        match kind {
            Kind::Winding => Self::Winding,
            Kind::Dressing => Self::Dressing,
            Kind::Correction => Self::Correction,
            Kind::Path => Self::Path,
        }
    }
}

impl ResultKind {
    /// The kind of the result folder `root`.
    ///
    /// # Errors
    ///
    /// [`ViewError::NoFolder`], the summary's or report's read errors,
    /// [`ViewError::ResultsWithin`] for a folder of results (as `formcam
    /// demo` writes), or [`ViewError::UnknownResult`].
    pub fn of(root: &Path) -> Result<Self, ViewError> {
        if !root.is_dir() {
            return Err(ViewError::NoFolder {
                path: root.to_path_buf(),
            });
        }
        let keys = |name: &str| {
            read_summary(&root.join(name)).map(|m| {
                move |key: &str| match m.get(key) {
                    None => Entry::Absent,
                    Some(Value::Array(_)) => Entry::List,
                    Some(_) => Entry::Value,
                }
            })
        };
        if let Some(kind) = Kind::of(|name| root.join(name).is_file(), keys)? {
            return Ok(kind.into());
        }
        let within = results_within(root);
        if !within.is_empty() {
            return Err(ViewError::ResultsWithin {
                path: root.to_path_buf(),
                names: within.join(", "),
            });
        }
        Err(ViewError::UnknownResult {
            path: root.to_path_buf(),
        })
    }
}

/// The subfolders of `root` that look like results (a `summary.json` or a
/// `report.json`), by name.
fn results_within(root: &Path) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(root) else {
        return Vec::new();
    };
    let mut names: Vec<String> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.join(SUMMARY).is_file() || p.join(REPORT).is_file())
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    names.sort();
    names
}

/// What the view reads of a result folder.
#[derive(Debug, Clone)]
pub struct RunFolder {
    /// The folder.
    pub root: PathBuf,
    /// `summary.json`, as written.
    pub summary: Map<String, Value>,
    /// The machine the program runs on.
    pub machine: Machine,
    /// The machine file it was read from (`None`: a shipped machine).
    pub machine_file: Option<PathBuf>,
    /// The program file (`program.<ext>`), its text and dialect.
    pub program: Option<ProgramFile>,
    /// The path table (`path.csv`, or the first layer's), when written.
    pub path_table: Option<(PathBuf, String)>,
}

/// A program file of the result.
#[derive(Debug, Clone)]
pub struct ProgramFile {
    /// Where it is.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// The dialect its extension names.
    pub dialect: Dialect,
}

impl RunFolder {
    /// The machine file's folder (its meshes are named relative to it);
    /// none for a shipped machine.
    pub fn machine_dir(&self) -> Option<&Path> {
        self.machine_file.as_deref().and_then(Path::parent)
    }

    /// The job the summary names (`job`: its absolute path; a relative
    /// one, in a result written before formcam recorded it so, is taken
    /// from the folder the view runs in).
    pub fn job(&self) -> Option<PathBuf> {
        self.summary
            .get("job")
            .and_then(Value::as_str)
            .map(PathBuf::from)
    }

    /// The copy of the job as it ran the result keeps (`job.toml`, or
    /// `job.wind` for a `.wind` document), if it has one (a result written
    /// before formcam kept it has none).
    pub fn job_copy(&self) -> Option<PathBuf> {
        [names::JOB, names::JOB_WIND]
            .into_iter()
            .map(|name| self.root.join(name))
            .find(|p| p.is_file())
    }

    /// Reads the result folder `root`: `summary.json`, the machine (from
    /// `machine`, else the shipped machine or the machine file the summary
    /// names, relative to its job's folder), `program_file` and the path
    /// table.
    ///
    /// # Errors
    ///
    /// [`ViewError`] naming the file and the field; [`ViewError::NoProgram`]
    /// for a winding result without a program (the view plays one).
    pub fn open(root: &Path, machine: Option<&Path>) -> Result<Self, ViewError> {
        if !root.is_dir() {
            return Err(ViewError::NoFolder {
                path: root.to_path_buf(),
            });
        }
        let summary_path = root.join(SUMMARY);
        let summary = read_summary(&summary_path)?;
        if !summary.contains_key("program_file") {
            return Err(ViewError::NoProgram {
                path: root.to_path_buf(),
            });
        }
        let (machine, machine_file) = match machine {
            Some(path) => (load_machine(path)?, Some(path.to_path_buf())),
            None => summary_machine(&summary_path, &summary)?,
        };
        let program = match summary.get("program_file").and_then(Value::as_str) {
            Some(name) => Some(read_program(root, &summary_path, name)?),
            None => None,
        };
        Ok(Self {
            root: root.to_path_buf(),
            summary,
            machine,
            machine_file,
            program,
            path_table: read_path_table(root)?,
        })
    }
}

pub(crate) fn read_text(path: &Path) -> Result<String, ViewError> {
    formcam_files::read_text(path).map_err(|source| ViewError::Read {
        path: path.to_path_buf(),
        source,
    })
}

/// A JSON file holding an object (`summary.json`, `report.json`).
pub(crate) fn read_summary(path: &Path) -> Result<Map<String, Value>, ViewError> {
    let text = read_text(path)?;
    match serde_json::from_str::<Value>(&text) {
        Ok(Value::Object(m)) => Ok(m),
        Ok(_) => Err(ViewError::Summary {
            path: path.to_path_buf(),
            reason: "the top level is no object".into(),
        }),
        Err(e) => Err(ViewError::Summary {
            path: path.to_path_buf(),
            reason: e.to_string(),
        }),
    }
}

/// A machine file (URDF or TOML by its extension).
pub fn load_machine(path: &Path) -> Result<Machine, ViewError> {
    let text = read_text(path)?;
    Machine::from_file_text(path, &text).map_err(|source| ViewError::Machine {
        path: path.to_path_buf(),
        source,
    })
}

/// The machine the summary names: `machine_shipped`, or `machine_file`
/// relative to the folder of `job` (the job file's absolute path, found
/// from any folder; a relative one, in a result written before formcam
/// recorded it so, is taken from the folder the view runs in), and that
/// file.
pub(crate) fn summary_machine(
    path: &Path,
    summary: &Map<String, Value>,
) -> Result<(Machine, Option<PathBuf>), ViewError> {
    if let Some(name) = summary.get("machine_shipped").and_then(Value::as_str) {
        let shipped =
            formcam_machine::shipped::shipped(name).ok_or_else(|| ViewError::UnknownShipped {
                path: path.to_path_buf(),
                name: formcam_files::quote(name).to_string(),
            })?;
        return Machine::from_file_text(Path::new(name), shipped.text)
            .map(|m| (m, None))
            .map_err(|source| ViewError::Machine {
                path: PathBuf::from(name),
                source,
            });
    }
    let file =
        summary
            .get("machine_file")
            .and_then(Value::as_str)
            .ok_or(ViewError::SummaryField {
                path: path.to_path_buf(),
                field: "machine_file",
                what: "the machine the program runs on; give it with --machine",
            })?;
    let job = PathBuf::from(summary.get("job").and_then(Value::as_str).unwrap_or(""));
    let base = job.parent().unwrap_or(Path::new(""));
    let machine = base.join(file);
    if !machine.is_file() {
        return Err(ViewError::MachineNotFound {
            summary: path.to_path_buf(),
            machine,
            job,
        });
    }
    Ok((load_machine(&machine)?, Some(machine)))
}

fn read_program(root: &Path, summary: &Path, name: &str) -> Result<ProgramFile, ViewError> {
    let path = root.join(name);
    let dialect = Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .and_then(Dialect::from_extension)
        .filter(|_| !name.contains(['/', '\\']))
        .ok_or_else(|| ViewError::ProgramDialect {
            path: summary.to_path_buf(),
            name: formcam_files::quote(name).to_string(),
        })?;
    let text = read_text(&path)?;
    Ok(ProgramFile {
        path,
        text,
        dialect,
    })
}

/// `path.csv`, or that of the first layer (`layer-01/path.csv`).
pub(crate) fn read_path_table(root: &Path) -> Result<Option<(PathBuf, String)>, ViewError> {
    for path in [
        root.join(PATH.file),
        root.join(names::layer_dir(1)).join(PATH.file),
    ] {
        if path.is_file() {
            let text = read_text(&path)?;
            return Ok(Some((path, text)));
        }
    }
    Ok(None)
}
