//! Collisions between the machine's solids, the bed and the mandrel along a
//! program's timeline (parry3d, in `f64`).
//!
//! * `solids` — each `[[link.visual]]` as a parry shape on its link (a box,
//!   a cylinder turned from parry's `y` axis to our `z`, a ball, a mesh as
//!   the convex hull of its vertices), the bed (a plane or a solid in the
//!   world frame).
//! * `mandrel` — the winding job's mandrel as a solid of revolution
//!   (convex frustums holding the surface), one per layer, grown by the
//!   laminate laid by the end of that layer; the layer of each block from
//!   the layers' labels in the program's comments.
//! * `pairs` — which pairs are checked (not on one link, not on links
//!   joined directly, not ignored by the machine file).
//! * `sweep` — how far a solid can travel within a block, so that the
//!   samples are close enough.
//! * `radial` — a lower bound of the distance from a solid to the mandrel
//!   from radii and heights alone.
//! * `check` — per sample the broad phase (the gap between boxes, the
//!   radial bound), then the exact distance only where the bounds come
//!   within the margin; a pair shown clear skipped until its travel could
//!   close the gap; [`Collisions::check`].

mod check;
mod mandrel;
mod pairs;
mod radial;
mod solids;
mod sweep;

pub use check::Collisions;
pub use mandrel::{CHORD_TOLERANCE_MM, Laminate, SIDES, revolution_solid};
pub use pairs::{Pair, exempt};
pub use solids::{Body, Mount, machine_bodies, visual_shape};
