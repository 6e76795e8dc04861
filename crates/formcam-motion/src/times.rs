//! Block times: eq. 17 (preliminary), eq. 18 (pairwise, docs/winding.md) and the
//! global optimum of the same problem.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SecondOrderConeT,
    SolverStatus, SupportedConeT,
};

use crate::{MotionError, SetupStage, SolverFault};

/// The most rounds of pairwise sweeps before they count as unsettled.
const PAIRWISE_ROUNDS: usize = 10_000;

/// One axis's limits (its units per second: mm/s or rad/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisLimits {
    /// Velocity limit `f_max`.
    pub v_max: f64,
    /// Velocity-jump limit `rho` between neighbouring blocks.
    pub dv_max: f64,
}

/// Block times.
#[derive(Debug, Clone, PartialEq)]
pub struct Timing {
    /// `mu_i = t*_i / t_i` in `(0, 1]`.
    pub mu: Vec<f64>,
    /// Block times, s.
    pub times: Vec<f64>,
    /// Their sum, s.
    pub total: f64,
}

impl Timing {
    fn from_mu(t_star: &[f64], mu: Vec<f64>) -> Self {
        let times: Vec<f64> = t_star.iter().zip(&mu).map(|(t, m)| t / m).collect();
        let total = times.iter().sum();
        Self { mu, times, total }
    }
}

/// The axis motions of each block (`width` per block) between the block ends
/// `ends` of the rows `values`.
pub fn deltas(values: &[f64], width: usize, ends: &[usize]) -> Vec<f64> {
    let mut out = Vec::with_capacity(ends.len().saturating_sub(1) * width);
    for w in ends.windows(2) {
        for j in 0..width {
            out.push(values[w[1] * width + j] - values[w[0] * width + j]);
        }
    }
    out
}

fn check_limits(limits: &[AxisLimits]) -> Result<(), MotionError> {
    for (i, l) in limits.iter().enumerate() {
        for (name, v) in [("v_max", l.v_max), ("dv_max", l.dv_max)] {
            if v.is_nan() || v <= 0.0 {
                return Err(MotionError::Field {
                    field: format!("axis #{}: {name}", i + 1),
                    reason: format!("must be > 0, got {v}"),
                });
            }
        }
    }
    Ok(())
}

/// What every timing method starts from: the blocks' velocity coefficients
/// `a_i^k = Delta_i^k / t*_i` (so `v_i^k = a_i^k mu_i`) and the jump limits.
struct Jumps {
    a: Vec<f64>,
    rho: Vec<f64>,
    n: usize,
    w: usize,
}

impl Jumps {
    fn new(deltas: &[f64], t_star: &[f64], limits: &[AxisLimits]) -> Result<Self, MotionError> {
        check_limits(limits)?;
        let w = limits.len().max(1);
        Ok(Self {
            a: coefficients(deltas, t_star, w),
            rho: limits.iter().map(|l| l.dv_max).collect(),
            n: t_star.len(),
            w,
        })
    }
}

/// The controller's least block time `tau` when a job gives none, s.
pub const DEFAULT_TAU_S: f64 = 0.004;

/// Eq. 17: `t*_i = max(max_k |Delta_i^k| / f_max^k, tau)`.
pub fn preliminary_times(
    deltas: &[f64],
    limits: &[AxisLimits],
    tau: f64,
) -> Result<Vec<f64>, MotionError> {
    check_limits(limits)?;
    if !(tau.is_finite() && tau > 0.0) {
        return Err(MotionError::Field {
            field: "tau".into(),
            reason: format!("the least block time must be a finite number > 0 s, got {tau}"),
        });
    }
    let w = limits.len();
    Ok(deltas
        .chunks_exact(w.max(1))
        .map(|d| {
            d.iter()
                .zip(limits)
                .map(|(d, l)| d.abs() / l.v_max)
                .fold(tau, f64::max)
        })
        .collect())
}

/// Velocity coefficients: `v_i^k = a_i^k mu_i` with `a_i^k = Delta_i^k / t*_i`.
fn coefficients(deltas: &[f64], t_star: &[f64], w: usize) -> Vec<f64> {
    deltas
        .chunks_exact(w)
        .zip(t_star)
        .flat_map(|(d, t)| d.iter().map(move |v| v / t))
        .collect()
}

