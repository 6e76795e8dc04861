use crate::{CubicSpline, GeomError, Jet, Meridian, read_pairs};

/// A meridian given as a table of `(z, r)` points, made C2 by a [`CubicSpline`]
/// so that `r''` exists everywhere.
///
/// `smoothing = 0` interpolates the points (not-a-knot spline); `smoothing > 0`
/// fits the Reinsch smoothing spline, see [`CubicSpline`] for the objective and
/// how to choose the value (mm^3). The domain is `[first z, last z]`; outside it
/// the end cubic pieces continue.
#[derive(Debug, Clone, PartialEq)]
pub struct Tabulated {
    spline: CubicSpline,
    z_range: (f64, f64),
}

impl Tabulated {
    /// A meridian through (or smoothing) `points` given as `(z, r)` in mm.
    ///
    /// Needs at least 4 points, all finite, `z` strictly increasing and `r > 0`
    /// (also after smoothing); errors name the 1-based row.
    pub fn new(points: &[(f64, f64)], smoothing: f64) -> Result<Self, GeomError> {
        if points.len() < 4 {
            return Err(GeomError::TooFewPoints {
                count: points.len(),
            });
        }
        for (i, &(z, r)) in points.iter().enumerate() {
            let row = i + 1;
            if !z.is_finite() {
                return Err(GeomError::Table {
                    row,
                    reason: format!("z is not a finite number: {z}"),
                });
            }
            if !r.is_finite() {
                return Err(GeomError::Table {
                    row,
                    reason: format!("r is not a finite number: {r}"),
                });
            }
            if r <= 0.0 {
                return Err(GeomError::Table {
                    row,
                    reason: format!("r must be > 0 mm, got {r}"),
                });
            }
        }
        let z: Vec<f64> = points.iter().map(|p| p.0).collect();
        let r: Vec<f64> = points.iter().map(|p| p.1).collect();
        let spline = CubicSpline::fit(&z, &r, smoothing)?;
        if let Some(i) = spline.values().iter().position(|&v| v.is_nan() || v <= 0.0) {
            return Err(GeomError::Table {
                row: i + 1,
                reason: format!(
                    "smoothed r must be > 0 mm, got {} (reduce smoothing)",
                    spline.values()[i]
                ),
            });
        }
        let z_range = (z[0], z[z.len() - 1]);
        Ok(Self { spline, z_range })
    }

    /// Reads the points from CSV text, one `z, r` pair per line, then as [`Tabulated::new`].
    ///
    /// Values are separated by a comma, a semicolon or whitespace. With
    /// semicolons a decimal comma is accepted (`12,5; 40,0`). Blank lines and
    /// lines starting with `#` are skipped, and so is a first line in which no
    /// field is a number (a header such as `z,r`). Row numbers in errors count
    /// data lines only.
    pub fn from_csv_str(text: &str, smoothing: f64) -> Result<Self, GeomError> {
        Self::new(&read_pairs(text, ("z", "r"))?, smoothing)
    }

    /// The spline through the table.
    pub fn spline(&self) -> &CubicSpline {
        &self.spline
    }
}

impl Meridian for Tabulated {
    fn z_range(&self) -> (f64, f64) {
        self.z_range
    }

