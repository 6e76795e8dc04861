//! How a controller turns a per-minute feed into a block time: the length
//! the feed is measured along, per dialect (`docs/check.md`).

use formcam_nc::{AxisSpec, Dialect};

/// The rule by which a controller applies a per-minute feed (`G94`,
/// `FEDRAT/f,MMPM`) to a block that moves linear and rotary axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FeedRule {
    /// LinuxCNC (rs274ngc): the length along the X, Y, Z path as if the
    /// other axes stood still; when X, Y, Z stand still, along U, V, W;
    /// when those stand still too, the angle of A, B, C (`sqrt(dA² + dB² + dC²)`,
    /// degrees per minute).
    LinuxCnc,
    /// Sinumerik 840D: the path feed over the axes of `FGROUP`, by default
    /// the geometry axes X, Y, Z; the other axes are synchronous axes that
    /// take the same time. When no geometry axis moves, the feed applies to
    /// the axes that move (mm/min, degrees per minute).
    Sinumerik840d,
    /// ISO/Fanuc-style G-code and CLDATA `FEDRAT/f,MMPM` (formcam's
    /// assumption, the convention of its writers): the length of the
    /// linear axes' travel; when no linear axis moves, the angle of the
    /// rotary axes (degrees per minute).
    Iso,
    /// Marlin (FiberPath / Cyclone winders): every axis counts as a length,
    /// degrees as millimetres — the Euclidean norm of all axis deltas.
    Marlin,
}

impl FeedRule {
    /// The rule of a dialect's controller.
    pub fn of(dialect: Dialect) -> Self {
        match dialect {
            Dialect::LinuxCnc => Self::LinuxCnc,
            Dialect::Sinumerik840d => Self::Sinumerik840d,
            Dialect::Iso | Dialect::Cldata => Self::Iso,
            Dialect::MarlinXab => Self::Marlin,
        }
    }

    /// The rule's name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::LinuxCnc => "linuxcnc",
            Self::Sinumerik840d => "sinumerik-840d",
            Self::Iso => "iso",
            Self::Marlin => "marlin",
        }
    }

    /// The length (mm, or degrees when only rotary axes count) a per-minute
    /// feed is measured along for the move `from` → `to` on `axes`.
    pub fn length(self, axes: &[AxisSpec], from: &[f64], to: &[f64]) -> f64 {
        let group = |keep: &dyn Fn(&AxisSpec) -> bool| -> f64 {
            axes.iter()
                .zip(from.iter().zip(to))
                .filter(|(a, _)| keep(a))
                .map(|(_, (p, q))| (q - p) * (q - p))
                .sum::<f64>()
                .sqrt()
        };
        let named = |letters: &'static str| {
            move |a: &AxisSpec| {
                a.name.len() == 1 && letters.contains(a.name.to_ascii_uppercase().as_str())
            }
        };
        match self {
            Self::LinuxCnc => [named("XYZ"), named("UVW"), named("ABC")]
                .iter()
                .map(|g| group(g))
                .find(|l| *l > 0.0)
                .unwrap_or(0.0),
            Self::Sinumerik840d => {
                let geometry = group(&named("XYZ"));
                if geometry > 0.0 {
                    geometry
                } else {
                    group(&|_| true)
                }
            }
            Self::Iso => {
                let linear = group(&|a| !a.rotary);
                if linear > 0.0 {
                    linear
                } else {
                    group(&|a| a.rotary)
                }
            }
            Self::Marlin => group(&|_| true),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axes() -> Vec<AxisSpec> {
        vec![
            AxisSpec::rotary_modulo("A"),
            AxisSpec::linear("X"),
            AxisSpec::linear("Y"),
            AxisSpec::rotary("B"),
        ]
    }

    #[test]
    fn each_rule_measures_its_own_length() {
        let a = axes();
        let o = [0.0; 4];
        // A 90°, X 3, Y 4, B 12.
        let p = [90.0, 3.0, 4.0, 12.0];
        assert_eq!(FeedRule::LinuxCnc.length(&a, &o, &p), 5.0);
        assert_eq!(FeedRule::Sinumerik840d.length(&a, &o, &p), 5.0);
        assert_eq!(FeedRule::Iso.length(&a, &o, &p), 5.0);
        let all = (90.0f64 * 90.0 + 9.0 + 16.0 + 144.0).sqrt();
        assert_eq!(FeedRule::Marlin.length(&a, &o, &p), all);
        // Only rotary axes: their angle.
        let r = [30.0, 0.0, 0.0, 40.0];
        for rule in [FeedRule::LinuxCnc, FeedRule::Sinumerik840d, FeedRule::Iso] {
            assert_eq!(rule.length(&a, &o, &r), 50.0, "{rule:?}");
        }
        // A linear axis outside X, Y, Z: LinuxCNC's U, V, W come next.
        let uv = [AxisSpec::linear("U"), AxisSpec::rotary("C")];
        assert_eq!(
            FeedRule::LinuxCnc.length(&uv, &[0.0, 0.0], &[2.0, 9.0]),
            2.0
        );
        assert_eq!(FeedRule::of(Dialect::Cldata), FeedRule::Iso);
    }
}
