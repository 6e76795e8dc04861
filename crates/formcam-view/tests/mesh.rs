//! Mesh solids on the page: `/api/machine` lists every mesh solid (its
//! file, triangles, index, or why it cannot be read) and `/api/mesh/N`
//! sends its triangles, read as the checker reads them — relative to the
//! machine file, scaled by the visual's `scale` (a URDF mesh's `scale`
//! times 1000), a shipped machine's from formcam itself — each vertex at
//! its place once the visual's origin is applied.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_machine::read_mesh;
use formcam_view::{Page, ViewOptions, ViewServer};
use nalgebra::{Point3, Quaternion, Translation3, UnitQuaternion};
use serde_json::Value;

/// An ASCII STL tetrahedron: four triangles on four corners.
const TETRA_STL: &str = "solid tetra
 facet normal 0 0 -1
  outer loop
   vertex 0 0 0
   vertex 0 10 0
   vertex 10 0 0
  endloop
 endfacet
 facet normal 0 -1 0
  outer loop
   vertex 0 0 0
   vertex 10 0 0
   vertex 0 0 10
  endloop
 endfacet
 facet normal -1 0 0
  outer loop
   vertex 0 0 0
   vertex 0 0 10
   vertex 0 10 0
  endloop
 endfacet
 facet normal 1 1 1
  outer loop
   vertex 10 0 0
   vertex 0 10 0
   vertex 0 0 10
  endloop
 endfacet
endsolid tetra
";

/// An OBJ cube of edge 2 about the origin: eight corners, six quads
/// (twelve triangles once fanned).
const CUBE_OBJ: &str = "# a cube
o cube
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
vn 0 0 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
";

/// A fresh folder under the test's scratch space.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A result folder `NAME/out` whose summary names the machine file
/// `NAME/machine/MACHINE_NAME` (holding `machine_text`) relative to its job,
/// the test meshes in `NAME/machine/parts/`.
fn result_with_machine(name: &str, machine_name: &str, machine_text: &str) -> PathBuf {
    let dir = scratch(name);
    let parts = dir.join("machine").join("parts");
    std::fs::create_dir_all(&parts).unwrap();
    std::fs::write(parts.join("tetra.stl"), TETRA_STL).unwrap();
    std::fs::write(parts.join("cube.obj"), CUBE_OBJ).unwrap();
    std::fs::write(dir.join("machine").join(machine_name), machine_text).unwrap();
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    // The machine named relative to the job, as `formcam wind` writes it.
    let summary = serde_json::json!({
        "job": dir.join("job.toml").display().to_string(),
        "machine_file": format!("machine/{machine_name}"),
    });
    std::fs::write(out.join("summary.json"), summary.to_string()).unwrap();
    write_pass(&out);
    out
}

/// No program: the result opens as its path, a pass along a tube.
fn write_pass(out: &Path) {
    std::fs::write(
        out.join("path.csv"),
        "s,z,r,v,alpha,c,mu,alpha_deg,thickness\n\
         0,0,50,0,0.9599,40.96,0,55,0.61\n\
         0.523,0.3,50,0.0086,0.9599,40.96,0,55,0.61\n",
    )
    .unwrap();
}

/// A server for `dir` answering on a background thread: its address.
fn start(dir: &Path) -> std::net::SocketAddr {
    let server = ViewServer::bind(dir, &ViewOptions::default(), Page::none()).unwrap();
    let addr = server.addr();
    let _ = server.spawn();
    addr
}

/// A GET: status and body.
fn get(addr: std::net::SocketAddr, url: &str) -> (u16, Vec<u8>) {
    let a = formcam_testkit::get(addr, url);
    (a.status, a.body)
}

fn get_json(addr: std::net::SocketAddr, url: &str) -> Value {
    let (status, body) = get(addr, url);
    assert_eq!(status, 200, "{url}: {}", String::from_utf8_lossy(&body));
    serde_json::from_slice(&body).unwrap()
}

