//! Inverse kinematics (eq. 2, docs/machines.md): axis values that put the payout point
//! on the target, `T(x) (r + l tau) = Y(x)`, with the orientation equations where
//! the machine has more than three driven axes besides the spindle.
//!
//! * The spindle turns the mandrel so that the eye (or the path point,
//!   `spindle_follows = "path"`) faces the payout point's home direction.
//! * The other axes: Levenberg–Marquardt (`levenberg-marquardt`), seeded from the
//!   previous point; residuals are the position (mm) and, scaled by
//!   [`ORIENTATION_SCALE`], the orientation equations: a winder's eye roller
//!   perpendicular to the free band (and to the band's normal when a fifth axis
//!   allows), a placement head pressing along the inward normal with its roller
//!   across the path.
//! * Lathe-type winders (spindle, carriage along it, optional radial cross feed,
//!   optional eye rotation about the cross feed) are solved in closed form.

use std::cell::RefCell;
use std::f64::consts::{PI, TAU};
use std::fmt;

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DMatrix, DVector, Dyn, Isometry3, Owned, Point3, Unit, Vector3};
use rayon::prelude::*;
use serde::Serialize;

use crate::chain::{Chain, Frame};
use crate::file::{MachineKind, SpindleFollows};
use crate::{Fk, IkFault, JointKind, Machine, MachineError, Target};

/// Orientation residuals (dimensionless) are weighed as lengths of this many mm.
pub const ORIENTATION_SCALE: f64 = 100.0;

/// Which solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IkMethod {
    /// The closed form where the machine has one, else the solver.
    Auto,
    /// Levenberg–Marquardt for every machine.
    Solver,
    /// The closed form (an error where the machine has none).
    ClosedForm,
}

/// What kind of problem the inverse kinematics found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum IssueKind {
    /// An axis beyond its limits.
    Limit,
    /// The payout point (or the orientation) not reached.
    Unreachable,
    /// The eye closer to the mandrel than the clearance.
    Clearance,
    /// An axis jumping to another branch between two points.
    Jump,
}

impl IssueKind {
    /// The name in files and messages: `limit`, `unreachable`, `clearance`, `jump`.
    pub fn name(self) -> &'static str {
        match self {
            IssueKind::Limit => "limit",
            IssueKind::Unreachable => "unreachable",
            IssueKind::Clearance => "clearance",
            IssueKind::Jump => "jump",
        }
    }
}

impl fmt::Display for IssueKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// A problem found at some points.
#[derive(Debug, Clone, PartialEq)]
pub struct Issue {
    /// What kind.
    pub kind: IssueKind,
    /// The axis concerned (NC address), if one.
    pub axis: Option<String>,
    /// The first `x` where it happens, mm.
    pub x: f64,
    /// How many points.
    pub count: usize,
    /// The worst excess (mm or rad beyond the limit; the residual in mm; the jump).
    pub worst: f64,
}

/// The axis values of a whole trajectory.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisTrack {
    /// Which solver produced it.
    pub closed_form: bool,
    /// Axis values, point after point (rad or mm, in the order of the
    /// machine's axes): see [`AxisTrack::rows`].
    pub values: Vec<f64>,
    /// Axes per point.
    pub width: usize,
    /// Position residual per point, mm.
    pub residual_mm: Vec<f64>,
    /// Orientation residual per point (largest of the equations' cosines).
    pub residual_orientation: Vec<f64>,
    /// Problems found.
    pub issues: Vec<Issue>,
}

impl AxisTrack {
    /// The axis values of each point.
    pub fn rows(&self) -> std::slice::ChunksExact<'_, f64> {
        self.values.chunks_exact(self.width.max(1))
    }

    /// The axis values of point `i`.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.values[i * self.width..(i + 1) * self.width]
    }

    /// Whether every axis stays within its limits.
    pub fn limits_ok(&self) -> bool {
        !self.issues.iter().any(|i| i.kind == IssueKind::Limit)
    }

    /// The largest position residual, mm.
    pub fn max_residual_mm(&self) -> f64 {
        self.residual_mm.iter().copied().fold(0.0, f64::max)
    }
}

/// Where a joint moves: the world frame of its motion at a pose.
fn joint_axis(m: &Machine, poses: &[Isometry3<f64>], link: usize) -> (Point3<f64>, Vector3<f64>) {
    let l = &m.links[link];
    let f = match l.parent {
        Some(p) => poses[p] * l.joint.pre,
        None => l.joint.pre,
    };
    (
        Point3::from(f.translation.vector),
        f.rotation * l.joint.direction.into_inner(),
    )
}

