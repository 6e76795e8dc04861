//! Mesh solids: STL (binary and ASCII) and Wavefront OBJ files read into a
//! triangle mesh (vertices in mm, triangles as vertex indices).
//!
//! * STL: a binary file is an 80-byte header, a little-endian `u32`
//!   triangle count and 50 bytes per triangle (normal, three vertices as
//!   `f32`, a 2-byte attribute); its length must be exactly
//!   `84 + 50 n`. A file whose length is not that and that starts with
//!   `solid` is read as ASCII: `facet normal`, `outer loop`, three
//!   `vertex x y z`, `endloop`, `endfacet`, ..., `endsolid`. Normals are not
//!   used (the vertices' order is kept).
//! * OBJ: `v x y z [w]` vertices and `f` faces of three or more vertex
//!   references (`i`, `i/t`, `i//n`, `i/t/n`; 1-based, negative counting back
//!   from the last vertex read); polygons are fanned from their first
//!   vertex. Other statements (`vn`, `vt`, `o`, `g`, `s`, `usemtl`, `mtllib`,
//!   `l`, `p`, comments) are passed over.
//!
//! Every vertex is scaled per axis by the mesh's scale as it is read.
//! Errors name the file and the line (ASCII STL, OBJ) or byte offset
//! (binary STL).

use std::path::{Path, PathBuf};

use formcam_files::{ReadError, excerpt};
use nalgebra::Point3;

/// A triangle mesh: vertices (mm) and triangles (indices into `vertices`).
#[derive(Debug, Clone, PartialEq)]
pub struct TriMesh {
    /// The vertices, mm.
    pub vertices: Vec<Point3<f64>>,
    /// The triangles, three vertex indices each.
    pub triangles: Vec<[u32; 3]>,
}

/// A mesh file's format, by its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// STL, binary or ASCII (`.stl`).
    Stl,
    /// Wavefront OBJ (`.obj`).
    Obj,
}

impl MeshFormat {
    /// The format of `path` by its extension (any case); `None` when it
    /// names neither.
    pub fn of(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "stl" => Some(Self::Stl),
            "obj" => Some(Self::Obj),
            _ => None,
        }
    }
}

/// Where in a mesh file a fault lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshPlace {
    /// A line of a text file (1-based).
    Line(usize),
    /// A byte offset of a binary file.
    Offset(usize),
    /// The file as a whole.
    File,
}

impl std::fmt::Display for MeshPlace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Line(l) => write!(f, "line {l}"),
            Self::Offset(o) => write!(f, "byte {o}"),
            Self::File => write!(f, "file"),
        }
    }
}

/// What is wrong in a mesh file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshFault {
    /// A binary STL shorter or longer than its triangle count says.
    #[error("a binary STL of {count} triangles has {expected} bytes, this one {len}")]
    Length {
        /// The triangle count in the header.
        count: u64,
        /// The length it implies.
        expected: u64,
        /// The file's length.
        len: u64,
    },
    /// A file too short to be a binary STL and not an ASCII one.
    #[error("not an STL file: shorter than 84 bytes and not starting with `solid`")]
    NotStl,
    /// A word that is not what the format expects there.
    #[error("expected {expected}, found {found}")]
    Expected {
        /// What the format allows here.
        expected: &'static str,
        /// What the file has (quoted).
        found: String,
    },
    /// A number that cannot be read or is not finite.
    #[error("\"{0}\" is not a finite number")]
    Number(String),
    /// A vertex index out of range.
    #[error("vertex index {index} is out of range (1 to {count}, or -1 to -{count})")]
    Index {
        /// The index as written.
        index: i64,
        /// How many vertices were read by then.
        count: usize,
    },
    /// A face with fewer than three vertices.
    #[error("a face needs at least 3 vertices, this one has {0}")]
    ShortFace(usize),
    /// A file without a triangle.
    #[error("no triangle")]
    Empty,
    /// A text format that is not UTF-8.
    #[error("not UTF-8 text")]
    NotText,
}

