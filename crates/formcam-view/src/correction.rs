//! A correction result (`formcam correct JOB -o OUT`): the deviation map of
//! the measurements its `report.json` names — every measured point at its
//! nominal place, with its deviation — and the deviation per section and
//! per run of the report's history (`/api/correction`). A closed-loop
//! simulation (`formcam correct simulate`) is shown the same way: the map
//! of every round's CMM report (`cmm-<k>.csv`), the last round's first.
//!
//! For the page's 3-D view every map carries its deviation at the vertices
//! of the nominal surface ([`SurfaceMesh`]: the measured sections' grid,
//! two triangles per facet). A correction's body also carries the next
//! part predicted from the corrected program (`predicted-cmm.csv`, the
//! deviation after) and what happened to each node of the program
//! (`node-status.csv`, [`NodeMarks`]); a closed loop's "after" is its next
//! round.

use std::path::{Component, Path, PathBuf};

use formcam_correct::{Grid, MeasuredPoint, Measurements, Placement};
use formcam_results::correction::{NODE_STATUS, PREDICTED, node_status};
use formcam_results::names;
use serde::Serialize;
use serde_json::{Map, Value};
use ts_rs::TS;

use crate::{Table, ViewError};

/// The most program nodes [`NodeMarks`] sends (one in every `every` past
/// it); the counts are always of every node.
pub const NODE_MARKS: usize = 100_000;

/// What `/api/correction` sends.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
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
    #[ts(type = "Record<string, unknown>")]
    pub report: Map<String, Value>,
    /// The nominal surface of the map's sections, `None` where they make
    /// no grid (fewer than two sections, ...).
    pub surface: Option<SurfaceMesh>,
    /// A correction's prediction of the next part, made on the corrected
    /// mould (`predicted-cmm.csv`): the deviation after; `None` for a
    /// closed loop (its next round is the after) or a folder without it.
    pub after: Option<DeviationMap>,
    /// What happened to each node of a correction's program
    /// (`node-status.csv`); `None` for a closed loop.
    pub nodes: Option<NodeMarks>,
}

/// The nominal surface meshed from the measured sections: the vertices of
/// formcam-correct's [`Grid`] as measured (`points_per_section` a row,
/// section after section in their spatial order), two triangles per facet.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct SurfaceMesh {
    /// Points per section (vertices a row).
    pub nu: usize,
    /// Sections (rows).
    pub nv: usize,
    /// The vertices `[x, y, z]`, mm, row `j` vertex `i` at `j * nu + i`.
    pub vertices: Vec<[f64; 3]>,
    /// Vertex indices, three per triangle, counter-clockwise seen along
    /// the grid's normal.
    pub triangles: Vec<[u32; 3]>,
}

/// The program's nodes marked by what the correction did with them.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
pub struct NodeMarks {
    /// The file read (`node-status.csv`).
    pub file: String,
    /// Each node sent: `x`, mm (before the correction).
    pub x: Vec<f64>,
    /// `y`, mm.
    pub y: Vec<f64>,
    /// `z`, mm.
    pub z: Vec<f64>,
    /// Where each node sent lies.
    pub placement: Vec<Placement>,
    /// Whether each node sent moved (a displacement other than 0).
    pub moved: Vec<bool>,
    /// One node in `every` is sent (1: all of them).
    pub every: usize,
    /// Every node counted, sent or not.
    pub counts: NodeCounts,
}

/// The nodes of a program counted by what happened to them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, TS)]
pub struct NodeCounts {
    /// Every movable node.
    pub nodes: usize,
    /// Nodes moved (inside or extrapolated), as the report's
    /// `nodes_corrected`.
    pub moved: usize,
    /// Nodes over the measured area.
    pub inside: usize,
    /// Nodes beyond it within the margin, corrected by extrapolation.
    pub extrapolated: usize,
    /// Nodes beyond the margin, left as they were.
    pub outside: usize,
    /// Nodes with a coordinate the program never set, left as they were.
    pub unknown: usize,
}

/// The measured points of one CMM report at their nominal places, with
/// their deviations.
#[derive(Debug, Clone, Default, PartialEq, Serialize, TS)]
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
    /// The signed deviation at each vertex of the map's [`SurfaceMesh`]
    /// (empty where the sections make no grid), mm.
    pub vertex_deviation: Vec<f64>,
}

