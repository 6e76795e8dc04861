//! The pull-speed optimum (eqs. 12–15): `l(x)` discretised and chosen
//! lexicographically — max min `u`, then min max `u`, then min `∫ (u - U)^2 dx`
//! (LP, LP, QP by Clarabel) — with the turn `V(l)` (and `R(l)` for a fixed bath)
//! linearised and relinearised in sequence.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
    SupportedConeT, ZeroConeT,
};

use super::band::eye_at;
use super::spec::EyeSpec;
use crate::{CircuitPoint, WindingError};

/// A sparse problem for Clarabel: `min 1/2 x'Px + q'x`, equality rows then `<=` rows.
struct Problem {
    n: usize,
    p_diag: Vec<(usize, f64)>,
    q: Vec<f64>,
    eq: Vec<(Vec<(usize, f64)>, f64)>,
    le: Vec<(Vec<(usize, f64)>, f64)>,
}

impl Problem {
    fn new(n: usize) -> Self {
        Self {
            n,
            p_diag: Vec::new(),
            q: vec![0.0; n],
            eq: Vec::new(),
            le: Vec::new(),
        }
    }

    fn solve(&self, stage: &str) -> Result<Vec<f64>, WindingError> {
        let m = self.eq.len() + self.le.len();
        let (mut ii, mut jj, mut vv) = (Vec::new(), Vec::new(), Vec::new());
        for (row, (coef, _)) in self.eq.iter().chain(&self.le).enumerate() {
            for &(j, v) in coef {
                ii.push(row);
                jj.push(j);
                vv.push(v);
            }
        }
        let a = CscMatrix::new_from_triplets(m, self.n, ii, jj, vv);
        let (pi, pv): (Vec<usize>, Vec<f64>) = self.p_diag.iter().copied().unzip();
        let p = CscMatrix::new_from_triplets(self.n, self.n, pi.clone(), pi, pv);
        let b: Vec<f64> = self.eq.iter().chain(&self.le).map(|r| r.1).collect();
        let mut cones: Vec<SupportedConeT<f64>> = Vec::new();
        if !self.eq.is_empty() {
            cones.push(ZeroConeT(self.eq.len()));
        }
        cones.push(NonnegativeConeT(self.le.len()));
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .max_iter(400)
            .build()
            .map_err(|e| WindingError::field("eye", format!("solver settings: {e:?}")))?;
        let mut solver = DefaultSolver::new(&p, &self.q, &a, &b, &cones, settings)
            .map_err(|e| WindingError::field("eye", format!("{stage}: solver setup: {e:?}")))?;
        solver.solve();
        match solver.solution.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => Ok(solver.solution.x.clone()),
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                Err(WindingError::infeasible(
                    "eye.l_max",
                    format!(
                        "{stage}: no free length l(x) keeps the clearance, stays under l_max, never \
                         slackens the band and never turns the mandrel back (the LP is infeasible)"
                    ),
                ))
            }
            other => Err(WindingError::infeasible(
                "eye",
                format!("{stage}: the solver stopped with {other:?}"),
            )),
        }
    }
}

/// Lexicographic pull-speed optimum on the nodes `pts` (`pts[n]` closes the cycle).
pub(super) fn optimise(
    pts: &[CircuitPoint],
    l_min: &[f64],
    spec: &EyeSpec,
    k: f64,
) -> Result<Vec<f64>, WindingError> {
    let n = pts.len() - 1;
    if let Some(i) = (0..=n).find(|&i| l_min[i] > spec.l_max) {
        return Err(WindingError::infeasible(
            "eye.l_max",
            format!(
                "keeping the clearance of {} mm needs a free length of {:.3} mm at x = {:.3} mm \
                 (z = {:.3} mm), more than l_max = {} mm",
                spec.clearance, l_min[i], pts[i].x, pts[i].z, spec.l_max
            ),
        ));
    }
    let lo: Vec<f64> = (0..n)
        .map(|i| l_min[i].max(l_min[if i == 0 { n } else { i }]))
        .collect();
    // Start: a constant length when one fits, else the least lengths. A fixed bath
    // needs a start that keeps every constraint (each trust region around it then
    // holds a feasible point): the constant length if the mandrel never turns back
    // with it, else the optimum of a moving bath.
    let top = lo.iter().copied().fold(0.0, f64::max);
    let constant = (top <= spec.l_max).then(|| vec![top; n]);
    let mut l0: Vec<f64> = match constant {
        Some(c) if k == 0.0 || turns_forward(pts, &c) => c,
        _ if k != 0.0 => {
            let mut start = optimise(pts, l_min, spec, 0.0)?;
            start.truncate(n);
            start
        }
        Some(c) => c,
        None => lo.clone(),
    };
    // k = 1 linearises R(l); both linearise the turn V(l) of the no-reverse rows.
    let iterations = 8;
    let mut trust = 0.25 * spec.l_max;
    let mut best = l0.clone();
    let mut best_min = f64::NEG_INFINITY;
    for _ in 0..iterations {
        let (_, l) = Stages::new(pts, &lo, spec, &l0, trust, k).min()?;
        let exact = exact_u_min(pts, &l, k);
        let forward = turns_forward(pts, &l);
        if exact > best_min + 1e-12 || (k == 0.0 && forward) {
            let gain = exact - best_min;
            best_min = best_min.max(exact);
            best = l.clone();
            l0 = l;
            // Converged: the linearisations no longer move the optimum.
            if forward && (k == 0.0 || gain < 1e-4) {
                break;
            }
        } else if k == 0.0 {
            // Only the turn is linearised: relinearise at the new solution.
            l0 = l;
        } else {
            trust *= 0.5;
        }
    }
    // Stages 2 and 3 around the stage-1 optimum; the turn rows are relinearised
    // at their solution until the exact check holds, else the stage-1 optimum
    // (which keeps every constraint) stands.
    let mut at = best.clone();
    let mut out = None;
    for _ in 0..4 {
        let stages = Stages::new(pts, &lo, spec, &at, trust, k);
        let (t_star, _) = stages.min()?;
        let (w_star, _) = stages.max(t_star)?;
        let l = stages.rms(t_star, w_star)?;
        if turns_forward(pts, &l) {
            out = Some(l);
            break;
        }
        at = l;
    }
    let mut l = out.unwrap_or(best);
    l.push(l[0]);
    Ok(l)
}

