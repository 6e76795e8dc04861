//! Import of URDF robot descriptions: each URDF link becomes a [`LinkSpec`] hung
//! on its parent by the URDF joint whose child it is.
//!
//! URDF and the machine file place a joint the same way: the joint frame is the
//! parent's frame moved by `origin` (translation, then roll-pitch-yaw about the
//! fixed x, y, z axes), and the joint turns about or slides along `axis` in that
//! frame. Only the units change: metres become mm, radians become degrees and
//! velocities per second become velocities per minute.

use std::collections::{HashMap, HashSet};

use serde::Deserialize;

use crate::file::{
    CollisionSpec, JointType, LinkSpec, MachineFile, MachineTable, OriginSpec, PointSpec,
    VisualSpec,
};
use crate::machine::{Machine, line_col};
use crate::{MachineError, UrdfFault};

/// Millimetres per metre.
const MM: f64 = 1000.0;

/// The machine-file links of a URDF document.
///
/// One [`LinkSpec`] per URDF `<link>`, in document order; the URDF `<joint>`
/// whose child is the link becomes its joint (the root link has none):
///
/// - `revolute` and `continuous` become revolute joints (a `continuous` joint
///   has no position limits), `prismatic` a prismatic joint, `fixed` a fixed
///   one; `floating`, `planar` and `spherical` joints, and `mimic` joints, are
///   errors.
/// - `origin` becomes the joint's origin (m → mm, rad → degrees) and `axis` its
///   direction.
/// - Movable joints are driven. Their NC address is the joint's name when that
///   is a valid address (ASCII letters and digits only, like `J1` or `A`);
///   otherwise it is `J` followed by the joint's 1-based position among the
///   movable joints in document order (the next free number when another joint
///   already uses that address).
/// - `<limit lower upper>` (rad or m) become `min_deg`/`max_deg` or
///   `min_mm`/`max_mm`; a limit that is infinite (URDF 1.2 and later: omitted),
///   or `lower` and `upper` both 0 (what URDF 1.0 and 1.1 read when they are
///   omitted), means no limit.
///   `velocity` (rad/s or m/s) becomes `v_max_deg_min` or `v_max_mm_min` (per
///   minute); 0 or infinite means no limit. Effort, dynamics, calibration and
///   safety controllers are not used; URDF has no home values (they are 0).
/// - Visuals with a `box`, `cylinder`, `sphere` or `mesh` geometry become
///   visuals with their sizes and origin in mm; a mesh keeps its file name as
///   written (relative to the URDF file; a `file://` prefix is dropped, a
///   `package://` name is an error) and its vertices, in metres, are
///   multiplied by its `scale` times 1000 (a mesh drawn in mm has scale 0.001). The colour is the material's `rgba` as
///   `#rrggbb` (a material given by name only takes the colour of the document's
///   material of that name), else the default. A `capsule` is an error.
/// - Inertials and collision geometry are ignored.
///
/// # Errors
///
/// [`MachineError::Urdf`] when urdf-rs cannot read the document,
/// [`MachineError::Field`] (at `joint "<name>"` or `link "<name>"`) for an
/// unsupported joint type, a mimic joint, a joint whose child is not a link or a
/// link that is the child of two joints, and a capsule visual. The links
/// themselves are checked by [`Machine::from_file`].
pub fn links_from_urdf(text: &str) -> Result<Vec<LinkSpec>, MachineError> {
    let robot = urdf_rs::read_from_string(text)
        .map_err(|e| UrdfFault::from(e).misnested(misnested(text)))?;
    let link_names: HashSet<&str> = robot.links.iter().map(|l| l.name.as_str()).collect();
    let materials: HashMap<&str, &urdf_rs::Color> = robot
        .materials
        .iter()
        .filter_map(|m| m.color.as_ref().map(|c| (m.name.as_str(), c)))
        .collect();

    // The joint of each link and the NC addresses of the movable joints.
    let mut joint_of: HashMap<&str, &urdf_rs::Joint> = HashMap::new();
    for j in &robot.joints {
        let place = format!("joint \"{}\"", j.name);
        let child = j.child.link.as_str();
        if !link_names.contains(child) {
            return Err(MachineError::field(
                place,
                "child",
                format!("no link is named \"{child}\""),
            ));
        }
        if let Some(other) = joint_of.insert(child, j) {
            return Err(MachineError::field(
                place,
                "child",
                format!(
                    "link \"{child}\" is already the child of joint \"{}\"",
                    other.name
                ),
            ));
        }
        joint_type(j)?;
        if j.mimic.is_some() {
            return Err(MachineError::field(
                place,
                "mimic",
                "mimic joints are not supported (each movable joint is a driven axis)",
            ));
        }
    }
    let addresses = addresses(&robot.joints)?;

    robot
        .links
        .iter()
        .map(|l| {
            let place = format!("link \"{}\"", l.name);
            let visuals = l
                .visual
                .iter()
                .map(|v| visual(v, &materials, &place))
                .collect::<Result<Vec<_>, _>>()?;
            let mut spec = LinkSpec {
                name: l.name.clone(),
                parent: None,
                joint: None,
                driven: false,
                axis: None,
                dh: None,
                origin: None,
                direction: None,
                min_deg: None,
                max_deg: None,
                v_max_deg_min: None,
                dv_max_deg_min: None,
                min_mm: None,
                max_mm: None,
                v_max_mm_min: None,
                dv_max_mm_min: None,
                modulo: None,
                home_deg: None,
                home_mm: None,
                a_max_deg_s2: None,
                a_max_mm_s2: None,
                value_deg: None,
                value_mm: None,
                visuals,
            };
            if let Some(j) = joint_of.get(l.name.as_str()) {
                set_joint(&mut spec, j, &addresses)?;
            }
            Ok(spec)
        })
        .collect()
}

