//! Property: a constant normal offset is corrected exactly. The part
//! measures `d` proud of the nominal surface along its normal everywhere
//! (random `d`; a random tilted plane, cylinder or sphere cap, built
//! analytically, sampled on a random grid); with gain 1, for both
//! interpolations:
//!
//! * plane: every node inside the measured area moves by `-d n`, to 1e-9 mm;
//! * cylinder and sphere: a node at a measured point moves by `-d n` there,
//!   to 1e-9 mm; between the measured points the interpolated normals are
//!   not the surface's, so a node moves by `-d n` within the interpolation
//!   error of a field whose second derivatives are `|d| / R^2`:
//!   `|d| (hu^2 + hv^2) / (4 R^2)` (the bilinear bound `h^2 / 8` per
//!   direction, doubled for the foot's offset on the patch); the bilinear
//!   displacement is, exactly (1e-9 mm), `-d` times the bilinear blend of
//!   the facet's corner normals at the foot's `(s, t)`.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use formcam_correct::{Corrector, Grid, Interpolation, Options, Placement};
use proptest::prelude::*;

type V3 = [f64; 3];

/// A surface the tests know exactly: `z(x, y)` and its unit normal (`+z` side).
#[derive(Debug, Clone, Copy)]
enum Shape {
    /// `z = a x + b y + c`.
    Plane { a: f64, b: f64, c: f64 },
    /// The upper half of a cylinder of radius `r` along `y`.
    Cylinder { r: f64 },
    /// The upper half of a sphere of radius `r` about the origin.
    Sphere { r: f64 },
}

impl Shape {
    fn z(self, x: f64, y: f64) -> f64 {
        match self {
            Shape::Plane { a, b, c } => a * x + b * y + c,
            Shape::Cylinder { r } => (r * r - x * x).sqrt(),
            Shape::Sphere { r } => (r * r - x * x - y * y).sqrt(),
        }
    }

    fn normal(self, x: f64, y: f64) -> V3 {
        match self {
            Shape::Plane { a, b, .. } => {
                let l = (1.0 + a * a + b * b).sqrt();
                [-a / l, -b / l, 1.0 / l]
            }
            Shape::Cylinder { r } => [x / r, 0.0, self.z(x, y) / r],
            Shape::Sphere { r } => [x / r, y / r, self.z(x, y) / r],
        }
    }

    /// The radius of curvature (infinite for the plane).
    fn radius(self) -> f64 {
        match self {
            Shape::Plane { .. } => f64::INFINITY,
            Shape::Cylinder { r } | Shape::Sphere { r } => r,
        }
    }

    /// The plan area sampled: `[-w, w] x [-w, w]`.
    fn half_width(self) -> f64 {
        match self {
            Shape::Plane { .. } => 60.0,
            Shape::Cylinder { r } | Shape::Sphere { r } => 0.5 * r,
        }
    }
}

fn shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        (-0.8f64..0.8, -0.8f64..0.8, -50.0f64..50.0).prop_map(|(a, b, c)| Shape::Plane { a, b, c }),
        (40.0f64..400.0).prop_map(|r| Shape::Cylinder { r }),
        (40.0f64..400.0).prop_map(|r| Shape::Sphere { r }),
    ]
}

/// The grid of `nu x nv` points over the shape's plan area, each measured
/// `d` along the normal.
fn grid(s: Shape, nu: usize, nv: usize, d: f64) -> (Grid, f64, f64) {
    let w = s.half_width();
    let (hu, hv) = (2.0 * w / (nu - 1) as f64, 2.0 * w / (nv - 1) as f64);
    let mut nominal = Vec::new();
    let mut deviation = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (x, y) = (-w + i as f64 * hu, -w + j as f64 * hv);
            nominal.push([x, y, s.z(x, y)]);
            deviation.push(s.normal(x, y).map(|n| d * n));
        }
    }
    let g = Grid {
        nu,
        nv,
        nominal,
        deviation,
        normal: None,
        resampled: false,
        reordered: false,
    };
    (g, hu, hv)
}

fn dist(a: V3, b: V3) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn a_constant_normal_offset_is_corrected_exactly(
        s in shape(),
        nu in 3usize..9,
        nv in 3usize..9,
        d in -2.0f64..2.0,
        plan in proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0), 1..40),
    ) {
        let (g, hu, hv) = grid(s, nu, nv, d);
        let w = s.half_width();
        // Nodes on the surface: the measured points and random points between.
        let mut nodes: Vec<V3> = g.nominal.clone();
        let measured = nodes.len();
        for (u, v) in &plan {
            let (x, y) = (w * (1.999 * u - 0.9995), w * (1.999 * v - 0.9995));
            nodes.push([x, y, s.z(x, y)]);
        }
        let bound = d.abs() * (hu * hu + hv * hv) / (4.0 * s.radius().powi(2)) + 1e-9;
        for interpolation in [Interpolation::Bilinear, Interpolation::Bicubic] {
            let options = Options { gain: 1.0, interpolation, ..Options::default() };
            let corr = Corrector::new(&g, options).map_err(|e| TestCaseError::fail(e.to_string()))?;
            for (k, (p, c)) in nodes.iter().zip(corr.correct(&nodes)).enumerate() {
                prop_assert_eq!(c.placement, Placement::Inside, "{:?} node {} at {:?}", interpolation, k, p);
                let want = s.normal(p[0], p[1]).map(|n| -d * n);
                let err = dist(c.displacement, want);
                let tol = if k < measured || s.radius().is_infinite() { 1e-9 } else { bound };
                prop_assert!(
                    err <= tol,
                    "{:?} {:?} node {} at {:?}: {:?} vs {:?} ({} > {})",
                    interpolation, s, k, p, c.displacement, want, err, tol
                );
                if interpolation == Interpolation::Bilinear {
                    let (i, j) = (c.facet.0 as usize, c.facet.1 as usize);
                    let corner = |a: usize, b: usize| g.deviation[(j + b) * nu + i + a];
                    let (si, ti) = (c.s, c.t);
                    let blend: Vec<f64> = (0..3)
                        .map(|m| {
                            -((1.0 - si) * (1.0 - ti) * corner(0, 0)[m]
                                + si * (1.0 - ti) * corner(1, 0)[m]
                                + (1.0 - si) * ti * corner(0, 1)[m]
                                + si * ti * corner(1, 1)[m])
                        })
                        .collect();
                    let err = dist(c.displacement, [blend[0], blend[1], blend[2]]);
                    prop_assert!(err <= 1e-9, "bilinear blend at node {}: {}", k, err);
                }
            }
        }
    }
}
