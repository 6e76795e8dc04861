//! Coons patches over the grid's facets: the nominal surface and the
//! deviation field, bilinear (eq. 1 of docs/correction.md) or bicubic Hermite (C1,
//! slopes by finite differences), and the foot of the normal from a point.

use crate::Grid;
use crate::vec3::{V3, axpy, cross, dot, sub, unit};

/// How the surface and the deviations are interpolated between measured points.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, strum::IntoStaticStr, strum::VariantNames,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
pub enum Interpolation {
    /// The bilinear Coons patch per facet (eq. 1, docs/correction.md).
    Bilinear,
    /// Bicubic Hermite (Ferguson) patches with slopes and twists from finite
    /// differences over the grid: C1 across facets.
    Bicubic,
}

impl Interpolation {
    /// `bilinear` or `bicubic`.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "bilinear" => Some(Self::Bilinear),
            "bicubic" => Some(Self::Bicubic),
            _ => None,
        }
    }

    /// The name.
    pub fn name(self) -> &'static str {
        self.into()
    }
}

impl std::str::FromStr for Interpolation {
    type Err = crate::Rule;

    /// `bilinear` or `bicubic`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::from_name(s).ok_or(crate::Rule::Word {
            allowed: crate::INTERPOLATIONS,
        })
    }
}

/// Value and derivatives of a patch at `(s, t)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Jet {
    pub f: V3,
    pub fs: V3,
    pub ft: V3,
    pub fss: V3,
    pub fst: V3,
    pub ftt: V3,
}

/// The foot of the normal on one facet.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Foot {
    pub s: f64,
    pub t: f64,
    /// Squared distance from the point.
    pub d2: f64,
}

/// Slopes of a grid field along `i` (within sections) and `j` (across).
fn slopes(v: &[V3], nu: usize, nv: usize, along_u: bool) -> Vec<V3> {
    let (n, stride, count) = if along_u { (nu, 1, nv) } else { (nv, nu, nu) };
    let mut out = vec![[0.0; 3]; v.len()];
    for line in 0..count {
        let base = if along_u { line * nu } else { line };
        let at = |k: usize| v[base + k * stride];
        for k in 0..n {
            let d = if n == 2 {
                sub(at(1), at(0))
            } else if k == 0 {
                // Second order, one-sided.
                let (a, b, c) = (at(0), at(1), at(2));
                [0, 1, 2].map(|x| (-3.0 * a[x] + 4.0 * b[x] - c[x]) / 2.0)
            } else if k == n - 1 {
                let (a, b, c) = (at(n - 1), at(n - 2), at(n - 3));
                [0, 1, 2].map(|x| (3.0 * a[x] - 4.0 * b[x] + c[x]) / 2.0)
            } else {
                let (a, c) = (at(k - 1), at(k + 1));
                [0, 1, 2].map(|x| (c[x] - a[x]) / 2.0)
            };
            out[base + k * stride] = d;
        }
    }
    out
}

/// The bilinear form (eq. 1) of corner values `[00, 10, 01, 11]` at
/// `(s, t)`: value, `d/ds`, `d/dt`, `d2/ds dt` — the formula as written,
/// which the per-facet coefficients ([`Linear`]) are checked against.
#[cfg(test)]
fn bilinear(c: [V3; 4], s: f64, t: f64) -> (V3, V3, V3, V3) {
    let [p00, p10, p01, p11] = c;
    let e0 = sub(p10, p00);
    let e1 = sub(p11, p01);
    let f0 = axpy(p00, s, e0);
    let f1 = axpy(p01, s, e1);
    let ft = sub(f1, f0);
    (axpy(f0, t, ft), axpy(e0, t, sub(e1, e0)), ft, sub(e1, e0))
}

