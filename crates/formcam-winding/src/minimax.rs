//! The concave-meridian problem (eqs. 5–6): the Clairaut function `C(z)` that
//! joins the two polar openings with the smallest worst-case slippage while the
//! band stays on the surface.
//!
//! Eq. 3 reads `C' = mu B(z, C)` with
//! `B = C^2/r^2 - r r'' (1 - C^2/r^2) / (1 + r'^2)` (proportional to the band's
//! normal curvature). `B = 0` exactly on the bridging limit of eq. 6, and `B > 0`
//! inside the feasible region `C_b(z) <= C <= r(z)`. So a path with
//! `max |mu| <= M` is a solution of the differential inclusion
//! `C' in [-M B, +M B]` that stays in the feasible region.
//!
//! The direct search: for a trial `M` the set of `C` reachable at `z` from the
//! start opening is an interval bounded by the two extreme trajectories
//! (`mu = +M` and `mu = -M`, clipped by `C <= r` and by the bridging limit). The
//! smallest `M` for which the far opening `C = r(z_end)` is reachable is the
//! optimum, found by bisection. The path is then built inside the intersection of
//! the forward and backward reachable tubes, staying geodesic (`C' = 0`) wherever
//! the tube allows and running at `|mu| = M` where it does not: pieces of constant
//! slippage joined to pieces that follow the boundary of the feasible region, as
//! docs/winding.md describes.

use formcam_geom::{Jet, Meridian};

use crate::ode::bisect;
use crate::{PathPoint, WindingError};

/// The optimal path of the minimax problem, sampled on a grid in `z`.
#[derive(Debug, Clone)]
pub struct MinimaxPath {
    /// Grid nodes, mm.
    pub z: Vec<f64>,
    /// Clairaut function at the nodes, mm.
    pub c: Vec<f64>,
    /// Bridging limit `C_b(z)` at the nodes (0 where the meridian is convex), mm.
    pub c_bridge: Vec<f64>,
    /// Slippage on each interval `[z_i, z_i+1]` (the last node repeats the last interval).
    pub mu: Vec<f64>,
    /// The optimal worst-case slippage `max |mu|` (the bisection's smallest feasible
    /// bound): the least worst `|mu|` of any path, an infimum where only a path
    /// grazing a turn-around would reach it.
    pub mu_max: f64,
    /// The worst-case slippage the returned path is laid at (`mu_max` and a hair
    /// of slack; up to 1 % more where the optimum is such an infimum).
    pub mu_path: f64,
    /// `z` intervals where the path lies on the bridging limit (within 1e-6 of the radius).
    pub bridging_active: Vec<(f64, f64)>,
}

/// Bridging limit `C_b(z)` of eq. 6 (0 where `r'' <= 0`).
pub fn bridging_limit(j: &Jet) -> f64 {
    if j.d2r > 0.0 {
        let q = j.r * j.r * j.r * j.d2r / (1.0 + j.dr * j.dr + j.r * j.d2r);
        q.max(0.0).sqrt()
    } else {
        0.0
    }
}

/// `B(z, C)`: `C' = mu B` (eq. 3).
pub fn b_factor(j: &Jet, c: f64) -> f64 {
    let u = c * c / (j.r * j.r);
    u - j.r * j.d2r * (1.0 - u) / (1.0 + j.dr * j.dr)
}

struct Grid {
    z: Vec<f64>,
    node: Vec<Jet>,
    mid: Vec<Jet>,
    cb: Vec<f64>,
}