/// The spindle's rule: the angle that turns the face point to the home direction.
#[derive(Debug, Clone, Copy)]
struct Spindle {
    axis: usize,
    origin: Point3<f64>,
    k: Vector3<f64>,
    home: Vector3<f64>,
    follows: SpindleFollows,
}

impl Spindle {
    fn new(m: &Machine) -> Result<Option<Self>, MachineError> {
        let Some(axis) = m.roles.spindle else {
            return Ok(None);
        };
        let poses = m.poses(&m.home());
        let (origin, k) = joint_axis(m, &poses, m.axes[axis].link);
        let p = poses[m.points[m.roles.payout].link] * m.points[m.roles.payout].position;
        let d = p - origin;
        let perp = d - k * d.dot(&k);
        if perp.norm() < 1e-9 {
            return Err(IkFault::PayoutOnSpindleAxis.into());
        }
        Ok(Some(Self {
            axis,
            origin,
            k,
            home: perp.normalize(),
            follows: m.roles.spindle_follows,
        }))
    }

    /// The spindle value, near `prev`, that turns the face point of `t` to the
    /// home direction, given the mandrel's pose `mandrel` at spindle value `cur`.
    fn angle(&self, t: &Target, mandrel: &Isometry3<f64>, cur: f64, prev: f64) -> f64 {
        let face = match self.follows {
            SpindleFollows::Eye => t.point,
            SpindleFollows::Path => t.path_point,
        };
        let d = mandrel * face - self.origin;
        let perp = d - self.k * d.dot(&self.k);
        let delta = self
            .k
            .dot(&perp.cross(&self.home))
            .atan2(perp.dot(&self.home));
        unwrap_near(cur + delta, prev, TAU)
    }
}

/// `a` shifted by a multiple of `period` to lie nearest `near`.
fn unwrap_near(a: f64, near: f64, period: f64) -> f64 {
    a + period * ((near - a) / period).round()
}

/// The equations at one target for the axes `q` (only those in `unknowns` move).
struct Equations<'a> {
    m: &'a Machine,
    t: &'a Target,
    unknowns: &'a [usize],
    q: Vec<f64>,
    /// Per axis: whether it moves the payout point's link, the mandrel's link.
    moves: &'a [(bool, bool)],
    /// The forward kinematics (every link the equations read).
    fk: &'a Fk,
    /// Link poses, reused between evaluations.
    poses: RefCell<Vec<Isometry3<f64>>>,
}

/// Per axis: whether it moves the payout point's link and the mandrel's link.
fn moves(m: &Machine) -> Vec<(bool, bool)> {
    let head = m.points[m.roles.payout].link;
    m.axes
        .iter()
        .map(|a| {
            (
                m.is_ancestor(a.link, head),
                m.is_ancestor(a.link, m.roles.mandrel),
            )
        })
        .collect()
}

/// How many orientation equations `m` has.
fn orientation_rows(m: &Machine) -> usize {
    let roles = &m.roles;
    match roles.kind {
        // Beyond three driven axes (the spindle counted), one orientation
        // equation per axis, at most the two of the eye roller.
        MachineKind::Winder => match roles.roller_axis {
            Some(_) => m.axes.len().saturating_sub(3).min(2),
            None => 0,
        },
        // Pressing along `-m` (two rows, and a third that tells it from
        // pressing along `+m`), the roller across the path.
        MachineKind::Placement => 3 + usize::from(roles.roller_axis.is_some()),
    }
}

/// At most seven residuals, without allocating.
#[derive(Debug, Clone, Copy)]
struct Residuals {
    v: [f64; 7],
    n: usize,
}

impl Residuals {
    fn push(&mut self, x: f64) {
        if self.n < self.v.len() {
            self.v[self.n] = x;
            self.n += 1;
        }
    }
}

impl std::ops::Deref for Residuals {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        &self.v[..self.n]
    }
}

/// Residuals and, when asked, their Jacobian columns for the unknowns.
struct Evaluated {
    r: Residuals,
    jac: Option<DMatrix<f64>>,
}

impl<'a> Equations<'a> {
    fn new(
        m: &'a Machine,
        t: &'a Target,
        unknowns: &'a [usize],
        moves: &'a [(bool, bool)],
        fk: &'a Fk,
        q: &[f64],
    ) -> Self {
        Self {
            m,
            t,
            unknowns,
            q: q.to_vec(),
            moves,
            fk,
            poses: RefCell::new(Vec::with_capacity(m.links.len())),
        }
    }