/// One round of a closed loop: what the CMM saw of the part it made.
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
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
#[derive(Debug, Clone, PartialEq, Serialize, TS)]
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
    /// as `report`) and the measurements it names (absolute, as formcam
    /// records them; a relative name, in a report written before it did,
    /// is taken from the folder `formcam view` runs in, as it was for
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
        let report_path = root.join(names::REPORT);
        let name = report
            .get("measurements")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string();
        let m = read_measurements(&report_path, Path::new(&name))?;
        let program = std::fs::read_dir(root).ok().and_then(|d| {
            d.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| names::is_corrected(n) && !n.ends_with(".svg"))
                .min()
        });
        let mut body = Self::of(&m, plain_path(&name, root), program, report);
        let predicted = root.join(PREDICTED.file);
        if predicted.is_file() {
            body.after = Some(DeviationMap::of(&read_table_measurements(&predicted)?));
        }
        let status = root.join(NODE_STATUS.file);
        if status.is_file() {
            body.nodes = Some(NodeMarks::read(&status, NODE_MARKS)?);
        }
        Ok(body)
    }

    /// A closed loop's result: the map of each round the report lists
    /// (`cmm-<iteration>.csv`), the last one's on top.
    fn read_loop(root: &Path, report: Map<String, Value>) -> Result<Self, ViewError> {
        let report_path = root.join(names::REPORT);
        let rounds = report
            .get("rounds")
            .and_then(Value::as_array)
            .map(Vec::as_slice)
            .unwrap_or_default();
        let mut maps = Vec::with_capacity(rounds.len());
        // The last round's nominal surface (every round probes the same).
        let mut surface = None;
        for (k, r) in rounds.iter().enumerate() {
            let iteration = r
                .get("iteration")
                .and_then(Value::as_u64)
                .map_or(k, |i| i as usize);
            let measurements = names::round_cmm(iteration);
            let m = read_measurements(&report_path, &root.join(&measurements))?;
            surface = SurfaceMesh::of(&m);
            maps.push(RoundMap {
                iteration,
                measurements,
                program: names::round_program(iteration),
                map: DeviationMap::of(&m),
            });
        }
        let last = maps.last().ok_or_else(|| ViewError::SummaryField {
            path: report_path.clone(),
            field: "rounds",
            what: "a closed loop's rounds, at least one",
        })?;
        Ok(Self {
            surface,
            after: None,
            nodes: None,
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
            surface: SurfaceMesh::of(m),
            after: None,
            nodes: None,
        }
    }
}

/// A result's own CMM table (`predicted-cmm.csv`), errors naming it.
fn read_table_measurements(path: &Path) -> Result<Measurements, ViewError> {
    let text = crate::folder::read_text(path)?;
    Measurements::from_file_text(path, &text).map_err(|e| ViewError::Table {
        path: path.to_path_buf(),
        line: 0,
        problem: e.to_string(),
    })
}

/// The grid of `m`'s sections as measured; `None` where they make none.
fn grid_of(m: &Measurements) -> Option<Grid> {
    Grid::from_measurements(m, None).ok()
}

impl SurfaceMesh {
    /// The nominal surface of `m`'s sections; `None` where they make no
    /// grid.
    pub fn of(m: &Measurements) -> Option<Self> {
        grid_of(m).map(|g| Self::of_grid(&g))
    }

