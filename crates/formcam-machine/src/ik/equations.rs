//! The equations at one target (eq. 2): the position rows and the
//! orientation rows, their residuals and Jacobian, as a least-squares
//! problem.

use std::cell::RefCell;

use levenberg_marquardt::LeastSquaresProblem;
use nalgebra::{DMatrix, DVector, Dyn, Isometry3, Owned, Point3, Vector3};

use super::{ORIENTATION_SCALE, joint_axis};
use crate::file::MachineKind;
use crate::{Fk, JointKind, Machine, Target};

/// The equations at one target for the axes `q` (only those in `unknowns` move).
pub(super) struct Equations<'a> {
    m: &'a Machine,
    t: &'a Target,
    /// The axes that move.
    pub(super) unknowns: &'a [usize],
    /// The axis values.
    pub(super) q: Vec<f64>,
    /// Per axis: whether it moves the payout point's link, the mandrel's link.
    moves: &'a [(bool, bool)],
    /// The forward kinematics (every link the equations read).
    fk: &'a Fk,
    /// Link poses, reused between evaluations.
    poses: RefCell<Vec<Isometry3<f64>>>,
}

/// Per axis: whether it moves the payout point's link and the mandrel's link.
pub(super) fn moves(m: &Machine) -> Vec<(bool, bool)> {
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
pub(super) fn orientation_rows(m: &Machine) -> usize {
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
pub(super) struct Residuals {
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
pub(super) struct Evaluated {
    /// The residuals.
    pub(super) r: Residuals,
    /// Their Jacobian, when asked.
    pub(super) jac: Option<DMatrix<f64>>,
}

impl<'a> Equations<'a> {
    /// The equations at `t` from the axis values `q`.
    pub(super) fn new(
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

    /// The residuals at the axis values, with their Jacobian when asked.
    pub(super) fn eval(&self, with_jacobian: bool) -> Evaluated {
        let mut buf = self.poses.borrow_mut();
        self.fk.poses_into(&self.q, &mut buf);
        let poses: &[Isometry3<f64>] = &buf;
        let at = World::at(self.m, self.t, poses);
        let rows = orientation_rows(self.m);
        let r = at.residuals(self.m.roles.kind, rows);
        let jac = with_jacobian.then(|| self.jacobian(poses, &at, rows, r.len()));
        Evaluated { r, jac }
    }

    /// The Jacobian of the `n` residuals: a column per unknown.
    fn jacobian(
        &self,
        poses: &[Isometry3<f64>],
        at: &World,
        rows: usize,
        n: usize,
    ) -> DMatrix<f64> {
        let mut j = DMatrix::zeros(n, self.unknowns.len());
        for (c, &ax) in self.unknowns.iter().enumerate() {
            self.column(poses, at, rows, ax, &mut j, c);
        }
        j
    }

    /// Column `c` of the Jacobian `j`: the residuals' derivatives by axis `ax`.
    fn column(
        &self,
        poses: &[Isometry3<f64>],
        at: &World,
        rows: usize,
        ax: usize,
        j: &mut DMatrix<f64>,
        c: usize,
    ) {
        let m = self.m;
        let (o, w) = joint_axis(m, poses, m.axes[ax].link);
        let motion = Motion {
            o,
            w,
            rev: m.axes[ax].kind == JointKind::Revolute,
        };
        let (moves_head, moves_mandrel) = self.moves[ax];
        let (band, normal, side) = (&at.band, &at.normal, &at.side);
        let dp = motion.point(&at.p, moves_head) - motion.point(&at.target, moves_mandrel);
        j[(0, c)] = dp.x;
        j[(1, c)] = dp.y;
        j[(2, c)] = dp.z;
        let d_band = motion.direction(band, moves_mandrel);
        let d_normal = motion.direction(normal, moves_mandrel);
        let s = ORIENTATION_SCALE;
        let mut row = 3;
        let mut put = |v: f64| {
            j[(row, c)] = s * v;
            row += 1;
        };
        match m.roles.kind {
            MachineKind::Winder => {
                if let Some(a) = at.roller {
                    let da = motion.direction(&a, moves_head);
                    if rows >= 1 {
                        put(da.dot(band) + a.dot(&d_band));
                    }
                    if rows >= 2 {
                        put(da.dot(normal) + a.dot(&d_normal));
                    }
                }
            }
            MachineKind::Placement => {
                let n = at.press.unwrap_or_else(Vector3::z);
                let dn = motion.direction(&n, moves_head);
                let d_side = d_normal.cross(band) + normal.cross(&d_band);
                put(dn.dot(band) + n.dot(&d_band));
                put(dn.dot(side) + n.dot(&d_side));
                put(dn.dot(normal) + n.dot(&d_normal));
                if let Some(a) = at.roller {
                    let da = motion.direction(&a, moves_head);
                    put(da.dot(band) + a.dot(&d_band));
                }
            }
        }
    }
}

/// What the equations compare, in the world frame at the axis values.
struct World {
    /// The payout point.
    p: Point3<f64>,
    /// The target point.
    target: Point3<f64>,
    /// The target's band direction.
    band: Vector3<f64>,
    /// The mandrel's normal at the target.
    normal: Vector3<f64>,
    /// The roller's axis, where the machine has one.
    roller: Option<Vector3<f64>>,
    /// The head's pressing direction, where the machine has one.
    press: Option<Vector3<f64>>,
    /// Across the band on the surface: `normal × band`.
    side: Vector3<f64>,
}

impl World {
    /// The world quantities of `m` at `t` for the link poses `poses`.
    fn at(m: &Machine, t: &Target, poses: &[Isometry3<f64>]) -> Self {
        let roles = &m.roles;
        let payout = &m.points[roles.payout];
        let head = poses[payout.link];
        let mandrel = poses[roles.mandrel];
        let p = head * payout.position;
        let target = mandrel * t.point;
        let band = mandrel.rotation * t.band.into_inner();
        let normal = mandrel.rotation * t.normal.into_inner();
        let roller = roles.roller_axis.map(|a| head.rotation * a.into_inner());
        let press = roles.head_normal.map(|a| head.rotation * a.into_inner());
        let side = normal.cross(&band);
        Self {
            p,
            target,
            band,
            normal,
            roller,
            press,
            side,
        }
    }

    /// The residuals: the position's, then `rows` orientation rows of a
    /// machine of `kind`, scaled by [`ORIENTATION_SCALE`].
    fn residuals(&self, kind: MachineKind, rows: usize) -> Residuals {
        let (p, target, band, normal) = (&self.p, &self.target, &self.band, &self.normal);
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
        match kind {
            MachineKind::Winder => {
                if let Some(a) = self.roller {
                    if rows >= 1 {
                        r.push(s * a.dot(band));
                    }
                    if rows >= 2 {
                        r.push(s * a.dot(normal));
                    }
                }
            }
            MachineKind::Placement => {
                let n = self.press.unwrap_or_else(Vector3::z);
                r.push(s * n.dot(band));
                r.push(s * n.dot(&self.side));
                // Zero where the head presses along `-m`, 2 where along `+m`
                // (which the two rows above allow too).
                r.push(s * (1.0 + n.dot(normal)));
                if let Some(a) = self.roller {
                    r.push(s * a.dot(band));
                }
            }
        }
        r
    }
}

/// The motion of one axis's joint: a turn about, or a slide along, `w`
/// through `o`.
struct Motion {
    /// A point on the joint's line.
    o: Point3<f64>,
    /// The joint's direction.
    w: Vector3<f64>,
    /// Whether it turns.
    rev: bool,
}

impl Motion {
    /// The derivative of the point `x`, carried by the joint when `moved`.
    fn point(&self, x: &Point3<f64>, moved: bool) -> Vector3<f64> {
        if !moved {
            Vector3::zeros()
        } else if self.rev {
            self.w.cross(&(x - self.o))
        } else {
            self.w
        }
    }

    /// The derivative of the direction `d`, carried by the joint when `moved`.
    fn direction(&self, d: &Vector3<f64>, moved: bool) -> Vector3<f64> {
        if moved && self.rev {
            self.w.cross(d)
        } else {
            Vector3::zeros()
        }
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
