//! The checks a winding program must pass before it is written, and the
//! `[checks]` table by which a job accepts some of them failing by name.
//!
//! A program whose payout eye breaks a constraint, whose axes leave their limits
//! or miss the eye, or whose block times break the axes' limits is not written
//! unless the job lists each failed check in `[checks] allow`; then the summary
//! and the program's header say which were accepted.

use formcam_machine::IssueKind;
use formcam_winding::eye::{Constraint, Violation};
use serde::{Deserialize, Serialize};
use strum::VariantNames;

use crate::ProgramError;

/// A check of a winding program (the name users write in `[checks] allow`).
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    PartialOrd,
    Ord,
    Hash,
    Deserialize,
    Serialize,
    strum::IntoStaticStr,
    strum::VariantNames,
)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum Check {
    /// The eye's free length and position repeat after a circuit.
    Cyclicity,
    /// The eye keeps its clearance from the mandrel.
    Clearance,
    /// The free band stays within the eye's largest free length.
    #[serde(rename = "l_max")]
    #[strum(serialize = "l_max")]
    LMax,
    /// The band is pulled, never fed back (it would go slack).
    Slack,
    /// The mandrel never turns backwards.
    ReverseRotation,
    /// Every axis stays within its limits.
    Limits,
    /// The machine reaches every eye point.
    Unreachable,
    /// The block times keep the axes' velocity and velocity-jump limits.
    Timing,
    /// The block times keep the axes' acceleration limits (`[motion] acceleration`).
    Acceleration,
}

impl Check {
    /// The name users write.
    pub fn name(self) -> &'static str {
        self.into()
    }

    /// What the check holds, in a few words (`formcam wind --help`).
    pub fn meaning(self) -> &'static str {
        match self {
            Check::Cyclicity => "the eye's circuit closes",
            Check::Clearance => "the eye keeps its clearance",
            Check::LMax => "the free band within l_max",
            Check::Slack => "the band never goes slack",
            Check::ReverseRotation => "the mandrel never turns backwards",
            Check::Limits => "every axis within its limits",
            Check::Unreachable => "every eye point reached",
            Check::Timing => "block times within the velocity limits",
            Check::Acceleration => "block times within the acceleration limits",
        }
    }

    /// Every check, in order.
    pub const ALL: [Check; 9] = [
        Check::Cyclicity,
        Check::Clearance,
        Check::LMax,
        Check::Slack,
        Check::ReverseRotation,
        Check::Limits,
        Check::Unreachable,
        Check::Timing,
        Check::Acceleration,
    ];

    /// The check an inverse-kinematics issue belongs to (branch jumps are
    /// reported, not checked).
    pub fn of_issue(kind: IssueKind) -> Option<Check> {
        match kind {
            IssueKind::Limit => Some(Check::Limits),
            IssueKind::Unreachable => Some(Check::Unreachable),
            IssueKind::Clearance => Some(Check::Clearance),
            IssueKind::Jump => None,
        }
    }
}

impl From<Constraint> for Check {
    /// The check an eye constraint's violation belongs to.
    fn from(constraint: Constraint) -> Check {
        match constraint {
            Constraint::Cyclicity => Check::Cyclicity,
            Constraint::Clearance => Check::Clearance,
            Constraint::LMax => Check::LMax,
            Constraint::Slack => Check::Slack,
            Constraint::ReverseRotation => Check::ReverseRotation,
        }
    }
}

/// The checks' names, in the order of [`Check::ALL`] (the words of
/// `[checks] allow`).
pub const CHECK_NAMES: &[&str] = Check::VARIANTS;

impl std::str::FromStr for Check {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Check::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| {
                format!(
                    "\"{s}\" is not a check; allowed: {}",
                    Check::ALL.map(Check::name).join(", ")
                )
            })
    }
}

/// The `[checks]` table of a job.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChecksJob {
    /// Checks whose failure the job accepts: the program is written anyway.
    #[serde(default)]
    pub allow: Vec<Check>,
}

/// A check that failed in one layer.
#[derive(Debug, Clone, PartialEq)]
pub struct Violated {
    /// Which check.
    pub check: Check,
    /// The layer's label (`layer 2 (helical)`).
    pub layer: String,
    /// What failed, where: `drive axis X beyond its limit at x = ...`.
    pub detail: String,
}

/// Refuses the program when a check failed that `allow` does not accept:
/// the error names the layer, what failed and how to accept it.
pub fn enforce(allow: &[Check], violated: &[Violated]) -> Result<(), ProgramError> {
    match violated.iter().find(|v| !allow.contains(&v.check)) {
        None => Ok(()),
        Some(v) => Err(ProgramError::Refused {
            check: v.check,
            layer: v.layer.clone(),
            detail: v.detail.clone(),
        }),
    }
}

/// The eye's broken constraints over a layer's circuit, as failed checks.
pub fn eye_violations(layer: &str, violations: &[Violation]) -> Vec<Violated> {
    violations
        .iter()
        .map(|v| {
            let check = Check::from(v.constraint);
            let what = match check {
                Check::Slack => "let the band go slack (the eye feeds it back)",
                Check::Clearance => "bring the eye within its clearance of the mandrel",
                Check::LMax => "let the free band grow beyond eye.l_max",
                Check::ReverseRotation => "turn the mandrel backwards",
                _ => "leave the eye's circuit unclosed (cyclicity)",
            };
            Violated {
                check,
                layer: layer.to_string(),
                detail: format!(
                    "{what} at x = {:.3} mm ({} points, worst {:.4})",
                    v.x, v.count, v.worst
                ),
            }
        })
        .collect()
}

/// The accepted checks that failed, each once, in [`Check`] order.
pub fn accepted(violated: &[Violated]) -> Vec<Check> {
    let mut c: Vec<Check> = violated.iter().map(|v| v.check).collect();
    c.sort();
    c.dedup();
    c
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn names_round_trip_through_the_table() {
        let all = Check::ALL;
        for c in all {
            assert_eq!(c.name().parse::<Check>().unwrap(), c);
        }
        assert!(
            "slak"
                .parse::<Check>()
                .unwrap_err()
                .contains("reverse-rotation")
        );
        let text = format!(
            "allow = [{}]",
            all.iter()
                .map(|c| format!("\"{}\"", c.name()))
                .collect::<Vec<_>>()
                .join(", ")
        );
        let job: ChecksJob = toml::from_str(&text).unwrap();
        assert_eq!(job.allow, all);
        assert!(toml::from_str::<ChecksJob>("allow = [\"slak\"]").is_err());
        assert!(toml::from_str::<ChecksJob>("alow = []").is_err());
    }

    #[test]
    fn only_unaccepted_failures_refuse() {
        let v = vec![
            Violated {
                check: Check::Slack,
                layer: "layer 1".into(),
                detail: "let the band go slack".into(),
            },
            Violated {
                check: Check::Limits,
                layer: "layer 2".into(),
                detail: "drive axis X beyond its limit".into(),
            },
        ];
        let e = enforce(&[Check::Slack], &v).unwrap_err().to_string();
        assert!(
            e.contains("layer 2") && e.contains("allow = [\"limits\"]"),
            "{e}"
        );
        assert!(enforce(&[Check::Limits, Check::Slack], &v).is_ok());
        assert!(enforce(&[], &[]).is_ok());
        assert_eq!(accepted(&v), [Check::Slack, Check::Limits]);
    }
}
