//! The machine file as users write it (TOML), before validation.

use serde::Deserialize;

/// A machine file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MachineFile {
    /// The `[machine]` table: what the chain is for.
    pub machine: MachineTable,
    /// The links, each with the joint that connects it to its parent.
    #[serde(default, rename = "link")]
    pub links: Vec<LinkSpec>,
    /// Key points fixed to links.
    #[serde(default, rename = "point")]
    pub points: Vec<PointSpec>,
    /// How the simulator checks the solids for collisions.
    #[serde(default)]
    pub collision: Option<CollisionSpec>,
}

/// The `[collision]` table: the clearance the simulator keeps between
/// solids, the pairs of links it does not check, and the bed.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CollisionSpec {
    /// The clearance every pair of solids must keep, mm (default 5).
    pub margin_mm: Option<f64>,
    /// Pairs of links whose solids are not checked against each other
    /// (besides solids on one link and on links joined directly).
    #[serde(default)]
    pub ignore: Vec<[String; 2]>,
    /// The bed as a plane: everything below this height (world `z`, mm).
    pub bed_z_mm: Option<f64>,
    /// The bed as a solid in the world frame (a `[[link.visual]]` table).
    pub bed: Option<VisualSpec>,
}

/// What kind of machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MachineKind {
    /// A filament winder: the band leaves the payout point towards the mandrel.
    Winder,
    /// A fibre-placement head: a compaction roller presses the band on the mandrel.
    Placement,
}

/// Which point the spindle keeps facing the delivery head.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpindleFollows {
    /// The eye (the payout point stays in one plane with the spindle axis).
    Eye,
    /// The path point (the eye may leave that plane; a vertical axis follows it).
    Path,
}

/// The `[machine]` table.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MachineTable {
    /// Name shown in reports.
    pub name: String,
    /// `winder` or `placement`.
    pub kind: MachineKind,
    /// The link that carries the mandrel: its `z` axis is the mandrel's axis, its
    /// origin the mandrel's `z = 0`, its `x` axis the mandrel's `v = 0`.
    pub mandrel: String,
    /// NC address of the axis that turns the mandrel, if any.
    pub spindle: Option<String>,
    /// What the spindle keeps facing the head: `eye` (default) or `path`.
    pub spindle_follows: Option<SpindleFollows>,
    /// The key point where the band leaves the machine (winder) or the centre of
    /// the compaction roller (placement).
    pub payout: String,
    /// Direction fixed to the payout point's link: the axis of the eye roller or
    /// of the compaction roller.
    pub roller_axis: Option<[f64; 3]>,
    /// Placement: direction fixed to the payout point's link that presses into the
    /// mandrel (it is kept along the inward surface normal).
    pub head_normal: Option<[f64; 3]>,
    /// Placement: radius `h` of the compaction roller, mm.
    pub roller_radius: Option<f64>,
    /// The key points the band passes, from the creel to the payout point.
    pub band_path: Option<Vec<String>>,
}

/// A joint type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JointType {
    /// Turns about its axis.
    Revolute,
    /// Slides along its axis.
    Prismatic,
    /// Rigid.
    Fixed,
}

/// Denavit–Hartenberg parameters (distal convention:
/// `Rz(theta) Tz(d) Tx(a) Rx(alpha)`, the joint turning `theta` or sliding `d`).
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DhSpec {
    /// Common normal length, mm.
    #[serde(default)]
    pub a: f64,
    /// Twist, degrees.
    #[serde(default)]
    pub alpha_deg: f64,
    /// Offset along `z`, mm.
    #[serde(default)]
    pub d: f64,
    /// Angle about `z`, degrees.
    #[serde(default)]
    pub theta_deg: f64,
}

/// A plain transform: translation, then roll-pitch-yaw (about fixed x, y, z).
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OriginSpec {
    /// Translation, mm.
    #[serde(default)]
    pub xyz: [f64; 3],
    /// Roll, pitch, yaw, degrees.
    #[serde(default)]
    pub rpy_deg: [f64; 3],
}

