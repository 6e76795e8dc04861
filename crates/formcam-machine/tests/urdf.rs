//! URDF import: the placement arm as URDF against its TOML machine file.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;

use formcam_machine::links_from_urdf;
use formcam_machine::{JointKind, Machine, MachineError, Shape};
use formcam_machine::{JointType, MachineFile, PointSpec};
use nalgebra::{Isometry3, UnitQuaternion, Vector3};

fn read(path: &str) -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(path);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The placement arm from its TOML file and from `tests/data/arm.urdf`, with the
/// same `[machine]` table and key points (moved into the URDF link frames).
fn arms() -> (Machine, Machine) {
    let text = read("../../machines/placement-arm.toml");
    let toml_arm = Machine::from_toml(&text).unwrap();
    let file: MachineFile = toml::from_str(&text).unwrap();
    // A URDF arm link's frame is the TOML link's frame times the inverse of the
    // link's DH post-transform: a point p of the TOML link lies at post * p.
    let points = file
        .points
        .iter()
        .map(|p| {
            let link = toml_arm.links.iter().find(|l| l.name == p.link).unwrap();
            let xyz = link.joint.post * nalgebra::Point3::from(p.xyz);
            PointSpec {
                name: p.name.clone(),
                link: p.link.clone(),
                xyz: xyz.coords.into(),
            }
        })
        .collect();
    let urdf_arm = Machine::from_urdf(&read("tests/data/arm.urdf"), file.machine, points)
        .unwrap_or_else(|e| panic!("arm.urdf: {e}"));
    (toml_arm, urdf_arm)
}

/// Deterministic pseudo-random numbers in `[0, 1)`.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn rotation_error(a: &Isometry3<f64>, b: &Isometry3<f64>) -> f64 {
    let d = a.rotation.to_rotation_matrix().matrix() - b.rotation.to_rotation_matrix().matrix();
    d.amax()
}

fn translation_error(a: &Isometry3<f64>, b: &Isometry3<f64>) -> f64 {
    (a.translation.vector - b.translation.vector).amax()
}

#[test]
fn urdf_rpy_is_nalgebra_euler_angles() {
    // URDF: roll about fixed x, then pitch about fixed y, then yaw about fixed z.
    let (r, p, y) = (0.3, -1.1, 2.4);
    let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), y)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), p)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), r);
    let e = UnitQuaternion::from_euler_angles(r, p, y);
    let d = q.to_rotation_matrix().matrix() - e.to_rotation_matrix().matrix();
    assert!(d.amax() < 1e-15, "{d}");
}

#[test]
fn arm_matches_its_toml_file() {
    let (t, u) = arms();
    assert_eq!(t.links.len(), u.links.len());
    assert_eq!(t.axes.len(), u.axes.len());
    assert_eq!(u.links[u.roles.mandrel].name, "mandrel");
    assert_eq!(u.axes[u.roles.spindle.unwrap()].name, "A");
    assert_eq!(u.points[u.roles.payout].name, "roller");

    // Axes by NC address: kind and limits (URDF has no homes or jump limits).
    for a in &t.axes {
        let b = &u.axes[u.axis(&a.name).unwrap()];
        assert_eq!(a.kind, b.kind, "{}", a.name);
        assert_eq!(t.links[a.link].name, u.links[b.link].name, "{}", a.name);
        for (x, y) in [(a.min, b.min), (a.max, b.max), (a.v_max, b.v_max)] {
            assert!(x == y || (x - y).abs() < 1e-12, "{}: {x} vs {y}", a.name);
        }
    }

    let mut rng = Lcg(0x5eed);
    for _ in 0..50 {
        // Axis values within the limits (±2 pi, the rotator unlimited).
        let q_toml: Vec<f64> = t
            .axes
            .iter()
            .map(|_| (2.0 * rng.next() - 1.0) * 2.0 * std::f64::consts::PI)
            .collect();
        let q_urdf: Vec<f64> = u
            .axes
            .iter()
            .map(|b| q_toml[t.axis(&b.name).unwrap()])
            .collect();
        let pt = t.poses(&q_toml);
        let pu = u.poses(&q_urdf);

        // Key points by name.
        let kt = t.key_points(&q_toml);
        let ku = u.key_points(&q_urdf);
        for (i, p) in t.points.iter().enumerate() {
            let j = u.points.iter().position(|x| x.name == p.name).unwrap();
            let d = (kt[i] - ku[j]).amax();
            assert!(d < 1e-9, "point {}: {d} mm", p.name);
        }

        // The mandrel and the head, whose frames are the same in both.
        for name in ["mandrel", "head"] {
            let i = t.links.iter().position(|l| l.name == name).unwrap();
            let j = u.links.iter().position(|l| l.name == name).unwrap();
            assert!(translation_error(&pt[i], &pu[j]) < 1e-9, "{name}");
            assert!(rotation_error(&pt[i], &pu[j]) < 1e-12, "{name}");
        }

        // Every link: the TOML frame is the URDF frame times the DH post-transform,
        // and every visual lies at the same place.
        for (i, l) in t.links.iter().enumerate() {
            let j = u.links.iter().position(|x| x.name == l.name).unwrap();
            let expected = pu[j] * l.joint.post;
            assert!(translation_error(&pt[i], &expected) < 1e-9, "{}", l.name);
            assert!(rotation_error(&pt[i], &expected) < 1e-12, "{}", l.name);
            assert_eq!(l.visuals.len(), u.links[j].visuals.len(), "{}", l.name);
            for (a, b) in l.visuals.iter().zip(&u.links[j].visuals) {
                let (wa, wb) = (pt[i] * a.origin, pu[j] * b.origin);
                assert!(translation_error(&wa, &wb) < 1e-9, "{} visual", l.name);
                assert!(rotation_error(&wa, &wb) < 1e-12, "{} visual", l.name);
                assert_eq!(a.color, b.color, "{} visual", l.name);
                let close = |x: f64, y: f64| (x - y).abs() < 1e-9;
                let same = match (&a.shape, &b.shape) {
                    (Shape::Box(x), Shape::Box(y)) => (0..3).all(|k| close(x[k], y[k])),
                    (
                        Shape::Cylinder { radius, length },
                        Shape::Cylinder {
                            radius: r,
                            length: h,
                        },
                    ) => close(*radius, *r) && close(*length, *h),
                    (Shape::Sphere(x), Shape::Sphere(y)) => close(*x, *y),
                    (Shape::Mesh(x), Shape::Mesh(y)) => x == y,
                    _ => false,
                };
                assert!(same, "{}: {:?} vs {:?}", l.name, a.shape, b.shape);
            }
        }
    }
}