/// Whether some axis reverses between blocks `i` and `j`.
fn reverses(a: &[f64], i: usize, j: usize, w: usize) -> bool {
    (0..w).any(|k| a[i * w + k] * a[j * w + k] < 0.0)
}

/// Eq. 18 for one pair: the `(mu_i, mu_j)` in `(0, c_i] x (0, c_j]` with every
/// velocity jump within `rho` that minimises `t_i / mu_i + t_j / mu_j`: a vertex
/// of the feasible polygon or the Lagrange point on one of its edges.
fn pair_optimum(
    (ti, tj): (f64, f64),
    (ai, aj): (&[f64], &[f64]),
    rho: &[f64],
    (ci, cj): (f64, f64),
) -> (f64, f64) {
    // Half-planes alpha mu_i + beta mu_j <= gamma.
    let mut lines: Vec<(f64, f64, f64)> = vec![(1.0, 0.0, ci), (0.0, 1.0, cj)];
    for k in 0..rho.len() {
        if ai[k] != 0.0 || aj[k] != 0.0 {
            lines.push((ai[k], -aj[k], rho[k]));
            lines.push((-ai[k], aj[k], rho[k]));
        }
    }
    let feasible = |u: f64, v: f64| {
        u > 0.0
            && v > 0.0
            && lines
                .iter()
                .all(|&(a, b, g)| a * u + b * v <= g + 1e-12 * (1.0 + g.abs()))
    };
    if feasible(ci, cj) {
        return (ci, cj);
    }
    let cost = |u: f64, v: f64| ti / u + tj / v;
    let mut best: Option<(f64, f64, f64)> = None;
    let mut consider = |u: f64, v: f64| {
        if feasible(u, v) {
            let c = cost(u, v);
            if best.is_none_or(|b| c < b.2) {
                best = Some((u, v, c));
            }
        }
    };
    for (p, &(a1, b1, g1)) in lines.iter().enumerate() {
        // The Lagrange point on this edge: t_i/mu_i^2 = l a, t_j/mu_j^2 = l b.
        if a1 > 0.0 && b1 > 0.0 && g1 > 0.0 {
            let s = g1 / ((a1 * ti).sqrt() + (b1 * tj).sqrt());
            consider(s * (ti / a1).sqrt(), s * (tj / b1).sqrt());
        }
        for &(a2, b2, g2) in &lines[p + 1..] {
            let det = a1 * b2 - a2 * b1;
            if det.abs() > 1e-300 {
                consider((g1 * b2 - g2 * b1) / det, (a1 * g2 - a2 * g1) / det);
            }
        }
    }
    // A polygon with no vertex in the open quadrant is thin along an axis: shrink
    // towards the origin, which is always feasible.
    best.map_or_else(
        || {
            let mut s = 0.5;
            while !feasible(ci * s, cj * s) && s > 1e-12 {
                s *= 0.5;
            }
            (ci * s, cj * s)
        },
        |b| (b.0, b.1),
    )
}

/// Eq. 18 (docs/winding.md), pairwise: pairs `(i, i+1)` (and `(n, 1)`: the program is
/// cyclic) are optimised in turn, each only slowing its two blocks, and the sweep
/// repeats until every pair keeps its velocity jumps.
pub fn pairwise(
    deltas: &[f64],
    t_star: &[f64],
    limits: &[AxisLimits],
) -> Result<Timing, MotionError> {
    let Jumps { a, rho, n, w } = Jumps::new(deltas, t_star, limits)?;
    let mut mu = vec![1.0; n];
    if n < 2 {
        return Ok(Timing::from_mu(t_star, mu));
    }
    for _ in 0..PAIRWISE_ROUNDS {
        let mut changed = false;
        for i in 0..n {
            let j = (i + 1) % n;
            let (u, v) = pair_optimum(
                (t_star[i], t_star[j]),
                (&a[i * w..(i + 1) * w], &a[j * w..(j + 1) * w]),
                &rho,
                (mu[i], mu[j]),
            );
            if u < mu[i] || v < mu[j] {
                changed = true;
                mu[i] = u.min(mu[i]);
                mu[j] = v.min(mu[j]);
            }
        }
        if !changed {
            return Ok(Timing::from_mu(t_star, mu));
        }
    }
    Err(SolverFault::PairwiseUnsettled {
        rounds: PAIRWISE_ROUNDS,
    }
    .into())
}

