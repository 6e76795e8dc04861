//! A winding result without a program (`/api/path`): the path a job wound
//! and its tables, no timeline. The mandrel carries the pass of
//! `path.csv`; the band is that pass laid once per circuit, each circuit
//! turned by a full turn over the circuits (the starts a closed pattern
//! covers, in that order rather than the pattern's); the eye trajectory is
//! `eye.csv`'s over one circuit. A result naming a machine shows it at the
//! first row of its `axes.csv` (or at home), the mandrel, band and eye
//! placed on its mandrel link; one without a machine shows them alone.

use std::path::Path;

use formcam_machine::Machine;
use formcam_results::names;
use formcam_results::winding::{AXES, EYE, eye, path};
use nalgebra::{Isometry3, Point3};
use serde::Serialize;
use serde_json::{Map, Value};
use ts_rs::TS;

use crate::ViewError;
use crate::band::BAND_POINTS;
use crate::folder::{load_machine, summary_machine};
use crate::mesh::DrawnMesh;
use crate::scene::{LinkScene, MachineScene, thin};
use crate::table::Table;

/// What `/api/path` sends.
#[derive(Debug, Clone, Serialize, TS)]
pub struct PathBody {
    /// Every link's world pose `[x, y, z, qx, qy, qz, qw]` as shown.
    pub poses: Vec<[f64; 7]>,
    /// What the machine's pose is: `home`, `axes.csv row 1`, or `none`
    /// (no machine: the mandrel alone).
    pub pose: String,
    /// The band: the pass laid per circuit, in the mandrel link's frame.
    pub band: PathBand,
    /// The eye trajectory over one circuit (`eye.csv`), world mm, when
    /// the result has one.
    pub eye: Option<Vec<[f64; 3]>>,
}

/// The band of a path-only result (as `/api/band`'s, without laying times).
#[derive(Debug, Clone, Serialize, TS)]
pub struct PathBand {
    /// The link carrying the mandrel (the points' frame).
    pub link: usize,
    /// The band's width for drawing, mm: `2 pi r cos(alpha) / circuits`
    /// where the pass is widest.
    pub width_mm: f64,
    /// The points, circuit after circuit, `[x, y, z]` mm.
    pub points: Vec<[f64; 3]>,
    /// Where each circuit's points start.
    pub layers: Vec<usize>,
    /// Rows of the pass (`path.csv`) before thinning.
    pub table_points: usize,
    /// Circuits drawn.
    pub circuits: usize,
}

/// A path-only result read once: the machine's scene and `/api/path`.
#[derive(Debug, Clone)]
pub struct PathView {
    /// The machine's solids, or one bare link carrying the mandrel.
    pub scene: MachineScene,
    /// `/api/path`.
    pub body: PathBody,
    /// The machine's meshes drawn (`/api/mesh/N`).
    pub meshes: Vec<DrawnMesh>,
}

impl PathView {
    /// The path-only winding result under `root` (`summary` its
    /// `summary.json`), on `machine` (a file) or the machine the summary
    /// names, if any; `pass` is its path table's text and file.
    ///
    /// # Errors
    ///
    /// The machine's or a table's read errors, naming the file.
    pub fn read(
        root: &Path,
        summary: &Map<String, Value>,
        machine: Option<&Path>,
        pass: (&Path, &str),
    ) -> Result<Self, ViewError> {
        let (machine, file) = match machine {
            Some(p) => (Some(load_machine(p)?), Some(p.to_path_buf())),
            None if summary.contains_key("machine_shipped")
                || summary.contains_key("machine_file") =>
            {
                let (m, file) = summary_machine(&root.join(names::SUMMARY), summary)?;
                (Some(m), file)
            }
            None => (None, None),
        };
        let mesh_dir = file.as_deref().and_then(Path::parent);
        let (scene, meshes, world, pose) = match &machine {
            Some(m) => {
                let (q, pose) = first_row(root, m)?;
                let (scene, meshes) = MachineScene::read(m, mesh_dir);
                (scene, meshes, m.poses(&q), pose)
            }
            None => (
                bare(),
                Vec::new(),
                vec![Isometry3::identity()],
                "none".into(),
            ),
        };
        let link = scene.mandrel;
        let mandrel_pose = world.get(link).copied().unwrap_or_else(Isometry3::identity);
        let poses = world.iter().map(pose7).collect();
        let circuits = summary
            .get("circuits")
            .and_then(Value::as_u64)
            .map_or(1, |c| c.max(1) as usize);
        let band = pass_band(pass.1, pass.0, link, circuits)?;
        let eye = eye_points(root, &mandrel_pose)?;
        Ok(Self {
            scene,
            body: PathBody {
                poses,
                pose,
                band,
                eye,
            },
            meshes,
        })
    }
}

/// One bare link carrying the mandrel: no machine to draw.
fn bare() -> MachineScene {
    MachineScene {
        name: "no machine".into(),
        links: vec![LinkScene {
            name: "mandrel".into(),
            parent: None,
            solids: Vec::new(),
        }],
        mandrel: 0,
        payout: 0,
    }
}

fn pose7(p: &Isometry3<f64>) -> [f64; 7] {
    let t = p.translation.vector;
    let q = p.rotation.quaternion();
    [t.x, t.y, t.z, q.i, q.j, q.k, q.w]
}