impl Grid {
    fn new<M: Meridian>(m: &M, n: usize) -> Self {
        let (za, zb) = m.z_range();
        // Nodes cluster quadratically at both ends (z - z_a ~ t^2), where the path
        // turns and eq. 1 has its 1/sqrt(r - C) singularity: in t the integrand is
        // regular, so the quadrature of the turn angle converges as h^2, not h^1.5.
        // The meridian's breakpoints are added so that no interval straddles a jump
        // of r''.
        let mut z: Vec<f64> = (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64;
                if i == n {
                    zb
                } else {
                    za + (zb - za) * t * t * (3.0 - 2.0 * t)
                }
            })
            .collect();
        z.extend(m.breakpoints().into_iter().filter(|b| *b > za && *b < zb));
        z.sort_by(f64::total_cmp);
        z.dedup_by(|a, b| (*a - *b).abs() < 1e-9 * (zb - za));
        let node: Vec<Jet> = z.iter().map(|&z| m.eval(z)).collect();
        let mid: Vec<Jet> = z.windows(2).map(|w| m.eval(0.5 * (w[0] + w[1]))).collect();
        let cb = node.iter().map(bridging_limit).collect();
        Self { z, node, mid, cb }
    }

    fn n(&self) -> usize {
        self.z.len() - 1
    }

    /// One RK4 step of `dC/dt = rate B` over interval `i`, with `t = z` forwards
    /// and `t = -z` backwards (the inclusion is symmetric, so a positive `rate`
    /// always gives the upper envelope).
    fn step(&self, i: usize, c: f64, rate: f64, fwd: bool) -> f64 {
        let h = self.z[i + 1] - self.z[i];
        let (j0, j1) = if fwd {
            (&self.node[i], &self.node[i + 1])
        } else {
            (&self.node[i + 1], &self.node[i])
        };
        let jm = &self.mid[i];
        let f = |j: &Jet, c: f64| rate * b_factor(j, c).max(0.0);
        let k1 = f(j0, c);
        let k2 = f(jm, c + 0.5 * h * k1);
        let k3 = f(jm, c + 0.5 * h * k2);
        let k4 = f(j1, c + h * k3);
        c + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    }

    /// Reachable tube from one end with `|mu| <= m`; `None` when it empties.
    fn sweep(&self, m: f64, fwd: bool) -> Option<(Vec<f64>, Vec<f64>)> {
        let n = self.n();
        let mut lo = vec![0.0; n + 1];
        let mut hi = vec![0.0; n + 1];
        let start = if fwd { 0 } else { n };
        lo[start] = self.node[start].r;
        hi[start] = self.node[start].r;
        for k in 0..n {
            let (i, next) = if fwd {
                (k, k + 1)
            } else {
                (n - 1 - k, n - 1 - k)
            };
            let cur = if fwd { k } else { n - k };
            let up = self.step(i, hi[cur], m, fwd).min(self.node[next].r);
            let dn = self.step(i, lo[cur], -m, fwd).max(self.cb[next]).max(0.0);
            if dn > up + 1e-8 * self.node[next].r {
                return None;
            }
            hi[next] = up;
            lo[next] = dn.min(up);
        }
        Some((lo, hi))
    }

    fn feasible(&self, m: f64) -> bool {
        let n = self.n();
        match self.sweep(m, true) {
            Some((lo, hi)) => {
                let target = self.node[n].r;
                hi[n] >= target * (1.0 - 1e-9) && lo[n] <= target * (1.0 + 1e-9)
            }
            None => false,
        }
    }
}

/// Solves eqs. 5–6 on `nodes` intervals of `z`; `mu_limit` is the largest slippage
/// the band can hold (the search gives up beyond it).
///
/// The turn-arounds need no narrowing meridian: at `C = r` eq. 3 reads
/// `C' = mu`, and `C <= r` on leaving the start and on arriving at the end
/// needs `mu <= r'(z_start)` and `mu >= r'(z_end)`. Where the meridian widens
/// towards an end (a waisted shell whose ends flare) friction holds the turn,
/// `|mu| >= |r'|` there, and the search starts from that bound.
pub fn minimax<M: Meridian>(
    m: &M,
    nodes: usize,
    mu_limit: f64,
) -> Result<MinimaxPath, WindingError> {
    let g = Grid::new(m, nodes.max(16));
    let m_end = turn_bound(&g);
    check_turn_bound(m, &g, m_end, mu_limit)?;
    // The optimum is the smallest feasible worst-case slippage of the bisection.
    let mu_max = least_worst_mu(&g, m_end, mu_limit)?;
    let (c, m_path) = lay_path(&g, mu_max)?;
    let mut mu = interval_mu(&g, &c);
    mu.push(*mu.last().unwrap_or(&0.0));
    let bridging_active = bridging_intervals(&g, &c);
    Ok(MinimaxPath {
        z: g.z,
        c,
        c_bridge: g.cb,
        mu,
        mu_max,
        mu_path: m_path,
        bridging_active,
    })
}