/// The global optimum: least `sum t*_i / mu_i` with `0 < mu <= 1` and every
/// velocity jump within its limit.
pub fn global(
    deltas: &[f64],
    t_star: &[f64],
    limits: &[AxisLimits],
) -> Result<Timing, MotionError> {
    let Jumps { a, rho, n, w } = Jumps::new(deltas, t_star, limits)?;
    if n < 2 {
        return Ok(Timing::from_mu(t_star, vec![1.0; n]));
    }
    let cap = vec![1.0; n];
    if (0..n).all(|i| !reverses(&a, i, (i + 1) % n, w)) {
        return Ok(Timing::from_mu(t_star, greatest(&a, &rho, n, w, &cap)));
    }
    windowed(&a, &rho, t_star, n, w, &cap, false)
}

/// Times a whole sequence of blocks that were timed in parts (the layers of a
/// program, each timed as its own cyclic circuit, and the moves between them):
/// the least `sum t*_i / mu_i` with `0 < mu_i <= cap_i` (`cap`: each block's
/// `mu` as timed in its part, 1 for a block not timed yet) and every velocity
/// jump within its limit, the sequence starting and ending at rest.
///
/// Within each part the caps already keep the jumps, so only blocks near the
/// joins are slowed: the greatest element below the caps (monotone sweeps),
/// then a cone program in a window round each join where an axis reverses and
/// the sweeps leave a jump broken (the windows of [`global`]).
pub fn join_times(
    deltas: &[f64],
    t_star: &[f64],
    cap: &[f64],
    limits: &[AxisLimits],
) -> Result<Timing, MotionError> {
    let w = limits.len().max(1);
    let n = t_star.len();
    if deltas.len() != n * w || cap.len() != n {
        return Err(MotionError::Field {
            field: "join_times".into(),
            reason: format!(
                "{n} blocks need {} motions and {n} caps, got {} and {}",
                n * w,
                deltas.len(),
                cap.len()
            ),
        });
    }
    if let Some(c) = cap.iter().find(|c| !(**c > 0.0 && **c <= 1.0)) {
        return Err(MotionError::Field {
            field: "cap".into(),
            reason: format!("every cap must lie in (0, 1], got {c}"),
        });
    }
    if n == 0 {
        return Ok(Timing::from_mu(t_star, Vec::new()));
    }
    // A standstill block after the last closes the sequence into a cycle: the
    // machine stands before the first block and after the last.
    let mut d = deltas.to_vec();
    d.extend(std::iter::repeat_n(0.0, w));
    let mut ts = t_star.to_vec();
    ts.push(1.0);
    let mut caps = cap.to_vec();
    caps.push(1.0);
    let Jumps { a, rho, n: m, w } = Jumps::new(&d, &ts, limits)?;
    let mut timing = windowed(&a, &rho, &ts, m, w, &caps, true)?;
    timing.mu.truncate(n);
    Ok(Timing::from_mu(t_star, timing.mu))
}

/// The global optimum as one cone program over all blocks (Clarabel): slower
/// than [`global`], which solves windows round the reversals; kept to check it.
pub fn global_by_cone(
    deltas: &[f64],
    t_star: &[f64],
    limits: &[AxisLimits],
) -> Result<Timing, MotionError> {
    let Jumps { a, rho, n, w } = Jumps::new(deltas, t_star, limits)?;
    if n < 2 {
        return Ok(Timing::from_mu(t_star, vec![1.0; n]));
    }
    let cap = vec![1.0; n];
    cone_program(
        &a,
        &rho,
        t_star,
        &(0..n).collect::<Vec<_>>(),
        None,
        n,
        w,
        &cap,
    )
}

