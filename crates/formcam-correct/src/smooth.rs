//! Separating measurement noise from the warp: a penalised least-squares fit
//! of the grid deviations,
//!
//! ```text
//! minimise  sum |m - d|^2 + lambda * sum (|m_uu|^2 + 2 |m_uv|^2 + |m_vv|^2)
//! ```
//!
//! (second differences over the grid, a discrete thin plate), with `lambda`
//! chosen by the discrepancy principle (bisection on `log lambda`): the mean
//! squared residual equals the stated noise variance. Each `lambda`'s
//! system `(I + lambda L) m = d` is solved by conjugate gradients
//! preconditioned by a multigrid V-cycle (cubic prolongation, Galerkin
//! coarse levels, symmetric Gauss–Seidel, a dense Cholesky factor on the
//! coarsest level), warm-started from the previous `lambda`, to an error
//! below 1e-7 of the noise level (a fit that only steers the bisection stops
//! as soon as its side of the target is sure): the time grows a little
//! faster than the number of points (the weight chosen grows with the
//! density of the points, and with it the iterations).
//! Where the report gives normals, the scalar normal deviation is smoothed;
//! otherwise each component.

use crate::Grid;
use crate::vec3::{V3, dot, scale};

/// What the smoothing did.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Smoothing {
    /// The stated noise level (standard deviation, mm).
    pub noise_mm: f64,
    /// The chosen weight of the roughness penalty.
    pub lambda: f64,
    /// RMS of the removed part (the estimated noise), mm.
    pub removed_rms_mm: f64,
    /// The data were smoother than the noise level says: the smoothest
    /// (bilinear-plane) fit was taken.
    pub saturated: bool,
}

/// Below this many unknowns a level is solved directly (dense Cholesky).
const COARSEST: usize = 200;
/// Gauss–Seidel sweeps before and after the coarse-grid correction.
const SWEEPS: usize = 2;
/// A guard on the iterations of one solve (a V-cycle preconditioned solve
/// takes a dozen or two whatever the grid's size).
const MAX_ITERATIONS: usize = 500;

/// A sparse matrix in compressed rows.
#[derive(Debug, Clone, Default)]
struct Csr {
    ptr: Vec<usize>,
    col: Vec<u32>,
    val: Vec<f64>,
}

impl Csr {
    fn row(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let r = self.ptr[i]..self.ptr[i + 1];
        self.col[r.clone()]
            .iter()
            .zip(&self.val[r])
            .map(|(&c, &v)| (c as usize, v))
    }

    fn rows(&self) -> usize {
        self.ptr.len() - 1
    }

    /// The transpose, with `cols` columns in `self`.
    fn transpose(&self, cols: usize) -> Self {
        let mut count = vec![0usize; cols + 1];
        for &c in &self.col {
            count[c as usize + 1] += 1;
        }
        for k in 0..cols {
            count[k + 1] += count[k];
        }
        let mut next = count.clone();
        let mut col = vec![0u32; self.col.len()];
        let mut val = vec![0.0; self.val.len()];
        for i in 0..self.rows() {
            for (c, v) in self.row(i) {
                col[next[c]] = i as u32;
                val[next[c]] = v;
                next[c] += 1;
            }
        }
        Self {
            ptr: count,
            col,
            val,
        }
    }
}

/// One level of the hierarchy: `A = M + lambda L` on a common pattern.
#[derive(Debug, Clone)]
struct Level {
    ptr: Vec<usize>,
    col: Vec<u32>,
    /// `M` (`None`: the identity, on the finest level).
    mass: Option<Vec<f64>>,
    /// `L`.
    rough: Vec<f64>,
    /// Where each row's diagonal entry is.
    diag: Vec<usize>,
}

impl Level {
    fn n(&self) -> usize {
        self.ptr.len() - 1
    }

    /// Entry `k` of `M + lambda L`, in row `i`.
    #[inline(always)]
    fn entry(&self, i: usize, k: usize, lambda: f64) -> f64 {
        self.mass_at(i, k) + lambda * self.rough[k]
    }