/// Why a mesh file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The file could not be read (missing, not a regular file, too large).
    #[error("{}: {source}", source.path().display())]
    Read {
        /// The reason, with the path.
        #[from]
        source: ReadError,
    },
    /// The extension names no mesh format.
    #[error("{}: a mesh is an STL (.stl) or OBJ (.obj) file", path.display())]
    Extension {
        /// The mesh file.
        path: PathBuf,
    },
    /// The file's content is not a valid mesh.
    #[error("{}: {place}: {fault}", path.display())]
    Format {
        /// The mesh file.
        path: PathBuf,
        /// Where.
        place: MeshPlace,
        /// What is wrong.
        fault: MeshFault,
    },
}

/// Reads the mesh file `path` (STL or OBJ by its extension) through
/// formcam-files' reader, every vertex multiplied by `scale` per axis.
///
/// # Errors
///
/// [`MeshError::Read`] when the file cannot be read, [`MeshError::Extension`]
/// for another extension, [`MeshError::Format`] naming the line or byte.
pub fn read_mesh(path: &Path, scale: [f64; 3]) -> Result<TriMesh, MeshError> {
    let format = MeshFormat::of(path).ok_or_else(|| MeshError::Extension {
        path: path.to_path_buf(),
    })?;
    let bytes = formcam_files::read_bytes(path)?;
    parse_mesh(&bytes, format, scale).map_err(|(place, fault)| MeshError::Format {
        path: path.to_path_buf(),
        place,
        fault,
    })
}

/// Reads the mesh a machine's visual names, as every reader of a machine's
/// meshes finds it: `file` relative to `dir`, the machine file's folder
/// (the working folder when there is none); a shipped machine's mesh
/// (`meshes/chuck-flange.stl`, [`crate::shipped::shipped_mesh`]) is taken
/// from formcam itself when `dir` is none or holds no such file (a shipped
/// machine named by its name, or its file copied without its meshes).
/// Every vertex is multiplied by `scale`.
///
/// # Errors
///
/// As [`read_mesh`], naming the file as resolved.
pub fn read_visual_mesh(
    file: &str,
    scale: [f64; 3],
    dir: Option<&Path>,
) -> Result<TriMesh, MeshError> {
    let path = dir.map_or_else(|| PathBuf::from(file), |d| d.join(file));
    match crate::shipped::shipped_mesh(file) {
        Some(m) if dir.is_none() || !path.exists() => {
            let name = PathBuf::from(m.file);
            let format =
                MeshFormat::of(&name).ok_or_else(|| MeshError::Extension { path: name.clone() })?;
            parse_mesh(m.bytes, format, scale).map_err(|(place, fault)| MeshError::Format {
                path: name,
                place,
                fault,
            })
        }
        _ => read_mesh(&path, scale),
    }
}

/// Parses the bytes of a mesh file in `format`, every vertex multiplied by
/// `scale`.
///
/// # Errors
///
/// Where the content is wrong and what is wrong.
pub fn parse_mesh(
    bytes: &[u8],
    format: MeshFormat,
    scale: [f64; 3],
) -> Result<TriMesh, (MeshPlace, MeshFault)> {
    let mut mesh = match format {
        MeshFormat::Stl => parse_stl(bytes)?,
        MeshFormat::Obj => {
            let text =
                std::str::from_utf8(bytes).map_err(|_| (MeshPlace::File, MeshFault::NotText))?;
            parse_obj(text)?
        }
    };
    if mesh.triangles.is_empty() {
        return Err((MeshPlace::File, MeshFault::Empty));
    }
    for v in &mut mesh.vertices {
        for (c, s) in v.coords.iter_mut().zip(scale) {
            *c *= s;
        }
    }
    Ok(mesh)
}

/// An STL file, binary when its length matches its triangle count, else ASCII.
fn parse_stl(bytes: &[u8]) -> Result<TriMesh, (MeshPlace, MeshFault)> {
    let ascii = bytes.trim_ascii_start().starts_with(b"solid");
    if bytes.len() >= 84 {
        let count = u64::from(u32::from_le_bytes([
            bytes[80], bytes[81], bytes[82], bytes[83],
        ]));
        let expected = 84 + 50 * count;
        if expected == bytes.len() as u64 {
            return Ok(parse_stl_binary(bytes));
        }
        if !ascii {
            return Err((
                MeshPlace::Offset(80),
                MeshFault::Length {
                    count,
                    expected,
                    len: bytes.len() as u64,
                },
            ));
        }
    } else if !ascii {
        return Err((MeshPlace::File, MeshFault::NotStl));
    }
    let text = std::str::from_utf8(bytes).map_err(|_| (MeshPlace::File, MeshFault::NotText))?;
    parse_stl_ascii(text)
}

