//! The solids the check moves: each `[[link.visual]]` of the machine as a
//! parry shape on its link, the bed in the world frame, and the mandrel.

use std::f64::consts::FRAC_PI_2;
use std::path::Path;

use formcam_machine::{Bed, Machine, Shape, Visual, read_visual_mesh};
use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::shape::SharedShape;

use crate::SimError;

/// Where a solid is fixed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mount {
    /// On a link (index into [`Machine::links`]), placed in its frame.
    Link(usize),
    /// In the world frame (the bed); it counts as the base link's for the
    /// exemptions.
    World,
}

/// One solid of the check.
#[derive(Clone)]
pub struct Body {
    /// Where it is fixed.
    pub mount: Mount,
    /// The link (the base link for the bed).
    pub link: usize,
    /// Its name in reports: its link's, or `bed`.
    pub name: String,
    /// Its shape per stage (one stage for machine solids; the mandrel has
    /// one per layer).
    pub shapes: Vec<SharedShape>,
    /// Its placement in its link's (or the world) frame.
    pub origin: Isometry3<f64>,
    /// The radius of a sphere about the link frame's origin holding it, mm
    /// (infinite for a plane).
    pub reach: f64,
    /// Whether it is the bed's half-space (its own broad-phase box).
    pub plane: bool,
    /// Whether it is a solid of revolution about its link's `z` axis (the
    /// mandrel): a joint turning about that axis does not move it.
    pub revolution: bool,
}

impl std::fmt::Debug for Body {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Body")
            .field("mount", &self.mount)
            .field("name", &self.name)
            .field("stages", &self.shapes.len())
            .field("reach", &self.reach)
            .finish()
    }
}

impl Body {
    /// A solid `shape` placed by `origin` on `mount`.
    pub fn new(
        machine: &Machine,
        mount: Mount,
        shape: SharedShape,
        origin: Isometry3<f64>,
    ) -> Self {
        let (link, name) = match mount {
            Mount::Link(l) => (l, machine.links[l].name.clone()),
            Mount::World => (0, "bed".to_string()),
        };
        let reach = reach(std::slice::from_ref(&shape), &origin);
        Self {
            mount,
            link,
            name,
            shapes: vec![shape],
            origin,
            reach,
            plane: false,
            revolution: false,
        }
    }

    /// The shape at stage `stage` (the last one past the end).
    pub fn shape(&self, stage: usize) -> &SharedShape {
        &self.shapes[stage.min(self.shapes.len() - 1)]
    }

    /// Its box in the world at `pose` (the solid's own pose), stage `stage`.
    pub fn aabb(&self, pose: &Isometry3<f64>, stage: usize) -> Aabb {
        if self.plane {
            // Everything below the plane's height.
            let z = pose.translation.vector.z;
            let inf = f64::INFINITY;
            Aabb::new(Point3::new(-inf, -inf, -inf), Point3::new(inf, inf, z))
        } else {
            self.shape(stage).compute_aabb(pose)
        }
    }
}

/// The radius of the sphere about the frame's origin that holds every
/// shape placed by `origin`.
pub(crate) fn reach(shapes: &[SharedShape], origin: &Isometry3<f64>) -> f64 {
    shapes
        .iter()
        .map(|s| {
            let b = s.compute_local_bounding_sphere();
            (origin * b.center()).coords.norm() + b.radius()
        })
        .fold(0.0, f64::max)
}

/// The parry shape of a visual and its placement in the link's frame;
/// meshes are read relative to `mesh_dir` (the machine file's folder; a
/// shipped machine's from formcam, `read_visual_mesh`) as the convex hull
/// of their vertices.
pub fn visual_shape(
    v: &Visual,
    mesh_dir: Option<&Path>,
) -> Result<(SharedShape, Isometry3<f64>), SimError> {
    Ok(match &v.shape {
        Shape::Box([x, y, z]) => (SharedShape::cuboid(x / 2.0, y / 2.0, z / 2.0), v.origin),
        // parry's cylinder runs along its y axis; ours along z.
        Shape::Cylinder { radius, length } => (
            SharedShape::cylinder(length / 2.0, *radius),
            v.origin * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), FRAC_PI_2),
        ),
        Shape::Sphere(r) => (SharedShape::ball(*r), v.origin),
        Shape::Mesh(file) => {
            let mesh = read_visual_mesh(file, v.scale, mesh_dir)?;
            (hull(&mesh.vertices), v.origin)
        }
    })
}

/// The convex hull of `points`, or their box when they span no volume.
fn hull(points: &[Point3<f64>]) -> SharedShape {
    SharedShape::convex_hull(points).unwrap_or_else(|| {
        let aabb = Aabb::from_points(points.iter().copied());
        let half = aabb.half_extents().map(|h| h.max(1e-6));
        let c = aabb.center();
        SharedShape::compound(vec![(
            Isometry3::translation(c.x, c.y, c.z),
            SharedShape::cuboid(half.x, half.y, half.z),
        )])
    })
}

/// Every solid of `machine`: its links' visuals (meshes read from
/// `mesh_dir`), then the bed.
pub fn machine_bodies(machine: &Machine, mesh_dir: Option<&Path>) -> Result<Vec<Body>, SimError> {
    let mut bodies = Vec::new();
    for (l, link) in machine.links.iter().enumerate() {
        for v in &link.visuals {
            let (shape, origin) = visual_shape(v, mesh_dir)?;
            bodies.push(Body::new(machine, Mount::Link(l), shape, origin));
        }
    }
    match &machine.collision.bed {
        None => {}
        Some(Bed::Plane(z)) => {
            let mut b = Body::new(
                machine,
                Mount::World,
                SharedShape::halfspace(Vector3::z_axis()),
                Isometry3::translation(0.0, 0.0, *z),
            );
            b.plane = true;
            b.reach = f64::INFINITY;
            bodies.push(b);
        }
        Some(Bed::Solid(v)) => {
            let (shape, origin) = visual_shape(v, mesh_dir)?;
            bodies.push(Body::new(machine, Mount::World, shape, origin));
        }
    }
    Ok(bodies)
}