    /// Entry `k` of `M`, in row `i` (no mass given: the identity).
    #[inline(always)]
    fn mass_at(&self, i: usize, k: usize) -> f64 {
        match &self.mass {
            Some(m) => m[k],
            None => f64::from(u8::from(self.col[k] as usize == i)),
        }
    }
}

/// The thin-plate penalty `L` on an `nu x nv` grid (point `(i, j)` at
/// `j * nu + i`), assembled row by row: the `u u` and `v v` second
/// differences and twice the mixed one, each row coupling the point with
/// its neighbours up to two apart along a line and one apart diagonally.
fn finest(nu: usize, nv: usize) -> Level {
    let n = nu * nv;
    let mut ptr = Vec::with_capacity(n + 1);
    let mut col: Vec<u32> = Vec::with_capacity(13 * n);
    let mut rough = Vec::with_capacity(13 * n);
    let mut diag = Vec::with_capacity(n);
    ptr.push(0);
    let second = [1.0, -2.0, 1.0];
    for j in 0..nv {
        for i in 0..nu {
            // A 5 x 5 accumulator round the row's point, offsets -2..=2.
            let mut acc = [[0.0f64; 5]; 5];
            let mut used = [[false; 5]; 5];
            let mut add = |di: isize, dj: isize, v: f64| {
                let (a, b) = ((di + 2) as usize, (dj + 2) as usize);
                acc[b][a] += v;
                used[b][a] = true;
            };
            // Second differences along u centred at c = i - 1, i, i + 1.
            for c in i.saturating_sub(1)..=(i + 1) {
                if c == 0 || c + 1 >= nu {
                    continue;
                }
                let own = second[i + 1 - c];
                for (q, w) in second.iter().enumerate() {
                    add((c + q) as isize - 1 - i as isize, 0, own * w);
                }
            }
            for c in j.saturating_sub(1)..=(j + 1) {
                if c == 0 || c + 1 >= nv {
                    continue;
                }
                let own = second[j + 1 - c];
                for (q, w) in second.iter().enumerate() {
                    add(0, (c + q) as isize - 1 - j as isize, own * w);
                }
            }
            // Mixed differences over the cells with corner (a, b) round (i, j).
            for b in j.saturating_sub(1)..=j {
                for a in i.saturating_sub(1)..=i {
                    if a + 1 >= nu || b + 1 >= nv {
                        continue;
                    }
                    let sign = |x: usize, y: usize| if (x - a) == (y - b) { 1.0 } else { -1.0 };
                    let own = sign(i, j);
                    for y in b..=b + 1 {
                        for x in a..=a + 1 {
                            add(
                                x as isize - i as isize,
                                y as isize - j as isize,
                                2.0 * own * sign(x, y),
                            );
                        }
                    }
                }
            }
            for (b, (row, flags)) in acc.iter().zip(&used).enumerate() {
                for (a, (&v, &u)) in row.iter().zip(flags).enumerate() {
                    let here = a == 2 && b == 2;
                    if u || here {
                        if here {
                            diag.push(col.len());
                        }
                        let (x, y) = (i + a - 2, j + b - 2);
                        col.push((y * nu + x) as u32);
                        rough.push(v);
                    }
                }
            }
            ptr.push(col.len());
        }
    }
    Level {
        ptr,
        col,
        mass: None,
        rough,
        diag,
    }
}

