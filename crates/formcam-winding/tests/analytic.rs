//! Validation of the path engine against analytic solutions.

#![allow(clippy::unwrap_used, clippy::needless_range_loop)]

mod common;

use common::{Waist, vessel};

use std::f64::consts::{FRAC_PI_2, PI};

use formcam_geom::{Cone, Cylinder, DomeShape, Meridian, Mirrored, Vessel};
use formcam_winding::{
    Ends, LayerSpec, Method, MuLaw, PassEnd, Slippage, TraceOptions, minimax, plan_layer, shoot,
    trace,
};
use formcam_winding::{b_factor, bridging_limit};

#[test]
fn cylinder_geodesic_is_a_helix() {
    let cyl = Cylinder::new(50.0, 200.0).unwrap();
    let alpha = 0.6;
    let law = MuLaw::Constant(0.0);
    let tr = trace(&cyl, &law, alpha, &TraceOptions::default()).unwrap();
    assert!(matches!(tr.end, PassEnd::Exit { .. }));
    let pts = tr.sample(&cyl, &law, 501);
    for p in &pts {
        assert!(
            (p.v - p.z * alpha.tan() / 50.0).abs() < 1e-9,
            "v at z = {}",
            p.z
        );
        assert!((p.alpha - alpha).abs() < 1e-12);
    }
    let last = pts.last().unwrap();
    assert!((last.z - 200.0).abs() < 1e-12);
    assert!((last.v - 200.0 * alpha.tan() / 50.0).abs() < 1e-9);
    assert!((last.s - 200.0 / alpha.cos()).abs() < 1e-9);
}

#[test]
fn hemisphere_vessel_circuit_turns_two_pi_plus_helix() {
    let v = vessel(30.0, 30.0);
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Poles {
            start: 30.0,
            end: 30.0,
        },
        ..LayerSpec::default()
    };
    let layer = plan_layer(&v, &spec).unwrap();
    let alpha = (0.3f64).asin();
    let expect = 2.0 * PI + 2.0 * 300.0 * alpha.tan() / 100.0;
    assert!(
        (layer.report.turn_angle_circuit_rad - expect).abs() < 1e-9,
        "{} vs {expect}",
        layer.report.turn_angle_circuit_rad
    );
    assert!((layer.report.alpha_equator_rad - alpha).abs() < 1e-9);
    assert_eq!(layer.pass.method, Method::Geodesic);
    // Each half dome adds exactly pi/2: the pass's turn where it enters the cylinder.
    let h = (100.0f64 * 100.0 - 900.0).sqrt();
    let law = MuLaw::Constant(0.0);
    let tr = trace(&v, &law, FRAC_PI_2, &TraceOptions::default()).unwrap();
    let s_in = formcam_winding::find_root(|s| tr.state_at(s)[0] - h, 0.0, tr.length(), 1e-13, 0.0);
    assert!((tr.state_at(s_in)[1] - FRAC_PI_2).abs() < 1e-8);
    // A sphere (no cylinder): half a great circle per pass.
    let sphere = Vessel::new(
        100.0,
        0.0,
        (DomeShape::Hemisphere, 30.0),
        (DomeShape::Hemisphere, 30.0),
    )
    .unwrap();
    let tr = trace(&sphere, &law, FRAC_PI_2, &TraceOptions::default()).unwrap();
    assert!(
        (tr.turn_angle() - PI).abs() < 1e-9,
        "{}",
        tr.turn_angle() - PI
    );
    assert!((tr.length() - PI * 100.0).abs() < 1e-8);
}

#[test]
fn cone_geodesic_matches_closed_form() {
    for (r0, r1) in [(40.0, 80.0), (80.0, 60.0)] {
        let cone = Cone::new(r0, r1, 150.0).unwrap();
        let beta = cone.half_angle();
        let alpha0: f64 = 0.5;
        let c = r0 * alpha0.sin();
        let law = MuLaw::Constant(0.0);
        let tr = trace(&cone, &law, alpha0, &TraceOptions::default()).unwrap();
        for p in tr.sample(&cone, &law, 301) {
            let theta = ((c / p.r).acos() - (c / r0).acos()) / beta.sin();
            assert!(
                (p.v - theta).abs() < 1e-9,
                "cone {r0}->{r1} z {}: {} vs {theta}",
                p.z,
                p.v
            );
            assert!((p.c - c).abs() < 1e-9);
        }
    }
}

