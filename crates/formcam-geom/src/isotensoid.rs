use std::f64::consts::FRAC_PI_2;

use crate::{GeomError, Jet, positive};

/// Smallest `polar_opening / radius` accepted. Below it the meridian's final
/// turn (about `radius * rho0^3` long in `w`) is narrower than double precision
/// can place next to the dome height.
const MIN_OPENING_RATIO: f64 = 1e-3;

/// Positive nodes of the 8-point Gauss–Legendre rule on `[-1, 1]`.
const GL_X: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
/// Weights belonging to [`GL_X`].
const GL_W: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// Panels the parameter range is split into before adaptive refinement.
const INITIAL_PANELS: u32 = 16;
/// Bisection depth limit of the table refinement.
const MAX_DEPTH: u32 = 50;
/// Allowed interpolation error of the parameter, relative to its local scale.
const THETA_TOL: f64 = 1e-13;
/// Allowed relative difference between a panel's quadrature and that of its halves.
const QUAD_TOL: f64 = 1e-14;

/// One table node: the parameter `theta` at distance `w` from the equator,
/// with `dtheta/dw` and `d2theta/dw2`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Node {
    w: f64,
    theta: f64,
    d1: f64,
    d2: f64,
}

/// The geodesic-isotensoid dome of netting theory: under internal pressure the
/// fibres, laid on geodesics whose Clairaut constant is the polar opening `r0`,
/// carry equal tension everywhere.
///
/// With `rho = r / R` (`R` the equator radius), `rho0 = r0 / R` and
/// `K = sqrt(1 - rho0^2)`, the sine of the angle between the surface normal and
/// the axis is `S(r) = rho^3 K / sqrt(rho^2 - rho0^2)`, and the meridian `r(w)`,
/// `w` the axial distance from the equator towards the pole, obeys
/// `r'' = -S'(r) / S^3` with `r(0) = R`, `r'(0) = 0`, so `r'^2 = 1/S^2 - 1`.
/// The dome ends at `r_s = R rho_s`, the root above `rho0` of
/// `rho^2 (1 + rho^2) = rho0^2 (1 + rho^2 + rho^4)`, where `S = 1` again: the
/// meridian turns parallel to the axis there (`r' = 0`, `r'' > 0`). `rho_s` is
/// only slightly above `rho0` (`rho_s^2 ~ rho0^2 + rho0^6`), so the final turn is
/// very sharp for small openings. A dome exists for `rho0^2 < 2/3` only.
///
/// Implementation: with `u = rho^2 = u_s + (1 - u_s) sin^2(theta)`,
/// `theta` in `[0, pi/2]`, the meridian is `w(theta) = R * integral from theta
/// to pi/2 of u / sqrt(u - u_m)`, `u_m < 0` the other root of the end-radius
/// quadratic in `u`; the integrand has no singularity. `new` tabulates
/// `theta(w)` with adaptive Gauss–Legendre panels; `eval_w` interpolates `theta`
/// by quintic Hermite and returns `r`, `r'` and `r''` from exact formulas at that
/// `theta`, so the three always lie on the true meridian.
#[derive(Debug, Clone, PartialEq)]
pub struct Isotensoid {
    radius: f64,
    polar_opening: f64,
    /// `rho0^2`.
    q: f64,
    /// `rho_s^2`.
    u_s: f64,
    /// `1 - u_s`.
    c: f64,
    /// `-u_m > 0`, so that `u - u_m = u + v0`.
    v0: f64,
    end_radius: f64,
    height: f64,
    /// Increasing in `w`, from `(0, pi/2)` to `(height, 0)`.
    nodes: Vec<Node>,
}