#[test]
fn unsupported_joint_type_names_joint_and_type() {
    let text = r#"<robot name="r">
        <link name="base"/>
        <link name="puck"/>
        <joint name="free" type="floating">
            <parent link="base"/>
            <child link="puck"/>
        </joint>
    </robot>"#;
    let e = links_from_urdf(text).unwrap_err();
    assert!(
        matches!(&e, MachineError::Field { place, field, .. } if place == "joint \"free\"" && field == "type"),
        "{e:?}"
    );
    let s = e.to_string();
    assert!(s.contains("free") && s.contains("floating"), "{s}");
    assert!(!s.contains('\n'), "{s}");
}

#[test]
fn malformed_xml_is_a_urdf_error() {
    let e = links_from_urdf(r#"<robot name="r"><link name="a"></robot>"#).unwrap_err();
    match &e {
        MachineError::Urdf(fault) => {
            let m = fault.to_string();
            assert!(!m.is_empty() && !m.contains('\n'), "{m}");
        }
        other => panic!("expected MachineError::Urdf, got {other:?}"),
    }
}

#[test]
fn units_names_limits_and_colours() {
    let text = r#"<robot name="r">
        <material name="red"><color rgba="1 0 0 1"/></material>
        <link name="base">
            <visual>
                <origin xyz="0.001 0 0" rpy="0 0 1.5707963267948966"/>
                <geometry><sphere radius="0.05"/></geometry>
                <material name="red"/>
            </visual>
            <visual>
                <geometry><mesh filename="file://meshes/base.stl" scale="0.001 0.002 0.001"/></geometry>
            </visual>
        </link>
        <link name="carriage"/>
        <link name="spindle"/>
        <link name="tool"/>
        <joint name="slide-x" type="prismatic">
            <parent link="base"/>
            <child link="carriage"/>
            <origin xyz="0.1 0.2 0.3"/>
            <axis xyz="1 0 0"/>
            <limit lower="-0.5" upper="1.5" effort="10" velocity="0.25"/>
        </joint>
        <joint name="C" type="continuous">
            <parent link="carriage"/>
            <child link="spindle"/>
            <limit effort="1" velocity="3.141592653589793"/>
        </joint>
        <joint name="tool_turn" type="revolute">
            <parent link="spindle"/>
            <child link="tool"/>
            <axis xyz="0 1 0"/>
        </joint>
    </robot>"#;
    let links = links_from_urdf(text).unwrap();
    let names: Vec<&str> = links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["base", "carriage", "spindle", "tool"]);

    let base = &links[0];
    assert!(base.parent.is_none() && base.joint.is_none() && !base.driven);
    assert_eq!(base.visuals.len(), 2);
    let s = &base.visuals[0];
    assert_eq!(s.shape, "sphere");
    assert!((s.radius.unwrap() - 50.0).abs() < 1e-12);
    assert!((s.origin.xyz[0] - 1.0).abs() < 1e-12);
    assert!((s.origin.rpy_deg[2] - 90.0).abs() < 1e-12);
    assert_eq!(s.color.as_deref(), Some("#ff0000"));
    let m = &base.visuals[1];
    assert_eq!(m.shape, "mesh");
    // The `file://` prefix dropped; metres times the scale, in mm.
    assert_eq!(m.file.as_deref(), Some("meshes/base.stl"));
    assert_eq!(m.scale, Some([1.0, 2.0, 1.0]));
    assert_eq!(m.color, None);
    // A ROS package name cannot be resolved: refused, naming the link.
    let package = text.replace("file://meshes/base.stl", "package://cell/base.stl");
    let e = links_from_urdf(&package).unwrap_err().to_string();
    assert!(
        e.starts_with("link \"base\": visual.mesh.filename: \"package://cell/base.stl\": package:// names are not resolved"),
        "{e}"
    );

    // A name that is no NC address: J and its place among the movable joints.
    let c = &links[1];
    assert_eq!(c.parent.as_deref(), Some("base"));
    assert_eq!(c.joint, Some(JointType::Prismatic));
    assert!(c.driven);
    assert_eq!(c.axis.as_deref(), Some("J1"));
    assert_eq!(c.direction, Some([1.0, 0.0, 0.0]));
    let o = c.origin.unwrap();
    for (x, y) in o.xyz.iter().zip([100.0, 200.0, 300.0]) {
        assert!((x - y).abs() < 1e-9);
    }
    assert!((c.min_mm.unwrap() + 500.0).abs() < 1e-9);
    assert!((c.max_mm.unwrap() - 1500.0).abs() < 1e-9);
    assert!((c.v_max_mm_min.unwrap() - 15_000.0).abs() < 1e-9);
    assert!(c.min_deg.is_none() && c.v_max_deg_min.is_none());

    // Continuous: revolute without position limits, velocity per minute.
    let s = &links[2];
    assert_eq!(s.joint, Some(JointType::Revolute));
    assert_eq!(s.axis.as_deref(), Some("C"));
    assert!(s.min_deg.is_none() && s.max_deg.is_none());
    assert!((s.v_max_deg_min.unwrap() - 10_800.0).abs() < 1e-9);

    // A revolute joint without <limit>: no limits; the third movable joint.
    let t = &links[3];
    assert_eq!(t.axis.as_deref(), Some("J3"));
    assert!(t.min_deg.is_none() && t.max_deg.is_none() && t.v_max_deg_min.is_none());

    // The links make a machine.
    let table = toml::from_str::<MachineFile>(
        "[machine]\nname = \"r\"\nkind = \"winder\"\nmandrel = \"spindle\"\npayout = \"eye\"\n",
    )
    .unwrap()
    .machine;
    let eye = PointSpec {
        name: "eye".into(),
        link: "tool".into(),
        xyz: [0.0, 0.0, 10.0],
    };
    let m = Machine::from_urdf(text, table, vec![eye]).unwrap();
    assert_eq!(m.axes.len(), 3);
    let x = &m.axes[m.axis("J1").unwrap()];
    assert_eq!(x.kind, JointKind::Prismatic);
    assert!((x.v_max - 250.0).abs() < 1e-9, "{}", x.v_max);
}