/// Hermite basis `[h0, h1, g0, g1]` and its first and second derivatives.
#[inline(always)]
fn hermite(s: f64) -> [[f64; 4]; 3] {
    let s2 = s * s;
    let s3 = s2 * s;
    [
        [
            2.0 * s3 - 3.0 * s2 + 1.0,
            -2.0 * s3 + 3.0 * s2,
            s3 - 2.0 * s2 + s,
            s3 - s2,
        ],
        [
            6.0 * s2 - 6.0 * s,
            -6.0 * s2 + 6.0 * s,
            3.0 * s2 - 4.0 * s + 1.0,
            3.0 * s2 - 2.0 * s,
        ],
        [
            12.0 * s - 6.0,
            -12.0 * s + 6.0,
            6.0 * s - 4.0,
            6.0 * s - 2.0,
        ],
    ]
}

/// A grid field with its slopes (for bicubic patches).
#[derive(Debug, Clone)]
struct Field {
    v: Vec<V3>,
    u: Vec<V3>,
    w: Vec<V3>,
    uw: Vec<V3>,
}

impl Field {
    fn new(v: &[V3], nu: usize, nv: usize) -> Self {
        let u = slopes(v, nu, nv, true);
        let w = slopes(v, nu, nv, false);
        let uw = slopes(&u, nu, nv, false);
        Self {
            v: v.to_vec(),
            u,
            w,
            uw,
        }
    }

    /// The 16 Hermite coefficients of facet `(i, j)`: `c[a][b]`, `a, b` in
    /// `[corner 0, corner 1, slope 0, slope 1]`.
    fn coefficients(&self, nu: usize, i: usize, j: usize) -> [[V3; 4]; 4] {
        let k = |a: usize, b: usize| (j + b) * nu + i + a;
        let mut c = [[[0.0; 3]; 4]; 4];
        for a in 0..2 {
            for b in 0..2 {
                c[a][b] = self.v[k(a, b)];
                c[a + 2][b] = self.u[k(a, b)];
                c[a][b + 2] = self.w[k(a, b)];
                c[a + 2][b + 2] = self.uw[k(a, b)];
            }
        }
        c
    }
}

/// `sum_a sum_b bs[a] bt[b] c[a][b]`.
#[cfg(test)]
fn contract(c: &[[V3; 4]; 4], bs: &[f64; 4], bt: &[f64; 4]) -> V3 {
    let mut out = [0.0; 3];
    for a in 0..4 {
        let mut row = [0.0; 3];
        for b in 0..4 {
            row = axpy(row, bt[b], c[a][b]);
        }
        out = axpy(out, bs[a], row);
    }
    out
}

/// A facet's bilinear form (eq. 1) with its differences taken once:
/// `[P00, P01, e0, e1, e1 - e0]`, `e0 = P10 - P00`, `e1 = P11 - P01`.
type Linear = [V3; 5];

/// A facet of the nominal surface: its bilinear form with what every foot
/// of the normal on it starts from, computed once.
#[derive(Debug, Clone, Copy)]
struct Nominal {
    /// The bilinear form.
    form: Linear,
    /// `F`, `F_s`, `F_t` at the facet's centre `(0.5, 0.5)`, where the
    /// foot's Newton starts: [`eval_linear`] there, so the same bits.
    centre: [V3; 3],
    /// The squared length of the shorter of the edges from corner `00`.
    shorter_edge2: f64,
}

/// A facet's 16 Hermite coefficients ([`Field::coefficients`]) side by side.
type Cubic = [[V3; 4]; 4];

/// The bilinear forms of a grid field, one per facet (`j * (nu - 1) + i`).
fn linear_cells(v: &[V3], nu: usize, nv: usize) -> Vec<Linear> {
    let mut out = Vec::with_capacity((nu - 1) * (nv - 1));
    for j in 0..nv - 1 {
        for i in 0..nu - 1 {
            let k = j * nu + i;
            let (p00, p10, p01, p11) = (v[k], v[k + 1], v[k + nu], v[k + nu + 1]);
            let (e0, e1) = (sub(p10, p00), sub(p11, p01));
            out.push([p00, p01, e0, e1, sub(e1, e0)]);
        }
    }
    out
}