impl Isotensoid {
    /// The isotensoid dome on a cylinder of `radius` for fibres that turn at
    /// `polar_opening`. Needs `0.001 * radius <= polar_opening < radius * sqrt(2/3)`:
    /// above that bound the meridian curves outward at the equator and no dome
    /// exists.
    pub fn new(radius: f64, polar_opening: f64) -> Result<Self, GeomError> {
        let radius = positive("radius", radius)?;
        let polar_opening = positive("polar_opening", polar_opening)?;
        if polar_opening >= radius {
            return Err(GeomError::OutOfRange {
                field: "polar_opening",
                value: polar_opening,
                allowed: format!("0 < polar_opening < radius ({radius})"),
            });
        }
        let rho0 = polar_opening / radius;
        let q = rho0 * rho0;
        if 3.0 * q >= 2.0 {
            return Err(GeomError::OutOfRange {
                field: "polar_opening",
                value: polar_opening,
                allowed: format!(
                    "polar_opening < radius * sqrt(2/3) ({}) for a geodesic-isotensoid dome",
                    radius * (2.0f64 / 3.0).sqrt()
                ),
            });
        }
        if rho0 < MIN_OPENING_RATIO {
            return Err(GeomError::OutOfRange {
                field: "polar_opening",
                value: polar_opening,
                allowed: format!(
                    "polar_opening >= {MIN_OPENING_RATIO} * radius ({}) for a geodesic-isotensoid dome",
                    MIN_OPENING_RATIO * radius
                ),
            });
        }
        // Roots of (1 - q) u^2 + (1 - q) u - q = 0, written without cancellation.
        let d = ((1.0 + 3.0 * q) / (1.0 - q)).sqrt();
        let u_s = 2.0 * q / ((1.0 - q) * (1.0 + d));
        let v0 = 0.5 * (1.0 + d);
        let mut iso = Self {
            radius,
            polar_opening,
            q,
            u_s,
            c: 1.0 - u_s,
            v0,
            end_radius: radius * u_s.sqrt(),
            height: 0.0,
            nodes: Vec::new(),
        };
        iso.build_table();
        Ok(iso)
    }

    /// Equator radius, mm.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The polar opening (Clairaut constant of the fibres), mm.
    pub fn polar_opening(&self) -> f64 {
        self.polar_opening
    }

    /// Radius where the dome ends, `r_s = R rho_s`, slightly above the polar opening, mm.
    pub fn end_radius(&self) -> f64 {
        self.end_radius
    }

    /// Axial distance from the equator to the dome's end (where `r = r_s`), mm.
    pub fn height(&self) -> f64 {
        self.height
    }

    /// `r(w)`, `dr/dw` and `d2r/dw2` at axial distance `w` from the equator.
    ///
    /// On `[0, height]` `dr/dw <= 0`. Outside, the meridian continues by mirror
    /// symmetry about `w = 0` and `w = height` (as the differential equation
    /// does): `r(-w) = r(w)`, `r(2 height - w) = r(w)`, with `dr` negated.
    /// A non-finite `w` gives NaN.
    pub fn eval_w(&self, w: f64) -> Jet {
        let h = self.height;
        let (local, flip) = if (0.0..=h).contains(&w) {
            (w, false)
        } else if (-h..0.0).contains(&w) {
            (-w, true)
        } else if w > h && w <= 2.0 * h {
            (2.0 * h - w, true)
        } else if w.is_finite() {
            let m = w.rem_euclid(2.0 * h);
            if m <= h {
                (m, false)
            } else {
                (2.0 * h - m, true)
            }
        } else {
            return Jet {
                r: f64::NAN,
                dr: f64::NAN,
                d2r: f64::NAN,
            };
        };
        let jet = self.jet_at(self.theta_at(local.clamp(0.0, h)));
        if flip {
            Jet { dr: -jet.dr, ..jet }
        } else {
            jet
        }
    }

    /// `sin(theta)` and `cos(theta)` on `[0, pi/2]`, with `FRAC_PI_2` taken as
    /// the exact right angle (so `cos` vanishes exactly at the equator).
    fn sin_cos(theta: f64) -> (f64, f64) {
        (theta.sin(), (FRAC_PI_2 - theta).sin())
    }