/// The axis values of `axes.csv`'s first row (degrees of rotary axes
/// turned to rad), the machine's home for an axis it does not list; home
/// where there is no `axes.csv`.
fn first_row(root: &Path, m: &Machine) -> Result<(Vec<f64>, String), ViewError> {
    let mut q = m.home();
    let file = root.join(AXES.file);
    if !file.is_file() {
        return Ok((q, "home".into()));
    }
    let t = Table::read(&file)?;
    if t.is_empty() {
        return Ok((q, "home".into()));
    }
    for (k, a) in m.axes.iter().enumerate() {
        if t.has(&a.name)
            && let Some(v) = t.numbers(&a.name)?.first()
        {
            q[k] = if a.is_rotary() { v.to_radians() } else { *v };
        }
    }
    Ok((q, format!("{} row 1", AXES.file)))
}

/// The pass of the path table laid once per circuit, each turned by
/// `2 pi / circuits` about the mandrel's axis, thinned to [`BAND_POINTS`].
fn pass_band(text: &str, file: &Path, link: usize, circuits: usize) -> Result<PathBand, ViewError> {
    let t = Table::parse(text, file)?;
    let (z, r, v) = (
        t.numbers(path::Z)?,
        t.numbers(path::R)?,
        t.numbers(path::V)?,
    );
    let alpha = if t.has(path::ALPHA) {
        t.numbers(path::ALPHA)?
    } else {
        vec![0.0; z.len()]
    };
    let rows: Vec<[f64; 4]> = (0..z.len()).map(|i| [z[i], r[i], v[i], alpha[i]]).collect();
    let per = (BAND_POINTS / circuits).max(2);
    let pass = thin(&rows, per);
    let mut points = Vec::with_capacity(pass.len() * circuits);
    let mut layers = Vec::with_capacity(circuits);
    for k in 0..circuits {
        layers.push(points.len());
        let turn = std::f64::consts::TAU * k as f64 / circuits as f64;
        points.extend(
            pass.iter()
                .map(|[z, r, v, _]| [r * (v + turn).cos(), r * (v + turn).sin(), *z]),
        );
    }
    let widest = rows
        .iter()
        .copied()
        .fold([0.0, 0.0, 0.0, 0.0], |a, b| if b[1] > a[1] { b } else { a });
    let w = std::f64::consts::TAU * widest[1] * widest[3].cos().abs() / circuits as f64;
    Ok(PathBand {
        link,
        width_mm: if w.is_finite() && w > 0.01 {
            w.min(200.0)
        } else {
            10.0
        },
        points,
        layers,
        table_points: rows.len(),
        circuits,
    })
}

/// `eye.csv`'s eye points (`eye_z`, `eye_r`, `eye_v` in the mandrel's
/// frame) placed by the mandrel's pose, or `None` without the table.
fn eye_points(root: &Path, mandrel: &Isometry3<f64>) -> Result<Option<Vec<[f64; 3]>>, ViewError> {
    let file = root.join(EYE.file);
    if !file.is_file() {
        return Ok(None);
    }
    let t = Table::read(&file)?;
    if ![eye::EYE_Z, eye::EYE_R, eye::EYE_V]
        .iter()
        .all(|c| t.has(c))
    {
        return Ok(None);
    }
    let (z, r, v) = (
        t.numbers(eye::EYE_Z)?,
        t.numbers(eye::EYE_R)?,
        t.numbers(eye::EYE_V)?,
    );
    let points = (0..z.len())
        .map(|i| {
            let p = mandrel * Point3::new(r[i] * v[i].cos(), r[i] * v[i].sin(), z[i]);
            [p.x, p.y, p.z]
        })
        .collect();
    Ok(Some(points))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use formcam_results::winding::PATH;

    #[test]
    fn each_circuit_is_the_pass_turned_by_its_share_of_a_turn() {
        let text = "s,z,r,v,alpha\n0,0,30,0,0.5\n1,10,40,0.25,0.5\n2,20,50,0.5,0.5\n";
        let b = pass_band(text, Path::new(PATH.file), 0, 4).unwrap();
        assert_eq!(b.layers, vec![0, 3, 6, 9]);
        assert_eq!(b.points.len(), 12);
        for k in 0..4 {
            let turn = std::f64::consts::FRAC_PI_2 * k as f64;
            let p = b.points[3 * k + 1];
            assert!((p[0] - 40.0 * (0.25 + turn).cos()).abs() < 1e-9);
            assert!((p[1] - 40.0 * (0.25 + turn).sin()).abs() < 1e-9);
            assert!((p[2] - 10.0).abs() < 1e-9);
        }
        let w = std::f64::consts::TAU * 50.0 * 0.5f64.cos() / 4.0;
        assert!((b.width_mm - w).abs() < 1e-9);
        assert_eq!(b.table_points, 3);
    }

    #[test]
    fn the_band_is_thinned_to_its_budget() {
        let mut text = String::from("z,r,v\n");
        for i in 0..5000 {
            text.push_str(&format!("{i},30,{}\n", f64::from(i) * 0.01));
        }
        let b = pass_band(&text, Path::new(PATH.file), 2, 60).unwrap();
        assert!(b.points.len() <= BAND_POINTS);
        assert_eq!(b.layers.len(), 60);
        assert_eq!(b.link, 2);
        assert_eq!(b.table_points, 5000);
    }
}