/// Checks that the turn-arounds' least `|mu|` (`m_end`, [`turn_bound`]) is
/// within `mu_limit`, naming the end that needs it.
fn check_turn_bound<M: Meridian>(
    m: &M,
    g: &Grid,
    m_end: f64,
    mu_limit: f64,
) -> Result<(), WindingError> {
    if m_end > mu_limit {
        let n = g.n();
        let (za, zb) = m.z_range();
        let (z, slope) = if -g.node[0].dr >= g.node[n].dr {
            (za, g.node[0].dr)
        } else {
            (zb, g.node[n].dr)
        };
        return Err(WindingError::infeasible(
            "winding.mu_limit",
            format!(
                "the meridian widens towards its end at z = {z:.3} mm (r' = {slope:.4}), so friction \
                 must hold the turn-around there: |mu| >= {m_end:.4}, above mu_limit = {mu_limit}"
            ),
        ));
    }
    Ok(())
}

/// The least worst-case `|mu|` that reaches the far opening: a feasible bound
/// found by doubling from `m_end`, then bisection down to it (0 where the
/// geodesic reaches it).
fn least_worst_mu(g: &Grid, m_end: f64, mu_limit: f64) -> Result<f64, WindingError> {
    let feasible = |mu: f64| mu >= m_end && g.feasible(mu);
    let mut hi_m = feasible_bound(g, &feasible, m_end, mu_limit)?;
    if feasible(0.0) {
        hi_m = 0.0;
    }
    if hi_m > 0.0 {
        // To 1e-8 relative: far below the grid's own discretisation error
        // (about 1e-5 relative).
        hi_m = bisect(feasible, m_end, hi_m, 60, 1e-8);
    }
    Ok(hi_m)
}

/// A feasible worst-case `|mu|`: from `m_end` (or 1e-3) doubled until feasible,
/// `mu_limit` itself as the last try; the error that no band lies on the
/// meridian within `mu_limit`.
fn feasible_bound(
    g: &Grid,
    feasible: &impl Fn(f64) -> bool,
    m_end: f64,
    mu_limit: f64,
) -> Result<f64, WindingError> {
    let mut hi_m = 1e-3f64.min(mu_limit).max(m_end);
    while !feasible(hi_m) {
        hi_m *= 2.0;
        if hi_m > mu_limit {
            if feasible(mu_limit) {
                hi_m = mu_limit;
                break;
            }
            let concave = g.cb.iter().any(|c| *c > 0.0);
            let why = if concave {
                "needs more friction or lifts off the concave part (bridging)"
            } else {
                "needs more friction"
            };
            return Err(WindingError::infeasible(
                "winding.mu_limit",
                format!(
                    "no band can lie on this meridian with |mu| <= {mu_limit}: every path between the \
                     polar openings {why}"
                ),
            ));
        }
    }
    Ok(hi_m)
}

