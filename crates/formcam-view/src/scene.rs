//! What the page draws besides the timeline: the machine's solids in their
//! links' frames (boxes, cylinders, spheres and meshes, whose triangles
//! are sent on their own) and the mandrel (its meridian and the path) in
//! the mandrel link's frame. The page places them by the poses it is sent.

use std::path::Path;

use formcam_machine::{Machine, Shape, read_visual_mesh};
use formcam_results::Column;
use formcam_results::winding::path;
use serde::Serialize;
use ts_rs::TS;

use crate::ViewError;
use crate::mesh::{DrawnMesh, MESH_TRIANGLES};

/// The machine's solids.
#[derive(Debug, Clone, Serialize, TS)]
pub struct MachineScene {
    /// The machine's name.
    pub name: String,
    /// Links in the order of the timeline's poses.
    pub links: Vec<LinkScene>,
    /// The link carrying the mandrel.
    pub mandrel: usize,
    /// The payout point: an index into the key points.
    pub payout: usize,
}

/// One link's solids.
#[derive(Debug, Clone, Serialize, TS)]
pub struct LinkScene {
    /// Name.
    pub name: String,
    /// Its parent's index; none for the base.
    pub parent: Option<usize>,
    /// Solids in the link's frame.
    pub solids: Vec<Solid>,
}

/// A solid placed in its link's frame.
#[derive(Debug, Clone, Serialize, TS)]
pub struct Solid {
    /// Its shape.
    #[serde(flatten)]
    pub shape: SolidShape,
    /// Its placement in the link's frame: `[x, y, z, qx, qy, qz, qw]`.
    pub origin: [f64; 7],
    /// Colour `#rrggbb`.
    pub color: String,
}

/// The shapes the page draws.
#[derive(Debug, Clone, Serialize, TS)]
#[serde(tag = "shape", rename_all = "lowercase")]
pub enum SolidShape {
    /// A box centred on the origin: edge lengths, mm.
    Box {
        /// Edge lengths along x, y, z, mm.
        size: [f64; 3],
    },
    /// A cylinder along local `z`, centred on the origin.
    Cylinder {
        /// Radius, mm.
        radius: f64,
        /// Length, mm.
        length: f64,
    },
    /// A sphere about the origin.
    Sphere {
        /// Radius, mm.
        radius: f64,
    },
    /// A mesh file's triangles (`/api/mesh/N`), in the visual's frame.
    Mesh {
        /// The file as the machine names it.
        file: String,
        /// Its index for `/api/mesh/N`; none when it could not be read.
        #[serde(skip_serializing_if = "Option::is_none")]
        #[ts(optional)]
        mesh: Option<usize>,
        /// The file's triangles.
        triangles: usize,
        /// The triangles drawn (fewer than the file's past
        /// [`MESH_TRIANGLES`]).
        drawn: usize,
        /// Why the file could not be read (naming it as resolved).
        #[serde(skip_serializing_if = "Option::is_none")]
        #[ts(optional)]
        error: Option<String>,
    },
}

impl MachineScene {
    /// The solids of `m`, its mesh files read as [`MachineScene::read`]
    /// reads them without a folder (a shipped machine's).
    pub fn of(m: &Machine) -> Self {
        Self::read(m, None).0
    }

    /// The solids of `m` and the meshes drawn: each mesh solid's file read
    /// as the checker reads it (relative to `mesh_dir`, the machine file's
    /// folder, its scale applied; a shipped machine's from formcam) and
    /// thinned past [`MESH_TRIANGLES`]; a mesh that cannot be read is a
    /// solid with its `error`.
    pub fn read(m: &Machine, mesh_dir: Option<&Path>) -> (Self, Vec<DrawnMesh>) {
        let mut meshes = Vec::new();
        let links = m
            .links
            .iter()
            .map(|l| LinkScene {
                name: l.name.clone(),
                parent: l.parent,
                solids: l
                    .visuals
                    .iter()
                    .map(|v| {
                        let shape = match &v.shape {
                            Shape::Box(size) => SolidShape::Box { size: *size },
                            Shape::Cylinder { radius, length } => SolidShape::Cylinder {
                                radius: *radius,
                                length: *length,
                            },
                            Shape::Sphere(radius) => SolidShape::Sphere { radius: *radius },
                            Shape::Mesh(file) => mesh_solid(file, v.scale, mesh_dir, &mut meshes),
                        };
                        let t = v.origin.translation.vector;
                        let q = v.origin.rotation.quaternion();
                        Solid {
                            shape,
                            origin: [t.x, t.y, t.z, q.i, q.j, q.k, q.w],
                            color: v.color.clone(),
                        }
                    })
                    .collect(),
            })
            .collect();
        let scene = Self {
            name: m.name.clone(),
            links,
            mandrel: m.roles.mandrel,
            payout: m.roles.payout,
        };
        (scene, meshes)
    }
}