/// With reversals: the optimum lies below the greatest element `g` of the
/// relaxation without the reversing rows, and differs from it only near the
/// reversals (the slow-down before and the speed-up after). Each reversal gets a
/// window of blocks solved as a cone program with `g` fixed outside it; a window
/// whose edges do not settle back onto `g` is doubled. Windows that would cover
/// the whole program become one cone program over all blocks.
///
/// `cap`: the greatest `mu` of each block. `only_broken`: windows only round
/// the reversals whose jump `g` breaks (the others already hold below the caps).
fn windowed(
    a: &[f64],
    rho: &[f64],
    t_star: &[f64],
    n: usize,
    w: usize,
    cap: &[f64],
    only_broken: bool,
) -> Result<Timing, MotionError> {
    let g = greatest(a, rho, n, w, cap);
    let broken = |i: usize| {
        let j = (i + 1) % n;
        (0..w).any(|k| (a[i * w + k] * g[i] - a[j * w + k] * g[j]).abs() > rho[k])
    };
    let pairs: Vec<usize> = (0..n)
        .filter(|&i| reverses(a, i, (i + 1) % n, w) && (!only_broken || broken(i)))
        .collect();
    if pairs.is_empty() {
        let mut mu = g;
        restore_feasibility(&mut mu, a, rho, n, w);
        return Ok(Timing::from_mu(t_star, mu));
    }
    let mut half = 16usize;
    loop {
        if 2 * half * pairs.len() >= n {
            return cone_program(a, rho, t_star, &(0..n).collect::<Vec<_>>(), None, n, w, cap);
        }
        // Windows [i + 1 - half, i + half] around each reversal, merged.
        let mut spans: Vec<(usize, usize)> = Vec::new();
        for &i in &pairs {
            let start = i + n + 1 - half; // shifted by n: no underflow
            let end = start + 2 * half - 1;
            match spans.last_mut() {
                Some(last) if start <= last.1 + 1 => last.1 = last.1.max(end),
                _ => spans.push((start, end)),
            }
        }
        // The last window may wrap onto the first.
        if spans.len() >= 2
            && let (Some(&first), Some(last)) = (spans.first(), spans.last())
            && last.1 + 1 >= first.0 + n
        {
            let merged = (last.0, first.1 + n);
            spans.pop();
            spans[0] = merged;
        }
        if spans.iter().map(|s| s.1 - s.0 + 1).sum::<usize>() >= n {
            half = n;
            continue;
        }
        let mut mu = g.clone();
        let mut settled = true;
        for &(s, e) in &spans {
            let idx: Vec<usize> = (s..=e).map(|i| i % n).collect();
            let left = g[(s + n - 1) % n];
            let right = g[(e + 1) % n];
            let sol = cone_program(a, rho, t_star, &idx, Some((left, right)), n, w, cap)?;
            let edge = |k: usize| (sol.mu[k] - g[idx[k]]).abs() <= 1e-6 * g[idx[k]];
            if !edge(0) || !edge(idx.len() - 1) {
                settled = false;
                break;
            }
            for (k, &i) in idx.iter().enumerate() {
                mu[i] = sol.mu[k];
            }
        }
        if settled {
            restore_feasibility(&mut mu, a, rho, n, w);
            return Ok(Timing::from_mu(t_star, mu));
        }
        half *= 2;
    }
}