    /// The mesh of `g`'s nominal points.
    pub fn of_grid(g: &Grid) -> Self {
        let (nu, nv) = (g.nu, g.nv);
        let at = |i: usize, j: usize| (j * nu + i) as u32;
        let mut triangles = Vec::with_capacity(2 * g.facets());
        for j in 0..nv.saturating_sub(1) {
            for i in 0..nu.saturating_sub(1) {
                triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        Self {
            nu,
            nv,
            vertices: g.nominal.clone(),
            triangles,
        }
    }
}

/// The signed deviation at each vertex of `g`: along the grid's normal
/// where the report gives normals (as [`signed_deviation`]), else in `z`.
fn vertex_deviation(g: &Grid) -> Vec<f64> {
    let mut out = Vec::with_capacity(g.nu * g.nv);
    for j in 0..g.nv {
        for i in 0..g.nu {
            let d = g.deviation_at(i, j);
            out.push(match g.normal {
                Some(_) => {
                    let n = g.normal_at(i, j);
                    d[0] * n[0] + d[1] * n[1] + d[2] * n[2]
                }
                None => d[2],
            });
        }
    }
    out
}

impl NodeMarks {
    /// Reads the node status file `path` (`line, x, y, z, placement, dx,
    /// dy, dz`), sending at most about `most` nodes (one in every
    /// `every`) and counting all of them.
    ///
    /// # Errors
    ///
    /// [`ViewError::Read`], or [`ViewError::Table`] naming the line of a
    /// missing column, a bad number or an unknown placement.
    pub fn read(path: &Path, most: usize) -> Result<Self, ViewError> {
        let t = Table::read(path)?;
        let [x, y, z, dx, dy, dz] = [
            node_status::X,
            node_status::Y,
            node_status::Z,
            node_status::DX,
            node_status::DY,
            node_status::DZ,
        ]
        .map(|c| t.numbers(c));
        let (x, y, z, dx, dy, dz) = (x?, y?, z?, dx?, dy?, dz?);
        let placement = t
            .words(node_status::PLACEMENT)?
            .into_iter()
            .enumerate()
            .map(|(k, w)| {
                Placement::from_name(w).ok_or_else(|| ViewError::Table {
                    path: path.to_path_buf(),
                    line: k + 2,
                    problem: format!(
                        "`{}` is `{}`: inside, extrapolated, outside or unknown",
                        node_status::PLACEMENT.name,
                        formcam_files::quote(w)
                    ),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let moved: Vec<bool> = (0..t.len())
            .map(|k| dx[k] != 0.0 || dy[k] != 0.0 || dz[k] != 0.0)
            .collect();
        let mut counts = NodeCounts {
            nodes: t.len(),
            moved: moved.iter().filter(|m| **m).count(),
            ..NodeCounts::default()
        };
        for p in &placement {
            match p {
                Placement::Inside => counts.inside += 1,
                Placement::Extrapolated => counts.extrapolated += 1,
                Placement::Outside => counts.outside += 1,
                Placement::Unknown => counts.unknown += 1,
            }
        }
        let every = t.len().div_ceil(most.max(1)).max(1);
        let pick = |v: &[f64]| v.iter().step_by(every).copied().collect::<Vec<_>>();
        Ok(Self {
            file: NODE_STATUS.file.to_owned(),
            x: pick(&x),
            y: pick(&y),
            z: pick(&z),
            placement: placement.iter().step_by(every).copied().collect(),
            moved: moved.iter().step_by(every).copied().collect(),
            every,
            counts,
        })
    }
}

impl DeviationMap {
    /// The map of `m`: its points in order, their deviations, per section.
    pub fn of(m: &Measurements) -> Self {
        let mut map = Self {
            vertex_deviation: grid_of(m).map(|g| vertex_deviation(&g)).unwrap_or_default(),
            ..Self::default()
        };
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
        let csv = PREDICTED.header_with(&[], true)
            + "S1,1,0,0,1,0.3,0,1.4,0.6,0,0.8\n\
                   S1,2,10,0,1,10,0,0.9,0,0,1\n\
                   S2,1,0,5,2,0,5,2.2,0,0,1\n";
        let m = Measurements::from_csv(&csv).unwrap();
        let b = CorrectionBody::of(&m, names::round_cmm(0), None, Map::new()).map;
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
    fn nodes_are_counted_every_one_and_sent_thinned() {
        let dir = std::env::temp_dir().join(format!("formcam-view-nodes-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(NODE_STATUS.file);
        std::fs::write(
            &path,
            NODE_STATUS.header()
                + "3,0,0,1,inside,0,0,-0.1\n4,1,0,1,inside,0,0,0\n5,2,0,1,extrapolated,0,0.01,0\n\
             6,3,0,1,outside,0,0,0\n7,4,0,1,unknown,0,0,0\n",
        )
        .unwrap();
        let all = NodeMarks::read(&path, 10).unwrap();
        assert_eq!(
            all.counts,
            NodeCounts {
                nodes: 5,
                moved: 2,
                inside: 2,
                extrapolated: 1,
                outside: 1,
                unknown: 1,
            }
        );
        assert_eq!((all.every, all.x.len()), (1, 5));
        assert_eq!(all.moved, [true, false, true, false, false]);
        assert_eq!(all.placement[2], Placement::Extrapolated);
        // At most two: one in three sent, every one counted.
        let few = NodeMarks::read(&path, 2).unwrap();
        assert_eq!((few.every, few.x.clone()), (3, vec![0.0, 3.0]));
        assert_eq!(few.placement, [Placement::Inside, Placement::Outside]);
        assert_eq!(few.counts, all.counts);
        std::fs::write(&path, NODE_STATUS.header() + "3,0,0,1,beside,0,0,0\n").unwrap();
        let e = NodeMarks::read(&path, 10).unwrap_err().to_string();
        assert!(
            e.ends_with(":2: `placement` is `beside`: inside, extrapolated, outside or unknown"),
            "{e}"
        );
        let _ = std::fs::remove_dir_all(&dir);
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
