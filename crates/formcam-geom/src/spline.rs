use crate::GeomError;

/// A C2 cubic spline `y(x)` on strictly increasing knots, interpolating or smoothing.
///
/// Stored as the knots, the spline's values there and its second derivatives
/// there; between two knots it is the cubic fixed by those four numbers.
///
/// * `smoothing = 0`: the interpolating spline with not-a-knot ends (the
///   third derivative is continuous at the second and the second-to-last knot),
///   which reproduces any cubic exactly.
/// * `smoothing = lambda > 0`: the Reinsch smoothing spline, the function that
///   minimises
///
///   `J(s) = sum_i (y_i - s(x_i))^2 + lambda * integral from x_0 to x_(n-1) of s''(x)^2 dx`,
///
///   a natural spline (`s'' = 0` at both ends). With `x`, `y` in mm, `lambda`
///   is in mm^3. For knots spaced `h` apart it damps a wave of length `L` by
///   `1 / (1 + lambda h (2 pi / L)^4)`: to halve features of length `L` and
///   shorter take `lambda = (L / (2 pi))^4 / h`. As `lambda -> 0` the spline
///   tends to the natural interpolating spline, as `lambda -> infinity` to the
///   least-squares straight line.
///
/// Outside the knots the spline continues the polynomial of its end piece.
#[derive(Debug, Clone, PartialEq)]
pub struct CubicSpline {
    x: Vec<f64>,
    y: Vec<f64>,
    m: Vec<f64>,
}

impl CubicSpline {
    /// Fits a spline to the points `(x[i], y[i])`; see the type's documentation
    /// for the meaning of `smoothing`.
    ///
    /// Needs at least 4 points, all finite, `x` strictly increasing, `x` and `y`
    /// of equal length (errors name the 1-based row) and a finite `smoothing >= 0`.
    pub fn fit(x: &[f64], y: &[f64], smoothing: f64) -> Result<Self, GeomError> {
        validate(x, y)?;
        if !smoothing.is_finite() {
            return Err(GeomError::NotFinite {
                field: "smoothing",
                value: smoothing,
            });
        }
        if smoothing < 0.0 {
            return Err(GeomError::OutOfRange {
                field: "smoothing",
                value: smoothing,
                allowed: "smoothing >= 0 (0 interpolates)".to_string(),
            });
        }
        let h: Vec<f64> = x.windows(2).map(|p| p[1] - p[0]).collect();
        let fitted = if smoothing == 0.0 {
            not_a_knot(&h, y).map(|m| (y.to_vec(), m))
        } else {
            reinsch(&h, y, smoothing)
        };
        let Some((values, m)) = fitted.filter(|(v, m)| v.iter().chain(m).all(|a| a.is_finite()))
        else {
            return Err(GeomError::Table {
                row: 1,
                reason: "cannot fit a spline to these points (numerically singular)".to_string(),
            });
        };
        Ok(Self {
            x: x.to_vec(),
            y: values,
            m,
        })
    }

    /// The knots `x_i`.
    pub fn knots(&self) -> &[f64] {
        &self.x
    }

    /// The spline's values at the knots: the data for an interpolating spline,
    /// the smoothed values otherwise.
    pub fn values(&self) -> &[f64] {
        &self.y
    }

    /// `integral of s''(x)^2 dx` over the knot range, the roughness the
    /// smoothing spline penalises.
    pub fn roughness(&self) -> f64 {
        self.x
            .windows(2)
            .zip(self.m.windows(2))
            .map(|(x, m)| (x[1] - x[0]) / 3.0 * (m[0] * m[0] + m[0] * m[1] + m[1] * m[1]))
            .sum()
    }

    /// Value, first and second derivative at `x`.
    pub fn eval(&self, x: f64) -> (f64, f64, f64) {
        let n = self.x.len();
        let i = self
            .x
            .partition_point(|&k| k <= x)
            .saturating_sub(1)
            .min(n - 2);
        self.piece(i, x)
    }

    /// The cubic of the interval `[x_i, x_(i+1)]`, evaluated at `x`.
    fn piece(&self, i: usize, x: f64) -> (f64, f64, f64) {
        let (x0, x1) = (self.x[i], self.x[i + 1]);
        let (y0, y1) = (self.y[i], self.y[i + 1]);
        let (m0, m1) = (self.m[i], self.m[i + 1]);
        let h = x1 - x0;
        let b = (x - x0) / h;
        let a = 1.0 - b;
        let value = a * y0 + b * y1 + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0;
        let slope = (y1 - y0) / h + ((3.0 * b * b - 1.0) * m1 - (3.0 * a * a - 1.0) * m0) * h / 6.0;
        (value, slope, a * m0 + b * m1)
    }
}

