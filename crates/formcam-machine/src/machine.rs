//! The validated machine: a tree of links, its driven axes, key points and solids.

use std::collections::HashMap;
use std::fmt::Write as _;

use nalgebra::{Isometry3, Point3, Translation3, Unit, UnitQuaternion, Vector3};

use crate::MachineError;
use crate::collision::Collision;
use crate::file::{
    DhSpec, JointType, LinkSpec, MachineFile, MachineKind, OriginSpec, SpindleFollows, VisualSpec,
};

/// How a joint moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointKind {
    /// Turns about its direction, rad.
    Revolute,
    /// Slides along its direction, mm.
    Prismatic,
    /// Rigid.
    Fixed,
}

/// The joint between a link and its parent: `pre * motion(q) * post`.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Type.
    pub kind: JointKind,
    /// Transform before the motion (a plain origin; identity for DH).
    pub pre: Isometry3<f64>,
    /// Direction of the motion in the frame after `pre`.
    pub direction: Unit<Vector3<f64>>,
    /// Transform after the motion (the DH part; identity for a plain origin).
    pub post: Isometry3<f64>,
    /// Index into [`Machine::axes`] when driven.
    pub axis: Option<usize>,
    /// The value of an undriven joint (rad or mm).
    pub value: f64,
    /// Whether `post` is the identity (a plain origin), so its product is skipped.
    plain: bool,
    /// Whether `pre` is the identity (DH parameters).
    dh: bool,
}

impl Joint {
    /// The joint's transform for the joint value `q` (rad or mm).
    #[inline]
    pub fn transform(&self, q: f64) -> Isometry3<f64> {
        let motion = match self.kind {
            JointKind::Revolute => Isometry3::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&self.direction, q),
            ),
            JointKind::Prismatic => Isometry3::from_parts(
                Translation3::from(self.direction.into_inner() * q),
                UnitQuaternion::identity(),
            ),
            JointKind::Fixed => return self.pre * self.post,
        };
        // One side is the identity (DH: `pre`; a plain origin: `post`).
        if self.plain {
            self.pre * motion
        } else if self.dh {
            motion * self.post
        } else {
            self.pre * motion * self.post
        }
    }
}

/// A solid for the viewer.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A box with edge lengths, centred on the origin, mm.
    Box([f64; 3]),
    /// A cylinder along local `z`, centred on the origin.
    Cylinder {
        /// Radius, mm.
        radius: f64,
        /// Length, mm.
        length: f64,
    },
    /// A sphere, mm.
    Sphere(f64),
    /// An STL or OBJ mesh, the path as written in the machine file
    /// (relative to it; read by [`crate::read_mesh`] when needed).
    Mesh(String),
}

/// A solid placed in a link's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Visual {
    /// The solid.
    pub shape: Shape,
    /// Its placement in the link's frame.
    pub origin: Isometry3<f64>,
    /// Colour `#rrggbb`.
    pub color: String,
    /// A mesh's factor per axis (its vertices as read times this; 1 for
    /// other shapes).
    pub scale: [f64; 3],
}

/// A link.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Name.
    pub name: String,
    /// Parent index (links are ordered parents first); none for the base.
    pub parent: Option<usize>,
    /// The joint to the parent.
    pub joint: Joint,
    /// Solids.
    pub visuals: Vec<Visual>,
}

/// A driven axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// NC address.
    pub name: String,
    /// The link it moves.
    pub link: usize,
    /// Revolute (rad) or prismatic (mm).
    pub kind: JointKind,
    /// Lower limit (rad or mm; `-inf` when unlimited).
    pub min: f64,
    /// Upper limit.
    pub max: f64,
    /// Velocity limit, rad/s or mm/s (`inf` when not given).
    pub v_max: f64,
    /// Velocity-jump limit between blocks, rad/s or mm/s.
    pub dv_max: f64,
    /// Acceleration limit, rad/s² or mm/s² (`inf` when not given).
    pub a_max: f64,
    /// Home value (rad or mm), where inverse kinematics starts.
    pub home: f64,
    /// The controller holds the axis within a turn (a modulo rotary axis;
    /// the machine file's `modulo`, by default the unlimited spindle).
    pub modulo: bool,
}