/// A binary STL whose length is known to match its count.
fn parse_stl_binary(bytes: &[u8]) -> TriMesh {
    let records = bytes[84..].chunks_exact(50);
    let mut vertices = Vec::with_capacity(records.len() * 3);
    let mut triangles = Vec::with_capacity(records.len());
    let f = |b: &[u8], at: usize| {
        f64::from(f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]))
    };
    for r in records {
        let first = vertices.len() as u32;
        for k in 0..3 {
            let at = 12 + 12 * k;
            vertices.push(Point3::new(f(r, at), f(r, at + 4), f(r, at + 8)));
        }
        triangles.push([first, first + 1, first + 2]);
    }
    TriMesh {
        vertices,
        triangles,
    }
}

/// The words of a text file, each with its line.
struct Words<'a> {
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    current: std::str::SplitAsciiWhitespace<'a>,
    line: usize,
}

impl<'a> Words<'a> {
    fn new(text: &'a str) -> Self {
        Self {
            lines: text.lines().enumerate(),
            current: "".split_ascii_whitespace(),
            line: 0,
        }
    }

    /// The next word and its line (`None` at the end).
    fn next(&mut self) -> Option<&'a str> {
        loop {
            if let Some(w) = self.current.next() {
                return Some(w);
            }
            let (i, l) = self.lines.next()?;
            self.line = i + 1;
            self.current = l.split_ascii_whitespace();
        }
    }

    /// The next word, which must be `word`.
    fn expect(&mut self, word: &'static str) -> Result<(), (MeshPlace, MeshFault)> {
        match self.next() {
            Some(w) if w.eq_ignore_ascii_case(word) => Ok(()),
            other => Err(self.fault(word, other)),
        }
    }

    /// The next word as a finite number.
    fn number(&mut self) -> Result<f64, (MeshPlace, MeshFault)> {
        let w = self.next().ok_or_else(|| self.fault("a number", None))?;
        finite(w).ok_or_else(|| (MeshPlace::Line(self.line), MeshFault::Number(excerpt(w))))
    }

    fn fault(&self, expected: &'static str, found: Option<&str>) -> (MeshPlace, MeshFault) {
        (
            MeshPlace::Line(self.line.max(1)),
            MeshFault::Expected {
                expected,
                found: found.map_or_else(
                    || "the end of the file".into(),
                    |w| format!("\"{}\"", excerpt(w)),
                ),
            },
        )
    }
}