#[test]
fn nongeodesic_cylinder_matches_closed_form() {
    let r = 60.0;
    let cyl = Cylinder::new(r, 250.0).unwrap();
    for mu in [0.1, -0.15] {
        let alpha0 = 0.7f64;
        let law = MuLaw::Constant(mu);
        let tr = trace(&cyl, &law, alpha0, &TraceOptions::default()).unwrap();
        for p in tr.sample(&cyl, &law, 301) {
            let inv = 1.0 / alpha0.sin() - mu * p.z / r;
            assert!(
                (1.0 / p.alpha.sin() - inv).abs() < 1e-9,
                "mu {mu} z {}",
                p.z
            );
        }
    }
}

#[test]
fn turn_angle_agrees_with_quadrature_of_eq1() {
    // Ellipsoidal domes: compare the s-integrated turn angle with eq. 1 integrated in z
    // after the substitution z = z_n + t^2 (which removes the 1/sqrt singularity).
    let v = Vessel::new(
        100.0,
        120.0,
        (DomeShape::Ellipsoid { axis_ratio: 0.6 }, 25.0),
        (DomeShape::Ellipsoid { axis_ratio: 0.6 }, 25.0),
    )
    .unwrap();
    let c = 25.0;
    let tr = trace(
        &v,
        &MuLaw::Constant(0.0),
        FRAC_PI_2,
        &TraceOptions::default(),
    )
    .unwrap();
    let f = |z: f64| {
        let j = v.eval(z);
        c * (1.0 + j.dr * j.dr).sqrt() / (j.r * (j.r * j.r - c * c).sqrt())
    };
    let (za, zb) = v.z_range();
    let zm = 0.5 * (za + zb);
    // Gauss-Legendre 5 points on many panels.
    let gl = |g: &dyn Fn(f64) -> f64, a: f64, b: f64, n: usize| {
        let x = [
            0.0,
            0.538_469_310_105_683_1,
            -0.538_469_310_105_683_1,
            0.906_179_845_938_664,
            -0.906_179_845_938_664,
        ];
        let w = [
            0.568_888_888_888_888_9,
            0.478_628_670_499_366_5,
            0.478_628_670_499_366_5,
            0.236_926_885_056_189_1,
            0.236_926_885_056_189_1,
        ];
        let h = (b - a) / n as f64;
        (0..n)
            .map(|i| {
                let m = a + h * (i as f64 + 0.5);
                (0..5).map(|k| w[k] * g(m + 0.5 * h * x[k])).sum::<f64>() * 0.5 * h
            })
            .sum::<f64>()
    };
    let tmax = (zm - za).sqrt();
    let left = gl(&|t: f64| 2.0 * t * f(za + t * t), 0.0, tmax, 4000);
    let right = gl(&|t: f64| 2.0 * t * f(zb - t * t), 0.0, tmax, 4000);
    let quad = left + right;
    assert!(
        (tr.turn_angle() - quad).abs() < 1e-8,
        "{} vs {quad}",
        tr.turn_angle()
    );
}

#[test]
fn shooting_meets_both_openings_from_either_end() {
    let v = vessel(30.0, 45.0);
    let shot = shoot(&v, 0.6).unwrap();
    assert!(shot.mu.abs() > 1e-4, "different openings need friction");
    assert!(shot.residual_mm < 1e-9, "residual {}", shot.residual_mm);
    assert!((shot.z_turn - v.z_end()).abs() < 1e-9);
    let back = shoot(&Mirrored(&v), 0.6).unwrap();
    assert!(back.residual_mm < 1e-9);
    assert!(
        (back.mu + shot.mu).abs() < 1e-9,
        "{} vs {}",
        back.mu,
        shot.mu
    );
    // The same path: C(z) agrees at matching z.
    let law_f = MuLaw::Constant(shot.mu);
    let law_b = MuLaw::Constant(back.mu);
    let opts = TraceOptions {
        exit_at_end: false,
        overrun: 10.0,
        ..TraceOptions::default()
    };
    let pf = trace(&v, &law_f, FRAC_PI_2, &opts)
        .unwrap()
        .sample(&v, &law_f, 400);
    let mb = Mirrored(&v);
    let tb = trace(&mb, &law_b, FRAC_PI_2, &opts).unwrap();
    let total = v.z_start() + v.z_end();
    for p in pf
        .iter()
        .step_by(7)
        .filter(|p| p.z > 1.0 && p.z < v.z_end() - 1.0)
    {
        let zt = total - p.z;
        let s =
            formcam_winding::find_root(|s| tb.state_at(s)[0] - zt, 0.0, tb.length(), 1e-13, 0.0);
        let y = tb.state_at(s);
        let c_b = mb.r(y[0]) * y[2].sin();
        assert!(
            (c_b - p.c).abs() < 1e-6,
            "C at z {}: {} vs {}",
            p.z,
            p.c,
            c_b
        );
    }
}