impl Axis {
    /// Whether the axis turns (its values are angles).
    pub fn is_rotary(&self) -> bool {
        self.kind == JointKind::Revolute
    }
}

/// A point fixed to a link.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyPoint {
    /// Name.
    pub name: String,
    /// Link.
    pub link: usize,
    /// Position in the link's frame, mm.
    pub position: Point3<f64>,
}

/// What the chain is for: the roles the inverse kinematics needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Roles {
    /// Winder or placement head.
    pub kind: MachineKind,
    /// The link carrying the mandrel frame.
    pub mandrel: usize,
    /// The axis turning the mandrel.
    pub spindle: Option<usize>,
    /// What the spindle keeps facing the head.
    pub spindle_follows: SpindleFollows,
    /// The payout point (or roller centre), an index into the key points.
    pub payout: usize,
    /// Roller axis, fixed to the payout point's link.
    pub roller_axis: Option<Unit<Vector3<f64>>>,
    /// Placement: the head's pressing direction, fixed to the payout point's link.
    pub head_normal: Option<Unit<Vector3<f64>>>,
    /// Placement: the compaction roller's radius, mm.
    pub roller_radius: f64,
    /// The band path's key points from the creel to the payout point.
    pub band_path: Vec<usize>,
}

/// A machine: links (parents before children), driven axes, key points, roles.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    /// Its name.
    pub name: String,
    /// Links, the base first.
    pub links: Vec<Link>,
    /// Driven axes, in the order of the file.
    pub axes: Vec<Axis>,
    /// Key points.
    pub points: Vec<KeyPoint>,
    /// Roles for the kinematics.
    pub roles: Roles,
    /// How the simulator checks its solids for collisions.
    pub collision: Collision,
}

fn iso(o: &OriginSpec) -> Isometry3<f64> {
    let [r, p, y] = o.rpy_deg.map(f64::to_radians);
    Isometry3::from_parts(
        Translation3::new(o.xyz[0], o.xyz[1], o.xyz[2]),
        UnitQuaternion::from_euler_angles(r, p, y),
    )
}

fn dh_post(dh: &DhSpec) -> Isometry3<f64> {
    let rz = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), dh.theta_deg.to_radians());
    let rx = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), dh.alpha_deg.to_radians());
    Isometry3::from_parts(Translation3::identity(), rz)
        * Isometry3::translation(dh.a, 0.0, dh.d)
        * Isometry3::from_parts(Translation3::identity(), rx)
}

fn unit(v: [f64; 3], place: &str, field: &str) -> Result<Unit<Vector3<f64>>, MachineError> {
    let v = Vector3::from(v);
    if v.iter().all(|c| c.is_finite()) && v.norm() > 1e-12 {
        Ok(Unit::new_normalize(v))
    } else {
        Err(MachineError::field(
            place,
            field,
            "must be a finite non-zero vector [x, y, z]",
        ))
    }
}

fn finite(v: f64, place: &str, field: &str) -> Result<f64, MachineError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(MachineError::field(place, field, "must be a finite number"))
    }
}

fn positive(v: Option<f64>, place: &str, field: &str) -> Result<f64, MachineError> {
    match v {
        None => Ok(f64::INFINITY),
        Some(v) if v.is_finite() && v > 0.0 => Ok(v),
        Some(v) => Err(MachineError::field(
            place,
            field,
            format!("must be a finite number > 0, got {v}"),
        )),
    }
}