/// The nominal surface's facets: each bilinear form with its centre's jet
/// and its shorter edge.
fn nominal_cells(v: &[V3], nu: usize, nv: usize) -> Vec<Nominal> {
    linear_cells(v, nu, nv)
        .into_iter()
        .map(|form| {
            let (f, fs, ft, _) = eval_linear(&form, 0.5, 0.5);
            let [p00, p01, a, _, _] = form;
            let b = sub(p01, p00);
            Nominal {
                form,
                centre: [f, fs, ft],
                shorter_edge2: dot(a, a).min(dot(b, b)),
            }
        })
        .collect()
}

/// A facet's bilinear form at `(s, t)`: value, `d/ds`, `d/dt`, `d2/ds dt`,
/// with the very operations of [`bilinear`] (the same bits).
#[inline(always)]
fn eval_linear(c: &Linear, s: f64, t: f64) -> (V3, V3, V3, V3) {
    let [p00, p01, e0, e1, twist] = *c;
    let f0 = axpy(p00, s, e0);
    let f1 = axpy(p01, s, e1);
    let ft = sub(f1, f0);
    (axpy(f0, t, ft), axpy(e0, t, twist), ft, twist)
}

/// The Hermite coefficients of a field with slopes, one record per facet.
fn cubic_cells(field: &Field, nu: usize, nv: usize) -> Vec<Cubic> {
    (0..(nu - 1) * (nv - 1))
        .map(|k| field.coefficients(nu, k % (nu - 1), k / (nu - 1)))
        .collect()
}

/// `sum_b bt[b] c[b]`, in [`contract`]'s order.
#[inline(always)]
fn row(c: &[V3; 4], bt: &[f64; 4]) -> V3 {
    let mut out = [0.0; 3];
    for b in 0..4 {
        out = axpy(out, bt[b], c[b]);
    }
    out
}

/// `sum_a bs[a] rows[a]`, in [`contract`]'s order.
#[inline(always)]
fn outer(rows: &[V3; 4], bs: &[f64; 4]) -> V3 {
    let mut out = [0.0; 3];
    for a in 0..4 {
        out = axpy(out, bs[a], rows[a]);
    }
    out
}

/// A bicubic patch at `(s, t)` with its derivatives: [`contract`] six
/// times, its sums along `t` shared (three sets instead of six), the same
/// operations in the same order (the same bits).
#[inline(always)]
fn eval_cubic(c: &Cubic, s: f64, t: f64) -> Jet {
    let hs = hermite(s);
    let ht = hermite(t);
    let rows = |m: usize| {
        [
            row(&c[0], &ht[m]),
            row(&c[1], &ht[m]),
            row(&c[2], &ht[m]),
            row(&c[3], &ht[m]),
        ]
    };
    let (r0, r1, r2) = (rows(0), rows(1), rows(2));
    Jet {
        f: outer(&r0, &hs[0]),
        fs: outer(&r0, &hs[1]),
        ft: outer(&r1, &hs[0]),
        fss: outer(&r0, &hs[2]),
        fst: outer(&r1, &hs[1]),
        ftt: outer(&r2, &hs[0]),
    }
}

/// A bicubic patch at `(s, t)`: value, `d/ds`, `d/dt` (as [`eval_cubic`]).
#[inline(always)]
fn eval_cubic_first(c: &Cubic, s: f64, t: f64) -> (V3, V3, V3) {
    let hs = hermite(s);
    let ht = hermite(t);
    let r0 = [
        row(&c[0], &ht[0]),
        row(&c[1], &ht[0]),
        row(&c[2], &ht[0]),
        row(&c[3], &ht[0]),
    ];
    let r1 = [
        row(&c[0], &ht[1]),
        row(&c[1], &ht[1]),
        row(&c[2], &ht[1]),
        row(&c[3], &ht[1]),
    ];
    (outer(&r0, &hs[0]), outer(&r0, &hs[1]), outer(&r1, &hs[0]))
}

/// The patches of both fields, precomputed per facet.
#[derive(Debug, Clone)]
enum Patches {
    /// Bilinear forms of the deviation (the nominal's are always kept).
    Bilinear { deviation: Vec<Linear> },
    /// Hermite coefficients of the nominal surface and the deviation.
    Bicubic {
        nominal: Vec<Cubic>,
        deviation: Vec<Cubic>,
    },
    /// The formulas as written, evaluated from the grid at every call: what
    /// the tests check the precomputed patches against.
    #[cfg(test)]
    Reference {
        nominal: Option<Field>,
        deviation: Option<Field>,
    },
}

