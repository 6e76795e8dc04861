//! The machine file's `[collision]` table, checked: the clearance, the pairs
//! of links not checked, the bed.

use crate::MachineError;
use crate::file::CollisionSpec;
use crate::machine::{Link, Visual, visual};

/// The clearance solids keep when a machine file does not say, mm.
pub const DEFAULT_MARGIN_MM: f64 = 5.0;

/// The floor the machine stands on, in the world frame.
#[derive(Debug, Clone, PartialEq)]
pub enum Bed {
    /// Everything below this height (world `z`, mm).
    Plane(f64),
    /// A solid placed in the world frame.
    Solid(Visual),
}

/// How the simulator checks a machine's solids.
#[derive(Debug, Clone, PartialEq)]
pub struct Collision {
    /// The clearance every pair of solids keeps, mm.
    pub margin: f64,
    /// Pairs of links (indices into [`crate::Machine::links`], the smaller
    /// first) whose solids are not checked against each other.
    pub ignore: Vec<[usize; 2]>,
    /// The bed, when the file gives one.
    pub bed: Option<Bed>,
}

impl Default for Collision {
    fn default() -> Self {
        Self {
            margin: DEFAULT_MARGIN_MM,
            ignore: Vec::new(),
            bed: None,
        }
    }
}

/// The collision settings of a machine file's `[collision]` table (the
/// defaults without one); link names are looked up in `links`.
pub(crate) fn settings(
    spec: Option<&CollisionSpec>,
    links: &[Link],
) -> Result<Collision, MachineError> {
    let Some(spec) = spec else {
        return Ok(Collision::default());
    };
    let place = "[collision]";
    let margin = match spec.margin_mm {
        None => DEFAULT_MARGIN_MM,
        Some(m) if m.is_finite() && m >= 0.0 => m,
        Some(m) => {
            return Err(MachineError::field(
                place,
                "margin_mm",
                format!("must be a finite number >= 0 (mm), got {m}"),
            ));
        }
    };
    let link = |name: &str| {
        links.iter().position(|l| l.name == name).ok_or_else(|| {
            MachineError::field(
                place,
                "ignore",
                format!("no link is named \"{}\"", formcam_files::excerpt(name)),
            )
        })
    };
    let mut ignore = Vec::with_capacity(spec.ignore.len());
    for [a, b] in &spec.ignore {
        let (i, j) = (link(a)?, link(b)?);
        ignore.push([i.min(j), i.max(j)]);
    }
    let bed = match (spec.bed_z_mm, &spec.bed) {
        (Some(_), Some(_)) => {
            return Err(MachineError::field(
                place,
                "bed",
                "give the bed as a plane (bed_z_mm) or as a solid (bed), not both",
            ));
        }
        (Some(z), None) if z.is_finite() => Some(Bed::Plane(z)),
        (Some(z), None) => {
            return Err(MachineError::field(
                place,
                "bed_z_mm",
                format!("must be a finite number (mm), got {z}"),
            ));
        }
        (None, Some(v)) => Some(Bed::Solid(visual(v, "[collision] bed")?)),
        (None, None) => None,
    };
    Ok(Collision {
        margin,
        ignore,
        bed,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use crate::Machine;

    const BASE: &str = "[machine]\nname = \"m\"\nkind = \"winder\"\nmandrel = \"spindle\"\n\
        payout = \"eye\"\n[[link]]\nname = \"bed\"\n[[link]]\nname = \"spindle\"\n\
        parent = \"bed\"\n[[link]]\nname = \"head\"\nparent = \"bed\"\n\
        [[point]]\nname = \"eye\"\nlink = \"head\"\n";

    #[test]
    fn defaults_without_a_table() {
        let m = Machine::from_toml(BASE).unwrap();
        assert_eq!(m.collision, super::Collision::default());
        assert_eq!(m.collision.margin, 5.0);
    }

    #[test]
    fn the_table_is_read_and_checked() {
        let m = Machine::from_toml(&format!(
            "{BASE}[collision]\nmargin_mm = 2.5\nignore = [[\"head\", \"spindle\"]]\nbed_z_mm = -10.0\n"
        ))
        .unwrap();
        assert_eq!(m.collision.margin, 2.5);
        assert_eq!(m.collision.ignore, [[1, 2]]);
        assert_eq!(m.collision.bed, Some(super::Bed::Plane(-10.0)));
        let solid = Machine::from_toml(&format!(
            "{BASE}[collision.bed]\nshape = \"box\"\nsize = [10.0, 10.0, 1.0]\n"
        ))
        .unwrap();
        assert!(matches!(solid.collision.bed, Some(super::Bed::Solid(_))));
        for (table, says) in [
            (
                "ignore = [[\"head\", \"tail\"]]",
                "[collision]: ignore: no link is named \"tail\"",
            ),
            (
                "margin_mm = -1.0",
                "[collision]: margin_mm: must be a finite number >= 0",
            ),
            (
                "bed_z_mm = 0.0\n[collision.bed]\nshape = \"sphere\"\nradius = 1.0",
                "[collision]: bed: give the bed as a plane",
            ),
            (
                "[collision.bed]\nshape = \"cone\"",
                "[collision] bed: visual.shape: unknown shape",
            ),
        ] {
            let e = Machine::from_toml(&format!("{BASE}[collision]\n{table}\n"))
                .unwrap_err()
                .to_string();
            assert!(e.starts_with(says), "{e}");
        }
    }
}
