//! What the checks found in the result's program, for `/api/violations`:
//! the report `formcam check` wrote (`check.json` in the folder), or the
//! simulator's axis checks run on the timeline when the view opens. Each
//! violation is passed on as the report writes it (a kind the view does not
//! know is still listed), with the time spans of its first and worst block.

use std::path::Path;

use formcam_sim::{AxisLimits, check_timeline};
use serde::Serialize;
use serde_json::Value;

use crate::ViewError;
use crate::timeline::Timeline;

/// `/api/violations`.
#[derive(Debug, Clone, Serialize)]
pub struct Violations {
    /// `check.json` when read from the folder, else `check` (run by the view).
    pub source: &'static str,
    /// Whether no check failed.
    pub clean: bool,
    /// Every violation as the report writes it (`kind`, `axis` or `links`,
    /// `block`, `line`, `time_s`, ...), with `spans`: the `[start, end]`
    /// times (s) of its first and worst block.
    pub violations: Vec<Value>,
    /// Every axis's position limits in NC units (`null` where unlimited).
    pub limits: Vec<AxisRange>,
}

/// An axis's position limits.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisRange {
    /// NC address.
    pub axis: String,
    /// `deg` or `mm`.
    pub unit: &'static str,
    /// Lower limit (`None` when unlimited).
    pub min: Option<f64>,
    /// Upper limit (`None` when unlimited).
    pub max: Option<f64>,
}

impl Violations {
    /// The violations of `tl`'s program: `check.json` under `root` when
    /// there is one and `report` (the result is shown on the machine it was
    /// checked on), else the simulator's axis checks on `tl`.
    ///
    /// # Errors
    ///
    /// `check.json` unreadable, no JSON object or without a `violations`
    /// list, naming the file.
    pub fn of(root: &Path, tl: &Timeline, report: bool) -> Result<Self, ViewError> {
        let limits = AxisLimits::of(tl.machine());
        let path = root.join("check.json");
        let (source, found) = if report && path.is_file() {
            ("check.json", read_report(&path)?)
        } else {
            let found = check_timeline(tl.sim(), &limits)
                .iter()
                .map(|v| serde_json::to_value(v).unwrap_or(Value::Null))
                .collect();
            ("check", found)
        };
        let violations: Vec<Value> = found
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
            source,
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