/// Coarse points of a line of `n`: every other one and the last; all of
/// them when `n <= 2`. Returns the count and, per fine point, its
/// interpolation from coarse points `[(index, weight)]`: cubic between
/// coarse points (`(-1, 9, 9, -1) / 16`), quadratic next to the ends,
/// linear on lines too short for either. The penalty is of fourth order: an
/// interpolation of order 4 (and its transpose for the restriction) keeps
/// the V-cycle's convergence from degrading with the grid's size and the
/// weight, which bilinear interpolation does not.
fn coarsen_line(n: usize) -> (usize, Vec<Vec<(usize, f64)>>) {
    if n <= 2 {
        return (n, (0..n).map(|i| vec![(i, 1.0)]).collect());
    }
    let coarse_of = |i: usize| {
        if i == n - 1 {
            (n - 1).div_ceil(2)
        } else {
            i / 2
        }
    };
    let weights = (0..n)
        .map(|i| {
            if i % 2 == 0 || i == n - 1 {
                vec![(coarse_of(i), 1.0)]
            } else if i >= 3 && i + 3 < n {
                vec![
                    (coarse_of(i - 3), -1.0 / 16.0),
                    (coarse_of(i - 1), 9.0 / 16.0),
                    (coarse_of(i + 1), 9.0 / 16.0),
                    (coarse_of(i + 3), -1.0 / 16.0),
                ]
            } else if i + 3 < n {
                vec![
                    (coarse_of(i - 1), 3.0 / 8.0),
                    (coarse_of(i + 1), 3.0 / 4.0),
                    (coarse_of(i + 3), -1.0 / 8.0),
                ]
            } else if i >= 3 {
                vec![
                    (coarse_of(i - 3), -1.0 / 8.0),
                    (coarse_of(i - 1), 3.0 / 4.0),
                    (coarse_of(i + 1), 3.0 / 8.0),
                ]
            } else {
                vec![(coarse_of(i - 1), 0.5), (coarse_of(i + 1), 0.5)]
            }
        })
        .collect();
    (coarse_of(n - 1) + 1, weights)
}

/// The prolongation from the coarse grid to an `nu x nv` grid (the tensor
/// product of the lines'), and the coarse grid's size.
fn prolongation(nu: usize, nv: usize) -> (Csr, usize, usize) {
    let (cu, wu) = coarsen_line(nu);
    let (cv, wv) = coarsen_line(nv);
    let mut p = Csr {
        ptr: vec![0],
        ..Csr::default()
    };
    for b in &wv {
        for a in &wu {
            for &(y, wy) in b {
                for &(x, wx) in a {
                    p.col.push((y * cu + x) as u32);
                    p.val.push(wx * wy);
                }
            }
            p.ptr.push(p.col.len());
        }
    }
    (p, cu, cv)
}

/// The Galerkin coarse level `P^T (M + lambda L) P`, both parts.
fn galerkin(fine: &Level, p: &Csr, pt: &Csr) -> Level {
    let nc = pt.rows();
    let mut ptr = vec![0];
    let (mut col, mut mass, mut rough, mut diag) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut slot = vec![usize::MAX; nc];
    let mut touched: Vec<usize> = Vec::new();
    let (mut am, mut al) = (vec![0.0; nc], vec![0.0; nc]);
    for big in 0..nc {
        for (i, wi) in pt.row(big) {
            for k in fine.ptr[i]..fine.ptr[i + 1] {
                let j = fine.col[k] as usize;
                let m = fine.mass_at(i, k);
                let l = fine.rough[k];
                for (c, wj) in p.row(j) {
                    if slot[c] == usize::MAX {
                        slot[c] = touched.len();
                        touched.push(c);
                        am[c] = 0.0;
                        al[c] = 0.0;
                    }
                    am[c] += wi * m * wj;
                    al[c] += wi * l * wj;
                }
            }
        }
        touched.sort_unstable();
        for &c in &touched {
            if c == big {
                diag.push(col.len());
            }
            col.push(c as u32);
            mass.push(am[c]);
            rough.push(al[c]);
            slot[c] = usize::MAX;
        }
        touched.clear();
        ptr.push(col.len());
    }
    Level {
        ptr,
        col,
        mass: Some(mass),
        rough,
        diag,
    }
}

/// The multigrid hierarchy of `I + lambda L` on an `nu x nv` grid, for any
/// `lambda`: each level holds `M` and `L` apart.
#[derive(Debug, Clone)]
struct Hierarchy {
    levels: Vec<Level>,
    /// `prolong[k]`: from level `k + 1` to level `k`; `restrict[k]` its
    /// transpose.
    prolong: Vec<Csr>,
    restrict: Vec<Csr>,
}