pub(crate) fn visual(v: &VisualSpec, place: &str) -> Result<Visual, MachineError> {
    let need = |x: Option<f64>, field: &str| -> Result<f64, MachineError> {
        match x {
            Some(x) if x.is_finite() && x > 0.0 => Ok(x),
            Some(x) => Err(MachineError::field(
                place,
                format!("visual.{field}"),
                format!("must be a finite number > 0, got {x}"),
            )),
            None => Err(MachineError::field(
                place,
                format!("visual.{field}"),
                format!("missing for a {}", v.shape),
            )),
        }
    };
    let shape = match v.shape.as_str() {
        "box" => {
            let s = v.size.ok_or_else(|| {
                MachineError::field(place, "visual.size", "missing for a box: [x, y, z] in mm")
            })?;
            for c in s {
                need(Some(c), "size")?;
            }
            Shape::Box(s)
        }
        "cylinder" => Shape::Cylinder {
            radius: need(v.radius, "radius")?,
            length: need(v.length, "length")?,
        },
        "sphere" => Shape::Sphere(need(v.radius, "radius")?),
        "mesh" => Shape::Mesh(v.file.clone().ok_or_else(|| {
            MachineError::field(
                place,
                "visual.file",
                "missing for a mesh: an STL or OBJ file",
            )
        })?),
        other => {
            return Err(MachineError::field(
                place,
                "visual.shape",
                format!("unknown shape \"{other}\" (box, cylinder, sphere or mesh)"),
            ));
        }
    };
    let color = v.color.clone().unwrap_or_else(|| "#9aa4b1".to_string());
    let hex = color.strip_prefix('#').unwrap_or("");
    if hex.len() != 6 || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
        return Err(MachineError::field(
            place,
            "visual.color",
            format!("\"{color}\" is not a colour #rrggbb"),
        ));
    }
    let scale = match (v.scale, &shape) {
        (None, _) => [1.0; 3],
        (Some(s), Shape::Mesh(_)) => {
            for c in s {
                need(Some(c), "scale")?;
            }
            s
        }
        (Some(_), _) => {
            return Err(MachineError::field(
                place,
                "visual.scale",
                "only for a mesh",
            ));
        }
    };
    Ok(Visual {
        shape,
        origin: iso(&v.origin),
        color,
        scale,
    })
}

