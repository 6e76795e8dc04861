//! The validated machine: a tree of links, its driven axes, key points and
//! solids. The machine file checked into this model is `validate`'s, the
//! reference forward kinematics `poses`'s, the readable table `table`'s.

use nalgebra::{Isometry3, Point3, Unit, Vector3};

use crate::collision::Collision;
use crate::file::{MachineKind, SpindleFollows};

mod poses;
mod table;
mod validate;

pub(crate) use validate::{line_col, visual};

/// How a joint moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointKind {
    /// Turns about its direction, rad.
    Revolute,
    /// Slides along its direction, mm.
    Prismatic,
    /// Rigid.
    Fixed,
}

/// The joint between a link and its parent: `pre * motion(q) * post`.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Type.
    pub kind: JointKind,
    /// Transform before the motion (a plain origin; identity for DH).
    pub pre: Isometry3<f64>,
    /// Direction of the motion in the frame after `pre`.
    pub direction: Unit<Vector3<f64>>,
    /// Transform after the motion (the DH part; identity for a plain origin).
    pub post: Isometry3<f64>,
    /// Index into [`Machine::axes`] when driven.
    pub axis: Option<usize>,
    /// The value of an undriven joint (rad or mm).
    pub value: f64,
    /// Whether `post` is the identity (a plain origin), so its product is skipped.
    plain: bool,
    /// Whether `pre` is the identity (DH parameters).
    dh: bool,
}

/// A solid for the viewer.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A box with edge lengths, centred on the origin, mm.
    Box([f64; 3]),
    /// A cylinder along local `z`, centred on the origin.
    Cylinder {
        /// Radius, mm.
        radius: f64,
        /// Length, mm.
        length: f64,
    },
    /// A sphere, mm.
    Sphere(f64),
    /// An STL or OBJ mesh, the path as written in the machine file
    /// (relative to it; read by [`crate::read_mesh`] when needed).
    Mesh(String),
}

/// A solid placed in a link's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Visual {
    /// The solid.
    pub shape: Shape,
    /// Its placement in the link's frame.
    pub origin: Isometry3<f64>,
    /// Colour `#rrggbb`.
    pub color: String,
    /// A mesh's factor per axis (its vertices as read times this; 1 for
    /// other shapes).
    pub scale: [f64; 3],
}

/// A link.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Name.
    pub name: String,
    /// Parent index (links are ordered parents first); none for the base.
    pub parent: Option<usize>,
    /// The joint to the parent.
    pub joint: Joint,
    /// Solids.
    pub visuals: Vec<Visual>,
}

/// A driven axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// NC address.
    pub name: String,
    /// The link it moves.
    pub link: usize,
    /// Revolute (rad) or prismatic (mm).
    pub kind: JointKind,
    /// Lower limit (rad or mm; `-inf` when unlimited).
    pub min: f64,
    /// Upper limit.
    pub max: f64,
    /// Velocity limit, rad/s or mm/s (`inf` when not given).
    pub v_max: f64,
    /// Velocity-jump limit between blocks, rad/s or mm/s.
    pub dv_max: f64,
    /// Acceleration limit, rad/s² or mm/s² (`inf` when not given).
    pub a_max: f64,
    /// Home value (rad or mm), where inverse kinematics starts.
    pub home: f64,
    /// The controller holds the axis within a turn (a modulo rotary axis;
    /// the machine file's `modulo`, by default the unlimited spindle).
    pub modulo: bool,
}

impl Axis {
    /// Whether the axis turns (its values are angles).
    pub fn is_rotary(&self) -> bool {
        self.kind == JointKind::Revolute
    }
}

/// A point fixed to a link.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyPoint {
    /// Name.
    pub name: String,
    /// Link.
    pub link: usize,
    /// Position in the link's frame, mm.
    pub position: Point3<f64>,
}

/// What the chain is for: the roles the inverse kinematics needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Roles {
    /// Winder or placement head.
    pub kind: MachineKind,
    /// The link carrying the mandrel frame.
    pub mandrel: usize,
    /// The axis turning the mandrel.
    pub spindle: Option<usize>,
    /// What the spindle keeps facing the head.
    pub spindle_follows: SpindleFollows,
    /// The payout point (or roller centre), an index into the key points.
    pub payout: usize,
    /// Roller axis, fixed to the payout point's link.
    pub roller_axis: Option<Unit<Vector3<f64>>>,
    /// Placement: the head's pressing direction, fixed to the payout point's link.
    pub head_normal: Option<Unit<Vector3<f64>>>,
    /// Placement: the compaction roller's radius, mm.
    pub roller_radius: f64,
    /// The band path's key points from the creel to the payout point.
    pub band_path: Vec<usize>,
}

/// A machine: links (parents before children), driven axes, key points, roles.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    /// Its name.
    pub name: String,
    /// Links, the base first.
    pub links: Vec<Link>,
    /// Driven axes, in the order of the file.
    pub axes: Vec<Axis>,
    /// Key points.
    pub points: Vec<KeyPoint>,
    /// Roles for the kinematics.
    pub roles: Roles,
    /// How the simulator checks its solids for collisions.
    pub collision: Collision,
}

impl Machine {
    /// The home axis values (rad or mm).
    pub fn home(&self) -> Vec<f64> {
        self.axes.iter().map(|a| a.home).collect()
    }

    /// Index of the axis with NC address `name`.
    pub fn axis(&self, name: &str) -> Option<usize> {
        self.axes.iter().position(|a| a.name == name)
    }

    /// Whether link `a` is `b` or one of its ancestors.
    pub fn is_ancestor(&self, a: usize, b: usize) -> bool {
        let mut k = Some(b);
        while let Some(i) = k {
            if i == a {
                return true;
            }
            k = self.links[i].parent;
        }
        false
    }
}
