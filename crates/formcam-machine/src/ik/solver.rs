//! The solver: Gauss–Newton from the extrapolated previous solution,
//! Levenberg–Marquardt when that fails, point after point.

use std::f64::consts::{PI, TAU};

use levenberg_marquardt::LevenbergMarquardt;
use nalgebra::DVector;

use super::equations::{Equations, moves};
use super::spindle::Spindle;
use super::unwrap_near;
use crate::{Fk, Machine, Target};

/// The axis values of every target by the solver (Gauss–Newton, else
/// Levenberg–Marquardt), seeded point after point: the spindle by its rule,
/// the other axes from the path extrapolated through the two points before.
pub(super) fn by_solver(m: &Machine, spindle: Option<Spindle>, targets: &[Target]) -> Vec<f64> {
    let unknowns: Vec<usize> = (0..m.axes.len())
        .filter(|&a| Some(a) != spindle.map(|s| s.axis))
        .collect();
    let mut q = m.home();
    let mut prev = q.clone();
    let mut values = Vec::with_capacity(targets.len() * m.axes.len());
    let lm = LevenbergMarquardt::new().with_tol(1e-15).with_patience(200);
    let moves = moves(m);
    let fk = Fk::new(m);
    let fk_mandrel = Fk::for_links(m, &[m.roles.mandrel]);
    let equations = |t, q: &[f64]| Equations::new(m, t, &unknowns, &moves, &fk, q);
    let mut before = q.clone();
    let mut poses = Vec::with_capacity(m.links.len());
    for (i, t) in targets.iter().enumerate() {
        if let Some(sp) = &spindle {
            fk_mandrel.poses_into(&q, &mut poses);
            q[sp.axis] = sp.angle(t, &poses[m.roles.mandrel], q[sp.axis], prev[sp.axis]);
        }
        if !unknowns.is_empty() {
            // Start from the path extrapolated through the two previous points.
            let mut start = q.clone();
            if i >= 2 {
                for &a in &unknowns {
                    start[a] = 2.0 * prev[a] - before[a];
                }
            }
            q = match newton(equations(t, &start)) {
                Some(done) => done,
                None => lm.minimize(equations(t, &q)).0.q,
            };
            // Revolute joints: the turn nearest the previous point's.
            for &a in &unknowns {
                if m.axes[a].is_rotary() {
                    q[a] = unwrap_near(q[a], prev[a], TAU);
                }
            }
            if i == 0 {
                nearest_home_branch(m, t, &unknowns, &moves, &fk, &mut q);
            }
        }
        values.extend_from_slice(&q);
        before.clone_from(&prev);
        prev.clone_from(&q);
    }
    values
}

/// Gauss–Newton from a close start (the fast path between neighbouring points):
/// the axes when the residual falls below 1e-12 within a few steps, each step
/// decreasing it; `None` otherwise (Levenberg–Marquardt then takes over).
fn newton(mut eq: Equations<'_>) -> Option<Vec<f64>> {
    let mut e = eq.eval(true);
    let norm = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>().sqrt();
    let mut res = norm(&e.r);
    for _ in 0..8 {
        if res < 1e-12 {
            return Some(eq.q);
        }
        let j = e.jac?;
        let r = DVector::from_column_slice(&e.r);
        let step = j.svd(true, true).solve(&(-r), 1e-12).ok()?;
        let mut q = eq.q.clone();
        for (k, &a) in eq.unknowns.iter().enumerate() {
            q[a] += step[k];
        }
        let old = std::mem::replace(&mut eq.q, q);
        e = eq.eval(true);
        let next = norm(&e.r);
        if next.is_nan() || next >= res {
            eq.q = old;
            return None;
        }
        res = next;
    }
    (res < 1e-12).then_some(eq.q)
}

/// At the first point: a rotary axis that can turn half a turn without moving
/// the payout point or breaking the orientation equations (an eye roller is the
/// same roller either way round) takes the half turn nearest its home value.
fn nearest_home_branch(
    m: &Machine,
    t: &Target,
    unknowns: &[usize],
    moves: &[(bool, bool)],
    fk: &Fk,
    q: &mut [f64],
) {
    let norm = |q: &[f64]| {
        let e = Equations::new(m, t, unknowns, moves, fk, q).eval(false);
        e.r.iter().map(|v| v * v).sum::<f64>().sqrt()
    };
    let base = norm(q);
    for &a in unknowns {
        if !m.axes[a].is_rotary() {
            continue;
        }
        let home = m.axes[a].home;
        let near = unwrap_near(q[a], home, PI);
        if (near - q[a]).abs() < 1e-12 {
            continue;
        }
        let mut alt = q.to_vec();
        alt[a] = near;
        if norm(&alt) <= base.max(1e-9) {
            q[a] = near;
        }
    }
}