impl Hierarchy {
    fn new(nu: usize, nv: usize) -> Self {
        let mut levels = vec![finest(nu, nv)];
        let (mut prolong, mut restrict) = (Vec::new(), Vec::new());
        let (mut u, mut v) = (nu, nv);
        loop {
            let last = &levels[levels.len() - 1];
            if last.n() <= COARSEST {
                break;
            }
            let (p, cu, cv) = prolongation(u, v);
            if cu * cv == u * v {
                break;
            }
            let pt = p.transpose(cu * cv);
            let coarse = galerkin(last, &p, &pt);
            levels.push(coarse);
            prolong.push(p);
            restrict.push(pt);
            (u, v) = (cu, cv);
        }
        Self {
            levels,
            prolong,
            restrict,
        }
    }
}

/// `I + lambda L` ready to solve: the values of every level and the
/// coarsest level's Cholesky factor.
struct Operator<'h> {
    h: &'h Hierarchy,
    /// `M + lambda L` per level, on the level's pattern.
    vals: Vec<Vec<f64>>,
    /// The diagonal per level.
    diag: Vec<Vec<f64>>,
    /// Lower triangle, row-major, of the coarsest level.
    chol: Vec<f64>,
}

/// When a solve may stop short of its tolerance: `stop(m, bound)` with the
/// iterate and a bound on the 2-norm of its error.
type Stop<'a> = &'a dyn Fn(&[f64], f64) -> bool;