/// `/api/mesh/N` read back: positions and triangles.
fn mesh(addr: std::net::SocketAddr, n: u64) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let (status, b) = get(addr, &format!("/api/mesh/{n}"));
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&b));
    let u = |at: usize| u32::from_le_bytes(b[at..at + 4].try_into().unwrap());
    let f = |at: usize| f32::from_le_bytes(b[at..at + 4].try_into().unwrap());
    let (nv, nt) = (u(0) as usize, u(4) as usize);
    assert_eq!(b.len(), 8 + 12 * nv + 12 * nt);
    let positions = (0..nv)
        .map(|k| [f(8 + 12 * k), f(12 + 12 * k), f(16 + 12 * k)])
        .collect();
    let at = 8 + 12 * nv;
    let triangles = (0..nt)
        .map(|k| [u(at + 12 * k), u(at + 12 * k + 4), u(at + 12 * k + 8)])
        .collect();
    (positions, triangles)
}

/// The solids of link `link` in `/api/machine`.
fn solids<'a>(machine: &'a Value, link: &str) -> &'a Vec<Value> {
    machine["links"]
        .as_array()
        .unwrap()
        .iter()
        .find(|l| l["name"] == link)
        .unwrap()["solids"]
        .as_array()
        .unwrap()
}

/// The vertices of a mesh placed by its solid's `origin`, in the link's frame.
fn placed(solid: &Value, positions: &[[f32; 3]]) -> Vec<Point3<f64>> {
    let o: Vec<f64> = solid["origin"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let q = UnitQuaternion::from_quaternion(Quaternion::new(o[6], o[3], o[4], o[5]));
    let t = Translation3::new(o[0], o[1], o[2]);
    positions
        .iter()
        .map(|p| t * (q * Point3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))))
        .collect()
}

fn has_point(points: &[Point3<f64>], want: Point3<f64>) -> bool {
    points.iter().any(|p| (p - want).norm() < 1e-5)
}

#[test]
fn stl_and_obj_meshes_of_a_toml_machine_are_sent_scaled_and_placed() {
    let shipped = formcam_machine::shipped::shipped("winder-4axis")
        .unwrap()
        .text;
    let at = shipped.find("[[point]]").unwrap();
    // On the last link (the eye): the tetrahedron scaled (1, 2, 3), turned
    // 90 degrees about x and moved 5 mm along x; the cube as it is; a mesh
    // that is not there.
    let visuals = r##"[[link.visual]]
shape = "mesh"
file = "parts/tetra.stl"
scale = [1.0, 2.0, 3.0]
origin = { xyz = [5.0, 0.0, 0.0], rpy_deg = [90.0, 0.0, 0.0] }

[[link.visual]]
shape = "mesh"
file = "parts/cube.obj"
color = "#aa5500"

[[link.visual]]
shape = "mesh"
file = "parts/gone.stl"

"##;
    let text = format!("{}{visuals}{}", &shipped[..at], &shipped[at..]);
    let out = result_with_machine("mesh-toml", "m.toml", &text);
    let addr = start(&out);
    let machine = get_json(addr, "/api/machine");
    let eye = solids(&machine, "eye");
    assert_eq!(eye.len(), 4);
    let (tetra, cube, gone) = (&eye[1], &eye[2], &eye[3]);
    assert_eq!(tetra["shape"], "mesh");
    assert_eq!(tetra["file"], "parts/tetra.stl");
    assert_eq!(
        (tetra["triangles"].as_u64(), tetra["drawn"].as_u64()),
        (Some(4), Some(4))
    );
    assert_eq!(cube["color"], "#aa5500");

    let (p, t) = mesh(addr, tetra["mesh"].as_u64().unwrap());
    assert_eq!((p.len(), t.len()), (4, 4));
    let points = placed(tetra, &p);
    // (0, 0, 10) scaled to (0, 0, 30), turned about x to (0, -30, 0), moved.
    assert!(
        has_point(&points, Point3::new(5.0, -30.0, 0.0)),
        "{points:?}"
    );
    // (0, 10, 0) to (0, 20, 0), then (0, 0, 20), moved.
    assert!(
        has_point(&points, Point3::new(5.0, 0.0, 20.0)),
        "{points:?}"
    );
    // Each triangle's corners as the file gives them, in order.
    let file_tri = [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 0.0, 30.0]];
    let second: Vec<[f32; 3]> = t[1].iter().map(|&i| p[i as usize]).collect();
    assert_eq!(second, file_tri.map(|c| c.map(|v: f64| v as f32)));

    let (p, t) = mesh(addr, cube["mesh"].as_u64().unwrap());
    assert_eq!((p.len(), t.len()), (8, 12));
    assert!(p.iter().all(|c| c.iter().all(|v| v.abs() == 1.0)));
    assert_eq!(cube["triangles"], 12);

    // A missing mesh is no gap: the solid says why, naming the file.
    assert!(gone.get("mesh").is_none());
    let why = gone["error"].as_str().unwrap();
    assert!(why.contains("parts/gone.stl"), "{why}");
    assert_eq!(gone["drawn"], 0);

    // Only the meshes listed are served; nothing is taken from the URL.
    let listed = machine["links"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|l| l["solids"].as_array().unwrap())
        .filter(|s| s.get("mesh").is_some())
        .count();
    // The shipped winder's flange, the tetrahedron and the cube.
    assert_eq!(listed, 3);
    assert_eq!(get(addr, &format!("/api/mesh/{listed}")).0, 404);
    assert_eq!(get(addr, "/api/mesh/parts").0, 404);
    assert_eq!(get(addr, "/api/mesh/-1").0, 404);
    assert_eq!(get(addr, "/api/mesh/..%2fm.toml").0, 400);
    assert_eq!(get(addr, "/api/mesh/0/1").0, 404);
}

