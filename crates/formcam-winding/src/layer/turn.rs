//! `pass_turn` and `circuit_length`: the turn angles and fibre length of one
//! pass, and the band length of a circuit with its turn-arounds.

use std::f64::consts::FRAC_PI_2;

use formcam_geom::Meridian;

use super::lay::Laid;
use super::spec::{Ends, LayerSpec};
use crate::PathPoint;
use crate::circuit::Turnaround;
use crate::path::PassEnd;
use crate::pattern::Pattern;

/// Turn angles of one pass and its fibre length.
pub(super) struct PassTurn {
    /// On the mandrel's surface, rad.
    pub(super) surface: f64,
    /// Added at polar bosses where the path leaves the meridian below 90°, rad.
    pub(super) boss: f64,
    /// Fibre length of the pass, the bosses' faces included, mm.
    pub(super) length: f64,
}

impl PassTurn {
    /// The turn of one pass, boss included, rad.
    pub(super) fn total(&self) -> f64 {
        self.surface + self.boss
    }
}

/// The turn angles of one pass (on the surface, and at polar bosses where the
/// path leaves the meridian below 90°) and its length with the bosses' faces.
pub(super) fn pass_turn<M: Meridian>(
    m: &M,
    spec: &LayerSpec,
    laid: &Laid,
    last: &PathPoint,
) -> PassTurn {
    let (za, zb) = m.z_range();
    let poles = matches!(spec.ends, Ends::Poles { .. });
    let boss = if poles {
        let mut b = 0.0;
        if let PassEnd::Exit { alpha, .. } = laid.start {
            b += FRAC_PI_2 - alpha;
        }
        if let PassEnd::Exit { alpha, .. } = laid.end {
            b += FRAC_PI_2 - alpha;
        }
        b
    } else {
        0.0
    };
    let boss_len = |pe: &PassEnd, r: f64| match pe {
        PassEnd::Exit { alpha, .. } if poles => r * alpha.cos(),
        _ => 0.0,
    };
    PassTurn {
        surface: last.v,
        boss,
        length: last.s + boss_len(&laid.start, m.r(za)) + boss_len(&laid.end, m.r(zb)),
    }
}

/// The band length of one circuit: two passes and the turn-arounds (see
/// `circuit`: the band laid while the mandrel dwells, and at a boss the rest of
/// the turn).
pub(super) fn circuit_length<M: Meridian>(
    m: &M,
    laid: &Laid,
    last: &PathPoint,
    pattern: &Pattern,
    tube: bool,
) -> f64 {
    let dwell_end = 0.5 * pattern.dwell_rad;
    let far = Turnaround::new(m, &laid.end, dwell_end, tube, true);
    let near = Turnaround::new(m, &laid.start, dwell_end, tube, false);
    2.0 * last.s + far.length() + near.length()
}
