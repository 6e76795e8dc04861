//! A correction result (`formcam correct JOB -o OUT`): the deviation map of
//! the measurements its `report.json` names — every measured point at its
//! nominal place, with its deviation — and the deviation per section and
//! per run of the report's history (`/api/correction`). A closed-loop
//! simulation (`formcam correct simulate`) is shown the same way: the map
//! of every round's CMM report (`cmm-<k>.csv`), the last round's first.

use std::path::{Component, Path, PathBuf};

use formcam_correct::{MeasuredPoint, Measurements};
use serde::Serialize;
use serde_json::{Map, Value};

use crate::ViewError;

/// What `/api/correction` sends.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CorrectionBody {
    /// The measurement file shown (the report's `measurements`, or the last
    /// round's CMM report), its path made plain ([`plain_path`]).
    pub measurements: String,
    /// The closed loop's scenario file, made plain; `None` for a correction.
    pub scenario: Option<String>,
    /// The corrected program's file in the folder (the last round's
    /// program of a closed loop), if there.
    pub program: Option<String>,
    /// The map of `measurements`.
    #[serde(flatten)]
    pub map: DeviationMap,
    /// A closed loop's rounds in order, each with its map (empty for a
    /// correction).
    pub rounds: Vec<RoundMap>,
    /// The report's keys (`max_deviation_mm`, `history`, or a loop's
    /// `rounds` and `section_study`, ...), as written.
    pub report: Map<String, Value>,
}

/// The measured points of one CMM report at their nominal places, with
/// their deviations.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct DeviationMap {
    /// Every measured point's nominal `x`, mm.
    pub x: Vec<f64>,
    /// Nominal `y`, mm.
    pub y: Vec<f64>,
    /// Nominal `z`, mm.
    pub z: Vec<f64>,
    /// The deviation, mm: along the nominal normal where the report gives
    /// it (positive outward), else actual − nominal in `z`.
    pub deviation: Vec<f64>,
    /// Each point's section (an index into `sections`).
    pub section: Vec<usize>,
    /// Per section in the report's order.
    pub sections: Vec<SectionStats>,
}

/// One round of a closed loop: what the CMM saw of the part it made.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoundMap {
    /// The round (0: the nominal program, before any correction).
    pub iteration: usize,
    /// Its CMM report in the folder (`cmm-<k>.csv`).
    pub measurements: String,
    /// Its program in the folder (`program-<k>.nc`).
    pub program: String,
    /// The map of its CMM report.
    #[serde(flatten)]
    pub map: DeviationMap,
}

/// One section's deviations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SectionStats {
    /// The section's name.
    pub name: String,
    /// Its points.
    pub points: usize,
    /// The least deviation, mm.
    pub min: f64,
    /// The largest, mm.
    pub max: f64,
    /// The RMS deviation, mm.
    pub rms: f64,
}

/// The signed deviation of a point: along its normal where given, else in `z`.
pub fn signed_deviation(p: &MeasuredPoint) -> f64 {
    let d = [
        p.actual[0] - p.nominal[0],
        p.actual[1] - p.nominal[1],
        p.actual[2] - p.nominal[2],
    ];
    match p.normal {
        Some(n) => d[0] * n[0] + d[1] * n[1] + d[2] * n[2],
        None => d[2],
    }
}

/// `name` as a reader wants to see it: `.` and `..` resolved lexically
/// (`a/b/../c` is `a/c`; a `..` at the start stays), and relative to
/// `root` when it lies inside it.
pub fn plain_path(name: &str, root: &Path) -> String {
    let plain = lexical(Path::new(name));
    let within = [root.to_path_buf(), lexical(root)]
        .into_iter()
        .chain(root.canonicalize().ok())
        .find_map(|r| plain.strip_prefix(&r).ok().map(Path::to_path_buf));
    match within {
        Some(rel) if !rel.as_os_str().is_empty() => rel.display().to_string(),
        _ => plain.display().to_string(),
    }
}

/// `p` with `.` dropped and each `..` taking the name before it away.
fn lexical(p: &Path) -> PathBuf {
    let mut out: Vec<Component<'_>> = Vec::new();
    for c in p.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => match out.last() {
                Some(Component::Normal(_)) => {
                    out.pop();
                }
                // `/..` is `/`.
                Some(Component::RootDir | Component::Prefix(_)) => {}
                _ => out.push(c),
            },
            _ => out.push(c),
        }
    }
    if out.is_empty() {
        return PathBuf::from(".");
    }
    out.iter().collect()
}

/// A measurement file, read and parsed (CSV, or DMIS by the extension);
/// errors name `report` and the file.
fn read_measurements(report: &Path, path: &Path) -> Result<Measurements, ViewError> {
    let text = crate::folder::read_text(path)?;
    Measurements::from_file_text(path, &text).map_err(|source| ViewError::Measurements {
        report: report.to_path_buf(),
        measurements: path.to_path_buf(),
        source: Box::new(source),
    })
}

