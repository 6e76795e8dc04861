//! What the inverse kinematics found wrong: limits, unreachable points, the
//! eye's clearance and branch jumps, each with the first `x` it happens at.

use std::fmt;

use serde::Serialize;

use super::{AxisTrack, ORIENTATION_SCALE};
use crate::{Machine, Target};

/// What kind of problem the inverse kinematics found.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, strum::IntoStaticStr, strum::EnumString,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
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
        self.into()
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

/// Limits, unreachable points, the eye's clearance and branch jumps.
pub(super) fn feasibility(m: &Machine, targets: &[Target], t: &AxisTrack) -> Vec<Issue> {
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
