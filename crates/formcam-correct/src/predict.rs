//! The next part predicted from a correction: what the CMM would read of
//! the part moulded on the corrected mould, by the closed loop's model
//! ([`crate::simulate`]): the part follows the mould, so wherever the
//! mould's surface moves, the part's moves with it.

use crate::vec3::add;
use crate::{Corrector, MeasuredPoint, Measurements, Section};

/// The file of a correction's result with the next part's predicted
/// measurements ([`predict_next`], written by [`Measurements::to_csv`]).
pub const PREDICTED_FILE: &str = "predicted-cmm.csv";

/// The measurements of the next part predicted for the correction
/// `corrector` made from `measurements`: every measured point's actual
/// point moved by the displacement the corrector gives a node at the
/// point's nominal place (the mould's surface there moves by it, and the
/// part with it: the warp repeats itself). Within the measured area the
/// deviation after is the deviation before less `gain` times the
/// interpolated (and smoothed) deviation, along the normal for a ball-end
/// tool; a point the corrector leaves outside keeps its deviation. The
/// sections, names, nominal points and normals are those measured.
pub fn predict_next(measurements: &Measurements, corrector: &Corrector) -> Measurements {
    let sections = measurements
        .sections
        .iter()
        .map(|s| Section {
            name: s.name.clone(),
            points: s
                .points
                .iter()
                .map(|p| MeasuredPoint {
                    actual: add(p.actual, corrector.correct_node(p.nominal).displacement),
                    ..p.clone()
                })
                .collect(),
        })
        .collect();
    Measurements { sections }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use crate::{Grid, Interpolation, Options, Tool};

    /// A flat plate `z = 0`, sections `y = const`, whose part deviates by
    /// `dev(x, y)` along `+z` (the normal), the normal given or not.
    fn plate(dev: impl Fn(f64, f64) -> f64, normals: bool) -> Measurements {
        let sections = (0..5)
            .map(|j| {
                let y = 10.0 * j as f64;
                Section {
                    name: format!("Y{y}"),
                    points: (0..7)
                        .map(|i| {
                            let x = 15.0 * i as f64;
                            MeasuredPoint {
                                point: (i + 1).to_string(),
                                nominal: [x, y, 0.0],
                                actual: [x, y, dev(x, y)],
                                normal: normals.then_some([0.0, 0.0, 1.0]),
                            }
                        })
                        .collect(),
                }
            })
            .collect();
        Measurements { sections }
    }

    fn signed(p: &MeasuredPoint) -> f64 {
        p.actual[2] - p.nominal[2]
    }

    #[test]
    fn a_bilinear_warp_is_taken_off_by_the_gain() {
        // The deviation field is bilinear, so both patches reproduce it
        // exactly anywhere: after = (1 - gain) * before at every point.
        let dev = |x: f64, y: f64| 0.05 + 0.002 * x - 0.003 * y + 1e-4 * x * y;
        for (gain, tool, interpolation, normals) in [
            (1.0, Tool::Point, Interpolation::Bilinear, false),
            (0.5, Tool::Point, Interpolation::Bicubic, true),
            (
                0.8,
                Tool::Ball { radius: 3.0 },
                Interpolation::Bilinear,
                true,
            ),
        ] {
            let m = plate(dev, normals);
            let grid = Grid::from_measurements(&m, None).unwrap();
            let options = Options {
                gain,
                tool,
                interpolation,
                margin_mm: 0.0,
            };
            let c = Corrector::new(&grid, options).unwrap();
            let after = predict_next(&m, &c);
            assert_eq!(after.len(), m.len());
            for (a, b) in after.points().zip(m.points()) {
                assert_eq!(
                    (&a.point, a.nominal, a.normal),
                    (&b.point, b.nominal, b.normal)
                );
                let want = (1.0 - gain) * dev(b.nominal[0], b.nominal[1]);
                assert!(
                    (signed(a) - want).abs() < 1e-12,
                    "gain {gain}, {tool:?}: {} vs {want} at {:?}",
                    signed(a),
                    b.nominal
                );
                // Only along the normal: x and y stay.
                assert!((a.actual[0] - b.actual[0]).abs() < 1e-12);
                assert!((a.actual[1] - b.actual[1]).abs() < 1e-12);
            }
            assert!(after.max_deviation() <= (1.0 - gain) * m.max_deviation() + 1e-12);
        }
    }

    #[test]
    fn sections_resampled_by_arc_length_still_predict_a_linear_warp() {
        // Sections resampled to 13 points: linear along each section, so the
        // grid's deviation is still exact and the full gain leaves nothing.
        let dev = |x: f64, y: f64| 0.1 - 0.001 * x + 0.002 * y;
        let m = plate(dev, true);
        let grid = Grid::from_measurements(&m, Some(13)).unwrap();
        assert!(grid.resampled);
        let c = Corrector::new(&grid, Options::default()).unwrap();
        let after = predict_next(&m, &c);
        assert!(after.max_deviation() < 1e-12, "{}", after.max_deviation());
    }
}
