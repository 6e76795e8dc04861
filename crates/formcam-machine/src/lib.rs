//! Machine models of formcam: kinematic trees read from TOML machine files or
//! URDF, forward kinematics for every link and key point, inverse kinematics of
//! winders (eye trajectory → axes) and fibre-placement heads, feasibility checks
//! and the length of band past each key point of the band path.
//!
//! A machine is a tree of links (a hierarchical model, like LinuxCNC's
//! vismach): each link hangs on its parent by a joint `pre * motion(q) * post`
//! (Denavit–Hartenberg parameters or a plain origin), driven by an NC axis or
//! fixed. One link carries the mandrel frame, one key point is the payout point.

mod axes_csv;
mod band;
mod chain;
mod collision;
mod error;
mod file;
mod fk;
mod format;
mod ik;
mod machine;
mod mesh;
pub mod shipped;
mod target;
mod urdf;

pub use axes_csv::{AxesRow, read_axes_csv};
pub use band::{BandPassed, band_passed};
pub use collision::{Bed, Collision, DEFAULT_MARGIN_MM};
pub use error::{AxesCsvError, IkFault, MachineError, UrdfFault};
pub use file::{
    CollisionSpec, DhSpec, JointType, LinkSpec, MachineFile, MachineKind, MachineTable, OriginSpec,
    PointSpec, SpindleFollows, VisualSpec,
};
pub use fk::Fk;
pub use format::MachineFormat;
pub use ik::{AxisTrack, IkMethod, Issue, IssueKind, ORIENTATION_SCALE, solve};
pub use machine::{Axis, Joint, JointKind, KeyPoint, Link, Machine, Roles, Shape, Visual};
pub use mesh::{
    MeshError, MeshFault, MeshFormat, MeshPlace, TriMesh, parse_mesh, read_mesh, read_visual_mesh,
};
pub use target::{PathPoint, Target};
pub use urdf::links_from_urdf;