/// `lambda`'s dependence on `l` at each node, linear: `lambda_i = c1_i l_i + c0_i + s_i`
/// (exact for `k = 0`; linearised `R` for `k = 1`).
struct Linear {
    c1: Vec<f64>,
    c0: Vec<f64>,
}

impl Linear {
    fn new(pts: &[CircuitPoint], l0: &[f64], k: f64) -> Self {
        let n = pts.len() - 1;
        let mut c1 = vec![1.0; n];
        let mut c0 = vec![0.0; n];
        if k != 0.0 {
            for i in 0..n {
                let (_, r, _, _, g) = eye_at(&pts[i], l0[i]);
                c1[i] = 1.0 - k * g;
                c0[i] = -k * (r - g * l0[i]);
            }
        }
        Self { c1, c0 }
    }
}

fn exact_u_min(pts: &[CircuitPoint], l: &[f64], k: f64) -> f64 {
    let n = pts.len() - 1;
    let lam = |i: usize| {
        let li = l[i % n];
        let (_, r, _, _, _) = eye_at(&pts[i], li);
        li + pts[i].x - k * r
    };
    (0..n)
        .map(|i| (lam(i + 1) - lam(i)) / (pts[i + 1].x - pts[i].x))
        .fold(f64::INFINITY, f64::min)
}

/// The eye's turn `V` at free length `l` and its slope `dV/dl`.
fn turn_and_slope(p: &CircuitPoint, l: f64) -> (f64, f64) {
    let (_, r, v, _, _) = eye_at(p, l);
    (
        v,
        if r > 0.0 {
            p.r * p.alpha.sin() / (r * r)
        } else {
            0.0
        },
    )
}

/// Whether the mandrel never turns back along `l` (cyclic, `l[n] = l[0]`).
fn turns_forward(pts: &[CircuitPoint], l: &[f64]) -> bool {
    let n = l.len();
    (0..n).all(|i| {
        let (vi, _) = turn_and_slope(&pts[i], l[i]);
        let (vj, _) = turn_and_slope(&pts[i + 1], l[(i + 1) % n]);
        vj - vi >= -1e-9
    })
}

/// The three stages on the discretised `l(x)`, linearised at `l0` (the turn `V`,
/// and `R` for a fixed bath), with what every stage shares.
struct Stages<'a> {
    pts: &'a [CircuitPoint],
    lo: &'a [f64],
    spec: &'a EyeSpec,
    l0: &'a [f64],
    lin: Linear,
    trust: f64,
    k: f64,
}

impl<'a> Stages<'a> {
    fn new(
        pts: &'a [CircuitPoint],
        lo: &'a [f64],
        spec: &'a EyeSpec,
        l0: &'a [f64],
        trust: f64,
        k: f64,
    ) -> Self {
        Self {
            pts,
            lo,
            spec,
            l0,
            lin: Linear::new(pts, l0, k),
            trust,
            k,
        }
    }

    fn n(&self) -> usize {
        self.lo.len()
    }

