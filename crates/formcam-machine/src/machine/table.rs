//! The machine as a readable table: links, joints, axes, limits, points.

use std::fmt::Write as _;

use super::{JointKind, Machine};

impl Machine {
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