impl<'h> Operator<'h> {
    fn new(h: &'h Hierarchy, lambda: f64) -> Self {
        let vals: Vec<Vec<f64>> = h
            .levels
            .iter()
            .map(|l| {
                (0..l.n())
                    .flat_map(|i| (l.ptr[i]..l.ptr[i + 1]).map(move |k| (i, k)))
                    .map(|(i, k)| l.entry(i, k, lambda))
                    .collect()
            })
            .collect();
        let diag = h
            .levels
            .iter()
            .zip(&vals)
            .map(|(l, v)| l.diag.iter().map(|&k| v[k]).collect())
            .collect();
        let k = h.levels.len() - 1;
        let (last, v) = (&h.levels[k], &vals[k]);
        let n = last.n();
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            for k in last.ptr[i]..last.ptr[i + 1] {
                a[i * n + last.col[k] as usize] = v[k];
            }
        }
        // Cholesky in place (the matrix is I + lambda L projected: SPD).
        for j in 0..n {
            let mut d = a[j * n + j];
            for k in 0..j {
                d -= a[j * n + k] * a[j * n + k];
            }
            let d = d.max(f64::MIN_POSITIVE).sqrt();
            a[j * n + j] = d;
            for i in j + 1..n {
                let mut s = a[i * n + j];
                for k in 0..j {
                    s -= a[i * n + k] * a[j * n + k];
                }
                a[i * n + j] = s / d;
            }
        }
        Self {
            h,
            vals,
            diag,
            chol: a,
        }
    }

    /// Row `i` of level `k` times `x`.
    #[inline(always)]
    fn row_times(&self, k: usize, i: usize, x: &[f64]) -> f64 {
        let l = &self.h.levels[k];
        let (from, to) = (l.ptr[i], l.ptr[i + 1]);
        l.col[from..to]
            .iter()
            .zip(&self.vals[k][from..to])
            .map(|(&c, &a)| a * x[c as usize])
            .sum()
    }

    /// `y = A x` on the finest level.
    fn apply(&self, x: &[f64], y: &mut [f64]) {
        for (i, y) in y.iter_mut().enumerate() {
            *y = self.row_times(0, i, x);
        }
    }

    /// One Gauss–Seidel sweep on level `k`, forward or backward.
    fn sweep(&self, k: usize, b: &[f64], x: &mut [f64], forward: bool) {
        let d = &self.diag[k];
        let n = b.len();
        for step in 0..n {
            let i = if forward { step } else { n - 1 - step };
            let r = b[i] - self.row_times(k, i, x);
            x[i] += r / d[i];
        }
    }

    /// `x = B b`: one V-cycle from zero (symmetric: forward sweeps before,
    /// backward sweeps after the coarse correction), a preconditioner for
    /// conjugate gradients.
    fn vcycle(&self, k: usize, b: &[f64], x: &mut [f64]) {
        let h = self.h;
        x.fill(0.0);
        if k + 1 == h.levels.len() {
            let n = b.len();
            let a = &self.chol;
            for i in 0..n {
                let mut s = b[i];
                for j in 0..i {
                    s -= a[i * n + j] * x[j];
                }
                x[i] = s / a[i * n + i];
            }
            for i in (0..n).rev() {
                let mut s = x[i];
                for j in i + 1..n {
                    s -= a[j * n + i] * x[j];
                }
                x[i] = s / a[i * n + i];
            }
            return;
        }
        for _ in 0..SWEEPS {
            self.sweep(k, b, x, true);
        }
        let r: Vec<f64> = (0..b.len())
            .map(|i| b[i] - self.row_times(k, i, x))
            .collect();
        let restrict = &h.restrict[k];
        let bc: Vec<f64> = (0..restrict.rows())
            .map(|c| restrict.row(c).map(|(i, w)| w * r[i]).sum())
            .collect();
        let mut xc = vec![0.0; bc.len()];
        self.vcycle(k + 1, &bc, &mut xc);
        for (i, x) in x.iter_mut().enumerate() {
            *x += h.prolong[k].row(i).map(|(c, w)| w * xc[c]).sum::<f64>();
        }
        for _ in 0..SWEEPS {
            self.sweep(k, b, x, false);
        }
    }

    /// Solves `A m_f = d_f` for every field `f` (the fields stacked, each
    /// `n` long: one block-diagonal system) from `m`, by conjugate gradients
    /// preconditioned by a V-cycle per field, until the error's bound
    /// `2 sqrt(r . B r)` is below `tol`, or `stop` says the iterate is good
    /// enough. (`r . A^-1 r` is the squared energy norm of the error, and as
    /// `A >= I` it bounds the squared 2-norm; the V-cycle `B` is close to
    /// `A^-1`, `B A` having its eigenvalues in `(0, 1]` and mostly near 1,
    /// and the factor 2 covers the rest.)
    /// Returns the iterations taken.
    fn solve(&self, d: &[f64], m: &mut [f64], tol: f64, stop: Stop<'_>) -> usize {
        let n = self.h.levels[0].n();
        let len = d.len();
        let apply = |x: &[f64], y: &mut [f64]| {
            for (x, y) in x.chunks(n).zip(y.chunks_mut(n)) {
                self.apply(x, y);
            }
        };
        let precondition = |r: &[f64], z: &mut [f64]| {
            for (r, z) in r.chunks(n).zip(z.chunks_mut(n)) {
                self.vcycle(0, r, z);
            }
        };
        let mut r = vec![0.0; len];
        apply(m, &mut r);
        for (r, d) in r.iter_mut().zip(d) {
            *r = d - *r;
        }
        let mut z = vec![0.0; len];
        precondition(&r, &mut z);
        let mut p = z.clone();
        let mut rz: f64 = r.iter().zip(&z).map(|(a, b)| a * b).sum();
        let mut q = vec![0.0; len];
        for it in 0..MAX_ITERATIONS {
            let bound = 2.0 * rz.max(0.0).sqrt();
            if !rz.is_finite() || bound <= tol || stop(m, bound) {
                return it;
            }
            apply(&p, &mut q);
            let pq: f64 = p.iter().zip(&q).map(|(a, b)| a * b).sum();
            if pq.is_nan() || pq <= 0.0 {
                return it;
            }
            let alpha = rz / pq;
            for k in 0..len {
                m[k] += alpha * p[k];
                r[k] -= alpha * q[k];
            }
            precondition(&r, &mut z);
            let rz_new: f64 = r.iter().zip(&z).map(|(a, b)| a * b).sum();
            let beta = rz_new / rz;
            rz = rz_new;
            for k in 0..len {
                p[k] = z[k] + beta * p[k];
            }
        }
        MAX_ITERATIONS
    }
}

