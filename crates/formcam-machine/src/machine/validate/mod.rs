//! A machine file checked into a [`Machine`]: errors name the link (or the
//! point, or `[machine]`) and the field.

use std::collections::HashMap;

use nalgebra::Point3;

use super::{Axis, KeyPoint, Link, Machine, Roles};
use crate::MachineError;
use crate::file::{MachineFile, MachineKind, SpindleFollows};

mod joint;
mod numbers;
mod placement;
mod visual;

use joint::joint;
use numbers::{finite, unit};
pub(crate) use visual::visual;

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
}

pub(crate) fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}