/// The joint of a link spec, with its axis when driven (its index still unset).
fn joint(l: &LinkSpec, place: &str) -> Result<(Joint, Option<Axis>), MachineError> {
    let kind = match l.joint.unwrap_or(JointType::Fixed) {
        JointType::Revolute => JointKind::Revolute,
        JointType::Prismatic => JointKind::Prismatic,
        JointType::Fixed => JointKind::Fixed,
    };
    let deg = [
        ("min_deg", l.min_deg),
        ("max_deg", l.max_deg),
        ("v_max_deg_min", l.v_max_deg_min),
        ("dv_max_deg_min", l.dv_max_deg_min),
        ("value_deg", l.value_deg),
        ("home_deg", l.home_deg),
        ("a_max_deg_s2", l.a_max_deg_s2),
    ];
    let mm = [
        ("min_mm", l.min_mm),
        ("max_mm", l.max_mm),
        ("v_max_mm_min", l.v_max_mm_min),
        ("dv_max_mm_min", l.dv_max_mm_min),
        ("value_mm", l.value_mm),
        ("home_mm", l.home_mm),
        ("a_max_mm_s2", l.a_max_mm_s2),
    ];
    let (wrong, own, why): (Vec<_>, [(&str, Option<f64>); 7], &str) = match kind {
        JointKind::Revolute => (mm.to_vec(), deg, "a revolute joint takes degrees (*_deg)"),
        JointKind::Prismatic => (deg.to_vec(), mm, "a prismatic joint takes mm (*_mm)"),
        JointKind::Fixed => (
            [deg, mm].concat(),
            deg,
            "a fixed joint has no limits or value",
        ),
    };
    if let Some((field, _)) = wrong.iter().find(|(_, v)| v.is_some()) {
        return Err(MachineError::field(place, *field, why));
    }
    // Degrees and per-minute rates become radians and per-second rates.
    let scale = if kind == JointKind::Revolute {
        1f64.to_radians()
    } else {
        1.0
    };
    let val = |i: usize| -> Result<Option<f64>, MachineError> {
        own[i]
            .1
            .map(|v| finite(v, place, own[i].0).map(|v| v * scale))
            .transpose()
    };
    let min = val(0)?.unwrap_or(f64::NEG_INFINITY);
    let max = val(1)?.unwrap_or(f64::INFINITY);
    if min > max {
        return Err(MachineError::field(
            place,
            own[0].0,
            format!(
                "{} > {} = {}: the lower limit must not exceed the upper",
                own[0].1.unwrap_or(0.0),
                own[1].0,
                own[1].1.unwrap_or(0.0)
            ),
        ));
    }
    let v_max = positive(own[2].1, place, own[2].0)? * scale / 60.0;
    let dv_max = positive(own[3].1, place, own[3].0)? * scale / 60.0;
    let a_max = positive(own[6].1, place, own[6].0)? * scale;
    let axis = match (l.driven, &l.axis) {
        (true, _) if kind == JointKind::Fixed => {
            return Err(MachineError::field(
                place,
                "driven",
                "a fixed joint cannot be driven (joint = \"revolute\" or \"prismatic\")",
            ));
        }
        (true, None) => {
            return Err(MachineError::field(
                place,
                "axis",
                "missing: the NC address of the driven joint (e.g. \"X\", \"A\")",
            ));
        }
        (true, Some(name)) => {
            if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric()) {
                return Err(MachineError::field(
                    place,
                    "axis",
                    format!("\"{name}\" is not an NC address (letters and digits)"),
                ));
            }
            if own[4].1.is_some() {
                return Err(MachineError::field(
                    place,
                    own[4].0,
                    "a driven joint has no fixed value",
                ));
            }
            let home = val(5)?.unwrap_or(0.0);
            if home < min || home > max {
                return Err(MachineError::field(
                    place,
                    own[5].0,
                    "must lie within the limits",
                ));
            }
            if l.modulo == Some(true) {
                if kind != JointKind::Revolute {
                    return Err(MachineError::field(
                        place,
                        "modulo",
                        "only a revolute joint turns modulo 360 degrees",
                    ));
                }
                if min.is_finite() || max.is_finite() {
                    return Err(MachineError::field(
                        place,
                        "modulo",
                        "a modulo axis turns without end: no min_deg or max_deg",
                    ));
                }
            }
            Some(Axis {
                name: name.clone(),
                link: 0,
                kind,
                min,
                max,
                v_max,
                dv_max,
                a_max,
                home,
                // The spindle's default is set once the spindle is known.
                modulo: l.modulo.unwrap_or(false),
            })
        }
        (false, Some(_)) => {
            return Err(MachineError::field(
                place,
                "axis",
                "given for a joint that is not driven (set driven = true)",
            ));
        }
        (false, None) => None,
    };
    if axis.is_none() && l.modulo.is_some() {
        return Err(MachineError::field(
            place,
            "modulo",
            "only a driven revolute joint is a modulo axis",
        ));
    }
    if axis.is_none() && own[5].1.is_some() {
        return Err(MachineError::field(
            place,
            own[5].0,
            "only a driven joint has a home value",
        ));
    }
    let value = val(4)?.unwrap_or(0.0);
    let (pre, direction, post) = match (&l.dh, &l.origin) {
        (Some(_), Some(_)) => {
            return Err(MachineError::field(
                place,
                "dh",
                "give either dh or origin, not both",
            ));
        }
        (Some(_), None) if l.direction.is_some() => {
            return Err(MachineError::field(
                place,
                "direction",
                "a DH joint moves about/along z; direction goes with origin",
            ));
        }
        (Some(dh), None) => {
            for (f, v) in [
                ("dh.a", dh.a),
                ("dh.alpha_deg", dh.alpha_deg),
                ("dh.d", dh.d),
                ("dh.theta_deg", dh.theta_deg),
            ] {
                finite(v, place, f)?;
            }
            (Isometry3::identity(), Vector3::z_axis(), dh_post(dh))
        }
        (None, o) => {
            let o = o.unwrap_or_default();
            for (i, v) in o.xyz.iter().chain(&o.rpy_deg).enumerate() {
                finite(
                    *v,
                    place,
                    if i < 3 {
                        "origin.xyz"
                    } else {
                        "origin.rpy_deg"
                    },
                )?;
            }
            let dir = match l.direction {
                Some(d) => unit(d, place, "direction")?,
                None => Vector3::z_axis(),
            };
            (iso(&o), dir, Isometry3::identity())
        }
    };
    Ok((
        Joint {
            kind,
            pre,
            direction,
            post,
            axis: None,
            value,
            plain: post == Isometry3::identity(),
            dh: pre == Isometry3::identity(),
        },
        axis,
    ))
}