/// Where the elements of a URDF document are not properly nested (an end
/// tag that is not the innermost open element's: an element closed in the
/// wrong place, or one left open): the line of that end tag and the element
/// still open, with the line it opened on. `None` when the elements nest (or
/// the XML fails first on something else, which urdf-rs then reports).
///
/// XML readers say only that the elements are not properly nested; the
/// document is read again here, a line at a time, to find where.
fn misnested(text: &str) -> Option<String> {
    let mut parser = rustyxml::Parser::new();
    let mut open: Vec<(String, usize)> = Vec::new();
    for (k, line) in text.split_inclusive('\n').enumerate() {
        let lineno = k + 1;
        parser.feed_str(line);
        for event in &mut parser {
            match event {
                Ok(rustyxml::Event::ElementStart(tag)) => open.push((tag.name, lineno)),
                Ok(rustyxml::Event::ElementEnd(tag)) => {
                    let message = match open.pop() {
                        // The root closed: what follows is not read.
                        Some((name, _)) if name == tag.name && open.is_empty() => return None,
                        Some((name, _)) if name == tag.name => continue,
                        Some((name, at)) => format!(
                            "line {lineno}: </{}> where <{}> of line {at} is still open \
                             (elements not properly nested)",
                            formcam_files::quote(&tag.name),
                            formcam_files::quote(&name),
                        ),
                        None => format!(
                            "line {lineno}: </{}> after the root element is closed \
                             (elements not properly nested)",
                            formcam_files::quote(&tag.name),
                        ),
                    };
                    return Some(message);
                }
                Ok(_) => {}
                Err(_) => return None,
            }
        }
    }
    None
}

/// The machine-file joint type of a URDF joint.
fn joint_type(j: &urdf_rs::Joint) -> Result<JointType, MachineError> {
    match j.joint_type {
        urdf_rs::JointType::Revolute | urdf_rs::JointType::Continuous => Ok(JointType::Revolute),
        urdf_rs::JointType::Prismatic => Ok(JointType::Prismatic),
        urdf_rs::JointType::Fixed => Ok(JointType::Fixed),
        ref other => {
            let name = format!("{other:?}").to_ascii_lowercase();
            Err(MachineError::field(
                format!("joint \"{}\"", j.name),
                "type",
                format!(
                    "joint type \"{name}\" is not supported (revolute, continuous, prismatic or fixed)"
                ),
            ))
        }
    }
}

/// Whether `name` is a valid NC address.
fn is_address(name: &str) -> bool {
    !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric())
}