#[test]
fn auto_layer_reports_shooting() {
    let v = vessel(30.0, 45.0);
    let spec = LayerSpec {
        slippage: Slippage::Auto,
        ends: Ends::Poles {
            start: 30.0,
            end: 45.0,
        },
        ..LayerSpec::default()
    };
    let layer = plan_layer(&v, &spec).unwrap();
    assert_eq!(layer.pass.method, Method::Shooting);
    assert!(layer.pass.boundary_residual_mm.unwrap() < 1e-9);
    let first = layer.points.first().unwrap();
    let last = layer.points.last().unwrap();
    assert!((first.c - 30.0).abs() < 1e-9);
    assert!((last.c - 45.0).abs() < 1e-6);
}

/// Worst |mu| of the straight segment (z0, c0) -> (z1, c1), or None if it leaves the feasible region.
fn segment_cost(m: &Waist, z0: f64, c0: f64, z1: f64, c1: f64) -> Option<f64> {
    let slope = (c1 - c0) / (z1 - z0);
    let mut worst: f64 = 0.0;
    for k in 0..=24 {
        let z = z0 + (z1 - z0) * k as f64 / 24.0;
        let c = c0 + slope * (z - z0);
        let j = m.eval(z);
        if c > j.r + 1e-9 || c < bridging_limit(&j) - 1e-9 {
            return None;
        }
        let b = b_factor(&j, c);
        if b <= 0.0 {
            if slope != 0.0 {
                return None;
            }
            continue;
        }
        worst = worst.max((slope / b).abs());
    }
    Some(worst)
}

#[test]
fn concave_minimax_beats_brute_force_and_respects_bridging() {
    let m = Waist { len: 300.0 };
    // The geodesic bridges here, so mu = 0 is refused.
    let spec = LayerSpec {
        slippage: Slippage::Geodesic,
        ends: Ends::Poles {
            start: m.r(0.0),
            end: m.r(300.0),
        },
        ..LayerSpec::default()
    };
    assert!(plan_layer(&m, &spec).is_err());

    let sol = minimax(&m, 4000, 3.0).unwrap();
    // Eq. 6 everywhere.
    for (i, (&z, &c)) in sol.z.iter().zip(&sol.c).enumerate() {
        let j = m.eval(z);
        assert!(c >= -1e-12 && c <= j.r + 1e-9, "C out of [0, r] at {z}");
        assert!(
            c >= sol.c_bridge[i] - 1e-7,
            "bridging at z = {z}: {c} < {}",
            sol.c_bridge[i]
        );
    }
    assert!(
        (sol.c[0] - m.r(0.0)).abs() < 1e-12 && (sol.c.last().unwrap() - m.r(300.0)).abs() < 1e-12
    );
    // The reported mu is the worst-case slippage of the returned C(z): recompute it
    // with the integral of B over each interval (Simpson), which is exact enough even
    // where B vanishes at the touch of the bridging limit.
    let mut worst: f64 = 0.0;
    for i in 0..sol.z.len() - 1 {
        let (z0, z1) = (sol.z[i], sol.z[i + 1]);
        let (c0, c1) = (sol.c[i], sol.c[i + 1]);
        let b = (b_factor(&m.eval(z0), c0)
            + 4.0 * b_factor(&m.eval(0.5 * (z0 + z1)), 0.5 * (c0 + c1))
            + b_factor(&m.eval(z1), c1))
            / 6.0;
        worst = worst.max(((c1 - c0) / (z1 - z0) / b).abs());
    }
    eprintln!("minimax {} recomputed {worst}", sol.mu_max);
    assert!(
        (worst - sol.mu_max).abs() <= 5e-3 * sol.mu_max,
        "{worst} vs {}",
        sol.mu_max
    );
    // The optimum does not depend on the grid.
    let fine = minimax(&m, 16000, 3.0).unwrap();
    assert!(
        (fine.mu_max - sol.mu_max).abs() <= 1e-3 * sol.mu_max,
        "{} vs {}",
        fine.mu_max,
        sol.mu_max
    );
    assert!(
        !sol.bridging_active.is_empty(),
        "the bridging limit binds on this waist"
    );

    // Brute force over piecewise-linear C on a coarse grid.
    let nodes = 25;
    let levels = 80;
    let zs: Vec<f64> = (0..nodes)
        .map(|i| 300.0 * i as f64 / (nodes - 1) as f64)
        .collect();
    let level_c = |i: usize, l: usize| {
        if i == 0 {
            m.r(0.0)
        } else if i == nodes - 1 {
            m.r(300.0)
        } else {
            let j = m.eval(zs[i]);
            let lo = bridging_limit(&j);
            lo + (j.r - lo) * l as f64 / (levels - 1) as f64
        }
    };
    let mut best = vec![f64::INFINITY; levels];
    best[0] = 0.0;
    for i in 1..nodes {
        let mut next = vec![f64::INFINITY; levels];
        let prev_levels = if i == 1 { 1 } else { levels };
        let cur_levels = if i == nodes - 1 { 1 } else { levels };
        for a in 0..prev_levels {
            if !best[a].is_finite() {
                continue;
            }
            for b in 0..cur_levels {
                if let Some(cost) =
                    segment_cost(&m, zs[i - 1], level_c(i - 1, a), zs[i], level_c(i, b))
                {
                    next[b] = next[b].min(best[a].max(cost));
                }
            }
        }
        best = next;
    }
    let brute = best[0];
    assert!(brute.is_finite());
    eprintln!("brute force on a {nodes}-node grid: {brute}");
    assert!(
        sol.mu_max <= brute * 1.001,
        "minimax {} vs brute force {brute}",
        sol.mu_max
    );
    // ... and the coarse grid is not far off: the optimum is real, not an artefact.
    assert!(
        brute <= 1.5 * sol.mu_max,
        "minimax {} vs brute force {brute}",
        sol.mu_max
    );

    // mu = "auto" falls back to the minimax on this mandrel.
    let spec = LayerSpec {
        slippage: Slippage::Auto,
        ends: Ends::Poles {
            start: m.r(0.0),
            end: m.r(300.0),
        },
        mu_limit: 3.0,
        ..LayerSpec::default()
    };
    let layer = plan_layer(&m, &spec).unwrap();
    assert_eq!(layer.pass.method, Method::Minimax);
    assert!(layer.report.turn_angle_pass_rad.is_finite() && layer.report.turn_angle_pass_rad > 0.0);
}

