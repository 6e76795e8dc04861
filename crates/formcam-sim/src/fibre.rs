//! Where the free fibre is at each time of a winding program: from the
//! payout point (forward kinematics of the program's axes) to its contact
//! point on the mandrel, which the program does not hold: the planner hands
//! each wound layer's circuit on ([`WoundCircuit`]).
//!
//! The contact point is found by the mandrel's angle: within a layer the
//! spindle turns one way, so the program's spindle angle at a time, less the
//! layer's turn (measured where the program starts the layer) and the turns
//! of the circuits before, is the angle of one planned row of the layer's
//! circuit, and that row's path point is the contact point. Where the
//! spindle stands still over several rows (a hoop's end, a dwell) the row
//! is the one whose eye is nearest the program's payout point, in the
//! path's own order.

use formcam_geom::Meridian;
use formcam_machine::{AxisTrack, Fk, JointKind, Machine, MachineKind, Target};
use formcam_winding::job::Mandrel;
use nalgebra::{Isometry3, Point3};

use crate::{SimError, Timeline};

/// One wound layer as the fibre check needs it: the planned circuit (axes,
/// path points and eye points per row) and the surface it is laid on.
#[derive(Debug, Clone)]
pub struct FibreLayer {
    /// The layer's label (`layer 2 (helical)`).
    pub label: String,
    /// The surface the layer is laid on: the mandrel grown by the layers
    /// before (its `z = 0` at [`FibreLayer::z_shift`] on the machine's
    /// mandrel).
    pub mandrel: Mandrel,
    /// Where the surface's `z = 0` lies in the machine's mandrel frame, mm.
    pub z_shift: f64,
    /// The spindle angle of each row of the first circuit, NC degrees.
    spindle_deg: Vec<f64>,
    /// The path point of each row, the machine's mandrel frame, mm.
    contacts: Vec<Point3<f64>>,
    /// The eye of each row, the machine's mandrel frame, mm.
    eyes: Vec<Point3<f64>>,
    /// The first circuit's axes at its start (NC units).
    start: Vec<f64>,
    /// Circuits in the layer.
    circuits: u32,
    /// The spindle's turn over one circuit, degrees.
    circuit_turn_deg: f64,
}

impl FibreLayer {
    /// Rows in one circuit.
    pub fn rows(&self) -> usize {
        self.contacts.len()
    }

    /// The planned path point (contact) of row `k` of the first circuit,
    /// mandrel frame.
    pub fn contact(&self, k: usize) -> Option<Point3<f64>> {
        self.contacts.get(k).copied()
    }

    /// The planned eye of row `k` of the first circuit, mandrel frame.
    pub fn eye(&self, k: usize) -> Option<Point3<f64>> {
        self.eyes.get(k).copied()
    }

    /// The surface's clearance of a point `p` of the mandrel frame: its
    /// radial distance outside the surface of revolution over
    /// `sqrt(1 + r'²)` (the distance along the normal to first order); `None`
    /// beyond the surface's ends.
    pub fn gap(&self, p: &Point3<f64>) -> Option<f64> {
        let z = p.z - self.z_shift;
        let (lo, hi) = self.mandrel.z_range();
        if !(lo..=hi).contains(&z) {
            return None;
        }
        let j = self.mandrel.eval(z);
        let dr = if j.dr.is_finite() { j.dr } else { 0.0 };
        Some((p.x.hypot(p.y) - j.r) / (1.0 + dr * dr).sqrt())
    }

    /// The total spindle turn of the layer, degrees (signed).
    fn total_turn_deg(&self) -> f64 {
        f64::from(self.circuits) * self.circuit_turn_deg
    }
}

/// One wound layer's planned circuit as the planner hands it to the fibre:
/// what it was laid on and what the machine was asked to reach.
#[derive(Debug, Clone, Copy)]
pub struct WoundCircuit<'a> {
    /// The layer's label (`layer 2 (helical)`).
    pub label: &'a str,
    /// The surface the layer is laid on (the mandrel grown by the layers
    /// before).
    pub mandrel: &'a Mandrel,
    /// Where the surface's `z = 0` lies in the machine's mandrel frame, mm.
    pub z_shift: f64,
    /// The circuit's targets, one per row.
    pub targets: &'a [Target],
    /// The circuit's axes, one row per target (`None`: planned without the
    /// machine's axes).
    pub track: Option<&'a AxisTrack>,
    /// Circuits in the layer.
    pub circuits: u32,
}