/// The NC address of each movable joint, by joint name.
fn addresses(joints: &[urdf_rs::Joint]) -> Result<HashMap<&str, String>, MachineError> {
    let mut movable = Vec::new();
    for j in joints {
        if joint_type(j)? != JointType::Fixed {
            movable.push(j.name.as_str());
        }
    }
    let mut taken: HashSet<String> = movable
        .iter()
        .filter(|n| is_address(n))
        .map(|n| n.to_string())
        .collect();
    let mut out = HashMap::new();
    for (k, name) in movable.iter().enumerate() {
        let address = if is_address(name) {
            name.to_string()
        } else {
            let mut n = k + 1;
            while taken.contains(&format!("J{n}")) {
                n += 1;
            }
            let a = format!("J{n}");
            taken.insert(a.clone());
            a
        };
        out.insert(*name, address);
    }
    Ok(out)
}

/// A URDF pose as a machine-file origin (mm, degrees).
fn origin(p: &urdf_rs::Pose) -> OriginSpec {
    OriginSpec {
        xyz: p.xyz.0.map(|v| v * MM),
        rpy_deg: p.rpy.0.map(f64::to_degrees),
    }
}

/// A finite limit, scaled; none when infinite.
fn limit(v: f64, scale: f64) -> Option<f64> {
    (!v.is_infinite()).then_some(v * scale)
}

/// Fills the joint fields of `spec` from the URDF joint `j`.
fn set_joint(
    spec: &mut LinkSpec,
    j: &urdf_rs::Joint,
    addresses: &HashMap<&str, String>,
) -> Result<(), MachineError> {
    let kind = joint_type(j)?;
    spec.parent = Some(j.parent.link.clone());
    spec.joint = Some(kind);
    spec.origin = Some(origin(&j.origin));
    if kind == JointType::Fixed {
        return Ok(());
    }
    spec.direction = Some(j.axis.xyz.0);
    spec.driven = true;
    spec.axis = addresses.get(j.name.as_str()).cloned();
    let l = &j.limit;
    let bounded =
        j.joint_type != urdf_rs::JointType::Continuous && !(l.lower == 0.0 && l.upper == 0.0);
    let v = (l.velocity != 0.0 && !l.velocity.is_infinite()).then_some(l.velocity);
    if kind == JointType::Revolute {
        let deg = 1f64.to_degrees();
        if bounded {
            spec.min_deg = limit(l.lower, deg);
            spec.max_deg = limit(l.upper, deg);
        }
        spec.v_max_deg_min = v.map(|v| v * deg * 60.0);
    } else {
        if bounded {
            spec.min_mm = limit(l.lower, MM);
            spec.max_mm = limit(l.upper, MM);
        }
        spec.v_max_mm_min = v.map(|v| v * MM * 60.0);
    }
    Ok(())
}