impl CorrectionBody {
    /// Reads the correction result in `root`: `report.json` (already read
    /// as `report`) and the measurements it names (a relative name is
    /// taken from the folder `formcam view` runs in, as it was for
    /// `formcam correct`; CSV, or DMIS by the extension) — or, for a
    /// closed loop's report (its `rounds`, no `measurements`), each
    /// round's `cmm-<k>.csv` in `root`.
    ///
    /// # Errors
    ///
    /// [`ViewError::Read`] or [`ViewError::Measurements`] naming the report
    /// and the file.
    pub fn read(root: &Path, report: Map<String, Value>) -> Result<Self, ViewError> {
        if !report.contains_key("measurements") && report.contains_key("rounds") {
            return Self::read_loop(root, report);
        }
        let report_path = root.join("report.json");
        let name = report
            .get("measurements")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string();
        let m = read_measurements(&report_path, Path::new(&name))?;
        let program = std::fs::read_dir(root).ok().and_then(|d| {
            d.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| n.starts_with("corrected.") && !n.ends_with(".svg"))
                .min()
        });
        Ok(Self::of(&m, plain_path(&name, root), program, report))
    }

    /// A closed loop's result: the map of each round the report lists
    /// (`cmm-<iteration>.csv`), the last one's on top.
    fn read_loop(root: &Path, report: Map<String, Value>) -> Result<Self, ViewError> {
        let report_path = root.join("report.json");
        let rounds = report
            .get("rounds")
            .and_then(Value::as_array)
            .map(Vec::as_slice)
            .unwrap_or_default();
        let mut maps = Vec::with_capacity(rounds.len());
        for (k, r) in rounds.iter().enumerate() {
            let iteration = r
                .get("iteration")
                .and_then(Value::as_u64)
                .map_or(k, |i| i as usize);
            let measurements = format!("cmm-{iteration}.csv");
            let m = read_measurements(&report_path, &root.join(&measurements))?;
            maps.push(RoundMap {
                iteration,
                measurements,
                program: format!("program-{iteration}.nc"),
                map: DeviationMap::of(&m),
            });
        }
        let last = maps.last().ok_or_else(|| ViewError::SummaryField {
            path: report_path.clone(),
            field: "rounds",
            what: "a closed loop's rounds, at least one",
        })?;
        Ok(Self {
            measurements: last.measurements.clone(),
            scenario: report
                .get("scenario")
                .and_then(Value::as_str)
                .map(|s| plain_path(s, root)),
            program: Some(last.program.clone()).filter(|p| root.join(p).is_file()),
            map: last.map.clone(),
            rounds: maps,
            report,
        })
    }

    /// The map of `m`.
    pub fn of(
        m: &Measurements,
        measurements: String,
        program: Option<String>,
        report: Map<String, Value>,
    ) -> Self {
        Self {
            measurements,
            scenario: None,
            program,
            map: DeviationMap::of(m),
            rounds: Vec::new(),
            report,
        }
    }
}

impl DeviationMap {
    /// The map of `m`: its points in order, their deviations, per section.
    pub fn of(m: &Measurements) -> Self {
        let mut map = Self::default();
        for (k, s) in m.sections.iter().enumerate() {
            let devs: Vec<f64> = s.points.iter().map(signed_deviation).collect();
            for (p, d) in s.points.iter().zip(&devs) {
                map.x.push(p.nominal[0]);
                map.y.push(p.nominal[1]);
                map.z.push(p.nominal[2]);
                map.deviation.push(*d);
                map.section.push(k);
            }
            let n = devs.len().max(1) as f64;
            map.sections.push(SectionStats {
                name: s.name.clone(),
                points: devs.len(),
                min: devs.iter().copied().fold(f64::INFINITY, f64::min),
                max: devs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                rms: (devs.iter().map(|d| d * d).sum::<f64>() / n).sqrt(),
            });
        }
        map
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    #[test]
    fn deviations_along_the_normal_and_per_section() {
        let csv = "section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act,nx,ny,nz\n\
                   S1,1,0,0,1,0.3,0,1.4,0.6,0,0.8\n\
                   S1,2,10,0,1,10,0,0.9,0,0,1\n\
                   S2,1,0,5,2,0,5,2.2,0,0,1\n";
        let m = Measurements::from_csv(csv).unwrap();
        let b = CorrectionBody::of(&m, "cmm.csv".into(), None, Map::new()).map;
        assert_eq!(b.x, [0.0, 10.0, 0.0]);
        assert_eq!(b.y, [0.0, 0.0, 5.0]);
        assert_eq!(b.section, [0, 0, 1]);
        // 0.3 * 0.6 + 0.4 * 0.8 = 0.5 along the normal.
        let want = [0.5, -0.1, 0.2];
        for (d, w) in b.deviation.iter().zip(want) {
            assert!((d - w).abs() < 1e-12, "{d} {w}");
        }
        assert_eq!(b.sections.len(), 2);
        assert_eq!(b.sections[0].points, 2);
        assert!((b.sections[0].min + 0.1).abs() < 1e-12);
        assert!((b.sections[0].max - 0.5).abs() < 1e-12);
        assert!((b.sections[0].rms - (0.13f64).sqrt()).abs() < 1e-12);
        assert!((b.sections[1].rms - 0.2).abs() < 1e-12);
    }

    #[test]
    fn paths_are_resolved_lexically_and_made_relative_to_the_folder() {
        let root = Path::new("/data/run/out");
        assert_eq!(
            plain_path("/data/src/crates/cli/../../examples/correct/cmm.csv", root),
            "/data/src/examples/correct/cmm.csv"
        );
        assert_eq!(plain_path("./a/./b/../c.csv", root), "a/c.csv");
        assert_eq!(plain_path("../x/../y.csv", root), "../y.csv");
        assert_eq!(plain_path("/../a.csv", root), "/a.csv");
        assert_eq!(
            plain_path("/data/run/out/sub/../cmm-3.csv", root),
            "cmm-3.csv"
        );
        assert_eq!(
            plain_path("/data/run/outer/cmm.csv", root),
            "/data/run/outer/cmm.csv"
        );
        assert_eq!(plain_path("/data/run/out", root), "/data/run/out");
    }
}