/// The free fibre of a winding job on its machine: every wound layer's
/// planned circuit, in winding order.
#[derive(Debug, Clone)]
pub struct FreeFibre {
    machine: Machine,
    spindle: usize,
    layers: Vec<FibreLayer>,
}

/// Where the fibre is at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FibreState {
    /// The layer (index into [`FreeFibre::layers`]).
    pub layer: usize,
    /// The circuit (0-based).
    pub circuit: u32,
    /// The planned row before the contact, and how far towards the next.
    pub row: usize,
    /// The fraction between `row` and `row + 1`.
    pub fraction: f64,
    /// The payout point, world, mm.
    pub payout: Point3<f64>,
    /// The contact point on the mandrel, world, mm.
    pub contact: Point3<f64>,
    /// The payout point in the mandrel frame of the planned circuit, mm.
    pub payout_mandrel: Point3<f64>,
    /// The contact point in that frame, on the surface, mm.
    pub contact_mandrel: Point3<f64>,
    /// The planned eye there, in that frame, mm.
    pub planned_eye_mandrel: Point3<f64>,
}

impl FibreState {
    /// The free length, mm.
    pub fn length(&self) -> f64 {
        (self.payout - self.contact).norm()
    }
}

/// Which layer each block of a timeline winds, and the layer's turn there.
#[derive(Debug, Clone, PartialEq)]
pub struct FibreTrack {
    /// Per block: `(layer, turn)` (the program's spindle angle less the
    /// planned one at the layer's start, degrees), or `None` where no layer
    /// is being wound (moves between layers, skip layers, rapids).
    pub blocks: Vec<Option<(usize, f64)>>,
}

impl FreeFibre {
    /// A fibre on the winder `machine` with no layer yet ([`FreeFibre::add`]
    /// takes them in winding order).
    pub fn new(machine: Machine) -> Result<Self, SimError> {
        if machine.roles.kind != MachineKind::Winder {
            return Err(SimError::Fibre {
                what: format!(
                    "{} is not a winder: a placement head has no free fibre",
                    machine.name
                ),
            });
        }
        let spindle = machine.roles.spindle.ok_or_else(|| SimError::Fibre {
            what: format!("{} has no spindle", machine.name),
        })?;
        Ok(Self {
            machine,
            spindle,
            layers: Vec::new(),
        })
    }

    /// The next wound layer of the program, planned to its program on this
    /// fibre's machine: its first circuit's rows (skip layers are not
    /// handed on).
    pub fn add(&mut self, l: &WoundCircuit<'_>) -> Result<(), SimError> {
        let (machine, spindle) = (&self.machine, self.spindle);
        let nc = |a: usize, v: f64| {
            if machine.axes[a].kind == JointKind::Revolute {
                v.to_degrees()
            } else {
                v
            }
        };
        let Some(track) = l.track else {
            return Err(SimError::Fibre {
                what: format!("{}: planned without the machine's axes", l.label),
            });
        };
        let n = l.targets.len();
        if n < 2 || track.values.len() != n * track.width {
            return Err(SimError::Fibre {
                what: format!("{}: fewer than two planned points", l.label),
            });
        }
        let spindle_deg: Vec<f64> = track.rows().map(|r| nc(spindle, r[spindle])).collect();
        let start: Vec<f64> = track
            .row(0)
            .iter()
            .enumerate()
            .map(|(a, v)| nc(a, *v))
            .collect();
        let circuit_turn_deg = spindle_deg[n - 1] - spindle_deg[0];
        if circuit_turn_deg == 0.0 {
            return Err(SimError::Fibre {
                what: format!("{}: the spindle does not turn over a circuit", l.label),
            });
        }
        self.layers.push(FibreLayer {
            label: l.label.to_string(),
            mandrel: l.mandrel.clone(),
            z_shift: l.z_shift,
            spindle_deg,
            contacts: l.targets.iter().map(|t| t.path_point).collect(),
            eyes: l.targets.iter().map(|t| t.point).collect(),
            start,
            circuits: l.circuits.max(1),
            circuit_turn_deg,
        });
        Ok(())
    }