/// Smooths the fields `d` (each of `nu * nv` values) with one `lambda` chosen
/// so the mean squared residual over all fields is `noise^2` (per value):
/// bisection on `log10 lambda` in `[-8, 10]` to 1e-3. A fit whose only use
/// is the bisection's next step stops as soon as its residual is surely on
/// one side of the target (the error bound of the solve against the
/// distance to it); the fit returned is solved to 1e-7 of the noise level.
fn fit(fields: &[Vec<f64>], nu: usize, nv: usize, noise: f64) -> (Vec<Vec<f64>>, f64, bool) {
    let count = (fields.len() * nu * nv) as f64;
    let hierarchy = Hierarchy::new(nu, nv);
    let d: Vec<f64> = fields.concat();
    let tol = 1e-7 * noise;
    let target = noise * noise;
    // The root of the target's sum of squares.
    let goal = (target * count).sqrt();
    let residual = |m: &[f64]| {
        d.iter()
            .zip(m)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt()
    };
    // |(|d - m|) - (|d - m*|)| <= |m - m*| <= bound: the side is sure when
    // the distance to the goal exceeds the bound.
    let decided = |m: &[f64], bound: f64| (residual(m) - goal).abs() > 2.0 * bound;
    let precise = |_: &[f64], _: f64| false;
    let run = |lambda: f64, m: &mut Vec<f64>, stop: Stop<'_>| {
        let op = Operator::new(&hierarchy, lambda);
        op.solve(&d, m, tol, stop);
        residual(m).powi(2) / count
    };
    let split = |m: Vec<f64>| -> Vec<Vec<f64>> { m.chunks(nu * nv).map(<[f64]>::to_vec).collect() };
    let (mut lo, mut hi) = (-8.0f64, 10.0f64);
    let mut m = d.clone();
    if run(10f64.powf(hi), &mut m, &decided) <= target {
        run(10f64.powf(hi), &mut m, &precise);
        return (split(m), 10f64.powf(hi), true);
    }
    let mut lambda = 10f64.powf(hi);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        lambda = 10f64.powf(mid);
        // The step after which the bisection ends is the fit returned.
        let last = 0.5 * (hi - lo) < 1e-3;
        let ms = run(lambda, &mut m, if last { &precise } else { &decided });
        if ms > target {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi - lo < 1e-3 {
            break;
        }
    }
    (split(m), lambda, false)
}

/// Replaces the grid's deviations by their smoothed values, for measurement
/// noise of standard deviation `noise_mm` (along the normal where the grid
/// has normals, else per component). `noise_mm = 0` leaves them as they are.
pub fn smooth(grid: &mut Grid, noise_mm: f64) -> Smoothing {
    let (nu, nv) = (grid.nu, grid.nv);
    if noise_mm <= 0.0 || nu < 2 || nv < 2 {
        return Smoothing {
            noise_mm,
            lambda: 0.0,
            removed_rms_mm: 0.0,
            saturated: false,
        };
    }
    let before = grid.deviation.clone();
    let (fits, lambda, saturated) = match &grid.normal {
        Some(normals) => {
            let d: Vec<f64> = grid
                .deviation
                .iter()
                .zip(normals)
                .map(|(d, n)| dot(*d, *n))
                .collect();
            let (f, l, s) = fit(&[d], nu, nv, noise_mm);
            for ((dev, n), v) in grid.deviation.iter_mut().zip(normals).zip(&f[0]) {
                *dev = scale(*n, *v);
            }
            (f, l, s)
        }
        None => {
            let comps: Vec<Vec<f64>> = (0..3)
                .map(|c| grid.deviation.iter().map(|d| d[c]).collect())
                .collect();
            let (f, l, s) = fit(&comps, nu, nv, noise_mm);
            for (k, dev) in grid.deviation.iter_mut().enumerate() {
                *dev = [f[0][k], f[1][k], f[2][k]];
            }
            (f, l, s)
        }
    };
    let _ = fits;
    let removed: f64 = before
        .iter()
        .zip(&grid.deviation)
        .map(|(a, b): (&V3, &V3)| {
            let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            dot(d, d)
        })
        .sum::<f64>()
        / before.len() as f64;
    Smoothing {
        noise_mm,
        lambda,
        removed_rms_mm: removed.sqrt(),
        saturated,
    }
}