/// The interpolated surface and deviation field over a grid. Each facet's
/// patch data (corners and edge differences, or the 16 Hermite
/// coefficients) is gathered once into one contiguous record, so that an
/// evaluation reads one record and repeats no subtraction.
#[derive(Debug, Clone)]
pub struct Surface<'g> {
    grid: &'g Grid,
    kind: Interpolation,
    /// The nominal surface's bilinear forms (both kinds: the bicubic foot
    /// starts from the bilinear one, extrapolation continues it), with the
    /// jet at each facet's centre.
    linear: Vec<Nominal>,
    patches: Patches,
}

impl<'g> Surface<'g> {
    /// Patches of `kind` over `grid`.
    pub fn new(grid: &'g Grid, kind: Interpolation) -> Self {
        let (nu, nv) = (grid.nu, grid.nv);
        let patches = match kind {
            Interpolation::Bilinear => Patches::Bilinear {
                deviation: linear_cells(&grid.deviation, nu, nv),
            },
            Interpolation::Bicubic => Patches::Bicubic {
                nominal: cubic_cells(&Field::new(&grid.nominal, nu, nv), nu, nv),
                deviation: cubic_cells(&Field::new(&grid.deviation, nu, nv), nu, nv),
            },
        };
        Self {
            grid,
            kind,
            linear: nominal_cells(&grid.nominal, nu, nv),
            patches,
        }
    }

    /// The same patches evaluated by the formulas as written (eq. 1, the
    /// Hermite form) from the grid at every call.
    #[cfg(test)]
    pub(crate) fn reference(grid: &'g Grid, kind: Interpolation) -> Self {
        let field = |v: &[V3]| match kind {
            Interpolation::Bilinear => None,
            Interpolation::Bicubic => Some(Field::new(v, grid.nu, grid.nv)),
        };
        Self {
            grid,
            kind,
            linear: Vec::new(),
            patches: Patches::Reference {
                nominal: field(&grid.nominal),
                deviation: field(&grid.deviation),
            },
        }
    }