/// `#rrggbb` of an `rgba` colour with components in `[0, 1]`.
fn hex(c: &urdf_rs::Color) -> String {
    let [r, g, b, _] = c.rgba.0.map(|v| {
        let v = if v.is_finite() {
            v.clamp(0.0, 1.0)
        } else {
            0.0
        };
        (v * 255.0).round() as u8
    });
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// A URDF visual as a machine-file visual (mm).
fn visual(
    v: &urdf_rs::Visual,
    materials: &HashMap<&str, &urdf_rs::Color>,
    place: &str,
) -> Result<VisualSpec, MachineError> {
    let mut spec = VisualSpec {
        shape: String::new(),
        size: None,
        radius: None,
        length: None,
        file: None,
        scale: None,
        origin: origin(&v.origin),
        color: v.material.as_ref().and_then(|m| {
            m.color
                .as_ref()
                .or_else(|| materials.get(m.name.as_str()).copied())
                .map(hex)
        }),
    };
    match &v.geometry {
        urdf_rs::Geometry::Box { size } => {
            spec.shape = "box".into();
            spec.size = Some(size.0.map(|s| s * MM));
        }
        urdf_rs::Geometry::Cylinder { radius, length } => {
            spec.shape = "cylinder".into();
            spec.radius = Some(radius * MM);
            spec.length = Some(length * MM);
        }
        urdf_rs::Geometry::Sphere { radius } => {
            spec.shape = "sphere".into();
            spec.radius = Some(radius * MM);
        }
        urdf_rs::Geometry::Mesh { filename, scale } => {
            if filename.starts_with("package://") {
                return Err(MachineError::field(
                    place,
                    "visual.mesh.filename",
                    format!(
                        "\"{}\": package:// names are not resolved (no ROS package path); \
                         give the file relative to the URDF file",
                        formcam_files::excerpt(filename)
                    ),
                ));
            }
            spec.shape = "mesh".into();
            spec.file = Some(
                filename
                    .strip_prefix("file://")
                    .unwrap_or(filename)
                    .to_string(),
            );
            // URDF meshes are in metres times their scale.
            let s = scale.as_ref().map_or([1.0; 3], |s| s.0);
            spec.scale = Some(s.map(|v| v * MM));
        }
        urdf_rs::Geometry::Capsule { .. } => {
            return Err(MachineError::field(
                place,
                "visual",
                "capsule geometry is not supported (box, cylinder, sphere or mesh)",
            ));
        }
    }
    Ok(spec)
}

impl Machine {
    /// Reads a machine from a URDF document (see [`links_from_urdf`]) with the
    /// `[machine]` table and key points that URDF has no place for.
    ///
    /// # Errors
    ///
    /// Those of [`links_from_urdf`] and [`Machine::from_file`].
    pub fn from_urdf(
        text: &str,
        machine: MachineTable,
        points: Vec<PointSpec>,
    ) -> Result<Machine, MachineError> {
        let file = MachineFile {
            machine,
            links: links_from_urdf(text)?,
            points,
            collision: None,
        };
        Machine::from_file(&file)
    }

    /// Reads a machine from a whole URDF document: the links from the URDF
    /// (see [`links_from_urdf`]), the `[machine]` table and the `[[point]]`
    /// key points from the text of its `<formcam>` element, a child of
    /// `<robot>` (an extension element, which other URDF readers skip),
    /// written as in a TOML machine file (mm, degrees; points in the URDF
    /// link frames):
    ///
    /// ```xml
    /// <robot name="arm">
    ///   ...
    ///   <formcam><![CDATA[
    ///   [machine]
    ///   name = "arm"
    ///   kind = "placement"
    ///   ...
    ///   [[point]]
    ///   name = "roller"
    ///   link = "head"
    ///   xyz = [0.0, 0.0, 175.0]
    ///   ]]></formcam>
    /// </robot>
    /// ```
    ///
    /// # Errors
    ///
    /// [`MachineError::Urdf`] when the document cannot be read, has no
    /// `<formcam>` element or its text is no valid `[machine]` table and
    /// points (the line and column counted in that text); then those of
    /// [`Machine::from_urdf`].
    pub fn from_urdf_document(text: &str) -> Result<Machine, MachineError> {
        let links = links_from_urdf(text)?;
        let roles = formcam_roles(text)?;
        Machine::from_file(&MachineFile {
            machine: roles.machine,
            links,
            points: roles.points,
            collision: roles.collision,
        })
    }
}

/// What URDF has no place for: the `<formcam>` element's TOML.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FormcamRoles {
    /// The `[machine]` table.
    machine: MachineTable,
    /// The key points.
    #[serde(default, rename = "point")]
    points: Vec<PointSpec>,
    /// The `[collision]` table.
    #[serde(default)]
    collision: Option<CollisionSpec>,
}

/// The roles in the `<formcam>` element of a URDF document (already read by
/// urdf-rs, so well-formed).
fn formcam_roles(text: &str) -> Result<FormcamRoles, MachineError> {
    let robot: rustyxml::Element =
        text.parse()
            .map_err(|e: rustyxml::BuilderError| MachineError::Xml {
                message: e.to_string(),
            })?;
    let element = robot
        .get_child("formcam", None)
        .ok_or(MachineError::NoFormcamElement)?;
    let roles = element.content_str();
    toml::from_str(&roles).map_err(|e| {
        let at = e.span().map_or(roles.len(), |s| s.start);
        let (line, column) = e.span().map_or((0, 0), |s| line_col(&roles, s.start));
        MachineError::FormcamElement {
            line,
            column,
            message: formcam_files::syntax_message(e.message(), &roles, at).replace('\n', " "),
        }
    })
}