    /// Rows common to every stage: bounds, trust region, no slack, no reverse rotation.
    fn rows(&self, prob: &mut Problem) {
        let (pts, l0, n) = (self.pts, self.l0, self.n());
        for i in 0..n {
            let j = (i + 1) % n;
            let dx = pts[i + 1].x - pts[i].x;
            prob.le.push((vec![(i, -1.0)], -self.lo[i]));
            prob.le.push((vec![(i, 1.0)], self.spec.l_max));
            if self.k != 0.0 {
                prob.le.push((vec![(i, 1.0)], l0[i] + self.trust));
                prob.le.push((vec![(i, -1.0)], -(l0[i] - self.trust)));
            }
            // No slack: l_j - l_i + dx >= 0.
            prob.le.push((vec![(i, 1.0), (j, -1.0)], dx));
            // No reverse rotation, linearised at l0: V_j(l_j) >= V_i(l_i), with
            // dV/dl = r sin(alpha) / R^2 > 0.
            let (vi, gi) = turn_and_slope(&pts[i], l0[i]);
            let (vj, gj) = turn_and_slope(&pts[i + 1], l0[j]);
            prob.le
                .push((vec![(i, gi), (j, -gj)], vj - vi - gj * l0[j] + gi * l0[i]));
        }
    }

    /// `u_i = 1 + (D_i + e_i)/dx_i` with `D_i = c1_j l_j - c1_i l_i`: the
    /// coefficients of `D_i / dx_i` and the constant `1 + e_i / dx_i`.
    fn u_terms(&self, i: usize) -> (Vec<(usize, f64)>, f64) {
        let (c1, c0) = (&self.lin.c1, &self.lin.c0);
        let j = (i + 1) % c1.len();
        let dx = self.pts[i + 1].x - self.pts[i].x;
        (
            vec![(j, c1[j] / dx), (i, -c1[i] / dx)],
            1.0 + (c0[j] - c0[i]) / dx,
        )
    }

    /// Stage 1: the largest lower bound `t` of `u`, and its `l`.
    fn min(&self) -> Result<(f64, Vec<f64>), WindingError> {
        let n = self.n();
        let mut prob = Problem::new(n + 1);
        prob.q[n] = -1.0;
        self.rows(&mut prob);
        for i in 0..n {
            // t <= u_i  ->  t - D_i/dx <= const
            let (row, c) = self.u_terms(i);
            let mut row: Vec<(usize, f64)> = row.iter().map(|&(j, v)| (j, -v)).collect();
            row.push((n, 1.0));
            prob.le.push((row, c));
        }
        let x = prob.solve("stage 1 (max min u)")?;
        Ok((x[n], x[..n].to_vec()))
    }

    /// Stage 2: the smallest upper bound `w` of `u` keeping `u >= t*`, and its `l`.
    fn max(&self, t_star: f64) -> Result<(f64, Vec<f64>), WindingError> {
        let n = self.n();
        let mut prob = Problem::new(n + 1);
        prob.q[n] = 1.0;
        self.rows(&mut prob);
        let t_lo = t_star - 1e-7 * (1.0 + t_star.abs());
        for i in 0..n {
            let (row, c) = self.u_terms(i);
            // u_i <= w  ->  D_i/dx - w <= -c
            let mut up = row.clone();
            up.push((n, -1.0));
            prob.le.push((up, -c));
            // u_i >= t*  ->  -D_i/dx <= c - t*
            let down: Vec<(usize, f64)> = row.iter().map(|&(j, v)| (j, -v)).collect();
            prob.le.push((down, c - t_lo));
        }
        let x = prob.solve("stage 2 (min max u)")?;
        Ok((x[n], x[..n].to_vec()))
    }

    /// Stage 3: the least RMS of `u - U` within `[t*, w*]`.
    fn rms(&self, t_star: f64, w_star: f64) -> Result<Vec<f64>, WindingError> {
        let (pts, n) = (self.pts, self.n());
        // Variables: l_0..l_{n-1}, u_0..u_{n-1}.
        let mut prob = Problem::new(2 * n);
        let total = pts[n].x - pts[0].x;
        let t_lo = t_star - 1e-7 * (1.0 + t_star.abs());
        let w_hi = w_star + 1e-7 * (1.0 + w_star.abs());
        for i in 0..n {
            let dx = pts[i + 1].x - pts[i].x;
            let (row, c) = self.u_terms(i);
            // u_i - D_i/dx = c
            let mut eq: Vec<(usize, f64)> = row.iter().map(|&(j, v)| (j, -v)).collect();
            eq.push((n + i, 1.0));
            prob.eq.push((eq, c));
            prob.le.push((vec![(n + i, 1.0)], w_hi));
            prob.le.push((vec![(n + i, -1.0)], -t_lo));
            // (u_i - U)^2 dx / X with U = 1 (the mean of u over a closed cycle).
            let w = dx / total;
            prob.p_diag.push((n + i, 2.0 * w));
            prob.q[n + i] = -2.0 * w;
            // Tie-break: among equally even pull speeds, the shortest free band.
            prob.q[i] = 1e-9 * w;
        }
        self.rows(&mut prob);
        let x = prob.solve("stage 3 (min rms of u - U)")?;
        Ok(x[..n].to_vec())
    }
}