    /// The grid.
    pub fn grid(&self) -> &'g Grid {
        self.grid
    }

    /// The interpolation.
    pub fn kind(&self) -> Interpolation {
        self.kind
    }

    /// The nominal surface of facet `(i, j)` at `(s, t)`.
    pub fn point(&self, i: usize, j: usize, s: f64, t: f64) -> [f64; 3] {
        self.jet(i, j, s, t).f
    }

    /// The index of facet `(i, j)` in the per-facet records.
    #[inline(always)]
    fn cell(&self, i: usize, j: usize) -> usize {
        j * (self.grid.nu - 1) + i
    }

    /// The squared length of the shorter of the edges from corner `(i, j)`
    /// of facet `(i, j)` (along `s` and along `t`).
    #[inline(always)]
    pub(crate) fn shorter_edge2(&self, i: usize, j: usize) -> f64 {
        #[cfg(test)]
        if let Patches::Reference { .. } = self.patches {
            let g = self.grid;
            let (a, b) = (
                sub(g.at(i + 1, j), g.at(i, j)),
                sub(g.at(i, j + 1), g.at(i, j)),
            );
            return dot(a, a).min(dot(b, b));
        }
        self.linear[self.cell(i, j)].shorter_edge2
    }

    /// The bilinear patch of facet `(i, j)` at its centre `(0.5, 0.5)`, where
    /// every foot's Newton starts: the record's, so not evaluated per node.
    #[inline(always)]
    fn centre(&self, i: usize, j: usize) -> Jet {
        #[cfg(test)]
        if let Patches::Reference { .. } = self.patches {
            return self.bilinear(i, j, 0.5, 0.5);
        }
        let c = &self.linear[self.cell(i, j)];
        let [f, fs, ft] = c.centre;
        Jet {
            f,
            fs,
            ft,
            fss: [0.0; 3],
            fst: c.form[4],
            ftt: [0.0; 3],
        }
    }

    /// The bilinear patch of facet `(i, j)` (used for extrapolation too).
    #[inline(always)]
    pub(crate) fn bilinear(&self, i: usize, j: usize, s: f64, t: f64) -> Jet {
        #[cfg(test)]
        if let Patches::Reference { .. } = self.patches {
            let g = self.grid;
            let corners = [
                g.at(i, j),
                g.at(i + 1, j),
                g.at(i, j + 1),
                g.at(i + 1, j + 1),
            ];
            let (f, fs, ft, fst) = bilinear(corners, s, t);
            return Jet {
                f,
                fs,
                ft,
                fss: [0.0; 3],
                fst,
                ftt: [0.0; 3],
            };
        }
        let (f, fs, ft, fst) = eval_linear(&self.linear[self.cell(i, j)].form, s, t);
        Jet {
            f,
            fs,
            ft,
            fss: [0.0; 3],
            fst,
            ftt: [0.0; 3],
        }
    }

    /// The nominal surface of facet `(i, j)` at `(s, t)`, with derivatives.
    #[inline(always)]
    pub(crate) fn jet(&self, i: usize, j: usize, s: f64, t: f64) -> Jet {
        match &self.patches {
            Patches::Bilinear { .. } => self.bilinear(i, j, s, t),
            Patches::Bicubic { nominal, .. } => eval_cubic(&nominal[self.cell(i, j)], s, t),
            #[cfg(test)]
            Patches::Reference { nominal, .. } => match nominal {
                None => self.bilinear(i, j, s, t),
                Some(field) => {
                    let c = field.coefficients(self.grid.nu, i, j);
                    let hs = hermite(s);
                    let ht = hermite(t);
                    Jet {
                        f: contract(&c, &hs[0], &ht[0]),
                        fs: contract(&c, &hs[1], &ht[0]),
                        ft: contract(&c, &hs[0], &ht[1]),
                        fss: contract(&c, &hs[2], &ht[0]),
                        fst: contract(&c, &hs[1], &ht[1]),
                        ftt: contract(&c, &hs[0], &ht[2]),
                    }
                }
            },
        }
    }

    /// The deviation interpolated on facet `(i, j)` at `(s, t)` and its
    /// slopes along `s` and `t`.
    pub(crate) fn deviation(&self, i: usize, j: usize, s: f64, t: f64) -> (V3, V3, V3) {
        match &self.patches {
            Patches::Bilinear { deviation } => {
                let (f, fs, ft, _) = eval_linear(&deviation[self.cell(i, j)], s, t);
                (f, fs, ft)
            }
            Patches::Bicubic { deviation, .. } => {
                eval_cubic_first(&deviation[self.cell(i, j)], s, t)
            }
            #[cfg(test)]
            Patches::Reference { deviation, .. } => {
                let g = self.grid;
                match deviation {
                    None => {
                        let corners = [
                            g.deviation_at(i, j),
                            g.deviation_at(i + 1, j),
                            g.deviation_at(i, j + 1),
                            g.deviation_at(i + 1, j + 1),
                        ];
                        let (f, fs, ft, _) = bilinear(corners, s, t);
                        (f, fs, ft)
                    }
                    Some(field) => {
                        let c = field.coefficients(g.nu, i, j);
                        let hs = hermite(s);
                        let ht = hermite(t);
                        (
                            contract(&c, &hs[0], &ht[0]),
                            contract(&c, &hs[1], &ht[0]),
                            contract(&c, &hs[0], &ht[1]),
                        )
                    }
                }
            }
        }
    }

    /// The deviation interpolated on facet `(i, j)` at `(s, t)`: the value
    /// of [`Self::deviation`] (the same operations), without the slopes.
    #[inline(always)]
    pub(crate) fn deviation_value(&self, i: usize, j: usize, s: f64, t: f64) -> V3 {
        match &self.patches {
            Patches::Bilinear { deviation } => eval_linear(&deviation[self.cell(i, j)], s, t).0,
            Patches::Bicubic { deviation, .. } => {
                eval_cubic_first(&deviation[self.cell(i, j)], s, t).0
            }
            #[cfg(test)]
            Patches::Reference { .. } => self.deviation(i, j, s, t).0,
        }
    }

    /// The unit normal of facet `(i, j)` at `(s, t)`, turned toward `p`.
    pub(crate) fn normal_toward(&self, i: usize, j: usize, s: f64, t: f64, p: V3) -> V3 {
        let jet = self.jet(i, j, s, t);
        let n = unit(cross(jet.fs, jet.ft));
        if dot(n, sub(p, jet.f)) < 0.0 {
            [-n[0], -n[1], -n[2]]
        } else {
            n
        }
    }

    /// The foot of the normal from `p` on facet `(i, j)`: the `(s, t)` that
    /// minimises the distance, in `[0, 1]^2` when `clamp` (projected Newton;
    /// Gauss–Newton where the Hessian is not positive definite; a halving
    /// line search keeps every step a descent). Without `clamp`, the facet's
    /// bilinear form is continued beyond its edges (for extrapolation).
    pub(crate) fn foot(&self, i: usize, j: usize, p: V3, clamp: bool) -> Foot {
        let (lo, hi) = if clamp { (0.0, 1.0) } else { (-50.0, 51.0) };
        let eval = |s, t| self.bilinear(i, j, s, t);
        let linear = newton::<false>(eval, p, lo, hi, (0.5, 0.5, self.centre(i, j)));
        if !clamp || self.kind == Interpolation::Bilinear {
            return linear;
        }
        // Bicubic: from the bilinear foot, which is close.
        let eval = |s, t| self.jet(i, j, s, t);
        let start = (linear.s, linear.t, eval(linear.s, linear.t));
        newton::<true>(eval, p, lo, hi, start)
    }
}