    /// `u = rho^2` at `theta`, accurate near both ends.
    fn u_at(&self, s: f64, co: f64) -> f64 {
        if s * s > 0.5 {
            1.0 - self.c * co * co
        } else {
            self.u_s + self.c * s * s
        }
    }

    /// The meridian at parameter `theta`.
    fn jet_at(&self, theta: f64) -> Jet {
        let (s, co) = Self::sin_cos(theta);
        let u = self.u_at(s, co);
        let su = u.sqrt();
        let v = u + self.v0;
        // dr/dw = (dr/dtheta) / (dw/dtheta); r'' = -S'(r)/S^3 simplified.
        let dr = -self.c * s * co * v.sqrt() / (u * su);
        let d2r = -(2.0 * u - 3.0 * self.q) / (self.radius * (1.0 - self.q) * u * u * u * su);
        Jet {
            r: self.radius * su,
            dr,
            d2r,
        }
    }

    /// `g(theta) = u / sqrt(u - u_m)`, so that `dw/dtheta = -R g`, and `dg/dtheta`.
    fn g(&self, theta: f64) -> (f64, f64) {
        let (s, co) = Self::sin_cos(theta);
        let u = self.u_at(s, co);
        let v = u + self.v0;
        let sv = v.sqrt();
        (u / sv, self.c * s * co * (u + 2.0 * self.v0) / (v * sv))
    }

    /// `R * integral of g` over `[a, b]` by 8-point Gauss–Legendre.
    fn panel(&self, a: f64, b: f64) -> f64 {
        let mid = 0.5 * (a + b);
        let half = 0.5 * (b - a);
        let sum: f64 = GL_X
            .iter()
            .zip(GL_W)
            .map(|(x, wt)| wt * (self.g(mid - half * x).0 + self.g(mid + half * x).0))
            .sum();
        self.radius * half * sum
    }

    /// A table node at parameter `theta` placed at `w`.
    fn node(&self, theta: f64, w: f64) -> Node {
        let (g, dg) = self.g(theta);
        let rg = self.radius * g;
        Node {
            w,
            theta,
            d1: -1.0 / rg,
            d2: -dg / (rg * rg * g),
        }
    }

    /// Tabulates `theta(w)` on panels refined until the quintic Hermite
    /// interpolant and the panel quadrature both meet their tolerances.
    fn build_table(&mut self) {
        let scale0 = self.u_s.sqrt();
        let n0 = INITIAL_PANELS;
        let mut stack: Vec<(f64, f64, u32)> = (0..n0)
            .map(|k| {
                (
                    FRAC_PI_2 * f64::from(k) / f64::from(n0),
                    FRAC_PI_2 * f64::from(k + 1) / f64::from(n0),
                    0,
                )
            })
            .collect();
        let mut panels: Vec<(f64, f64, f64)> = Vec::new();
        while let Some((a, b, depth)) = stack.pop() {
            let m = 0.5 * (a + b);
            let whole = self.panel(a, b);
            let (i_am, i_mb) = (self.panel(a, m), self.panel(m, b));
            let halves = i_am + i_mb;
            let quad_ok = (whole - halves).abs() <= QUAD_TOL * halves;
            // Local w: 0 at theta = b (nearer the equator), `halves` at theta = a.
            let nb = self.node(b, 0.0);
            let na = self.node(a, halves);
            let theta_m = interpolate(&nb, &na, i_mb);
            let herm_ok = (theta_m - m).abs() <= THETA_TOL * (scale0 + m);
            if (quad_ok && herm_ok) || depth >= MAX_DEPTH || halves.is_nan() || halves <= 0.0 {
                panels.push((a, b, halves));
            } else {
                stack.push((a, m, depth + 1));
                stack.push((m, b, depth + 1));
            }
        }
        // From the equator (theta = pi/2, w = 0) towards the end (theta = 0).
        panels.sort_by(|x, y| y.0.total_cmp(&x.0));
        let mut nodes = Vec::with_capacity(panels.len() + 1);
        let mut w = 0.0;
        nodes.push(self.node(FRAC_PI_2, 0.0));
        for &(a, _, integral) in &panels {
            w += integral;
            nodes.push(self.node(a, w));
        }
        self.height = w;
        self.nodes = nodes;
    }

