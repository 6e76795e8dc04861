//! The mandrel as a solid: its surface of revolution about the mandrel
//! link's `z` axis, as a compound of convex frustums, grown by the
//! laminate laid so far.

use std::f64::consts::PI;

use formcam_geom::Meridian;
use formcam_nc::Dialect;
use nalgebra::{Isometry3, Point3};
use parry3d_f64::shape::SharedShape;

/// The sides of the polygon each ring of the solid is drawn with.
pub const SIDES: usize = 64;

/// How far the frustums' chords may lie inside the meridian, mm; every
/// ring is widened by it.
pub const CHORD_TOLERANCE_MM: f64 = 0.05;

/// The solid of revolution of `meridian` about `z`: one convex frustum per
/// stretch of `z` (the stretches split until the chord between their ends
/// is within [`CHORD_TOLERANCE_MM`] of `r` at their middle), each ring a
/// polygon of [`SIDES`] sides drawn round the circle of radius
/// `r + CHORD_TOLERANCE_MM`, so that the solid holds the surface. `None`
/// when the meridian gives no finite radius.
pub fn revolution_solid(meridian: &dyn Meridian) -> Option<SharedShape> {
    let zs = knots(meridian)?;
    let grow = 1.0 / (PI / SIDES as f64).cos();
    let ring = |z: f64| -> Vec<Point3<f64>> {
        let r = (meridian.r(z).max(0.0) + CHORD_TOLERANCE_MM) * grow;
        (0..SIDES)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / SIDES as f64;
                Point3::new(r * a.cos(), r * a.sin(), z)
            })
            .collect()
    };
    let mut parts = Vec::with_capacity(zs.len());
    let mut below = ring(zs[0]);
    for &z in &zs[1..] {
        let above = ring(z);
        let mut points = below.clone();
        points.extend_from_slice(&above);
        parts.push((Isometry3::identity(), SharedShape::convex_hull(&points)?));
        below = above;
    }
    Some(SharedShape::compound(parts))
}

/// The `z` values the solid's rings stand on: the ends, the breakpoints,
/// and halvings until each stretch's chord is within the tolerance.
fn knots(m: &dyn Meridian) -> Option<Vec<f64>> {
    let (z0, z1) = m.z_range();
    if !(z0.is_finite() && z1.is_finite() && z1 > z0) {
        return None;
    }
    let mut fixed = vec![z0];
    fixed.extend(m.breakpoints().into_iter().filter(|z| *z > z0 && *z < z1));
    fixed.push(z1);
    let min_step = (z1 - z0) * 1e-6;
    let mut out = vec![z0];
    for w in fixed.windows(2) {
        // A stack of stretches still to look at, the leftmost on top.
        let mut todo = vec![(w[0], w[1])];
        while let Some((a, b)) = todo.pop() {
            let (ra, rb, rm) = (m.r(a), m.r(b), m.r(0.5 * (a + b)));
            if !(ra.is_finite() && rb.is_finite() && rm.is_finite()) {
                return None;
            }
            if (rm - 0.5 * (ra + rb)).abs() > CHORD_TOLERANCE_MM && b - a > min_step {
                let mid = 0.5 * (a + b);
                todo.push((mid, b));
                todo.push((a, mid));
            } else {
                out.push(b);
            }
        }
    }
    Some(out)
}

/// The winding job's mandrel, layer by layer: the solid while each layer
/// is wound (the mandrel grown by the layers before and by the whole of
/// that layer, [`revolution_solid`]), and each layer's label as the
/// program's comments carry it. The planner makes it from the layers it
/// planned (formcam-program's `laminate`).
pub struct Laminate {
    /// The layers' labels (`layer 1`, `layer 2 (hoop)`).
    pub labels: Vec<String>,
    /// The solid per layer.
    pub solids: Vec<SharedShape>,
    /// The laminate's thickness counted per layer, mm.
    pub thickness: Vec<f64>,
}

impl std::fmt::Debug for Laminate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Laminate")
            .field("labels", &self.labels)
            .field("thickness", &self.thickness)
            .finish()
    }
}

impl Laminate {
    /// The layer each block of a program written in `dialect` is wound in,
    /// from the layers' labels in the blocks' comments as that dialect
    /// writes them ([`Dialect::comment_as_written`]: `layer 2 [helical]` in
    /// LinuxCNC and ISO); the block a label stands on starts its layer.
    /// When no block carries a label, every block counts in the last layer
    /// (the whole laminate).
    pub fn stage_of_blocks<'a>(
        &self,
        dialect: Dialect,
        comments: impl Iterator<Item = Option<&'a str>>,
    ) -> Vec<usize> {
        let labels: Vec<String> = self
            .labels
            .iter()
            .map(|l| dialect.comment_as_written(l))
            .collect();
        let mut current = 0;
        let mut seen = false;
        let mut out = Vec::new();
        for c in comments {
            if let Some(c) = c
                && let Some(k) = labels
                    .iter()
                    .position(|l| c.split("; ").any(|part| part.trim() == l))
            {
                current = k;
                seen = true;
            }
            out.push(current);
        }
        if !seen {
            out.fill(self.solids.len().saturating_sub(1));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use formcam_geom::Cylinder;
    use nalgebra::Vector3;

    #[test]
    fn the_solid_holds_the_surface_within_the_polygon() {
        let c = Cylinder::new(100.0, 300.0).unwrap();
        let s = revolution_solid(&c).unwrap();
        let id = Isometry3::identity();
        // On the surface: inside; 1 mm out: outside.
        for k in 0..16 {
            let a = k as f64 * 0.37;
            let dir = Vector3::new(a.cos(), a.sin(), 0.0);
            let on = Point3::from(dir * 100.0 + Vector3::z() * (10.0 + 17.0 * k as f64));
            assert!(s.contains_point(&id, &on), "{on}");
            let out = Point3::from(dir * 101.0 + Vector3::z() * 150.0);
            assert!(!s.contains_point(&id, &out), "{out}");
        }
        assert!(!s.contains_point(&id, &Point3::new(0.0, 0.0, 301.0)));
        assert!(s.contains_point(&id, &Point3::new(0.0, 0.0, 299.0)));
    }
}