    fn eval(&self, with_jacobian: bool) -> Evaluated {
        let m = self.m;
        let roles = &m.roles;
        let mut buf = self.poses.borrow_mut();
        self.fk.poses_into(&self.q, &mut buf);
        let poses: &[Isometry3<f64>] = &buf;
        let payout = &m.points[roles.payout];
        let head = poses[payout.link];
        let mandrel = poses[roles.mandrel];
        let p = head * payout.position;
        let target = mandrel * self.t.point;
        let band = mandrel.rotation * self.t.band.into_inner();
        let normal = mandrel.rotation * self.t.normal.into_inner();
        let roller = roles.roller_axis.map(|a| head.rotation * a.into_inner());
        let press = roles.head_normal.map(|a| head.rotation * a.into_inner());
        let side = normal.cross(&band);
        let s = ORIENTATION_SCALE;
        let mut r = Residuals {
            v: [
                p.x - target.x,
                p.y - target.y,
                p.z - target.z,
                0.0,
                0.0,
                0.0,
                0.0,
            ],
            n: 3,
        };
        let rows = orientation_rows(m);
        match roles.kind {
            MachineKind::Winder => {
                if let Some(a) = roller {
                    if rows >= 1 {
                        r.push(s * a.dot(&band));
                    }
                    if rows >= 2 {
                        r.push(s * a.dot(&normal));
                    }
                }
            }
            MachineKind::Placement => {
                let n = press.unwrap_or_else(Vector3::z);
                r.push(s * n.dot(&band));
                r.push(s * n.dot(&side));
                // Zero where the head presses along `-m`, 2 where along `+m`
                // (which the two rows above allow too).
                r.push(s * (1.0 + n.dot(&normal)));
                if let Some(a) = roller {
                    r.push(s * a.dot(&band));
                }
            }
        }
        let jac = with_jacobian.then(|| {
            let mut j = DMatrix::zeros(r.len(), self.unknowns.len());
            for (c, &ax) in self.unknowns.iter().enumerate() {
                let link = m.axes[ax].link;
                let (o, w) = joint_axis(m, poses, link);
                let rev = m.axes[ax].kind == JointKind::Revolute;
                let (moves_head, moves_mandrel) = self.moves[ax];
                // Derivatives of a point and of a direction carried by the joint.
                let dpt = |x: &Point3<f64>, moved: bool| {
                    if !moved {
                        Vector3::zeros()
                    } else if rev {
                        w.cross(&(x - o))
                    } else {
                        w
                    }
                };
                let ddir = |d: &Vector3<f64>, moved: bool| {
                    if moved && rev {
                        w.cross(d)
                    } else {
                        Vector3::zeros()
                    }
                };
                let dp = dpt(&p, moves_head) - dpt(&target, moves_mandrel);
                j[(0, c)] = dp.x;
                j[(1, c)] = dp.y;
                j[(2, c)] = dp.z;
                let d_band = ddir(&band, moves_mandrel);
                let d_normal = ddir(&normal, moves_mandrel);
                let mut row = 3;
                let mut put = |v: f64| {
                    j[(row, c)] = s * v;
                    row += 1;
                };
                match roles.kind {
                    MachineKind::Winder => {
                        if let Some(a) = roller {
                            let da = ddir(&a, moves_head);
                            if rows >= 1 {
                                put(da.dot(&band) + a.dot(&d_band));
                            }
                            if rows >= 2 {
                                put(da.dot(&normal) + a.dot(&d_normal));
                            }
                        }
                    }
                    MachineKind::Placement => {
                        let n = press.unwrap_or_else(Vector3::z);
                        let dn = ddir(&n, moves_head);
                        let d_side = d_normal.cross(&band) + normal.cross(&d_band);
                        put(dn.dot(&band) + n.dot(&d_band));
                        put(dn.dot(&side) + n.dot(&d_side));
                        put(dn.dot(&normal) + n.dot(&d_normal));
                        if let Some(a) = roller {
                            let da = ddir(&a, moves_head);
                            put(da.dot(&band) + a.dot(&d_band));
                        }
                    }
                }
            }
            j
        });
        Evaluated { r, jac }
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Equations<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        for (k, &ax) in self.unknowns.iter().enumerate() {
            self.q[ax] = x[k];
        }
    }

