//! A mesh solid as the page draws it: the triangles of an STL or OBJ file
//! the machine names (read as the checker reads them), equal vertices
//! joined, thinned for drawing only past [`MESH_TRIANGLES`], and sent as
//! binary (`/api/mesh/N`).
//!
//! The binary answer, little-endian: the vertex count `nv` (`u32`), the
//! triangle count `nt` (`u32`), `3 nv` positions (`f32`, mm, in the
//! visual's frame, its scale applied), `3 nt` vertex indices (`u32`).

use std::collections::HashMap;

use formcam_machine::TriMesh;

/// The most triangles drawn of one mesh; a mesh with more is thinned by
/// vertex clustering (for drawing only: the checks use the file's).
pub const MESH_TRIANGLES: usize = 100_000;

/// A mesh ready to send: positions and triangles, and how many triangles
/// the file has.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawnMesh {
    /// Vertex positions, mm (equal vertices joined).
    pub positions: Vec<[f32; 3]>,
    /// Triangles, three indices into `positions` each.
    pub triangles: Vec<[u32; 3]>,
    /// The file's triangles (more than `triangles.len()` when thinned).
    pub file_triangles: usize,
}

impl DrawnMesh {
    /// `mesh` for drawing: its vertices as `f32`, equal ones joined, and at
    /// most `cap` triangles (thinned by clustering its vertices on a grid,
    /// as fine as keeps it within `cap`).
    pub fn of(mesh: &TriMesh, cap: usize) -> Self {
        let (positions, triangles) = weld(mesh);
        let file_triangles = mesh.triangles.len();
        if triangles.len() <= cap {
            return Self {
                positions,
                triangles,
                file_triangles,
            };
        }
        let mut cells = 1024;
        loop {
            let (p, t) = cluster(&positions, &triangles, cells);
            if t.len() <= cap || cells == 1 {
                return Self {
                    positions: p,
                    triangles: t,
                    file_triangles,
                };
            }
            cells /= 2;
        }
    }

    /// Whether fewer triangles are drawn than the file has.
    pub fn thinned(&self) -> bool {
        self.triangles.len() < self.file_triangles
    }

    /// The binary answer of `/api/mesh/N` (see the module's description).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(8 + 12 * (self.positions.len() + self.triangles.len()));
        // Counts fit: a mesh file is at most the input cap (256 MiB by default).
        out.extend_from_slice(
            &u32::try_from(self.positions.len())
                .unwrap_or(0)
                .to_le_bytes(),
        );
        out.extend_from_slice(
            &u32::try_from(self.triangles.len())
                .unwrap_or(0)
                .to_le_bytes(),
        );
        for p in &self.positions {
            for c in p {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        for t in &self.triangles {
            for i in t {
                out.extend_from_slice(&i.to_le_bytes());
            }
        }
        out
    }
}

/// The vertices as `f32`, those equal as `f32` joined (an STL repeats each
/// vertex in every triangle it belongs to), the triangles renumbered.
fn weld(mesh: &TriMesh) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut index: HashMap<[u32; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let renumber: Vec<u32> = mesh
        .vertices
        .iter()
        .map(|v| {
            // Positions drawn in f32: mm of a machine fit.
            let p = [v.x as f32, v.y as f32, v.z as f32];
            let key = p.map(|c| if c == 0.0 { 0 } else { c.to_bits() });
            *index.entry(key).or_insert_with(|| {
                positions.push(p);
                (positions.len() - 1) as u32
            })
        })
        .collect();
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| renumber[i as usize]))
        .collect();
    (positions, triangles)
}