/// The path at the optimum `hi_m` and the worst-case slippage it is laid at.
/// It is built with a hair of slack so both tubes are non-degenerate. Where
/// that path would touch a turn-around inside the pass (C = r: a hoop, with an
/// infinite turn angle), the optimum is an infimum no path attains: the path is
/// then laid a little above it, kept off C = r (see [`build`]).
fn lay_path(g: &Grid, hi_m: f64) -> Result<(Vec<f64>, f64), WindingError> {
    for (slack, lift) in builds() {
        let m_path = hi_m * (1.0 + slack);
        let c = build(g, m_path, lift)?;
        if clear_of_turns(g, &c) && (lift.is_none() || worst_mu(g, &c) <= m_path * (1.0 + 1e-3)) {
            return Ok((c, m_path));
        }
    }
    let n = g.n();
    let c = build(g, hi_m * (1.0 + 1e-7), None)?;
    let z_touch = (1..n)
        .find(|&i| !clear_at(g, &c, i))
        .map_or(g.z[n / 2], |i| g.z[i]);
    Err(WindingError::infeasible(
        "winding.mu",
        format!(
            "the least-slippage path touches a turn-around inside the mandrel at z = {z_touch:.3} mm \
             (C = r): the band cannot run from one polar opening to the other on this meridian \
             (a meridian that neither narrows nor widens towards an end has no least slippage)"
        ),
    ))
}

/// The `z` intervals where the path `c` lies on the bridging limit (within
/// 1e-6 of the largest radius).
fn bridging_intervals(g: &Grid, c: &[f64]) -> Vec<(f64, f64)> {
    let n = g.n();
    let rmax = g.node.iter().fold(0.0f64, |a, j| a.max(j.r));
    let mut bridging_active = Vec::new();
    let mut open: Option<f64> = None;
    #[allow(clippy::needless_range_loop)]
    for i in 0..=n {
        let on = g.cb[i] > 0.0 && c[i] - g.cb[i] <= 1e-6 * rmax;
        match (on, open) {
            (true, None) => open = Some(g.z[i]),
            (false, Some(a)) => {
                bridging_active.push((a, g.z[i - 1]));
                open = None;
            }
            _ => {}
        }
    }
    if let Some(a) = open {
        bridging_active.push((a, g.z[n]));
    }
    bridging_active
}

/// The least `|mu|` the two turn-arounds need: `-r'` at the start and `r'` at the
/// end where the meridian widens towards them (0 where it narrows).
fn turn_bound(g: &Grid) -> f64 {
    (-g.node[0].dr).max(g.node[g.n()].dr).max(0.0)
}

/// The builds tried in turn: relative slack above the optimum, and where the
/// path is held ([`build`]). The first is the plain build (geodesic wherever the
/// tubes allow); the others lay the path a little above an optimum that only a
/// path grazing a turn-around would reach, nearer the optimum first.
fn builds() -> impl Iterator<Item = (f64, Option<f64>)> {
    let lowered = [1e-6, 1e-5, 1e-4, 1e-3, 1e-2]
        .into_iter()
        .flat_map(|slack| [0.5, 0.2, 0.05, 0.0].map(|lift| (slack, Some(lift))));
    std::iter::once((1e-7, None)).chain(lowered)
}

/// The path inside the forward and backward tubes at worst-case slippage `mu`:
/// each step as close to the geodesic (`C' = 0`) as the tubes and the one-step
/// reach `C' in [-mu B, mu B]` allow. With `lift = Some(t)` the geodesic is
/// capped at `t` of the way from the lowest path of the tubes up to `r`, so that
/// where the meridian narrows under the path (an end that flares) it descends
/// at `|mu|` early instead of riding `C = r` (a hoop); `t = 0` is the lowest path.
fn build(g: &Grid, mu: f64, lift: Option<f64>) -> Result<Vec<f64>, WindingError> {
    let rebuild = || {
        WindingError::infeasible(
            "winding.mu",
            "the minimax path could not be rebuilt (grid too coarse?)",
        )
    };
    let n = g.n();
    let (flo, fhi) = g.sweep(mu, true).ok_or_else(rebuild)?;
    let (blo, bhi) = g.sweep(mu, false).ok_or_else(rebuild)?;
    let mut c = vec![g.node[0].r; n + 1];
    for i in 0..n {
        let up = g.step(i, c[i], mu, true);
        let dn = g.step(i, c[i], -mu, true);
        let floor = flo[i + 1].max(blo[i + 1]);
        let lo = dn.max(floor);
        let hi = up.min(fhi[i + 1]).min(bhi[i + 1]);
        let target = match lift {
            Some(t) if i + 1 < n => c[i].min(floor + t * (g.node[i + 1].r - floor)),
            _ => c[i],
        };
        c[i + 1] = if lo <= hi {
            target.clamp(lo, hi)
        } else {
            0.5 * (lo + hi)
        };
    }
    Ok(c)
}