#[test]
fn urdf_1_2_omitted_limits_are_unlimited() {
    let text = r#"<robot name="r" version="1.2">
        <link name="base"/>
        <link name="arm"/>
        <joint name="B" type="revolute">
            <parent link="base"/>
            <child link="arm"/>
            <axis xyz="0 0 1"/>
            <limit upper="1.5707963267948966"/>
        </joint>
    </robot>"#;
    let links = links_from_urdf(text).unwrap();
    let arm = &links[1];
    assert!(arm.min_deg.is_none(), "{:?}", arm.min_deg);
    assert!((arm.max_deg.unwrap() - 90.0).abs() < 1e-12);
    assert!(arm.v_max_deg_min.is_none());
}

#[test]
fn joint_problems_are_field_errors() {
    let two_parents = r#"<robot name="r">
        <link name="a"/><link name="b"/><link name="c"/>
        <joint name="j1" type="fixed"><parent link="a"/><child link="c"/></joint>
        <joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint>
    </robot>"#;
    let e = links_from_urdf(two_parents).unwrap_err().to_string();
    assert!(e.contains("j2") && e.contains("j1"), "{e}");

    let no_child = r#"<robot name="r">
        <link name="a"/>
        <joint name="j" type="fixed"><parent link="a"/><child link="ghost"/></joint>
    </robot>"#;
    let e = links_from_urdf(no_child).unwrap_err().to_string();
    assert!(e.contains("ghost"), "{e}");

    let planar = r#"<robot name="r">
        <link name="a"/><link name="b"/>
        <joint name="p" type="planar"><parent link="a"/><child link="b"/></joint>
    </robot>"#;
    let e = links_from_urdf(planar).unwrap_err().to_string();
    assert!(e.contains("\"p\"") && e.contains("planar"), "{e}");
}