/// The mesh with its vertices clustered on a grid of `cells` cells along
/// its longest side: one vertex per occupied cell (the mean of its own),
/// triangles that collapse or repeat another dropped.
fn cluster(
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
    cells: u32,
) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in positions {
        for (k, c) in p.iter().enumerate() {
            lo[k] = lo[k].min(*c);
            hi[k] = hi[k].max(*c);
        }
    }
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0_f32, f32::max);
    let size = (extent / cells as f32).max(f32::MIN_POSITIVE);
    let mut cell_of: HashMap<[i64; 3], u32> = HashMap::new();
    let mut sums: Vec<([f64; 3], u32)> = Vec::new();
    let renumber: Vec<u32> = positions
        .iter()
        .map(|p| {
            let key = [0, 1, 2].map(|k| ((p[k] - lo[k]) / size).floor() as i64);
            let c = *cell_of.entry(key).or_insert_with(|| {
                sums.push(([0.0; 3], 0));
                (sums.len() - 1) as u32
            });
            let s = &mut sums[c as usize];
            for (sum, c) in s.0.iter_mut().zip(p) {
                *sum += f64::from(*c);
            }
            s.1 += 1;
            c
        })
        .collect();
    let out_positions = sums
        .iter()
        .map(|(s, n)| s.map(|c| (c / f64::from(*n)) as f32))
        .collect();
    let mut seen = std::collections::HashSet::new();
    let out_triangles = triangles
        .iter()
        .map(|t| t.map(|i| renumber[i as usize]))
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .filter(|t| {
            // The same triangle the same way round, from its least index.
            let r = t
                .iter()
                .enumerate()
                .min_by_key(|(_, v)| **v)
                .map_or(0, |(k, _)| k);
            seen.insert([t[r], t[(r + 1) % 3], t[(r + 2) % 3]])
        })
        .collect();
    (out_positions, out_triangles)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use nalgebra::Point3;

    /// A sphere of `n` x `2n` quads (two triangles each), as an STL gives it:
    /// every triangle with its own three vertices.
    fn sphere(n: u32, r: f64) -> TriMesh {
        let at = |i: u32, j: u32| {
            let th = std::f64::consts::PI * f64::from(i) / f64::from(n);
            let ph = std::f64::consts::PI * f64::from(j) / f64::from(n);
            Point3::new(
                r * th.sin() * ph.cos(),
                r * th.sin() * ph.sin(),
                r * th.cos(),
            )
        };
        let mut vertices = Vec::new();
        let mut triangles = Vec::new();
        for i in 0..n {
            for j in 0..2 * n {
                for t in [
                    [(i, j), (i + 1, j), (i + 1, j + 1)],
                    [(i, j), (i + 1, j + 1), (i, j + 1)],
                ] {
                    let k = vertices.len() as u32;
                    vertices.extend(t.iter().map(|&(a, b)| at(a, b)));
                    triangles.push([k, k + 1, k + 2]);
                }
            }
        }
        TriMesh {
            vertices,
            triangles,
        }
    }

    #[test]
    fn equal_vertices_are_joined_and_every_triangle_kept() {
        let n = 12;
        let m = sphere(n, 50.0);
        let d = DrawnMesh::of(&m, MESH_TRIANGLES);
        assert_eq!(d.triangles.len(), m.triangles.len());
        assert_eq!(d.file_triangles, m.triangles.len());
        assert!(!d.thinned());
        // The grid's points: the poles once each, the rest once per seam
        // column (j = 0 and j = 2n meet at the same place only to rounding).
        assert!(d.positions.len() <= ((n + 1) * (2 * n + 1)) as usize);
        assert!(d.positions.len() < m.vertices.len() / 3);
        // Every triangle's corners are the file's.
        for (t, s) in d.triangles.iter().zip(&m.triangles) {
            for k in 0..3 {
                let (p, q) = (d.positions[t[k] as usize], m.vertices[s[k] as usize]);
                assert!((f64::from(p[0]) - q.x).abs() < 1e-4);
                assert!((f64::from(p[2]) - q.z).abs() < 1e-4);
            }
        }
    }

    #[test]
    fn a_mesh_past_the_cap_is_thinned_to_it_on_its_own_surface() {
        let m = sphere(160, 100.0);
        assert!(m.triangles.len() > 50_000);
        let d = DrawnMesh::of(&m, 5_000);
        assert!(d.thinned());
        assert!(
            d.triangles.len() <= 5_000 && d.triangles.len() > 500,
            "{}",
            d.triangles.len()
        );
        // Cluster means of points on the sphere stay near it.
        for p in &d.positions {
            let r = p.iter().map(|c| f64::from(*c).powi(2)).sum::<f64>().sqrt();
            assert!((r - 100.0).abs() < 10.0, "{r}");
        }
        for t in &d.triangles {
            assert!(t.iter().all(|&i| (i as usize) < d.positions.len()));
            assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
        }
    }

    #[test]
    fn the_binary_answer_holds_the_counts_then_positions_then_indices() {
        let m = TriMesh {
            vertices: vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(10.0, 0.0, 0.0),
                Point3::new(0.0, 10.0, 0.0),
                Point3::new(10.0, 0.0, 0.0),
                Point3::new(0.0, 10.0, 0.0),
                Point3::new(10.0, 10.0, 2.5),
            ],
            triangles: vec![[0, 1, 2], [3, 5, 4]],
        };
        let d = DrawnMesh::of(&m, MESH_TRIANGLES);
        let b = d.to_bytes();
        let u = |at: usize| u32::from_le_bytes(b[at..at + 4].try_into().unwrap());
        let f = |at: usize| f32::from_le_bytes(b[at..at + 4].try_into().unwrap());
        assert_eq!((u(0), u(4)), (4, 2));
        assert_eq!(b.len(), 8 + 12 * 4 + 12 * 2);
        assert_eq!([f(8 + 36), f(8 + 40), f(8 + 44)], [10.0, 10.0, 2.5]);
        let at = 8 + 48;
        assert_eq!([u(at), u(at + 4), u(at + 8)], [0, 1, 2]);
        assert_eq!([u(at + 12), u(at + 16), u(at + 20)], [1, 3, 2]);
    }
}