/// Slippage on each interval of the path: `dC` over the integral of `B`
/// (Simpson), which stays accurate where `B` vanishes at a touch of the
/// bridging limit.
fn interval_mu(g: &Grid, c: &[f64]) -> Vec<f64> {
    (0..g.n())
        .map(|i| {
            let cm = 0.5 * (c[i] + c[i + 1]);
            let bint = (b_factor(&g.node[i], c[i])
                + 4.0 * b_factor(&g.mid[i], cm)
                + b_factor(&g.node[i + 1], c[i + 1]))
                / 6.0;
            let dc = (c[i + 1] - c[i]) / (g.z[i + 1] - g.z[i]);
            if bint > 0.0 {
                dc / bint
            } else if dc == 0.0 {
                0.0
            } else {
                f64::INFINITY.copysign(dc)
            }
        })
        .collect()
}

/// Worst `|mu|` of the path.
fn worst_mu(g: &Grid, c: &[f64]) -> f64 {
    interval_mu(g, c).iter().fold(0.0, |a, m| a.max(m.abs()))
}

/// Whether node `i` keeps off the turn-around: `r - C` at least 1e-6 of the
/// distance to the nearer end (a pass leaves its turns at a finite angle).
fn clear_at(g: &Grid, c: &[f64], i: usize) -> bool {
    let (za, zb) = (g.z[0], g.z[g.n()]);
    let gap = g.node[i].r - c[i];
    gap > 0.0 && gap >= 1e-6 * (g.z[i] - za).min(zb - g.z[i])
}

/// Whether the path touches `C = r` nowhere inside the pass.
fn clear_of_turns(g: &Grid, c: &[f64]) -> bool {
    (1..g.n()).all(|i| clear_at(g, c, i))
}

impl MinimaxPath {
    /// The path as points: winding angle from `C`, turn angle and path length by
    /// quadrature of eq. 1 with the `1/sqrt(r - C)` singularity at the
    /// turn-arounds integrated exactly on each interval (linear `r - C`).
    pub fn points<M: Meridian>(&self, m: &M) -> Vec<PathPoint> {
        clairaut_points(m, &self.z, &self.c, &self.mu)
    }
}

/// Path points from a Clairaut function tabulated on a `z` grid.
pub fn clairaut_points<M: Meridian>(m: &M, z: &[f64], c: &[f64], mu: &[f64]) -> Vec<PathPoint> {
    let mut out = Vec::with_capacity(z.len());
    let (mut s, mut v) = (0.0, 0.0);
    for i in 0..z.len() {
        let j = m.eval(z[i]);
        if i > 0 {
            let jm = m.eval(0.5 * (z[i - 1] + z[i]));
            let cm = 0.5 * (c[i - 1] + c[i]);
            let g0 = (m.r(z[i - 1]) - c[i - 1]).max(0.0);
            let g1 = (j.r - c[i]).max(0.0);
            let h = z[i] - z[i - 1];
            let denom = g0.sqrt() + g1.sqrt();
            let w = if denom > 0.0 { 2.0 * h / denom } else { 0.0 };
            let q = (1.0 + jm.dr * jm.dr).sqrt();
            let rc = (jm.r + cm).sqrt();
            v += cm * q / (jm.r * rc) * w;
            s += q * jm.r / rc * w;
        }
        let alpha = (c[i] / j.r).clamp(-1.0, 1.0).asin();
        out.push(PathPoint {
            s,
            z: z[i],
            r: j.r,
            v,
            alpha,
            c: c[i],
            mu: mu.get(i).copied().unwrap_or(0.0),
        });
    }
    out
}