    fn eval(&self, z: f64) -> Jet {
        let (r, dr, d2r) = self.spline.eval(z);
        Jet { r, dr, d2r }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(f: impl Fn(f64) -> f64, z0: f64, z1: f64, n: usize) -> Vec<(f64, f64)> {
        (0..n)
            .map(|i| {
                let z = z0 + (z1 - z0) * i as f64 / (n - 1) as f64;
                (z, f(z))
            })
            .collect()
    }

    /// Largest errors in r, r', r'' against the exact `(r, r', r'')` over the range.
    fn worst(t: &Tabulated, exact: impl Fn(f64) -> (f64, f64, f64)) -> (f64, f64, f64) {
        let (z0, z1) = t.z_range();
        let mut e = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..=1000 {
            let z = z0 + (z1 - z0) * i as f64 / 1000.0;
            let j = t.eval(z);
            let (r, dr, d2r) = exact(z);
            e = (
                e.0.max((j.r - r).abs()),
                e.1.max((j.dr - dr).abs()),
                e.2.max((j.d2r - d2r).abs()),
            );
        }
        e
    }

    #[test]
    fn reproduces_a_sampled_hemisphere() {
        // Sphere of radius 100 on z in [-80, 80], 1 mm spacing.
        let rad = 100.0f64;
        let exact = |z: f64| {
            let q = (rad * rad - z * z).sqrt();
            (q, -z / q, -rad * rad / (q * q * q))
        };
        let t = Tabulated::new(&sample(|z| exact(z).0, -80.0, 80.0, 161), 0.0).unwrap();
        assert_eq!(t.z_range(), (-80.0, 80.0));
        assert!(t.breakpoints().is_empty());
        let (er, edr, ed2r) = worst(&t, exact);
        assert!(er < 2e-5, "r error {er:e}");
        assert!(edr < 1e-4, "r' error {edr:e}");
        assert!(ed2r < 5e-4, "r'' error {ed2r:e}");
        // Away from the steep ends: r to 2e-10 relative, r'' to 2e-4 relative (the
        // spline's O(h^2) curvature error).
        for z in [-40.0, -3.3, 0.0, 17.2, 50.0] {
            let (j, (r, dr, d2r)) = (t.eval(z), exact(z));
            assert!((j.r - r).abs() < 2e-10 * r, "z {z}");
            assert!((j.dr - dr).abs() < 5e-8, "z {z}");
            assert!(
                (j.d2r - d2r).abs() < 2e-4 * d2r.abs(),
                "z {z}: {} vs {d2r}",
                j.d2r
            );
        }
    }

    #[test]
    fn reproduces_a_sampled_ellipse() {
        // Half ellipse r = a sqrt(1 - (z/b)^2), a = 120, b = 60, on |z| <= 50, 1 mm apart.
        let (a, b) = (120.0f64, 60.0f64);
        let exact = |z: f64| {
            let s = (1.0 - (z / b).powi(2)).sqrt();
            (a * s, -a * z / (b * b * s), -a / (b * b * s * s * s))
        };
        let t = Tabulated::new(&sample(|z| exact(z).0, -50.0, 50.0, 101), 0.0).unwrap();
        let (er, edr, _) = worst(&t, exact);
        assert!(er < 3e-4, "r error {er:e}");
        assert!(edr < 2e-3, "r' error {edr:e}");
        let (j, (r, _, d2r)) = (t.eval(0.0), exact(0.0));
        assert!((j.r - r).abs() < 1e-5 * r);
        assert!((j.d2r - d2r).abs() < 1e-3 * d2r.abs(), "{} vs {d2r}", j.d2r);
    }

    #[test]
    fn smoothing_removes_noise() {
        // Cylinder r = 50 with +-0.05 mm of deterministic noise.
        let pts: Vec<(f64, f64)> = (0..101)
            .map(|i| (i as f64, 50.0 + 0.05 * ((i * 37 % 11) as f64 / 5.0 - 1.0)))
            .collect();
        let rough = Tabulated::new(&pts, 0.0).unwrap();
        let smooth = Tabulated::new(&pts, 1e4).unwrap();
        let max_curv = |t: &Tabulated| {
            (0..=1000)
                .map(|i| t.d2r(i as f64 * 0.1).abs())
                .fold(0.0, f64::max)
        };
        assert!(
            max_curv(&smooth) < 1e-3 * max_curv(&rough),
            "{} vs {}",
            max_curv(&smooth),
            max_curv(&rough)
        );
        assert!((smooth.r(50.0) - 50.0).abs() < 0.02);
    }

    #[test]
    fn reads_csv_with_and_without_header() {
        let pts = sample(|z| 40.0 + 0.01 * z * z, 0.0, 30.0, 7);
        let plain: String = pts.iter().map(|(z, r)| format!("{z},{r}\n")).collect();
        let expected = Tabulated::new(&pts, 0.0).unwrap();
        assert_eq!(Tabulated::from_csv_str(&plain, 0.0).unwrap(), expected);
        let with_header = format!("\u{feff}z,r\n# mandrel profile\n\n{plain}\n");
        assert_eq!(
            Tabulated::from_csv_str(&with_header, 0.0).unwrap(),
            expected
        );
        let spaced: String = pts
            .iter()
            .map(|(z, r)| format!("  {z}\t {r} \r\n"))
            .collect();
        assert_eq!(
            Tabulated::from_csv_str(&format!("z [mm]   r [mm]\n{spaced}"), 0.0).unwrap(),
            expected
        );
        let semi: String = pts.iter().map(|(z, r)| format!("{z} ; {r};\n")).collect();
        assert_eq!(Tabulated::from_csv_str(&semi, 0.0).unwrap(), expected);
        let decimal_comma = "z;r\n0;40\n1,5;40,5\n3;41\n4,25;41,75\n";
        let t = Tabulated::from_csv_str(decimal_comma, 0.0).unwrap();
        assert_eq!(t.spline().knots(), &[0.0, 1.5, 3.0, 4.25]);
        assert_eq!(t.spline().values(), &[40.0, 40.5, 41.0, 41.75]);
    }

    #[test]
    fn reports_csv_errors_by_row() {
        let table = |row, reason: &str| {
            Err(GeomError::Table {
                row,
                reason: reason.to_string(),
            })
        };
        let csv = "z,r\n0,10\n1,abc\n2,10\n3,10\n";
        assert_eq!(
            Tabulated::from_csv_str(csv, 0.0),
            table(2, "cannot read r: 'abc'")
        );
        let csv = "0,10\n# note\n1,10\nx1,10\n3,10\n";
        assert_eq!(
            Tabulated::from_csv_str(csv, 0.0),
            table(3, "cannot read z: 'x1'")
        );
        let csv = "0,10\n1,10,7\n2,10\n3,10\n";
        assert!(matches!(
            Tabulated::from_csv_str(csv, 0.0),
            Err(GeomError::Table { row: 2, .. })
        ));
        let csv = "0 10\n1\n2 10\n3 10\n";
        assert!(matches!(
            Tabulated::from_csv_str(csv, 0.0),
            Err(GeomError::Table { row: 2, .. })
        ));
        // A first line with a number in it is data, not a header.
        let csv = "0,abc\n1,10\n2,10\n3,10\n";
        assert_eq!(
            Tabulated::from_csv_str(csv, 0.0),
            table(1, "cannot read r: 'abc'")
        );
        assert_eq!(
            Tabulated::from_csv_str("z,r\n0,1\n1,1\n", 0.0),
            Err(GeomError::TooFewPoints { count: 2 })
        );
        assert_eq!(
            Tabulated::from_csv_str("", 0.0),
            Err(GeomError::TooFewPoints { count: 0 })
        );
        assert!(matches!(
            Tabulated::from_csv_str("0,1\n1,1\n1,1\n3,1\n", 0.0),
            Err(GeomError::Table { row: 3, reason }) if reason.contains("duplicate z")
        ));
        assert!(matches!(
            Tabulated::from_csv_str("0,1\n1,1\n2,-1\n3,1\n", 0.0),
            Err(GeomError::Table { row: 3, reason }) if reason.contains("r must be > 0")
        ));
        // "inf" and "NaN" parse as f64 but are not accepted.
        assert_eq!(
            Tabulated::from_csv_str("0,1\n1,inf\n2,1\n3,1\n", 0.0),
            table(2, "cannot read r: 'inf'")
        );
    }

    #[test]
    fn reports_bad_points() {
        let good = [
            (0.0, 10.0),
            (1.0, 11.0),
            (2.0, 11.5),
            (3.0, 11.0),
            (4.0, 10.0),
        ];
        let bad_row = |row: usize, pts: &[(f64, f64)], word: &str| match Tabulated::new(pts, 0.0) {
            Err(GeomError::Table { row: got, reason }) => {
                assert_eq!(got, row, "{reason}");
                assert!(reason.contains(word), "{reason}");
            }
            other => panic!("unexpected {other:?}"),
        };
        assert!(Tabulated::new(&good, 0.0).is_ok());
        assert_eq!(
            Tabulated::new(&good[..3], 0.0),
            Err(GeomError::TooFewPoints { count: 3 })
        );
        let mut p = good;
        p[1].0 = f64::NAN;
        bad_row(2, &p, "z is not a finite");
        let mut p = good;
        p[4].1 = f64::INFINITY;
        bad_row(5, &p, "r is not a finite");
        let mut p = good;
        p[2].1 = 0.0;
        bad_row(3, &p, "r must be > 0");
        let mut p = good;
        p[3].0 = 2.0;
        bad_row(4, &p, "duplicate z");
        let mut p = good;
        p[3].0 = 1.5;
        bad_row(4, &p, "z not increasing");
        assert!(matches!(
            Tabulated::new(&good, -1.0),
            Err(GeomError::OutOfRange {
                field: "smoothing",
                ..
            })
        ));
        assert!(matches!(
            Tabulated::new(&good, f64::NAN),
            Err(GeomError::NotFinite {
                field: "smoothing",
                ..
            })
        ));
        // Heavy smoothing tends to the least-squares line, here below the axis at z = 0.
        let steep = [(0.0, 0.1), (1.0, 0.1), (2.0, 0.1), (3.0, 0.1), (4.0, 20.0)];
        assert!(Tabulated::new(&steep, 0.0).is_ok());
        assert!(matches!(
            Tabulated::new(&steep, 1e6),
            Err(GeomError::Table { row: 1, reason }) if reason.contains("smoothed r must be > 0")
        ));
    }
}