/// Checks lengths, count, finiteness and strictly increasing `x`.
fn validate(x: &[f64], y: &[f64]) -> Result<(), GeomError> {
    if x.len() != y.len() {
        return Err(GeomError::Table {
            row: x.len().min(y.len()) + 1,
            reason: format!("{} z values but {} values", x.len(), y.len()),
        });
    }
    if x.len() < 4 {
        return Err(GeomError::TooFewPoints { count: x.len() });
    }
    for (i, (&xi, &yi)) in x.iter().zip(y).enumerate() {
        let row = i + 1;
        if !xi.is_finite() {
            return Err(GeomError::Table {
                row,
                reason: format!("z is not a finite number: {xi}"),
            });
        }
        if !yi.is_finite() {
            return Err(GeomError::Table {
                row,
                reason: format!("value is not a finite number: {yi}"),
            });
        }
        if i > 0 {
            let prev = x[i - 1];
            if xi == prev {
                return Err(GeomError::Table {
                    row,
                    reason: format!("duplicate z {xi}"),
                });
            }
            if xi < prev {
                return Err(GeomError::Table {
                    row,
                    reason: format!("z not increasing: {xi} after {prev}"),
                });
            }
        }
    }
    Ok(())
}

/// Second derivatives at the knots of the not-a-knot interpolating spline.
/// `h` are the knot spacings (at least 3).
fn not_a_knot(h: &[f64], y: &[f64]) -> Option<Vec<f64>> {
    let n = y.len();
    let k = n - 2;
    let slope: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    // Rows for the interior knots i = 1..n-2, unknowns M_1..M_(n-2).
    let mut sub = vec![0.0; k];
    let mut diag = vec![0.0; k];
    let mut sup = vec![0.0; k];
    let mut rhs = vec![0.0; k];
    for j in 0..k {
        let i = j + 1;
        sub[j] = h[i - 1];
        diag[j] = 2.0 * (h[i - 1] + h[i]);
        sup[j] = h[i];
        rhs[j] = 6.0 * (slope[i] - slope[i - 1]);
    }
    // Not-a-knot: M_0 = ((h0 + h1) M_1 - h0 M_2) / h1, eliminated from the first row;
    // likewise M_(n-1) from the last.
    let (h0, h1) = (h[0], h[1]);
    diag[0] = (h0 + h1) * (h0 + 2.0 * h1) / h1;
    sup[0] = (h1 * h1 - h0 * h0) / h1;
    let (hp, hl) = (h[n - 3], h[n - 2]);
    sub[k - 1] = (hp * hp - hl * hl) / hp;
    diag[k - 1] = (hp + hl) * (2.0 * hp + hl) / hp;
    let inner = solve_tridiagonal(&sub[1..], &diag, &sup[..k - 1], &rhs)?;
    let mut m = Vec::with_capacity(n);
    m.push(((h0 + h1) * inner[0] - h0 * inner[1]) / h1);
    m.extend_from_slice(&inner);
    m.push(((hp + hl) * inner[k - 1] - hl * inner[k - 2]) / hp);
    Some(m)
}

/// Fitted values and second derivatives of the Reinsch smoothing spline
/// (natural ends) for spacings `h`, data `y`, weight `lambda > 0`.
fn reinsch(h: &[f64], y: &[f64], lambda: f64) -> Option<(Vec<f64>, Vec<f64>)> {
    let n = y.len();
    let k = n - 2;
    // Unknowns gamma_i = s''(x_i), i = 1..n-2; (R + lambda Q^T Q) gamma = Q^T y.
    let inv: Vec<f64> = h.iter().map(|v| 1.0 / v).collect();
    let mut a0 = vec![0.0; k];
    let mut a1 = vec![0.0; k];
    let mut a2 = vec![0.0; k];
    let mut rhs = vec![0.0; k];
    for j in 0..k {
        let i = j + 1;
        let (p, c) = (inv[i - 1], inv[i]);
        a0[j] = (h[i - 1] + h[i]) / 3.0 + lambda * (p * p + (p + c) * (p + c) + c * c);
        if j + 1 < k {
            let nx = inv[i + 1];
            a1[j] = h[i] / 6.0 - lambda * ((p + c) * c + c * (c + nx));
        }
        if j + 2 < k {
            a2[j] = lambda * c * inv[i + 1];
        }
        rhs[j] = (y[i + 1] - y[i]) * c - (y[i] - y[i - 1]) * p;
    }
    let inner = solve_pentadiagonal_spd(&a0, &a1, &a2, &rhs)?;
    let mut m = Vec::with_capacity(n);
    m.push(0.0);
    m.extend_from_slice(&inner);
    m.push(0.0);
    // s(x_r) = y_r - lambda (Q gamma)_r.
    let values = (0..n)
        .map(|r| {
            let mut q = 0.0;
            if r > 0 {
                q += (m[r - 1] - m[r]) * inv[r - 1];
            }
            if r + 1 < n {
                q += (m[r + 1] - m[r]) * inv[r];
            }
            y[r] - lambda * q
        })
        .collect();
    Some((values, m))
}