#[test]
fn minimax_on_a_convex_vessel_agrees_with_shooting() {
    let v = vessel(30.0, 45.0);
    let shot = shoot(&v, 0.6).unwrap();
    let mm = minimax(&v, 6000, 0.6).unwrap();
    assert!(
        (mm.mu_max - shot.mu.abs()).abs() < 2e-3 * shot.mu.abs(),
        "minimax {} vs shooting {}",
        mm.mu_max,
        shot.mu
    );
    // The same path: the quadrature of eq. 1 on the minimax grid gives the
    // shooting pass's turn angle and length.
    let pts = mm.points(&v);
    let last = pts.last().unwrap();
    eprintln!(
        "turn angle: minimax {} shooting {} (diff {:e}); length diff {:e}",
        last.v,
        shot.trace.turn_angle(),
        last.v - shot.trace.turn_angle(),
        last.s - shot.trace.length()
    );
    assert!((last.v - shot.trace.turn_angle()).abs() < 5e-5);
    assert!((last.s - shot.trace.length()).abs() < 1e-3);
}

#[test]
fn clairaut_quadrature_through_the_turn_arounds() {
    // A geodesic given as C(z) = const on a grid: the quadrature of eq. 1 with the
    // 1/sqrt(r - C) singularity integrated exactly per interval.
    let v = vessel(30.0, 30.0);
    let (za, zb) = v.z_range();
    let mut errs = Vec::new();
    for n in [1000usize, 4000, 16000] {
        let z: Vec<f64> = (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64;
                za + (zb - za) * t * t * (3.0 - 2.0 * t)
            })
            .collect();
        let c = vec![30.0; n + 1];
        let mu = vec![0.0; n + 1];
        let pts = formcam_winding::clairaut_points(&v, &z, &c, &mu);
        let expect = PI + 300.0 * 0.3f64.asin().tan() / 100.0;
        let err = pts.last().unwrap().v - expect;
        eprintln!("n = {n}: turn angle error {err:e}");
        errs.push(err.abs());
    }
    // Second order: a grid four times finer is about sixteen times more accurate.
    assert!(
        errs[0] / errs[1] > 12.0 && errs[1] / errs[2] > 12.0,
        "{errs:?}"
    );
    assert!(errs[2] < 1e-6, "{errs:?}");
}