/// The plain conjugate gradients this module used before, the reference of
/// its tests.
#[cfg(test)]
#[path = "../benches/common/cg_reference.rs"]
mod cg_reference;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Measurements;

    /// The smoothing as it was before the multigrid: plain conjugate
    /// gradients to a relative residual of 1e-12 (at most `4 n` steps), the
    /// same bisection on `lambda`. The reference the multigrid's surfaces
    /// must equal.
    use super::cg_reference as reference;

    /// A pseudo-random noise of standard deviation `sigma` (deterministic).
    fn noise_source(seed: u64, sigma: f64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            let mut s = 0.0;
            for _ in 0..12 {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                s += (state >> 11) as f64 / (1u64 << 53) as f64;
            }
            (s - 6.0) * sigma
        }
    }

    /// A flat `nu x nv` grid, 5 mm apart, with a smooth warp and noise: the
    /// normal component only (with normals) or every component.
    fn noisy(nu: usize, nv: usize, sigma: f64, normals: bool) -> Grid {
        let mut noise = noise_source(12345, sigma);
        let mut nominal = Vec::new();
        let mut deviation = Vec::new();
        for j in 0..nv {
            for i in 0..nu {
                let (x, y) = (i as f64 * 5.0, j as f64 * 5.0);
                nominal.push([x, y, 0.0]);
                let w = 0.4 * (x / 60.0).sin() * (y / 45.0).cos();
                deviation.push(if normals {
                    [0.0, 0.0, w + noise()]
                } else {
                    [0.3 * w + noise(), -0.2 * w + noise(), w + noise()]
                });
            }
        }
        Grid {
            nu,
            nv,
            nominal,
            deviation,
            normal: normals.then(|| vec![[0.0, 0.0, 1.0]; nu * nv]),
            resampled: false,
            reordered: false,
        }
    }

    /// The fields `smooth` fits, as it takes them from the grid.
    fn fields(g: &Grid) -> Vec<Vec<f64>> {
        match &g.normal {
            Some(n) => vec![
                g.deviation
                    .iter()
                    .zip(n)
                    .map(|(d, n)| dot(*d, *n))
                    .collect(),
            ],
            None => (0..3)
                .map(|c| g.deviation.iter().map(|d| d[c]).collect())
                .collect(),
        }
    }

    #[test]
    fn the_smoothed_surface_is_the_one_of_plain_conjugate_gradients() {
        let example = Measurements::from_csv(include_str!("../../../examples/correct/cmm.csv"))
            .and_then(|m| Grid::from_measurements(&m, None));
        let Ok(example) = example else {
            panic!("the bundled CMM report: {example:?}");
        };
        for (name, grid, noise) in [
            ("40 x 30, normal", noisy(40, 30, 0.02, true), 0.02),
            ("23 x 17, components", noisy(23, 17, 0.01, false), 0.01),
            ("bundled example", example, 0.003),
        ] {
            let (want, _, want_saturated) = reference::fit(&fields(&grid), grid.nu, grid.nv, noise);
            let mut g = grid.clone();
            let s = smooth(&mut g, noise);
            assert_eq!(s.saturated, want_saturated, "{name}");
            let got = fields(&g);
            let worst = got
                .iter()
                .flatten()
                .zip(want.iter().flatten())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-6, "{name}: {worst} mm from the reference");
        }
    }

    #[test]
    fn line_interpolation_reproduces_cubics_and_sums_to_one() {
        for n in [3, 4, 5, 6, 9, 10, 17] {
            let (nc, w) = coarsen_line(n);
            // The coarse points' fine positions.
            let mut at = vec![0.0; nc];
            for (i, row) in w.iter().enumerate() {
                if let [(c, x)] = row[..] {
                    assert_eq!(x, 1.0);
                    at[c] = i as f64;
                }
            }
            for (i, row) in w.iter().enumerate() {
                let sum: f64 = row.iter().map(|r| r.1).sum();
                assert!((sum - 1.0).abs() < 1e-15, "n {n}, point {i}");
                // Linear everywhere; quadratic where three coarse points
                // are used, cubic where four.
                let degree = match row.len() {
                    4 => 3,
                    3 => 2,
                    _ => 1,
                };
                for k in 1..=degree {
                    let f = |x: f64| x.powi(k);
                    let got: f64 = row.iter().map(|&(c, x)| x * f(at[c])).sum();
                    assert!((got - f(i as f64)).abs() < 1e-9, "n {n}, point {i}, x^{k}");
                }
            }
        }
    }

    #[test]
    fn each_solve_meets_its_tolerance_for_every_weight() {
        // 37 x 23 points: three levels below the finest.
        let g = noisy(37, 23, 0.02, true);
        let d = &fields(&g)[0];
        let h = Hierarchy::new(g.nu, g.nv);
        assert!(h.levels.len() >= 3, "{}", h.levels.len());
        for lambda in [1e-6, 1e-2, 1.0, 1e2, 1e4, 1e6, 1e8, 1e10] {
            let op = Operator::new(&h, lambda);
            let mut m = vec![0.0; d.len()];
            let tol = 1e-9;
            op.solve(d, &mut m, tol, &|_, _| false);
            // The residual by the old matrix-free product.
            let mut am = vec![0.0; d.len()];
            reference::apply(&m, &mut am, g.nu, g.nv, lambda);
            let r = d
                .iter()
                .zip(&am)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            // |r| <= sqrt(|A|) |e|_A, |A| <= 1 + 64 lambda.
            assert!(
                r <= 2.0 * (1.0 + 64.0 * lambda).sqrt() * tol + 1e-12 * lambda,
                "lambda {lambda}: residual {r}"
            );
        }
    }

    #[test]
    fn smoothing_recovers_a_smooth_field_under_noise() {
        let (nu, nv) = (40, 30);
        let mut nominal = Vec::new();
        let mut truth = Vec::new();
        let mut dev = Vec::new();
        // A deterministic pseudo-random noise of standard deviation ~0.02.
        let mut state = 12345u64;
        let mut noise = || {
            let mut s = 0.0;
            for _ in 0..12 {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                s += (state >> 11) as f64 / (1u64 << 53) as f64;
            }
            (s - 6.0) * 0.02
        };
        for j in 0..nv {
            for i in 0..nu {
                let (x, y) = (i as f64 * 5.0, j as f64 * 5.0);
                nominal.push([x, y, 0.0]);
                let w = 0.4 * (x / 60.0).sin() * (y / 45.0).cos();
                truth.push(w);
                dev.push([0.0, 0.0, w + noise()]);
            }
        }
        let mut g = Grid {
            nu,
            nv,
            nominal,
            deviation: dev,
            normal: Some(vec![[0.0, 0.0, 1.0]; nu * nv]),
            resampled: false,
            reordered: false,
        };
        let err = |g: &Grid| {
            (g.deviation
                .iter()
                .zip(&truth)
                .map(|(d, t)| (d[2] - t).powi(2))
                .sum::<f64>()
                / truth.len() as f64)
                .sqrt()
        };
        let raw = err(&g);
        let s = smooth(&mut g, 0.02);
        let smoothed = err(&g);
        assert!(!s.saturated);
        assert!((s.removed_rms_mm - 0.02).abs() < 2e-4, "{s:?}");
        assert!(smoothed < 0.5 * raw, "raw {raw}, smoothed {smoothed}");
    }
}