    /// The same fibre on `machine` (the job's machine with other solids, or
    /// the one a program is checked on): its axes, links and key points must
    /// be the job's machine's, in the same order.
    pub fn with_machine(mut self, machine: Machine) -> Result<Self, SimError> {
        let same = |a: &Machine, b: &Machine| {
            a.axes.len() == b.axes.len()
                && a.axes.iter().zip(&b.axes).all(|(x, y)| x.name == y.name)
                && a.links.len() == b.links.len()
                && a.points.len() == b.points.len()
                && a.roles.mandrel == b.roles.mandrel
                && a.roles.payout == b.roles.payout
                && a.roles.spindle == b.roles.spindle
        };
        if !same(&self.machine, &machine) {
            return Err(SimError::Fibre {
                what: format!(
                    "the job was planned on {}, whose axes, links or roles are not {}'s",
                    self.machine.name, machine.name
                ),
            });
        }
        self.machine = machine;
        Ok(self)
    }

    /// The machine the job was planned on.
    pub fn machine(&self) -> &Machine {
        &self.machine
    }

    /// The wound layers, in winding order.
    pub fn layers(&self) -> &[FibreLayer] {
        &self.layers
    }

    /// Which layer each block of `tl` winds: the program is followed block
    /// by block; a layer starts at the first feed block that starts where
    /// the layer's first circuit starts (every axis but the spindle within
    /// twice the written resolution), its turn the program's spindle angle
    /// there less the planned one, and ends at the block whose end has
    /// turned the spindle through all its circuits.
    pub fn follow(&self, tl: &Timeline) -> Result<FibreTrack, SimError> {
        let names_match = tl.axes().len() == self.machine.axes.len()
            && tl
                .axes()
                .iter()
                .zip(&self.machine.axes)
                .all(|(a, m)| a.name == m.name);
        if !names_match {
            return Err(SimError::Fibre {
                what: format!(
                    "the program's axes ({}) are not the job's machine's ({})",
                    tl.axes()
                        .iter()
                        .map(|a| a.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                    self.machine
                        .axes
                        .iter()
                        .map(|a| a.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            });
        }
        let s = self.spindle;
        let tol: Vec<f64> = tl
            .axes()
            .iter()
            .map(|a| 2.0 * crate::limits::resolution(a.rotary) + 1e-9)
            .collect();
        let mut blocks = vec![None; tl.len()];
        let mut layer = 0;
        let mut inside: Option<f64> = None;
        for b in tl.blocks() {
            let Some(l) = self.layers.get(layer) else {
                break;
            };
            if inside.is_none()
                && b.kind == formcam_nc::Motion::Linear
                && !b.dwell
                && b.from
                    .iter()
                    .zip(&l.start)
                    .zip(&tol)
                    .enumerate()
                    .all(|(a, ((p, q), t))| a == s || (p - q).abs() <= *t)
            {
                inside = Some(b.from[s] - l.spindle_deg[0]);
            }
            let Some(turn) = inside else {
                continue;
            };
            blocks[b.index] = Some((layer, turn));
            let total = l.total_turn_deg();
            let done = (b.to[s] - turn - l.spindle_deg[0]) * total.signum();
            if done >= total.abs() - tol[s] {
                inside = None;
                layer += 1;
            }
        }
        Ok(FibreTrack { blocks })
    }

    /// A sampler of the fibre along `tl` (followed as `track`).
    pub fn sampler<'a>(&'a self, tl: &'a Timeline, track: &'a FibreTrack) -> FibreSampler<'a> {
        FibreSampler {
            fibre: self,
            tl,
            track,
            fk: Fk::new(&self.machine),
            mandrel_fk: Fk::for_links(&self.machine, &[self.machine.roles.mandrel]),
            poses: Vec::new(),
            planned: Vec::new(),
            nc: vec![0.0; tl.axes().len()],
            q: vec![0.0; self.machine.axes.len()],
        }
    }
}

/// The fibre at any time of one timeline, with the buffers forward
/// kinematics reuses.
pub struct FibreSampler<'a> {
    fibre: &'a FreeFibre,
    tl: &'a Timeline,
    track: &'a FibreTrack,
    fk: Fk,
    /// The chain down to the mandrel link alone (the planned circuit's
    /// frame).
    mandrel_fk: Fk,
    poses: Vec<Isometry3<f64>>,
    planned: Vec<Isometry3<f64>>,
    nc: Vec<f64>,
    q: Vec<f64>,
}

