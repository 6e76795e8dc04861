//! What the checks found in the result's program, for `/api/violations`:
//! the report `formcam check` wrote (`check.json` in the folder), or else
//! formcam-sim's whole check run when the view opens
//! ([`formcam_sim::check_text_with`], as `formcam wind` and `formcam check`
//! run it): the axes, the collisions of the machine's solids and the bed,
//! and, when the job that made the result is found (the copy the folder
//! keeps, `job.toml`, else `summary.json`'s `job`), the mandrel grown by its
//! laminate and the free fibre. `checks` names the checks the view ran and
//! `unchecked` why one was left out. Each violation is passed on as the
//! report writes it (a kind the view does not know is still listed), with
//! the time spans of its first and worst block.

use std::path::Path;

use formcam_results::names;
use formcam_sim::{AxisLimits, MandrelCheck, check_text_with, check_timeline};
use serde::Serialize;
use serde_json::Value;
use ts_rs::TS;

use crate::ViewError;
use crate::folder::{ProgramFile, RunFolder};
use crate::timeline::Timeline;

/// `/api/violations`.
#[derive(Debug, Clone, Serialize, TS)]
pub struct Violations {
    /// `check.json` when read from the folder, else `check` (run by the view).
    pub source: &'static str,
    /// The checks the view ran (`source` `check`): `axes` (position,
    /// velocity, velocity jump, acceleration), `collisions` (the machine's
    /// solids and the bed), `mandrel` (the job's mandrel grown by its
    /// laminate, among the collisions) and `snag` (the free fibre); empty
    /// for `check.json`, whose checks `formcam` chose when it wrote it.
    pub checks: Vec<&'static str>,
    /// Why a check was left out of the view's own (the job that made the
    /// result not found, or a check that could not run), else `null`.
    pub unchecked: Option<String>,
    /// Whether no check failed.
    pub clean: bool,
    /// Every violation as the report writes it (`kind`, `axis` or `links`,
    /// `block`, `line`, `time_s`, ...), with `spans`: the `[start, end]`
    /// times (s) of its first and worst block.
    #[ts(type = "Array<Record<string, unknown>>")]
    pub violations: Vec<Value>,
    /// Every axis's position limits in NC units (`null` where unlimited).
    pub limits: Vec<AxisRange>,
}

/// An axis's position limits.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct AxisRange {
    /// NC address.
    pub axis: String,
    /// `deg` or `mm`.
    #[ts(type = "\"deg\" | \"mm\"")]
    pub unit: &'static str,
    /// Lower limit (`None` when unlimited).
    pub min: Option<f64>,
    /// Upper limit (`None` when unlimited).
    pub max: Option<f64>,
}

impl Violations {
    /// The violations of `tl`, the program of `folder`: `check.json` in the
    /// folder when there is one and `report` (the result is shown on the
    /// machine it was checked on), else formcam-sim's check run now.
    ///
    /// # Errors
    ///
    /// `check.json` unreadable, no JSON object or without a `violations`
    /// list, naming the file.
    pub fn of(folder: &RunFolder, tl: &Timeline, report: bool) -> Result<Self, ViewError> {
        let limits = AxisLimits::of(tl.machine());
        let path = folder.root.join(names::CHECK);
        let ran = if report && path.is_file() {
            Ran {
                source: names::CHECK,
                found: read_report(&path)?,
                checks: Vec::new(),
                unchecked: None,
            }
        } else {
            Ran::now(folder, tl)
        };
        let violations: Vec<Value> = ran
            .found
            .into_iter()
            .map(|mut v| {
                let spans: Vec<[f64; 2]> = ["block", "worst_block"]
                    .iter()
                    .filter_map(|k| v.get(*k).and_then(Value::as_u64))
                    .filter_map(|b| tl.block_span((b as usize).checked_sub(1)?))
                    .map(|(s, e)| [s, e])
                    .collect();
                if let Value::Object(m) = &mut v {
                    m.insert("spans".into(), serde_json::json!(spans));
                }
                v
            })
            .collect();
        Ok(Self {
            source: ran.source,
            checks: ran.checks,
            unchecked: ran.unchecked,
            clean: violations.is_empty(),
            violations,
            limits: limits
                .iter()
                .map(|l| AxisRange {
                    axis: l.name.clone(),
                    unit: if l.rotary { "deg" } else { "mm" },
                    min: Some(l.min).filter(|v| v.is_finite()),
                    max: Some(l.max).filter(|v| v.is_finite()),
                })
                .collect(),
        })
    }
}

