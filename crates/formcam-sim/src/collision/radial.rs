//! A cheap lower bound of the distance from a solid to a solid of
//! revolution (the mandrel), between the boxes and the exact query.
//!
//! Seen in the revolution solid's frame, two points `p` and `s` are at
//! least `sqrt((ρp - ρs)² + (zp - zs)²)` apart, `ρ` the distance from the
//! `z` axis: `|p - s|² = ρp² + ρs² - 2 ρp ρs cos Δθ + Δz²` and `cos Δθ ≤ 1`.
//! Each convex part of the solid lies within `z ∈ [lo, hi]` and `ρ ≤ ρmax`
//! (the largest radius of its vertices: the radius is convex, so no point
//! of the hull lies further out than its vertices). The other solid, turned
//! about `z` so that its centre lies on `+x` (which changes no `ρ`), lies in
//! its box: `ρ ≥ x ≥ xmin` and `z ∈ [zmin, zmax]`. So the distance is at
//! least the smallest over the parts of `hypot(max(0, xmin - ρmax),
//! gap of the z ranges)`. The bound needs no symmetry; it is close to the
//! distance where the solid is one of revolution and the other solid is
//! small across.

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use parry3d_f64::shape::{Shape, SharedShape};

/// One convex part of a solid: its `z` range and largest radius.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Part {
    lo: f64,
    hi: f64,
    rho: f64,
}

/// The parts of a solid about its frame's `z` axis.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Radial {
    parts: Vec<Part>,
}

impl Radial {
    /// The parts of `shape` (a compound's parts each, a convex polyhedron
    /// by its vertices, any other shape by the corners of its box).
    pub(crate) fn of(shape: &SharedShape) -> Self {
        let parts = match shape.as_compound() {
            Some(c) => c
                .shapes()
                .iter()
                .map(|(iso, s)| part(iso, s.as_ref()))
                .collect(),
            None => vec![part(&Isometry3::identity(), shape.as_ref())],
        };
        Self { parts }
    }

    /// A lower bound of the distance to the solid from any point with
    /// `ρ ≥ x_min` and `z` within `[z_min, z_max]`; infinite for a solid of
    /// no parts.
    pub(crate) fn bound(&self, x_min: f64, z_min: f64, z_max: f64) -> f64 {
        let mut best = f64::INFINITY;
        for p in &self.parts {
            let dz = (p.lo - z_max).max(z_min - p.hi).max(0.0);
            if dz >= best {
                continue;
            }
            let dr = (x_min - p.rho).max(0.0);
            best = best.min((dr * dr + dz * dz).sqrt());
        }
        best
    }

    /// A lower bound of the distance to the solid from `other` placed at
    /// `rel` in the solid's frame.
    pub(crate) fn bound_to(&self, other: &SharedShape, rel: &Isometry3<f64>) -> f64 {
        let c = rel * other.compute_local_bounding_sphere().center();
        let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -c.y.atan2(c.x));
        let turned = turn * rel;
        let b = other.compute_aabb(&turned);
        self.bound(b.mins.x, b.mins.z, b.maxs.z)
    }
}

/// The `z` range and largest radius of `shape` placed by `iso`.
fn part(iso: &Isometry3<f64>, shape: &dyn Shape) -> Part {
    let corners;
    let points: &[Point3<f64>] = match shape.as_convex_polyhedron() {
        Some(p) => p.points(),
        None => {
            corners = shape.compute_local_aabb().vertices();
            &corners
        }
    };
    let mut out = Part {
        lo: f64::INFINITY,
        hi: f64::NEG_INFINITY,
        rho: 0.0,
    };
    for p in points {
        let q = iso * p;
        out.lo = out.lo.min(q.z);
        out.hi = out.hi.max(q.z);
        out.rho = out.rho.max(q.x.hypot(q.y));
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::collision::mandrel::revolution_solid;
    use formcam_geom::Cylinder;
    use parry3d_f64::query;

    #[test]
    fn the_bound_is_below_the_distance_and_close_to_it_beside_a_cylinder() {
        let c = Cylinder::new(100.0, 300.0).unwrap();
        let solid = revolution_solid(&c).unwrap();
        let radial = Radial::of(&solid);
        let ball = SharedShape::ball(10.0);
        let id = Isometry3::identity();
        for k in 0..40 {
            let a = 0.3 * k as f64;
            let (rho, z) = (115.0 + 3.0 * k as f64, -60.0 + 11.0 * k as f64);
            let at = Isometry3::translation(rho * a.cos(), rho * a.sin(), z);
            let exact = query::distance(&id, solid.as_ref(), &at, ball.as_ref()).unwrap();
            let bound = radial.bound_to(&ball, &at);
            assert!(bound <= exact + 1e-9, "{k}: {bound} > {exact}");
            // Beside the cylinder (not past its ends) within the polygon's
            // widening and the chord tolerance.
            if (0.0..=300.0).contains(&z) {
                assert!(exact - bound < 0.2, "{k}: {bound} vs {exact}");
            }
        }
    }
}