/// No axis reverses between neighbours: every jump constraint bounds each `mu`
/// from above by an increasing function of its neighbour's, so the feasible set
/// has a greatest element — the optimum of any decreasing cost. Forward and
/// backward sweeps from `mu = 1` reach it.
///
/// Where an axis does reverse, its jump rows are left out: the result is then
/// the greatest element of that relaxation, above every feasible `mu`.
///
/// `cap`: where the sweeps start, each block's greatest `mu`.
fn greatest(a: &[f64], rho: &[f64], n: usize, w: usize, cap: &[f64]) -> Vec<f64> {
    let mut mu = cap.to_vec();
    // The bound on mu_i from its neighbour j.
    let bound = |mu: &[f64], i: usize, j: usize| {
        let mut m = 1.0f64;
        for k in 0..w {
            if a[i * w + k] * a[j * w + k] < 0.0 {
                continue;
            }
            let (ai, aj) = (a[i * w + k].abs(), a[j * w + k].abs());
            if ai > 0.0 {
                m = m.min((rho[k] + aj * mu[j]) / ai);
            }
        }
        m
    };
    for _ in 0..100_000 {
        let mut changed = false;
        for i in (0..n).chain((0..n).rev()) {
            let prev = (i + n - 1) % n;
            let next = (i + 1) % n;
            let m = bound(&mu, i, prev).min(bound(&mu, i, next));
            if m < mu[i] * (1.0 - 1e-15) {
                mu[i] = m;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    mu
}

/// Sparse rows of a cone program: triplets and right-hand sides.
#[derive(Default)]
struct Rows {
    ii: Vec<usize>,
    jj: Vec<usize>,
    vv: Vec<f64>,
    b: Vec<f64>,
    row: usize,
}

impl Rows {
    fn put(&mut self, r: usize, c: usize, v: f64) {
        self.ii.push(r);
        self.jj.push(c);
        self.vv.push(v);
    }

    /// `|ai mu_i - aj mu_j| <= rho` as two rows; a side with no column is fixed
    /// at its value. Rows that cannot bind with `mu <= 1` are left out.
    fn jump(
        &mut self,
        (ci, ai, vi): (Option<usize>, f64, f64),
        (cj, aj, vj): (Option<usize>, f64, f64),
        rho: f64,
    ) {
        let most = if ai * aj < 0.0 {
            ai.abs() + aj.abs()
        } else {
            ai.abs().max(aj.abs())
        };
        if most <= rho {
            return;
        }
        for sign in [1.0, -1.0] {
            let mut rhs = rho;
            match ci {
                Some(c) => self.put(self.row, c, sign * ai),
                None => rhs -= sign * ai * vi,
            }
            match cj {
                Some(c) => self.put(self.row, c, -sign * aj),
                None => rhs += sign * aj * vj,
            }
            self.b.push(rhs);
            self.row += 1;
        }
    }
}

/// A cone program (Clarabel) over the consecutive blocks `idx`: variables
/// `mu_k, s_k`; minimise `sum s_k` with `s_k mu_k >= t*_k` (a rotated cone),
/// `mu_k <= 1` and the jump rows between neighbours. `fixed`: the `mu` of the
/// blocks just before and after `idx`, which stay; `None` when `idx` is the whole
/// cyclic program. `cap`: each block's greatest `mu` (by block index).
#[allow(clippy::too_many_arguments)]
fn cone_program(
    a: &[f64],
    rho: &[f64],
    t_star: &[f64],
    idx: &[usize],
    fixed: Option<(f64, f64)>,
    n: usize,
    w: usize,
    cap: &[f64],
) -> Result<Timing, MotionError> {
    let m = idx.len();
    // Columns: mu_0..mu_{m-1}, s_0..s_{m-1}.
    let mut r = Rows::default();
    for (k, &i) in idx.iter().enumerate() {
        // mu_k <= cap (mu_k > 0 follows from the cone).
        r.put(r.row, k, 1.0);
        r.b.push(cap[i]);
        r.row += 1;
    }
    for k in 0..m {
        let i = idx[k];
        let (cj, j, vj) = match (k + 1 < m, fixed) {
            (true, _) => (Some(k + 1), idx[k + 1], 0.0),
            (false, None) => (Some(0), idx[0], 0.0),
            (false, Some((_, right))) => (None, (i + 1) % n, right),
        };
        for q in 0..w {
            r.jump((Some(k), a[i * w + q], 0.0), (cj, a[j * w + q], vj), rho[q]);
        }
        if k == 0
            && let Some((left, _)) = fixed
        {
            let o = (i + n - 1) % n;
            for q in 0..w {
                r.jump(
                    (None, a[o * w + q], left),
                    (Some(0), a[i * w + q], 0.0),
                    rho[q],
                );
            }
        }
    }
    let linear = r.row;
    // Rotated cones: (s + mu, s - mu, 2 sqrt(t*)) in the second-order cone.
    for (k, &i) in idx.iter().enumerate() {
        let row = r.row;
        r.put(row, m + k, -1.0);
        r.put(row, k, -1.0);
        r.put(row + 1, m + k, -1.0);
        r.put(row + 1, k, 1.0);
        r.b.extend([0.0, 0.0, 2.0 * t_star[i].sqrt()]);
        r.row += 3;
    }
    let Rows { ii, jj, vv, b, row } = r;
    let amat = CscMatrix::new_from_triplets(row, 2 * m, ii, jj, vv);
    let p = CscMatrix::new_from_triplets(2 * m, 2 * m, vec![], vec![], vec![]);
    let mut q = vec![0.0; 2 * m];
    for v in &mut q[m..] {
        *v = 1.0;
    }
    let mut cones: Vec<SupportedConeT<f64>> = vec![NonnegativeConeT(linear)];
    cones.extend((0..m).map(|_| SecondOrderConeT(3)));
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(200)
        .build()
        .map_err(|e| refused(SetupStage::Settings, e))?;
    let mut solver = DefaultSolver::new(&p, &q, &amat, &b, &cones, settings)
        .map_err(|e| refused(SetupStage::Setup, e))?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {
            let mut mu: Vec<f64> = solver.solution.x[..m]
                .iter()
                .zip(idx)
                .map(|(v, &i)| v.clamp(1e-12, cap[i]))
                .collect();
            if fixed.is_none() {
                // Interior-point solutions sit a hair inside or outside the jump
                // rows: scale down to keep every row exactly.
                restore_feasibility(&mut mu, a, rho, n, w);
            }
            let ts: Vec<f64> = idx.iter().map(|&i| t_star[i]).collect();
            Ok(Timing::from_mu(&ts, mu))
        }
        other => Err(SolverFault::Stopped(other).into()),
    }
}

/// Clarabel's refusal of its settings or problem.
fn refused(stage: SetupStage, e: impl std::fmt::Debug) -> MotionError {
    SolverFault::Refused {
        stage,
        detail: format!("{e:?}"),
    }
    .into()
}

/// Lowers `mu` where a jump row is broken by rounding, until none is, by no more
/// than the breach itself.
///
/// A row whose axis keeps its direction lowers only the faster block, to the
/// slower one's velocity plus the jump: the correction then travels along a
/// chain of binding rows as the same small velocity. (Scaling both blocks of the
/// row instead lowers the slower one, which breaks its other row by `|a mu| /
/// rho` times as much, and so on round the chain: a breach of one ulp grew into
/// blocks timed at 30x their least time.) A row across a reversal scales both
/// blocks; lowering never breaks such a row again.
fn restore_feasibility(mu: &mut [f64], a: &[f64], rho: &[f64], n: usize, w: usize) {
    // Aim a hair inside each row, so that rounding cannot leave it broken.
    const INSIDE: f64 = 1.0 - 1e-12;
    let fix = |mu: &mut [f64], i: usize, j: usize| {
        let mut changed = false;
        for k in 0..w {
            let (ai, aj) = (a[i * w + k], a[j * w + k]);
            if (ai * mu[i] - aj * mu[j]).abs() <= rho[k] {
                continue;
            }
            changed = true;
            if ai * aj < 0.0 {
                let s = rho[k] / (ai.abs() * mu[i] + aj.abs() * mu[j]) * INSIDE;
                mu[i] *= s;
                mu[j] *= s;
            } else if (ai * mu[i]).abs() > (aj * mu[j]).abs() {
                mu[i] = (rho[k] * INSIDE + aj.abs() * mu[j]) / ai.abs();
            } else {
                mu[j] = (rho[k] * INSIDE + ai.abs() * mu[i]) / aj.abs();
            }
        }
        changed
    };
    // Forward and backward sweeps: a correction travels either way.
    for _ in 0..10_000 {
        let mut changed = false;
        for i in (0..n).chain((0..n).rev()) {
            changed |= fix(mu, i, (i + 1) % n);
        }
        if !changed {
            return;
        }
    }
}

/// Broken limits of the block times `times`: `(block, axis, excess)` for every
/// velocity above `v_max` and every jump above `dv_max` (cyclic), with a relative
/// tolerance of 1e-9.
pub fn check_timing(
    deltas: &[f64],
    times: &[f64],
    limits: &[AxisLimits],
) -> Vec<(usize, usize, f64)> {
    let w = limits.len().max(1);
    let n = times.len();
    let mut out = Vec::new();
    let v = |i: usize, k: usize| deltas[i * w + k] / times[i];
    for i in 0..n {
        for (k, l) in limits.iter().enumerate() {
            let vi = v(i, k).abs();
            if vi > l.v_max * (1.0 + 1e-9) {
                out.push((i, k, vi - l.v_max));
            }
            if n >= 2 {
                let jump = (v(i, k) - v((i + 1) % n, k)).abs();
                if jump > l.dv_max * (1.0 + 1e-9) {
                    out.push((i, k, jump - l.dv_max));
                }
            }
        }
    }
    out
}