/// The violations found, by which checks.
struct Ran {
    source: &'static str,
    found: Vec<Value>,
    checks: Vec<&'static str>,
    unchecked: Option<String>,
}

impl Ran {
    /// formcam-sim's check of the folder's program now: the whole check
    /// with the job's mandrel and fibre when the job is found, else (or
    /// when that fails) without them, else the axis checks alone.
    fn now(folder: &RunFolder, tl: &Timeline) -> Self {
        let mut unchecked = Vec::new();
        if let Some(program) = &folder.program {
            let mesh_dir = folder.machine_file.as_deref().and_then(Path::parent);
            let check = |mandrel: Option<&MandrelCheck>| {
                check_text_with(
                    &program.path,
                    &program.text,
                    tl.machine(),
                    "",
                    mesh_dir,
                    mandrel,
                )
            };
            match job_check(folder, program) {
                Ok(mandrel) => match check(Some(&mandrel)) {
                    Ok(r) => {
                        let mut checks = vec!["axes", "collisions", "mandrel"];
                        if mandrel.fibre().is_some() {
                            checks.push("snag");
                        } else {
                            unchecked.push("snag: the job has no free fibre".to_string());
                        }
                        return Self::found(&r.violations, checks, unchecked);
                    }
                    Err(e) => unchecked.push(format!("mandrel and snag: {e}")),
                },
                Err(why) => unchecked.push(format!("mandrel and snag: {why}")),
            }
            match check(None) {
                Ok(r) => return Self::found(&r.violations, vec!["axes", "collisions"], unchecked),
                Err(e) => unchecked.push(format!("collisions: {e}")),
            }
        }
        let found = check_timeline(tl.sim(), &AxisLimits::of(tl.machine()));
        Self::found(&found, vec!["axes"], unchecked)
    }

    /// The view's own check's violations.
    fn found(
        violations: &[formcam_sim::Violation],
        checks: Vec<&'static str>,
        unchecked: Vec<String>,
    ) -> Self {
        Self {
            source: "check",
            found: violations
                .iter()
                .map(|v| serde_json::to_value(v).unwrap_or(Value::Null))
                .collect(),
            checks,
            unchecked: (!unchecked.is_empty()).then(|| unchecked.join("; ")),
        }
    }
}

/// The mandrel check of the job that made the result (a `.wind` document
/// with the eye clearance the summary gives), planned now: the job's text
/// as it ran, the copy the folder keeps, with the files it names found
/// from the folder of the job `summary.json` names (`job`); without a copy
/// (a result written before formcam kept one), the job file itself. Why
/// not, in words.
fn job_check(folder: &RunFolder, program: &ProgramFile) -> Result<MandrelCheck, String> {
    let job = folder.job().ok_or("summary.json names no job")?;
    let clearance = folder
        .summary
        .get("eye_clearance_mm")
        .and_then(Value::as_f64);
    let (read, wind) = match folder.job_copy() {
        Some(copy) => {
            let base = job.parent().unwrap_or(Path::new(""));
            let wind = formcam_program::read_job_from(&copy, base, clearance)
                .map_err(|e| e.to_string())?;
            (copy, wind)
        }
        None if job.is_file() => {
            let wind = formcam_program::read_job(&job, clearance).map_err(|e| e.to_string())?;
            (job, wind)
        }
        None => {
            return Err(format!(
                "the job that made {} ({}) is not found",
                program.path.display(),
                job.display()
            ));
        }
    };
    formcam_program::mandrel_check(&wind)
        .map_err(|e| formcam_program::JobFileError::job(&read, e).to_string())
}

/// The `violations` of a report `formcam check` wrote.
fn read_report(path: &Path) -> Result<Vec<Value>, ViewError> {
    let bad = |problem: String| ViewError::Table {
        path: path.to_path_buf(),
        line: 0,
        problem,
    };
    let text = formcam_files::read_text(path).map_err(|source| ViewError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let value: Value = serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
    match value.get("violations") {
        Some(Value::Array(list)) => Ok(list.clone()),
        _ => Err(bad(
            "no list `violations` (a report of `formcam check`)".into()
        )),
    }
}
