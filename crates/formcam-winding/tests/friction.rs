//! Turn-arounds held by friction: the minimax path on shells whose ends flare,
//! and `turnaround = "friction"` on tubes.

#![allow(clippy::unwrap_used, clippy::needless_range_loop)]

mod common;

use common::{Flare, Parabola};

use formcam_geom::{Cone, Cylinder, Jet, Meridian};
use formcam_winding::job::{LayerKind, Mandrel, MandrelKind, MandrelSpec, MuField, WindingSpec};
use formcam_winding::{
    Ends, LayerSpec, Method, PassEnd, Slippage, TubeTurn, friction_turns, minimax, plan_layer,
};
use formcam_winding::{b_factor, bridging_limit};

fn poles<M: Meridian>(m: &M, slippage: Slippage) -> LayerSpec {
    let (za, zb) = m.z_range();
    LayerSpec {
        slippage,
        ends: Ends::Poles {
            start: m.r(za),
            end: m.r(zb),
        },
        mu_limit: 3.0,
        ..LayerSpec::default()
    }
}

/// Worst |mu| of the straight segment (z0, c0) -> (z1, c1) of a Clairaut
/// function, or None where it leaves the feasible region `C_b <= C <= r`.
fn segment_cost<M: Meridian>(m: &M, z0: f64, c0: f64, z1: f64, c1: f64) -> Option<f64> {
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

/// The least worst |mu| over every piecewise-linear C(z) on `nodes` equal
/// intervals whose inner nodes take one of `levels` values between the
/// bridging limit and r (r itself excluded: a turn-around inside the pass),
/// from C = r at one end to C = r at the other (dynamic programming over
/// the worst slippage so far).
fn brute_force<M: Meridian>(m: &M, nodes: usize, levels: usize) -> f64 {
    let (za, zb) = m.z_range();
    let zs: Vec<f64> = (0..=nodes)
        .map(|i| za + (zb - za) * i as f64 / nodes as f64)
        .collect();
    let level_c = |i: usize, l: usize| {
        let j = m.eval(zs[i]);
        if i == 0 || i == nodes {
            j.r
        } else {
            let lo = bridging_limit(&j);
            lo + (j.r - lo) * l as f64 / levels as f64
        }
    };
    let mut best = vec![f64::INFINITY; levels];
    best[0] = 0.0;
    for i in 1..=nodes {
        let mut next = vec![f64::INFINITY; levels];
        let prev_levels = if i == 1 { 1 } else { levels };
        let cur_levels = if i == nodes { 1 } else { levels };
        for a in 0..prev_levels {
            if !best[a].is_finite() {
                continue;
            }
            for b in 0..cur_levels {
                if let Some(cost) =
                    segment_cost(m, zs[i - 1], level_c(i - 1, a), zs[i], level_c(i, b))
                {
                    next[b] = next[b].min(best[a].max(cost));
                }
            }
        }
        best = next;
    }
    best[0]
}

#[test]
fn minimax_on_a_flaring_shell_is_optimal() {
    let m = Flare { len: 300.0 };
    let (za, zb) = m.z_range();
    // The ends widen: the turns need |mu| >= |r'| = 0.1 there.
    assert!(m.dr(za) < 0.0 && m.dr(zb) > 0.0);
    let sol = minimax(&m, 4000, 3.0).unwrap();
    eprintln!(
        "flaring shell: optimal max |mu| {}, path laid at {}",
        sol.mu_max, sol.mu_path
    );
    assert!(sol.mu_max >= 0.1);
    assert!(sol.mu_path >= sol.mu_max && sol.mu_path <= sol.mu_max * (1.0 + 1e-4));
    // Eq. 4 at both ends, eq. 6 everywhere, and no turn-around inside the pass.
    let n = sol.z.len() - 1;
    assert!((sol.c[0] - m.r(za)).abs() < 1e-12 && (sol.c[n] - m.r(zb)).abs() < 1e-12);
    for i in 1..n {
        let j = m.eval(sol.z[i]);
        assert!(sol.c[i] < j.r, "C = r inside at z = {}", sol.z[i]);
        assert!(
            sol.c[i] >= bridging_limit(&j) - 1e-7,
            "bridging at {}",
            sol.z[i]
        );
    }
    // The slippage of the returned C(z), recomputed: within the path's bound,
    // and the bound reached (the worst case is where the optimum says).
    let mut worst: f64 = 0.0;
    for i in 0..n {
        let (z0, z1) = (sol.z[i], sol.z[i + 1]);
        let (c0, c1) = (sol.c[i], sol.c[i + 1]);
        let b = (b_factor(&m.eval(z0), c0)
            + 4.0 * b_factor(&m.eval(0.5 * (z0 + z1)), 0.5 * (c0 + c1))
            + b_factor(&m.eval(z1), c1))
            / 6.0;
        worst = worst.max(((c1 - c0) / (z1 - z0) / b).abs());
    }
    assert!(
        worst <= sol.mu_path * (1.0 + 1e-3) && worst >= sol.mu_max * (1.0 - 1e-3),
        "recomputed {worst} vs {} / {}",
        sol.mu_max,
        sol.mu_path
    );
    // The optimum does not depend on the grid.
    let fine = minimax(&m, 16000, 3.0).unwrap();
    assert!(
        (fine.mu_max - sol.mu_max).abs() <= 1e-3 * sol.mu_max,
        "{} vs {}",
        fine.mu_max,
        sol.mu_max
    );
    // No feasible C(z) of a coarse grid has a lower worst |mu|, and the grid's
    // best is not far off (the optimum is real, not an artefact).
    let brute = brute_force(&m, 24, 80);
    eprintln!("brute force on a 24-interval, 80-level grid: {brute}");
    assert!(brute.is_finite());
    assert!(
        sol.mu_max <= brute,
        "minimax {} vs brute force {brute}",
        sol.mu_max
    );
    assert!(
        brute <= 1.5 * sol.mu_max,
        "minimax {} vs brute force {brute}",
        sol.mu_max
    );

    // The layer: both "minimax" and "auto" (no constant mu turns at both
    // flaring ends) lay this path and report the optimum.
    for slippage in [Slippage::Minimax, Slippage::Auto] {
        let layer = plan_layer(&m, &poles(&m, slippage.clone())).unwrap();
        assert_eq!(layer.pass.method, Method::Minimax, "{slippage:?}");
        assert_eq!(layer.pass.mu_optimal, Some(sol.mu_max));
        assert_eq!(layer.pass.mu_max_abs, sol.mu_path);
        assert!(matches!(layer.pass.start, PassEnd::TurnAround { .. }));
        assert!(matches!(layer.pass.end, PassEnd::TurnAround { .. }));
        let turn = layer.report.turn_angle_pass_rad;
        assert!(turn.is_finite() && turn > 0.0);
        // The pattern covers the parallel the bands cross most widely, not the
        // widest one (where the pass turns).
        assert!(layer.report.alpha_equator_rad < 1.5);
        assert!(layer.report.thickness_max_mm.is_finite());
        assert!(
            layer
                .points
                .iter()
                .all(|p| p.mu.abs() <= sol.mu_path * 1.001)
        );
    }
}

#[test]
fn flaring_ends_alone_bind_on_a_parabolic_waist() {
    // r = 50 + a (z - L/2)^2: r' = -aL at z = 0 and +aL at z = L; |r'| falls
    // towards the waist, so the turns bind: the optimum is aL.
    let m = Parabola {
        len: 300.0,
        a: 1e-3,
    };
    let sol = minimax(&m, 4000, 3.0).unwrap();
    assert!(
        (sol.mu_max - 0.3).abs() <= 1e-6,
        "{} vs a L = 0.3",
        sol.mu_max
    );
    // A limit below what the turns need is an error that says so.
    let e = minimax(&m, 4000, 0.25).unwrap_err().to_string();
    assert!(e.contains("widens") && e.contains("0.3000"), "{e}");
}

/// A tube's friction layer: `mu` at the turns, geodesic of `deg` at z = 0.
fn friction_spec(mu: f64, deg: f64) -> LayerSpec {
    LayerSpec {
        slippage: Slippage::Constant(mu),
        ends: Ends::Tube {
            winding_angle: deg.to_radians(),
        },
        turnaround: TubeTurn::Friction,
        ..LayerSpec::default()
    }
}

#[test]
fn friction_turns_on_a_cylinder_follow_the_closed_form() {
    let (r, len, mu) = (50.0, 400.0, 0.2);
    let a0 = 40f64.to_radians();
    let cyl = Cylinder::new(r, len).unwrap();
    let layer = plan_layer(&cyl, &friction_spec(mu, 40.0)).unwrap();
    assert_eq!(layer.pass.method, Method::FrictionTurn);
    // 1/sin(alpha) = 1/sin(alpha0) - mu dz / R towards each end: the zone.
    let w0 = 1.0 / a0.sin();
    let zone = r * (w0 - 1.0) / mu;
    let turns = friction_turns(&cyl, mu, a0, 0.6).unwrap();
    assert!(
        (turns.start_zone - zone).abs() < 1e-9,
        "{}",
        turns.start_zone
    );
    assert!((turns.end_zone - zone).abs() < 1e-9, "{}", turns.end_zone);
    // In path length s from the turn, w = 1/sin(alpha) = sqrt(1 + (mu s / R)^2),
    // z = R (w - 1) / mu, v = asinh(mu s / R) / mu.
    let s1 = r * (w0 * w0 - 1.0).sqrt() / mu;
    let v1 = (mu * s1 / r).asinh() / mu;
    let s_mid = (len - 2.0 * zone) / a0.cos();
    let s_tot = 2.0 * s1 + s_mid;
    let v_tot = 2.0 * v1 + s_mid * a0.sin() / r;
    let closed = |s: f64| -> (f64, f64, f64, f64) {
        let zone_at = |s: f64| {
            let w = (1.0 + (mu * s / r).powi(2)).sqrt();
            (
                r * (w - 1.0) / mu,
                (mu * s / r).asinh() / mu,
                (1.0 / w).asin(),
            )
        };
        if s <= s1 {
            let (z, v, a) = zone_at(s);
            (z, v, a, -mu)
        } else if s <= s1 + s_mid {
            let d = s - s1;
            (zone + d * a0.cos(), v1 + d * a0.sin() / r, a0, 0.0)
        } else {
            let (z, v, a) = zone_at(s_tot - s);
            (len - z, v_tot - v, a, mu)
        }
    };
    assert!((layer.pass.length_mm - s_tot).abs() < 1e-9);
    assert!((layer.report.turn_angle_pass_rad - v_tot).abs() < 1e-9);
    assert!(matches!(layer.pass.start, PassEnd::TurnAround { z } if z == 0.0));
    assert!(matches!(layer.pass.end, PassEnd::TurnAround { z } if (z - len).abs() < 1e-9));
    let mut worst: f64 = 0.0;
    for p in &layer.points {
        let (z, v, a, m) = closed(p.s);
        worst = worst
            .max((p.z - z).abs())
            .max((p.v - v).abs())
            .max((p.alpha - a).abs());
        if (p.z - zone).abs() > 1e-6 && (p.z - (len - zone)).abs() > 1e-6 {
            assert_eq!(p.mu, m, "mu at z = {}", p.z);
        }
    }
    eprintln!("cylinder friction turns: worst deviation from the closed form {worst:e}");
    assert!(worst < 1e-9, "{worst}");
    // The pattern and the dwell follow as for any pass; the pattern is set on
    // the geodesic's angle, not at the turns.
    assert!((layer.report.alpha_equator_rad - a0).abs() < 1e-9);
    assert!(layer.report.thickness_max_mm.is_finite());
}

/// Eq. 3 for C(z), integrated by the classical RK4 with fixed steps.
fn rk4_c(m: &Cone, mu: f64, z0: f64, c0: f64, z1: f64, steps: usize) -> f64 {
    let f = |z: f64, c: f64| {
        let Jet { r, dr, d2r } = m.eval(z);
        let u = c * c / (r * r);
        mu * (u - r * d2r * (1.0 - u) / (1.0 + dr * dr))
    };
    let h = (z1 - z0) / steps as f64;
    let (mut z, mut c) = (z0, c0);
    for _ in 0..steps {
        let k1 = f(z, c);
        let k2 = f(z + 0.5 * h, c + 0.5 * h * k1);
        let k3 = f(z + 0.5 * h, c + 0.5 * h * k2);
        let k4 = f(z + h, c + h * k3);
        c += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        z += h;
    }
    c
}

#[test]
fn friction_turns_on_a_cone_follow_eq3() {
    let cone = Cone::new(40.0, 60.0, 400.0).unwrap();
    let (mu, a0) = (0.5, 35f64.to_radians());
    let layer = plan_layer(&cone, &friction_spec(mu, 35.0)).unwrap();
    let turns = friction_turns(&cone, mu, a0, 0.6).unwrap();
    let c0 = 40.0 * a0.sin();
    assert!((turns.c0 - c0).abs() < 1e-12);
    let (z1, z2) = (turns.start_zone, 400.0 - turns.end_zone);
    // The zones end where eq. 3, from C = r at each end, reaches C0.
    assert!((rk4_c(&cone, -mu, 0.0, 40.0, z1, 20000) - c0).abs() < 1e-9);
    assert!((rk4_c(&cone, mu, 400.0, 60.0, z2, 20000) - c0).abs() < 1e-9);
    // And the pass follows it: C = r sin(alpha) along the traced pass.
    let mut worst: f64 = 0.0;
    for p in layer.points.iter().step_by(20) {
        let c = if p.z < z1 {
            rk4_c(&cone, -mu, 0.0, 40.0, p.z, 4000)
        } else if p.z > z2 {
            rk4_c(&cone, mu, 400.0, 60.0, p.z, 4000)
        } else {
            c0
        };
        worst = worst.max((p.c - c).abs());
    }
    eprintln!("cone friction turns: worst |C - C_rk4| {worst:e} mm");
    assert!(worst < 1e-8, "{worst}");
    assert!(matches!(layer.pass.end, PassEnd::TurnAround { z } if (z - 400.0).abs() < 1e-9));
    // A cone that widens faster than mu can hold at its wide end.
    let steep = Cone::new(40.0, 240.0, 400.0).unwrap();
    let e = plan_layer(&steep, &friction_spec(0.4, 35.0)).unwrap_err();
    assert!(e.to_string().contains("mu > 0.5"), "{e}");
}

#[test]
fn friction_zones_longer_than_half_the_tube_name_the_mu_that_fits() {
    let (r, len) = (50.0, 200.0);
    let cyl = Cylinder::new(r, len).unwrap();
    let a0 = 40f64.to_radians();
    let e = plan_layer(&cyl, &friction_spec(0.2, 40.0))
        .unwrap_err()
        .to_string();
    // Each zone R (1/sin a0 - 1) / mu must be at most L / 2.
    let fit = 2.0 * r * (1.0 / a0.sin() - 1.0) / len;
    let said: f64 = e
        .split("mu >= ")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    assert!(e.starts_with("winding.mu"), "{e}");
    assert!((said - fit).abs() < 1e-6, "{e} (closed form {fit})");
    // ... and it does fit: the two zones meet in the middle.
    let layer = plan_layer(&cyl, &friction_spec(fit * (1.0 + 1e-9), 40.0)).unwrap();
    let t = friction_turns(&cyl, fit * (1.0 + 1e-9), a0, 0.6).unwrap();
    assert!((t.start_zone + t.end_zone - len).abs() < 1e-6);
    assert!(layer.report.turn_angle_pass_rad.is_finite());
}

#[test]
fn the_job_turns_tubes_by_friction() {
    let none = |_: &str| -> Result<String, String> { Err("no files".into()) };
    let cyl = MandrelSpec {
        kind: Some(MandrelKind::Cylinder),
        radius: Some(50.0),
        length: Some(400.0),
        ..MandrelSpec::default()
    }
    .build(none)
    .unwrap();
    let winding = WindingSpec {
        mu: Some(MuField::Number(0.2)),
        winding_angle_deg: Some(40.0),
        band_width: Some(10.0),
        band_thickness: Some(0.5),
        turnaround: Some("friction".into()),
        ..WindingSpec::default()
    };
    let spec = winding.layer_spec(&cyl).unwrap();
    assert_eq!(spec.turnaround, TubeTurn::Friction);
    // The band turns on the tube: no dwell is needed beyond the pattern's.
    assert_eq!(spec.dwell_min, 0.0);
    let layer = plan_layer(&cyl, &spec).unwrap();
    assert_eq!(layer.pass.method, Method::FrictionTurn);
    assert_eq!(layer.pass.mu_max_abs, 0.2);
    // The circuit closes with the pattern's dwell as for any pass.
    let circuit = formcam_winding::Circuit::new(&cyl, &layer);
    let expect = layer.report.turn_angle_circuit_with_dwell_rad;
    assert!((circuit.turn_angle() - expect).abs() < 1e-9);

    let errors = [
        (
            WindingSpec {
                turnaround: Some("hop".into()),
                ..winding.clone()
            },
            &cyl,
            "winding.turnaround",
        ),
        (
            WindingSpec {
                mu: Some(MuField::Word("auto".into())),
                ..winding.clone()
            },
            &cyl,
            "winding.mu",
        ),
        (
            WindingSpec {
                kind: Some(LayerKind::Hoop),
                winding_angle_deg: None,
                ..winding.clone()
            },
            &cyl,
            "winding.turnaround",
        ),
    ];
    for (w, m, field) in errors {
        let e = w
            .layer_spec(m)
            .and_then(|s| plan_layer(m, &s))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(field), "{e}");
    }
    let vessel: Mandrel = MandrelSpec {
        kind: Some(MandrelKind::Vessel),
        radius: Some(100.0),
        cylinder_length: Some(300.0),
        polar_opening: Some(30.0),
        ..MandrelSpec::default()
    }
    .build(none)
    .unwrap();
    let e = WindingSpec {
        winding_angle_deg: None,
        ..winding
    }
    .layer_spec(&vessel)
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("winding.turnaround"), "{e}");
}