#[test]
fn a_urdf_mesh_is_in_metres_times_its_scale() {
    let arm = std::fs::read_to_string(repo().join("machines/placement-arm.urdf")).unwrap();
    let flange = r#"<link name="flange">
    <visual>
      <origin xyz="0 0 0.01" rpy="0 0 1.5707963267948966"/>
      <geometry>
        <mesh filename="parts/cube.obj" scale="0.002 0.002 0.002"/>
      </geometry>
    </visual>
  </link>"#;
    assert!(arm.contains("<link name=\"flange\"/>"));
    let text = arm.replace("<link name=\"flange\"/>", flange);
    let out = result_with_machine("mesh-urdf", "arm.urdf", &text);
    let addr = start(&out);
    let machine = get_json(addr, "/api/machine");
    let solid = &solids(&machine, "flange")[0];
    assert_eq!(solid["shape"], "mesh");
    let (p, t) = mesh(addr, solid["mesh"].as_u64().unwrap());
    assert_eq!((p.len(), t.len()), (8, 12));
    // A corner (1, 1, 1) is at 2 mm a side (0.002 m per unit), turned a
    // quarter about z, 10 mm up.
    let points = placed(solid, &p);
    assert!(
        has_point(&points, Point3::new(-2.0, 2.0, 12.0)),
        "{points:?}"
    );
    assert!(
        has_point(&points, Point3::new(2.0, -2.0, 8.0)),
        "{points:?}"
    );
}

#[test]
fn the_shipped_winders_chuck_flange_is_sent_from_formcam_itself() {
    let dir = scratch("mesh-shipped");
    std::fs::write(
        dir.join("summary.json"),
        r#"{"job": "vessel.toml", "machine_shipped": "winder-4axis"}"#,
    )
    .unwrap();
    write_pass(&dir);
    let addr = start(&dir);
    let machine = get_json(addr, "/api/machine");
    let solid = solids(&machine, "mandrel")
        .iter()
        .find(|s| s["shape"] == "mesh")
        .unwrap();
    assert_eq!(solid["file"], "meshes/chuck-flange.stl");
    let file = read_mesh(&repo().join("machines/meshes/chuck-flange.stl"), [1.0; 3]).unwrap();
    assert_eq!(solid["triangles"], file.triangles.len());
    let (p, t) = mesh(addr, solid["mesh"].as_u64().unwrap());
    assert_eq!(t.len(), file.triangles.len());
    // Every triangle's corners are the file's, in order.
    for (drawn, f) in t.iter().zip(&file.triangles) {
        for k in 0..3 {
            let (a, b) = (p[drawn[k] as usize], file.vertices[f[k] as usize]);
            assert!(
                (f64::from(a[0]) - b.x).abs()
                    + (f64::from(a[1]) - b.y).abs()
                    + (f64::from(a[2]) - b.z).abs()
                    < 1e-9,
                "{a:?} {b:?}"
            );
        }
    }
}