/// A mesh solid: its file read and added to `meshes`, or its error.
fn mesh_solid(
    file: &str,
    scale: [f64; 3],
    dir: Option<&Path>,
    meshes: &mut Vec<DrawnMesh>,
) -> SolidShape {
    match read_visual_mesh(file, scale, dir) {
        Ok(mesh) => {
            let drawn = DrawnMesh::of(&mesh, MESH_TRIANGLES);
            let shape = SolidShape::Mesh {
                file: file.to_string(),
                mesh: Some(meshes.len()),
                triangles: drawn.file_triangles,
                drawn: drawn.triangles.len(),
                error: None,
            };
            meshes.push(drawn);
            shape
        }
        Err(e) => SolidShape::Mesh {
            file: file.to_string(),
            mesh: None,
            triangles: 0,
            drawn: 0,
            error: Some(e.to_string()),
        },
    }
}

/// The mandrel in its link's frame (`z` along its axis).
#[derive(Debug, Clone, Serialize, TS)]
pub struct MandrelScene {
    /// The link carrying it.
    pub link: usize,
    /// The meridian `[z, r]` by increasing `z`, mm: where the path runs.
    pub meridian: Vec<[f64; 2]>,
    /// The path of one pass `[x, y, z]`, mm (at most [`PATH_POINTS`]).
    pub path: Vec<[f64; 3]>,
    /// Points of the path table before thinning.
    pub path_points: usize,
}

/// The most path points sent for drawing.
pub const PATH_POINTS: usize = 20_000;

/// The most meridian points sent for drawing.
pub const MERIDIAN_POINTS: usize = 512;

impl MandrelScene {
    /// The mandrel from a path table (`z`, `r`, `v` columns; `path` names it
    /// in errors): its meridian where the path runs, and the path.
    ///
    /// # Errors
    ///
    /// A missing column or a cell that is no finite number, with its line.
    pub fn from_path_table(link: usize, text: &str, path: &Path) -> Result<Self, ViewError> {
        let bad = |line: usize, problem: String| ViewError::PathTable {
            path: path.to_path_buf(),
            line,
            problem,
        };
        let mut rows = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let (_, header) = rows.next().ok_or_else(|| bad(1, "empty file".into()))?;
        let names: Vec<&str> = header.split(',').map(str::trim).collect();
        let col = |c: Column| {
            names
                .iter()
                .position(|n| *n == c.name)
                .ok_or_else(|| bad(1, format!("no column `{}`", c.name)))
        };
        let (cz, cr, cv) = (col(path::Z)?, col(path::R)?, col(path::V)?);
        let mut points = Vec::new();
        for (i, line) in rows {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            let num = |k: usize, c: Column| {
                cells
                    .get(k)
                    .and_then(|s| s.parse::<f64>().ok())
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| bad(i + 1, format!("`{}` is no finite number", c.name)))
            };
            points.push((num(cz, path::Z)?, num(cr, path::R)?, num(cv, path::V)?));
        }
        let mut meridian: Vec<[f64; 2]> = points.iter().map(|p| [p.0, p.1]).collect();
        meridian.sort_by(|a, b| a[0].total_cmp(&b[0]));
        meridian.dedup_by(|a, b| a[0] == b[0]);
        let path = thin(&points, PATH_POINTS)
            .into_iter()
            .map(|(z, r, v)| [r * v.cos(), r * v.sin(), z])
            .collect();
        Ok(Self {
            link,
            meridian: thin(&meridian, MERIDIAN_POINTS),
            path,
            path_points: points.len(),
        })
    }
}

/// At most `n` (>= 2) of `items`, evenly spread, the first and last kept.
pub fn thin<T: Copy>(items: &[T], n: usize) -> Vec<T> {
    let n = n.max(2);
    if items.len() <= n {
        return items.to_vec();
    }
    let last = items.len() - 1;
    (0..n).map(|i| items[i * last / (n - 1)]).collect()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use formcam_results::winding::PATH;

    #[test]
    fn thinning_keeps_both_ends_and_at_most_n() {
        let v: Vec<usize> = (0..1001).collect();
        let t = thin(&v, 10);
        assert_eq!(t.len(), 10);
        assert_eq!((t[0], t[9]), (0, 1000));
        assert!(t.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(thin(&v[..5], 10), v[..5].to_vec());
    }

    #[test]
    fn the_path_lies_on_the_meridian_it_comes_from() {
        let text = "s,z,r,v\n0,0,30,0\n1,10,40,0.5\n2,20,50,3.0\n";
        let m = MandrelScene::from_path_table(2, text, Path::new(PATH.file)).unwrap();
        assert_eq!(m.meridian, vec![[0.0, 30.0], [10.0, 40.0], [20.0, 50.0]]);
        for (p, [_, r]) in m.path.iter().zip(&m.meridian) {
            assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - r).abs() < 1e-12);
        }
        assert_eq!(m.link, 2);
    }

    #[test]
    fn a_missing_column_names_it() {
        let e = MandrelScene::from_path_table(0, "s,z,r\n0,0,1\n", Path::new(PATH.file))
            .unwrap_err()
            .to_string();
        assert_eq!(e, format!("{}:1: no column `{}`", PATH.file, path::V.name));
    }
}
