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