/// Solves a tridiagonal system (`sub`, `sup` of length `diag.len() - 1`) by
/// Gaussian elimination with partial pivoting; `None` if it is singular.
fn solve_tridiagonal(sub: &[f64], diag: &[f64], sup: &[f64], rhs: &[f64]) -> Option<Vec<f64>> {
    let n = diag.len();
    // Upper-triangular rows after elimination: entries at columns i, i+1, i+2.
    let mut u = vec![[0.0; 4]; n];
    let mut cur = [diag[0], sup.first().copied().unwrap_or(0.0), 0.0, rhs[0]];
    for i in 0..n - 1 {
        let next = [
            sub[i],
            diag[i + 1],
            sup.get(i + 1).copied().unwrap_or(0.0),
            rhs[i + 1],
        ];
        let (piv, other) = if next[0].abs() > cur[0].abs() {
            (next, cur)
        } else {
            (cur, next)
        };
        if piv[0] == 0.0 {
            return None;
        }
        let f = other[0] / piv[0];
        u[i] = piv;
        cur = [
            other[1] - f * piv[1],
            other[2] - f * piv[2],
            0.0,
            other[3] - f * piv[3],
        ];
    }
    u[n - 1] = cur;
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let [d, e1, e2, b] = u[i];
        if d == 0.0 {
            return None;
        }
        let mut s = b;
        if i + 1 < n {
            s -= e1 * x[i + 1];
        }
        if i + 2 < n {
            s -= e2 * x[i + 2];
        }
        x[i] = s / d;
    }
    Some(x)
}