impl Machine {
    /// Reads a machine from the text of a TOML machine file.
    pub fn from_toml(text: &str) -> Result<Self, MachineError> {
        let file: MachineFile = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((0, 0), |s| line_col(text, s.start));
            MachineError::Syntax {
                line,
                column,
                message: formcam_files::syntax_message(
                    e.message(),
                    text,
                    e.span().map_or(text.len(), |s| s.start),
                ),
            }
        })?;
        Self::from_file(&file)
    }

    /// Builds and checks a machine from its parsed file.
    pub fn from_file(f: &MachineFile) -> Result<Self, MachineError> {
        // Names, parents, the root.
        let mut index: HashMap<&str, usize> = HashMap::new();
        for (i, l) in f.links.iter().enumerate() {
            if l.name.is_empty() {
                return Err(MachineError::field(
                    format!("link #{}", i + 1),
                    "name",
                    "must not be empty",
                ));
            }
            if index.insert(l.name.as_str(), i).is_some() {
                return Err(MachineError::field(
                    format!("link \"{}\"", l.name),
                    "name",
                    "used by two links",
                ));
            }
        }
        let mut parent = vec![None; f.links.len()];
        for (i, l) in f.links.iter().enumerate() {
            if let Some(p) = &l.parent {
                let j = *index.get(p.as_str()).ok_or_else(|| {
                    MachineError::field(
                        format!("link \"{}\"", l.name),
                        "parent",
                        format!("no link is named \"{p}\""),
                    )
                })?;
                parent[i] = Some(j);
            }
        }
        let roots: Vec<usize> = (0..f.links.len())
            .filter(|&i| parent[i].is_none())
            .collect();
        match roots.as_slice() {
            [_] => {}
            [] if f.links.is_empty() => {
                return Err(MachineError::field(
                    "[machine]",
                    "link",
                    "no links: give at least the base ([[link]] without a parent)",
                ));
            }
            [] => {}
            [a, b, ..] => {
                return Err(MachineError::field(
                    format!("link \"{}\"", f.links[*b].name),
                    "parent",
                    format!(
                        "missing: only the base (\"{}\") has no parent",
                        f.links[*a].name
                    ),
                ));
            }
        }
        // Order parents first; links never reached lie on a cycle.
        let mut order = Vec::with_capacity(f.links.len());
        let mut placed = vec![false; f.links.len()];
        let mut frontier: Vec<usize> = roots.clone();
        while let Some(i) = frontier.pop() {
            placed[i] = true;
            order.push(i);
            for (j, p) in parent.iter().enumerate().rev() {
                if *p == Some(i) && !placed[j] {
                    frontier.push(j);
                }
            }
        }
        if let Some(i) = (0..f.links.len()).find(|&i| !placed[i]) {
            return Err(MachineError::field(
                format!("link \"{}\"", f.links[i].name),
                "parent",
                "the links form a cycle (a link is its own ancestor)",
            ));
        }
        let mut new_index = vec![0; f.links.len()];
        for (k, &i) in order.iter().enumerate() {
            new_index[i] = k;
        }
        let mut links = Vec::with_capacity(order.len());
        let mut axes: Vec<Axis> = Vec::new();
        // The file's link of each axis.
        let mut link_of_axis: Vec<usize> = Vec::new();
        for &i in &order {
            let l = &f.links[i];
            let place = format!("link \"{}\"", l.name);
            let (mut j, axis) = joint(l, &place)?;
            if let Some(mut a) = axis {
                if axes.iter().any(|b| b.name == a.name) {
                    return Err(MachineError::field(
                        place,
                        "axis",
                        format!("\"{}\" drives two joints", a.name),
                    ));
                }
                a.link = links.len();
                j.axis = Some(axes.len());
                axes.push(a);
                link_of_axis.push(i);
            }
            let visuals = l
                .visuals
                .iter()
                .map(|v| visual(v, &place))
                .collect::<Result<Vec<_>, _>>()?;
            links.push(Link {
                name: l.name.clone(),
                parent: parent[i].map(|p| new_index[p]),
                joint: j,
                visuals,
            });
        }
        let link_named = |name: &str, place: &str, field: &str| {
            links.iter().position(|l| l.name == name).ok_or_else(|| {
                MachineError::field(place, field, format!("no link is named \"{name}\""))
            })
        };
        let mut points = Vec::with_capacity(f.points.len());
        for p in &f.points {
            let place = format!("point \"{}\"", p.name);
            if points.iter().any(|q: &KeyPoint| q.name == p.name) {
                return Err(MachineError::field(place, "name", "used by two points"));
            }
            for v in p.xyz {
                finite(v, &place, "xyz")?;
            }
            points.push(KeyPoint {
                name: p.name.clone(),
                link: link_named(&p.link, &place, "link")?,
                position: Point3::from(p.xyz),
            });
        }
        let m = &f.machine;
        let place = "[machine]";
        let point_named = |name: &str, field: &str| {
            points.iter().position(|q| q.name == name).ok_or_else(|| {
                MachineError::field(place, field, format!("no point is named \"{name}\""))
            })
        };
        let payout = point_named(&m.payout, "payout")?;
        let spindle = match &m.spindle {
            None => None,
            Some(name) => {
                let i = axes.iter().position(|a| &a.name == name).ok_or_else(|| {
                    MachineError::field(
                        place,
                        "spindle",
                        format!("no driven axis is named \"{name}\""),
                    )
                })?;
                if !axes[i].is_rotary() {
                    return Err(MachineError::field(
                        place,
                        "spindle",
                        format!("axis \"{name}\" is prismatic; the spindle turns"),
                    ));
                }
                Some(i)
            }
        };
        // The spindle turns modulo 360 degrees unless the file says otherwise
        // or it has limits.
        if let Some(i) = spindle {
            let a = &mut axes[i];
            let given = f.links.get(link_of_axis[i]).and_then(|l| l.modulo);
            a.modulo = given.unwrap_or(a.min.is_infinite() && a.max.is_infinite());
        }
        let roller_radius = match (m.kind, m.roller_radius) {
            (MachineKind::Placement, Some(h)) if h.is_finite() && h > 0.0 => h,
            (MachineKind::Placement, _) => {
                return Err(MachineError::field(
                    place,
                    "roller_radius",
                    "a placement head needs the compaction roller's radius h > 0, mm",
                ));
            }
            (MachineKind::Winder, None) => 0.0,
            (MachineKind::Winder, Some(_)) => {
                return Err(MachineError::field(
                    place,
                    "roller_radius",
                    "only for kind = \"placement\"",
                ));
            }
        };
        let band_path = m
            .band_path
            .iter()
            .flatten()
            .map(|n| point_named(n, "band_path"))
            .collect::<Result<Vec<_>, _>>()?;
        if let Some(&last) = band_path.last()
            && last != payout
        {
            return Err(MachineError::field(
                place,
                "band_path",
                "must end at the payout point",
            ));
        }
        let roles = Roles {
            kind: m.kind,
            mandrel: link_named(&m.mandrel, place, "mandrel")?,
            spindle,
            spindle_follows: m.spindle_follows.unwrap_or(SpindleFollows::Eye),
            payout,
            roller_axis: m
                .roller_axis
                .map(|v| unit(v, place, "roller_axis"))
                .transpose()?,
            head_normal: m
                .head_normal
                .map(|v| unit(v, place, "head_normal"))
                .transpose()?,
            roller_radius,
            band_path,
        };
        if roles.kind == MachineKind::Placement && roles.head_normal.is_none() {
            return Err(MachineError::field(
                place,
                "head_normal",
                "a placement head needs the direction that presses into the mandrel",
            ));
        }
        let collision = crate::collision::settings(f.collision.as_ref(), &links)?;
        Ok(Machine {
            name: m.name.clone(),
            links,
            axes,
            points,
            roles,
            collision,
        })
    }

    /// The home axis values (rad or mm).
    pub fn home(&self) -> Vec<f64> {
        self.axes.iter().map(|a| a.home).collect()
    }

    /// Index of the axis with NC address `name`.
    pub fn axis(&self, name: &str) -> Option<usize> {
        self.axes.iter().position(|a| a.name == name)
    }

    /// World poses of every link for the axis values `q` (rad or mm, in the order
    /// of [`Machine::axes`]).
    pub fn poses(&self, q: &[f64]) -> Vec<Isometry3<f64>> {
        let mut out = Vec::with_capacity(self.links.len());
        self.poses_into(q, &mut out);
        out
    }

    /// [`Machine::poses`] into a buffer (cleared first), for repeated calls.
    pub fn poses_into(&self, q: &[f64], out: &mut Vec<Isometry3<f64>>) {
        out.clear();
        for l in &self.links {
            let v = l
                .joint
                .axis
                .map_or(l.joint.value, |a| q.get(a).copied().unwrap_or(0.0));
            let t = l.joint.transform(v);
            let pose = match l.parent {
                Some(p) => out[p] * t,
                None => t,
            };
            out.push(pose);
        }
    }

    /// World positions of every key point for the axis values `q`.
    pub fn key_points(&self, q: &[f64]) -> Vec<Point3<f64>> {
        let poses = self.poses(q);
        self.points
            .iter()
            .map(|p| poses[p.link] * p.position)
            .collect()
    }

    /// Whether link `a` is `b` or one of its ancestors.
    pub fn is_ancestor(&self, a: usize, b: usize) -> bool {
        let mut k = Some(b);
        while let Some(i) = k {
            if i == a {
                return true;
            }
            k = self.links[i].parent;
        }
        false
    }

    /// The chain as a readable table: links, joints, axes, limits, points.
    pub fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "machine: {} ({:?})", self.name, self.roles.kind);
        let _ = writeln!(
            s,
            "{:<16} {:<16} {:<10} {:<5} {:>12} {:>12} {:>12} {:>7}",
            "link", "parent", "joint", "axis", "min", "max", "v_max/min", "modulo"
        );
        for l in &self.links {
            let parent = l.parent.map_or("-", |p| self.links[p].name.as_str());
            let kind = match l.joint.kind {
                JointKind::Revolute => "revolute",
                JointKind::Prismatic => "prismatic",
                JointKind::Fixed => "fixed",
            };
            let (axis, lo, hi, v, modulo) = match l.joint.axis {
                Some(a) => {
                    let ax = &self.axes[a];
                    let (k, unit) = if ax.is_rotary() {
                        (1f64.to_degrees(), "deg")
                    } else {
                        (1.0, "mm")
                    };
                    let f = |x: f64| {
                        if x.is_finite() {
                            format!("{:.3} {unit}", x * k)
                        } else {
                            "none".to_string()
                        }
                    };
                    let modulo = match (ax.is_rotary(), ax.modulo) {
                        (false, _) => "-",
                        (true, true) => "yes",
                        (true, false) => "no",
                    };
                    (
                        ax.name.as_str(),
                        f(ax.min),
                        f(ax.max),
                        f(ax.v_max * 60.0),
                        modulo,
                    )
                }
                None => ("-", String::new(), String::new(), String::new(), ""),
            };
            let _ = writeln!(
                s,
                "{:<16} {:<16} {:<10} {:<5} {:>12} {:>12} {:>12} {:>7}",
                l.name, parent, kind, axis, lo, hi, v, modulo
            );
        }
        let _ = writeln!(s, "points:");
        for p in &self.points {
            let _ = writeln!(
                s,
                "  {:<14} on {:<14} at [{:.3}, {:.3}, {:.3}] mm",
                p.name, self.links[p.link].name, p.position.x, p.position.y, p.position.z
            );
        }
        let r = &self.roles;
        let _ = writeln!(
            s,
            "mandrel on \"{}\"; spindle {}; payout point \"{}\"",
            self.links[r.mandrel].name,
            r.spindle.map_or("none", |a| self.axes[a].name.as_str()),
            self.points[r.payout].name
        );
        s
    }
}

pub(crate) fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}
