//! Property: the areas removed add up. For random allowances (the profile
//! offset by a random depth, or a random wavy worn contour above it) and
//! random steps, each pass's steps remove, summed, the area between the
//! contour before the pass and the contour after it, and all steps the area
//! between the initial and the final contour, to 1e-9 of that area (the
//! simulation cuts polylines exactly; only rounding is left). No step
//! removes a negative area.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use formcam_dress::{Allowance, Contour, DressJob, DressSpec, Point, dress};
use proptest::prelude::*;

const EXAMPLE: &str = include_str!("../../../examples/dress-ballscrew-nut.toml");

/// The area between two contours (the first above the second), over a base
/// below both.
fn between(above: &Contour, below: &Contour) -> f64 {
    let base = above
        .points()
        .iter()
        .chain(below.points())
        .map(|p| p.y)
        .fold(f64::INFINITY, f64::min);
    above.area(base) - below.area(base)
}

/// The example job with step `h` and allowance `depth`, or a worn contour
/// `depth + amp sin(k x + phase)` above the profile.
fn spec(h: f64, depth: f64, wave: Option<(f64, f64, f64)>) -> DressSpec {
    let mut j = DressJob::from_toml(EXAMPLE).unwrap();
    j.process.step = h;
    j.process.depth = Some(depth);
    let mut s = j.spec(None).unwrap();
    if let Some((amp, k, phase)) = wave {
        let profile = formcam_dress::Profile::new(&s.wheel).unwrap();
        let half = 0.5 * s.wheel.width;
        let n = 1500;
        let pts = (0..=n)
            .map(|i| {
                let x = -half + s.wheel.width * i as f64 / n as f64;
                let y = profile.y_at(x).unwrap() + depth + amp * (1.0 + (k * x + phase).sin());
                Point::new(x, y)
            })
            .collect();
        s.allowance = Allowance::Contour(pts);
    }
    s
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    #[test]
    fn removed_areas_add_up_pass_by_pass(
        h in 0.006f64..0.03,
        depth in 0.005f64..0.25,
        wave in proptest::option::of((0.001f64..0.04, 1.0f64..12.0, 0.0f64..6.3)),
    ) {
        let d = dress(&spec(h, depth, wave)).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let f = &d.forming;
        let total = f.area_between();
        prop_assert!(total > 0.0);
        let mut before = &f.initial;
        for (k, after) in f.after_pass.iter().enumerate() {
            let steps: Vec<f64> = f.steps.iter().filter(|s| s.pass == k).map(|s| s.area).collect();
            prop_assert!(steps.iter().all(|a| *a >= 0.0), "pass {}: a negative step", k);
            let removed: f64 = steps.iter().sum();
            let want = between(before, after);
            prop_assert!(
                (removed - want).abs() <= 1e-9 * total,
                "pass {}: steps remove {}, the contours differ by {} ({:e} of {})",
                k, removed, want, (removed - want) / total, total
            );
            before = after;
        }
        prop_assert!(
            (f.removed() - total).abs() <= 1e-9 * total,
            "{} removed vs {} between", f.removed(), total
        );
    }
}