/// A link and the joint to its parent.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinkSpec {
    /// Unique name.
    pub name: String,
    /// Parent link; none for the base.
    pub parent: Option<String>,
    /// Joint type (`fixed` when absent).
    pub joint: Option<JointType>,
    /// Whether an actuator drives the joint.
    #[serde(default)]
    pub driven: bool,
    /// NC address of a driven joint (`X`, `A`, ...).
    pub axis: Option<String>,
    /// Denavit–Hartenberg parameters (the joint moves about/along the parent's `z`).
    pub dh: Option<DhSpec>,
    /// Plain transform to the joint frame (the joint then moves along `direction`).
    pub origin: Option<OriginSpec>,
    /// Joint direction in the joint frame (with `origin`; default `[0, 0, 1]`).
    pub direction: Option<[f64; 3]>,
    /// Revolute limits, degrees.
    pub min_deg: Option<f64>,
    /// Revolute limits, degrees.
    pub max_deg: Option<f64>,
    /// Revolute velocity limit, degrees per minute.
    pub v_max_deg_min: Option<f64>,
    /// Revolute velocity-jump limit between blocks, degrees per minute.
    pub dv_max_deg_min: Option<f64>,
    /// Prismatic limits, mm.
    pub min_mm: Option<f64>,
    /// Prismatic limits, mm.
    pub max_mm: Option<f64>,
    /// Prismatic velocity limit, mm per minute.
    pub v_max_mm_min: Option<f64>,
    /// Prismatic velocity-jump limit between blocks, mm per minute.
    pub dv_max_mm_min: Option<f64>,
    /// Revolute acceleration limit, degrees per s² (the option `[motion] acceleration`).
    pub a_max_deg_s2: Option<f64>,
    /// Prismatic acceleration limit, mm per s².
    pub a_max_mm_s2: Option<f64>,
    /// A driven revolute joint the controller holds within a turn (a modulo
    /// rotary axis: re-zeroed or written modulo 360° in the program). Only
    /// for revolute joints without `min_deg`/`max_deg`; default: true for the
    /// machine's spindle when it has no limits, false otherwise.
    pub modulo: Option<bool>,
    /// Home value of a driven revolute joint (where inverse kinematics starts), degrees.
    pub home_deg: Option<f64>,
    /// Home value of a driven prismatic joint, mm.
    pub home_mm: Option<f64>,
    /// Value of an undriven (constructive) revolute joint, degrees.
    pub value_deg: Option<f64>,
    /// Value of an undriven (constructive) prismatic joint, mm.
    pub value_mm: Option<f64>,
    /// Geometry for the viewer.
    #[serde(default, rename = "visual")]
    pub visuals: Vec<VisualSpec>,
}

/// A solid for the viewer, in the link's frame.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VisualSpec {
    /// `box`, `cylinder` (along local `z`), `sphere` or `mesh`.
    pub shape: String,
    /// Box edge lengths, mm.
    pub size: Option<[f64; 3]>,
    /// Cylinder or sphere radius, mm.
    pub radius: Option<f64>,
    /// Cylinder length, mm.
    pub length: Option<f64>,
    /// Mesh: an STL or OBJ file, relative to the machine file.
    pub file: Option<String>,
    /// Mesh: the factor per axis its vertices are multiplied by (default 1).
    pub scale: Option<[f64; 3]>,
    /// Placement in the link's frame.
    #[serde(default)]
    pub origin: OriginSpec,
    /// Colour, `#rrggbb`.
    pub color: Option<String>,
}

/// A key point fixed to a link.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointSpec {
    /// Unique name.
    pub name: String,
    /// The link it is fixed to.
    pub link: String,
    /// Position in the link's frame, mm.
    #[serde(default)]
    pub xyz: [f64; 3],
}