/// `machines/placement-arm.urdf`: the arm's URDF with its roles in `<formcam>`.
fn shipped_urdf() -> String {
    read("../../machines/placement-arm.urdf")
}

#[test]
fn a_urdf_document_with_formcam_roles_is_the_toml_arm() {
    let t = Machine::from_toml(&read("../../machines/placement-arm.toml")).unwrap();
    let u = Machine::from_urdf_document(&shipped_urdf()).unwrap();
    assert_eq!(u.name, t.name);
    assert_eq!(u.roles.kind, t.roles.kind);
    assert_eq!(u.points[u.roles.payout].name, "roller");
    assert_eq!(u.axes[u.roles.spindle.unwrap()].name, "A");
    let names = |m: &Machine| m.axes.iter().map(|a| a.name.clone()).collect::<Vec<_>>();
    assert_eq!(names(&u), names(&t));
    let mut rng = Lcg(0xa11);
    for _ in 0..50 {
        let q: Vec<f64> = t
            .axes
            .iter()
            .map(|_| (2.0 * rng.next() - 1.0) * 2.0 * std::f64::consts::PI)
            .collect();
        for (a, b) in t.key_points(&q).iter().zip(u.key_points(&q)) {
            let d = (a - b).amax();
            assert!(d < 1e-9, "{d} mm");
        }
    }
}

#[test]
fn the_extension_chooses_the_machine_reader() {
    let urdf = shipped_urdf();
    let toml = read("../../machines/placement-arm.toml");
    for name in ["arm.urdf", "arm.XML"] {
        let m = Machine::from_file_text(std::path::Path::new(name), &urdf).unwrap();
        assert_eq!(m.name, "fibre-placement arm", "{name}");
        // A URDF document read as TOML is a TOML syntax error, as before.
        let e = Machine::from_file_text(std::path::Path::new("arm.toml"), &urdf).unwrap_err();
        assert!(matches!(e, MachineError::Syntax { .. }), "{e}");
    }
    let m = Machine::from_file_text(std::path::Path::new("arm.toml"), &toml).unwrap();
    assert_eq!(m.name, "fibre-placement arm");
}

#[test]
fn a_urdf_document_without_formcam_roles_says_what_is_missing() {
    let e = Machine::from_urdf_document(&read("tests/data/arm.urdf"))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("URDF: no <formcam> element"), "{e}");
    assert!(e.contains("[machine]") && e.contains("[[point]]"), "{e}");
}

#[test]
fn formcam_roles_errors_name_the_line_in_the_element() {
    let text = shipped_urdf().replace("roller_radius = 25.0", "roller_radius = \"big\"");
    let e = Machine::from_urdf_document(&text).unwrap_err().to_string();
    assert!(e.starts_with("URDF: <formcam> 11:17: "), "{e}");
    // The roles themselves are checked as in a TOML file.
    let text = shipped_urdf().replace("payout = \"roller\"", "payout = \"eye\"");
    let e = Machine::from_urdf_document(&text).unwrap_err().to_string();
    assert!(e.contains("payout"), "{e}");
}

/// An element closed in the wrong place (or left open) names the line of the
/// end tag and the element still open, with its line, as the other URDF
/// errors name their line.
#[test]
fn misnested_elements_name_the_line() {
    let text = shipped_urdf();
    // A link left open: found where its parent closes.
    let open = text.replacen("<link name=\"mandrel\"/>", "<link name=\"mandrel\">", 1);
    let line = |needle: &str| {
        text.lines()
            .position(|l| l.contains(needle))
            .map(|k| k + 1)
            .unwrap()
    };
    let e = Machine::from_urdf_document(&open).unwrap_err().to_string();
    assert_eq!(
        e,
        format!(
            "URDF: line {}: </robot> where <link> of line {} is still open \
             (elements not properly nested)",
            line("</robot>"),
            line("<link name=\"mandrel\"/>")
        )
    );
    // An element closed inside another: `</visual>` inside `<geometry>`.
    let inside = text.replacen(
        "      </geometry>\n      <material name=\"blue\">",
        "      </visual>\n      <material name=\"blue\">",
        1,
    );
    assert_ne!(inside, text);
    let e = Machine::from_urdf_document(&inside)
        .unwrap_err()
        .to_string();
    let at = inside
        .lines()
        .position(|l| l.contains("<material name=\"blue\">"))
        .unwrap();
    assert!(
        e.starts_with(&format!(
            "URDF: line {at}: </visual> where <geometry> of line "
        )),
        "{e}"
    );
}