    /// The parameter at `w` in `[0, height]`.
    fn theta_at(&self, w: f64) -> f64 {
        let n = self.nodes.len();
        let i = self
            .nodes
            .partition_point(|node| node.w <= w)
            .saturating_sub(1)
            .min(n - 2);
        let (a, b) = (&self.nodes[i], &self.nodes[i + 1]);
        interpolate(a, b, w).clamp(0.0, FRAC_PI_2)
    }
}

/// Quintic Hermite interpolation of `theta` between nodes `a` and `b` at `w`.
fn interpolate(a: &Node, b: &Node, w: f64) -> f64 {
    let h = b.w - a.w;
    if h.is_nan() || h <= 0.0 {
        return a.theta;
    }
    let t = (w - a.w) / h;
    let (t2, t3) = (t * t, t * t * t);
    let (t4, t5) = (t3 * t, t3 * t2);
    let h1 = t - 6.0 * t3 + 8.0 * t4 - 3.0 * t5;
    let h2 = 0.5 * (t2 - 3.0 * t3 + 3.0 * t4 - t5);
    let h3 = 0.5 * (t3 - 2.0 * t4 + t5);
    let h4 = -4.0 * t3 + 7.0 * t4 - 3.0 * t5;
    let h5 = 10.0 * t3 - 15.0 * t4 + 6.0 * t5;
    a.theta
        + (b.theta - a.theta) * h5
        + h * (a.d1 * h1 + b.d1 * h4)
        + h * h * (a.d2 * h2 + b.d2 * h3)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Dome, DomeShape};

    /// Cases (R, r0) covering small, usual and large openings.
    const CASES: [(f64, f64); 5] = [
        (100.0, 10.0),
        (100.0, 30.0),
        (150.0, 45.0),
        (100.0, 80.0),
        (100.0, 2.0),
    ];

    /// `rho^2 (1 + rho^2) - rho0^2 (1 + rho^2 + rho^4)`.
    fn end_poly(rho: f64, rho0: f64) -> f64 {
        let p = rho * rho;
        p * (1.0 + p) - rho0 * rho0 * (1.0 + p + p * p)
    }

    /// `rho_s` by bisection of [`end_poly`], independent of the closed form.
    fn rho_s_bisect(rho0: f64) -> f64 {
        let (mut lo, mut hi) = (rho0, 1.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if end_poly(mid, rho0) < 0.0 {
                lo = mid
            } else {
                hi = mid
            }
        }
        0.5 * (lo + hi)
    }

    /// Composite 8-point Gauss–Legendre of `f` on `[a, b]` with `n` panels.
    fn gauss(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let step = (b - a) / n as f64;
        (0..n)
            .map(|k| {
                let mid = a + (k as f64 + 0.5) * step;
                let half = 0.5 * step;
                half * GL_X
                    .iter()
                    .zip(GL_W)
                    .map(|(x, w)| w * (f(mid - half * x) + f(mid + half * x)))
                    .sum::<f64>()
            })
            .sum()
    }

    /// `w(rho)` from the closed form `dz/drho = -R rho^3 K / sqrt((1 - rho^2) f(rho))`,
    /// `f` the end polynomial, with `rho = rho_s + d`, `d = (1 - rho_s) sin^2(phi)`
    /// removing both endpoint singularities and `f = d F(d)` expanded about its root
    /// `rho_s` (found by bisection) to avoid cancellation.
    fn closed_form_w(radius: f64, r0: f64, phi0: f64) -> f64 {
        let rho0 = r0 / radius;
        let q = rho0 * rho0;
        let k = (1.0 - q).sqrt();
        let rs = rho_s_bisect(rho0);
        let integrand = |phi: f64| {
            let d = (1.0 - rs) * phi.sin().powi(2);
            let p = rs + d;
            let f_over_d = (1.0 - q)
                * (2.0 * rs
                    + 4.0 * rs.powi(3)
                    + d * (1.0 + 6.0 * rs * rs)
                    + 4.0 * rs * d * d
                    + d.powi(3));
            2.0 * radius * p.powi(3) * k / ((1.0 + p) * f_over_d).sqrt()
        };
        gauss(integrand, phi0, FRAC_PI_2, 400)
    }

    /// `rho` at the closed form's parameter `phi`.
    fn closed_form_rho(radius: f64, r0: f64, phi: f64) -> f64 {
        let rs = rho_s_bisect(r0 / radius);
        rs + (1.0 - rs) * phi.sin().powi(2)
    }

    /// `S(r)` exactly as the problem states it.
    fn s_of_r(radius: f64, r0: f64, r: f64) -> f64 {
        let (rho, rho0) = (r / radius, r0 / radius);
        rho.powi(3) * (1.0 - rho0 * rho0).sqrt() / (rho * rho - rho0 * rho0).sqrt()
    }

    #[test]
    fn gauss_legendre_rule_is_exact_to_degree_15() {
        for k in 0..16 {
            let exact = if k % 2 == 0 {
                2.0 / (k as f64 + 1.0)
            } else {
                0.0
            };
            let got = gauss(|x| x.powi(k), -1.0, 1.0, 1);
            assert!((got - exact).abs() < 1e-15, "x^{k}: {got} vs {exact}");
        }
    }

    #[test]
    fn starts_at_the_equator() {
        for (radius, r0) in CASES {
            let iso = Isotensoid::new(radius, r0).unwrap();
            let q = (r0 / radius).powi(2);
            let j = iso.eval_w(0.0);
            assert_eq!(j.r, radius);
            assert_eq!(j.dr, 0.0);
            let d2r = -(2.0 - 3.0 * q) / ((1.0 - q) * radius);
            assert!(
                (j.d2r - d2r).abs() < 1e-13 * d2r.abs(),
                "{} vs {d2r}",
                j.d2r
            );
        }
    }

    #[test]
    fn ends_at_the_singular_radius() {
        for (radius, r0) in CASES {
            let iso = Isotensoid::new(radius, r0).unwrap();
            let rho0 = r0 / radius;
            let rs = iso.end_radius() / radius;
            assert!(rs > rho0);
            assert!(
                end_poly(rs, rho0).abs() < 1e-12,
                "residual {}",
                end_poly(rs, rho0)
            );
            assert!((rs - rho_s_bisect(rho0)).abs() < 1e-14);
            assert!((s_of_r(radius, r0, iso.end_radius()) - 1.0).abs() < 1e-9);
            let j = iso.eval_w(iso.height());
            assert_eq!(j.r, iso.end_radius());
            assert_eq!(j.dr, 0.0);
            assert!(j.d2r > 0.0);
            assert_eq!(iso.polar_opening(), r0);
            assert_eq!(iso.radius(), radius);
        }
    }

    #[test]
    fn height_matches_closed_form_quadrature() {
        for (radius, r0) in CASES {
            let iso = Isotensoid::new(radius, r0).unwrap();
            let h = closed_form_w(radius, r0, 0.0);
            assert!(
                (iso.height() - h).abs() < 1e-11 * h,
                "{radius} {r0}: {} vs {h}",
                iso.height()
            );
        }
        // Known proportions: a small opening gives a dome about 0.6 R deep.
        let iso = Isotensoid::new(100.0, 10.0).unwrap();
        assert!(
            iso.height() > 55.0 && iso.height() < 65.0,
            "{}",
            iso.height()
        );
    }

    #[test]
    fn radius_matches_closed_form_inside() {
        for (radius, r0) in CASES {
            let iso = Isotensoid::new(radius, r0).unwrap();
            for i in 0..=40 {
                // Dense towards the end, where the meridian turns.
                let phi = FRAC_PI_2 * (i as f64 / 40.0).powi(2);
                let rho = closed_form_rho(radius, r0, phi);
                let w = closed_form_w(radius, r0, phi);
                let j = iso.eval_w(w);
                // Relative error in r, allowing for the rounding of w (slope times 1e-14 h).
                let err = (j.r - radius * rho).abs();
                let tol = 1e-12 * radius * rho + 1e-14 * iso.height() * j.dr.abs();
                assert!(
                    err < tol,
                    "{radius} {r0} rho {rho}: err {err:e} tol {tol:e}"
                );
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for (radius, r0) in CASES {
            let iso = Isotensoid::new(radius, r0).unwrap();
            let h = iso.height();
            for i in 1..200 {
                // Points spread over the dome and crowded at its end.
                let x = i as f64 / 200.0;
                let w = h * (1.0 - (1.0 - x).powi(4));
                // Step on the local length scale: R rho0^3 at the end.
                let e = 3e-5 * (radius * (r0 / radius).powi(3) + (h - w).min(w));
                let (a, b, c) = (iso.eval_w(w - e), iso.eval_w(w), iso.eval_w(w + e));
                let dr_fd = (c.r - a.r) / (2.0 * e);
                let d2r_fd = (c.dr - a.dr) / (2.0 * e);
                assert!(
                    (b.dr - dr_fd).abs() < 1e-6 * (1.0 + b.dr.abs()),
                    "{r0} w {w}: {} vs {dr_fd}",
                    b.dr
                );
                assert!(
                    (b.d2r - d2r_fd).abs() < 1e-6 * b.d2r.abs().max(1.0 / radius),
                    "{r0} w {w}: {} vs {d2r_fd}",
                    b.d2r
                );
                assert!(b.dr <= 0.0);
            }
        }
    }

    #[test]
    fn satisfies_the_meridian_equation() {
        for (radius, r0) in CASES {
            let iso = Isotensoid::new(radius, r0).unwrap();
            let h = iso.height();
            for i in 0..=100 {
                let w = h * i as f64 / 100.0;
                let j = iso.eval_w(w);
                let s = s_of_r(radius, r0, j.r);
                let slope2 = 1.0 / (s * s) - 1.0;
                // The test's own S(r) loses digits to rho^2 - rho0^2 near the end.
                let cond = j.r * j.r / (j.r * j.r - r0 * r0);
                let tol = (1e-10 + 1e-15 * cond) * (1.0 + slope2);
                assert!(
                    (j.dr * j.dr - slope2).abs() < tol,
                    "{r0} w {w}: {} vs {slope2}",
                    j.dr * j.dr
                );
                // S'(r) by Richardson-extrapolated central differences, step
                // relative to r - r0 (S varies on that scale near the end).
                let e = 1e-2 * (j.r - r0);
                let central = |e: f64| {
                    (s_of_r(radius, r0, j.r + e) - s_of_r(radius, r0, j.r - e)) / (2.0 * e)
                };
                let ds = (4.0 * central(e) - central(2.0 * e)) / 3.0;
                let d2r = -ds / s.powi(3);
                let tol = (1e-7 + 1e-15 * j.r / e) * j.d2r.abs().max(1.0 / radius);
                assert!((j.d2r - d2r).abs() < tol, "{r0} w {w}: {} vs {d2r}", j.d2r);
            }
        }
    }

    #[test]
    fn netting_identity_and_positive_normal_curvature() {
        for (radius, r0) in CASES {
            let iso = Isotensoid::new(radius, r0).unwrap();
            let h = iso.height();
            for i in 0..=1000 {
                let x = i as f64 / 1000.0;
                let w = h * (1.0 - (1.0 - x).powi(3));
                let j = iso.eval_w(w);
                let sin_a = r0 / j.r;
                let cos2 = 1.0 - sin_a * sin_a;
                let tan2 = sin_a * sin_a / cos2;
                let slope2 = 1.0 + j.dr * j.dr;
                let ratio = -j.r * j.d2r / slope2;
                assert!(
                    (ratio - (2.0 - tan2)).abs() < 1e-8 * (1.0 + tan2),
                    "{r0} w {w}: {ratio} vs {}",
                    2.0 - tan2
                );
                let k_m = -j.d2r / slope2.powf(1.5);
                let k_p = 1.0 / (j.r * slope2.sqrt());
                let k_n = cos2 * k_m + sin_a * sin_a * k_p;
                assert!(k_n > 0.0, "{r0} w {w}: normal curvature {k_n}");
            }
        }
    }

    #[test]
    fn continues_by_mirror_symmetry() {
        let iso = Isotensoid::new(100.0, 30.0).unwrap();
        let h = iso.height();
        for w in [0.1, 5.0, 0.5 * h, h - 1.0, h - 1e-3] {
            let j = iso.eval_w(w);
            for (m, flip) in [
                (-w, true),
                (2.0 * h - w, true),
                (2.0 * h + w, false),
                (-2.0 * h - w, true),
            ] {
                let k = iso.eval_w(m);
                assert!((k.r - j.r).abs() < 1e-9, "w {w} -> {m}");
                let sign = if flip { -1.0 } else { 1.0 };
                assert!(
                    (k.dr - sign * j.dr).abs() < 1e-7 * (1.0 + j.dr.abs()),
                    "w {w} -> {m}"
                );
                assert!((k.d2r - j.d2r).abs() < 1e-7 * j.d2r.abs(), "w {w} -> {m}");
            }
        }
        assert!(iso.eval_w(h + 1e-3).dr > 0.0);
        assert!(iso.eval_w(f64::NAN).r.is_nan());
        assert!(iso.eval_w(f64::INFINITY).dr.is_nan());
    }

    #[test]
    fn table_is_compact() {
        for (radius, r0) in CASES {
            let iso = Isotensoid::new(radius, r0).unwrap();
            let n = iso.nodes.len();
            assert!(n < 2000, "{r0}: {n} nodes");
            assert!(
                iso.nodes
                    .windows(2)
                    .all(|p| p[0].w < p[1].w && p[0].theta > p[1].theta)
            );
        }
    }

    #[test]
    fn dome_uses_it() {
        let d = Dome::new(DomeShape::Isotensoid, 100.0, 30.0).unwrap();
        let iso = Isotensoid::new(100.0, 30.0).unwrap();
        assert_eq!(d.height(), iso.height());
        assert!((d.end_radius() - iso.end_radius()).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_input() {
        let field_of = |e: GeomError| match e {
            GeomError::NotFinite { field, .. }
            | GeomError::NotPositive { field, .. }
            | GeomError::OutOfRange { field, .. } => field,
            other => panic!("unexpected {other:?}"),
        };
        assert_eq!(
            field_of(Isotensoid::new(f64::NAN, 10.0).unwrap_err()),
            "radius"
        );
        assert_eq!(field_of(Isotensoid::new(-5.0, 10.0).unwrap_err()), "radius");
        assert_eq!(
            field_of(Isotensoid::new(100.0, f64::INFINITY).unwrap_err()),
            "polar_opening"
        );
        assert_eq!(
            field_of(Isotensoid::new(100.0, 0.0).unwrap_err()),
            "polar_opening"
        );
        assert!(matches!(
            Isotensoid::new(100.0, 100.0),
            Err(GeomError::OutOfRange {
                field: "polar_opening",
                ..
            })
        ));
        // Beyond radius * sqrt(2/3) = 81.65 no dome exists.
        assert!(matches!(
            Isotensoid::new(100.0, 82.0),
            Err(GeomError::OutOfRange {
                field: "polar_opening",
                ..
            })
        ));
        assert!(Isotensoid::new(100.0, 81.6).is_ok());
        assert!(matches!(
            Isotensoid::new(100.0, 0.05),
            Err(GeomError::OutOfRange {
                field: "polar_opening",
                ..
            })
        ));
        assert!(Isotensoid::new(100.0, 0.1).is_ok());
    }
}