/// A finite number, or none.
fn finite(w: &str) -> Option<f64> {
    w.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// An ASCII STL file: `solid [name]`, facets, `endsolid [name]`.
fn parse_stl_ascii(text: &str) -> Result<TriMesh, (MeshPlace, MeshFault)> {
    let mut words = Words::new(text);
    words.expect("solid")?;
    // The name runs to the end of its line.
    words.current = "".split_ascii_whitespace();
    let mut mesh = TriMesh {
        vertices: Vec::new(),
        triangles: Vec::new(),
    };
    loop {
        match words.next() {
            Some(w) if w.eq_ignore_ascii_case("facet") => {}
            Some(w) if w.eq_ignore_ascii_case("endsolid") => return Ok(mesh),
            other => return Err(words.fault("`facet` or `endsolid`", other)),
        }
        words.expect("normal")?;
        for _ in 0..3 {
            words.number()?;
        }
        words.expect("outer")?;
        words.expect("loop")?;
        let first = mesh.vertices.len() as u32;
        for _ in 0..3 {
            words.expect("vertex")?;
            let (x, y, z) = (words.number()?, words.number()?, words.number()?);
            mesh.vertices.push(Point3::new(x, y, z));
        }
        mesh.triangles.push([first, first + 1, first + 2]);
        words.expect("endloop")?;
        words.expect("endfacet")?;
    }
}

/// A Wavefront OBJ file's vertices and faces.
fn parse_obj(text: &str) -> Result<TriMesh, (MeshPlace, MeshFault)> {
    let mut mesh = TriMesh {
        vertices: Vec::new(),
        triangles: Vec::new(),
    };
    let mut face: Vec<u32> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let place = MeshPlace::Line(i + 1);
        let line = raw.split('#').next().unwrap_or("");
        let mut words = line.split_ascii_whitespace();
        match words.next() {
            Some("v") => {
                let mut xyz = [0.0; 3];
                for c in &mut xyz {
                    let w = words.next().ok_or_else(|| {
                        (
                            place,
                            MeshFault::Expected {
                                expected: "three coordinates after `v`",
                                found: format!("\"{}\"", excerpt(raw.trim())),
                            },
                        )
                    })?;
                    *c = finite(w).ok_or_else(|| (place, MeshFault::Number(excerpt(w))))?;
                }
                mesh.vertices.push(Point3::from(xyz));
            }
            Some("f") => {
                face.clear();
                for w in words {
                    let head = w.split('/').next().unwrap_or("");
                    let index: i64 = head.parse().map_err(|_| {
                        (
                            place,
                            MeshFault::Expected {
                                expected: "a vertex index (i, i/t, i//n or i/t/n)",
                                found: format!("\"{}\"", excerpt(w)),
                            },
                        )
                    })?;
                    let count = mesh.vertices.len();
                    let resolved = if index > 0 {
                        index - 1
                    } else {
                        count as i64 + index
                    };
                    if index == 0 || resolved < 0 || resolved >= count as i64 {
                        return Err((place, MeshFault::Index { index, count }));
                    }
                    face.push(resolved as u32);
                }
                if face.len() < 3 {
                    return Err((place, MeshFault::ShortFace(face.len())));
                }
                for pair in face[1..].windows(2) {
                    mesh.triangles.push([face[0], pair[0], pair[1]]);
                }
            }
            _ => {}
        }
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    const ONE: [f64; 3] = [1.0; 3];

    fn binary(tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut b = vec![b' '; 80];
        b.extend_from_slice(&(tris.len() as u32).to_le_bytes());
        for t in tris {
            b.extend_from_slice(&[0u8; 12]);
            for v in t {
                for c in v {
                    b.extend_from_slice(&c.to_le_bytes());
                }
            }
            b.extend_from_slice(&[0u8; 2]);
        }
        b
    }

    #[test]
    fn binary_stl_reads_every_triangle() {
        let t = [[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.5]]];
        let mut b = binary(&[t[0], t[0]]);
        // A binary file may start with `solid` too.
        b[..5].copy_from_slice(b"solid");
        let m = parse_mesh(&b, MeshFormat::Stl, [2.0, 1.0, 1.0]).unwrap();
        assert_eq!(m.triangles, [[0, 1, 2], [3, 4, 5]]);
        assert_eq!(m.vertices[1], Point3::new(2.0, 0.0, 0.0));
        assert_eq!(m.vertices[2], Point3::new(0.0, 2.0, 0.5));
    }

    #[test]
    fn binary_stl_of_the_wrong_length_names_the_count() {
        let t = [[0.0f32; 3]; 3];
        let mut b = binary(&[t, t]);
        b.truncate(b.len() - 7);
        let e = parse_mesh(&b, MeshFormat::Stl, ONE).unwrap_err();
        assert_eq!(
            e,
            (
                MeshPlace::Offset(80),
                MeshFault::Length {
                    count: 2,
                    expected: 184,
                    len: 177
                }
            )
        );
        assert_eq!(
            parse_mesh(b"abc", MeshFormat::Stl, ONE).unwrap_err(),
            (MeshPlace::File, MeshFault::NotStl)
        );
    }

    const ASCII: &str = "solid part name\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   \
                         vertex 10 0 0\n   vertex 0 10 1e1\n  endloop\n endfacet\nendsolid part\n";

    #[test]
    fn ascii_stl_reads_facets() {
        let m = parse_mesh(ASCII.as_bytes(), MeshFormat::Stl, ONE).unwrap();
        assert_eq!(m.triangles, [[0, 1, 2]]);
        assert_eq!(m.vertices[2], Point3::new(0.0, 10.0, 10.0));
    }

    #[test]
    fn malformed_ascii_stl_names_the_line() {
        let bad = ASCII.replace("vertex 10 0 0", "vertex 10 zero 0");
        let e = parse_mesh(bad.as_bytes(), MeshFormat::Stl, ONE).unwrap_err();
        assert_eq!(e.0, MeshPlace::Line(5));
        assert!(matches!(e.1, MeshFault::Number(_)), "{e:?}");
        let cut = &ASCII[..ASCII.find("endloop").unwrap()];
        let e = parse_mesh(cut.as_bytes(), MeshFormat::Stl, ONE).unwrap_err();
        assert!(
            matches!(
                e.1,
                MeshFault::Expected {
                    expected: "endloop",
                    ..
                }
            ),
            "{e:?}"
        );
        let empty = parse_mesh(b"solid x\nendsolid x\n", MeshFormat::Stl, ONE).unwrap_err();
        assert_eq!(empty, (MeshPlace::File, MeshFault::Empty));
        let nan = ASCII.replace("vertex 0 0 0", "vertex 0 nan 0");
        let e = parse_mesh(nan.as_bytes(), MeshFormat::Stl, ONE).unwrap_err();
        assert_eq!(e, (MeshPlace::Line(4), MeshFault::Number("nan".into())));
    }

    #[test]
    fn obj_fans_polygons_and_counts_negative_indices_back() {
        let text = "# a quad and a triangle\no part\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
                    vn 0 0 1\nf 1//1 2//1 3//1 4//1\nv 0 0 5\nf -1 -2 -3\n";
        let m = parse_mesh(text.as_bytes(), MeshFormat::Obj, [1.0, 1.0, 0.5]).unwrap();
        assert_eq!(m.triangles, [[0, 1, 2], [0, 2, 3], [4, 3, 2]]);
        assert_eq!(m.vertices[4], Point3::new(0.0, 0.0, 2.5));
    }

    #[test]
    fn malformed_obj_names_the_line() {
        let cases: [(&str, MeshFault); 4] = [
            (
                "v 0 0 0\nv 1 0 0\nf 1 2 3\n",
                MeshFault::Index { index: 3, count: 2 },
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
                MeshFault::ShortFace(2),
            ),
            (
                "v 0 0\n",
                MeshFault::Expected {
                    expected: "three coordinates after `v`",
                    found: "\"v 0 0\"".into(),
                },
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 -4 2\n",
                MeshFault::Index {
                    index: -4,
                    count: 3,
                },
            ),
        ];
        for (text, fault) in cases {
            let e = parse_mesh(text.as_bytes(), MeshFormat::Obj, ONE).unwrap_err();
            assert_eq!(e.1, fault, "{text}");
            assert_eq!(e.0, MeshPlace::Line(text.lines().count()), "{text}");
        }
        let e = parse_mesh(b"v 0 0 0\n", MeshFormat::Obj, ONE).unwrap_err();
        assert_eq!(e, (MeshPlace::File, MeshFault::Empty));
    }

    #[test]
    fn read_mesh_names_the_file() {
        let dir = std::env::temp_dir().join(format!("formcam-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("bad.obj");
        std::fs::write(&p, "v 0 0 0\nf 1 1 x\n").unwrap();
        let e = read_mesh(&p, ONE).unwrap_err().to_string();
        assert!(
            e.contains("bad.obj: line 2: expected a vertex index"),
            "{e}"
        );
        let e = read_mesh(&dir.join("part.ply"), ONE)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("part.ply: a mesh is an STL (.stl) or OBJ (.obj) file"),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_visual_mesh_is_the_machines_folders_else_the_shipped_one() {
        let dir = std::env::temp_dir().join(format!("formcam-vmesh-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("meshes")).unwrap();
        let shipped = crate::shipped::SHIPPED_MESHES[0];
        let from_formcam = read_visual_mesh(shipped.file, [2.0; 3], None).unwrap();
        let own = parse_mesh(shipped.bytes, MeshFormat::Stl, [2.0; 3]).unwrap();
        assert_eq!(from_formcam, own);
        // A copied machine without its meshes still finds the shipped one.
        assert_eq!(
            read_visual_mesh(shipped.file, [2.0; 3], Some(&dir)).unwrap(),
            own
        );
        // A file beside the machine comes first.
        std::fs::write(dir.join(shipped.file), ASCII).unwrap();
        let beside = read_visual_mesh(shipped.file, ONE, Some(&dir)).unwrap();
        assert_eq!(beside.triangles.len(), 1);
        let e = read_visual_mesh("meshes/gone.obj", ONE, Some(&dir))
            .unwrap_err()
            .to_string();
        assert!(e.contains("meshes/gone.obj"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