/// Minimises `|F(s, t) - p|^2` over `[lo, hi]^2` from `start` (`s`, `t`
/// and `F`'s jet there, which the caller may have at hand): projected
/// Newton, Gauss–Newton where the Hessian is not positive definite, a
/// halving line search keeping every step a descent. Without `CURVED` the
/// patch is bilinear (`fss = ftt = 0`) and `r . fss`, `r . ftt` are left
/// out: adding those zeros changes no bit.
#[inline(always)]
fn newton<const CURVED: bool>(
    eval: impl Fn(f64, f64) -> Jet,
    p: V3,
    lo: f64,
    hi: f64,
    start: (f64, f64, Jet),
) -> Foot {
    let (mut s, mut t, mut jet) = start;
    let mut r = sub(jet.f, p);
    let mut f = dot(r, r);
    for _ in 0..40 {
        let gs = dot(r, jet.fs);
        let gt = dot(r, jet.ft);
        let a = dot(jet.fs, jet.fs);
        let b = dot(jet.fs, jet.ft);
        let c = dot(jet.ft, jet.ft);
        let (mut hss, mut hst, mut htt) = if CURVED {
            (
                a + dot(r, jet.fss),
                b + dot(r, jet.fst),
                c + dot(r, jet.ftt),
            )
        } else {
            (a, b + dot(r, jet.fst), c)
        };
        if hss <= 0.0 || htt <= 0.0 || hss * htt - hst * hst <= 1e-14 * (a * c).max(1e-300) {
            (hss, hst, htt) = (a, b, c);
        }
        // Active bounds: at a bound with the gradient pushing out.
        let fix_s = (s <= lo && gs > 0.0) || (s >= hi && gs < 0.0);
        let fix_t = (t <= lo && gt > 0.0) || (t >= hi && gt < 0.0);
        let (ds, dt) = match (fix_s, fix_t) {
            (true, true) => break,
            (true, false) => (0.0, if htt > 0.0 { -gt / htt } else { 0.0 }),
            (false, true) => (if hss > 0.0 { -gs / hss } else { 0.0 }, 0.0),
            (false, false) => {
                let det = hss * htt - hst * hst;
                if det.abs() < 1e-300 {
                    break;
                }
                ((-gs * htt + gt * hst) / det, (-gt * hss + gs * hst) / det)
            }
        };
        if ds.abs() + dt.abs() < 1e-13 {
            break;
        }
        let mut k = 1.0;
        let mut moved = false;
        for _ in 0..20 {
            let ns = (s + k * ds).clamp(lo, hi);
            let nt = (t + k * dt).clamp(lo, hi);
            let nj = eval(ns, nt);
            let nr = sub(nj.f, p);
            let nf = dot(nr, nr);
            if nf <= f {
                let step = (ns - s).abs() + (nt - t).abs();
                (s, t, jet, r, f) = (ns, nt, nj, nr, nf);
                moved = step > 1e-13;
                break;
            }
            k *= 0.5;
        }
        if !moved {
            break;
        }
    }
    Foot { s, t, d2: f }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(f: impl Fn(f64, f64) -> f64, nu: usize, nv: usize) -> Grid {
        let mut nominal = Vec::new();
        for j in 0..nv {
            for i in 0..nu {
                let (x, y) = (i as f64 * 10.0, j as f64 * 12.0);
                nominal.push([x, y, f(x, y)]);
            }
        }
        Grid {
            nu,
            nv,
            deviation: vec![[0.0; 3]; nominal.len()],
            nominal,
            normal: None,
            resampled: false,
            reordered: false,
        }
    }

    #[test]
    fn bicubic_reproduces_the_grid_and_is_c1() {
        let g = grid(
            |x, y| 0.01 * x * x - 0.02 * x * y + (y / 30.0).sin() * 5.0,
            5,
            4,
        );
        let s = Surface::new(&g, Interpolation::Bicubic);
        for j in 0..3 {
            for i in 0..4 {
                let c = s.jet(i, j, 0.0, 0.0);
                assert!(sub(c.f, g.at(i, j)).iter().all(|v| v.abs() < 1e-12));
                let e = s.jet(i, j, 1.0, 1.0);
                assert!(sub(e.f, g.at(i + 1, j + 1)).iter().all(|v| v.abs() < 1e-12));
            }
        }
        // Slopes agree across the edge s = 1 | s = 0.
        for t in [0.0, 0.3, 0.77, 1.0] {
            let a = s.jet(1, 1, 1.0, t);
            let b = s.jet(2, 1, 0.0, t);
            assert!(sub(a.fs, b.fs).iter().all(|v| v.abs() < 1e-12));
            assert!(sub(a.f, b.f).iter().all(|v| v.abs() < 1e-12));
        }
    }

    #[test]
    fn foot_matches_a_brute_force_search_on_curved_facets() {
        // A strongly curved facet (a saddle): the foot by Newton against a
        // dense search over (s, t).
        let g = grid(|x, y| 0.08 * x * x - 0.05 * y * y + 0.03 * x * y, 3, 3);
        for kind in [Interpolation::Bilinear, Interpolation::Bicubic] {
            let surf = Surface::new(&g, kind);
            for (k, p) in [
                [3.0, 4.0, 5.0],
                [7.0, 2.0, -3.0],
                [12.0, 5.0, 1.0],
                [5.0, 11.0, 8.0],
            ]
            .into_iter()
            .enumerate()
            {
                let foot = surf.foot(0, 0, p, true);
                let n = 400;
                let mut best = f64::INFINITY;
                let mut arg = (0.0, 0.0);
                for a in 0..=n {
                    for b in 0..=n {
                        let (s, t) = (a as f64 / n as f64, b as f64 / n as f64);
                        let r = sub(surf.jet(0, 0, s, t).f, p);
                        if dot(r, r) < best {
                            best = dot(r, r);
                            arg = (s, t);
                        }
                    }
                }
                assert!(
                    foot.d2 <= best + 1e-12,
                    "{kind:?} point {k}: {} > {best}",
                    foot.d2
                );
                assert!(
                    (foot.s - arg.0).abs() < 4e-3 && (foot.t - arg.1).abs() < 4e-3,
                    "{kind:?} point {k}: ({}, {}) vs {arg:?}",
                    foot.s,
                    foot.t
                );
            }
        }
    }

    /// A grid of `nu x nv` points about `dx x dy` apart, every coordinate
    /// jittered, with random deviations: what the property tests draw.
    fn random_grid() -> impl proptest::strategy::Strategy<Value = Grid> {
        use proptest::prelude::*;
        (2usize..7, 2usize..7, 1.0..20.0f64, 1.0..20.0f64).prop_flat_map(|(nu, nv, dx, dy)| {
            let n = nu * nv;
            (
                prop::collection::vec((-0.2..0.2f64, -0.2..0.2f64, -5.0..5.0f64), n),
                prop::collection::vec(prop::array::uniform3(-0.5..0.5f64), n),
            )
                .prop_map(move |(jitter, deviation)| {
                    let nominal = (0..n)
                        .map(|k| {
                            let (i, j) = ((k % nu) as f64, (k / nu) as f64);
                            let (a, b, z) = jitter[k];
                            [(i + a) * dx, (j + b) * dy, z]
                        })
                        .collect();
                    Grid {
                        nu,
                        nv,
                        nominal,
                        deviation,
                        normal: None,
                        resampled: false,
                        reordered: false,
                    }
                })
        })
    }

    /// Equal to 1e-12 mm (the records give the very bits, in fact).
    fn close(a: V3, b: V3) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12)
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(128))]

        /// The per-facet records (bilinear differences taken once, bicubic
        /// sums along `t` shared) give the formulas as written to 1e-12 mm:
        /// values and every derivative, nominal and deviation.
        #[test]
        fn precomputed_patches_equal_the_formulas(
            g in random_grid(),
            cell in (0.0..1.0f64, 0.0..1.0f64),
            (s, t) in (-0.5..1.5f64, -0.5..1.5f64),
        ) {
            let i = ((cell.0 * (g.nu - 1) as f64) as usize).min(g.nu - 2);
            let j = ((cell.1 * (g.nv - 1) as f64) as usize).min(g.nv - 2);
            for kind in [Interpolation::Bilinear, Interpolation::Bicubic] {
                let fast = Surface::new(&g, kind);
                let slow = Surface::reference(&g, kind);
                let (a, b) = (fast.jet(i, j, s, t), slow.jet(i, j, s, t));
                for (x, y) in [
                    (a.f, b.f),
                    (a.fs, b.fs),
                    (a.ft, b.ft),
                    (a.fss, b.fss),
                    (a.fst, b.fst),
                    (a.ftt, b.ftt),
                ] {
                    proptest::prop_assert!(close(x, y), "{kind:?} ({i}, {j}) at ({s}, {t}): {x:?} vs {y:?}");
                }
                let (a, b) = (fast.bilinear(i, j, s, t), slow.bilinear(i, j, s, t));
                proptest::prop_assert!(close(a.f, b.f) && close(a.fs, b.fs) && close(a.ft, b.ft));
                let (a, b) = (fast.deviation(i, j, s, t), slow.deviation(i, j, s, t));
                proptest::prop_assert!(
                    close(a.0, b.0) && close(a.1, b.1) && close(a.2, b.2),
                    "{kind:?} deviation: {a:?} vs {b:?}"
                );
                proptest::prop_assert!(
                    (fast.shorter_edge2(i, j) - slow.shorter_edge2(i, j)).abs() <= 1e-12
                );
                // The centre's jet kept in the record, where every foot
                // starts, and the deviation's value alone: the very bits.
                let (a, b) = (fast.centre(i, j), slow.bilinear(i, j, 0.5, 0.5));
                for (x, y) in [(a.f, b.f), (a.fs, b.fs), (a.ft, b.ft), (a.fst, b.fst)] {
                    proptest::prop_assert_eq!(x.map(f64::to_bits), y.map(f64::to_bits));
                }
                proptest::prop_assert_eq!(
                    fast.deviation_value(i, j, s, t).map(f64::to_bits),
                    fast.deviation(i, j, s, t).0.map(f64::to_bits)
                );
            }
        }
    }
}