    fn params(&self) -> DVector<f64> {
        DVector::from_iterator(
            self.unknowns.len(),
            self.unknowns.iter().map(|&a| self.q[a]),
        )
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let e = self.eval(false);
        Some(DVector::from_column_slice(&e.r))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        self.eval(true).jac
    }
}

/// The closed form of a lathe-type winder.
#[derive(Debug, Clone)]
struct Lathe {
    spindle: Spindle,
    /// Mandrel pose at home.
    mandrel0: Isometry3<f64>,
    /// Payout point at home, relative to the spindle axis: axial part and radial vector.
    p_axial: f64,
    p_perp: Vector3<f64>,
    carriage: (usize, f64),
    cross: Option<(usize, Vector3<f64>)>,
    /// Eye rotation: axis index, world direction, roller axis at home.
    eye: Option<(usize, Vector3<f64>, Vector3<f64>)>,
    /// Home axis values: every closed-form value is an offset from them.
    home: Vec<f64>,
}

impl Lathe {
    /// The closed form, if the machine is lathe-type.
    fn detect(m: &Machine, spindle: Option<Spindle>) -> Option<Self> {
        let spindle = spindle?;
        if m.roles.kind != MachineKind::Winder || spindle.follows != SpindleFollows::Eye {
            return None;
        }
        let home = m.home();
        let poses = m.poses(&home);
        let payout = &m.points[m.roles.payout];
        let p0 = poses[payout.link] * payout.position;
        let d = p0 - spindle.origin;
        let k = spindle.k;
        let p_axial = d.dot(&k);
        let p_perp = d - k * p_axial;
        let (mut carriage, mut cross, mut eye) = (None, None, None);
        for (i, a) in m.axes.iter().enumerate() {
            if i == spindle.axis {
                continue;
            }
            if m.is_ancestor(a.link, m.roles.mandrel) || !m.is_ancestor(a.link, payout.link) {
                return None;
            }
            let (o, w) = joint_axis(m, &poses, a.link);
            match a.kind {
                JointKind::Prismatic
                    if (w.dot(&k).abs() - 1.0).abs() < 1e-9 && carriage.is_none() =>
                {
                    carriage = Some((i, w.dot(&k)));
                }
                JointKind::Prismatic
                    if w.dot(&k).abs() < 1e-9
                        && cross.is_none()
                        && w.cross(&p_perp).norm() < 1e-9 * p_perp.norm() =>
                {
                    cross = Some((i, w));
                }
                JointKind::Revolute if eye.is_none() => {
                    let off = p0 - o;
                    if (off - w * off.dot(&w)).norm() > 1e-9 {
                        return None;
                    }
                    let a0 = poses[payout.link].rotation * m.roles.roller_axis?.into_inner();
                    if a0.dot(&w).abs() > 1e-9 {
                        return None;
                    }
                    eye = Some((i, w, a0));
                }
                _ => return None,
            }
        }
        // Translations must not hang below the eye's rotation.
        if let Some((e, _, _)) = eye {
            for (ax, _) in carriage
                .iter()
                .map(|c| (c.0, ()))
                .chain(cross.iter().map(|c| (c.0, ())))
            {
                if m.is_ancestor(m.axes[e].link, m.axes[ax].link) {
                    return None;
                }
            }
            if let Some((_, w, _)) = eye
                && let Some((_, c)) = cross
                && w.cross(&c).norm() > 1e-9
            {
                return None;
            }
        }
        Some(Self {
            spindle,
            mandrel0: poses[m.roles.mandrel],
            p_axial,
            p_perp,
            carriage: carriage?,
            cross,
            eye,
            home,
        })
    }

    /// Axis values for `t`, near `prev`.
    #[cfg(test)]
    fn solve(&self, t: &Target, prev: &[f64], q: &mut [f64]) {
        let sp = self.spindle.axis;
        self.raw(t, q);
        q[sp] = unwrap_near(q[sp], prev[sp], TAU);
        if let Some((ei, _, _)) = self.eye {
            self.eye_raw(t, q);
            q[ei] = unwrap_near(q[ei], prev[ei], PI);
        }
    }