impl FibreSampler<'_> {
    /// The world pose of every link at the last time sampled.
    pub fn link_poses(&self) -> &[Isometry3<f64>] {
        &self.poses
    }

    /// The fibre at `t` (s) within block `block` of the timeline, or `None`
    /// where that block winds no layer.
    pub fn at(&mut self, block: usize, t: f64) -> Option<FibreState> {
        let (li, turn) = (*self.track.blocks.get(block)?)?;
        let f = self.fibre;
        let layer = f.layers.get(li)?;
        let s = f.spindle;
        sample_block(self.tl, block, t, &mut self.nc);
        for ((q, v), a) in self.q.iter_mut().zip(&self.nc).zip(&f.machine.axes) {
            *q = if a.kind == JointKind::Revolute {
                v.to_radians()
            } else {
                *v
            };
        }
        self.fk.poses_into(&self.q, &mut self.poses);
        let payout = f.machine.points.get(f.machine.roles.payout).map(|p| {
            self.poses
                .get(p.link)
                .map_or(p.position, |pose| pose * p.position)
        })?;
        // The angle in the first circuit.
        let phi = self.nc[s] - turn;
        let rel = phi - layer.spindle_deg[0];
        let c = (rel / layer.circuit_turn_deg)
            .floor()
            .clamp(0.0, f64::from(layer.circuits - 1));
        let phi0 = phi - c * layer.circuit_turn_deg;
        // The planned circuit's mandrel frame.
        let spindle_q = self.q[s];
        self.q[s] = phi0.to_radians();
        self.mandrel_fk.poses_into(&self.q, &mut self.planned);
        self.q[s] = spindle_q;
        let frame = *self.planned.get(f.machine.roles.mandrel)?;
        let payout_m = frame.inverse_transform_point(&payout);
        let (row, fraction) = locate(layer, phi0, &payout_m);
        let lerp = |a: Point3<f64>, b: Point3<f64>| a + (b - a) * fraction;
        let next = (row + 1).min(layer.rows() - 1);
        let mut contact_m = lerp(layer.contacts[row], layer.contacts[next]);
        // Onto the surface: the chord between two path points lies inside.
        let z = contact_m.z - layer.z_shift;
        let (lo, hi) = layer.mandrel.z_range();
        let r = layer.mandrel.eval(z.clamp(lo, hi)).r;
        let rho = contact_m.x.hypot(contact_m.y);
        if rho > 0.0 && r.is_finite() {
            contact_m.x *= r / rho;
            contact_m.y *= r / rho;
        }
        Some(FibreState {
            layer: li,
            circuit: c as u32,
            row,
            fraction,
            payout,
            contact: frame * contact_m,
            payout_mandrel: payout_m,
            contact_mandrel: contact_m,
            planned_eye_mandrel: lerp(layer.eyes[row], layer.eyes[next]),
        })
    }
}

/// The axis values of block `block` of `tl` at `t` (linear within it).
fn sample_block(tl: &Timeline, block: usize, t: f64, out: &mut [f64]) {
    let Some(b) = tl.block(block) else {
        tl.sample_into(t, out);
        return;
    };
    let f = if b.duration_s > 0.0 {
        ((t - b.start_s) / b.duration_s).clamp(0.0, 1.0)
    } else {
        1.0
    };
    for ((o, p), q) in out.iter_mut().zip(b.from).zip(b.to) {
        *o = p + f * (q - p);
    }
}

/// The row before the first circuit's angle `phi` and the fraction towards
/// the next; where the spindle stands still over rows, the segment of eyes
/// nearest `payout` (mandrel frame).
fn locate(layer: &FibreLayer, phi: f64, payout: &Point3<f64>) -> (usize, f64) {
    let a = &layer.spindle_deg;
    let n = a.len();
    let sign = layer.circuit_turn_deg.signum();
    // Rows whose angle is at most phi (in the direction of the turn).
    let k = a
        .partition_point(|v| (v - phi) * sign <= 0.0)
        .clamp(1, n - 1)
        - 1;
    let (lo, hi) = (a[k], a[k + 1]);
    if (hi - lo).abs() > 1e-9 {
        return (k, ((phi - lo) / (hi - lo)).clamp(0.0, 1.0));
    }
    // Standing still: the run of rows at this angle.
    let mut first = k;
    while first > 0 && (a[first - 1] - lo).abs() <= 1e-9 {
        first -= 1;
    }
    let mut last = k + 1;
    while last + 1 < n && (a[last + 1] - lo).abs() <= 1e-9 {
        last += 1;
    }
    let mut best = (f64::INFINITY, k, 0.0);
    for j in first..last {
        let (p, q) = (layer.eyes[j], layer.eyes[j + 1]);
        let d = q - p;
        let len2 = d.norm_squared();
        let u = if len2 > 0.0 {
            ((payout - p).dot(&d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let dist = (p + d * u - payout).norm();
        if dist < best.0 {
            best = (dist, j, u);
        }
    }
    (best.1, best.2)
}