/// Solves a symmetric positive definite pentadiagonal system (diagonal `a0`,
/// first and second superdiagonals `a1`, `a2`, same length, tails unused) by
/// `L D L^T`; `None` if a pivot is not positive.
fn solve_pentadiagonal_spd(a0: &[f64], a1: &[f64], a2: &[f64], rhs: &[f64]) -> Option<Vec<f64>> {
    let n = a0.len();
    let mut d = vec![0.0; n];
    let mut l1 = vec![0.0; n];
    let mut l2 = vec![0.0; n];
    for i in 0..n {
        let mut di = a0[i];
        let mut e = a1[i];
        if i >= 1 {
            di -= l1[i - 1] * l1[i - 1] * d[i - 1];
            e -= l1[i - 1] * d[i - 1] * l2[i - 1];
        }
        if i >= 2 {
            di -= l2[i - 2] * l2[i - 2] * d[i - 2];
        }
        if di.is_nan() || di <= 0.0 {
            return None;
        }
        d[i] = di;
        l1[i] = e / di;
        l2[i] = a2[i] / di;
    }
    let mut z = rhs.to_vec();
    for i in 0..n {
        if i >= 1 {
            z[i] -= l1[i - 1] * z[i - 1];
        }
        if i >= 2 {
            z[i] -= l2[i - 2] * z[i - 2];
        }
    }
    for i in 0..n {
        z[i] /= d[i];
    }
    for i in (0..n).rev() {
        if i + 1 < n {
            z[i] -= l1[i] * z[i + 1];
        }
        if i + 2 < n {
            z[i] -= l2[i] * z[i + 2];
        }
    }
    Some(z)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uneven knots on [-2, 3].
    fn knots() -> Vec<f64> {
        vec![-2.0, -1.7, -0.9, -0.2, 0.0, 0.45, 1.3, 1.4, 2.2, 3.0]
    }

    fn cubic(x: f64) -> (f64, f64, f64) {
        (
            1.5 - 0.7 * x + 0.3 * x * x - 0.25 * x * x * x,
            -0.7 + 0.6 * x - 0.75 * x * x,
            0.6 - 1.5 * x,
        )
    }

    /// A wiggly test function and noise-like data.
    fn wiggly(n: usize) -> (Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..n)
            .map(|i| i as f64 * 0.5 + 0.1 * (i as f64 * 1.7).sin())
            .collect();
        let y = x
            .iter()
            .enumerate()
            .map(|(i, v)| v.sin() + 0.05 * ((i * 7919) % 13) as f64 / 13.0)
            .collect();
        (x, y)
    }

    #[test]
    fn not_a_knot_reproduces_a_cubic() {
        for n in [4, 5, 10] {
            let x: Vec<f64> = knots().into_iter().take(n).collect();
            let y: Vec<f64> = x.iter().map(|&v| cubic(v).0).collect();
            let s = CubicSpline::fit(&x, &y, 0.0).unwrap();
            assert_eq!(s.knots(), &x[..]);
            for i in 0..=200 {
                // Including 1 unit of extrapolation on both sides.
                let t = x[0] - 1.0 + (x[n - 1] - x[0] + 2.0) * i as f64 / 200.0;
                let (v, d, dd) = s.eval(t);
                let (ev, ed, edd) = cubic(t);
                assert!((v - ev).abs() < 1e-9, "n {n} x {t}: {v} vs {ev}");
                assert!((d - ed).abs() < 1e-9, "n {n} x {t}: {d} vs {ed}");
                assert!((dd - edd).abs() < 1e-9, "n {n} x {t}: {dd} vs {edd}");
            }
        }
    }

    #[test]
    fn interpolates_and_is_c2_at_knots() {
        let (x, y) = wiggly(12);
        for smoothing in [0.0, 0.3] {
            let s = CubicSpline::fit(&x, &y, smoothing).unwrap();
            for (i, &xi) in x.iter().enumerate().take(x.len() - 1).skip(1) {
                let (l, r) = (s.piece(i - 1, xi), s.piece(i, xi));
                assert!((l.0 - r.0).abs() < 1e-12, "value at knot {i}");
                assert!((l.1 - r.1).abs() < 1e-12, "slope at knot {i}");
                assert!((l.2 - r.2).abs() < 1e-12, "curvature at knot {i}");
            }
            if smoothing == 0.0 {
                for (xi, yi) in x.iter().zip(&y) {
                    assert!((s.eval(*xi).0 - yi).abs() < 1e-13);
                }
                // Not-a-knot: the third derivative is continuous at x_1 and x_(n-2).
                let third = |i: usize| (s.m[i + 1] - s.m[i]) / (x[i + 1] - x[i]);
                let n = x.len();
                assert!((third(0) - third(1)).abs() < 1e-9 * third(0).abs().max(1.0));
                assert!((third(n - 3) - third(n - 2)).abs() < 1e-9 * third(n - 2).abs().max(1.0));
            } else {
                assert_eq!(s.eval(x[0]).2, 0.0, "natural end");
                assert_eq!(s.eval(x[x.len() - 1]).2, 0.0, "natural end");
            }
        }
    }

    #[test]
    fn smoothing_spline_satisfies_its_optimality_condition() {
        // Minimiser of sum (y - s)^2 + lambda int s''^2: y_i - s(x_i) = lambda * jump of s''' at x_i.
        let (x, y) = wiggly(15);
        for lambda in [1e-3, 0.1, 2.0, 50.0] {
            let s = CubicSpline::fit(&x, &y, lambda).unwrap();
            let n = x.len();
            let third = |i: usize| {
                if i < n - 1 {
                    (s.m[i + 1] - s.m[i]) / (x[i + 1] - x[i])
                } else {
                    0.0
                }
            };
            for (i, (yi, si)) in y.iter().zip(s.values()).enumerate() {
                let jump = third(i) - if i > 0 { third(i - 1) } else { 0.0 };
                let residual = yi - si;
                assert!(
                    (residual - lambda * jump).abs() < 1e-12,
                    "lambda {lambda} knot {i}: {residual} vs {}",
                    lambda * jump
                );
            }
        }
    }

    #[test]
    fn smoothing_trades_fit_for_roughness() {
        let (x, y) = wiggly(20);
        let interp = CubicSpline::fit(&x, &y, 0.0).unwrap();
        let mut last_roughness = interp.roughness();
        let mut last_misfit = 0.0;
        for lambda in [1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0] {
            let s = CubicSpline::fit(&x, &y, lambda).unwrap();
            let misfit: f64 = y
                .iter()
                .zip(s.values())
                .map(|(a, b)| (a - b) * (a - b))
                .sum();
            assert!(s.roughness() < last_roughness, "lambda {lambda}");
            assert!(misfit > last_misfit, "lambda {lambda}");
            (last_roughness, last_misfit) = (s.roughness(), misfit);
        }
        // Huge smoothing approaches the least-squares line (zero roughness).
        let s = CubicSpline::fit(&x, &y, 1e9).unwrap();
        assert!(s.roughness() < 1e-12, "{}", s.roughness());
        // Tiny smoothing approaches interpolation.
        for lambda in [1e-6, 1e-9, 1e-12] {
            let s = CubicSpline::fit(&x, &y, lambda).unwrap();
            let worst = y
                .iter()
                .zip(s.values())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 100.0 * lambda, "lambda {lambda}: {worst}");
        }
    }

    #[test]
    fn smoothing_spline_roughness_is_exact() {
        // A natural spline's roughness computed from its pieces by Simpson's rule
        // (exact for the quadratic s''^2 on each piece).
        let (x, y) = wiggly(9);
        let s = CubicSpline::fit(&x, &y, 0.5).unwrap();
        let simpson: f64 = x
            .windows(2)
            .map(|p| {
                let f = |t: f64| s.eval(t).2.powi(2);
                (p[1] - p[0]) / 6.0 * (f(p[0]) + 4.0 * f(0.5 * (p[0] + p[1])) + f(p[1]))
            })
            .sum();
        assert!((s.roughness() - simpson).abs() < 1e-12 * simpson);
    }

    #[test]
    fn reports_bad_tables() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let y = [1.0, 2.0, 1.0, 0.0, 1.0];
        assert_eq!(
            CubicSpline::fit(&x[..3], &y[..3], 0.0),
            Err(GeomError::TooFewPoints { count: 3 })
        );
        assert!(matches!(
            CubicSpline::fit(&x, &y[..4], 0.0),
            Err(GeomError::Table { row: 5, .. })
        ));
        let row_reason = |x: &[f64], y: &[f64]| match CubicSpline::fit(x, y, 0.0) {
            Err(GeomError::Table { row, reason }) => (row, reason),
            other => panic!("unexpected {other:?}"),
        };
        let (row, reason) = row_reason(&[0.0, 1.0, 1.0, 3.0, 4.0], &y);
        assert_eq!(row, 3);
        assert!(reason.contains("duplicate z"), "{reason}");
        let (row, reason) = row_reason(&[0.0, 1.0, 2.0, 1.5, 4.0], &y);
        assert_eq!(row, 4);
        assert!(reason.contains("z not increasing"), "{reason}");
        let (row, reason) = row_reason(&[0.0, f64::NAN, 2.0, 3.0, 4.0], &y);
        assert_eq!(row, 2);
        assert!(reason.contains("not a finite"), "{reason}");
        let (row, _) = row_reason(&x, &[1.0, 2.0, 1.0, 0.0, f64::INFINITY]);
        assert_eq!(row, 5);
        assert!(matches!(
            CubicSpline::fit(&x, &y, f64::NAN),
            Err(GeomError::NotFinite {
                field: "smoothing",
                ..
            })
        ));
        assert!(matches!(
            CubicSpline::fit(&x, &y, -1.0),
            Err(GeomError::OutOfRange {
                field: "smoothing",
                ..
            })
        ));
    }

    #[test]
    fn evaluates_nan_without_panicking() {
        let (x, y) = wiggly(6);
        let s = CubicSpline::fit(&x, &y, 0.0).unwrap();
        assert!(s.eval(f64::NAN).0.is_nan());
    }

    #[test]
    fn tridiagonal_solver_pivots() {
        // A zero leading diagonal forces a row interchange.
        let sub = [1.0, 2.0];
        let diag = [0.0, 3.0, 1.0];
        let sup = [2.0, 1.0];
        let x_true = [1.0, -2.0, 0.5];
        let rhs = [
            diag[0] * x_true[0] + sup[0] * x_true[1],
            sub[0] * x_true[0] + diag[1] * x_true[1] + sup[1] * x_true[2],
            sub[1] * x_true[1] + diag[2] * x_true[2],
        ];
        let x = solve_tridiagonal(&sub, &diag, &sup, &rhs).unwrap();
        for (a, b) in x.iter().zip(x_true) {
            assert!((a - b).abs() < 1e-14);
        }
        assert!(solve_tridiagonal(&[0.0], &[0.0, 1.0], &[0.0], &[1.0, 1.0]).is_none());
    }
}