    /// The axis values of every target, each row near the one before (the
    /// first near home). The rows depend on each other only through the
    /// turns of the rotary axes, so the work is split in phases: the axes of
    /// every row in chunks on rayon's pool (the same chunks whatever the
    /// number of threads), the spindle's turns in order, the eye's angle
    /// (which reads the spindle's value) in chunks, its half turns in order.
    /// Each value is the same number as solving the rows one after another.
    fn track(&self, targets: &[Target]) -> Vec<f64> {
        const CHUNK: usize = 4096;
        let w = self.home.len().max(1);
        let mut values = vec![0.0; targets.len() * w];
        let in_chunks = |values: &mut [f64], f: &(dyn Fn(&Target, &mut [f64]) + Sync)| {
            values
                .par_chunks_mut(CHUNK * w)
                .zip(targets.par_chunks(CHUNK))
                .for_each(|(rows, ts)| {
                    for (q, t) in rows.chunks_exact_mut(w).zip(ts) {
                        f(t, q);
                    }
                });
        };
        let in_order = |values: &mut [f64], axis: usize, period: f64| {
            let mut prev = self.home[axis];
            for q in values.chunks_exact_mut(w) {
                q[axis] = unwrap_near(q[axis], prev, period);
                prev = q[axis];
            }
        };
        in_chunks(&mut values, &|t, q| self.raw(t, q));
        in_order(&mut values, self.spindle.axis, TAU);
        if let Some((ei, _, _)) = self.eye {
            in_chunks(&mut values, &|t, q| self.eye_raw(t, q));
            in_order(&mut values, ei, PI);
        }
        values
    }

    /// The carriage, the cross feed and the spindle for `t`, the spindle as
    /// home plus its turn within a turn.
    fn raw(&self, t: &Target, q: &mut [f64]) {
        let sp = &self.spindle;
        let k = sp.k;
        let d0 = self.mandrel0 * t.point - sp.origin;
        let a_e = d0.dot(&k);
        let d0_perp = d0 - k * a_e;
        let r_e = d0_perp.norm();
        let (ci, sign) = self.carriage;
        q[ci] = self.home[ci] + (a_e - self.p_axial) / sign;
        let p_perp = match self.cross {
            Some((xi, c)) => {
                let b = self.p_perp.dot(&c);
                let disc = b * b - self.p_perp.norm_squared() + r_e * r_e;
                let roots = [-b + disc.max(0.0).sqrt(), -b - disc.max(0.0).sqrt()];
                // The root on the payout point's home side of the axis.
                let u = roots
                    .into_iter()
                    .find(|u| (self.p_perp + c * *u).dot(&self.p_perp) > 0.0)
                    .unwrap_or(roots[0]);
                q[xi] = self.home[xi] + u;
                self.p_perp + c * u
            }
            None => self.p_perp,
        };
        let delta = k.dot(&d0_perp.cross(&p_perp)).atan2(d0_perp.dot(&p_perp));
        q[sp.axis] = self.home[sp.axis] + delta;
    }

    /// The eye's rotation for `t` at the spindle's value in `q`, as home plus
    /// its angle within a half turn.
    fn eye_raw(&self, t: &Target, q: &mut [f64]) {
        let Some((ei, w, a0)) = self.eye else {
            return;
        };
        let sp = &self.spindle;
        let turn = q[sp.axis] - self.home[sp.axis];
        let rot = nalgebra::UnitQuaternion::from_axis_angle(&Unit::new_unchecked(sp.k), turn);
        let band = rot * (self.mandrel0.rotation * t.band.into_inner());
        let theta = (-a0.dot(&band)).atan2(w.cross(&a0).dot(&band));
        q[ei] = self.home[ei] + theta;
    }
}

/// Solves the axes for every target, seeded point after point.
pub fn solve(m: &Machine, targets: &[Target], method: IkMethod) -> Result<AxisTrack, MachineError> {
    let spindle = Spindle::new(m)?;
    let lathe = match method {
        IkMethod::Solver => None,
        IkMethod::Auto => Lathe::detect(m, spindle),
        IkMethod::ClosedForm => Some(Lathe::detect(m, spindle).ok_or_else(|| {
            MachineError::from(IkFault::NoClosedForm {
                machine: m.name.clone(),
            })
        })?),
    };
    let values = match &lathe {
        Some(l) => l.track(targets),
        None => by_solver(m, spindle, targets),
    };
    let mut track = AxisTrack {
        closed_form: lathe.is_some(),
        values,
        width: m.axes.len(),
        residual_mm: Vec::new(),
        residual_orientation: Vec::new(),
        issues: Vec::new(),
    };
    (track.residual_mm, track.residual_orientation) = residuals(m, targets, &track.values);
    track.issues = feasibility(m, targets, &track);
    Ok(track)
}

/// The axis values of every target by the solver (Gauss–Newton, else
/// Levenberg–Marquardt), seeded point after point: the spindle by its rule,
/// the other axes from the path extrapolated through the two points before.
fn by_solver(m: &Machine, spindle: Option<Spindle>, targets: &[Target]) -> Vec<f64> {
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

/// The position residual (mm) and the orientation residual (the largest of the
/// equations' cosines) of every point of a solved trajectory (`values`, a row
/// of axis values per target), by forward kinematics.
///
/// Every point is checked, whichever solver produced it: the closed form is
/// exact only where the point is reachable (a cross feed's discriminant
/// clipped at zero, an eye turned as near as it goes), and a point checked at
/// a sample would let such a stretch between samples pass unseen. The check
/// is cheap instead: the forward kinematics is specialised to the payout
/// point's and the mandrel's chains ([`Chain`]: rotation matrices, whatever
/// does not depend on the axes folded in advance, one `sin_cos` per turning
/// joint), equal to the reference's poses to rounding. Long trajectories are
/// checked in runs, one per worker of rayon's pool, each writing its own
/// stretch of the two outputs.
fn residuals(m: &Machine, targets: &[Target], values: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let width = m.axes.len().max(1);
    let n = targets.len().min(values.len() / width);
    let mut pos = vec![0.0; n];
    let mut ori = vec![0.0; n];
    let chain = Chain::new(m, &[m.points[m.roles.payout].link, m.roles.mandrel]);
    let rows = orientation_rows(m);
    let run = |ts: &[Target], values: &[f64], pos: &mut [f64], ori: &mut [f64]| {
        let mut frames = Vec::with_capacity(m.links.len());
        let rows_of = ts.iter().zip(values.chunks_exact(width));
        for ((t, q), (p, o)) in rows_of.zip(pos.iter_mut().zip(ori.iter_mut())) {
            chain.frames_into(q, &mut frames);
            (*p, *o) = point_residuals(m, rows, &frames, t);
        }
    };
    let threads = rayon::current_num_threads().min(n / 20_000).clamp(1, 16);
    if threads == 1 {
        run(targets, values, &mut pos, &mut ori);
    } else {
        let per = n.div_ceil(threads);
        targets[..n]
            .par_chunks(per)
            .zip(values.par_chunks(per * width))
            .zip(pos.par_chunks_mut(per).zip(ori.par_chunks_mut(per)))
            .for_each(|((ts, vs), (p, o))| run(ts, vs, p, o));
    }
    (pos, ori)
}

/// The position residual (mm) and the orientation residual (the largest of
/// the equations' cosines) at target `t`, from the world frames of the
/// payout point's and the mandrel's links: the residuals of [`Equations`],
/// the orientation ones unscaled.
fn point_residuals(m: &Machine, rows: usize, frames: &[Frame], t: &Target) -> (f64, f64) {
    let roles = &m.roles;
    let payout = &m.points[roles.payout];
    let head = &frames[payout.link];
    let mandrel = &frames[roles.mandrel];
    let d = head.point(&payout.position) - mandrel.point(&t.point);
    let pos = (d.x * d.x + d.y * d.y + d.z * d.z).sqrt();
    let band = mandrel.rotation * t.band.into_inner();
    let normal = mandrel.rotation * t.normal.into_inner();
    let roller = roles.roller_axis.map(|a| head.rotation * a.into_inner());
    let mut ori = 0.0_f64;
    let mut put = |v: f64| ori = ori.max(v.abs());
    match roles.kind {
        MachineKind::Winder => {
            if let Some(a) = roller {
                if rows >= 1 {
                    put(a.dot(&band));
                }
                if rows >= 2 {
                    put(a.dot(&normal));
                }
            }
        }
        MachineKind::Placement => {
            let n = roles
                .head_normal
                .map_or_else(Vector3::z, |a| head.rotation * a.into_inner());
            put(n.dot(&band));
            put(n.dot(&normal.cross(&band)));
            put(1.0 + n.dot(&normal));
            if let Some(a) = roller {
                put(a.dot(&band));
            }
        }
    }
    (pos, ori)
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

/// Limits, unreachable points, the eye's clearance and branch jumps.
fn feasibility(m: &Machine, targets: &[Target], t: &AxisTrack) -> Vec<Issue> {
    let mut out: Vec<Issue> = Vec::new();
    let mut note = |kind: IssueKind, axis: Option<&str>, x: f64, excess: f64| {
        if let Some(i) = out
            .iter_mut()
            .find(|i| i.kind == kind && i.axis.as_deref() == axis)
        {
            i.count += 1;
            i.worst = i.worst.max(excess);
        } else {
            out.push(Issue {
                kind,
                axis: axis.map(str::to_string),
                x,
                count: 1,
                worst: excess,
            });
        }
    };
    for (i, (q, tg)) in t.rows().zip(targets).enumerate() {
        for (a, ax) in m.axes.iter().enumerate() {
            let v = q[a];
            let excess = (ax.min - v).max(v - ax.max);
            if excess > 1e-9 {
                note(IssueKind::Limit, Some(&ax.name), tg.x, excess);
            }
        }
        let res = t.residual_mm[i].max(ORIENTATION_SCALE * t.residual_orientation[i]);
        if res > 1e-6 {
            note(IssueKind::Unreachable, None, tg.x, res);
        }
        if tg.clearance_margin < -1e-6 {
            note(IssueKind::Clearance, None, tg.x, -tg.clearance_margin);
        }
    }
    // A jump: a step much longer than both neighbouring steps on the same axis
    // (the solution flipped to another branch between two points).
    for (a, ax) in m.axes.iter().enumerate() {
        let floor = if ax.is_rotary() {
            1f64.to_radians()
        } else {
            1.0
        };
        // Steps between neighbouring rows, with the step before and after.
        let step = |k: usize| (t.row(k + 1)[a] - t.row(k)[a]).abs();
        let n = t.rows().len().saturating_sub(1);
        let mut before = 0.0;
        for k in 0..n {
            let here = step(k);
            let after = if k + 1 < n { step(k + 1) } else { 0.0 };
            if here > floor && here > 20.0 * f64::max(before, after) {
                note(IssueKind::Jump, Some(&ax.name), targets[k + 1].x, here);
            }
            before = here;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    proptest::proptest! {
        /// The check's residuals are the equations' (the reference forward
        /// kinematics) within 1e-9 mm and 1e-12 on random axis values and
        /// targets, for every shipped machine.
        #[test]
        fn residuals_are_the_equations_ones(
            u in proptest::collection::vec(-1.0..1.0_f64, 8),
            p in proptest::collection::vec(-500.0..500.0_f64, 3),
            b in proptest::collection::vec(-1.0..1.0_f64, 6),
        ) {
            for s in crate::shipped::SHIPPED {
                let m = s.machine().unwrap();
                let q: Vec<f64> = m
                    .axes
                    .iter()
                    .zip(&u)
                    .map(|(a, u)| if a.is_rotary() { 20.0 * u } else { 2000.0 * u })
                    .collect();
                let band = Vector3::new(b[0], b[1], b[2] + 2.0);
                let normal = Vector3::new(b[3] + 2.0, b[4], b[5]);
                let t = Target {
                    x: 0.0,
                    point: Point3::new(p[0], p[1], p[2]),
                    path_point: Point3::new(p[0], p[1], p[2]),
                    band: Unit::new_normalize(band),
                    normal: Unit::new_normalize(normal),
                    free_length: 0.0,
                    clearance_margin: 0.0,
                };
                let unknowns: Vec<usize> = (0..m.axes.len()).collect();
                let mv = moves(&m);
                let fk = Fk::new(&m);
                let e = Equations::new(&m, &t, &unknowns, &mv, &fk, &q).eval(false);
                let pos = (e.r[0] * e.r[0] + e.r[1] * e.r[1] + e.r[2] * e.r[2]).sqrt();
                let ori = e.r[3..]
                    .iter()
                    .map(|v| (v / ORIENTATION_SCALE).abs())
                    .fold(0.0, f64::max);
                let chain = Chain::new(&m, &[m.points[m.roles.payout].link, m.roles.mandrel]);
                let mut frames = Vec::new();
                chain.frames_into(&q, &mut frames);
                let (p2, o2) = point_residuals(&m, orientation_rows(&m), &frames, &t);
                proptest::prop_assert!((p2 - pos).abs() < 1e-9, "{}: {p2} vs {pos}", s.name);
                proptest::prop_assert!((o2 - ori).abs() < 1e-12, "{}: {o2} vs {ori}", s.name);
            }
        }
    }

    proptest::proptest! {
        /// The closed form recovers random axis values of the lathe-type
        /// shipped winders from the target the reference forward kinematics
        /// gives there (the eye's point, a band across the roller), within
        /// 1e-9 mm and 1e-12 rad.
        #[test]
        fn closed_form_inverts_the_reference_kinematics(
            u in proptest::collection::vec(-1.0..1.0_f64, 4),
            d in proptest::collection::vec(-1.0..1.0_f64, 3),
        ) {
            for s in crate::shipped::SHIPPED {
                let m = s.machine().unwrap();
                let Some(lathe) = Lathe::detect(&m, Spindle::new(&m).unwrap()) else {
                    continue;
                };
                let q: Vec<f64> = m
                    .axes
                    .iter()
                    .zip(&u)
                    .map(|(a, u)| match a.kind {
                        JointKind::Revolute if Some(a.link) == m.roles.spindle.map(|s| m.axes[s].link) => 20.0 * u,
                        JointKind::Revolute => 1.5 * u,
                        _ => a.home + 0.5 * (a.max - a.min).min(1000.0) * (u + 1.0) / 2.0,
                    })
                    .collect();
                let poses = m.poses(&q);
                let mandrel = poses[m.roles.mandrel];
                let payout = &m.points[m.roles.payout];
                let p = poses[payout.link] * payout.position;
                // A band across the roller (any band where the machine has no eye axis).
                let across = m.roles.roller_axis.map_or(Vector3::new(d[0], d[1], d[2]), |a| {
                    (poses[payout.link].rotation * a.into_inner()).cross(&Vector3::new(d[0], d[1], d[2]))
                });
                proptest::prop_assume!(across.norm() > 1e-3);
                let band = mandrel.rotation.inverse() * across;
                let point = mandrel.inverse_transform_point(&p);
                let t = Target {
                    x: 0.0,
                    point,
                    path_point: point,
                    band: Unit::new_normalize(band),
                    normal: Unit::new_normalize(band.cross(&Vector3::new(1.0, 2.0, 3.0))),
                    free_length: 0.0,
                    clearance_margin: 0.0,
                };
                let mut got = q.clone();
                lathe.solve(&t, &q, &mut got);
                for (a, (g, w)) in m.axes.iter().zip(got.iter().zip(&q)) {
                    let tol = if a.is_rotary() { 1e-12 } else { 1e-9 };
                    proptest::prop_assert!((g - w).abs() < tol, "{}: {got:?} vs {q:?}", s.name);
                }
            }
        }
    }

    /// A placement head pressing along `+m` (outward) meets the two rows of
    /// pressing across the band, but is no solution: its residual is 2
    /// (pressing along `-m`: 0).
    #[test]
    fn a_head_pressing_outward_is_no_solution() {
        let m = crate::shipped::shipped("placement-arm")
            .unwrap()
            .machine()
            .unwrap();
        let q = m.home();
        let poses = m.poses(&q);
        let head = poses[m.points[m.roles.payout].link];
        let mandrel = poses[m.roles.mandrel];
        let to_mandrel = |v: Vector3<f64>| mandrel.rotation.inverse() * (head.rotation * v);
        let press = to_mandrel(m.roles.head_normal.unwrap().into_inner());
        let roller = to_mandrel(m.roles.roller_axis.unwrap().into_inner());
        let point = mandrel.inverse_transform_point(&(head * m.points[m.roles.payout].position));
        let chain = Chain::new(&m, &[m.points[m.roles.payout].link, m.roles.mandrel]);
        let mut frames = Vec::new();
        chain.frames_into(&q, &mut frames);
        for (sign, want) in [(-1.0, 0.0), (1.0, 2.0)] {
            let t = Target {
                x: 0.0,
                point,
                path_point: point,
                band: Unit::new_normalize(roller.cross(&press)),
                normal: Unit::new_normalize(sign * press),
                free_length: 0.0,
                clearance_margin: 0.0,
            };
            let (pos, ori) = point_residuals(&m, orientation_rows(&m), &frames, &t);
            assert!(
                pos < 1e-9 && (ori - want).abs() < 1e-9,
                "{sign}: {pos} {ori}"
            );
        }
    }

    /// The names `summary.json` and `[checks] allow` know.
    #[test]
    fn issue_kinds_keep_their_names_in_files_and_messages() {
        let kinds = [
            (IssueKind::Limit, "limit"),
            (IssueKind::Unreachable, "unreachable"),
            (IssueKind::Clearance, "clearance"),
            (IssueKind::Jump, "jump"),
        ];
        for (k, name) in kinds {
            assert_eq!(k.to_string(), name);
            assert_eq!(format!("{k:<12}|"), format!("{name:<12}|"));
            assert_eq!(serde_json::to_value(k).unwrap(), name);
        }
    }
}
